//! A conservative ray test against the eight quantised child boxes of a CWBVH node.
//!
//! obvhs' own test clamps the entry distance to a fixed `1e-4` instead of the ray's `t_min`
//! (surfaces closer than that are missed) and has no allowance for rounding (a ray grazing a box
//! face, which is where the extreme primitive of the box lies, can be rejected). This test clamps
//! to `0` and widens every slab by a bound on its rounding error.

use glam::{Vec3A, Vec4};
use obvhs::cwbvh::node::{CwBvhNode, extract_byte64};

use super::query::RayQuery;

/// Relative error bound of a slab distance `q * (e / d) + (p - o) / d` in units of its terms'
/// magnitudes: a few roundings (subtraction, reciprocal, two products, sum) and the outward
/// rounding of the stored box planes, with room to spare.
const SLAB_ERROR: f32 = 8.0 * f32::EPSILON;

/// The child boxes are quantised to `0..=255` steps of the node's extent.
const QUANT_MAX: f32 = 255.0;

/// Bitmask of the children of `node` that the ray may hit at `0 <= t <= t_max`, in the layout
/// obvhs' `traverse!` expects (inner children in the high byte, leaf primitives below).
#[inline(always)]
pub(crate) fn hit_children(node: &CwBvhNode, ray: &RayQuery, t_max: f32, oct_inv4: u32) -> u32 {
    let scale = node.compute_extent() * ray.inv_dir;
    let offset = (Vec3A::from(node.p) - ray.origin) * ray.inv_dir;
    let error = ((offset.abs() + scale.abs() * QUANT_MAX) * SLAB_ERROR).min(Vec3A::splat(f32::MAX));
    let near_offset = offset - error;
    let far_offset = offset + error;
    let (child_bits8, bit_index8) = node.get_child_and_index_bits(oct_inv4);

    let mut hit_mask = 0;
    for half in 0..2 {
        let lanes = |q: &[u8; 8]| {
            let i = 4 * half;
            Vec4::new(
                q[i] as f32,
                q[i + 1] as f32,
                q[i + 2] as f32,
                q[i + 3] as f32,
            )
        };
        let slab = |lo: &[u8; 8], hi: &[u8; 8], neg: bool, scale: f32, near: f32, far: f32| {
            let (q_near, q_far) = if neg {
                (lanes(hi), lanes(lo))
            } else {
                (lanes(lo), lanes(hi))
            };
            (
                q_near * scale + Vec4::splat(near),
                q_far * scale + Vec4::splat(far),
            )
        };
        let (x0, x1) = slab(
            &node.child_min_x,
            &node.child_max_x,
            ray.neg.test(0),
            scale.x,
            near_offset.x,
            far_offset.x,
        );
        let (y0, y1) = slab(
            &node.child_min_y,
            &node.child_max_y,
            ray.neg.test(1),
            scale.y,
            near_offset.y,
            far_offset.y,
        );
        let (z0, z1) = slab(
            &node.child_min_z,
            &node.child_max_z,
            ray.neg.test(2),
            scale.z,
            near_offset.z,
            far_offset.z,
        );
        let t_enter = x0.max(y0).max(z0).max(Vec4::ZERO);
        let t_exit = x1.min(y1).min(z1).min(Vec4::splat(t_max));
        let hits = t_enter.cmple(t_exit).bitmask();
        for lane in 0..4 {
            if hits & (1 << lane) != 0 {
                let child = 4 * half + lane;
                hit_mask |= extract_byte64(child_bits8, child) << extract_byte64(bit_index8, child);
            }
        }
    }
    hit_mask
}
