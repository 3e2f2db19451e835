//! The error function and its inverse, needed by Beckmann visible-normal sampling.
//!
//! Absolute errors are below 10⁻⁶, ample for sampling in `f32`.

/// The error function erf(x) = 2/√π ∫₀ˣ e^(−t²) dt; ±1 at ±∞.
pub(crate) fn erf(x: f32) -> f32 {
    1.0 - erfc(x)
}

/// The complementary error function erfc(x) = 1 − erf(x), accurate also where it is tiny.
///
/// The Chebyshev fit from Numerical Recipes (fractional error < 1.2·10⁻⁷ everywhere), evaluated
/// in `f32`, which adds about 10⁻⁶ relative rounding error.
#[expect(
    clippy::excessive_precision,
    reason = "Numerical Recipes' published coefficients, kept verbatim"
)]
pub(crate) fn erfc(x: f32) -> f32 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let erfc_abs = t * (-z * z + poly).exp();
    if x >= 0.0 { erfc_abs } else { 2.0 - erfc_abs }
}

/// The inverse error function on (−1, 1): `erf(erfinv(y)) ≈ y`; ±∞ at ±1, NaN outside [−1, 1].
///
/// Mike Giles' single-precision approximation ("Approximating the erfinv function", GPU
/// Computing Gems, 2011), relative error about 4·10⁻⁷.
#[expect(
    clippy::excessive_precision,
    reason = "Giles' published coefficients, kept verbatim"
)]
pub(crate) fn erfinv(y: f32) -> f32 {
    if y.abs() >= 1.0 {
        return if y.abs() == 1.0 {
            f32::INFINITY.copysign(y)
        } else {
            f32::NAN
        };
    }
    let mut w = -((1.0 - y) * (1.0 + y)).ln();
    let p = if w < 5.0 {
        w -= 2.5;
        let mut p = 2.810_226_36e-08;
        p = 3.432_739_39e-07 + p * w;
        p = -3.523_387_7e-06 + p * w;
        p = -4.391_506_54e-06 + p * w;
        p = 0.000_218_580_87 + p * w;
        p = -0.001_253_725_03 + p * w;
        p = -0.004_177_681_64 + p * w;
        p = 0.246_640_727 + p * w;
        1.501_409_41 + p * w
    } else {
        w = w.sqrt() - 3.0;
        let mut p = -0.000_200_214_257;
        p = 0.000_100_950_558 + p * w;
        p = 0.001_349_343_22 + p * w;
        p = -0.003_673_428_44 + p * w;
        p = 0.005_739_507_73 + p * w;
        p = -0.007_622_461_3 + p * w;
        p = 0.009_438_870_47 + p * w;
        p = 1.001_674_06 + p * w;
        2.832_976_82 + p * w
    };
    p * y
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn erf_matches_tabulated_values() {
        // Values from Abramowitz & Stegun, table 7.1.
        let table = [
            (0.0_f32, 0.0_f64),
            (0.1, 0.112_462_92),
            (0.5, 0.520_499_88),
            (1.0, 0.842_700_79),
            (1.5, 0.966_105_15),
            (2.0, 0.995_322_27),
            (3.0, 0.999_977_91),
        ];
        for (x, expected) in table {
            assert!(
                (f64::from(erf(x)) - expected).abs() < 2e-7,
                "erf({x}) = {}",
                erf(x)
            );
            assert!((f64::from(erf(-x)) + expected).abs() < 2e-7, "erf(-{x})");
        }
        assert!((erfc(3.0) - 2.209_049_7e-5).abs() < 2e-6 * 2.2e-5);
        assert_eq!(erf(f32::INFINITY), 1.0);
        assert_eq!(erf(f32::NEG_INFINITY), -1.0);
    }

    #[test]
    fn erfinv_inverts_erf() {
        for i in -999..=999 {
            let y = i as f32 / 1000.0;
            let x = erfinv(y);
            assert!(x.is_finite());
            assert!((erf(x) - y).abs() < 5e-7, "y {y}: erf(erfinv) = {}", erf(x));
        }
        for y in [1.0 - 1e-6_f32, -(1.0 - 1e-6)] {
            assert!((erf(erfinv(y)) - y).abs() < 5e-7);
        }
        assert_eq!(erfinv(1.0), f32::INFINITY);
        assert!(erfinv(1.5).is_nan());
    }
}
