//! MIS heuristics: known values, weights of the two techniques summing to 1, the limits at 0 and ∞,
//! and an unbiased two-technique estimator.

use proptest::prelude::*;
use sampling::Rng;
use sampling::mis::{balance_heuristic, power_heuristic};

mod common;

type Heuristic = fn(f32, f32, f32, f32) -> f32;
const HEURISTICS: [(&str, Heuristic); 2] =
    [("balance", balance_heuristic), ("power", power_heuristic)];

#[test]
fn known_values() {
    assert_eq!(balance_heuristic(1.0, 1.0, 1.0, 3.0), 0.25);
    assert_eq!(balance_heuristic(2.0, 1.0, 1.0, 1.0), 2.0 / 3.0);
    assert!((power_heuristic(1.0, 1.0, 1.0, 3.0) - 0.1).abs() < 1e-7);
    assert!((power_heuristic(1.0, 2.0, 4.0, 0.25) - 0.8).abs() < 1e-7);
}

#[test]
fn limits_at_zero_and_infinity() {
    let inf = f32::INFINITY;
    for (name, h) in HEURISTICS {
        assert_eq!(
            h(1.0, 0.0, 1.0, 2.0),
            0.0,
            "{name}: f cannot produce the point"
        );
        assert_eq!(h(1.0, 0.0, 1.0, 0.0), 0.0, "{name}: neither can");
        assert_eq!(h(1.0, 2.0, 1.0, 0.0), 1.0, "{name}: only f can");
        assert_eq!(h(1.0, inf, 1.0, 5.0), 1.0, "{name}: f is a delta");
        assert_eq!(h(1.0, 5.0, 1.0, inf), 0.0, "{name}: g is a delta");
        assert_eq!(h(1.0, inf, 1.0, inf), 0.5, "{name}: both deltas");
        assert_eq!(h(0.0, 1.0, 1.0, 1.0), 0.0, "{name}: f takes no samples");
        assert_eq!(h(1.0, f32::NAN, 1.0, 1.0), 0.0, "{name}: NaN pdf");
        assert_eq!(h(1.0, 1.0, 1.0, f32::NAN), 1.0, "{name}: NaN other pdf");
        // Extreme but finite pdfs, where (n p)² over- or underflows in the textbook formula.
        assert_eq!(h(1.0, 1e-30, 1.0, 1e-30), 0.5, "{name}: tiny pdfs");
        assert_eq!(h(1.0, 3e30, 1.0, 3e30), 0.5, "{name}: huge pdfs");
    }
    assert_eq!(balance_heuristic(3.0, inf, 1.0, inf), 0.75);
    assert_eq!(power_heuristic(3.0, inf, 1.0, inf), 0.9);
    assert!((power_heuristic(1.0, 1e30, 1.0, 1e29) - 100.0 / 101.0).abs() < 1e-6);
}

fn pdf() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0_f32),
        Just(f32::INFINITY),
        Just(f32::MIN_POSITIVE),
        Just(f32::MAX),
        1e-30_f32..1e-20,
        0.0_f32..10.0,
        1e20_f32..1e30,
    ]
}

proptest! {
    #![proptest_config(common::fixed_seed(2000))]

    #[test]
    fn weights_are_finite_and_sum_to_one(
        n_f in 1.0_f32..8.0, pdf_f in pdf(), n_g in 1.0_f32..8.0, pdf_g in pdf(),
    ) {
        for (name, h) in HEURISTICS {
            let w_f = h(n_f, pdf_f, n_g, pdf_g);
            let w_g = h(n_g, pdf_g, n_f, pdf_f);
            prop_assert!((0.0..=1.0).contains(&w_f), "{name}: {w_f}");
            if pdf_f > 0.0 || pdf_g > 0.0 {
                // Wherever either technique can produce the point, its weights partition unity.
                prop_assert!((w_f + w_g - 1.0).abs() < 1e-6, "{name}: {w_f} + {w_g}");
            }
        }
        // The power heuristic favours the technique with the larger n p more strongly.
        let (b, p) = (balance_heuristic(n_f, pdf_f, n_g, pdf_g), power_heuristic(n_f, pdf_f, n_g, pdf_g));
        if b > 0.5 { prop_assert!(p >= b - 1e-6); }
        if b < 0.5 { prop_assert!(p <= b + 1e-6); }
    }
}

#[test]
fn a_two_technique_estimator_is_unbiased() {
    // ∫₀¹ 3x² dx = 1 with one sample from p_a(x) = 1 and one from p_b(x) = 2x, each weighted by MIS.
    // Over 200 000 trials the mean lies within 4 standard errors of 1 (probability 1 − 6e-5).
    let f = |x: f32| 3.0 * x * x;
    let (pa, pb) = (|_: f32| 1.0_f32, |x: f32| 2.0 * x);
    for (name, h) in HEURISTICS {
        let mut rng = Rng::new(21);
        let trials = 200_000;
        let (mut sum, mut sum_sq) = (0.0_f64, 0.0_f64);
        for _ in 0..trials {
            let xa = rng.next_f32();
            let xb = rng.next_f32().sqrt();
            let mut estimate = h(1.0, pa(xa), 1.0, pb(xa)) * f(xa) / pa(xa);
            if pb(xb) > 0.0 {
                estimate += h(1.0, pb(xb), 1.0, pa(xb)) * f(xb) / pb(xb);
            }
            sum += f64::from(estimate);
            sum_sq += f64::from(estimate) * f64::from(estimate);
        }
        let mean = sum / f64::from(trials);
        let standard_error =
            ((sum_sq / f64::from(trials) - mean * mean) / f64::from(trials)).sqrt();
        assert!(
            (mean - 1.0).abs() < 4.0 * standard_error,
            "{name}: mean {mean} ± {standard_error}"
        );
    }
}
