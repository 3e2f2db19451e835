//! The render driver: runs passes of samples over the image's tiles on the rayon thread pool
//! until a [`RenderBudget`] is spent.
//!
//! Every pixel's value depends only on the pixel and its sample indices: each pixel belongs to
//! one tile, its samples are added to its sums in sample-index order, and passes continue the
//! sample indices where the previous pass stopped. The film is therefore bit-identical whatever
//! the number of threads, the tile size, the order in which tiles finish, and how the samples
//! are split into passes. With blocks ([`render_blocks`]) the same holds per block: blocks are
//! aligned to the image, never cross a tile, and their samples are taken together in
//! sample-index order. Camera samples splatted into neighbouring pixels
//! ([`render_blocks_splatting`]) and light paths' splats are added in exact fixed-point sums,
//! which do not depend on the order of their terms.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use glam::{UVec2, Vec2, Vec3};
use rayon::prelude::*;

pub use crate::adaptive::Allocation;
use crate::auto::TechniquePilot;
use crate::budget::MAX_PASS_SECONDS;
pub use crate::budget::{BudgetError, RenderBudget};
use crate::film::{Film, FilteredSum, PixelSum, SplatSum};
use crate::filter::Splatter;
use crate::plan::{RenderPlan, Transport};
use crate::progress::Progress;
pub use crate::stop::StopSignal;
use crate::tiles::{Tile, tile_size_for, tiles};

/// How to drive a render, apart from its budget.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Draw a progress bar on standard error (only ever drawn when it is a terminal).
    pub progress: bool,
    /// Tile edge in pixels; `None` picks one from the image size and thread count.
    pub tile_size: Option<u32>,
    /// When raised, the render stops at the next pass boundary (after at least one pass) and
    /// returns the samples done so far, with [`RenderOutput::interrupted`] set.
    pub stop: Option<StopSignal>,
    /// Samples rendered earlier to continue from: the film's sums, and sample indices, carry on
    /// where they stopped, so the result has the same bits as one render of all the samples.
    /// The budget's `max_spp` counts these samples too; its `max_seconds` counts only this run.
    pub resume: Option<Arc<ResumePoint>>,
    /// How many samples each pixel gets (adaptive sampling); `None` gives every pixel the
    /// budget's samples per pixel. With an allocation the budget's `max_spp` is the mean over
    /// pixels, and pixel `p` takes sample indices `0 .. allocation.samples(p, mean)`.
    pub allocation: Option<Arc<Allocation>>,
    /// Longest a pass is planned to take once the speed is measured, in seconds:
    /// [`MAX_PASS_SECONDS`] unless a caller must stop sooner when asked (a stop waits for the
    /// pass under way). With a sample budget the image does not depend on it.
    pub max_pass_seconds: f64,
}

impl RenderOptions {
    /// No progress bar, automatic tile size, no stop signal, a fresh start.
    pub fn quiet() -> Self {
        Self {
            progress: false,
            tile_size: None,
            stop: None,
            resume: None,
            allocation: None,
            max_pass_seconds: MAX_PASS_SECONDS,
        }
    }
}

impl Default for RenderOptions {
    /// A progress bar (on terminals), automatic tile size, no stop signal, a fresh start.
    fn default() -> Self {
        Self {
            progress: true,
            ..Self::quiet()
        }
    }
}

/// An earlier render's accumulated samples, to continue from (see [`RenderOptions::resume`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ResumePoint {
    /// The sums so far; its size must be the image's.
    pub film: Film,
    /// Samples per pixel already in `film`: the next sample index of every pixel.
    pub spp: u32,
    /// Passes those samples took.
    pub passes: u32,
    /// Samples left out of `film` as NaN or infinite so far.
    pub non_finite: NonFiniteCounts,
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
    /// Counts `value`, which has a NaN or infinite channel.
    fn count(&mut self, value: Vec3) {
        if value.is_nan() {
            self.nan += 1;
        } else {
            self.inf += 1;
        }
    }

    /// Adds another count to this one.
    pub fn merge(&mut self, other: NonFiniteCounts) {
        self.nan += other.nan;
        self.inf += other.inf;
    }
}

