//! The `sampling` crate for notebooks: the random number generator, the warps with their pdfs
//! and inverses over arrays of points, and the samplers' points for a pixel. `strata.sampling`
//! (Python) wraps these with friendlier names.

use glam::{UVec2, Vec2, Vec3};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use sampling::rng::{sample_seed, wang_hash as wang};
use sampling::warp;
use sampling::{AnySampler, Sampler, SamplerKind};

use crate::errors::value_error;

/// Registers this module's classes and functions in `m`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Rng>()?;
    m.add_function(wrap_pyfunction!(wang_hash, m)?)?;
    m.add_function(wrap_pyfunction!(warp_sample, m)?)?;
    m.add_function(wrap_pyfunction!(warp_pdf, m)?)?;
    m.add_function(wrap_pyfunction!(warp_invert, m)?)?;
    m.add_function(wrap_pyfunction!(sampler_points, m)?)?;
    // The samplers' names, from the one list of them (`SamplerKind::ALL`).
    m.add("SAMPLERS", SamplerKind::ALL.map(SamplerKind::name).to_vec())?;
    Ok(())
}

/// Thomas Wang's 32-bit integer hash, as the generator seeds itself with.
#[pyfunction]
fn wang_hash(x: u32) -> u32 {
    wang(x)
}

/// Marsaglia's xorshift32 generator (shifts 13, 17, 5), its state the Wang hash of the seed: the
/// generator every Strata sampler draws its random numbers from.
#[pyclass(module = "strata.sampling")]
pub struct Rng(sampling::Rng);

#[pymethods]
impl Rng {
    /// The generator whose stream `seed` determines (nearby seeds give unrelated streams).
    #[new]
    fn new(seed: u32) -> Self {
        Self(sampling::Rng::new(seed))
    }

    /// The generator of one sample of pixel `(x, y)`, as the independent sampler draws it.
    #[staticmethod]
    fn for_sample(x: u32, y: u32, sample_index: u32, seed: u32) -> Self {
        Self(sampling::Rng::new(sample_seed(
            UVec2::new(x, y),
            sample_index,
            seed,
        )))
    }

    /// The next 32 uniformly distributed bits.
    fn next_u32(&mut self) -> u32 {
        self.0.next_u32()
    }

    /// A float uniform in [0, 1) (a multiple of 2⁻²⁴, never 1).
    fn next_f32(&mut self) -> f32 {
        self.0.next_f32()
    }

    /// An integer uniform in [0, n), without modulo bias.
    fn next_below(&mut self, n: u32) -> PyResult<u32> {
        if n == 0 {
            return Err(value_error("next_below(0): the range [0, 0) is empty"));
        }
        Ok(self.0.next_below(n))
    }

    /// The next `n` floats of [`next_f32`](Self::next_f32), as a `float32` array.
    fn random<'py>(&mut self, py: Python<'py>, n: usize) -> Bound<'py, PyArray1<f32>> {
        let values: Vec<f32> = (0..n).map(|_| self.0.next_f32()).collect();
        PyArray1::from_vec(py, values)
    }

    /// The next `n` values of [`next_u32`](Self::next_u32), as a `uint32` array.
    fn integers<'py>(&mut self, py: Python<'py>, n: usize) -> Bound<'py, PyArray1<u32>> {
        let values: Vec<u32> = (0..n).map(|_| self.0.next_u32()).collect();
        PyArray1::from_vec(py, values)
    }
}

/// The domains of the warps: the dimension of their points and, for the parameterised ones,
/// what the parameter is.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Domain {
    /// Unit directions with z ≥ 0, uniform by solid angle.
    UniformHemisphere,
    /// Unit directions with z ≥ 0, density cos θ / π.
    CosineHemisphere,
    /// Unit directions, uniform.
    UniformSphere,
    /// Points of the unit disc, by Shirley and Chiu's concentric map.
    ConcentricDisk,
    /// Unit directions within θ_max of +z; the parameter is cos θ_max.
    UniformCone(f32),
    /// Barycentric coordinates uniform by area on a triangle; the parameter is its area.
    UniformTriangle(f32),
}

