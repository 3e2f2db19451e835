//! Adaptive sampling: how many samples each pixel gets, decided by a pilot render.
//!
//! The image error Strata reports is the relative mean squared error, the mean over pixels of
//! `(estimate − reference)² / (reference² + ε)`. A pixel whose one-sample relative variance is
//! `r²` and whose sample costs `c` contributes `r² / n` with `n` samples, so for a fixed total
//! cost the error is smallest with `n ∝ r / √c` (minimise `Σ r²/n` subject to `Σ n c` fixed).
//! The pilot render estimates `r²` per pixel from its own samples (sample variance over
//! `mean² + ε`) and `c` from the rays its samples traced ([`PixelCosts`]), both blurred over the
//! 3 × 3 neighbourhood because a few samples give a very noisy variance, and the allocation gives
//! each pixel a share proportional to `r / √c`, clamped to [`MIN_SHARE`, `MAX_SHARE`] of the
//! mean so that an unlucky pilot neither starves a pixel nor spends the image on one (a wider
//! clamp, 0.1 to 8, lost more on scenes of uniform noise, the furnace, than it gained on Veach's). (Costs are
//! counted in rays, not timed, so that the allocation, and so the image, is reproducible.)
//!
//! The pilot is rendered with its own seed and its samples are **not** in the image: the sample
//! counts are then independent of the samples the image is made of, so each pixel's mean stays an
//! unbiased estimate. (Reusing the pilot samples would bias it: a pilot sample that happened to be
//! large raises the pixel's variance estimate, which buys more samples, which dilutes it.)
//!
//! **When `auto` uses it.** With no `--adaptive` flag, `auto` samples adaptively wherever the
//! pilot costs at most a sixteenth of the budget ([`crate::plan::AUTO_ADAPTIVE_MIN_SPP`] samples
//! per pixel or more, or a time budget), except in a saved, resumed or partial render; the other
//! presets only when asked.

use std::sync::atomic::{AtomicU64, Ordering};

use glam::UVec2;
use world::RayCounters;

use crate::budget::RenderBudget;
use crate::film::Film;
use crate::metrics::RELMSE_EPSILON;

/// Least share of the mean sample count a pixel gets.
pub const MIN_SHARE: f64 = 0.25;
/// Largest share of the mean sample count a pixel gets.
pub const MAX_SHARE: f64 = 4.0;
/// The pilot takes this fraction of the budget (samples or seconds)...
pub const PILOT_FRACTION: f64 = 1.0 / 16.0;
/// ...but at most this many samples per pixel...
pub const MAX_PILOT_SPP: u32 = 16;
/// ...and at least this many: a pixel's variance needs two samples. A budget of fewer than
/// twice this many is not split (the render reports that it did not sample adaptively).
pub const MIN_PILOT_SPP: u32 = 2;

/// Cost of a sample apart from its rays, in units of an occlusion ray (camera ray set-up,
/// sampler start, film update).
const SAMPLE_OVERHEAD: f64 = 1.0;
/// Cost of a closest-hit ray with the shading of its hit, in units of an occlusion ray.
const CLOSEST_RAY_COST: f64 = 2.0;

/// The cost of each pixel's samples, in units of an occlusion ray, summed as they are rendered
/// (from any thread).
#[derive(Debug)]
pub struct PixelCosts {
    width: u32,
    /// Per pixel: the closest-hit rays in the high 32 bits and occlusion rays in the low.
    rays: Vec<AtomicU64>,
}

impl PixelCosts {
    /// No cost yet for any pixel of a `width × height` image.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            rays: (0..u64::from(width) * u64::from(height))
                .map(|_| AtomicU64::new(0))
                .collect(),
        }
    }

    /// Adds the rays one sample of `pixel` traced.
    pub fn add(&self, pixel: UVec2, rays: RayCounters) {
        let packed = (rays.rays << 32) | rays.shadow_rays.min(u64::from(u32::MAX));
        let index = pixel.y as usize * self.width as usize + pixel.x as usize;
        self.rays[index].fetch_add(packed, Ordering::Relaxed);
    }

    /// The mean cost of a sample of each pixel that had `samples[i]` samples, in row order.
    fn per_sample(&self, samples: impl Iterator<Item = u32>) -> Vec<f64> {
        self.rays
            .iter()
            .zip(samples)
            .map(|(rays, n)| {
                let packed = rays.load(Ordering::Relaxed);
                let cost = CLOSEST_RAY_COST * (packed >> 32) as f64 + (packed & 0xFFFF_FFFF) as f64;
                SAMPLE_OVERHEAD + cost / f64::from(n.max(1))
            })
            .collect()
    }
}

