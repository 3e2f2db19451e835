//! Moving shapes: each an acceleration structure of its own in object space with its
//! [`Motion`], found by a ray when it passes through the box the shape sweeps over the shutter.
//!
//! A ray at time `t` is carried into the shape's object space by the inverse of its transform
//! at `t`, intersected there, and the hit carried back ([`Placement`]): the geometry never
//! needs rebuilding, a rotating shape is as exact as a static one, and static geometry keeps
//! its own hierarchy untouched. The moving shapes are tested one after the other, each behind
//! its swept box: a scene with a few moving objects (the common case for motion blur) pays
//! one box test per object per ray; one with thousands would want a hierarchy over the boxes.

use glam::Vec3;

use super::Accel;
use crate::{Aabb, Hit, Motion, Placement, Ray, Shape};

/// One moving shape.
pub(super) struct MovingShape {
    /// The shape alone, in object space.
    pub accel: Accel,
    /// Where it is when.
    pub motion: Motion,
    /// The box (world units) it sweeps over the shutter.
    pub swept: Aabb,
}

impl MovingShape {
    /// `shape` (object space) moving by `motion`.
    pub fn new(shape: Shape, motion: Motion) -> Self {
        let accel = Accel::new(vec![shape]);
        let swept = motion.bounds(&accel.bounds());
        Self {
            accel,
            motion,
            swept,
        }
    }

    /// The shape.
    pub fn shape(&self) -> &Shape {
        &self.accel.shapes()[0]
    }

    /// The closest hit of `ray` (world space) before `t_max`, as shape number `id`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32, id: u32) -> Option<Hit> {
        if !self.swept.hit_by(ray.origin, ray.dir, t_max) {
            return None;
        }
        let placement = self.motion.at(ray.time);
        let (local, scale) = to_object(&placement, ray);
        let hit = self.accel.intersect(&local, t_max * scale)?;
        Some(to_world(&placement, hit, scale, id))
    }

    /// Whether `ray` (world space) hits the shape before `t_max`.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        if !self.swept.hit_by(ray.origin, ray.dir, t_max) {
            return false;
        }
        let (local, scale) = to_object(&self.motion.at(ray.time), ray);
        self.accel.occluded(&local, t_max * scale)
    }
}

/// `ray` in object space with a unit direction, and how many object-space units one world
/// unit along the ray is.
#[inline]
fn to_object(placement: &Placement, ray: &Ray) -> (Ray, f32) {
    let dir = placement.vector_to_object(ray.dir);
    let scale = dir.length();
    let local = Ray {
        origin: placement.point_to_object(ray.origin),
        dir: dir / scale,
        time: ray.time,
    };
    (local, scale)
}

/// The object-space `hit` in world space, as shape `id`.
#[inline]
fn to_world(placement: &Placement, hit: Hit, scale: f32, id: u32) -> Hit {
    let p = placement.point_to_world(hit.p);
    let ng = placement.normal_to_world(hit.ng);
    let ns = placement.normal_to_world(hit.ns);
    Hit {
        t: hit.t / scale,
        p,
        p_error: placement.error_to_world(hit.p, hit.p_error, p),
        ng,
        ns: if ns.dot(ng) < 0.0 { -ns } else { ns },
        bary: hit.bary,
        time: hit.time,
        shape: id,
        prim: hit.prim,
    }
}

/// The object-space direction `v` at `hit` of a moving shape, in world space.
#[inline]
pub(super) fn vector_at(motion: &Motion, hit: &Hit, v: Vec3) -> Vec3 {
    motion.at(hit.time).vector_to_world(v)
}
