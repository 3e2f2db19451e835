//! Marsaglia's xorshift32 generator, seeded through the Wang hash.

use glam::UVec2;
use rand_core::TryRng;
use std::convert::Infallible;

/// State used when hashing a seed happens to give zero, which xorshift can never leave.
const NONZERO_FALLBACK: u32 = 0x9E37_79B9;

/// Thomas Wang's 32-bit integer hash: neighbouring inputs give unrelated outputs.
#[inline]
pub fn wang_hash(mut x: u32) -> u32 {
    x = (x ^ 61) ^ (x >> 16);
    x = x.wrapping_mul(9);
    x ^= x >> 4;
    x = x.wrapping_mul(0x27d4_eb2d);
    x ^ (x >> 15)
}

/// Marsaglia's xorshift32 (shifts 13, 17, 5): 32 bits of state, period 2³² − 1.
///
/// The state is never zero: seeds go through [`wang_hash`] and a zero hash is replaced.
/// Implements `rand_core`'s `TryRng` (and so `Rng`), so it plugs into the `rand` ecosystem.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rng {
    state: u32,
}

impl Rng {
    /// A generator whose stream is determined by `seed`; nearby seeds give unrelated streams.
    #[inline]
    pub fn new(seed: u32) -> Self {
        let hashed = wang_hash(seed);
        Self {
            state: if hashed == 0 {
                NONZERO_FALLBACK
            } else {
                hashed
            },
        }
    }

    /// The generator for one (pixel, sample index, seed) triple, so any sample can be replayed alone.
    #[inline]
    pub fn for_sample(pixel: UVec2, sample_index: u32, seed: u32) -> Self {
        Self::new(sample_seed(pixel, sample_index, seed))
    }

    /// The next 32 uniformly distributed bits.
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        let mut s = self.state;
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        self.state = s;
        s
    }

    /// A float uniform in [0, 1), never 1.0: see [`unit_f32_from_bits`].
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        unit_f32_from_bits(self.next_u32())
    }

    /// An integer uniform in [0, n) without modulo bias (Lemire's multiply-and-reject method).
    ///
    /// # Panics
    /// If `n` is zero.
    #[inline]
    pub fn next_below(&mut self, n: u32) -> u32 {
        assert!(n > 0, "next_below: the range [0, 0) is empty");
        let mut product = u64::from(self.next_u32()) * u64::from(n);
        let mut low = product as u32;
        if low < n {
            let threshold = n.wrapping_neg() % n;
            while low < threshold {
                product = u64::from(self.next_u32()) * u64::from(n);
                low = product as u32;
            }
        }
        (product >> 32) as u32
    }
}

/// Maps 32 uniform bits to a float uniform in [0, 1): the top 24 bits scaled by 2⁻²⁴, so every
/// result is a multiple of 2⁻²⁴ and the largest is 1 − 2⁻²⁴ (a plain `bits as f32 / 2³²` can round to 1.0).
#[inline]
pub fn unit_f32_from_bits(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// The seed of the stream for one (pixel, sample index, seed) triple: the three are hashed in turn.
#[inline]
pub fn sample_seed(pixel: UVec2, sample_index: u32, seed: u32) -> u32 {
    let h = wang_hash(seed);
    let h = wang_hash(h ^ pixel.x);
    let h = wang_hash(h.wrapping_add(0x68E3_1DA4) ^ pixel.y);
    wang_hash(h.wrapping_add(0xB529_7A4D) ^ sample_index)
}

impl TryRng for Rng {
    type Error = Infallible;

    #[inline]
    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        Ok(Rng::next_u32(self))
    }

    #[inline]
    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        rand_core::utils::next_u64_via_u32(self)
    }

    #[inline]
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        for chunk in dst.chunks_mut(4) {
            let bytes = Rng::next_u32(self).to_le_bytes();
            chunk.copy_from_slice(&bytes[..chunk.len()]);
        }
        Ok(())
    }
}
