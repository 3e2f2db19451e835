//! Everything about one ray that the traversal computes once instead of per node or primitive.

use glam::{BVec3A, Vec3A};

use crate::triangle::RayShear;

/// Reciprocal direction components are clamped to this magnitude so that box-slab distances
/// stay finite (and free of `0 * inf`) for rays parallel to an axis.
const MAX_INV_DIR: f32 = 1e30;

/// A ray prepared for traversal.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RayQuery {
    pub origin: Vec3A,
    pub dir: Vec3A,
    /// `1 / dir`, clamped to `MAX_INV_DIR`, with the sign of `neg` (so `-0.0` counts as positive).
    pub inv_dir: Vec3A,
    /// Which direction components are negative (`< 0.0`).
    pub neg: BVec3A,
    pub shear: RayShear,
}

impl RayQuery {
    #[inline(always)]
    pub fn new(origin: Vec3A, dir: Vec3A) -> Self {
        let neg = dir.cmplt(Vec3A::ZERO);
        let magnitude = dir.abs().max(Vec3A::splat(1.0 / MAX_INV_DIR));
        let inv_abs = magnitude.recip().min(Vec3A::splat(MAX_INV_DIR));
        let inv_dir = Vec3A::select(neg, -inv_abs, inv_abs);
        Self {
            origin,
            dir,
            inv_dir,
            neg,
            shear: RayShear::new(origin, dir),
        }
    }
}
