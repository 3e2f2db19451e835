//! Rays and the spawning of secondary rays from surfaces.

use glam::Vec3;

use crate::offset::offset_ray_origin;

/// A half-line `origin + t * dir`, `t > 0`, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Start point in world space.
    pub origin: Vec3,
    /// Unit direction.
    pub dir: Vec3,
    /// When the ray is traced, as a fraction of the shutter interval: 0 when the shutter opens,
    /// 1 when it closes (see [`crate::Motion`]). Moving shapes are intersected where they are
    /// then; static ones ignore it. 0 in a scene where nothing moves.
    pub time: f32,
}

impl Ray {
    /// The ray from `origin` in the direction of `dir`, which is normalised here (it must be
    /// non-zero and finite).
    #[inline]
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Self {
            origin,
            dir: dir.normalize(),
            time: 0.0,
        }
    }

    /// The same ray traced at `time` (a fraction of the shutter interval, see [`Ray::time`]).
    #[inline]
    pub fn at_time(self, time: f32) -> Self {
        Self { time, ..self }
    }

    /// The point at distance `t` (world units) along the ray.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }

    /// A ray leaving the surface point `p` (unit geometric normal `ng`, each coordinate within
    /// `p_error` of the exact surface point, as [`crate::Hit::p_error`]) in direction `dir`, its
    /// origin moved off the surface by [`offset_ray_origin`] so it does not hit that surface again.
    /// Works for both sides: reflection (`dir . ng > 0`) and transmission (`dir . ng < 0`).
    /// The ray is traced at time 0: [`crate::SpawnPoint`] keeps a hit's time.
    #[inline]
    pub fn spawn(p: Vec3, ng: Vec3, p_error: Vec3, dir: Vec3) -> Self {
        let dir = dir.normalize();
        Self {
            origin: offset_ray_origin(p, ng, p_error, dir),
            dir,
            time: 0.0,
        }
    }

    /// A shadow ray from the surface point `p` (unit geometric normal `ng`, coordinate error
    /// bound `p_error`) towards the surface point `target_p` (unit geometric normal `target_ng`,
    /// zero for a point light; error bound `target_error`), and the `t_max` to trace it with.
    ///
    /// Both ends are moved off their surfaces towards each other with [`offset_ray_origin`], so
    /// `occluded(&ray, t_max)` sees neither the start surface nor the target surface; `t_max` is
    /// the distance between the two moved points less [`SHADOW_EPSILON`] of it, which covers the
    /// rounding of the target surface's own `t`. When the points are so close that the moved
    /// points coincide or pass each other, the ray has direction `ng` and `t_max = 0`, so nothing
    /// can block it. Like [`Ray::spawn`], the ray is traced at time 0.
    #[inline(always)]
    pub fn spawn_to(
        p: Vec3,
        ng: Vec3,
        p_error: Vec3,
        target_p: Vec3,
        target_ng: Vec3,
        target_error: Vec3,
    ) -> (Self, f32) {
        let to_target = target_p - p;
        let origin = offset_ray_origin(p, ng, p_error, to_target);
        let end = offset_ray_origin(target_p, target_ng, target_error, -to_target);
        Self::between(origin, end, to_target, ng)
    }

    /// [`Ray::spawn_to`] from its two moved points: the shadow ray from `origin` to `end` (each
    /// already moved off its surface by [`offset_ray_origin`], towards the other) and its
    /// `t_max`, where `to_target` is the direction between the unmoved points. When the moved
    /// points coincide or pass each other, the ray has direction `fallback` and `t_max = 0`.
    #[inline]
    pub fn between(origin: Vec3, end: Vec3, to_target: Vec3, fallback: Vec3) -> (Self, f32) {
        let d = end - origin;
        let distance = d.length();
        if distance > 0.0 && distance.is_finite() && d.dot(to_target) > 0.0 {
            (
                Self {
                    origin,
                    dir: d / distance,
                    time: 0.0,
                },
                distance * (1.0 - SHADOW_EPSILON),
            )
        } else {
            (
                Self {
                    origin,
                    dir: fallback,
                    time: 0.0,
                },
                0.0,
            )
        }
    }
}

/// The fraction of a shadow ray's length left untested at its far end (2^-16): the far end is
/// moved off the target surface by the error bound of its position, but the `t` at which the
/// ray meets that surface is computed with an error of its own, a few `γ(n)` of the distance
/// for a ray that does not graze it (pbrt-v4 tests `1 − ShadowEpsilon` of its rays for the same
/// reason, with 1e-4). Relative to the ray, so it scales with the scene.
pub const SHADOW_EPSILON: f32 = 1.0 / 65536.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_normalises_and_at_walks_along() {
        let r = Ray::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.0, 3.0, 4.0));
        assert!((r.dir.length() - 1.0).abs() < 1e-6);
        assert!(r.at(5.0).abs_diff_eq(Vec3::new(1.0, 5.0, 7.0), 1e-5));
    }

    #[test]
    fn spawn_to_ends_short_of_the_target() {
        let p = Vec3::new(0.0, 0.0, 0.0);
        let target = Vec3::new(0.0, 0.0, 2.0);
        let e = Vec3::splat(1e-7);
        let (ray, t_max) = Ray::spawn_to(p, Vec3::Z, e, target, Vec3::NEG_Z, e);
        assert!(ray.origin.z > 0.0);
        assert!(ray.at(t_max).z < 2.0);
        assert!(t_max < 2.0 && t_max > 1.999);
        assert!(ray.dir.abs_diff_eq(Vec3::Z, 1e-6));
    }

    #[test]
    fn spawn_to_the_same_point_has_zero_length() {
        let p = Vec3::new(1.0, 1.0, 1.0);
        let e = Vec3::splat(1e-7);
        let (ray, t_max) = Ray::spawn_to(p, Vec3::Y, e, p, Vec3::NEG_Y, e);
        assert_eq!(t_max, 0.0);
        assert!(ray.dir.is_finite() && ray.origin.is_finite());
    }
}
