//! Area emitters on triangle meshes (Mitsuba's `area` emitter attached to a mesh shape).

use crate::area_sample::{area_pdf_towards, area_sample_towards};
use crate::emission::{EmissionSample, lambertian_emission};
use crate::light::{Emitter, Kind, one_sided};
use crate::sample::{LightSample, mean_rgb};
use glam::{Vec2, Vec3, Vec3A};
use sampling::distribution::CdfTable;
use sampling::warp::sample_uniform_triangle;
use std::f32::consts::PI;

/// A triangle mesh emitting constant radiance from the front side of each triangle, the side
/// its geometric normal `(p1 − p0) × (p2 − p0)` points to. Points are sampled uniformly by area:
/// on a mesh of two triangles that make a parallelogram (Mitsuba's `rectangle`), directly on the
/// parallelogram; otherwise a triangle by area, then a point on it.
#[derive(Clone, Debug)]
pub struct MeshAreaLight {
    triangles: Vec<[Vec3; 3]>,
    parallelogram: Option<Parallelogram>,
    /// Unit geometric normal of each triangle (zero for degenerate ones, which are never sampled).
    normals: Vec<Vec3>,
    /// The error bound of each triangle's sampled points ([`geometry::triangle_point_error`]).
    errors: Vec<Vec3>,
    area_distribution: CdfTable,
    total_area: f32,
    /// 1 / `total_area`: the density per unit area of a uniformly sampled point.
    pdf_area: f32,
    radiance: Vec3,
    /// A sphere around every triangle: centre and radius (world units).
    bounds: (Vec3, f32),
}

impl MeshAreaLight {
    /// An emitter over the given world-space triangles with `radiance` (W m⁻² sr⁻¹, RGB).
    /// `None` when the triangles have no area at all (such a light can never be seen).
    pub fn new(triangles: Vec<[Vec3; 3]>, radiance: Vec3) -> Option<Self> {
        let areas: Vec<f32> = triangles.iter().map(triangle_area).collect();
        let total_area: f32 = areas.iter().map(|&a| f64::from(a)).sum::<f64>() as f32;
        let area_distribution = CdfTable::new(&areas).ok()?;
        let normals: Vec<Vec3> = triangles
            .iter()
            .map(|[p0, p1, p2]| (*p1 - *p0).cross(*p2 - *p0).normalize_or_zero())
            .collect();
        let errors = triangles
            .iter()
            .map(|&t| geometry::triangle_point_error(t))
            .collect();
        let parallelogram = Parallelogram::of(&triangles, &normals);
        let (low, high) = triangles.iter().flatten().fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(low, high), &p| (low.min(p), high.max(p)),
        );
        let bounds = (0.5 * (low + high), 0.5 * (high - low).length());
        Some(Self {
            triangles,
            parallelogram,
            normals,
            errors,
            area_distribution,
            total_area,
            pdf_area: 1.0 / total_area,
            radiance,
            bounds,
        })
    }

    /// Emitted radiance, W m⁻² sr⁻¹ (RGB).
    pub fn radiance(&self) -> Vec3 {
        self.radiance
    }

    /// A sphere (centre, radius in world units) that contains the whole mesh.
    pub fn bounding_sphere(&self) -> (Vec3, f32) {
        self.bounds
    }

    /// Total surface area, world units squared.
    pub fn area(&self) -> f32 {
        self.total_area
    }

    /// A point uniform by area on the mesh, seen from `p`; `None` when it faces away or
    /// coincides with `p`. Always inlined: returned through memory, its sample is reloaded in
    /// pieces that straddle how it was stored, which stalls (3.7% of the path loop's perf
    /// samples on the Cornell box).
    #[inline(always)]
    pub fn sample_li(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let (p_light, p_light_error, n_light) = self.sample_point(u);
        area_sample_towards(
            p,
            p_light.into(),
            p_light_error.into(),
            n_light.into(),
            self.pdf_area,
            self.radiance,
        )
    }

    /// A point uniform by area with `u` ∈ [0, 1)², a bound on its coordinates' distance from
    /// the mesh's surface, and the unit normal there. Returned as 16-byte vectors: a caller that
    /// is not inlined with it then reloads them whole from where they were stored whole
    /// (reloading a 12-byte vector stored in two parts stalls, 4% of the path loop's perf samples
    /// on the Cornell box).
    #[inline]
    fn sample_point(&self, u: Vec2) -> (Vec3A, Vec3A, Vec3A) {
        let (p, error, n) = if let Some(quad) = &self.parallelogram {
            (
                quad.corner + u.x * quad.edge_u + u.y * quad.edge_v,
                quad.error,
                quad.normal,
            )
        } else {
            let (index, _pmf, u_remapped) = self.area_distribution.sample(u.x);
            let [p0, p1, p2] = self.triangles[index];
            let b = sample_uniform_triangle(Vec2::new(u_remapped, u.y));
            (
                p0 * b.x + p1 * b.y + p2 * b.z,
                self.errors[index],
                self.normals[index],
            )
        };
        (p.into(), error.into(), n.into())
    }

    /// Density per steradian with which [`Self::sample_li`] from `p` picks the point `p_light`
    /// (geometric normal `n_light`) of this mesh.
    #[inline]
    pub fn pdf_li(&self, p: Vec3, p_light: Vec3, n_light: Vec3) -> f32 {
        area_pdf_towards(p, p_light, n_light, self.pdf_area)
    }

    /// Light leaving the mesh: a point uniform by area (`u_point`) and a cosine-distributed
    /// direction about its front normal (`u_dir`).
    #[inline]
    pub fn sample_emission(&self, u_point: Vec2, u_dir: Vec2) -> Option<EmissionSample> {
        let (p, error, n) = self.sample_point(u_point);
        lambertian_emission(
            p.into(),
            error.into(),
            n.into(),
            self.radiance,
            self.total_area,
            u_dir,
        )
    }

    /// Emitted power (W, mean over channels): π · area · radiance for a one-sided Lambertian emitter.
    pub fn power(&self) -> f32 {
        PI * self.total_area * mean_rgb(self.radiance)
    }
}

