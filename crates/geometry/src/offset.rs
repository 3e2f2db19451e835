//! Moving ray origins off surfaces so that a new ray does not hit the surface it starts on.
//!
//! The method is pbrt-v4's (Pharr, Jakob and Humphreys, section 6.8.6, `OffsetRayOrigin`): a
//! surface point comes with a bound on the rounding error of each of its coordinates (its
//! `p_error`, from the arithmetic that computed it), the point moves along the geometric normal
//! far enough to leave the box of that error — by `|n| · p_error` — and each moved coordinate
//! is then rounded one more unit in the last place away from the surface, so that the addition's
//! own rounding cannot bring it back. The intersection tests add the other half: a hit must lie
//! beyond the error bound of its own `t` (see [`crate::triangle`] and [`crate::sphere`]).
//!
//! The offset is a bound on the actual error, so it scales with the coordinates and with the
//! magnitudes that computed them (a point near the origin on a huge triangle carries the error
//! of the triangle's large coordinates): a scene scaled by 1e-4 gets offsets 1e-4 times as large,
//! where a fixed offset near the origin (Wächter and Binder's `float_scale`) would be larger
//! than the scene's thin gaps.

use glam::{Vec3, Vec3A};

pub use crate::triangle::gamma;

/// An error bound of every point `b0 p0 + b1 p1 + b2 p2` of the triangle `p0, p1, p2` computed
/// in `f32` from barycentric coordinates `b` (non-negative, summing to 1 within rounding,
/// themselves computed with a few roundings): pbrt-v4's `γ(7) (b0 |p0| + b1 |p1| + b2 |p2|)`
/// per coordinate (section 6.8.5), bounded by `γ(7) max(|p0|, |p1|, |p2|)` so that it is one
/// number per triangle, computed once. Where the barycentric coordinates err, the point moves
/// within the triangle's plane, which the bound need not cover; what it covers is the point's
/// distance from that plane.
#[inline]
pub fn triangle_point_error([p0, p1, p2]: [Vec3; 3]) -> Vec3 {
    gamma(7.0) * p0.abs().max(p1.abs()).max(p2.abs())
}

/// The error bound of the point `center + radius · u` of a sphere computed in `f32` from a unit
/// vector `u` (itself a few roundings from unit length): `γ(5) (|center| + radius)` per
/// coordinate.
#[inline]
pub fn sphere_point_error(center: Vec3, radius: f32) -> Vec3 {
    gamma(5.0) * (center.abs() + Vec3::splat(radius))
}

/// Moves the surface point `p` (each coordinate within `p_error` of the exact surface point,
/// world units) off its surface, to the side of the unit geometric normal `ng` that the
/// direction `dir` leaves into (the side of `-ng` when `dir . ng < 0`).
///
/// A ray from the returned point in direction `dir` does not hit the surface around `p` again:
/// the point moves by `(|ng| · p_error) ng`, then each coordinate that moved one more unit in
/// the last place in the same direction. A zero `ng` (a point light) or `p_error` leaves `p` as
/// it is.
#[inline]
pub fn offset_ray_origin(p: Vec3, ng: Vec3, p_error: Vec3, dir: Vec3) -> Vec3 {
    let (p, ng, p_error) = (Vec3A::from(p), Vec3A::from(ng), Vec3A::from(p_error));
    let offset = ng.abs().dot(p_error) * ng;
    let offset = if ng.dot(dir.into()) < 0.0 {
        -offset
    } else {
        offset
    };
    Vec3::from(rounded_along(p + offset, offset))
}

/// [`offset_ray_origin`] to both sides at once: `p` moved to the side of the unit geometric
/// normal `ng` and to the side of `-ng`.
#[inline]
pub(crate) fn offset_both_sides(p: Vec3, ng: Vec3, p_error: Vec3) -> (Vec3, Vec3) {
    let (p, ng, p_error) = (Vec3A::from(p), Vec3A::from(ng), Vec3A::from(p_error));
    let offset = ng.abs().dot(p_error) * ng;
    (
        Vec3::from(rounded_along(p + offset, offset)),
        Vec3::from(rounded_along(p - offset, -offset)),
    )
}

