//! Two-sided z-tests with Šidák correction: comparing Monte Carlo estimates whose difference is
//! approximately normal (block or pixel means against a reference).

use crate::chi2::gamma_q;

/// The per-test level that keeps the family-wise level at `family_alpha` over `tests`
/// independent tests (Šidák): 1 − (1 − α)^(1/n).
pub fn sidak_alpha(family_alpha: f64, tests: usize) -> f64 {
    1.0 - (1.0 - family_alpha).powf(1.0 / tests.max(1) as f64)
}

/// P(|Z| ≥ |z|) for a standard normal Z: erfc(|z| / √2), computed as the regularised upper
/// incomplete gamma function Q(½, z² / 2).
pub fn two_sided_p_value(z: f64) -> f64 {
    if z.is_nan() {
        return 0.0;
    }
    gamma_q(0.5, 0.5 * z * z)
}

/// The |z| above which a two-sided test at level `alpha` rejects (e.g. 1.96 for 0.05).
pub fn two_sided_threshold(alpha: f64) -> f64 {
    let (mut lo, mut hi) = (0.0_f64, 40.0_f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if two_sided_p_value(mid) > alpha {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thresholds_match_normal_tables() {
        // Standard normal table: Φ⁻¹(0.975) = 1.959964, Φ⁻¹(0.995) = 2.575829, Φ⁻¹(0.9995) = 3.290527.
        for (alpha, z) in [(0.05, 1.959_964), (0.01, 2.575_829), (0.001, 3.290_527)] {
            let t = two_sided_threshold(alpha);
            assert!((t - z).abs() < 1e-5, "alpha {alpha}: {t} against {z}");
        }
    }

    #[test]
    fn sidak_keeps_the_family_level() {
        let each = sidak_alpha(0.01, 1000);
        assert!((1.0 - (1.0 - each).powi(1000) - 0.01).abs() < 1e-12);
        assert!((sidak_alpha(0.05, 1) - 0.05).abs() < 1e-15);
    }
}
