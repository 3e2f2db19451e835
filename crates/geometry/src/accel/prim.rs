//! Primitives as the BVH stores them: flat, in BVH leaf order, with the ids and normals needed
//! to turn a hit into a [`crate::Hit`] kept apart from the data traversal touches.

use glam::Vec3;

use crate::sphere::SphereGeom;
use crate::triangle::{TriangleCoords, TriangleHit};

use super::query::RayQuery;

/// The geometry of one primitive.
#[derive(Clone, Copy, Debug)]
pub(crate) enum PrimGeom {
    Triangle(TriangleCoords),
    Sphere(SphereGeom),
}

/// What a primitive test found: the distance, and barycentrics for triangles.
#[derive(Clone, Copy, Debug)]
pub(crate) enum PrimHit {
    Triangle(TriangleHit),
    Sphere(f32),
}

impl PrimHit {
    pub fn t(&self) -> f32 {
        match self {
            PrimHit::Triangle(hit) => hit.t,
            PrimHit::Sphere(t) => *t,
        }
    }
}

impl PrimGeom {
    #[inline(always)]
    pub fn intersect(&self, ray: &RayQuery, t_max: f32) -> Option<PrimHit> {
        match self {
            PrimGeom::Triangle(v) => ray.shear.intersect(v, t_max).map(PrimHit::Triangle),
            PrimGeom::Sphere(s) => s.intersect(ray.origin, ray.dir, t_max).map(PrimHit::Sphere),
        }
    }
}

/// Which shape and triangle a primitive came from, and its unit geometric normal (triangles only;
/// zero for spheres, whose normal depends on the hit point).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PrimInfo {
    pub shape: u32,
    pub prim: u32,
    pub ng: Vec3,
}

/// The unit vector along `v`, if `v` has a direction: scaled first so that tiny and huge
/// components neither underflow nor overflow when squared.
pub(crate) fn direction_of(v: Vec3) -> Option<Vec3> {
    let largest = v.abs().max_element();
    if !(largest > 0.0 && largest.is_finite()) {
        return None;
    }
    (v / largest).try_normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn direction_of_survives_extreme_magnitudes() {
        assert_eq!(direction_of(Vec3::new(0.0, 1e-30, 0.0)), Some(Vec3::Y));
        assert_eq!(direction_of(Vec3::new(-3e38, 0.0, 0.0)), Some(Vec3::NEG_X));
        assert_eq!(direction_of(Vec3::ZERO), None);
        assert_eq!(direction_of(Vec3::new(f32::NAN, 1.0, 0.0)), None);
        assert_eq!(direction_of(Vec3::new(f32::INFINITY, 1.0, 0.0)), None);
    }
}
