//! Analytic spheres and their numerically careful ray intersection.

use std::f32::consts::{PI, TAU};

use glam::{Mat3, Vec2, Vec3, Vec3A};

use crate::Aabb;

/// A sphere in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre in world space.
    pub center: Vec3,
    /// Radius in world units (positive).
    pub radius: f32,
    /// When true the geometric normal points inwards.
    pub flip_normals: bool,
    /// The rotation from world directions to the sphere's own frame, in which its surface
    /// coordinates are defined ([`Self::uv`]): the inverse of its `to_world`'s rotation.
    pub to_local: Mat3,
}

impl Sphere {
    /// World-space bounds.
    pub fn bounds(&self) -> Aabb {
        Aabb::new(self.center - self.radius, self.center + self.radius)
    }

    /// Surface area in world units squared.
    pub fn area(&self) -> f32 {
        2.0 * TAU * self.radius * self.radius
    }

    /// Unit geometric normal at the surface point `p`: outward, or inward with `flip_normals`.
    pub fn normal(&self, p: Vec3) -> Vec3 {
        let n = (p - self.center).normalize();
        if self.flip_normals { -n } else { n }
    }

    /// Surface coordinates `(phi / 2pi, theta / pi)` of the point with outward unit normal `n`
    /// (`phi` from +x towards +y in `[0, 2pi)`, `theta` from +z), as Mitsuba's sphere has them.
    pub fn uv(n: Vec3) -> Vec2 {
        let phi = n.y.atan2(n.x);
        let phi = if phi < 0.0 { phi + TAU } else { phi };
        Vec2::new(phi / TAU, n.z.clamp(-1.0, 1.0).acos() / PI)
    }
}

/// A sphere as the BVH stores it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SphereGeom {
    pub center: Vec3A,
    pub radius: f32,
}

impl SphereGeom {
    /// Distance along the unit direction `dir` from `origin` to the nearest surface point with
    /// `0 < t < t_max`, if any.
    ///
    /// Ray Tracing Gems ch. 7: the discriminant comes from the vector from the centre to the
    /// ray's closest approach, not from `b^2 - c`, so a small sphere far from the origin keeps its
    /// precision; the two roots come from the stable `q`, `c / q` pair.
    ///
    /// `c / q` is the root nearer zero, and its sign is the sign of `c = |oc|² − r²` (over `q`'s):
    /// whether the origin lies outside the sphere. Where `|c|` is within its rounding error,
    /// `γ(6) (|oc|² + r²)`, the origin is on the surface within rounding (a ray spawned from it,
    /// moved off by its error bound), and that root is no hit, as pbrt-v4 tests the lower bound
    /// of its interval `t`.
    #[inline(always)]
    pub fn intersect(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> Option<f32> {
        let oc = origin - self.center;
        let b = oc.dot(dir);
        let closest = oc - b * dir;
        let r2 = self.radius * self.radius;
        let discriminant = r2 - closest.length_squared();
        if discriminant < 0.0 {
            return None;
        }
        let oc2 = oc.length_squared();
        let c = oc2 - r2;
        let q = -(b + discriminant.sqrt().copysign(b));
        let on_surface = c.abs() <= crate::gamma(6.0) * (oc2 + r2);
        let near = if on_surface { f32::NEG_INFINITY } else { c / q };
        let (t0, t1) = if near < q { (near, q) } else { (q, near) };
        if t0 > 0.0 && t0 < t_max {
            Some(t0)
        } else if t1 > 0.0 && t1 < t_max {
            Some(t1)
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn geom(center: Vec3, radius: f32) -> SphereGeom {
        SphereGeom {
            center: center.into(),
            radius,
        }
    }

    #[test]
    fn hits_front_then_back() {
        let s = geom(Vec3::new(0.0, 0.0, -5.0), 1.0);
        let t = s.intersect(Vec3A::ZERO, Vec3A::NEG_Z, f32::INFINITY);
        assert_eq!(t, Some(4.0));
        let t = s.intersect(Vec3A::new(0.0, 0.0, -5.0), Vec3A::NEG_Z, f32::INFINITY);
        assert_eq!(t, Some(1.0));
        assert_eq!(s.intersect(Vec3A::ZERO, Vec3A::NEG_Z, 4.0), None);
        assert_eq!(s.intersect(Vec3A::ZERO, Vec3A::Z, f32::INFINITY), None);
    }

    #[test]
    fn small_sphere_far_away_keeps_precision() {
        // With b^2 - c in f32 the radius vanishes next to |oc|^2 = 1e10: rounding decides.
        let s = geom(Vec3::new(1e5, 0.0, 0.0), 1e-2);
        let origin = Vec3A::new(0.0, 0.005, 0.0);
        let t = s
            .intersect(origin, Vec3A::X, f32::INFINITY)
            .expect("ray passes within half a radius of the centre");
        // Exact: 1e5 - sqrt(1e-4 - 2.5e-5) = 1e5 - 0.00866.
        assert!((t - (1e5 - 0.008_660_254)).abs() < 0.01, "t = {t}");
        let miss = Vec3A::new(0.0, 0.0101, 0.0);
        assert_eq!(s.intersect(miss, Vec3A::X, f32::INFINITY), None);
    }

    #[test]
    fn uv_follows_mitsuba_parameterisation() {
        assert!(Sphere::uv(Vec3::Z).abs_diff_eq(Vec2::new(0.0, 0.0), 1e-6));
        assert!(Sphere::uv(Vec3::NEG_Y).abs_diff_eq(Vec2::new(0.75, 0.5), 1e-6));
        assert!(Sphere::uv(Vec3::NEG_Z).abs_diff_eq(Vec2::new(0.0, 1.0), 1e-6));
    }

    #[test]
    fn normal_flips_with_flip_normals() {
        let mut s = Sphere {
            center: Vec3::ONE,
            radius: 2.0,
            flip_normals: false,
            to_local: glam::Mat3::IDENTITY,
        };
        assert_eq!(s.normal(Vec3::new(1.0, 3.0, 1.0)), Vec3::Y);
        s.flip_normals = true;
        assert_eq!(s.normal(Vec3::new(1.0, 3.0, 1.0)), Vec3::NEG_Y);
        assert_eq!(s.area(), 16.0 * PI);
    }
}
