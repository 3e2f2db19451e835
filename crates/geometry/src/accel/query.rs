//! Everything about one ray that the traversal computes once instead of per node or primitive.

use glam::{BVec3A, Vec3A, Vec4};

use crate::triangle::RayShear;

/// Relative error bound of a computed slab distance `(plane - o) * (1 / d)`: four roundings
/// (the subtraction, the reciprocal, the product, and the scaling of the reciprocal below) make
/// at most `2 * f32::EPSILON`; this leaves a factor of four to spare. `1 - SLAB_ERROR` and
/// `1 + SLAB_ERROR` are exact in `f32`.
const SLAB_ERROR: f32 = 8.0 * f32::EPSILON;

/// A ray prepared for traversal.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RayQuery {
    pub origin: Vec3A,
    pub dir: Vec3A,
    pub shear: RayShear,
    /// The box test's view of the ray, see [`BoxRay`].
    pub boxes: BoxRay,
}

/// The ray as the 4-wide box test uses it, every number splatted to four lanes.
///
/// Slab distances are `(plane - origin) * inv`, with the reciprocal direction scaled down by
/// `1 - SLAB_ERROR` for the entry plane of each slab and up by `1 + SLAB_ERROR` for its exit
/// plane. Since a rounded product keeps the sign of the exact one, the computed entry distance
/// never exceeds the exact one and the computed exit distance is never below it, wherever they
/// are not negative (and negative ones decide nothing, the entry being clamped to zero).
///
/// A zero direction component has an infinite reciprocal, so the slab is all or nothing: from
/// `-inf` to `+inf` when the origin lies strictly between its planes, else empty. The box planes
/// are one float step outside the boxes they bound (see [`super::node::Node::set`]), so an
/// origin on a plane, where `0 * inf` would be NaN, lies outside the box itself.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BoxRay {
    /// Origin coordinates x, y, z.
    pub origin: [Vec4; 3],
    /// `1 / d` per axis (`+inf` for `d = -0.0`), times `1 - SLAB_ERROR`.
    pub inv_entry: [Vec4; 3],
    /// `1 / d` per axis (`+inf` for `d = -0.0`), times `1 + SLAB_ERROR`.
    pub inv_exit: [Vec4; 3],
    /// Per axis, 1 when the direction component is negative (the ray enters the slab through
    /// its maximum plane), else 0.
    pub flip: [usize; 3],
}

impl RayQuery {
    #[inline(always)]
    pub fn new(origin: Vec3A, dir: Vec3A) -> Self {
        Self {
            origin,
            dir,
            shear: RayShear::new(origin, dir),
            boxes: BoxRay::new(origin, dir),
        }
    }
}

impl BoxRay {
    #[inline(always)]
    fn new(origin: Vec3A, dir: Vec3A) -> Self {
        // `-0.0` counts as positive, consistently in `flip` and in the sign of `inv`.
        let neg: BVec3A = dir.cmplt(Vec3A::ZERO);
        let inv_abs = dir.abs().recip();
        let inv = Vec3A::select(neg, -inv_abs, inv_abs);
        let entry = inv * (1.0 - SLAB_ERROR);
        let exit = inv * (1.0 + SLAB_ERROR);
        Self {
            origin: [origin.x, origin.y, origin.z].map(Vec4::splat),
            inv_entry: [entry.x, entry.y, entry.z].map(Vec4::splat),
            inv_exit: [exit.x, exit.y, exit.z].map(Vec4::splat),
            flip: [0, 1, 2].map(|axis| usize::from(neg.test(axis))),
        }
    }
}
