//! Sine and cosine for the warps: of angles in [−π/4, π/4] by polynomials, and of whole turns
//! (2π·t) by reducing to those. Warps need them once per sample; the general `sin_cos` must
//! first reduce an arbitrary argument and costs several times more.

use std::f32::consts::FRAC_PI_2;

/// sin x and cos x for |x| ≤ π/4 by their Taylor polynomials to x⁷ and x⁸, whose truncation
/// errors there (below 3.2·10⁻⁷ and 2.5·10⁻⁸) are about float rounding.
#[inline]
pub(crate) fn sin_cos_quarter(x: f32) -> (f32, f32) {
    let x2 = x * x;
    // Products with reciprocal constants: a division by 6.0 would not be turned into one.
    let sin = x * (1.0 - x2 * (1.0 / 6.0) * (1.0 - x2 * (1.0 / 20.0) * (1.0 - x2 * (1.0 / 42.0))));
    let cos = 1.0
        - x2 * 0.5
            * (1.0 - x2 * (1.0 / 12.0) * (1.0 - x2 * (1.0 / 30.0) * (1.0 - x2 * (1.0 / 56.0))));
    (sin, cos)
}

/// (sin 2πt, cos 2πt) for `t` ≥ 0 in turns (the warps pass [0, 1)), within
/// 4·10⁻⁷ of the exact values: t is split into the nearest quarter turn q and a remainder of at
/// most an eighth of a turn, and the remainder's sine and cosine are rotated by q quarter turns
/// without branches (q is random in the warps, so a branch would be mispredicted).
#[inline]
pub fn sin_cos_turn(t: f32) -> (f32, f32) {
    let quarters = 4.0 * t;
    // Rounding by conversion: `round` is a library call without SSE4.1.
    let q = (quarters + 0.5) as i32;
    let (sin, cos) = sin_cos_quarter((quarters - q as f32) * FRAC_PI_2);
    // Odd quarters swap sine and cosine, by xor with a mask (an `if` on the parity compiled to a
    // branch, mispredicted half the time); quarters 2, 3 negate the sine, 1, 2 the cosine.
    let (sin, cos) = (sin.to_bits(), cos.to_bits());
    let swap = ((q & 1) as u32).wrapping_neg() & (sin ^ cos);
    let sin_sign = ((q & 2) as u32) << 30;
    let cos_sign = (((q + 1) & 2) as u32) << 30;
    (
        f32::from_bits(sin ^ swap ^ sin_sign),
        f32::from_bits(cos ^ swap ^ cos_sign),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::{FRAC_PI_4, TAU};

    #[test]
    fn quarter_sin_cos_matches_the_library_within_float_rounding() {
        for i in 0..=10_000 {
            let x = (i as f32 / 5_000.0 - 1.0) * FRAC_PI_4;
            let (sin, cos) = sin_cos_quarter(x);
            let (lib_sin, lib_cos) = x.sin_cos();
            assert!((sin - lib_sin).abs() < 4e-7, "sin {x}: {sin} vs {lib_sin}");
            assert!((cos - lib_cos).abs() < 2e-7, "cos {x}: {cos} vs {lib_cos}");
        }
    }

    #[test]
    fn turn_sin_cos_matches_double_precision_over_every_quadrant() {
        for i in 0..=20_000 {
            let t = i as f32 / 10_000.0 + 0.000_037;
            let (sin, cos) = sin_cos_turn(t);
            let angle = f64::from(t) * std::f64::consts::TAU;
            assert!(
                (f64::from(sin) - angle.sin()).abs() < 4e-7,
                "sin 2π·{t}: {sin}"
            );
            assert!(
                (f64::from(cos) - angle.cos()).abs() < 4e-7,
                "cos 2π·{t}: {cos}"
            );
        }
        // Exact quarter turns give exact axes.
        assert_eq!(sin_cos_turn(0.0), (0.0, 1.0));
        assert_eq!(sin_cos_turn(0.25), (1.0, 0.0));
        assert_eq!(sin_cos_turn(0.5), (0.0, -1.0));
        assert_eq!(sin_cos_turn(0.75), (-1.0, 0.0));
        assert!((sin_cos_turn(1.0 - f32::EPSILON).0 + TAU * f32::EPSILON).abs() < 1e-6);
    }
}