impl Domain {
    /// The warp called `name` with `parameter` (ignored by those that have none).
    fn named(name: &str, parameter: f32) -> PyResult<Self> {
        Ok(match name {
            "uniform_hemisphere" => Self::UniformHemisphere,
            "cosine_hemisphere" => Self::CosineHemisphere,
            "uniform_sphere" => Self::UniformSphere,
            "concentric_disk" => Self::ConcentricDisk,
            "uniform_cone" if parameter.is_finite() && (-1.0..1.0).contains(&parameter) => {
                Self::UniformCone(parameter)
            }
            "uniform_cone" => {
                return Err(value_error(format!(
                    "cos_theta_max {parameter} is not in [-1, 1)"
                )));
            }
            "uniform_triangle" if parameter.is_finite() && parameter > 0.0 => {
                Self::UniformTriangle(parameter)
            }
            "uniform_triangle" => {
                return Err(value_error(format!(
                    "area {parameter} is not a positive number"
                )));
            }
            other => return Err(value_error(format!("no warp called '{other}'"))),
        })
    }

    /// How many numbers a point of the domain has.
    fn point_dimension(self) -> usize {
        match self {
            Self::ConcentricDisk => 2,
            _ => 3,
        }
    }

    /// The point `u` maps to, as `point_dimension` numbers.
    fn sample(self, u: Vec2) -> [f32; 3] {
        match self {
            Self::UniformHemisphere => warp::sample_uniform_hemisphere(u).to_array(),
            Self::CosineHemisphere => warp::sample_cosine_hemisphere(u).to_array(),
            Self::UniformSphere => warp::sample_uniform_sphere(u).to_array(),
            Self::ConcentricDisk => {
                let p = warp::sample_concentric_disk(u);
                [p.x, p.y, 0.0]
            }
            Self::UniformCone(cos_max) => warp::sample_uniform_cone(u, 1.0 - cos_max).to_array(),
            Self::UniformTriangle(_) => warp::sample_uniform_triangle(u).to_array(),
        }
    }

    /// The density of `sample`'s points at `p` in the domain's measure (solid angle, area of
    /// the disc, or area of the triangle), zero outside the domain's support.
    fn pdf(self, p: [f32; 3]) -> f32 {
        match self {
            Self::UniformHemisphere if p[2] >= 0.0 => warp::uniform_hemisphere_pdf(),
            Self::CosineHemisphere => warp::cosine_hemisphere_pdf(p[2]),
            Self::UniformSphere => warp::uniform_sphere_pdf(),
            Self::ConcentricDisk if p[0] * p[0] + p[1] * p[1] <= 1.0 => warp::concentric_disk_pdf(),
            Self::UniformCone(cos_max) if p[2] >= cos_max => warp::uniform_cone_pdf(1.0 - cos_max),
            Self::UniformTriangle(area) if p.iter().all(|&b| b >= 0.0) => {
                warp::uniform_triangle_pdf(area)
            }
            _ => 0.0,
        }
    }

    /// The `u` that `sample` maps to the point `p`.
    fn invert(self, p: [f32; 3]) -> Vec2 {
        let w = Vec3::from_array(p);
        match self {
            Self::UniformHemisphere => warp::invert_uniform_hemisphere(w),
            Self::CosineHemisphere => warp::invert_cosine_hemisphere(w),
            Self::UniformSphere => warp::invert_uniform_sphere(w),
            Self::ConcentricDisk => warp::invert_concentric_disk(Vec2::new(p[0], p[1])),
            Self::UniformCone(cos_max) => warp::invert_uniform_cone(w, 1.0 - cos_max),
            Self::UniformTriangle(_) => warp::invert_uniform_triangle(w),
        }
    }
}

/// The rows of `points` (shape `(n, columns)`) as triples (padded with zeros).
fn rows(points: &PyReadonlyArray2<'_, f32>, columns: usize, what: &str) -> PyResult<Vec<[f32; 3]>> {
    let shape = points.shape();
    if shape[1] != columns {
        return Err(value_error(format!(
            "{what} has shape {shape:?}; expected (n, {columns})"
        )));
    }
    let view = points.as_array();
    Ok(view
        .rows()
        .into_iter()
        .map(|row| {
            let mut triple = [0.0; 3];
            for (t, &v) in triple.iter_mut().zip(row.iter()) {
                *t = v;
            }
            triple
        })
        .collect())
}

