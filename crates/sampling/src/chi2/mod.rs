//! A reusable chi-square goodness-of-fit harness: does a sampling routine produce values distributed as
//! its pdf says? In the manner of Mitsuba 3's `chi2.py` and pbrt-v4's `bsdfs_test.cpp`.
//!
//! [`chi2_test`] draws `sample_count` values from a sampling function, bins them on an equal-measure grid
//! over a [`Chi2Domain`], integrates the pdf over every bin by adaptive cubature to get the expected
//! counts, pools bins expecting fewer than 5 samples, and computes Pearson's statistic and its p-value
//! (regularised upper incomplete gamma function). It also fails at once on values outside the domain,
//! values where the pdf is zero, and a pdf integrating to more than 1. [`chi2_discrete`] does the same
//! for a distribution over indices, and [`integrate_pdf`] checks normalisation on its own.
//!
//! A sampling function may return `None` (a BSDF absorbing the sample): absorbed mass is allowed. The
//! expected counts are then those of a pdf integrating to less than 1, and the number of `None`s is
//! tested as one more cell against sample count × (1 − ∫ pdf).
//!
//! ```
//! use sampling::chi2::{Chi2Config, Chi2Domain, chi2_test};
//! use sampling::warp::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
//! use glam::Vec2;
//!
//! let config = Chi2Config { sample_count: 20_000, resolution: 8, ..Chi2Config::default() };
//! let outcome = chi2_test(
//!     Chi2Domain::Sphere,
//!     |rng| Some(sample_cosine_hemisphere(Vec2::new(rng.next_f32(), rng.next_f32()))),
//!     |w| cosine_hemisphere_pdf(w.z),
//!     &config,
//! );
//! assert!(outcome.passed, "{outcome}");
//! ```

mod gamma;

pub(crate) use gamma::{gamma_q, incomplete_beta};
mod outcome;
mod quadrature;

pub use outcome::{Chi2Bin, Chi2Outcome};

use crate::rng::Rng;
use glam::Vec3;
use outcome::{Tally, Verdict, conclude};
use quadrature::{Depth, Rect, integrate};
use std::f64::consts::{PI, TAU};

/// Refinement of a bin's cubature: always into 4² cells, and into cells 2¹⁰ times smaller than the bin
/// along discontinuities (a jump costs about 2¹¹ cells per bin it crosses).
const QUADRATURE_DEPTH: Depth = Depth { min: 2, max: 10 };
/// Cubature error allowed per bin, as a fraction of the standard deviation of the bin's count.
const QUADRATURE_ERROR_PER_SIGMA: f64 = 0.05;
/// How far from unit length a direction may be and still count as on the sphere.
const UNIT_LENGTH_TOLERANCE: f32 = 1e-3;

/// The domain whose values a [`chi2_test`] bins.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Chi2Domain {
    /// Unit directions (solid-angle measure, pdfs per steradian), binned on a grid of
    /// `resolution` rows in cos θ ∈ [−1, 1] by 2 · `resolution` columns in φ ∈ [−π, π): equal-area bins.
    Sphere,
    /// Points (x, y) of [0, 1]² (area measure; z is ignored), on a `resolution` × `resolution` grid.
    /// Map other planar domains onto it (a disc of radius 1 by (p + 1) / 2, with its pdf × 4).
    UnitSquare,
}

impl Chi2Domain {
    /// (columns, rows) of the grid at `resolution`.
    fn grid(self, resolution: u32) -> (u32, u32) {
        let resolution = resolution.max(1);
        match self {
            Self::Sphere => (2 * resolution, resolution),
            Self::UnitSquare => (resolution, resolution),
        }
    }

