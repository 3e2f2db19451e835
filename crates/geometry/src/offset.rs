//! Moving ray origins off surfaces so that a new ray does not hit the surface it starts on.
//!
//! The method is Wächter and Binder's ("A Fast and Robust Method for Avoiding Self-Intersection",
//! Ray Tracing Gems, 2019, ch. 6): each coordinate of the hit point moves a fixed number of units in
//! the last place along the geometric normal, which scales the offset with the magnitude of the
//! coordinate, the same way the rounding error of the hit point scales. Coordinates close to zero
//! have tiny ulps but carry the rounding error of larger operands, so near the origin a fixed
//! float offset is used instead.

use glam::{Vec3, Vec3A};

/// Coordinates with magnitude below this use the float offset (world units).
const ORIGIN: f32 = 1.0 / 32.0;
/// Float offset along the normal near the origin (world units).
const FLOAT_SCALE: f32 = 1.0 / 65536.0;
/// Integer offset along the normal elsewhere (units in the last place of each coordinate).
const INT_SCALE: f32 = 256.0;

/// Moves the surface point `p` off its surface, to the side of the unit geometric normal `ng`
/// that the direction `dir` leaves into (the side of `-ng` when `dir . ng < 0`).
///
/// A ray from the returned point in direction `dir` does not hit the surface around `p` again.
/// The offset is about `1.5e-5 * |p|` per coordinate (256 ulps), and `1.5e-5` world units for
/// coordinates smaller than `1/32`.
#[inline]
pub fn offset_ray_origin(p: Vec3, ng: Vec3, dir: Vec3) -> Vec3 {
    let (front, back) = offset_both_sides(p, ng);
    if ng.dot(dir) < 0.0 { back } else { front }
}

/// [`offset_ray_origin`] to both sides at once: `p` moved to the side of the unit geometric
/// normal `ng` and to the side of `-ng`. Each coordinate moves `trunc(INT_SCALE · ng)` units in
/// the last place on the front (away from zero for a positive count, towards it for a negative
/// one) and the opposite on the back, or `±FLOAT_SCALE · ng` where it is below `ORIGIN` in
/// magnitude.
#[inline]
pub(crate) fn offset_both_sides(p: Vec3, ng: Vec3) -> (Vec3, Vec3) {
    let (p, ng) = (Vec3A::from(p), Vec3A::from(ng));
    let (front_ulps, back_ulps) = moved_by_ulps(p, ng);
    let float_offset = FLOAT_SCALE * ng;
    let near_origin = p.abs().cmplt(Vec3A::splat(ORIGIN));
    (
        Vec3::from(Vec3A::select(near_origin, p + float_offset, front_ulps)),
        Vec3::from(Vec3A::select(near_origin, p - float_offset, back_ulps)),
    )
}

/// `p` moved by `trunc(INT_SCALE · ng)` units in the last place per coordinate, away from zero
/// for a positive count (the front), and by the negated counts (the back): the bit patterns plus
/// and minus the counts, negated for negative coordinates. Only meant for coordinates of
/// magnitude at least `ORIGIN`, whose bit patterns cannot cross zero. Four lanes at once with
/// SSE2 (part of every x86-64 processor): the conversion truncates as `as i32` does for the
/// counts of a unit normal, at most 256 in magnitude.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn moved_by_ulps(p: Vec3A, ng: Vec3A) -> (Vec3A, Vec3A) {
    use std::arch::x86_64::{
        __m128, _mm_add_epi32, _mm_castps_si128, _mm_castsi128_ps, _mm_cvttps_epi32,
        _mm_srai_epi32, _mm_sub_epi32, _mm_xor_si128,
    };
    // SAFETY: SSE2 is part of the x86-64 baseline, so these instructions are always there.
    let (front, back) = unsafe {
        let counts = _mm_cvttps_epi32(__m128::from(INT_SCALE * ng));
        let bits = _mm_castps_si128(__m128::from(p));
        // All ones in the lanes of negative coordinates: there `(c ^ -1) - (-1)` is `-c`.
        let negative = _mm_srai_epi32::<31>(bits);
        let away = _mm_sub_epi32(_mm_xor_si128(counts, negative), negative);
        (
            _mm_castsi128_ps(_mm_add_epi32(bits, away)),
            _mm_castsi128_ps(_mm_sub_epi32(bits, away)),
        )
    };
    (Vec3A::from(front), Vec3A::from(back))
}

