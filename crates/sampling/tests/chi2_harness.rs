//! The chi-square harness itself: it passes correct samplers and fails each kind of wrong one (wrong
//! shape, samples where the pdf is zero, a pdf integrating above 1, absorbed mass unaccounted for,
//! values outside the domain), and its report carries what is needed to replay a failure.
//!
//! Statistical passes use α = 0.01 and fixed seeds; the failures asserted here have p-values far below.

use glam::{Vec2, Vec3};
use sampling::chi2::{
    Chi2Config, Chi2Domain, chi2_discrete, chi2_p_value, chi2_test, integrate_pdf,
};
use sampling::warp::{
    cosine_hemisphere_pdf, sample_cosine_hemisphere, sample_uniform_sphere, uniform_hemisphere_pdf,
    uniform_sphere_pdf,
};
use std::f32::consts::TAU;

fn config(seed: u32) -> Chi2Config {
    Chi2Config {
        seed,
        sample_count: 200_000,
        resolution: 16,
        ..Chi2Config::default()
    }
}

fn u2(rng: &mut sampling::Rng) -> Vec2 {
    Vec2::new(rng.next_f32(), rng.next_f32())
}

/// Directions with density (n + 1) / (2π) cos^n θ on the upper hemisphere.
fn sample_cosine_power(u: Vec2, n: f32) -> Vec3 {
    let z = u.x.powf(1.0 / (n + 1.0));
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = (TAU * u.y).sin_cos();
    Vec3::new(r * c, r * s, z)
}

fn cosine_power_pdf(w: Vec3, n: f32) -> f32 {
    if w.z > 0.0 {
        (n + 1.0) / TAU * w.z.powf(n)
    } else {
        0.0
    }
}

#[test]
fn passes_a_correct_sampler_and_fails_a_slightly_wrong_one() {
    let sample = |rng: &mut sampling::Rng| Some(sample_cosine_power(u2(rng), 1.0));
    let right = chi2_test(
        Chi2Domain::Sphere,
        sample,
        |w| cosine_power_pdf(w, 1.0),
        &config(1),
    );
    assert!(right.passed, "{right}");
    assert_eq!(
        right.dof,
        16 * 32 / 2 - 1,
        "half the bins (the upper hemisphere) expect samples"
    );
    // A 10 % error in the exponent.
    let wrong = chi2_test(
        Chi2Domain::Sphere,
        sample,
        |w| cosine_power_pdf(w, 1.1),
        &config(1),
    );
    assert!(!wrong.passed, "{wrong}");
    assert!(wrong.p_value < 1e-6, "{wrong}");
    assert!(!wrong.worst_bins.is_empty());
}

#[test]
fn fails_a_sampler_that_lands_where_the_pdf_is_zero() {
    let outcome = chi2_test(
        Chi2Domain::Sphere,
        |rng| Some(sample_uniform_sphere(u2(rng))),
        |w| {
            if w.z >= 0.0 {
                uniform_hemisphere_pdf()
            } else {
                0.0
            }
        },
        &config(2),
    );
    assert!(!outcome.passed);
    assert!(outcome.zero_pdf_samples > 90_000, "{outcome}");
    assert!(
        outcome.report().contains("where the pdf is zero"),
        "{outcome}"
    );
}

#[test]
fn fails_a_pdf_that_integrates_above_one() {
    let outcome = chi2_test(
        Chi2Domain::Sphere,
        |rng| Some(sample_uniform_sphere(u2(rng))),
        |_| 1.01 * uniform_sphere_pdf(),
        &config(3),
    );
    assert!(!outcome.passed);
    assert!((outcome.pdf_integral - 1.01).abs() < 1e-4, "{outcome}");
    assert!(
        outcome.failures.iter().any(|f| f.contains("more than 1")),
        "{outcome}"
    );
}

/// A cosine sampler that absorbs 30 % of its samples (returns `None`).
fn lossy(rng: &mut sampling::Rng) -> Option<Vec3> {
    let w = sample_cosine_hemisphere(u2(rng));
    (rng.next_f32() >= 0.3).then_some(w)
}