    /// The value at parameter (a, b) ∈ [0, 1]²: φ = 2π a − π and cos θ = 2 b − 1 on the sphere.
    fn point(self, a: f64, b: f64) -> Vec3 {
        match self {
            Self::Sphere => {
                let z = 2.0 * b - 1.0;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let (sin_phi, cos_phi) = (TAU * a - PI).sin_cos();
                Vec3::new((r * cos_phi) as f32, (r * sin_phi) as f32, z as f32)
            }
            Self::UnitSquare => Vec3::new(a as f32, b as f32, 0.0),
        }
    }

    /// The domain's measure per unit of parameter area: 4π steradians, or 1.
    fn jacobian(self) -> f64 {
        match self {
            Self::Sphere => 4.0 * PI,
            Self::UnitSquare => 1.0,
        }
    }

    /// The parameter (a, b) ∈ [0, 1]² of a value, or `None` if the value is not in the domain.
    fn parameter(self, v: Vec3) -> Option<(f64, f64)> {
        match self {
            Self::Sphere => {
                let valid = v.is_finite() && (v.length() - 1.0).abs() <= UNIT_LENGTH_TOLERANCE;
                valid.then(|| {
                    let phi = f64::from(v.y).atan2(f64::from(v.x));
                    let z = f64::from(v.z).clamp(-1.0, 1.0);
                    ((phi + PI) / TAU, 0.5 * (z + 1.0))
                })
            }
            Self::UnitSquare => {
                let inside = (0.0..=1.0).contains(&v.x) && (0.0..=1.0).contains(&v.y);
                inside.then(|| (f64::from(v.x), f64::from(v.y)))
            }
        }
    }

    /// Names bin (column, row) of a grid with `columns` × `rows` bins in the domain's own coordinates.
    fn label(self, column: u32, row: u32, columns: u32, rows: u32) -> String {
        let (a0, a1) = (
            f64::from(column) / f64::from(columns),
            f64::from(column + 1) / f64::from(columns),
        );
        let (b0, b1) = (
            f64::from(row) / f64::from(rows),
            f64::from(row + 1) / f64::from(rows),
        );
        match self {
            Self::Sphere => format!(
                "cos θ ∈ [{:.3}, {:.3}), φ ∈ [{:.3}, {:.3})",
                2.0 * b0 - 1.0,
                2.0 * b1 - 1.0,
                TAU * a0 - PI,
                TAU * a1 - PI
            ),
            Self::UnitSquare => format!("x ∈ [{a0:.3}, {a1:.3}), y ∈ [{b0:.3}, {b1:.3})"),
        }
    }

    fn describe(self, columns: u32, rows: u32) -> String {
        match self {
            Self::Sphere => format!("on the sphere ({rows} cos θ × {columns} φ bins)"),
            Self::UnitSquare => format!("on the unit square ({columns} × {rows} bins)"),
        }
    }
}

/// Settings of a chi-square test. `Chi2Config { sample_count: 100_000, ..Default::default() }`.
#[derive(Clone, Debug, PartialEq)]
pub struct Chi2Config {
    /// Grid resolution: rows in cos θ (twice as many φ columns) on the sphere, bins per side on the
    /// square. Unused by [`chi2_discrete`]. Default 32.
    pub resolution: u32,
    /// How many times to call the sampling function. Default 1 000 000.
    pub sample_count: u32,
    /// Seed of the [`Rng`] handed to the sampling function. Default 0.
    pub seed: u32,
    /// Significance level α of one test: the chance of failing a correct sampler. Default 0.01.
    pub alpha: f64,
    /// How many tests share α (Šidák correction): each is run at 1 − (1 − α)^(1 / test_count). Default 1.
    pub test_count: u32,
    /// Cells expecting fewer samples than this are pooled into one. Default 5.
    pub min_expected: f64,
    /// How far above 1 the pdf's integral may be (cubature and `f32` rounding). Default 1e-3.
    pub pdf_integral_tolerance: f64,
}

impl Default for Chi2Config {
    fn default() -> Self {
        Self {
            resolution: 32,
            sample_count: 1_000_000,
            seed: 0,
            alpha: 0.01,
            test_count: 1,
            min_expected: 5.0,
            pdf_integral_tolerance: 1e-3,
        }
    }
}