/// `q` with each coordinate moved one unit in the last place in the direction of the sign of
/// the same coordinate of `offset` (unchanged where it is zero): pbrt's `NextFloatUp` and
/// `NextFloatDown`. A zero coordinate first takes the sign of its offset, so one unit from zero
/// is the smallest subnormal of that sign. Four lanes at once with SSE2 (part of every x86-64
/// processor): integer arithmetic on the bit patterns, moved away from zero where the signs of
/// the coordinate and of its offset agree and towards zero where they differ.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn rounded_along(q: Vec3A, offset: Vec3A) -> Vec3A {
    use std::arch::x86_64::{
        __m128, _mm_add_epi32, _mm_and_ps, _mm_andnot_ps, _mm_castps_si128, _mm_castsi128_ps,
        _mm_cmpeq_ps, _mm_cmpgt_ps, _mm_cmplt_ps, _mm_or_ps, _mm_set1_ps, _mm_setzero_ps,
        _mm_srai_epi32, _mm_sub_epi32, _mm_xor_si128,
    };
    // SAFETY: SSE2 is part of the x86-64 baseline, so these instructions are always there.
    let moved = unsafe {
        let (q, offset) = (__m128::from(q), __m128::from(offset));
        let zero = _mm_setzero_ps();
        // +1 where the offset is positive, −1 where it is negative (masks are −1 as integers).
        let steps = _mm_sub_epi32(
            _mm_castps_si128(_mm_cmplt_ps(offset, zero)),
            _mm_castps_si128(_mm_cmpgt_ps(offset, zero)),
        );
        // Zero coordinates become zeros with the offset's sign.
        let sign = _mm_and_ps(offset, _mm_set1_ps(-0.0));
        let is_zero = _mm_cmpeq_ps(q, zero);
        let q = _mm_or_ps(_mm_and_ps(is_zero, sign), _mm_andnot_ps(is_zero, q));
        let bits = _mm_castps_si128(q);
        // All ones in the lanes of negative coordinates: there `(s ^ -1) - (-1)` is `-s`.
        let negative = _mm_srai_epi32::<31>(bits);
        let away = _mm_sub_epi32(_mm_xor_si128(steps, negative), negative);
        _mm_castsi128_ps(_mm_add_epi32(bits, away))
    };
    Vec3A::from(moved)
}

/// [`rounded_along`] one coordinate at a time: the version for other processors, and the
/// reference the SSE2 one is tested against.
#[cfg(any(test, not(target_arch = "x86_64")))]
fn rounded_along_scalar(q: Vec3A, offset: Vec3A) -> Vec3A {
    let one = |q: f32, offset: f32| {
        let q = if q == 0.0 {
            0.0_f32.copysign(offset)
        } else {
            q
        };
        if offset > 0.0 {
            q.next_up()
        } else if offset < 0.0 {
            q.next_down()
        } else {
            q
        }
    };
    Vec3A::new(one(q.x, offset.x), one(q.y, offset.y), one(q.z, offset.z))
}

#[cfg(not(target_arch = "x86_64"))]
use rounded_along_scalar as rounded_along;

#[cfg(test)]
mod tests {
    use super::*;

