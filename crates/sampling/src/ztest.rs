//! Two-sided z-tests with Šidák correction: comparing Monte Carlo estimates whose difference is
//! approximately normal (block or pixel means against a reference); and Student's t for a mean
//! whose variance is estimated from a few independent repetitions (renders with other seeds).

use crate::chi2::{gamma_q, incomplete_beta};

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

/// P(|T| ≥ |t|) for Student's t with `dof` ≥ 1 degrees of freedom: the t statistic of a mean
/// of `dof + 1` independent normal values with their sample variance. Exact, by the finite
/// series of Abramowitz and Stegun 26.7.3 (odd `dof`) and 26.7.4 (even `dof`) in θ =
/// atan(|t| / √dof). NaN gives 0 (a rejection), as in [`two_sided_p_value`].
pub fn student_t_two_sided_p_value(t: f64, dof: u32) -> f64 {
    assert!(dof >= 1, "Student's t needs at least one degree of freedom");
    if t.is_nan() {
        return 0.0;
    }
    let theta = (t.abs() / f64::from(dof).sqrt()).atan();
    let (sin, cos) = theta.sin_cos();
    let cos2 = cos * cos;
    // P(|T| < |t|), a series in cos²θ whose terms follow each other by a ratio.
    let inside = if dof.is_multiple_of(2) {
        // sin θ (1 + ½ cos²θ + (1·3)/(2·4) cos⁴θ + … + (1·3…(ν−3))/(2·4…(ν−2)) cos^(ν−2)θ)
        let (mut term, mut sum) = (1.0, 1.0);
        for k in (2..dof).step_by(2) {
            term *= cos2 * f64::from(k - 1) / f64::from(k);
            sum += term;
        }
        sin * sum
    } else {
        // (2/π)(θ + sin θ cos θ (1 + ⅔ cos²θ + … + (2·4…(ν−3))/(3·5…(ν−2)) cos^(ν−3)θ)),
        // just (2/π) θ for ν = 1
        let mut sum = 0.0;
        if dof > 1 {
            let mut term = 1.0;
            sum = 1.0;
            for k in (2..dof - 1).step_by(2) {
                term *= cos2 * f64::from(k) / f64::from(k + 1);
                sum += term;
            }
        }
        std::f64::consts::FRAC_2_PI * (theta + sin * cos * sum)
    };
    (1.0 - inside).clamp(0.0, 1.0)
}

/// P(|T| ≥ |t|) for Student's t with a real number `dof` ≥ 1 of degrees of freedom, as Welch's
/// test of two means with unequal variances gets them (Welch–Satterthwaite); the normal
/// distribution when `dof` is infinite. The regularised incomplete beta function
/// I_{ν/(ν+t²)}(ν/2, ½); at whole `dof` it equals [`student_t_two_sided_p_value`]. NaN gives 0 (a
/// rejection).
pub fn welch_two_sided_p_value(t: f64, dof: f64) -> f64 {
    assert!(
        dof >= 1.0,
        "Student's t needs at least one degree of freedom, not {dof}"
    );
    if t.is_nan() {
        return 0.0;
    }
    if dof.is_infinite() {
        return two_sided_p_value(t);
    }
    incomplete_beta(0.5 * dof, 0.5, dof / (dof + t * t))
}

/// The |t| above which a two-sided test with `dof` ≥ 1 degrees of freedom (real, or infinite for
/// the normal) rejects at level `alpha`, for [`welch_two_sided_p_value`].
pub fn welch_threshold(alpha: f64, dof: f64) -> f64 {
    let (mut lo, mut hi) = (0.0_f64, 1e3_f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if welch_two_sided_p_value(mid, dof) > alpha {
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
    fn welch_matches_the_exact_series_and_tables() {
        // At whole degrees of freedom the incomplete beta agrees with the exact series.
        for dof in [1_u32, 2, 3, 7, 15, 31, 100] {
            for t in [0.0, 0.5, 1.7, 3.0, 6.0, 40.0] {
                let (beta, series) = (
                    welch_two_sided_p_value(t, f64::from(dof)),
                    student_t_two_sided_p_value(t, dof),
                );
                assert!(
                    (beta - series).abs() < 1e-12 * series.max(1e-300) + 1e-15,
                    "dof {dof}, t {t}: {beta} against {series}"
                );
            }
        }
        // Between whole degrees of freedom the p-value lies between its neighbours'.
        let (p15, p155, p16) = (
            welch_two_sided_p_value(3.0, 15.0),
            welch_two_sided_p_value(3.0, 15.5),
            welch_two_sided_p_value(3.0, 16.0),
        );
        assert!(p16 < p155 && p155 < p15, "{p16} < {p155} < {p15}");
        // Student's t table, two-sided: t(0.05, 10) = 2.228, t(0.01, 5) = 4.032,
        // t(0.001, 30) = 3.646, t(0.05, 1) = 12.706; and the normal limit 1.960.
        for (alpha, dof, t) in [
            (0.05, 10.0, 2.228),
            (0.01, 5.0, 4.032),
            (0.001, 30.0, 3.646),
            (0.05, 1.0, 12.706),
            (0.05, f64::INFINITY, 1.960),
        ] {
            let threshold = welch_threshold(alpha, dof);
            assert!(
                (threshold - t).abs() < 1e-3,
                "t({alpha}, {dof}) = {threshold}, tables say {t}"
            );
        }
        assert_eq!(welch_two_sided_p_value(f64::NAN, 4.5), 0.0);
    }

    #[test]
    fn student_t_matches_closed_forms_and_tables() {
        // ν = 1 is Cauchy: P(|T| ≥ t) = 1 − (2/π) atan t; ν = 2: 1 − t / √(2 + t²).
        for t in [0.0, 0.3, 1.0, 4.0, 50.0] {
            let cauchy = 1.0 - std::f64::consts::FRAC_2_PI * f64::atan(t);
            assert!((student_t_two_sided_p_value(t, 1) - cauchy).abs() < 1e-14);
            let two = 1.0 - t / (2.0 + t * t).sqrt();
            assert!((student_t_two_sided_p_value(-t, 2) - two).abs() < 1e-14);
        }
        // Quantiles from t tables (two-sided level, dof, t).
        for (alpha, dof, t) in [
            (0.05, 3, 3.182_446),
            (0.05, 10, 2.228_139),
            (0.01, 7, 3.499_483),
            (0.001, 15, 4.072_765),
            (0.001, 30, 3.645_959),
        ] {
            let p = student_t_two_sided_p_value(t, dof);
            assert!(
                (p - alpha).abs() < 1e-6 * alpha.max(1e-3),
                "dof {dof}: {p} against {alpha}"
            );
        }
        // Many degrees of freedom approach the normal, from above by 2φ(t)(t³ + t)/(4ν) to first
        // order in 1/ν (the Cornish–Fisher expansion; the next order is about 3e-8 here).
        let (t, nu) = (3.0_f64, 4000.0);
        let density = (-0.5 * t * t).exp() / (2.0 * std::f64::consts::PI).sqrt();
        let expected = two_sided_p_value(t) + 2.0 * density * (t.powi(3) + t) / (4.0 * nu);
        let many = student_t_two_sided_p_value(t, nu as u32);
        assert!((many - expected).abs() < 1e-7, "{many} against {expected}");
        assert_eq!(student_t_two_sided_p_value(f64::NAN, 5), 0.0);
    }

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
