//! The blue-noise sampler: Kronecker point sets per pixel, shifted by a blue-noise dither array.
//!
//! **When `auto` uses it.** Only when asked, by `--sampler bluenoise` (Mitsuba has no such
//! sampler, so no scene file names it).

use super::blue_noise_tile::{BlueNoiseTile, TILE_LOG2, blue_noise_tile};
use super::{Sampler, SamplerModel};
use crate::hash::{hash2, mix32, permute};
use crate::rng::unit_f32_from_bits;
use glam::{UVec2, Vec2};

/// The golden-ratio Kronecker step 1/φ in 0.32 fixed point: the best-spread 1D additive sequence.
const STEP_1D: u32 = 0x9E37_79B9;
/// The R₂ Kronecker steps (1/g, 1/g²) for the plastic number g (Roberts 2018) in 0.32 fixed point,
/// the second made odd so that the sequence has full period modulo 2³².
const STEP_2D: [u32; 2] = [0xC13F_A9A9, 0x91E1_0DA5];

/// Distributes the error of each pixel as blue noise in screen space: neighbouring pixels err in
/// opposite directions, which the eye forgives and a denoiser or the display's blur removes.
///
/// This is blue-noise dithered sampling (Georgiev and Fajardo 2016), the screen-space idea that Heitz and
/// Belcour (2019) extend. In every dimension, the samples of a pixel are one Kronecker (rank-1 lattice)
/// point set — {j/φ mod 1} in 1D and Roberts' R₂ set {j (1/g, 1/g²) mod 1} in 2D, indices j assigned to
/// sample indices by a permutation keyed per dimension — toroidally shifted by the pixel's value in a
/// 64 × 64 void-and-cluster blue-noise tile. A pixel's error is a function of its shift, and the shifts of
/// neighbouring pixels are as different as possible, so the errors are anti-correlated between neighbours.
///
/// Why this design rather than a Poisson-disc point set per pixel: the screen-space error distribution is
/// what is visible at the low sample counts where sampling patterns matter; Kronecker sets are as good
/// as stratification for smooth integrands at *any* sample count, are extensible (sample indices past
/// N continue the same sequence), and cost a few integer operations per dimension with no stored points.
///
/// Each dimension (and each axis of a 2D dimension) looks the tile up at its own random toroidal offset
/// and orientation (one of the square's 8 symmetries), keyed by (seed, dimension), and adds a per-pixel
/// hash below the tile's 12 bits of rank; the permutation of indices is keyed by (seed, dimension, block)
/// and is the same for all pixels, so every pixel's point set is the same set under a different shift,
/// as dithering requires. Over random seeds the shifts of different dimensions are independent and
/// uniform, so every dimension, and every pair of dimensions, is uniform on [0, 1): estimates are
/// unbiased.
///
/// Measured (tests/blue_noise.rs, 64 × 64 pixels, a smooth 2D integrand): the share of the error's
/// power below a quarter of the Nyquist frequency is 4.9× smaller than with independent samples at
/// 1 sample per pixel, 1.9× at 4 and 1.9× at 16, with an error variance close to the stratified
/// sampler's.
///
/// Limitations: the 64-pixel tile repeats, so pixels 64 apart get the same shifts (their errors are
/// correlated within one image). Two dimensions that happen to draw nearly the same placement (about
/// 1 in 1300 pairs of dimensions per seed) give strongly correlated values within that image: more
/// error in that render, never bias.
#[derive(Clone)]
pub struct BlueNoiseSampler {
    seed: u32,
    samples_per_pixel: u32,
    tile: &'static BlueNoiseTile,
    pixel: UVec2,
    pixel_hash: u32,
    block: u32,
    sample: u32,
    dimension: u32,
}

impl std::fmt::Debug for BlueNoiseSampler {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BlueNoiseSampler")
            .field("seed", &self.seed)
            .field("samples_per_pixel", &self.samples_per_pixel)
            .field("pixel", &self.pixel)
            .field("block", &self.block)
            .field("sample", &self.sample)
            .field("dimension", &self.dimension)
            .finish_non_exhaustive()
    }
}