/// What a finished render produced.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOutput {
    /// The accumulated samples.
    pub film: Film,
    /// Samples per pixel rendered (including any that were left out as non-finite), counting
    /// those of a [`ResumePoint`] continued from.
    pub spp: u32,
    /// Number of passes rendered, counting those of a [`ResumePoint`].
    pub passes: u32,
    /// Samples per pixel taken over from a [`ResumePoint`] (0 for a fresh start).
    pub resumed_spp: u32,
    /// Whether a [`StopSignal`] ended the render before its budget was spent.
    pub interrupted: bool,
    /// Wall-clock seconds spent rendering in this call.
    pub seconds: f64,
    /// Threads in the rayon pool the render ran on.
    pub threads: usize,
    /// Samples left out of the film as NaN or infinite.
    pub non_finite: NonFiniteCounts,
    /// Samples per pixel of an adaptive-sampling pilot, rendered but not in the film (0 without
    /// one); counted in `spp`, `passes`, `seconds` and `non_finite`.
    pub pilot_spp: u32,
    /// `auto`'s technique pilot and its choice (`None` for other presets); its time is counted
    /// in `seconds`.
    pub auto: Option<TechniquePilot>,
    /// Why adaptive sampling was asked for and not done (a budget too small to split), if so.
    pub adaptive_skipped: Option<String>,
}

impl RenderOutput {
    /// The plan that rendered this output's film: `plan` with the techniques `auto`'s pilot
    /// chose, where it ran.
    pub fn rendered_plan(&self, plan: &RenderPlan) -> RenderPlan {
        match &self.auto {
            Some(pilot) => RenderPlan {
                transport: Transport::Path(pilot.choice.settings),
                ..*plan
            },
            None => *plan,
        }
    }
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
    render_with_light_paths(width, height, budget, options, init, sample, None)
}

/// Traces the light path of a pixel sample, if it has one: `trace(scratch, pixel,
/// sample_index, splats)` pushes the (pixel, value) contributions the path makes anywhere on the
/// film onto `splats` and says whether it traced a path. It must depend only on `pixel` and
/// `sample_index`, like the sample function.
pub type LightPaths<'a, S> =
    dyn Fn(&mut S, UVec2, u32, &mut Vec<(UVec2, Vec3)>) -> bool + Sync + 'a;

/// [`render`], also tracing light paths for pixel samples with `light_paths` (when given)
/// and splatting its contributions onto the film ([`Film::add_splat`]). Splats are applied
/// after each pass in tile order, each tile's in the order traced, so the film stays
/// bit-identical whatever the threads.
pub fn render_with_light_paths<S, I, F>(
    width: u32,
    height: u32,
    budget: &RenderBudget,
    options: &RenderOptions,
    init: I,
    sample: F,
    light_paths: Option<&LightPaths<'_, S>>,
) -> Result<RenderOutput, BudgetError>
where
    I: Fn() -> S + Sync + Send,
    F: Fn(&mut S, UVec2, u32) -> Vec3 + Sync + Send,
{
    render_blocks(
        width,
        height,
        budget,
        options,
        1,
        init,
        |scratch: &mut S, pixels: &[UVec2], index: u32, values: &mut [Vec3]| {
            values[0] = sample(scratch, pixels[0], index);
        },
        light_paths,
    )
}

/// The most pixels in a block of [`render_blocks`] (a block edge of at most 4).
pub const MAX_BLOCK_PIXELS: usize = 16;

/// [`render_with_light_paths`] taking the samples of `block × block` pixels at once (`block` is
/// 1, 2 or 4; blocks are aligned to the image and cut by its edges): `sample_block(scratch,
/// pixels, sample_index, values)` writes one radiance sample of each of `pixels` (those of a
/// block that have sample `sample_index`, in row order) to `values`, of the same length. As
/// with [`render`], each value must depend only on the pixels and the sample index. Tiles are
/// rounded up to a multiple of the block, so that no block crosses a tile.
///
/// # Panics
/// If `block` is not 1, 2 or 4.
#[allow(clippy::too_many_arguments)]
pub fn render_blocks<S, I, F>(
    width: u32,
    height: u32,
    budget: &RenderBudget,
    options: &RenderOptions,
    block: u32,
    init: I,
    sample_block: F,
    light_paths: Option<&LightPaths<'_, S>>,
) -> Result<RenderOutput, BudgetError>
where
    I: Fn() -> S + Sync + Send,
    F: Fn(&mut S, &[UVec2], u32, &mut [Vec3]) + Sync + Send,
{
    render_blocks_splatting(
        width,
        height,
        budget,
        options,
        block,
        None,
        init,
        |scratch: &mut S, pixels: &[UVec2], index: u32, values: &mut [Vec3], _: &mut [Vec2]| {
            sample_block(scratch, pixels, index, values)
        },
        light_paths,
    )
}

