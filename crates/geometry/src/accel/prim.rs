//! Primitives as the BVH stores them: triangles in packets of four and spheres, in BVH leaf
//! order, with the ids and normals needed to turn a hit into a [`crate::Hit`] kept apart from
//! the data traversal touches.

use glam::Vec3;

use crate::sphere::SphereGeom;
use crate::triangle::TriangleHit;
use crate::triangle4::Triangle4;

/// The primitives' geometry, which the traversal reads.
#[derive(Debug, Default)]
pub(crate) struct Geometry {
    /// Triangle packets; leaves refer to them by index.
    pub packets: Vec<Triangle4>,
    /// Spheres, one per leaf.
    pub spheres: Vec<SphereGeom>,
}

/// Which primitive a ray hit, and how.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Found {
    Triangle {
        packet: usize,
        lane: usize,
        hit: TriangleHit,
    },
    Sphere {
        index: usize,
        t: f32,
    },
}

/// Which shape and triangle a primitive came from, its unit geometric normal (triangles only;
/// zero for spheres, whose normal depends on the hit point), and the error bound of its hit
/// points ([`crate::Hit::p_error`]: [`crate::triangle_point_error`] or
/// [`crate::sphere_point_error`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PrimInfo {
    pub shape: u32,
    pub prim: u32,
    pub ng: Vec3,
    pub p_error: Vec3,
}

impl PrimInfo {
    /// The entry of an unused lane of a triangle packet.
    pub const UNUSED: PrimInfo = PrimInfo {
        shape: u32::MAX,
        prim: u32::MAX,
        ng: Vec3::ZERO,
        p_error: Vec3::ZERO,
    };
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