impl BlueNoiseSampler {
    /// A blue-noise sampler for `seed` and `samples_per_pixel` (0 is treated as 1).
    ///
    /// The first sampler in a process builds the shared blue-noise tile (a few milliseconds).
    pub fn new(seed: u32, samples_per_pixel: u32) -> Self {
        Self {
            seed,
            samples_per_pixel: samples_per_pixel.max(1),
            tile: blue_noise_tile(),
            pixel: UVec2::ZERO,
            pixel_hash: 0,
            block: 0,
            sample: 0,
            dimension: 0,
        }
    }

    /// The number of samples per pixel N: sample indices are permuted within blocks of N.
    pub fn samples_per_pixel(&self) -> u32 {
        self.samples_per_pixel
    }

    /// The key of the next dimension, which it then consumes; it does not depend on the pixel.
    #[inline]
    fn next_dimension_key(&mut self) -> u32 {
        let key = hash2(self.seed, self.dimension);
        self.dimension = self.dimension.wrapping_add(1);
        key
    }

    /// The index into the Kronecker sequence of the current sample in the dimension with `key`.
    #[inline]
    fn sequence_index(&self, key: u32) -> u32 {
        let n = self.samples_per_pixel;
        // `permute` hashes its key, so each block gets an unrelated permutation.
        let within = permute(self.sample, n, key ^ self.block.wrapping_mul(0x9E37_79B9));
        self.block.wrapping_mul(n).wrapping_add(within)
    }

    /// The pixel's shift in 0.32 fixed point for one channel of a dimension: the blue-noise rank at a
    /// keyed offset and orientation of the tile gives the top 12 bits, a per-pixel hash the rest.
    #[inline]
    fn shift(&self, channel_key: u32) -> u32 {
        let mask = (1 << TILE_LOG2) - 1;
        let (mut x, mut y) = (
            self.pixel.x.wrapping_add(channel_key) & mask,
            self.pixel.y.wrapping_add(channel_key >> TILE_LOG2) & mask,
        );
        let orientation = channel_key >> (2 * TILE_LOG2);
        if orientation & 1 != 0 {
            std::mem::swap(&mut x, &mut y);
        }
        if orientation & 2 != 0 {
            x = mask - x;
        }
        if orientation & 4 != 0 {
            y = mask - y;
        }
        let rank = self.tile.rank(x, y);
        let jitter = mix32(channel_key ^ self.pixel_hash);
        (rank << (32 - 2 * TILE_LOG2)) | (jitter >> (2 * TILE_LOG2))
    }
}

impl SamplerModel for BlueNoiseSampler {
    /// The lattice has `samples_per_pixel` points.
    const PATTERN_DEPENDS_ON_SAMPLE_COUNT: bool = true;

    fn new(seed: u32, samples_per_pixel: u32) -> Self {
        BlueNoiseSampler::new(seed, samples_per_pixel)
    }

    fn samples_per_pixel(&self) -> u32 {
        BlueNoiseSampler::samples_per_pixel(self)
    }
}

impl Sampler for BlueNoiseSampler {
    #[inline]
    fn start_pixel_sample(&mut self, pixel: UVec2, sample_index: u32) {
        self.pixel = pixel;
        self.pixel_hash = hash2(pixel.x, pixel.y);
        self.block = sample_index / self.samples_per_pixel;
        self.sample = sample_index % self.samples_per_pixel;
        self.dimension = 0;
    }

    #[inline]
    fn next_1d(&mut self) -> f32 {
        let key = self.next_dimension_key();
        let j = self.sequence_index(key);
        let shift = self.shift(mix32(key));
        unit_f32_from_bits(j.wrapping_mul(STEP_1D).wrapping_add(shift))
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        let key = self.next_dimension_key();
        let j = self.sequence_index(key);
        let shift_x = self.shift(mix32(key));
        let shift_y = self.shift(mix32(key ^ 0x2545_F491));
        Vec2::new(
            unit_f32_from_bits(j.wrapping_mul(STEP_2D[0]).wrapping_add(shift_x)),
            unit_f32_from_bits(j.wrapping_mul(STEP_2D[1]).wrapping_add(shift_y)),
        )
    }
}
