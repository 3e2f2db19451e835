//! Weighted reservoir sampling: selection probability ∝ weight, bad weights ignored, and RIS estimates
//! with the unbiased contribution weight are unbiased.
//!
//! Chi-square tests: α = 0.01 each (two in this file), fixed seeds; the mean test uses 4 standard
//! errors. The one-number reservoir is also checked on an even grid of numbers, exactly.

use sampling::Reservoir;
use sampling::chi2::{Chi2Config, chi2_discrete};

#[test]
fn an_empty_reservoir_selects_nothing() {
    let r: Reservoir<u32> = Reservoir::default();
    assert_eq!(r.selected(), None);
    assert_eq!(r.count(), 0);
    assert_eq!(r.weight_sum(), 0.0);
    assert_eq!(r.contribution_weight(1.0), 0.0);
}

#[test]
fn selects_each_candidate_with_probability_proportional_to_its_weight() {
    let weights = [1.0_f32, 0.0, 3.0, 0.5, 5.0, 2.5];
    let total: f64 = weights.iter().map(|&w| f64::from(w)).sum();
    let outcome = chi2_discrete(
        weights.len(),
        |rng| {
            let mut r = Reservoir::new();
            for (i, &w) in weights.iter().enumerate() {
                r.update(i, w, rng.next_f32());
            }
            r.into_selected()
        },
        |i| f64::from(weights[i]) / total,
        &Chi2Config {
            seed: 3,
            sample_count: 300_000,
            ..Chi2Config::default()
        },
    );
    assert!(outcome.passed, "{outcome}");
}

#[test]
fn one_rescaled_number_selects_in_proportion_to_weight() {
    let weights = [1.0_f32, 0.0, 3.0, 0.5, 5.0, 2.5];
    let total: f64 = weights.iter().map(|&w| f64::from(w)).sum();
    let select = |mut u: f32| {
        let mut r = Reservoir::new();
        for (i, &w) in weights.iter().enumerate() {
            r.update_reusing(i, w, &mut u);
            assert!((0.0..1.0).contains(&u), "u left [0, 1): {u}");
        }
        r.into_selected()
    };
    let outcome = chi2_discrete(
        weights.len(),
        |rng| select(rng.next_f32()),
        |i| f64::from(weights[i]) / total,
        &Chi2Config {
            seed: 5,
            sample_count: 300_000,
            ..Chi2Config::default()
        },
    );
    assert!(outcome.passed, "{outcome}");
    // On an even grid of u each candidate takes a share of the grid within rounding of its
    // probability: the selection is a partition of [0, 1), not merely right on average.
    let grid = 1 << 16;
    let mut counts = [0u32; 6];
    for k in 0..grid {
        let u = (k as f32 + 0.5) / grid as f32;
        counts[select(u).expect("a positive weight")] += 1;
    }
    for (i, &count) in counts.iter().enumerate() {
        let share = f64::from(count) / f64::from(grid);
        let expected = f64::from(weights[i]) / total;
        assert!(
            (share - expected).abs() < 1e-3,
            "candidate {i}: {share} vs {expected}"
        );
    }
}

#[test]
fn one_rescaled_number_fails_the_grid_check_if_not_rescaled() {
    // The power of the grid check above: reusing u unchanged for every candidate (the mistake
    // the rescaling avoids) correlates the decisions and misses the probabilities.
    let weights = [1.0_f32, 3.0, 5.0];
    let total: f64 = weights.iter().map(|&w| f64::from(w)).sum();
    let grid = 1 << 12;
    let mut counts = [0u32; 3];
    for k in 0..grid {
        let u = (k as f32 + 0.5) / grid as f32;
        let mut r = Reservoir::new();
        for (i, &w) in weights.iter().enumerate() {
            r.update(i, w, u);
        }
        counts[r.into_selected().unwrap()] += 1;
    }
    let worst = counts
        .iter()
        .zip(weights)
        .map(|(&c, w)| (f64::from(c) / f64::from(grid) - f64::from(w) / total).abs())
        .fold(0.0, f64::max);
    assert!(worst > 0.05, "a reused number looked fine: {counts:?}");
}

#[test]
fn bad_weights_are_counted_but_never_selected() {
    let mut r = Reservoir::new();
    assert!(!r.update("zero", 0.0, 0.0));
    assert!(!r.update("negative", -1.0, 0.0));
    assert!(!r.update("nan", f32::NAN, 0.0));
    assert!(!r.update("infinite", f32::INFINITY, 0.0));
    assert_eq!(r.selected(), None);
    assert!(
        r.update("first positive", 0.5, 0.999_999_94),
        "the first positive weight is always kept"
    );
    assert!(!r.update("zero again", 0.0, 0.0));
    assert_eq!(r.selected(), Some(&"first positive"));
    assert_eq!(r.count(), 6);
    assert_eq!(r.weight_sum(), 0.5);
    // W = Σw / (M p̂(y)) = 0.5 / (6 · 0.25).
    assert!((r.contribution_weight(0.25) - 1.0 / 3.0).abs() < 1e-7);
    assert_eq!(r.contribution_weight(0.0), 0.0);
    assert_eq!(r.contribution_weight(f32::NAN), 0.0);
}

#[test]
fn resampled_importance_sampling_is_unbiased() {
    // ∫₀¹ f with f(x) = 3x² (= 1), M = 8 uniform candidates (p = 1), target p̂(x) = x + 0.1.
    // Over 100 000 trials the mean of f(y) W lies within 4 standard errors of 1.
    let f = |x: f32| 3.0 * x * x;
    let target = |x: f32| x + 0.1;
    let mut rng = sampling::Rng::new(17);
    let trials = 100_000;
    let (mut sum, mut sum_sq) = (0.0_f64, 0.0_f64);
    for _ in 0..trials {
        let mut r = Reservoir::new();
        for _ in 0..8 {
            let x = rng.next_f32();
            r.update(x, target(x) / 1.0, rng.next_f32());
        }
        let y = *r.selected().expect("positive target everywhere");
        let estimate = f64::from(f(y) * r.contribution_weight(target(y)));
        sum += estimate;
        sum_sq += estimate * estimate;
    }
    let mean = sum / f64::from(trials);
    let variance = sum_sq / f64::from(trials) - mean * mean;
    let standard_error = (variance / f64::from(trials)).sqrt();
    assert!(
        (mean - 1.0).abs() < 4.0 * standard_error,
        "mean {mean} ± {standard_error}"
    );
    // Resampling towards the target must beat plain uniform sampling (variance of 3x²: 4/5).
    assert!(variance < 0.8, "RIS variance {variance}");
}
