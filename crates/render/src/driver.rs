//! The render driver: runs passes of samples over the image's tiles on the rayon thread pool
//! until a [`RenderBudget`] is spent.
//!
//! Every pixel's value depends only on the pixel and its sample indices: each pixel belongs to
//! one tile, its samples are added to its sums in sample-index order, and passes continue the
//! sample indices where the previous pass stopped. The film is therefore bit-identical whatever
//! the number of threads, the tile size, the order in which tiles finish, and how the samples
//! are split into passes.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use glam::{UVec2, Vec3};
use rayon::prelude::*;

pub use crate::budget::{BudgetError, RenderBudget};
use crate::film::{Film, PixelSum};
use crate::progress::Progress;
use crate::tiles::{Tile, tile_size_for, tiles};

/// How to drive a render, apart from its budget.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderOptions {
    /// Draw a progress bar on standard error (only ever drawn when it is a terminal).
    pub progress: bool,
    /// Tile edge in pixels; `None` picks one from the image size and thread count.
    pub tile_size: Option<u32>,
}

impl RenderOptions {
    /// No progress bar, automatic tile size.
    pub fn quiet() -> Self {
        Self {
            progress: false,
            tile_size: None,
        }
    }
}

impl Default for RenderOptions {
    /// A progress bar (on terminals), automatic tile size.
    fn default() -> Self {
        Self {
            progress: true,
            tile_size: None,
        }
    }
}

/// Counts of sample values that were not finite; such samples are left out of the film
/// entirely (neither their value nor their count is added to their pixel).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NonFiniteCounts {
    /// Samples with at least one NaN channel.
    pub nan: u64,
    /// Samples with an infinite channel and no NaN.
    pub inf: u64,
}

impl NonFiniteCounts {
    /// Adds another count to this one.
    fn merge(&mut self, other: NonFiniteCounts) {
        self.nan += other.nan;
        self.inf += other.inf;
    }
}

/// What a finished render produced.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOutput {
    /// The accumulated samples.
    pub film: Film,
    /// Samples per pixel rendered (including any that were left out as non-finite).
    pub spp: u32,
    /// Number of passes rendered.
    pub passes: u32,
    /// Wall-clock seconds spent rendering.
    pub seconds: f64,
    /// Threads in the rayon pool the render ran on.
    pub threads: usize,
    /// Samples left out of the film as NaN or infinite.
    pub non_finite: NonFiniteCounts,
}

/// Renders a `width × height` image until `budget` is spent, on the current rayon thread pool
/// (run it inside `ThreadPool::install` to choose the threads).
///
/// `sample(scratch, pixel, sample_index)` returns one radiance sample of `pixel`; sample
/// indices run from 0 upwards. It must depend only on `pixel` and `sample_index` for the image
/// to be reproducible. `init` makes per-worker scratch state (sampler state, path buffers,
/// counters); rayon may create more than one per thread, and it must never change the values
/// returned. Per-worker counters can be gathered by a `Drop` impl on the scratch type.
pub fn render<S, I, F>(
    width: u32,
    height: u32,
    budget: &RenderBudget,
    options: &RenderOptions,
    init: I,
    sample: F,
) -> Result<RenderOutput, BudgetError>
where
    I: Fn() -> S + Sync + Send,
    F: Fn(&mut S, UVec2, u32) -> Vec3 + Sync + Send,
{
    budget.validate()?;
    let threads = rayon::current_num_threads();
    let tile_size = options
        .tile_size
        .unwrap_or_else(|| tile_size_for(width, height, threads));
    let tiles = tiles(width, height, tile_size);
    let mut film = Film::new(width, height);
    let progress = Progress::new(options.progress);
    let start = Instant::now();
    let (mut spp, mut passes, mut last_pass) = (0u32, 0u32, 0u32);
    let mut non_finite = NonFiniteCounts::default();
    loop {
        let pass_spp = budget.next_pass_spp(spp, start.elapsed().as_secs_f64(), last_pass);
        if pass_spp == 0 {
            break;
        }
        let report = |fraction_of_pass: f64| {
            let spp_fraction = budget.max_spp.map_or(0.0, |max| {
                (f64::from(spp) + fraction_of_pass * f64::from(pass_spp)) / f64::from(max)
            });
            let time_fraction = budget
                .max_seconds
                .map_or(0.0, |max| start.elapsed().as_secs_f64() / max);
            progress.set_fraction(spp_fraction.max(time_fraction));
        };
        let pass = render_pass(&mut film, &tiles, spp, pass_spp, &init, &sample, &report);
        non_finite.merge(pass);
        spp += pass_spp;
        passes += 1;
        last_pass = pass_spp;
        progress.set_message(format!("{spp} spp"));
    }
    let seconds = start.elapsed().as_secs_f64();
    progress.finish();
    Ok(RenderOutput {
        film,
        spp,
        passes,
        seconds,
        threads,
        non_finite,
    })
}

/// Renders samples `first_sample .. first_sample + spp` of every pixel of `tiles` into `film`,
/// in parallel over the tiles, calling `report(fraction of the pass done)` as tiles finish.
/// Returns the samples left out as non-finite. The film's sums are continued, not replaced, so
/// consecutive passes give the same bits as one pass of all their samples. The tiles must not
/// overlap (those from [`crate::tiles::tiles`] never do).
pub fn render_pass<S, I, F>(
    film: &mut Film,
    tiles: &[Tile],
    first_sample: u32,
    spp: u32,
    init: &I,
    sample: &F,
    report: &(dyn Fn(f64) + Sync),
) -> NonFiniteCounts
where
    I: Fn() -> S + Sync + Send,
    F: Fn(&mut S, UVec2, u32) -> Vec3 + Sync + Send,
{
    let end = first_sample.saturating_add(spp);
    let done = AtomicUsize::new(0);
    let shared: &Film = film;
    let results: Vec<(Vec<PixelSum>, NonFiniteCounts)> = tiles
        .par_iter()
        .map_init(init, |scratch, tile| {
            let mut counts = NonFiniteCounts::default();
            let sums = tile
                .pixels()
                .map(|pixel| {
                    let mut sums = *shared.pixel(pixel);
                    for index in first_sample..end {
                        let value = sample(scratch, pixel, index);
                        if value.is_finite() {
                            sums.add(value);
                        } else if value.is_nan() {
                            counts.nan += 1;
                        } else {
                            counts.inf += 1;
                        }
                    }
                    sums
                })
                .collect();
            let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
            report(finished as f64 / tiles.len() as f64);
            (sums, counts)
        })
        .collect();
    let mut total = NonFiniteCounts::default();
    for (tile, (sums, counts)) in tiles.iter().zip(results) {
        for (pixel, pixel_sums) in tile.pixels().zip(sums) {
            *film.pixel_mut(pixel) = pixel_sums;
        }
        total.merge(counts);
    }
    total
}
