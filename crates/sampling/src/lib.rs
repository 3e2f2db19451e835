//! Random numbers and sample mappings for Monte Carlo rendering.
//!
//! - [`Rng`]: Marsaglia's xorshift32 seeded through the Wang hash, with one replayable stream per
//!   (pixel, sample index, seed); implements `rand_core`'s traits.
//! - [`sampler`]: the [`Sampler`] trait and the independent, stratified, blue-noise and Sobol samplers
//!   ([`AnySampler`] picks one at run time).
//! - [`warp`]: maps from [0, 1)² to hemispheres, the sphere, discs, triangles and cones, each with its
//!   pdf and inverse.
//! - [`distribution::AliasTable`], [`mis`] heuristics and [`reservoir::Reservoir`] for choosing between
//!   lights, lobes and techniques.
//! - [`chi2`]: the goodness-of-fit harness that tests every sampling routine against its pdf, and
//!   [`ztest`]: Šidák-corrected z-tests for comparing estimates.
//!
//! Depends only on `glam` and `rand_core`, so it can be used outside Strata.
//!
//! ```
//! use glam::UVec2;
//! use sampling::{AnySampler, Frame, Sampler, SamplerKind};
//! use sampling::warp::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
//!
//! // Four stratified samples of pixel (10, 20), each picking a cosine-weighted direction around a normal.
//! let normal = glam::Vec3::new(0.0, 0.6, 0.8);
//! let frame = Frame::from_normal(normal);
//! let mut sampler = AnySampler::new(SamplerKind::Stratified, 7, 4);
//! for sample_index in 0..4 {
//!     sampler.start_pixel_sample(UVec2::new(10, 20), sample_index);
//!     let _pixel_offset = sampler.next_2d();
//!     let local = sample_cosine_hemisphere(sampler.next_2d());
//!     let world = frame.to_world(local);
//!     assert!(world.dot(normal) >= 0.0);
//!     assert!((cosine_hemisphere_pdf(local.z) - world.dot(normal) / std::f32::consts::PI).abs() < 1e-5);
//! }
//! ```

#![warn(missing_docs)]

mod cdf_table;
pub mod chi2;
pub mod distribution;
pub mod frame;
mod hash;
pub mod mis;
pub mod reservoir;
pub mod rng;
pub mod sampler;
pub mod warp;
pub mod ztest;

pub use distribution::AliasTable;
pub use frame::Frame;
pub use reservoir::Reservoir;
pub use rng::Rng;
pub use sampler::{
    AnySampler, BlueNoiseSampler, IndependentSampler, PrefixSampler, Sampler, SamplerKind,
    SamplerModel, SamplerVisitor, SobolSampler, StratifiedSampler, UnknownSamplerKind,
};