#[test]
fn absorbed_mass_is_allowed_when_the_pdf_accounts_for_it() {
    let outcome = chi2_test(
        Chi2Domain::Sphere,
        lossy,
        |w| 0.7 * cosine_hemisphere_pdf(w.z),
        &config(4),
    );
    assert!(outcome.passed, "{outcome}");
    assert!(
        outcome.absorbed_samples.abs_diff(60_000) < 1_000,
        "{outcome}"
    );
    assert!((outcome.pdf_integral - 0.7).abs() < 1e-4);
}

#[test]
fn absorbed_mass_the_pdf_does_not_account_for_fails() {
    let outcome = chi2_test(
        Chi2Domain::Sphere,
        lossy,
        |w| cosine_hemisphere_pdf(w.z),
        &config(5),
    );
    assert!(!outcome.passed, "{outcome}");
    let missing = chi2_test(
        Chi2Domain::Sphere,
        |rng| Some(sample_cosine_hemisphere(u2(rng))),
        |w| 0.7 * cosine_hemisphere_pdf(w.z),
        &config(6),
    );
    assert!(!missing.passed, "{missing}");
    assert!(missing.report().contains("absorbed"), "{missing}");
}

#[test]
fn fails_values_outside_the_domain() {
    let not_unit = chi2_test(
        Chi2Domain::Sphere,
        |rng| Some(1.01 * sample_uniform_sphere(u2(rng))),
        |_| uniform_sphere_pdf(),
        &config(7),
    );
    assert!(!not_unit.passed);
    assert_eq!(not_unit.invalid_samples, 200_000);
    let nan = chi2_test(
        Chi2Domain::UnitSquare,
        |rng| {
            Some(if rng.next_f32() < 0.001 {
                Vec3::NAN
            } else {
                u2(rng).extend(0.0)
            })
        },
        |_| 1.0,
        &config(8),
    );
    assert!(!nan.passed);
    assert!(nan.report().contains("outside the domain"), "{nan}");
    let outside = chi2_discrete(3, |_| Some(3), |_| 1.0 / 3.0, &config(9));
    assert!(!outside.passed);
    assert_eq!(outside.invalid_samples, 200_000);
}

#[test]
fn the_report_replays_the_test() {
    let outcome = chi2_test(
        Chi2Domain::UnitSquare,
        |rng| Some(Vec3::new(rng.next_f32().sqrt(), rng.next_f32(), 0.0)),
        |_| 1.0,
        &Chi2Config {
            seed: 1234,
            ..config(0)
        },
    );
    assert!(!outcome.passed);
    let report = outcome.to_string();
    for needle in [
        "seed 1234",
        "200000 samples",
        "FAILED",
        "degrees of freedom",
        "x ∈ [",
    ] {
        assert!(
            report.contains(needle),
            "report lacks {needle:?}:\n{report}"
        );
    }
    assert_eq!(report, outcome.report());
}

#[test]
fn sidak_correction_and_p_values() {
    let c = Chi2Config {
        alpha: 0.01,
        test_count: 10,
        ..Chi2Config::default()
    };
    assert!((c.alpha_corrected() - (1.0 - 0.99_f64.powf(0.1))).abs() < 1e-15);
    assert!((c.alpha_corrected() - 0.001_004_529).abs() < 1e-9);
    assert!((Chi2Config::default().alpha_corrected() - 0.01).abs() < 1e-15);
    // Table: P(χ²(20) ≥ 37.566) = 0.01.
    assert!((chi2_p_value(37.566, 20) - 0.01).abs() < 1e-4);
}

#[test]
fn integrates_pdfs_over_both_domains() {
    let sphere = integrate_pdf(Chi2Domain::Sphere, |_| uniform_sphere_pdf(), 8);
    assert!((sphere - 1.0).abs() < 1e-6, "{sphere}");
    // ∫ cos θ over the upper hemisphere = π.
    let cosine = integrate_pdf(Chi2Domain::Sphere, |w| w.z.max(0.0), 8);
    assert!((cosine - std::f64::consts::PI).abs() < 1e-5, "{cosine}");
    let square = integrate_pdf(Chi2Domain::UnitSquare, |p| 2.0 * p.x, 4);
    assert!((square - 1.0).abs() < 1e-6, "{square}");
}