/// Seed of the pilot render of a render seeded with `seed`: a different sample stream.
pub fn pilot_seed(seed: u32) -> u32 {
    seed ^ 0xA5A5_5A5A
}

/// The budgets of the pilot and of the image proper for a render with `budget`, or `None` when
/// the budget is too small to split (fewer than 2 × [`MIN_PILOT_SPP`] samples per pixel).
///
/// The pilot gets [`PILOT_FRACTION`] of the samples (at least [`MIN_PILOT_SPP`], at most
/// [`MAX_PILOT_SPP`]) or of the time; the image gets the rest of the samples (its `max_spp` is
/// the mean per pixel).
/// A time limit is shared out by the caller: the image gets what the pilot leaves.
pub fn split_budget(budget: &RenderBudget) -> Option<(RenderBudget, RenderBudget)> {
    let pilot_spp = match budget.max_spp {
        Some(spp) if spp < 2 * MIN_PILOT_SPP => return None,
        Some(spp) => ((f64::from(spp) * PILOT_FRACTION) as u32).clamp(MIN_PILOT_SPP, MAX_PILOT_SPP),
        None => MAX_PILOT_SPP,
    };
    let pilot = RenderBudget {
        max_spp: Some(pilot_spp),
        max_seconds: budget.max_seconds.map(|s| s * PILOT_FRACTION),
    };
    let image = RenderBudget {
        max_spp: budget.max_spp.map(|spp| spp - pilot_spp),
        max_seconds: budget.max_seconds,
    };
    Some((pilot, image))
}

/// Per-pixel shares of the samples: pixel `i` gets `max(1, round(share_i · v))` samples when
/// the mean is `v` samples per pixel. The shares average 1.
///
/// In whole rounds ([`Allocation::in_rounds`]) pixel `i` instead gets `k_i · t` samples, where
/// `k_i` is its share in quarters (at least 1) and `t` the rounds done; every pixel's count is
/// then `t` times a number known before the render, which splatting camera samples needs to
/// stay unbiased under a time budget ([`crate::filter::Splatter`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Allocation {
    width: u32,
    shares: Vec<f32>,
    /// Samples per round per pixel, when in whole rounds.
    rounds: Option<Rounds>,
}

/// An allocation's whole rounds: samples per round (`k_i`) per pixel and their mean `k̄`, kept
/// since every pixel's count in every pass needs it.
#[derive(Clone, Debug, PartialEq)]
struct Rounds {
    per_pixel: Vec<u32>,
    mean: f64,
}

impl Rounds {
    /// Rounds done at a mean of `mean_spp` samples per pixel.
    fn done_at(&self, mean_spp: u32) -> u32 {
        (f64::from(mean_spp) / self.mean)
            .round()
            .min(f64::from(u32::MAX)) as u32
    }
}

/// Samples per round of a pixel whose share is 1, in an allocation in whole rounds.
pub const SAMPLES_PER_ROUND: u32 = 4;

impl Allocation {
    /// The allocation that minimises relative MSE for the time spent according to the `pilot`
    /// film and the `costs` of its samples (see the module documentation). A pilot with no
    /// variance anywhere gives the uniform allocation.
    pub fn from_pilot(pilot: &Film, costs: &PixelCosts) -> Self {
        let (width, height) = (pilot.width() as usize, pilot.height() as usize);
        let relative_variance: Vec<f64> = pilot
            .pixels()
            .iter()
            .map(|p| {
                let mean = p.mean().as_dvec3();
                let relative = p.sample_variance() / (mean * mean + RELMSE_EPSILON);
                (relative.x + relative.y + relative.z) / 3.0
            })
            .collect();
        let blurred = box_blur_3x3(&relative_variance, width, height);
        let cost = box_blur_3x3(
            &costs.per_sample(pilot.pixels().iter().map(|p| p.count)),
            width,
            height,
        );
        let wanted: Vec<f64> = blurred
            .iter()
            .zip(&cost)
            .map(|(r2, c)| (r2 / c).sqrt())
            .collect();
        Self {
            width: pilot.width(),
            shares: normalised_shares(&wanted),
            rounds: None,
        }
    }