    /// Only where the four-lane version exists: elsewhere it is the scalar one.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_four_lane_roundings_are_those_of_one_coordinate_at_a_time() {
        // Both signs of coordinates and offsets, zeros of both signs, tiny and huge values,
        // subnormals and offsets that are zero in some coordinates.
        let mut rng = crate::test_rng::TestRng(11);
        let mut cases = vec![
            (Vec3A::new(1e4, -3.0, 7.0), Vec3A::new(0.0, 1.0, -1.0)),
            (Vec3A::new(0.0, -0.0, 0.0), Vec3A::new(1.0, 1.0, -1.0)),
            (Vec3A::new(-0.0, 0.0, -0.0), Vec3A::new(-1.0, -1.0, 0.0)),
            (
                Vec3A::new(1e-45, -1e-45, f32::MIN_POSITIVE),
                Vec3A::new(-1.0, 1.0, -1.0),
            ),
            (
                Vec3A::new(f32::MAX, -f32::MAX, 1.0),
                Vec3A::new(-1.0, 1.0, 1e-30),
            ),
        ];
        for scale in [1e-30, 1e-4, 1.0, 3e4] {
            for _ in 0..500 {
                cases.push((scale * rng.vec_a(), rng.vec_a()));
            }
        }
        for (q, offset) in cases {
            let four = rounded_along(q, offset).to_array().map(f32::to_bits);
            let one = rounded_along_scalar(q, offset).to_array().map(f32::to_bits);
            assert_eq!(four, one, "q {q:?}, offset {offset:?}");
        }
    }

    #[test]
    fn offset_moves_to_the_side_of_dir() {
        let p = Vec3::new(0.3, -2.0, 5.0);
        let ng = Vec3::new(0.0, 0.6, 0.8);
        let p_error = Vec3::splat(1e-6);
        for (dir, sign) in [(ng, 1.0), (-ng, -1.0), (Vec3::new(1.0, 0.1, 0.0), 1.0)] {
            let o = offset_ray_origin(p, ng, p_error, dir);
            assert!(
                sign * (o - p).dot(ng) > 0.0,
                "dir {dir}: {o} not on the right side of {p}"
            );
        }
    }

    #[test]
    fn offset_is_the_error_bound_along_the_normal_rounded_away() {
        let p = Vec3::new(1000.0, -3.0, 0.001);
        let p_error = Vec3::new(1e-4, 2e-6, 1e-9);
        // Along an axis: the bound of that coordinate, then one unit in the last place more.
        let o = offset_ray_origin(p, Vec3::X, p_error, Vec3::X);
        assert_eq!(o.x, (p.x + 1e-4).next_up());
        assert_eq!((o.y, o.z), (p.y, p.z));
        let o = offset_ray_origin(p, Vec3::NEG_Y, p_error, Vec3::NEG_Y);
        assert_eq!(o.y, (p.y - 2e-6).next_down());
        // The back side of +z.
        let o = offset_ray_origin(p, Vec3::Z, p_error, Vec3::NEG_Z);
        assert_eq!(o.z, (p.z - 1e-9).next_down());
        // Oblique: |n| · p_error along n.
        let n = Vec3::new(0.6, 0.0, -0.8);
        let d = 0.6 * 1e-4 + 0.8 * 1e-9;
        let o = offset_ray_origin(p, n, p_error, n);
        assert_eq!(o.x, (p.x + d * 0.6).next_up());
        assert_eq!(o.y, p.y);
        assert_eq!(o.z, (p.z - d * 0.8).next_down());
    }

    #[test]
    fn offset_scales_with_the_error_bound() {
        // The same point and bound scaled by 1e-4: the offset scales too (no absolute floor).
        let (p, n, e) = (Vec3::new(0.2, 0.5, -0.1), Vec3::Y, Vec3::splat(3e-7));
        let big = offset_ray_origin(p, n, e, n).y - p.y;
        let small = offset_ray_origin(1e-4 * p, n, 1e-4 * e, n).y - 1e-4 * p.y;
        assert!((small / big - 1e-4).abs() < 1e-5, "{small} against {big}");
    }

    #[test]
    fn offset_is_finite_at_zero_and_at_signed_zero_and_nothing_without_a_normal() {
        for p in [Vec3::ZERO, Vec3::new(-0.0, 0.0, -0.0)] {
            let n = Vec3::ONE.normalize();
            let o = offset_ray_origin(p, n, Vec3::splat(1e-7), Vec3::NEG_ONE);
            assert!(o.is_finite());
            assert!(o.cmplt(Vec3::ZERO).all(), "{o}");
            // No error bound, no offset.
            let o = offset_ray_origin(p, n, Vec3::ZERO, Vec3::NEG_ONE);
            assert_eq!(o, Vec3::ZERO);
        }
        let p = Vec3::new(1.0, 2.0, 3.0);
        assert_eq!(offset_ray_origin(p, Vec3::ZERO, Vec3::ONE, Vec3::X), p);
    }
}