/// [`render_blocks`] where `sample_block(scratch, pixels, sample_index, values, positions)`
/// also writes each sample's film position (pixels, inside its pixel) to `positions`. With a
/// `splatter` every finite sample is splatted into all the pixels its filter covers
/// ([`Splatter::splat`], [`Film::add_filtered`]) besides being added to its own pixel's sums,
/// and the film's values are the splatted ones; without one the positions are ignored. Samples
/// crossing a tile's edge are gathered per tile and added to the film after each pass in exact
/// sums, so the film stays bit-identical whatever the threads, tiles and passes. With an
/// allocation ([`RenderOptions::allocation`]) the splatted estimate is unbiased only in whole
/// rounds ([`Allocation::in_rounds`]): each sample then weighs 1 / (its pixel's samples per
/// round).
///
/// # Panics
/// If `block` is not 1, 2 or 4, or the splatter was made for another image size.
#[allow(clippy::too_many_arguments)]
pub fn render_blocks_splatting<S, I, F>(
    width: u32,
    height: u32,
    budget: &RenderBudget,
    options: &RenderOptions,
    block: u32,
    splatter: Option<&Splatter>,
    init: I,
    sample_block: F,
    light_paths: Option<&LightPaths<'_, S>>,
) -> Result<RenderOutput, BudgetError>
where
    I: Fn() -> S + Sync + Send,
    F: Fn(&mut S, &[UVec2], u32, &mut [Vec3], &mut [Vec2]) + Sync + Send,
{
    if let Some(splatter) = splatter {
        assert_eq!(
            splatter.size(),
            UVec2::new(width, height),
            "the splatter's image size"
        );
    }
    assert!(
        matches!(block, 1 | 2 | 4),
        "block edge {block} is not 1, 2 or 4"
    );
    budget.validate()?;
    let threads = rayon::current_num_threads();
    // Allocated sample counts make tiles' work unequal: four times as many tiles keeps the
    // threads evenly busy to the end of each pass.
    let balancing = if options.allocation.is_some() { 4 } else { 1 };
    let tile_size = options
        .tile_size
        .unwrap_or_else(|| tile_size_for(width, height, threads * balancing))
        .next_multiple_of(block);
    let tiles = tiles(width, height, tile_size);
    let fresh = || match splatter {
        Some(_) => Film::splatting(width, height),
        None => Film::new(width, height),
    };
    let (mut film, resumed_spp, mut passes, mut non_finite) = match options.resume.as_deref() {
        None => (fresh(), 0, 0, NonFiniteCounts::default()),
        Some(point) => {
            let size = (point.film.width(), point.film.height());
            if size != (width, height) {
                return Err(BudgetError::ResumeSize {
                    film: size,
                    image: (width, height),
                });
            }
            let mut film = point.film.clone();
            if splatter.is_some() && film.filtered().is_none() {
                film = film
                    .with_filtered(fresh().filtered().unwrap_or_default().to_vec())
                    .expect("the sizes match");
            }
            (film, point.spp, point.passes, point.non_finite)
        }
    };
    // This run's share of the budget: the sample limit counts the resumed samples too, and the
    // total never passes u32::MAX (sample indices are u32).
    let run_budget = RenderBudget {
        max_spp: Some(
            budget
                .max_spp
                .unwrap_or(u32::MAX)
                .saturating_sub(resumed_spp),
        ),
        ..*budget
    };
    // The samples' expected weights depend only on how many each pixel takes, so they are
    // added once for the whole run (see `add_expected_weights`), from these counts.
    let counts_before: Vec<u32> = match splatter {
        Some(_) => film.pixels().iter().map(|p| p.count).collect(),
        None => Vec::new(),
    };
    let progress = Progress::for_budget(options.progress, budget);
    let start = Instant::now();
    let (mut spp, mut last_pass) = (resumed_spp, 0u32);
    let mut interrupted = false;
    loop {
        let pass_spp = run_budget.next_pass_spp(
            spp - resumed_spp,
            start.elapsed().as_secs_f64(),
            last_pass,
            options.max_pass_seconds,
        );
        if pass_spp == 0 {
            break;
        }
        let stop_requested = options.stop.as_ref().is_some_and(StopSignal::is_raised);
        if stop_requested && spp > resumed_spp {
            interrupted = true;
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
        let pass = render_block_pass(
            &mut film,
            &tiles,
            PassSamples {
                first: spp,
                count: pass_spp,
                allocation: options.allocation.as_deref(),
            },
            block,
            splatter,
            &init,
            &sample_block,
            light_paths,
            &report,
        );
        non_finite.merge(pass);
        spp += pass_spp;
        passes += 1;
        last_pass = pass_spp;
        progress.set_message(format!("{spp} spp"));
    }
    if let Some(splatter) = splatter {
        add_expected_weights(
            &mut film,
            &tiles,
            splatter,
            options.allocation.as_deref(),
            &counts_before,
        );
    }
    let seconds = start.elapsed().as_secs_f64();
    progress.finish();
    Ok(RenderOutput {
        film,
        spp,
        passes,
        resumed_spp,
        interrupted,
        seconds,
        threads,
        non_finite,
        pilot_spp: 0,
        auto: None,
        adaptive_skipped: None,
    })
}

/// The samples of one pass: samples per pixel `first .. first + count`, or with an allocation
/// the samples that take each pixel from its count at mean `first` to its count at mean
/// `first + count`.
#[derive(Clone, Copy, Debug)]
pub struct PassSamples<'a> {
    /// Samples per pixel (the mean, with an allocation) done before this pass.
    pub first: u32,
    /// Samples per pixel (the mean, with an allocation) this pass adds.
    pub count: u32,
    /// Per-pixel sample counts, if not uniform.
    pub allocation: Option<&'a Allocation>,
}

