//! The Sobol sampler's defining properties: every aligned power-of-two block of a pixel's samples is a
//! (0, 2)-net in each 2D dimension and stratified in each 1D dimension, whatever the seed, pixel and
//! dimension; neighbouring dimensions are not correlated; and smooth integrands get far less error
//! than with independent samples, also at counts that are not powers of two.
//!
//! Fixed seeds; the statistical test states its level. Uniformity over seeds and decorrelation of
//! distant dimensions over seeds are tested with the other samplers in `samplers.rs`. Run with
//! `--nocapture` to see the figures.

use glam::{DVec2, UVec2, Vec2};
use sampling::ztest::{sidak_alpha, two_sided_threshold};
use sampling::{AnySampler, Sampler, SamplerKind, SobolSampler};
use std::f64::consts::TAU;

/// One pixel sample's values in the layout the tests use: 2D, 1D, 1D, 2D (dimensions 0 to 3).
#[derive(Clone, Copy, Debug)]
struct Values {
    first_2d: Vec2,
    first_1d: f32,
    second_1d: f32,
    second_2d: Vec2,
}

fn draw(sampler: &mut impl Sampler, pixel: UVec2, index: u32) -> Values {
    sampler.start_pixel_sample(pixel, index);
    Values {
        first_2d: sampler.next_2d(),
        first_1d: sampler.next_1d(),
        second_1d: sampler.next_1d(),
        second_2d: sampler.next_2d(),
    }
}

/// (seed, pixel) cases of the stratification tests, including extreme pixels.
const CASES: [(u32, UVec2); 4] = [
    (0, UVec2::new(0, 0)),
    (7, UVec2::new(311, 78)),
    (0xDEAD_BEEF, UVec2::new(4095, 2)),
    (u32::MAX, UVec2::new(u32::MAX, u32::MAX)),
];

/// Largest log₂ of the block size tested.
const MAX_LOG2: u32 = 10;

/// The starts of the aligned blocks of `n` samples tested: the first block, the next ones, and one
/// far along the sequence (where all 32 bits of the index matter).
fn block_starts(n: u32) -> [u32; 4] {
    [0, n, 5 * n, 0xB000_0000]
}

/// The cell of `x` among `2^bits` equal strata of [0, 1) (exact: `x` is a multiple of 2⁻²⁴).
fn stratum(x: f32, bits: u32) -> usize {
    (f64::from(x) * f64::from(1_u32 << bits)) as usize
}

/// Every elementary interval of area 1 / `points.len()` (2ᵃ columns × 2ᵇ rows, a + b = log₂ of the
/// count) must hold exactly one point.
fn assert_net(points: &[Vec2], what: &str) {
    let k = points.len().trailing_zeros();
    assert!(points.len().is_power_of_two());
    for a in 0..=k {
        let b = k - a;
        let mut hits = vec![0_u32; points.len()];
        for p in points {
            hits[(stratum(p.y, b) << a) | stratum(p.x, a)] += 1;
        }
        if let Some(cell) = hits.iter().position(|&h| h != 1) {
            panic!(
                "{what}: in the {}x{} intervals, cell {cell} (column {}, row {}) holds {} points",
                1 << a,
                1 << b,
                cell % (1 << a),
                cell >> a,
                hits[cell]
            );
        }
    }
}

/// `xs` (a power-of-two count) must put exactly one value in each of `xs.len()` equal strata.
fn assert_stratified(xs: &[f32], what: &str) {
    let bits = xs.len().trailing_zeros();
    let mut hits = vec![0_u32; xs.len()];
    for &x in xs {
        hits[stratum(x, bits)] += 1;
    }
    assert!(hits.iter().all(|&h| h == 1), "{what}: strata hit {hits:?}");
}

/// Calls `check` with the samples of every tested aligned block and a description for failures.
fn for_every_block(mut check: impl FnMut(&[Values], &str)) {
    for (seed, pixel) in CASES {
        let mut sampler = SobolSampler::new(seed, 16);
        for log2 in 0..=MAX_LOG2 {
            let n = 1_u32 << log2;
            for start in block_starts(n) {
                let block: Vec<Values> = (start..start + n)
                    .map(|index| draw(&mut sampler, pixel, index))
                    .collect();
                let what = format!("seed {seed}, pixel {pixel}, samples {start}..{}", start + n);
                check(&block, &what);
            }
        }
    }
}

#[test]
fn every_aligned_power_of_two_block_is_a_0_2_net_in_each_2d_dimension() {
    for_every_block(|block, what| {
        let first: Vec<Vec2> = block.iter().map(|v| v.first_2d).collect();
        assert_net(&first, &format!("{what}, dimension 0"));
        let second: Vec<Vec2> = block.iter().map(|v| v.second_2d).collect();
        assert_net(&second, &format!("{what}, dimension 3"));
    });
}

#[test]
fn every_aligned_power_of_two_block_is_stratified_in_each_1d_dimension() {
    for_every_block(|block, what| {
        let first: Vec<f32> = block.iter().map(|v| v.first_1d).collect();
        assert_stratified(&first, &format!("{what}, dimension 1"));
        let second: Vec<f32> = block.iter().map(|v| v.second_1d).collect();
        assert_stratified(&second, &format!("{what}, dimension 2"));
    });
}

