//! The independent sampler: every dimension of every sample is a fresh uniform random number.
//!
//! **When `auto` uses it.** Never by itself: a scene's `independent` sampler (Mitsuba's
//! default, which carries no intent) becomes Sobol under `auto`; `--sampler independent` or the
//! other presets keep it.

use super::{Sampler, SamplerModel};
use crate::rng::Rng;
use glam::{UVec2, Vec2};

/// Independent uniform numbers in [0, 1): the baseline every other sampler is compared against.
///
/// Each pixel sample draws from its own [`Rng::for_sample`] stream, so it can be replayed alone; the
/// dimensions of a sample are consecutive draws of that stream.
#[derive(Clone, Debug)]
pub struct IndependentSampler {
    seed: u32,
    samples_per_pixel: u32,
    rng: Rng,
}

impl IndependentSampler {
    /// An independent sampler for `seed`; `samples_per_pixel` (0 is treated as 1) is only recorded.
    pub fn new(seed: u32, samples_per_pixel: u32) -> Self {
        Self {
            seed,
            samples_per_pixel: samples_per_pixel.max(1),
            rng: Rng::for_sample(UVec2::ZERO, 0, seed),
        }
    }

    /// The number of samples per pixel given to [`IndependentSampler::new`].
    pub fn samples_per_pixel(&self) -> u32 {
        self.samples_per_pixel
    }
}

impl SamplerModel for IndependentSampler {
    /// One random stream per sample: sample `i` is the same whatever the count.
    const PATTERN_DEPENDS_ON_SAMPLE_COUNT: bool = false;

    /// Its numbers are independent already: the renderer draws them all from it.
    const INDEPENDENT_DIMENSIONS: bool = true;

    fn new(seed: u32, samples_per_pixel: u32) -> Self {
        IndependentSampler::new(seed, samples_per_pixel)
    }

    fn samples_per_pixel(&self) -> u32 {
        IndependentSampler::samples_per_pixel(self)
    }
}

impl Sampler for IndependentSampler {
    #[inline]
    fn start_pixel_sample(&mut self, pixel: UVec2, sample_index: u32) {
        self.rng = Rng::for_sample(pixel, sample_index, self.seed);
    }

    #[inline]
    fn next_1d(&mut self) -> f32 {
        self.rng.next_f32()
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        let x = self.rng.next_f32();
        Vec2::new(x, self.rng.next_f32())
    }
}