    /// The same allocation in whole rounds: pixel `i` takes `k_i = max(1, round(share_i ·
    /// SAMPLES_PER_ROUND))` samples per round, and at a mean of `v` samples per pixel the rounds
    /// done are `round(v / k̄)` with `k̄` the mean of the `k_i` (so the mean count stays within
    /// `k̄ / 2` of `v`). Pixels with equal shares (a block's, [`Self::blockwise`]) keep equal
    /// counts.
    pub fn in_rounds(mut self) -> Self {
        let per_pixel: Vec<u32> = self
            .shares
            .iter()
            .map(|&s| ((f64::from(s) * f64::from(SAMPLES_PER_ROUND)).round() as u32).max(1))
            .collect();
        let total: u64 = per_pixel.iter().map(|&k| u64::from(k)).sum();
        let mean = total as f64 / per_pixel.len().max(1) as f64;
        self.rounds = Some(Rounds { per_pixel, mean });
        self
    }

    /// Samples per round of `pixel` when the allocation is in whole rounds
    /// ([`Self::in_rounds`]), else `None`.
    pub fn per_round(&self, pixel: UVec2) -> Option<u32> {
        let rounds = self.rounds.as_ref()?;
        rounds.per_pixel.get(self.index(pixel)).copied()
    }

    /// The same allocation with every `block × block` block of pixels (aligned to the image, cut
    /// by its edges) given its pixels' mean share, so that all of a block's pixels take the
    /// same samples: path reuse traces a block's samples together and shares each sample index's
    /// paths among the pixels that have it, so pixels of one block with different counts would
    /// share less (on the Cornell box, per-pixel counts doubled path reuse's relMSE at 128 spp).
    /// The mean share stays 1.
    pub fn blockwise(mut self, block: u32) -> Self {
        let block = block.max(1) as usize;
        let width = self.width as usize;
        let height = self.shares.len() / width.max(1);
        for by in (0..height).step_by(block) {
            for bx in (0..width).step_by(block) {
                let (ys, xs) = (by..(by + block).min(height), bx..(bx + block).min(width));
                let count = (ys.len() * xs.len()) as f32;
                let mean = ys
                    .clone()
                    .flat_map(|y| xs.clone().map(move |x| (y, x)))
                    .map(|(y, x)| self.shares[y * width + x])
                    .sum::<f32>()
                    / count;
                for y in ys {
                    for x in xs.clone() {
                        self.shares[y * width + x] = mean;
                    }
                }
            }
        }
        self
    }

    /// The share of `pixel` (1 is the mean).
    pub fn share(&self, pixel: UVec2) -> f32 {
        self.shares[self.index(pixel)]
    }

    /// Samples `pixel` gets when the mean is `mean_spp` samples per pixel: 0 for 0, else at least
    /// 1; never decreasing as `mean_spp` grows, so passes can add samples pixel by pixel.
    /// In whole rounds: `k_i` times the rounds done, which may be 0 for small `mean_spp`.
    pub fn samples(&self, pixel: UVec2, mean_spp: u32) -> u32 {
        if mean_spp == 0 {
            return 0;
        }
        if let Some(rounds) = &self.rounds {
            let per_round = rounds.per_pixel[self.index(pixel)];
            return per_round.saturating_mul(rounds.done_at(mean_spp));
        }
        let wanted = (f64::from(self.share(pixel)) * f64::from(mean_spp)).round();
        wanted.clamp(1.0, f64::from(u32::MAX)) as u32
    }

    fn index(&self, pixel: UVec2) -> usize {
        pixel.y as usize * self.width as usize + pixel.x as usize
    }
}

/// The mean of each value's 3 × 3 neighbourhood (clipped at the image border).
fn box_blur_3x3(values: &[f64], width: usize, height: usize) -> Vec<f64> {
    let mut blurred = Vec::with_capacity(values.len());
    for y in 0..height {
        for x in 0..width {
            let (mut sum, mut count) = (0.0, 0.0);
            for ny in y.saturating_sub(1)..(y + 2).min(height) {
                for nx in x.saturating_sub(1)..(x + 2).min(width) {
                    sum += values[ny * width + nx];
                    count += 1.0;
                }
            }
            blurred.push(sum / count);
        }
    }
    blurred
}

