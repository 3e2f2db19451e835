//! A sampler's pattern for the first dimensions of every pixel sample only, independent uniform
//! numbers after them.

use super::Sampler;
use crate::rng::Rng;
use glam::{UVec2, Vec2};

/// Mixed into the seed of the independent numbers, so that they are unrelated to an
/// [`super::IndependentSampler`]'s with the same seed (which the pattern may be).
const TAIL_SALT: u32 = 0x7F4A_7C15;

/// The first `dimensions` dimensions of every pixel sample from `inner`, every later one an
/// independent uniform number in [0, 1).
///
/// Stratification pays where a dimension decides much of a sample's value (the pixel position,
/// the first bounces of a path) and hardly at all deep in a path, where the throughput is small
/// and many dimensions have been crossed; there a stratified or low-discrepancy pattern only costs
/// time (Owen-scrambled Sobol about 110 integer operations per 2D dimension, the stratified
/// sampler about 500, these independent numbers about 12). The independent numbers of a pixel
/// sample come from their own stream, a pure function of (seed, pixel, sample index) started at
/// the first of them, so a pixel sample can still be replayed alone, and a sample that never
/// needs them never pays for starting it.
#[derive(Clone, Debug)]
pub struct PrefixSampler<S> {
    inner: S,
    dimensions: u32,
    seed: u32,
    pixel: UVec2,
    sample_index: u32,
    /// Dimensions handed out in the current pixel sample.
    dimension: u32,
    /// The stream of the dimensions after the prefix, once one is asked for.
    tail: Option<Rng>,
}

impl<S: Sampler> PrefixSampler<S> {
    /// `inner` for the first `dimensions` dimensions of each pixel sample, independent numbers
    /// (from `seed`) for the rest.
    pub fn new(inner: S, dimensions: u32, seed: u32) -> Self {
        Self {
            inner,
            dimensions,
            seed: seed ^ TAIL_SALT,
            pixel: UVec2::ZERO,
            sample_index: 0,
            dimension: 0,
            tail: None,
        }
    }

    /// Whether the next dimension comes from the inner sampler; counts it.
    #[inline]
    fn next_from_inner(&mut self) -> bool {
        let from_inner = self.dimension < self.dimensions;
        self.dimension = self.dimension.saturating_add(1);
        from_inner
    }

    #[inline]
    fn tail(&mut self) -> &mut Rng {
        let (pixel, sample_index, seed) = (self.pixel, self.sample_index, self.seed);
        self.tail
            .get_or_insert_with(|| Rng::for_sample(pixel, sample_index, seed))
    }
}

impl<S: Sampler> Sampler for PrefixSampler<S> {
    #[inline]
    fn start_pixel_sample(&mut self, pixel: UVec2, sample_index: u32) {
        self.inner.start_pixel_sample(pixel, sample_index);
        self.pixel = pixel;
        self.sample_index = sample_index;
        self.dimension = 0;
        self.tail = None;
    }

    #[inline]
    fn next_1d(&mut self) -> f32 {
        if self.next_from_inner() {
            self.inner.next_1d()
        } else {
            self.tail().next_f32()
        }
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        if self.next_from_inner() {
            self.inner.next_2d()
        } else {
            let tail = self.tail();
            let x = tail.next_f32();
            Vec2::new(x, tail.next_f32())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::{IndependentSampler, SobolSampler};

    /// Draws `count` dimensions, alternating 2D and 1D, as a flat list of numbers.
    fn draws(sampler: &mut impl Sampler, count: u32) -> Vec<f32> {
        let mut values = Vec::new();
        for d in 0..count {
            if d % 2 == 0 {
                values.extend(sampler.next_2d().to_array());
            } else {
                values.push(sampler.next_1d());
            }
        }
        values
    }

    #[test]
    fn the_prefix_is_the_inner_samplers_and_the_rest_is_not() {
        let (seed, spp) = (5, 64);
        for prefix in [0, 1, 3, 6] {
            let mut inner = SobolSampler::new(seed, spp);
            let mut prefixed = PrefixSampler::new(SobolSampler::new(seed, spp), prefix, seed);
            for (pixel, index) in [
                (UVec2::new(3, 9), 0),
                (UVec2::new(3, 9), 17),
                (UVec2::ZERO, 63),
            ] {
                inner.start_pixel_sample(pixel, index);
                prefixed.start_pixel_sample(pixel, index);
                let (a, b) = (draws(&mut inner, 10), draws(&mut prefixed, 10));
                // Dimension d (2D and 1D by turns) starts at value ⌈3d / 2⌉.
                let split = (3 * prefix as usize).div_ceil(2);
                assert_eq!(
                    a[..split],
                    b[..split],
                    "prefix {prefix}, pixel {pixel}, sample {index}"
                );
                assert!(
                    a[split..].iter().zip(&b[split..]).all(|(x, y)| x != y),
                    "prefix {prefix}, pixel {pixel}, sample {index}: {a:?} against {b:?}"
                );
                assert!(b.iter().all(|v| (0.0..1.0).contains(v)));
            }
        }
    }

    #[test]
    fn the_rest_is_unrelated_to_an_independent_sampler_with_the_same_seed() {
        let seed = 11;
        let mut independent = IndependentSampler::new(seed, 1);
        let mut prefixed = PrefixSampler::new(IndependentSampler::new(seed, 1), 1, seed);
        independent.start_pixel_sample(UVec2::new(4, 2), 3);
        prefixed.start_pixel_sample(UVec2::new(4, 2), 3);
        let (a, b) = (draws(&mut independent, 8), draws(&mut prefixed, 8));
        assert_eq!(a[..2], b[..2]);
        // The tail does not restart the inner stream: no run of it reappears.
        assert!(b[2..].iter().all(|v| !a.contains(v)), "{a:?} against {b:?}");
    }

    #[test]
    fn a_pixel_sample_replays_alone_in_any_order() {
        let mut sampler = PrefixSampler::new(SobolSampler::new(2, 16), 2, 2);
        let mut replay = sampler.clone();
        let mut first = Vec::new();
        for index in 0..4 {
            sampler.start_pixel_sample(UVec2::new(1, 1), index);
            first.push(draws(&mut sampler, 7));
        }
        for index in (0..4).rev() {
            replay.start_pixel_sample(UVec2::new(1, 1), index);
            assert_eq!(
                draws(&mut replay, 7),
                first[index as usize],
                "sample {index}"
            );
        }
    }
}
