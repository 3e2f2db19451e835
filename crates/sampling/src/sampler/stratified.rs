//! The stratified sampler: correlated multi-jittered strata (Kensler 2013) for any sample count.
//!
//! **When `auto` uses it.** When the scene file asks for `stratified`, `multijitter` or
//! `orthogonal`, or `--sampler stratified` does: an explicit choice wins over `auto`'s Sobol.

use super::strata::{Strata, closest_factorisation};
use super::{Sampler, SamplerModel};
use crate::hash::{hash2, permute};
use crate::rng::{Rng, sample_seed};
use glam::{UVec2, Vec2};

/// Jittered stratified sampling for any number of samples per pixel N, decorrelated between dimensions.
///
/// The N samples of a pixel (indices 0..N, and each later block of N indices) are stratified in every
/// dimension:
/// - a **1D** dimension splits [0, 1) into N strata with one jittered sample in each;
/// - a **2D** dimension uses the factorisation N = m × n closest to square (m ≤ n) and puts the samples
///   in a multi-jittered pattern (Chiu, Shirley and Wang 1994; Kensler's correlated variant, 2013):
///   one sample in each of the m × n cells *and* one in each of the N columns and N rows of width 1 / N
///   (N-rooks). A prime N gives m = 1, where only the N-rooks (Latin hypercube) property remains.
///
/// Which sample gets which stratum is a permutation keyed by a hash of (pixel, dimension, block, seed),
/// so strata are permuted independently per dimension and per pixel: the pixel position and the lens,
/// light and BSDF dimensions of one sample are not correlated. Jitter comes from an [`Rng`] stream of
/// the sample's own. Every value is uniform on [0, 1) over random seeds, so estimates are unbiased.
#[derive(Clone, Debug)]
pub struct StratifiedSampler {
    seed: u32,
    samples_per_pixel: u32,
    columns: u32,
    rows: u32,
    strata: Strata,
    pixel_key: u32,
    sample: u32,
    dimension: u32,
    rng: Rng,
}

impl StratifiedSampler {
    /// A stratified sampler for `seed` with `samples_per_pixel` strata per dimension (0 is treated as 1).
    pub fn new(seed: u32, samples_per_pixel: u32) -> Self {
        let samples_per_pixel = samples_per_pixel.max(1);
        let (columns, rows) = closest_factorisation(samples_per_pixel);
        Self {
            seed,
            samples_per_pixel,
            columns,
            rows,
            strata: Strata::new(samples_per_pixel),
            pixel_key: 0,
            sample: 0,
            dimension: 0,
            rng: Rng::new(seed),
        }
    }

    /// The number of samples per pixel N: the number of strata of each dimension.
    pub fn samples_per_pixel(&self) -> u32 {
        self.samples_per_pixel
    }

    /// The grid m × n (columns × rows, m · n = N, m ≤ n) of the 2D dimensions' strata.
    pub fn grid(&self) -> UVec2 {
        UVec2::new(self.columns, self.rows)
    }

    /// The permutation key of the next dimension, which it then consumes.
    #[inline]
    fn next_dimension_key(&mut self) -> u32 {
        let key = hash2(self.pixel_key, self.dimension);
        self.dimension = self.dimension.wrapping_add(1);
        key
    }
}

impl SamplerModel for StratifiedSampler {
    /// The strata are blocks of `samples_per_pixel` samples.
    const PATTERN_DEPENDS_ON_SAMPLE_COUNT: bool = true;

    fn new(seed: u32, samples_per_pixel: u32) -> Self {
        StratifiedSampler::new(seed, samples_per_pixel)
    }

    fn samples_per_pixel(&self) -> u32 {
        StratifiedSampler::samples_per_pixel(self)
    }
}

impl Sampler for StratifiedSampler {
    #[inline]
    fn start_pixel_sample(&mut self, pixel: UVec2, sample_index: u32) {
        let block = sample_index / self.samples_per_pixel;
        self.sample = sample_index % self.samples_per_pixel;
        self.pixel_key = sample_seed(pixel, block, self.seed);
        self.dimension = 0;
        // The jitter stream of this sample: a function of (pixel, block, seed) and the index.
        self.rng = Rng::new(hash2(self.pixel_key ^ 0x3C6E_F372, self.sample));
    }

    #[inline]
    fn next_1d(&mut self) -> f32 {
        let key = self.next_dimension_key();
        let stratum = permute(self.sample, self.samples_per_pixel, key);
        self.strata.point(stratum, self.rng.next_f32())
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        let key = self.next_dimension_key();
        let n = self.samples_per_pixel;
        let cell = permute(self.sample, n, key);
        let (column, row) = (cell % self.columns, cell / self.columns);
        // Within column `column` the samples take distinct sub-columns (one per row), and within
        // row `row` distinct sub-rows (one per column): the N-rooks property on top of the m × n cells.
        // `permute` hashes its key, so distinct constants give unrelated permutations.
        let sub_column = permute(row, self.rows, key ^ 0x6A09_E667);
        let sub_row = permute(column, self.columns, key ^ 0xBB67_AE85);
        let x = self
            .strata
            .point(column * self.rows + sub_column, self.rng.next_f32());
        let y = self
            .strata
            .point(row * self.columns + sub_row, self.rng.next_f32());
        Vec2::new(x, y)
    }
}
