//! Samplers: the uniform numbers in [0, 1) that drive one pixel sample, handed out dimension by dimension.
//!
//! A renderer calls [`Sampler::start_pixel_sample`] for each (pixel, sample index) and then asks for
//! numbers with [`Sampler::next_1d`] and [`Sampler::next_2d`]. Every call opens a new *dimension*
//! (dimensions are counted in call order from 0 for each pixel sample), and each dimension is decorrelated
//! from the others by a scramble or permutation keyed by a hash of (pixel, dimension, seed). Strata's
//! integrators use this fixed order, and consume a dimension only for a feature the scene has:
//!
//! 1. pixel position, 2D;
//! 2. lens position, 2D, only if the camera has a lens;
//! 3. time, 1D, only if something moves while the shutter is open (motion blur): the whole
//!    path sees the scene at that fraction of the shutter interval;
//! 4. for each bounce: light choice 1D, point on the light 2D, BSDF lobe 1D, BSDF direction 2D,
//!    Russian roulette 1D.
//!
//! Every sampler is a pure function of (seed, samples per pixel, pixel, sample index, dimension): any
//! pixel sample can be replayed on its own, in any order and on any thread. None allocates per sample.
//!
//! | sampler | per-pixel pattern | across pixels |
//! |---|---|---|
//! | [`IndependentSampler`] | independent uniform numbers | independent |
//! | [`StratifiedSampler`] | multi-jittered strata in every dimension | independent permutations |
//! | [`BlueNoiseSampler`] | a rank-1 lattice (Kronecker) point set | blue-noise shifts: screen-space blue-noise error |
//! | [`SobolSampler`] | Owen-scrambled Sobol (0, 2)-sequence: a net at every power-of-two prefix, any count | independent index shuffles and scrambles |
//!
//! [`PrefixSampler`] wraps any of them so that only the first dimensions of each pixel sample
//! come from its pattern and the rest are independent numbers: the renderer stratifies the
//! camera and the first bounces, where it pays, and draws deeper bounces cheaply.

mod blue_noise;
mod blue_noise_tile;
mod independent;
mod owen;
mod prefix;
mod sobol;
mod strata;
mod stratified;

pub use blue_noise::BlueNoiseSampler;
pub use independent::IndependentSampler;
pub use prefix::PrefixSampler;
pub use sobol::SobolSampler;
pub use stratified::StratifiedSampler;

use std::fmt;
use std::str::FromStr;

use glam::{UVec2, Vec2};

/// A source of sample values in [0, 1) for Monte Carlo integration over a pixel, one dimension at a time.
pub trait Sampler {
    /// Begins sample `sample_index` of `pixel`: the next call returns dimension 0 of that sample.
    fn start_pixel_sample(&mut self, pixel: UVec2, sample_index: u32);

    /// The next dimension's value, in [0, 1) (never 1.0).
    fn next_1d(&mut self) -> f32;

    /// The next dimension's pair of values, each in [0, 1) (never 1.0); one call is one (2D) dimension.
    fn next_2d(&mut self) -> Vec2;
}

/// Which sampler an [`AnySampler`] is: the user-facing choice of sampling pattern.
///
/// Its names ([`SamplerKind::name`], [`Display`](fmt::Display) and [`FromStr`]) are the
/// renderer's command-line names: `independent`, `stratified`, `bluenoise` and `sobol`. (A scene
/// file names Mitsuba's samplers instead; the scene loader maps those onto these.)
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SamplerKind {
    /// [`IndependentSampler`]: independent uniform random numbers.
    #[default]
    Independent,
    /// [`StratifiedSampler`]: jittered, multi-jittered strata permuted per pixel and dimension.
    Stratified,
    /// [`BlueNoiseSampler`]: blue-noise-shifted Kronecker point sets (screen-space blue-noise error).
    BlueNoise,
    /// [`SobolSampler`]: Owen-scrambled Sobol points padded per dimension (a (0, 2)-net in every
    /// 2D dimension at every power-of-two prefix).
    Sobol,
}

impl SamplerKind {
    /// Every kind, in the order the command line lists them.
    pub const ALL: [SamplerKind; 4] = [
        SamplerKind::Independent,
        SamplerKind::Stratified,
        SamplerKind::BlueNoise,
        SamplerKind::Sobol,
    ];

