//! The xorshift32 generator: seeding, replay, uniformity of floats and bounded integers, `rand_core`.
//!
//! Statistical tests use fixed seeds and α = 0.01, Šidák-corrected over the chi-square tests in this file.

use glam::UVec2;
use sampling::chi2::{Chi2Config, Chi2Domain, chi2_discrete, chi2_test};
use sampling::rng::{Rng, sample_seed, unit_f32_from_bits, wang_hash};

/// Chi-square tests in this file, for the Šidák correction.
const CHI2_TESTS: u32 = 10;

fn config(seed: u32, sample_count: u32) -> Chi2Config {
    Chi2Config {
        seed,
        sample_count,
        resolution: 32,
        test_count: CHI2_TESTS,
        ..Chi2Config::default()
    }
}

/// The modular inverse of an odd number modulo 2³² (Newton's iteration doubles the correct bits).
fn inverse_odd(a: u32) -> u32 {
    let mut inverse = a;
    for _ in 0..5 {
        inverse = inverse.wrapping_mul(2_u32.wrapping_sub(a.wrapping_mul(inverse)));
    }
    inverse
}

/// Undoes Wang's hash step by step (each step is a bijection of u32).
fn wang_hash_inverse(mut x: u32) -> u32 {
    x ^= (x >> 15) ^ (x >> 30);
    x = x.wrapping_mul(inverse_odd(0x27d4_eb2d));
    x ^= (x >> 4) ^ (x >> 8) ^ (x >> 12) ^ (x >> 16) ^ (x >> 20) ^ (x >> 24) ^ (x >> 28);
    x = x.wrapping_mul(inverse_odd(9));
    x ^ 61 ^ (x >> 16)
}

#[test]
fn the_seed_that_hashes_to_zero_still_gives_a_working_generator() {
    let bad_seed = wang_hash_inverse(0);
    assert_eq!(wang_hash(bad_seed), 0, "the inverse is wrong");
    // A zero xorshift state would output zeros forever.
    let mut rng = Rng::new(bad_seed);
    let outputs: Vec<u32> = (0..4).map(|_| rng.next_u32()).collect();
    assert!(outputs.iter().all(|&x| x != 0), "{outputs:?}");
    assert!(outputs.windows(2).all(|w| w[0] != w[1]), "{outputs:?}");
}

#[test]
fn wang_hash_inverse_round_trips() {
    for x in [0_u32, 1, 61, 0xDEAD_BEEF, u32::MAX, 123_456_789] {
        assert_eq!(wang_hash_inverse(wang_hash(x)), x);
    }
}

#[test]
fn floats_map_the_top_24_bits_and_never_reach_one() {
    assert_eq!(unit_f32_from_bits(0), 0.0);
    assert_eq!(unit_f32_from_bits(0xFF), 0.0);
    assert_eq!(unit_f32_from_bits(u32::MAX), 1.0 - 2.0_f32.powi(-24));
    assert_eq!(unit_f32_from_bits(0x8000_0000), 0.5);
    let mut a = Rng::new(3);
    let mut b = a.clone();
    for _ in 0..1000 {
        let x = a.next_f32();
        assert_eq!(x, unit_f32_from_bits(b.next_u32()));
        assert!((0.0..1.0).contains(&x));
        assert_eq!(
            (x * 16_777_216.0).fract(),
            0.0,
            "{x} is not a multiple of 2^-24"
        );
    }
}

#[test]
fn floats_are_uniform_in_one_dimension() {
    let bins = 1000;
    let outcome = chi2_discrete(
        bins,
        |rng| Some((rng.next_f32() * bins as f32) as usize),
        |_| 1.0 / bins as f64,
        &config(1, 1_000_000),
    );
    assert!(outcome.passed, "{outcome}");
}

#[test]
fn consecutive_float_pairs_are_uniform_on_the_square() {
    let outcome = chi2_test(
        Chi2Domain::UnitSquare,
        |rng| Some(glam::Vec3::new(rng.next_f32(), rng.next_f32(), 0.0)),
        |_| 1.0,
        &config(2, 500_000),
    );
    assert!(outcome.passed, "{outcome}");
}

#[test]
fn bounded_integers_are_uniform_for_small_ranges() {
    for (seed, n) in [(3, 2_u32), (4, 3), (5, 7), (6, 1000)] {
        let outcome = chi2_discrete(
            n as usize,
            |rng| Some(rng.next_below(n) as usize),
            |_| 1.0 / f64::from(n),
            &config(seed, 200_000),
        );
        assert!(outcome.passed, "next_below({n}): {outcome}");
    }
    let mut rng = Rng::new(9);
    assert!((0..100).all(|_| rng.next_below(1) == 0));
}

