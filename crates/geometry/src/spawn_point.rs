//! A surface point that spawns several rays: its ray origins on both sides computed once.

use glam::Vec3;

use crate::Ray;
use crate::offset::offset_both_sides;

/// A surface point with its position moved off the surface to either side, as
/// [`crate::offset_ray_origin`] moves it for a ray leaving it (which depends on the direction only
/// through the side): for a path vertex that spawns a shadow ray and the next ray, or that other
/// paths connect to. Its rays are bit for bit those of [`Ray::spawn`] and [`Ray::spawn_to`].
/// How far it moves is its coordinates' error bound along the normal: see [`crate::Hit::p_error`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpawnPoint {
    /// Position on the surface (world units).
    pub p: Vec3,
    /// Unit geometric normal.
    pub ng: Vec3,
    /// `p` moved to the side `ng` points to (world units).
    pub front: Vec3,
    /// `p` moved to the other side (world units).
    pub back: Vec3,
    /// The time its rays are traced at, a fraction of the shutter interval ([`Ray::time`]).
    pub time: f32,
}

impl SpawnPoint {
    /// The surface point `p` with unit geometric normal `ng`, each coordinate within `p_error`
    /// of the exact surface point (world units), whose rays are traced at time 0.
    #[inline]
    pub fn new(p: Vec3, ng: Vec3, p_error: Vec3) -> Self {
        let (front, back) = offset_both_sides(p, ng, p_error);
        Self {
            p,
            ng,
            front,
            back,
            time: 0.0,
        }
    }

    /// The point `hit` found, whose rays are traced at the hit's time (a moving scene is seen
    /// at one time along the whole path).
    #[inline]
    pub fn of(hit: &crate::Hit) -> Self {
        Self {
            time: hit.time,
            ..Self::new(hit.p, hit.ng, hit.p_error)
        }
    }

    /// The origin of a ray leaving towards `dir` (any length): `front` unless `dir` points below
    /// the surface (`dir · ng < 0`).
    #[inline]
    pub fn origin_towards(&self, dir: Vec3) -> Vec3 {
        if self.ng.dot(dir) < 0.0 {
            self.back
        } else {
            self.front
        }
    }

    /// [`Ray::spawn`] from this point in the direction of `dir` (normalised here).
    #[inline]
    pub fn spawn(&self, dir: Vec3) -> Ray {
        let dir = dir.normalize();
        Ray {
            origin: self.origin_towards(dir),
            dir,
            time: self.time,
        }
    }

    /// [`Self::spawn`] for a direction of unit length already (within rounding, as a BSDF
    /// sample turned into world space is), kept as given: what `spawn` would do but for the
    /// normalisation, whose square root and division the next ray's traversal would wait for.
    #[inline]
    pub fn spawn_unit(&self, dir: Vec3) -> Ray {
        Ray {
            origin: self.origin_towards(dir),
            dir,
            time: self.time,
        }
    }

    /// [`Ray::spawn_to`] from this point to `target_p` (unit geometric normal `target_ng`, zero
    /// for a point light; coordinate error bound `target_error`): the shadow ray and its `t_max`.
    #[inline(always)]
    pub fn spawn_to(&self, target_p: Vec3, target_ng: Vec3, target_error: Vec3) -> (Ray, f32) {
        let to_target = target_p - self.p;
        let end = crate::offset_ray_origin(target_p, target_ng, target_error, -to_target);
        let (ray, t_max) = Ray::between(self.origin_towards(to_target), end, to_target, self.ng);
        (ray.at_time(self.time), t_max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::TestRng;

    /// Points near and far from the origin with error bounds of their size, unit normals, and
    /// directions that include the tangent plane (`dir · ng` exactly zero) and both sides.
    fn cases() -> Vec<(Vec3, Vec3, Vec3, Vec3)> {
        let mut rng = TestRng(7);
        let mut cases = Vec::new();
        for scale in [1e-3, 0.02, 1.0, 40.0, 3e4] {
            for _ in 0..200 {
                let p = scale * rng.vec();
                let e = crate::gamma(7.0) * scale * rng.vec().abs();
                let ng = rng.vec().normalize();
                let dir = rng.vec();
                cases.push((p, ng, e, dir));
                cases.push((p, ng, e, -dir));
                cases.push((p, ng, e, ng.any_orthonormal_vector()));
            }
        }
        let e = Vec3::splat(1e-7);
        cases.push((Vec3::ZERO, Vec3::Z, e, Vec3::X));
        cases.push((
            Vec3::new(1e4, -3.0, 7.0),
            Vec3::Y,
            1e4 * e,
            Vec3::new(1.0, 0.0, -2.0),
        ));
        cases.push((Vec3::new(-0.0, 5.0, 0.0), Vec3::NEG_Y, e, Vec3::Y));
        cases
    }

    #[test]
    fn rays_are_bit_for_bit_those_of_ray_spawn_and_spawn_to() {
        let mut tangent = 0;
        for (p, ng, e, dir) in cases() {
            let point = SpawnPoint::new(p, ng, e);
            let what = format!("p {p:?}, ng {ng:?}, dir {dir:?}");
            assert_eq!(point.spawn(dir), Ray::spawn(p, ng, e, dir), "spawn: {what}");
            let unit = dir.normalize();
            let kept = point.spawn_unit(unit);
            assert_eq!(kept.dir, unit, "spawn_unit changed the direction: {what}");
            // In the tangent plane the side is a coin toss that normalising again can flip.
            if ng.dot(unit).abs() > 1e-4 {
                assert_eq!(kept.origin, point.spawn(unit).origin, "spawn_unit: {what}");
            }
            let target = p + 3.0 * dir;
            assert_eq!(
                point.spawn_to(target, -ng, 2.0 * e),
                Ray::spawn_to(p, ng, e, target, -ng, 2.0 * e),
                "spawn_to: {what}"
            );
            tangent += usize::from(ng.dot(dir) == 0.0);
        }
        assert!(tangent > 0, "no case in the tangent plane");
    }

    #[test]
    fn the_two_sides_are_offset_ray_origin_to_either_side() {
        for (p, ng, e, _) in cases() {
            let point = SpawnPoint::new(p, ng, e);
            assert_eq!(
                point.front,
                crate::offset_ray_origin(p, ng, e, ng),
                "front at {p:?}"
            );
            assert_eq!(
                point.back,
                crate::offset_ray_origin(p, ng, e, -ng),
                "back at {p:?}"
            );
            assert!((point.front - p).dot(ng) > 0.0 && (point.back - p).dot(ng) < 0.0);
        }
    }
}