/// [`moved_by_ulps`] one coordinate at a time: the version for other processors, and the
/// reference the SSE2 one is tested against.
#[cfg(any(test, not(target_arch = "x86_64")))]
fn moved_by_ulps_scalar(p: Vec3A, ng: Vec3A) -> (Vec3A, Vec3A) {
    let counts = (INT_SCALE * ng).as_ivec3();
    let moved = |sign: i32| {
        Vec3A::new(
            offset_ulps(p.x, sign * counts.x),
            offset_ulps(p.y, sign * counts.y),
            offset_ulps(p.z, sign * counts.z),
        )
    };
    (moved(1), moved(-1))
}

#[cfg(not(target_arch = "x86_64"))]
use moved_by_ulps_scalar as moved_by_ulps;

/// Moves `x` by `ulps` units in the last place, away from zero for positive `ulps`.
#[cfg(any(test, not(target_arch = "x86_64")))]
fn offset_ulps(x: f32, ulps: i32) -> f32 {
    let signed = if x < 0.0 { -ulps } else { ulps };
    f32::from_bits((x.to_bits() as i32).wrapping_add(signed) as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Units in the last place from `a` to `b`, two floats of the same sign.
    fn ulps_between(a: f32, b: f32) -> i32 {
        (b.to_bits() as i32) - (a.to_bits() as i32)
    }

    /// Only where the four-lane version exists: elsewhere it is the scalar one.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_four_lane_ulp_moves_are_those_of_one_coordinate_at_a_time() {
        // Far from zero (where the ulp moves are used) and near it, both signs, with normals
        // whose scaled coordinates truncate from either side of an integer, and axis normals.
        let mut rng = crate::test_rng::TestRng(11);
        let mut cases = vec![
            (Vec3A::new(1e4, -3.0, 7.0), Vec3A::Y),
            (Vec3A::new(-0.5, 2.0, -1e6), Vec3A::NEG_Z),
            (Vec3A::new(f32::MAX, -f32::MAX, 1.0), Vec3A::ONE.normalize()),
        ];
        for scale in [0.05, 1.0, 3e4] {
            for _ in 0..500 {
                cases.push((scale * rng.vec_a(), rng.vec_a().normalize()));
            }
        }
        for (p, ng) in cases {
            let (front, back) = moved_by_ulps(p, ng);
            let (front_ref, back_ref) = moved_by_ulps_scalar(p, ng);
            let what = format!("p {p:?}, ng {ng:?}");
            assert_eq!(
                front.to_array().map(f32::to_bits),
                front_ref.to_array().map(f32::to_bits),
                "front: {what}"
            );
            assert_eq!(
                back.to_array().map(f32::to_bits),
                back_ref.to_array().map(f32::to_bits),
                "back: {what}"
            );
        }
    }

    #[test]
    fn offset_moves_to_the_side_of_dir() {
        let p = Vec3::new(0.3, -2.0, 5.0);
        let ng = Vec3::new(0.0, 0.6, 0.8);
        for (dir, sign) in [(ng, 1.0), (-ng, -1.0), (Vec3::new(1.0, 0.1, 0.0), 1.0)] {
            let o = offset_ray_origin(p, ng, dir);
            assert!(
                sign * (o - p).dot(ng) > 0.0,
                "dir {dir}: {o} not on the right side of {p}"
            );
        }
    }

    #[test]
    fn offset_is_256_ulps_away_from_origin_and_fixed_near_it() {
        let p = Vec3::new(1000.0, -3.0, 0.001);
        let o = offset_ray_origin(p, Vec3::X, Vec3::X);
        assert_eq!(ulps_between(p.x, o.x), 256);
        assert_eq!(o.y, p.y);
        assert_eq!(o.z, p.z);
        let o = offset_ray_origin(p, Vec3::NEG_Y, Vec3::NEG_Y);
        // A negative coordinate moving further from zero grows in magnitude.
        assert_eq!(ulps_between(-p.y, -o.y), 256);
        let o = offset_ray_origin(p, Vec3::Z, Vec3::NEG_Z);
        assert_eq!(o.z, p.z - FLOAT_SCALE);
    }

    #[test]
    fn offset_is_finite_at_zero_and_at_signed_zero() {
        for p in [Vec3::ZERO, Vec3::new(-0.0, 0.0, -0.0)] {
            let o = offset_ray_origin(p, Vec3::ONE.normalize(), Vec3::NEG_ONE);
            assert!(o.is_finite());
            assert!(o.cmplt(Vec3::ZERO).all());
        }
    }
}
