//! Turning per-sample radiance into images: reconstruction filters, the film that accumulates samples,
//! the tiled parallel driver with sample and time budgets, EXR/PNG input and output, image error
//! metrics, render statistics, and the command-line interface of the `strata` binary.
//!
//! Pixel coordinates are integer `(x, y)` with `(0, 0)` the top-left pixel; continuous image
//! coordinates put the centre of pixel `(x, y)` at `(x + 0.5, y + 0.5)`. Colours are linear RGB
//! `glam::Vec3` throughout.
//!
//! ```
//! use glam::{UVec2, Vec3};
//! use render::driver::{render, RenderBudget, RenderOptions};
//!
//! let budget = RenderBudget { max_spp: Some(4), max_seconds: None };
//! let output = render(8, 4, &budget, &RenderOptions::quiet(), || (), |_, pixel: UVec2, _sample| {
//!     Vec3::splat(pixel.x as f32)
//! })
//! .unwrap();
//! let image = output.film.to_image();
//! assert_eq!(image.pixel(3, 2), Vec3::splat(3.0));
//! ```

#![warn(missing_docs)]

pub mod adaptive;
pub mod atomic_write;
pub mod auto;
pub mod budget;
pub mod caustic_variance;
pub mod cli;
pub mod commands;
pub mod diff;
pub mod driver;
pub mod film;
pub mod film_exr;
pub mod filter;
pub mod fingerprint;
pub mod image;
pub mod merge;
pub mod metrics;
pub mod plan;
pub mod progress;
mod render_command;
pub mod session;
pub mod shard;
pub mod state;
pub mod stats;
pub mod stop;
pub mod summary;
pub mod tiles;
