//! The alias table: refusal of bad weights, exact pmfs, and sampling frequencies equal to the pmf.
//!
//! Chi-square test: α = 0.01 (one test in this file), fixed seed.

use proptest::prelude::*;
use sampling::chi2::{Chi2Config, chi2_discrete};
use sampling::distribution::{AliasTable, AliasTableError};

mod common;

#[test]
fn refuses_weights_it_cannot_sample() {
    assert_eq!(AliasTable::new(&[]).unwrap_err(), AliasTableError::Empty);
    assert_eq!(
        AliasTable::new(&[0.0, 0.0]).unwrap_err(),
        AliasTableError::ZeroTotal
    );
    assert_eq!(
        AliasTable::new(&[1.0, -0.5]).unwrap_err(),
        AliasTableError::Negative(1)
    );
    assert_eq!(
        AliasTable::new(&[1.0, f32::NAN]).unwrap_err(),
        AliasTableError::NonFinite(1)
    );
    assert_eq!(
        AliasTable::new(&[f32::INFINITY]).unwrap_err(),
        AliasTableError::NonFinite(0)
    );
    assert!(AliasTableError::Negative(3).to_string().contains('3'));
}

#[test]
fn pmf_is_the_normalised_weight() {
    let weights = [1.0, 0.0, 3.0, 4.0];
    let table = AliasTable::new(&weights).expect("valid weights");
    assert_eq!(table.len(), 4);
    assert!(!table.is_empty());
    for (i, w) in weights.iter().enumerate() {
        assert!(
            (table.pmf(i) - w / 8.0).abs() < 1e-7,
            "pmf({i}) = {}",
            table.pmf(i)
        );
    }
    assert_eq!(table.pmf(4), 0.0);
    let single = AliasTable::new(&[0.25]).expect("valid weights");
    assert_eq!(single.sample(0.0), (0, 1.0));
    assert_eq!(single.sample(0.999_999_94), (0, 1.0));
}

#[test]
fn chi_square_against_the_weights() {
    let weights = [1.0_f32, 0.0, 3.0, 0.5, 7.0, 0.0, 2.0, 1e-3, 10.0, 0.25];
    let total: f64 = weights.iter().map(|&w| f64::from(w)).sum();
    let table = AliasTable::new(&weights).expect("valid weights");
    let outcome = chi2_discrete(
        weights.len(),
        |rng| {
            let (i, pmf) = table.sample(rng.next_f32());
            // The returned pmf must be the chosen index's.
            assert_eq!(pmf, table.pmf(i));
            Some(i)
        },
        |i| f64::from(weights[i]) / total,
        &Chi2Config {
            seed: 5,
            sample_count: 500_000,
            ..Chi2Config::default()
        },
    );
    println!("figure: alias table: {}", outcome.summary());
    assert!(outcome.passed, "{outcome}");
}

#[test]
fn zero_weights_are_never_returned_even_at_the_ends_of_u() {
    let weights = [0.0, 2.0, 0.0, 0.0, 1.0, 0.0];
    let table = AliasTable::new(&weights).expect("valid weights");
    let steps = 100_000;
    let us = (0..steps)
        .map(|k| k as f32 / steps as f32)
        .chain([0.999_999_94, 1.0, -0.5, 2.0]);
    for u in us {
        let (i, pmf) = table.sample(u);
        assert!(weights[i] > 0.0, "u = {u} chose index {i} of weight 0");
        assert!(pmf > 0.0);
    }
}

proptest! {
    #![proptest_config(common::fixed_seed(32))]

    #[test]
    fn the_share_of_u_mapped_to_each_index_is_its_pmf(
        weights in prop::collection::vec(prop_oneof![Just(0.0_f32), 0.0_f32..100.0, 1e-6_f32..1e-3], 1..40),
    ) {
        prop_assume!(weights.iter().any(|&w| w > 0.0));
        let table = AliasTable::new(&weights).expect("valid weights");
        let total: f64 = weights.iter().map(|&w| f64::from(w)).sum();
        // A midpoint grid with `per_column` points in each of the n columns of u: every column's
        // split between its index and its alias is resolved to 1 / per_column of the column, so each
        // index's share is within n / (n · per_column) = 1 / per_column of its pmf.
        let per_column = 20_000;
        let points = weights.len() * per_column;
        let mut hits = vec![0_u32; weights.len()];
        for k in 0..points {
            let u = ((k as f64 + 0.5) / points as f64) as f32;
            hits[table.sample(u).0] += 1;
        }
        for (i, &w) in weights.iter().enumerate() {
            let share = f64::from(hits[i]) / points as f64;
            let pmf = f64::from(w) / total;
            prop_assert!((share - pmf).abs() <= 1.5 / per_column as f64,
                "index {i}: share {share}, pmf {pmf}");
            prop_assert!((f64::from(table.pmf(i)) - pmf).abs() <= 1e-6 * pmf.max(1e-6));
        }
    }
}