#[test]
fn extreme_seeds_pixels_and_indices_give_values_in_the_half_open_unit_interval() {
    let in_range = |x: f32| (0.0..1.0).contains(&x);
    for (seed, pixel) in CASES {
        let mut sampler = SobolSampler::new(seed, 1);
        for index in (0..64).chain(u32::MAX - 64..=u32::MAX) {
            let v = draw(&mut sampler, pixel, index);
            assert!(
                [v.first_2d, v.second_2d]
                    .iter()
                    .all(|p| in_range(p.x) && in_range(p.y))
                    && in_range(v.first_1d)
                    && in_range(v.second_1d),
                "seed {seed}, pixel {pixel}, sample {index}: {v:?}"
            );
        }
    }
}

/// Pairs of neighbouring dimensions tested for correlation, as (name, the pair of values).
type Pair = (&'static str, fn(&Values) -> (f32, f32));
const NEIGHBOURS: [Pair; 3] = [
    ("dimensions 0 (y) and 1", |v| (v.first_2d.y, v.first_1d)),
    ("dimensions 1 and 2", |v| (v.first_1d, v.second_1d)),
    ("dimensions 2 and 3 (x)", |v| (v.second_1d, v.second_2d.x)),
];

#[test]
fn neighbouring_dimensions_are_paired_like_independent_blocks_within_one_pixel() {
    // The 1024 samples of one pixel, as pairs of values from dimensions d and d + 1, binned on a
    // G × G grid (G = 8). Each dimension is stratified, and within an aligned block of G samples
    // its G strata are paired with the other dimension's by one bijection; for independent
    // shuffles the bijections of different blocks are independent, so each cell's count is
    // Binomial(1024 / G, 1 / G) and Pearson's statistic has mean G² − G = 56 (independent points:
    // G² − 1 = 63; one random pairing of all samples, as the stratified sampler makes: ≈ (G − 1)² =
    // 49). Related shuffles (say, one shared by both dimensions) put the pairs on a few lines and
    // the statistic in the hundreds. The statistic is not chi-square distributed (cells of one
    // block move together), so its mean over 128 pixels is z-tested against 56 instead:
    // α = 0.01, Šidák-corrected over the pairs, two-sided, with the standard error estimated from
    // the pixels.
    let (spp, side, pixels) = (1024_u32, 8_usize, 128_u32);
    let expected_mean = (side * side - side) as f64;
    let threshold = two_sided_threshold(sidak_alpha(0.01, NEIGHBOURS.len()));
    for (name, pick) in NEIGHBOURS {
        let statistics: Vec<f64> = (0..pixels)
            .map(|p| {
                let pixel = UVec2::new(37 * p, 1000 - 3 * p);
                let mut sampler = SobolSampler::new(p, spp);
                let mut counts = vec![0_u32; side * side];
                for index in 0..spp {
                    let (x, y) = pick(&draw(&mut sampler, pixel, index));
                    counts[stratum(x, 3) * side + stratum(y, 3)] += 1;
                }
                let expected = f64::from(spp) / (side * side) as f64;
                counts
                    .iter()
                    .map(|&c| (f64::from(c) - expected).powi(2) / expected)
                    .sum()
            })
            .collect();
        let n = f64::from(pixels);
        let mean = statistics.iter().sum::<f64>() / n;
        let variance = statistics.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / (n - 1.0);
        let z = (mean - expected_mean) / (variance / n).sqrt();
        println!("figure: {name}: mean statistic {mean:.1} (expected {expected_mean}), z {z:.2}");
        assert!(
            z.abs() < threshold,
            "{name}: mean statistic {mean:.2} over {pixels} pixels (seeds 0..{pixels}, pixel \
             (37 p, 1000 - 3 p)), expected {expected_mean}: |z| = {:.2} >= {threshold:.2}",
            z.abs()
        );
    }
}

/// A smooth, non-separable integrand over [0, 1)².
fn integrand_2d(u: DVec2) -> f64 {
    (u.x * u.y).exp() + (std::f64::consts::PI * u.x).sin() * u.y * u.y
}

/// ∫∫ [`integrand_2d`] = Σₙ 1 / (n! (n + 1)²) + 2 / (3π).
fn integral_2d() -> f64 {
    let mut factorial = 1.0;
    let mut sum = 0.0;
    for n in 0..30 {
        if n > 0 {
            factorial *= f64::from(n);
        }
        sum += 1.0 / (factorial * f64::from((n + 1) * (n + 1)));
    }
    sum + 2.0 / (3.0 * std::f64::consts::PI)
}

/// A smooth integrand over [0, 1), with ∫ = e − 1.
fn integrand_1d(x: f64) -> f64 {
    x.exp()
}

/// Pixels whose estimates are averaged.
const PIXELS: u32 = 1024;

/// Mean squared error over [`PIXELS`] pixels of the `spp`-sample estimates of the 2D integrand in
/// dimensions 0 and 3 and of the 1D integrand in dimensions 1 and 2 (the mean over the four).
fn mean_squared_error(kind: SamplerKind, spp: u32) -> f64 {
    let mut sampler = AnySampler::new(kind, 99, spp);
    let exact = [integral_2d(), std::f64::consts::E - 1.0];
    let mut total = 0.0;
    for p in 0..PIXELS {
        let pixel = UVec2::new(p % 32, p / 32);
        let mut sums = [0.0; 4];
        for index in 0..spp {
            let v = draw(&mut sampler, pixel, index);
            sums[0] += integrand_2d(v.first_2d.as_dvec2());
            sums[1] += integrand_1d(f64::from(v.first_1d));
            sums[2] += integrand_1d(f64::from(v.second_1d));
            sums[3] += integrand_2d(v.second_2d.as_dvec2());
        }
        for (d, sum) in sums.into_iter().enumerate() {
            let error = sum / f64::from(spp) - exact[usize::from(d == 1 || d == 2)];
            total += error * error;
        }
    }
    total / f64::from(4 * PIXELS)
}

#[test]
fn smooth_integrands_get_far_less_error_than_with_independent_samples() {
    // For smooth integrands Owen-scrambled nets reach a variance of O(N⁻³) against independent
    // samples' O(N⁻¹). Largest allowed ratio of Sobol to independent mean squared error, per count:
    // powers of two, and counts that are unions of a few nets (48 = 32 + 16, 140 = 128 + 8 + 4).
    for (spp, largest_ratio) in [(16, 0.05), (48, 0.02), (64, 0.005), (140, 0.02)] {
        let independent = mean_squared_error(SamplerKind::Independent, spp);
        let stratified = mean_squared_error(SamplerKind::Stratified, spp);
        let sobol = mean_squared_error(SamplerKind::Sobol, spp);
        println!(
            "figure: {spp} spp: mean squared error independent {independent:.3e}, stratified \
             {stratified:.3e} ({:.1}x less), sobol {sobol:.3e} ({:.1}x less)",
            independent / stratified,
            independent / sobol
        );
        assert!(
            sobol < largest_ratio * independent,
            "{spp} spp: Sobol's error {sobol:.3e} is not below {largest_ratio} x independent's \
             {independent:.3e} (seed 99, {PIXELS} pixels)"
        );
    }
}

/// Mean squared error over 2048 pixels of `spp`-sample estimates of `f(x, y)` (whose integral is 0)
/// with x and y from two different dimensions: the 1D dimensions 1 and 2, and the x of dimension 0
/// with the y of dimension 3 (the mean over the two).
fn interaction_error(kind: SamplerKind, spp: u32, f: fn(f64, f64) -> f64) -> f64 {
    let mut sampler = AnySampler::new(kind, 5, spp);
    let pixels = 2048;
    let mut total = 0.0;
    for p in 0..pixels {
        let pixel = UVec2::new(p % 64, p / 64);
        let mut sums = [0.0; 2];
        for index in 0..spp {
            let v = draw(&mut sampler, pixel, index);
            sums[0] += f(f64::from(v.first_1d), f64::from(v.second_1d));
            sums[1] += f(f64::from(v.first_2d.x), f64::from(v.second_2d.y));
        }
        total += sums
            .iter()
            .map(|s| (s / f64::from(spp)).powi(2))
            .sum::<f64>();
    }
    total / f64::from(2 * pixels)
}

#[test]
fn padding_costs_at_most_about_twice_independent_error_on_pure_interactions() {
    // Padding's known cost: integrands of two different dimensions with no part that depends on
    // one alone gain nothing from stratification, and nested index shuffles pair the samples of
    // each aligned pair {2m, 2m + 1} so that both dimensions change half together: the parity of
    // the halves (the 2 × 2 checkerboard) is the same for both samples of a pair, which doubles its
    // variance against independent samples. Finer or smoother interactions cost less. Larger
    // ratios would mean correlated dimensions.
    let checkerboard: fn(f64, f64) -> f64 = |x, y| if (x < 0.5) == (y < 0.5) { 1.0 } else { -1.0 };
    let sines: fn(f64, f64) -> f64 = |x, y| (TAU * x).sin() * (TAU * y).sin();
    let spp = 64;
    for (name, f, largest_ratio) in [
        ("2 x 2 checkerboard", checkerboard, 2.5),
        ("sin sin", sines, 2.5),
    ] {
        let independent = interaction_error(SamplerKind::Independent, spp, f);
        let sobol = interaction_error(SamplerKind::Sobol, spp, f);
        println!(
            "figure: {name}, {spp} spp: mean squared error independent {independent:.3e}, \
             sobol {sobol:.3e} ({:.2}x)",
            sobol / independent
        );
        assert!(
            sobol < largest_ratio * independent,
            "{name}: Sobol's error {sobol:.3e} is over {largest_ratio} x independent's \
             {independent:.3e} (seed 5, 2048 pixels, {spp} spp)"
        );
    }
}
