//! Random numbers and sample mappings for Monte Carlo rendering.
//!
//! Depends only on `glam` and `rand_core`, so it can be used outside Strata.

pub mod frame;
pub mod rng;
pub mod warp;

pub use frame::Frame;
pub use rng::Rng;