impl Chi2Config {
    /// The per-test significance level after Šidák correction: 1 − (1 − α)^(1 / test_count).
    pub fn alpha_corrected(&self) -> f64 {
        1.0 - (1.0 - self.alpha).powf(1.0 / f64::from(self.test_count.max(1)))
    }

    fn verdict(&self) -> Verdict {
        Verdict {
            seed: self.seed,
            sample_count: self.sample_count,
            min_expected: self.min_expected,
            alpha_corrected: self.alpha_corrected(),
            pdf_integral_tolerance: self.pdf_integral_tolerance,
        }
    }
}

/// Tests whether `sample` draws values distributed with density `pdf` over `domain`.
///
/// `sample` gets one [`Rng`] (seeded with `config.seed`) for all its calls and returns a value of the
/// domain (a unit direction, or a point of [0, 1]² in x and y) or `None` for an absorbed sample. `pdf` is
/// the density in the domain's measure (per steradian on the sphere, per unit area on the square).
pub fn chi2_test(
    domain: Chi2Domain,
    mut sample: impl FnMut(&mut Rng) -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f32,
    config: &Chi2Config,
) -> Chi2Outcome {
    let (columns, rows) = domain.grid(config.resolution);
    let bins = (columns * rows) as usize;
    let mut observed = vec![0.0; bins + 1];
    let mut tally_counts = [0_u64; 3];
    let mut first_problems = Vec::new();
    let mut rng = Rng::new(config.seed);
    for index in 0..config.sample_count {
        let Some(value) = sample(&mut rng) else {
            observed[bins] += 1.0;
            tally_counts[0] += 1;
            continue;
        };
        let Some((a, b)) = domain.parameter(value) else {
            tally_counts[1] += 1;
            if first_problems.len() < 3 {
                first_problems.push(format!("sample {index} is outside the domain: {value}"));
            }
            continue;
        };
        let density = pdf(value);
        if !(density > 0.0 && density.is_finite()) {
            tally_counts[2] += 1;
            if first_problems.len() < 3 {
                first_problems.push(format!("sample {index} at {value} has pdf {density}"));
            }
        }
        let column = ((a * f64::from(columns)) as u32).min(columns - 1);
        let row = ((b * f64::from(rows)) as u32).min(rows - 1);
        observed[(row * columns + column) as usize] += 1.0;
    }

    let n = f64::from(config.sample_count);
    let mut expected = bin_probabilities(domain, &pdf, columns, rows, |p| {
        QUADRATURE_ERROR_PER_SIGMA * (p.abs().max(1.0 / n.max(1.0)) / n.max(1.0)).sqrt()
    });
    let pdf_integral: f64 = expected.iter().sum();
    expected.iter_mut().for_each(|p| *p *= n);
    expected.push(n * (1.0 - pdf_integral).max(0.0));

    let tally = Tally {
        description: domain.describe(columns, rows),
        observed,
        expected,
        pdf_integral,
        absorbed_samples: tally_counts[0],
        invalid_samples: tally_counts[1],
        zero_pdf_samples: tally_counts[2],
        failures: first_problems,
    };
    conclude(tally, &config.verdict(), |i| {
        if i == bins {
            "absorbed (sample returned None)".to_owned()
        } else {
            let i = i as u32;
            domain.label(i % columns, i / columns, columns, rows)
        }
    })
}