impl PassSamples<'_> {
    /// The sample indices of `pixel` in this pass.
    pub fn indices(&self, pixel: UVec2) -> std::ops::Range<u32> {
        let end = self.first.saturating_add(self.count);
        match self.allocation {
            None => self.first..end,
            Some(a) => a.samples(pixel, self.first)..a.samples(pixel, end),
        }
    }
}

/// Renders the `samples` of every pixel of `tiles` into `film`, in parallel over the tiles,
/// calling `report(fraction of the pass done)` as tiles finish. Returns the samples left out as
/// non-finite. The film's sums are continued, not replaced, so consecutive passes give the same
/// bits as one pass of all their samples. The tiles must not overlap (those from
/// [`crate::tiles::tiles`] never do).
pub fn render_pass<S, I, F>(
    film: &mut Film,
    tiles: &[Tile],
    samples: PassSamples<'_>,
    init: &I,
    sample: &F,
    light_paths: Option<&LightPaths<'_, S>>,
    report: &(dyn Fn(f64) + Sync),
) -> NonFiniteCounts
where
    I: Fn() -> S + Sync + Send,
    F: Fn(&mut S, UVec2, u32) -> Vec3 + Sync + Send,
{
    render_block_pass(
        film,
        tiles,
        samples,
        1,
        None,
        init,
        &|scratch: &mut S, pixels: &[UVec2], index: u32, values: &mut [Vec3], _: &mut [Vec2]| {
            values[0] = sample(scratch, pixels[0], index);
        },
        light_paths,
        report,
    )
}