    /// The kind's name: `independent`, `stratified`, `bluenoise` or `sobol`.
    pub fn name(self) -> &'static str {
        match self {
            SamplerKind::Independent => "independent",
            SamplerKind::Stratified => "stratified",
            SamplerKind::BlueNoise => "bluenoise",
            SamplerKind::Sobol => "sobol",
        }
    }
}

impl fmt::Display for SamplerKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for SamplerKind {
    type Err = UnknownSamplerKind;

    /// The kind called `name` (exactly, as [`SamplerKind::name`] spells it).
    fn from_str(name: &str) -> Result<Self, Self::Err> {
        SamplerKind::ALL
            .into_iter()
            .find(|kind| kind.name() == name)
            .ok_or_else(|| UnknownSamplerKind(name.to_string()))
    }
}

/// A name that is not a [`SamplerKind`]'s; its message lists the names there are.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownSamplerKind(pub String);

impl fmt::Display for UnknownSamplerKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "no sampler called '{}' (expected ", self.0)?;
        for (i, kind) in SamplerKind::ALL.into_iter().enumerate() {
            let separator = match i {
                0 => "",
                _ if i + 1 == SamplerKind::ALL.len() => " or ",
                _ => ", ",
            };
            write!(f, "{separator}{kind}")?;
        }
        f.write_str(")")
    }
}

impl std::error::Error for UnknownSamplerKind {}

/// Any of the samplers behind one type, dispatched by `match` (no trait objects in the hot loop).
#[derive(Clone, Debug)]
pub enum AnySampler {
    /// An [`IndependentSampler`].
    Independent(IndependentSampler),
    /// A [`StratifiedSampler`].
    Stratified(StratifiedSampler),
    /// A [`BlueNoiseSampler`].
    BlueNoise(BlueNoiseSampler),
    /// A [`SobolSampler`].
    Sobol(SobolSampler),
}

impl AnySampler {
    /// The sampler of the given kind for `seed` and `samples_per_pixel` (0 is treated as 1).
    pub fn new(kind: SamplerKind, seed: u32, samples_per_pixel: u32) -> Self {
        match kind {
            SamplerKind::Independent => {
                Self::Independent(IndependentSampler::new(seed, samples_per_pixel))
            }
            SamplerKind::Stratified => {
                Self::Stratified(StratifiedSampler::new(seed, samples_per_pixel))
            }
            SamplerKind::BlueNoise => {
                Self::BlueNoise(BlueNoiseSampler::new(seed, samples_per_pixel))
            }
            SamplerKind::Sobol => Self::Sobol(SobolSampler::new(seed, samples_per_pixel)),
        }
    }

    /// Which sampler this is.
    pub fn kind(&self) -> SamplerKind {
        match self {
            Self::Independent(_) => SamplerKind::Independent,
            Self::Stratified(_) => SamplerKind::Stratified,
            Self::BlueNoise(_) => SamplerKind::BlueNoise,
            Self::Sobol(_) => SamplerKind::Sobol,
        }
    }

    /// The number of samples per pixel the pattern was built for.
    pub fn samples_per_pixel(&self) -> u32 {
        match self {
            Self::Independent(s) => s.samples_per_pixel(),
            Self::Stratified(s) => s.samples_per_pixel(),
            Self::BlueNoise(s) => s.samples_per_pixel(),
            Self::Sobol(s) => s.samples_per_pixel(),
        }
    }
}

impl Sampler for AnySampler {
    #[inline]
    fn start_pixel_sample(&mut self, pixel: UVec2, sample_index: u32) {
        match self {
            Self::Independent(s) => s.start_pixel_sample(pixel, sample_index),
            Self::Stratified(s) => s.start_pixel_sample(pixel, sample_index),
            Self::BlueNoise(s) => s.start_pixel_sample(pixel, sample_index),
            Self::Sobol(s) => s.start_pixel_sample(pixel, sample_index),
        }
    }

    #[inline]
    fn next_1d(&mut self) -> f32 {
        match self {
            Self::Independent(s) => s.next_1d(),
            Self::Stratified(s) => s.next_1d(),
            Self::BlueNoise(s) => s.next_1d(),
            Self::Sobol(s) => s.next_1d(),
        }
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        match self {
            Self::Independent(s) => s.next_2d(),
            Self::Stratified(s) => s.next_2d(),
            Self::BlueNoise(s) => s.next_2d(),
            Self::Sobol(s) => s.next_2d(),
        }
    }
}
