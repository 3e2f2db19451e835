//! Moving ray origins off surfaces so that a new ray does not hit the surface it starts on.
//!
//! The method is Wächter and Binder's ("A Fast and Robust Method for Avoiding Self-Intersection",
//! Ray Tracing Gems, 2019, ch. 6): each coordinate of the hit point moves a fixed number of units in
//! the last place along the geometric normal, which scales the offset with the magnitude of the
//! coordinate, the same way the rounding error of the hit point scales. Coordinates close to zero
//! have tiny ulps but carry the rounding error of larger operands, so near the origin a fixed
//! float offset is used instead.

use glam::{IVec3, Vec3};

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
    let n = if ng.dot(dir) < 0.0 { -ng } else { ng };
    moved_along(p, n, (INT_SCALE * n).as_ivec3())
}

/// [`offset_ray_origin`] to both sides at once: `p` moved to the side of `ng` and to the side of
/// `-ng`, the integer offsets converted once for both (truncation is odd, so the other side's
/// are their negations): bit for bit the points `offset_ray_origin(p, ng, ng)` and
/// `offset_ray_origin(p, ng, -ng)`.
#[inline]
pub(crate) fn offset_both_sides(p: Vec3, ng: Vec3) -> (Vec3, Vec3) {
    let of_i = (INT_SCALE * ng).as_ivec3();
    (moved_along(p, ng, of_i), moved_along(p, -ng, -of_i))
}

/// `p` moved along the unit vector `n`: by `of_i` = `INT_SCALE * n` (truncated) units in the last
/// place per coordinate, and by `FLOAT_SCALE * n` for coordinates near zero.
#[inline(always)]
fn moved_along(p: Vec3, n: Vec3, of_i: IVec3) -> Vec3 {
    let p_i = Vec3::new(
        offset_ulps(p.x, of_i.x),
        offset_ulps(p.y, of_i.y),
        offset_ulps(p.z, of_i.z),
    );
    let p_f = p + FLOAT_SCALE * n;
    Vec3::select(p.abs().cmplt(Vec3::splat(ORIGIN)), p_f, p_i)
}

/// Moves `x` by `ulps` units in the last place, away from zero for positive `ulps`.
/// Only used for `|x| >= ORIGIN`, where the bit pattern cannot cross zero.
#[inline]
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
