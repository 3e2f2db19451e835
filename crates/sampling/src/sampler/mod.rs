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
//!
//! The samplers form a closed set, declared once by the `sampler_set!` list below: one line per
//! sampler names its [`SamplerKind`] variant, its type (which implements [`Sampler`] and
//! [`SamplerModel`] in its own file), its name on the command line and in scene files, and a
//! one-line summary. [`SamplerKind::ALL`], the names' [`FromStr`], [`AnySampler`] and
//! [`SamplerKind::visit`] (how the renderer reaches its per-sample code for each sampler type) are
//! generated from it. Adding a sampler is its file, its line in the list (and the `mod` and `pub
//! use` above), and its tests; the tests of `tests/samplers.rs` run on every kind of
//! [`SamplerKind::ALL`]. A sampler takes only a seed and a sample count, which a scene file's
//! `<sampler>` gives as `seed` and `sample_count` to all of them.

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

/// What each sampler of the set provides besides [`Sampler`], so that code generic over the
/// sampler type can be reached from a [`SamplerKind`] ([`SamplerKind::visit`]) and [`AnySampler`]
/// can forward to it (see `sampler_set!`).
pub trait SamplerModel: Sampler + Clone + fmt::Debug + Send + Sync + 'static {
    /// Whether the numbers of sample `i` of a pixel depend on the sample count the sampler is
    /// laid out for: they do where the pattern's strata are blocks of that many samples
    /// (stratified, blue noise), not where every sample index has numbers of its own (one
    /// random stream per sample, one point of an endless sequence per index). Renders of the
    /// latter merge whatever their sample counts.
    const PATTERN_DEPENDS_ON_SAMPLE_COUNT: bool;

    /// Whether every dimension already holds independent numbers, so that a renderer gains
    /// nothing by drawing the deeper dimensions independently ([`PrefixSampler`]) and draws
    /// them all from this sampler. False for the samplers with a pattern.
    const INDEPENDENT_DIMENSIONS: bool = false;

    /// The sampler for `seed` and `samples_per_pixel` (0 is treated as 1).
    fn new(seed: u32, samples_per_pixel: u32) -> Self;

    /// The number of samples per pixel the pattern was built for.
    fn samples_per_pixel(&self) -> u32;
}

/// Code generic over the sampler type, run for the type that a [`SamplerKind`] names by
/// [`SamplerKind::visit`]: how a renderer compiles its per-sample code once per sampler, with
/// sampling inlined rather than dispatched per number.
pub trait SamplerVisitor {
    /// What the visit returns.
    type Output;

    /// Runs with `S`, the sampler the kind names.
    fn visit<S: SamplerModel>(self) -> Self::Output;
}