/// Tests whether `sample` draws indices in [0, `len`) with probability `pmf(i)`.
///
/// `sample` gets one [`Rng`] (seeded with `config.seed`) for all its calls; `None` is an absorbed
/// sample, tested against 1 − Σ pmf. `config.resolution` is not used.
pub fn chi2_discrete(
    len: usize,
    mut sample: impl FnMut(&mut Rng) -> Option<usize>,
    pmf: impl Fn(usize) -> f64,
    config: &Chi2Config,
) -> Chi2Outcome {
    let mut observed = vec![0.0; len + 1];
    let mut counts = [0_u64; 3];
    let mut failures = Vec::new();
    let probabilities: Vec<f64> = (0..len).map(&pmf).collect();
    let mut rng = Rng::new(config.seed);
    for index in 0..config.sample_count {
        match sample(&mut rng) {
            None => {
                observed[len] += 1.0;
                counts[0] += 1;
            }
            Some(i) if i >= len => {
                counts[1] += 1;
                if failures.len() < 3 {
                    failures.push(format!("sample {index} is index {i}, past the end {len}"));
                }
            }
            Some(i) => {
                if !(probabilities[i] > 0.0 && probabilities[i].is_finite()) {
                    counts[2] += 1;
                    if failures.len() < 3 {
                        failures.push(format!(
                            "sample {index} is index {i} with pmf {}",
                            probabilities[i]
                        ));
                    }
                }
                observed[i] += 1.0;
            }
        }
    }
    let n = f64::from(config.sample_count);
    let total: f64 = probabilities.iter().sum();
    let mut expected: Vec<f64> = probabilities.iter().map(|p| p * n).collect();
    expected.push(n * (1.0 - total).max(0.0));
    let tally = Tally {
        description: format!("over {len} indices"),
        observed,
        expected,
        pdf_integral: total,
        absorbed_samples: counts[0],
        invalid_samples: counts[1],
        zero_pdf_samples: counts[2],
        failures,
    };
    conclude(tally, &config.verdict(), |i| {
        if i == len {
            "absorbed (sample returned None)".to_owned()
        } else {
            format!("index {i}")
        }
    })
}

/// ∫ `pdf` over `domain` (dω on the sphere, dx dy on the unit square) by adaptive cubature over a grid
/// of the given `resolution` (as in [`Chi2Config::resolution`]). Smooth pdfs come out to about 1e-6;
/// pdfs that jump along a curve (a cone's rim, a triangle's edges) to about 1e-4 relative error, because
/// a jump can clip a cell between the cubature nodes unseen. A normalised pdf gives 1.
pub fn integrate_pdf(domain: Chi2Domain, pdf: impl Fn(Vec3) -> f32, resolution: u32) -> f64 {
    let (columns, rows) = domain.grid(resolution);
    let tolerance = 1e-6 / f64::from(columns * rows);
    bin_probabilities(domain, &pdf, columns, rows, |_| tolerance)
        .iter()
        .sum()
}

/// The integral of `pdf` over every bin, row-major, each to the absolute `tolerance(coarse estimate)`.
fn bin_probabilities(
    domain: Chi2Domain,
    pdf: &impl Fn(Vec3) -> f32,
    columns: u32,
    rows: u32,
    tolerance: impl Fn(f64) -> f64,
) -> Vec<f64> {
    let jacobian = domain.jacobian();
    let integrand = |a: f64, b: f64| f64::from(pdf(domain.point(a, b))) * jacobian;
    let (da, db) = (1.0 / f64::from(columns), 1.0 / f64::from(rows));
    (0..rows)
        .flat_map(|row| (0..columns).map(move |column| (column, row)))
        .map(|(column, row)| {
            let rect = Rect {
                a0: f64::from(column) * da,
                a1: f64::from(column + 1) * da,
                b0: f64::from(row) * db,
                b1: f64::from(row + 1) * db,
            };
            integrate(&integrand, rect, &tolerance, QUADRATURE_DEPTH)
        })
        .collect()
}

/// The p-value of a chi-square statistic with `dof` degrees of freedom: P(X ≥ `statistic`) for
/// X ~ χ²(dof), the regularised upper incomplete gamma function Q(dof / 2, statistic / 2).
pub fn chi2_p_value(statistic: f64, dof: u32) -> f64 {
    gamma::gamma_q(f64::from(dof) / 2.0, statistic / 2.0)
}