impl Emitter for MeshAreaLight {
    const KIND: Kind = Kind::Area;

    #[inline]
    fn sample_li(&self, p: Vec3, u: Vec2, _time: f32) -> Option<LightSample> {
        MeshAreaLight::sample_li(self, p, u)
    }

    #[inline]
    fn sample_emission(&self, u_point: Vec2, u_dir: Vec2, _time: f32) -> Option<EmissionSample> {
        MeshAreaLight::sample_emission(self, u_point, u_dir)
    }

    #[inline]
    fn radiance_towards(&self, ng: Vec3, w: Vec3) -> Vec3 {
        one_sided(self.radiance, ng, w)
    }

    #[inline]
    fn pdf_li_surface(&self, p: Vec3, p_light: Vec3, n_light: Vec3, _time: f32) -> f32 {
        self.pdf_li(p, p_light, n_light)
    }

    #[inline]
    fn pdf_emission_area(&self, _n_light: Vec3, _time: f32) -> f32 {
        1.0 / self.total_area
    }

    fn bounding_sphere(&self) -> Option<(Vec3, f32)> {
        Some(self.bounds)
    }

    fn power(&self) -> f32 {
        MeshAreaLight::power(self)
    }
}

/// Two triangles that together are the parallelogram `corner + u · edge_u + v · edge_v`,
/// u, v ∈ [0, 1], facing one way.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Parallelogram {
    corner: Vec3,
    edge_u: Vec3,
    edge_v: Vec3,
    /// The triangles' common unit normal.
    normal: Vec3,
    /// A bound on how far a point `corner + u · edge_u + v · edge_v` computed in `f32` lies
    /// from the two triangles, per coordinate: the rounding of the sum and of the edges,
    /// `γ(5) (|corner| + |edge_u| + |edge_v|)`, and how far the fourth corner lies from the
    /// first triangle's plane (the parallelogram is only nearly one).
    error: Vec3,
}

impl Parallelogram {
    /// The parallelogram `triangles` (with unit `normals`) make, if they are two triangles facing
    /// the same way that share a diagonal (two corners with identical coordinates) and whose
    /// other corners mirror each other across its midpoint (within 10⁻⁶ of the size).
    fn of(triangles: &[[Vec3; 3]], normals: &[Vec3]) -> Option<Self> {
        let ([first, second], [n0, n1]) = (triangles, normals) else {
            return None;
        };
        if *n0 == Vec3::ZERO || n0.dot(*n1) < 1.0 - 1e-6 {
            return None;
        }
        let shared: Vec<Vec3> = first
            .iter()
            .copied()
            .filter(|p| second.contains(p))
            .collect();
        let [a, b] = shared[..] else {
            return None;
        };
        let own = |t: &[Vec3; 3]| t.iter().copied().find(|p| *p != a && *p != b);
        let (corner, opposite) = (own(first)?, own(second)?);
        let size = (a - corner).length() + (b - corner).length();
        if (corner + opposite - a - b).length() > 1e-6 * size {
            return None;
        }
        let (edge_u, edge_v) = (a - corner, b - corner);
        let rounding = geometry::gamma(5.0) * (corner.abs() + edge_u.abs() + edge_v.abs());
        Some(Self {
            corner,
            edge_u,
            edge_v,
            normal: *n0,
            error: rounding + (corner + opposite - a - b).abs(),
        })
    }
}