/// [`render_pass`] by blocks of `block × block` pixels, as [`render_blocks`] takes them; each
/// tile's origin and size must be multiples of `block` except where the image ends.
#[allow(clippy::too_many_arguments)]
fn render_block_pass<S, I, F>(
    film: &mut Film,
    tiles: &[Tile],
    samples: PassSamples<'_>,
    block: u32,
    splatter: Option<&Splatter>,
    init: &I,
    sample_block: &F,
    light_paths: Option<&LightPaths<'_, S>>,
    report: &(dyn Fn(f64) + Sync),
) -> NonFiniteCounts
where
    I: Fn() -> S + Sync + Send,
    F: Fn(&mut S, &[UVec2], u32, &mut [Vec3], &mut [Vec2]) + Sync + Send,
{
    let done = AtomicUsize::new(0);
    let shared: &Film = film;
    // One tile per rayon job, so an idle thread can take any tile left: by default rayon
    // hands each thread a run of consecutive tiles that it cannot give up once started, and
    // where tiles' work differs (an allocation's sample counts, costly regions of the image) the
    // pass then waits for the thread with the heavy run (cbox with adaptive sampling, 2 threads:
    // 14% of the render time).
    let results: Vec<TileResult> = tiles
        .par_iter()
        .with_max_len(1)
        .map_init(init, |scratch, tile| {
            let region = splatter.map_or(*tile, |s| splat_region(tile, s));
            let mut result = TileResult {
                sums: tile.pixels().map(|pixel| *shared.pixel(pixel)).collect(),
                filtered: match splatter {
                    Some(_) => vec![SplatSum::default(); region.pixel_count()],
                    None => Vec::new(),
                },
                region,
                ..TileResult::default()
            };
            let mut taking = [UVec2::ZERO; MAX_BLOCK_PIXELS];
            let mut slots = [0usize; MAX_BLOCK_PIXELS];
            let mut values = [Vec3::ZERO; MAX_BLOCK_PIXELS];
            let mut positions = [Vec2::ZERO; MAX_BLOCK_PIXELS];
            for block_origin in block_origins(tile, block) {
                let mut members = [BlockMember::default(); MAX_BLOCK_PIXELS];
                let mut size = 0;
                for (pixel, slot) in block_pixels(tile, block_origin, block) {
                    let indices = samples.indices(pixel);
                    members[size] = BlockMember {
                        pixel,
                        slot,
                        first: indices.start,
                        end: indices.end,
                    };
                    size += 1;
                }
                let members = &members[..size];
                let first = members.iter().map(|m| m.first).min().unwrap_or(0);
                let end = members.iter().map(|m| m.end).max().unwrap_or(0);
                for index in first..end {
                    let mut count = 0;
                    for member in members {
                        if (member.first..member.end).contains(&index) {
                            taking[count] = member.pixel;
                            slots[count] = member.slot;
                            count += 1;
                        }
                    }
                    // Pixels' ranges may leave gaps (an empty range starts anywhere).
                    if count == 0 {
                        continue;
                    }
                    sample_block(
                        scratch,
                        &taking[..count],
                        index,
                        &mut values[..count],
                        &mut positions[..count],
                    );
                    for (((&pixel, &slot), &value), &position) in taking[..count]
                        .iter()
                        .zip(&slots)
                        .zip(&values)
                        .zip(&positions)
                    {
                        if value.is_finite() {
                            result.sums[slot].add(value);
                            if let Some(splatter) = splatter {
                                let (origin, row) = (region.origin, region.size.x as usize);
                                let filtered = &mut result.filtered;
                                // In whole rounds a pixel's samples weigh 1 / (its samples
                                // per round), so that every pixel weighs the same in total.
                                let per_round = samples
                                    .allocation
                                    .and_then(|a| a.per_round(pixel))
                                    .unwrap_or(1);
                                let scale = 1.0 / per_round as f32;
                                splatter.splat(position, pixel, |first, weight_y, weights_x| {
                                    let at = first - origin;
                                    let start = at.y as usize * row + at.x as usize;
                                    let row_value = value * (weight_y * scale);
                                    let sums = &mut filtered[start..start + weights_x.len()];
                                    for (sum, &weight_x) in sums.iter_mut().zip(weights_x) {
                                        sum.add_weighted(row_value, weight_x);
                                    }
                                });
                            }
                        } else {
                            result.counts.count(value);
                        }
                        if let Some(trace) = light_paths {
                            trace_light_path(trace, scratch, pixel, index, &mut result);
                        }
                    }
                }
            }
            let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
            report(finished as f64 / tiles.len() as f64);
            result
        })
        .collect();
    let mut total = NonFiniteCounts::default();
    for (tile, result) in tiles.iter().zip(results) {
        for (pixel, pixel_sums) in tile.pixels().zip(result.sums) {
            *film.pixel_mut(pixel) = pixel_sums;
        }
        for (pixel, value) in result.splats {
            film.add_splat(pixel, value);
        }
        for (pixel, sums) in result.region.pixels().zip(&result.filtered) {
            film.add_splat_sum(pixel, sums);
        }
        film.add_light_paths(result.light_paths);
        total.merge(result.counts);
    }
    total
}