/// `wanted` (non-negative; NaN counts as 0) scaled to mean 1 and clamped to
/// [`MIN_SHARE`, `MAX_SHARE`]; all ones when nothing is wanted anywhere.
fn normalised_shares(wanted: &[f64]) -> Vec<f32> {
    let clean: Vec<f64> = wanted
        .iter()
        .map(|&w| if w.is_finite() && w > 0.0 { w } else { 0.0 })
        .collect();
    let mut shares = clean.clone();
    // Clamping moves the mean; a few rounds of rescaling and clamping settle it.
    for _ in 0..8 {
        let mean = shares.iter().sum::<f64>() / shares.len().max(1) as f64;
        if !(mean > 0.0 && mean.is_finite()) {
            return vec![1.0; wanted.len()];
        }
        for share in &mut shares {
            *share = (*share / mean).clamp(MIN_SHARE, MAX_SHARE);
        }
    }
    shares.iter().map(|&s| s as f32).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// Every pixel of a `width × height` image the same share.
    fn uniform(width: u32, height: u32) -> Allocation {
        Allocation {
            width,
            shares: vec![1.0; width as usize * height as usize],
            rounds: None,
        }
    }

    #[test]
    fn allocations_in_rounds_give_every_pixel_a_multiple_of_its_share() {
        let allocation = Allocation {
            width: 4,
            shares: vec![0.25, 0.5, 1.0, 2.25],
            rounds: None,
        }
        .in_rounds();
        let pixels: Vec<UVec2> = (0..4).map(|x| UVec2::new(x, 0)).collect();
        let per_round: Vec<u32> = pixels
            .iter()
            .map(|&p| allocation.per_round(p).unwrap())
            .collect();
        assert_eq!(per_round, [1, 2, 4, 9]);
        let mut last = vec![0; 4];
        for mean in [0, 1, 3, 4, 9, 100, 1000] {
            let counts: Vec<u32> = pixels
                .iter()
                .map(|&p| allocation.samples(p, mean))
                .collect();
            let rounds = counts[0];
            for (count, k) in counts.iter().zip(&per_round) {
                assert_eq!(*count, k * rounds, "mean {mean}");
            }
            let taken = counts.iter().sum::<u32>() as f64 / 4.0;
            assert!(
                (taken - f64::from(mean)).abs() <= 2.0,
                "mean {mean}: {taken}"
            );
            assert!(counts.iter().zip(&last).all(|(c, l)| c >= l), "never fewer");
            last = counts;
        }
        assert_eq!(uniform(2, 2).per_round(UVec2::ZERO), None);
    }

    #[test]
    fn shares_follow_the_relative_standard_deviation() {
        // Left half: relative variance 4x the right half's, so twice the samples.
        let (width, height) = (8, 4);
        let mut pilot = Film::new(width, height);
        for y in 0..height {
            for x in 0..width {
                let spread = if x < width / 2 { 2.0 } else { 1.0 };
                for value in [1.0 - spread * 0.5, 1.0 + spread * 0.5] {
                    pilot.add(UVec2::new(x, y), Vec3::splat(value));
                }
            }
        }
        let allocation = Allocation::from_pilot(&pilot, &PixelCosts::new(width, height));
        let far_left = allocation.share(UVec2::new(0, 1));
        let far_right = allocation.share(UVec2::new(width - 1, 1));
        assert!(
            (far_left / far_right - 2.0).abs() < 1e-4,
            "{far_left} / {far_right}"
        );
        let mean: f32 = (0..height)
            .flat_map(|y| (0..width).map(move |x| UVec2::new(x, y)))
            .map(|p| allocation.share(p))
            .sum::<f32>()
            / (width * height) as f32;
        assert!((mean - 1.0).abs() < 1e-5, "mean share {mean}");
    }

    #[test]
    fn blockwise_shares_are_equal_within_blocks_and_keep_their_sum() {
        let (width, height) = (6, 5);
        let allocation = Allocation {
            width,
            shares: (0..width * height)
                .map(|i| 0.25 + (i % 7) as f32 * 0.3)
                .collect(),
            rounds: None,
        };
        let total: f32 = allocation.shares.iter().sum();
        let blocked = allocation.clone().blockwise(4);
        let blocked_total: f32 = blocked.shares.iter().sum();
        assert!(
            (total - blocked_total).abs() < 1e-4,
            "{total} vs {blocked_total}"
        );
        // The 4x4 block at the origin, the 2x4 one right of it, the cut ones below.
        for (a, b) in [
            ((0, 0), (3, 3)),
            ((4, 0), (5, 3)),
            ((0, 4), (3, 4)),
            ((4, 4), (5, 4)),
        ] {
            let share = |(x, y): (u32, u32)| blocked.share(UVec2::new(x, y));
            assert_eq!(share(a), share(b), "{a:?} and {b:?} share a block");
        }
        assert_ne!(
            blocked.share(UVec2::new(0, 0)),
            blocked.share(UVec2::new(4, 0)),
            "other blocks keep their own means"
        );
    }

    #[test]
    fn a_noiseless_pilot_gives_the_uniform_allocation() {
        let mut pilot = Film::new(3, 2);
        for y in 0..2 {
            for x in 0..3 {
                pilot.add(UVec2::new(x, y), Vec3::ONE);
                pilot.add(UVec2::new(x, y), Vec3::ONE);
            }
        }
        assert_eq!(
            Allocation::from_pilot(&pilot, &PixelCosts::new(3, 2)),
            uniform(3, 2)
        );
    }

    #[test]
    fn costlier_pixels_get_fewer_samples_for_the_same_noise() {
        // Equal noise everywhere; the right half's samples trace 4 closest-hit and 7 occlusion
        // rays (cost 1 + 8 + 7 = 16 units), the left half's none (cost 1): 4x the samples left.
        let (width, height) = (8, 2);
        let mut pilot = Film::new(width, height);
        let costs = PixelCosts::new(width, height);
        for y in 0..height {
            for x in 0..width {
                for value in [0.5, 1.5] {
                    pilot.add(UVec2::new(x, y), Vec3::splat(value));
                    if x >= width / 2 {
                        let rays = RayCounters {
                            rays: 4,
                            shadow_rays: 7,
                            connection_rays: 0,
                        };
                        costs.add(UVec2::new(x, y), rays);
                    }
                }
            }
        }
        let allocation = Allocation::from_pilot(&pilot, &costs);
        let ratio = allocation.share(UVec2::new(0, 0)) / allocation.share(UVec2::new(7, 0));
        assert!((ratio - 4.0).abs() < 1e-4, "share ratio {ratio}");
    }

    #[test]
    fn shares_are_clamped_and_keep_mean_one() {
        let mut wanted = vec![0.0; 99];
        wanted.push(1e9);
        wanted[3] = f64::NAN;
        let shares = normalised_shares(&wanted);
        assert!(
            shares
                .iter()
                .all(|&s| { (MIN_SHARE as f32 * 0.999..=MAX_SHARE as f32 * 1.001).contains(&s) })
        );
        let mean = shares.iter().map(|&s| f64::from(s)).sum::<f64>() / shares.len() as f64;
        assert!((mean - 1.0).abs() < 0.05, "mean share {mean}");
        assert_eq!(shares[99], MAX_SHARE as f32);
    }

    #[test]
    fn sample_counts_grow_with_the_mean_and_never_drop_to_zero() {
        let allocation = Allocation {
            width: 2,
            shares: vec![0.25, 1.75],
            rounds: None,
        };
        let (low, high) = (UVec2::new(0, 0), UVec2::new(1, 0));
        assert_eq!(allocation.samples(low, 0), 0);
        assert_eq!(allocation.samples(low, 1), 1);
        assert_eq!(allocation.samples(high, 8), 14);
        for pixel in [low, high] {
            let mut previous = 0;
            for mean in 0..5000 {
                let n = allocation.samples(pixel, mean);
                assert!(n >= previous, "mean {mean}: {n} < {previous}");
                previous = n;
            }
        }
    }

    #[test]
    fn budgets_split_between_pilot_and_image() {
        let (pilot, image) = split_budget(&RenderBudget::spp(256)).expect("splits");
        assert_eq!((pilot.max_spp, image.max_spp), (Some(16), Some(240)));
        let (pilot, image) = split_budget(&RenderBudget::spp(20)).expect("splits");
        assert_eq!((pilot.max_spp, image.max_spp), (Some(2), Some(18)));
        let (pilot, image) = split_budget(&RenderBudget::spp(4)).expect("splits");
        assert_eq!((pilot.max_spp, image.max_spp), (Some(2), Some(2)));
        assert_eq!(split_budget(&RenderBudget::spp(3)), None);
        assert_eq!(split_budget(&RenderBudget::spp(1)), None);
        let (pilot, image) = split_budget(&RenderBudget::seconds(2.0)).expect("splits");
        assert_eq!(pilot.max_seconds, Some(0.125));
        assert_eq!(image.max_spp, None);
    }
}