#[test]
fn bounded_integers_have_no_modulo_bias_for_large_ranges() {
    // With `next_u32() % n` for n = 3 · 2³⁰, values below 2³⁰ would come up twice as often
    // (probability 1/2 instead of 1/3): the thirds of the range must be equally likely.
    let n = 3 << 30;
    let outcome = chi2_discrete(
        3,
        |rng| Some((rng.next_below(n) >> 30) as usize),
        |_| 1.0 / 3.0,
        &config(7, 300_000),
    );
    assert!(outcome.passed, "{outcome}");

    // n = 2³² − 1 in 16 buckets of 2²⁸ values, the last one a value short.
    let n = u32::MAX;
    let bucket = 1_u64 << 28;
    let outcome = chi2_discrete(
        16,
        |rng| Some((rng.next_below(n) >> 28) as usize),
        |i| {
            let size = if i == 15 { bucket - 1 } else { bucket };
            size as f64 / f64::from(n)
        },
        &config(8, 300_000),
    );
    assert!(outcome.passed, "{outcome}");
}

#[test]
#[should_panic(expected = "empty")]
fn bounded_integers_refuse_an_empty_range() {
    Rng::new(0).next_below(0);
}

#[test]
fn per_sample_streams_replay_and_differ() {
    let pixel = UVec2::new(17, 923);
    let draw = |pixel, index, seed| {
        let mut rng = Rng::for_sample(pixel, index, seed);
        [rng.next_u32(), rng.next_u32(), rng.next_u32()]
    };
    assert_eq!(draw(pixel, 5, 1), draw(pixel, 5, 1));
    assert_eq!(
        Rng::for_sample(pixel, 5, 1),
        Rng::new(sample_seed(pixel, 5, 1))
    );
    let reference = draw(pixel, 5, 1);
    for other in [
        draw(UVec2::new(18, 923), 5, 1),
        draw(UVec2::new(17, 924), 5, 1),
        draw(UVec2::new(923, 17), 5, 1),
        draw(pixel, 6, 1),
        draw(pixel, 5, 2),
    ] {
        assert_ne!(reference, other);
    }

    // Distinct (pixel, index) triples get distinct seeds (4096 seeds among 2³²: a collision would be
    // a 1-in-500 accident for a good hash, and routine for a weak one).
    let mut seeds: Vec<u32> = (0..32)
        .flat_map(|y| {
            (0..32).flat_map(move |x| (0..4).map(move |i| sample_seed(UVec2::new(x, y), i, 0)))
        })
        .collect();
    seeds.sort_unstable();
    seeds.dedup();
    assert_eq!(seeds.len(), 32 * 32 * 4);
}

/// Pearson's correlation coefficient of paired values.
fn correlation(pairs: &[(f64, f64)]) -> f64 {
    let n = pairs.len() as f64;
    let (mx, my) = pairs
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (x, y) in pairs {
        sxy += (x - mx) * (y - my);
        sxx += (x - mx) * (x - mx);
        syy += (y - my) * (y - my);
    }
    sxy / (sxx * syy).sqrt()
}

#[test]
fn neighbouring_seeds_and_pixels_give_uncorrelated_streams() {
    // 40 000 pairs: |ρ| of independent streams is below 4 / √n = 0.02 with probability 1 − 6e-5.
    let n = 40_000_u32;
    let bound = 4.0 / f64::from(n).sqrt();
    let seeds: Vec<(f64, f64)> = (0..n)
        .map(|s| {
            let a = Rng::new(s).next_f32();
            let b = Rng::new(s + 1).next_f32();
            (f64::from(a), f64::from(b))
        })
        .collect();
    let rho = correlation(&seeds);
    assert!(rho.abs() < bound, "consecutive seeds: correlation {rho}");
    let pixels: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let p = UVec2::new(i % 200, i / 200);
            let a = Rng::for_sample(p, 0, 0).next_f32();
            let b = Rng::for_sample(p + UVec2::X, 0, 0).next_f32();
            (f64::from(a), f64::from(b))
        })
        .collect();
    let rho = correlation(&pixels);
    assert!(rho.abs() < bound, "neighbouring pixels: correlation {rho}");
}

#[test]
fn implements_rand_core_traits() {
    use rand_core::Rng as _;
    let mut a = Rng::new(11);
    let mut b = a.clone();
    let low = u64::from(b.next_u32());
    let high = u64::from(b.next_u32());
    assert_eq!(rand_core::Rng::next_u64(&mut a), (high << 32) | low);
    assert_eq!(rand_core::Rng::next_u32(&mut a), b.next_u32());

    let mut bytes = [0_u8; 7];
    a.fill_bytes(&mut bytes);
    let first = b.next_u32().to_le_bytes();
    let second = b.next_u32().to_le_bytes();
    assert_eq!(bytes[..4], first);
    assert_eq!(bytes[4..], second[..3]);
}