fn triangle_area(t: &[Vec3; 3]) -> f32 {
    let area = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
    if area.is_finite() { area } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light(triangles: Vec<[Vec3; 3]>) -> MeshAreaLight {
        MeshAreaLight::new(triangles, Vec3::ONE).expect("has area")
    }

    #[test]
    fn two_triangles_sharing_a_diagonal_are_sampled_as_a_parallelogram() {
        let [o, x, y] = [Vec3::new(1.0, 2.0, 3.0), Vec3::X, Vec3::new(0.5, 0.0, 2.0)];
        let quad = light(vec![[o, o + x, o + x + y], [o + x + y, o + y, o]]);
        let (corner, edge_u, edge_v) = (o + x, o - (o + x), o + x + y - (o + x));
        let rounding = geometry::gamma(5.0) * (corner.abs() + edge_u.abs() + edge_v.abs());
        let expected = Parallelogram {
            corner,
            edge_u,
            edge_v,
            normal: x.cross(y).normalize(),
            error: rounding + (corner + (o + y) - o - (o + x + y)).abs(),
        };
        assert_eq!(quad.parallelogram, Some(expected));
        // Its corners come from the corners of [0, 1)².
        let (p, error, n) = quad.sample_point(Vec2::ZERO);
        assert_eq!((Vec3::from(p), Vec3::from(n)), (o + x, expected.normal));
        assert_eq!(Vec3::from(error), expected.error);
        assert!(expected.error.cmpgt(Vec3::ZERO).all());
    }

    #[test]
    fn sampled_points_lie_on_the_mesh_within_their_error_bound() {
        // A parallelogram whose fourth corner is off the first triangle's plane by more than
        // the rounding (but within what counts as a parallelogram), and a single triangle far
        // from the origin.
        let [o, x, y] = [
            Vec3::new(0.1, -0.2, 0.05),
            Vec3::new(3.0, 0.1, 0.0),
            Vec3::new(0.2, 0.0, 2.0),
        ];
        let bent = o + x + y + Vec3::new(0.0, 4e-6, 0.0);
        let far = Vec3::new(1e3, -2e3, 5e2);
        let lights = [
            light(vec![[o + x, bent, o], [o + y, o, bent]]),
            light(vec![[far, far + x, far + y]]),
        ];
        assert!(lights[0].parallelogram.is_some());
        let mut rng = sampling::rng::Rng::new(5);
        for light in &lights {
            for _ in 0..1000 {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                let (p, error, n) = light.sample_point(u);
                let (p, error, n) = (Vec3::from(p), Vec3::from(error), Vec3::from(n));
                // The distance from the plane of the triangle the point projects into, in
                // double precision.
                let q = p.as_dvec3();
                let distance = light
                    .triangles
                    .iter()
                    .filter_map(|t| {
                        let [a, b, c] = t.map(|v| v.as_dvec3());
                        let normal = (b - a).cross(c - a);
                        let weight = |e0: glam::DVec3, e1: glam::DVec3| {
                            (e0 - q).cross(e1 - q).dot(normal) / normal.length_squared()
                        };
                        let inside = [weight(b, c), weight(c, a), weight(a, b)]
                            .iter()
                            .all(|&w| w >= -1e-9);
                        inside.then(|| (q - a).dot(normal.normalize()).abs())
                    })
                    .fold(f64::INFINITY, f64::min);
                assert!(distance.is_finite(), "{p} is on no triangle");
                let bound = f64::from(n.abs().dot(error));
                assert!(
                    distance <= bound,
                    "{p}: {distance} off the mesh, bound {bound}"
                );
            }
        }
    }

    #[test]
    fn other_pairs_are_sampled_by_triangle() {
        let [o, x, y] = [Vec3::ZERO, Vec3::X, Vec3::Y];
        // A kite: the second triangle's free corner does not mirror the first's.
        assert!(
            light(vec![[o, x, y], [x, x + 2.0 * y, y]])
                .parallelogram
                .is_none()
        );
        // The second triangle wound the other way faces the other way.
        assert!(
            light(vec![[o, x, y], [x, y, x + y]])
                .parallelogram
                .is_none()
        );
        // Two triangles that share one corner only.
        assert!(
            light(vec![[o, x, y], [x, 2.0 * x, x + y]])
                .parallelogram
                .is_none()
        );
    }
}