/// Declares the closed set of samplers once: each line names a [`SamplerKind`] variant, the
/// sampler type it stands for (which implements [`SamplerModel`] in its own file), its
/// command-line name and a one-line summary. Generates [`SamplerKind`] with [`SamplerKind::ALL`],
/// its names, summaries, [`fmt::Display`], [`FromStr`] and [`SamplerKind::visit`], and
/// [`AnySampler`] with its dispatch.
macro_rules! sampler_set {
    ($($(#[$attr:meta])* $variant:ident($ty:ident) = $name:literal, $summary:literal;)*) => {
        /// Which sampler an [`AnySampler`] is: the user-facing choice of sampling pattern.
        ///
        /// Its names ([`SamplerKind::name`], [`Display`](fmt::Display) and [`FromStr`]) are
        /// the renderer's command-line names, and a scene file's `<sampler type>` besides
        /// Mitsuba's own sampler names (which the scene loader maps onto these).
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
        pub enum SamplerKind {
            $($(#[$attr])* $variant,)*
        }

        /// The number of samplers in the set.
        const SAMPLER_COUNT: usize = [$($name),*].len();

        impl SamplerKind {
            /// Every kind, in the order the command line lists them.
            pub const ALL: [SamplerKind; SAMPLER_COUNT] = [$(SamplerKind::$variant),*];

            /// The kind's name, on the command line and in scene files.
            pub fn name(self) -> &'static str {
                match self {
                    $(SamplerKind::$variant => $name,)*
                }
            }

            /// What the sampler draws, in one line (the command line's help).
            pub fn summary(self) -> &'static str {
                match self {
                    $(SamplerKind::$variant => $summary,)*
                }
            }

            /// Runs `visitor` with the sampler type this kind names.
            #[inline]
            pub fn visit<V: SamplerVisitor>(self, visitor: V) -> V::Output {
                match self {
                    $(SamplerKind::$variant => visitor.visit::<$ty>(),)*
                }
            }

            /// Whether the numbers of sample `i` of a pixel depend on the sample count the
            /// sampler is laid out for ([`SamplerModel::PATTERN_DEPENDS_ON_SAMPLE_COUNT`]).
            pub fn pattern_depends_on_sample_count(self) -> bool {
                match self {
                    $(SamplerKind::$variant => {
                        <$ty as SamplerModel>::PATTERN_DEPENDS_ON_SAMPLE_COUNT
                    })*
                }
            }
        }

        /// Any of the samplers behind one type, dispatched by `match` (no trait objects in the
        /// hot loop).
        #[derive(Clone, Debug)]
        pub enum AnySampler {
            $(#[doc = concat!("A [`", stringify!($ty), "`].")] $variant($ty),)*
        }

        impl AnySampler {
            /// The sampler of the given kind for `seed` and `samples_per_pixel` (0 is treated
            /// as 1).
            pub fn new(kind: SamplerKind, seed: u32, samples_per_pixel: u32) -> Self {
                match kind {
                    $(SamplerKind::$variant => {
                        Self::$variant(<$ty as SamplerModel>::new(seed, samples_per_pixel))
                    })*
                }
            }

            /// Which sampler this is.
            pub fn kind(&self) -> SamplerKind {
                match self {
                    $(Self::$variant(_) => SamplerKind::$variant,)*
                }
            }

            /// The number of samples per pixel the pattern was built for.
            pub fn samples_per_pixel(&self) -> u32 {
                match self {
                    $(Self::$variant(s) => SamplerModel::samples_per_pixel(s),)*
                }
            }
        }

        impl Sampler for AnySampler {
            #[inline]
            fn start_pixel_sample(&mut self, pixel: UVec2, sample_index: u32) {
                match self {
                    $(Self::$variant(s) => s.start_pixel_sample(pixel, sample_index),)*
                }
            }

            #[inline]
            fn next_1d(&mut self) -> f32 {
                match self {
                    $(Self::$variant(s) => s.next_1d(),)*
                }
            }

            #[inline]
            fn next_2d(&mut self) -> Vec2 {
                match self {
                    $(Self::$variant(s) => s.next_2d(),)*
                }
            }
        }
    };
}

sampler_set! {
    /// [`IndependentSampler`]: independent uniform random numbers.
    #[default]
    Independent(IndependentSampler) = "independent", "Independent uniform random numbers";
    /// [`StratifiedSampler`]: jittered, multi-jittered strata permuted per pixel and dimension.
    Stratified(StratifiedSampler) = "stratified", "Stratified (jittered) samples";
    /// [`BlueNoiseSampler`]: blue-noise-shifted Kronecker point sets (screen-space blue-noise
    /// error).
    BlueNoise(BlueNoiseSampler) = "bluenoise", "Blue-noise samples";
    /// [`SobolSampler`]: Owen-scrambled Sobol points padded per dimension (a (0, 2)-net in every
    /// 2D dimension at every power-of-two prefix).
    Sobol(SobolSampler) = "sobol",
        "Owen-scrambled Sobol samples (a (0, 2)-net in every 2D dimension at every power-of-two \
         count)";
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
