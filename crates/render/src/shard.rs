//! `strata render --samples START..END`: one piece of a render split over processes or
//! machines, and the record of what a render's film holds (see [`crate::merge`]).
//!
//! A piece renders exactly the sample indices `START..END` of the render that `--spp N` would
//! make, `N` being `--spp` when given and `END` otherwise: the sampler's pattern is laid out for
//! `N` samples, and the render continues from sample index `START` with empty sums, as a resumed
//! render continues from its saved sample index ([`crate::driver::RenderOptions::resume`]).
//! Since every sample depends only on the pixel and its sample index, the piece's samples are
//! those of the whole render, whatever the thread count.

use std::ops::Range;
use std::sync::Arc;

use crate::commands::CommandError;
use crate::driver::{NonFiniteCounts, RenderBudget, RenderOutput, ResumePoint};
use crate::film::Film;
use crate::film_exr::{RenderRecord, SampleRanges, render_settings};
use crate::plan::RenderPlan;
use scene::SceneDesc;
use scene::limits::MAX_SAMPLE_COUNT;

/// Parses `START..END`: sample indices from START up to END, END excluded, with
/// `START < END ≤` [`MAX_SAMPLE_COUNT`].
pub fn parse_sample_range(text: &str) -> Result<Range<u32>, String> {
    let (start, end) = text
        .split_once("..")
        .ok_or_else(|| format!("'{text}' is not START..END (e.g. 0..64)"))?;
    let number = |s: &str| {
        s.trim()
            .parse::<u32>()
            .map_err(|e| format!("'{s}' in '{text}' is not a sample index: {e}"))
    };
    let (start, end) = (number(start)?, number(end)?);
    if start >= end {
        return Err(format!(
            "{start}..{end} holds no samples (START must be less than END)"
        ));
    }
    if end > MAX_SAMPLE_COUNT {
        return Err(format!(
            "{start}..{end} goes past the most samples per pixel, {MAX_SAMPLE_COUNT}"
        ));
    }
    Ok(start..end)
}

/// Makes `plan` render only `samples` of the render that `--spp N` makes (`N` is `spp_flag`,
/// or `samples.end` without it), and returns the point the driver starts from: sample index
/// `samples.start` with empty sums for a `width × height` image. Bad input when `samples` goes
/// past `N`.
pub fn start_piece(
    samples: Range<u32>,
    spp_flag: Option<u32>,
    plan: &mut RenderPlan,
    width: u32,
    height: u32,
) -> Result<Arc<ResumePoint>, CommandError> {
    let total = spp_flag.unwrap_or(samples.end);
    if samples.end > total {
        return Err(CommandError::BadInput(format!(
            "--samples {}..{} goes past --spp {total}, the render it is a piece of",
            samples.start, samples.end
        )));
    }
    plan.sampler_spp = total;
    plan.budget = RenderBudget::spp(samples.end);
    Ok(Arc::new(ResumePoint {
        film: Film::new(width, height),
        spp: samples.start,
        passes: 0,
        non_finite: NonFiniteCounts::default(),
    }))
}

/// The record of what `output`'s film holds: the scene's fingerprint `scene_hash`, the
/// settings of `plan` for `desc` (with the techniques `auto`'s pilot chose, where it ran: those
/// rendered the film), and the sample indices from `first` (the piece's START, else 0) up to
/// where the render stopped (without an adaptive pilot's samples, which are not in the film).
pub fn film_record(
    scene_hash: String,
    plan: &RenderPlan,
    desc: &SceneDesc,
    first: u32,
    output: &RenderOutput,
) -> RenderRecord {
    RenderRecord {
        scene: scene_hash,
        settings: render_settings(&output.rendered_plan(plan), desc),
        samples: SampleRanges::single(plan.seed, first..output.spp - output.pilot_spp),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_ranges_parse_and_bad_ones_say_why() {
        assert_eq!(parse_sample_range("0..64"), Ok(0..64));
        assert_eq!(parse_sample_range("16..17"), Ok(16..17));
        for (bad, why) in [
            ("8..8", "no samples"),
            ("9..8", "no samples"),
            ("0-8", "START..END"),
            ("a..8", "not a sample index"),
            ("0..-1", "not a sample index"),
            ("0..16777217", "goes past"),
        ] {
            let error = parse_sample_range(bad).unwrap_err();
            assert!(error.contains(why), "{bad}: {error}");
        }
    }
}