/// The points warp `name` (with `parameter`) maps the rows of `u` (shape `(n, 2)`, in [0, 1)²)
/// to: shape `(n, 3)` (directions or barycentric coordinates) or `(n, 2)` for the disc.
#[pyfunction]
#[pyo3(signature = (name, u, parameter = 0.0))]
fn warp_sample<'py>(
    py: Python<'py>,
    name: &str,
    u: PyReadonlyArray2<'py, f32>,
    parameter: f32,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let domain = Domain::named(name, parameter)?;
    let dimension = domain.point_dimension();
    let points = rows(&u, 2, "u")?;
    let values: Vec<f32> = points
        .iter()
        .flat_map(|p| domain.sample(Vec2::new(p[0], p[1]))[..dimension].to_vec())
        .collect();
    PyArray1::from_vec(py, values).reshape([points.len(), dimension])
}

/// The density of warp `name`'s points at the rows of `points`, as an `(n,)` array.
#[pyfunction]
#[pyo3(signature = (name, points, parameter = 0.0))]
fn warp_pdf<'py>(
    py: Python<'py>,
    name: &str,
    points: PyReadonlyArray2<'py, f32>,
    parameter: f32,
) -> PyResult<Bound<'py, PyArray1<f32>>> {
    let domain = Domain::named(name, parameter)?;
    let points = rows(&points, domain.point_dimension(), "points")?;
    Ok(PyArray1::from_vec(
        py,
        points.iter().map(|&p| domain.pdf(p)).collect(),
    ))
}

/// The `u` (shape `(n, 2)`) that warp `name` maps to the rows of `points`.
#[pyfunction]
#[pyo3(signature = (name, points, parameter = 0.0))]
fn warp_invert<'py>(
    py: Python<'py>,
    name: &str,
    points: PyReadonlyArray2<'py, f32>,
    parameter: f32,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let domain = Domain::named(name, parameter)?;
    let points = rows(&points, domain.point_dimension(), "points")?;
    let values: Vec<f32> = points
        .iter()
        .flat_map(|&p| domain.invert(p).to_array())
        .collect();
    PyArray1::from_vec(py, values).reshape([points.len(), 2])
}

/// The sampler kind called `name` (as `strata render --sampler` names it).
fn sampler_kind(name: &str) -> PyResult<SamplerKind> {
    name.parse()
        .map_err(|e: sampling::UnknownSamplerKind| value_error(e.to_string()))
}

/// The first `dimensions` numbers of each of the `spp` samples of pixel `(x, y)` that sampler
/// `kind` (laid out for `spp` samples, seeded with `seed`) gives, as an `(spp, dimensions)`
/// array: drawn in pairs (`next_2d`, one 2D dimension each, as the renderer draws film
/// positions and directions), the last alone (`next_1d`) when `dimensions` is odd.
#[pyfunction]
#[pyo3(signature = (kind, spp, seed = 0, x = 0, y = 0, dimensions = 2))]
fn sampler_points<'py>(
    py: Python<'py>,
    kind: &str,
    spp: u32,
    seed: u32,
    x: u32,
    y: u32,
    dimensions: usize,
) -> PyResult<Bound<'py, PyArray2<f32>>> {
    if spp == 0 {
        return Err(value_error("spp must be at least 1"));
    }
    let mut sampler = AnySampler::new(sampler_kind(kind)?, seed, spp);
    let mut values = Vec::with_capacity(spp as usize * dimensions);
    for index in 0..spp {
        sampler.start_pixel_sample(UVec2::new(x, y), index);
        for _ in 0..dimensions / 2 {
            values.extend(sampler.next_2d().to_array());
        }
        if dimensions % 2 == 1 {
            values.push(sampler.next_1d());
        }
    }
    PyArray1::from_vec(py, values).reshape([spp as usize, dimensions])
}