/// Adds to `film` the expected weights `W` of the samples its pixels took since their counts
/// were `counts_before` (in [`Film::pixels`] order): per sample and target pixel,
/// [`Splatter::for_each_expected`] over the pixel's samples per round, as each sample's own
/// weight is scaled ([`FilteredSum::add_expected`]). `W` depends only on a pixel's sample count,
/// and [`FilteredSum::add_expected`] gives the same bits for `n` samples at once as one at a
/// time, so one call after a run's passes stands for one per pass or per sample, at a
/// fraction of the cost (25 targets per pixel with Mitsuba's gaussian). In parallel over `tiles`.
fn add_expected_weights(
    film: &mut Film,
    tiles: &[Tile],
    splatter: &Splatter,
    allocation: Option<&Allocation>,
    counts_before: &[u32],
) {
    let shared: &Film = film;
    let width = shared.width() as usize;
    let results: Vec<(Tile, Vec<FilteredSum>)> = tiles
        .par_iter()
        .map(|tile| {
            let region = splat_region(tile, splatter);
            let mut filtered = vec![FilteredSum::default(); region.pixel_count()];
            let (origin, row) = (region.origin, region.size.x as usize);
            for pixel in tile.pixels() {
                let before = counts_before[pixel.y as usize * width + pixel.x as usize];
                let taken = shared.pixel(pixel).count - before;
                if taken == 0 {
                    continue;
                }
                let per_round = allocation.and_then(|a| a.per_round(pixel)).unwrap_or(1);
                let scale = 1.0 / f64::from(per_round);
                splatter.for_each_expected(pixel, |target, expected| {
                    let at = target - origin;
                    filtered[at.y as usize * row + at.x as usize]
                        .add_expected(taken, expected * scale);
                });
            }
            (region, filtered)
        })
        .collect();
    for (region, filtered) in results {
        for (pixel, sums) in region.pixels().zip(&filtered) {
            film.add_filtered(pixel, sums);
        }
    }
}

/// The pixels that the samples of `tile` can splat into: the tile grown by the splatter's
/// reach on every side, cut by the image.
fn splat_region(tile: &Tile, splatter: &Splatter) -> Tile {
    let reach = UVec2::splat(splatter.reach());
    let origin = tile.origin.saturating_sub(reach);
    let end = (tile.origin + tile.size + reach).min(splatter.size());
    Tile {
        origin,
        size: end - origin,
    }
}

/// The tile-relative origins of the blocks of `tile`, in row order.
fn block_origins(tile: &Tile, block: u32) -> impl Iterator<Item = UVec2> + '_ {
    let step = block as usize;
    (0..tile.size.y).step_by(step).flat_map(move |y| {
        (0..tile.size.x)
            .step_by(step)
            .map(move |x| UVec2::new(x, y))
    })
}

/// The pixels of the block at the tile-relative `origin`, in row order, each with its index in
/// [`Tile::pixels`] order.
fn block_pixels(
    tile: &Tile,
    origin: UVec2,
    block: u32,
) -> impl Iterator<Item = (UVec2, usize)> + '_ {
    let end = (origin + UVec2::splat(block)).min(tile.size);
    (origin.y..end.y).flat_map(move |y| {
        (origin.x..end.x).map(move |x| {
            (
                tile.origin + UVec2::new(x, y),
                (y * tile.size.x + x) as usize,
            )
        })
    })
}

/// A pixel of a block in a pass: where it is, its index in [`Tile::pixels`] order and its sample
/// indices `first .. end`.
#[derive(Clone, Copy, Debug, Default)]
struct BlockMember {
    pixel: UVec2,
    slot: usize,
    first: u32,
    end: u32,
}

/// Traces the light path of `pixel`'s sample `index`, if it has one, and keeps its finite
/// splats in `result`.
fn trace_light_path<S>(
    trace: &LightPaths<'_, S>,
    scratch: &mut S,
    pixel: UVec2,
    index: u32,
    result: &mut TileResult,
) {
    let first_splat = result.splats.len();
    if !trace(scratch, pixel, index, &mut result.splats) {
        return;
    }
    result.light_paths += 1;
    let mut kept = first_splat;
    for i in first_splat..result.splats.len() {
        if result.splats[i].1.is_finite() {
            result.splats[kept] = result.splats[i];
            kept += 1;
        } else {
            result.counts.count(result.splats[i].1);
        }
    }
    result.splats.truncate(kept);
}

/// What one tile of a pass produced.
#[derive(Default)]
struct TileResult {
    /// Its pixels' sums, in [`Tile::pixels`] order.
    sums: Vec<PixelSum>,
    /// The pixels its samples can splat into (the tile itself without a splatter).
    region: Tile,
    /// The camera samples splatted into `region`'s pixels, in [`Tile::pixels`] order; empty
    /// without a splatter.
    filtered: Vec<SplatSum>,
    /// Light paths' finite contributions anywhere on the film, in the order traced.
    splats: Vec<(UVec2, Vec3)>,
    /// Light paths traced.
    light_paths: u64,
    /// Samples and splats left out as non-finite.
    counts: NonFiniteCounts,
}
