//! Adaptive sampling takes the samples its allocation asks for, says when it cannot sample
//! adaptively, and keeps the image unbiased.
//!
//! **Samples taken.** The film's per-pixel sample counts are counted, not the spp asked for:
//! the pilot's samples are not in the image, so the counts average the budget minus the pilot
//! (each pixel's count is its allocation share times that mean, rounded), and every share lies
//! in [`MIN_SHARE`, `MAX_SHARE`]. Below 2 × [`MIN_PILOT_SPP`] samples per pixel the budget cannot
//! be split: the render takes every sample uniformly and says so (`adaptive_skipped`); from
//! there up the pilot takes at least [`MIN_PILOT_SPP`] and the counts vary.
//!
//! **Unbiasedness.** With the pilot's samples left out, each pixel's sample count is independent
//! of the samples averaged, so an adaptive render must agree with the reference integrator. The
//! test is `unbiased.rs`'s (`common::compare`): [`REPLICATES`] adaptive renders and as many of
//! the reference, compared on the whole image, 8 × 8 regions and 4 × 4 blocks with Welch's
//! t-test at a family-wise α = [`ALPHA`] per comparison (a third per level, Šidák's correction
//! within a level), and the power shown by rejecting the adaptive image × 1.005 (whole-image
//! test) and a typical block × 1.05 (block test). Seeds are fixed; a failure prints the scene,
//! both replicate sets (seeds, spp, size) and the worst unit of each level.

mod common;

use common::compare::{Replicates, check_unbiased};
use common::{load_file, load_version, mis_power, render_plan, scenes_dir};
use render::adaptive::{MAX_SHARE, MIN_PILOT_SPP, MIN_SHARE, split_budget};
use render::driver::{RenderBudget, RenderOutput};
use render::plan::{RenderPlan, Transport};
use sampling::sampler::SamplerKind;
use scene::RenderScene;

const SIZE: u32 = 24;
const ALPHA: f64 = 0.01;
/// Independent renders of the adaptive configuration and of the oracle.
const REPLICATES: u32 = 16;
const ORACLE_SEED: u32 = 1000;
const ADAPTIVE_SEED: u32 = 3000;

/// An adaptive MIS render of `scene` at `spp` samples per pixel (pilot included) with `seed`.
fn adaptive(scene: &RenderScene, spp: u32, seed: u32) -> RenderPlan {
    let settings = mis_power(
        common::max_depth(scene),
        scene.desc.integrator.hide_emitters,
    );
    RenderPlan {
        adaptive: true,
        ..RenderPlan::fixed_spp(
            Transport::Path(settings),
            SamplerKind::Independent,
            seed,
            spp,
        )
    }
}

/// The per-pixel sample counts of `output`'s film, row-major.
fn counts(output: &RenderOutput) -> Vec<u32> {
    output.film.pixels().iter().map(|p| p.count).collect()
}

/// Checks that an adaptive render of `spp` took the samples its allocation asks for: the
/// pilot's share of the budget, and per pixel a count whose mean is the rest.
fn check_samples_taken(name: &str, output: &RenderOutput, spp: u32) {
    let (pilot, image) = split_budget(&RenderBudget::spp(spp)).expect("the budget splits");
    let (pilot_spp, mean_spp) = (pilot.max_spp.unwrap(), image.max_spp.unwrap());
    assert_eq!(output.adaptive_skipped, None, "{name} at {spp} spp");
    assert_eq!(
        (output.pilot_spp, output.spp),
        (pilot_spp, spp),
        "{name} at {spp} spp: the pilot's spp, and the render's with the pilot's"
    );
    assert!(pilot_spp >= MIN_PILOT_SPP, "{name} at {spp} spp");
    let counts = counts(output);
    let pixels = counts.len() as f64;
    let taken = output.film.total_samples();
    assert_eq!(taken, counts.iter().map(|&c| u64::from(c)).sum::<u64>());
    // Each count is round(share × mean) with shares averaging 1: the rounding moves the mean by
    // at most half a sample, and the shares' mean (rescaled and clamped to [MIN_SHARE,
    // MAX_SHARE] a few times) is 1 to a fraction of a percent.
    let mean = taken as f64 / pixels;
    let expected = f64::from(mean_spp);
    assert!(
        (mean - expected).abs() <= 0.5 + 0.01 * expected,
        "{name} at {spp} spp: {mean} samples per pixel taken, the allocation's mean is {expected} \
         ({pilot_spp} of {spp} went to the pilot)"
    );
    let (fewest, most) = (*counts.iter().min().unwrap(), *counts.iter().max().unwrap());
    let lowest = (MIN_SHARE * expected).round().max(1.0) as u32;
    let highest = (MAX_SHARE * expected).round() as u32;
    assert!(
        lowest <= fewest && most <= highest,
        "{name} at {spp} spp: counts {fewest}..={most} outside the shares' {lowest}..={highest}"
    );
    assert!(
        fewest < most,
        "{name} at {spp} spp: every pixel took {fewest} samples; not adaptive"
    );
}

/// The adaptive render's samples at `spp`, and its unbiasedness against the reference.
fn check(name: &str, scene: &RenderScene, adaptive_spp: u32, oracle_spp: u32) {
    let oracle = Replicates::render(
        scene,
        "reference",
        ORACLE_SEED..ORACLE_SEED + REPLICATES,
        oracle_spp,
        |seed| {
            RenderPlan::fixed_spp(
                common::reference(scene),
                SamplerKind::Independent,
                seed,
                oracle_spp,
            )
        },
    );
    let adaptive = Replicates::render_with(
        scene,
        "adaptive mis",
        ADAPTIVE_SEED..ADAPTIVE_SEED + REPLICATES,
        adaptive_spp,
        |seed| adaptive(scene, adaptive_spp, seed),
        |output| check_samples_taken(name, output, adaptive_spp),
    );
    if let Err(failure) = check_unbiased(name, &adaptive, &oracle, ALPHA) {
        panic!("{failure}");
    }
}

#[test]
fn adaptive_sampling_is_unbiased_with_a_point_light_and_rough_metal() {
    let scene = load_file(&scenes_dir().join("pointlight.xml"), &[], SIZE, SIZE);
    check("pointlight", &scene, 256, 2048);
}

/// The glass Cornell box, whose caustics adaptive sampling gives the most samples to, with its
/// ceiling light enlarged as in `unbiased.rs` so that the reference converges.
#[test]
fn adaptive_sampling_is_unbiased_with_caustics() {
    let scene = load_version(
        &scenes_dir().join("cbox-glass.xml"),
        &[(
            r#"<scale x="0.23" y="0.19" z="0.19"/>"#,
            r#"<scale x="0.9" y="0.9" z="0.19"/>"#,
        )],
        &[],
        SIZE,
        Some(5),
    );
    check("cbox-glass", &scene, 256, 1024);
}

#[test]
fn below_two_pilots_adaptive_sampling_is_skipped_and_said() {
    let scene = load_file(&scenes_dir().join("cbox-glass.xml"), &[], SIZE, SIZE);
    for spp in 1..2 * MIN_PILOT_SPP {
        let output = render_plan(
            &scene,
            &adaptive(&scene, spp, 5),
            "adaptive below the pilot",
        );
        let reason = output
            .adaptive_skipped
            .as_deref()
            .unwrap_or_else(|| panic!("{spp} spp: adaptive sampling not done and not said"));
        assert!(
            reason.contains(&format!("{spp} spp")),
            "{spp} spp: the reason names the budget: {reason}"
        );
        assert_eq!(output.pilot_spp, 0, "{spp} spp: no pilot");
        assert!(
            counts(&output).iter().all(|&c| c == spp),
            "{spp} spp: every pixel takes every sample"
        );
    }
}

#[test]
fn from_two_pilots_up_adaptive_sampling_takes_its_allocation() {
    let scene = load_file(&scenes_dir().join("cbox-glass.xml"), &[], SIZE, SIZE);
    for spp in [2 * MIN_PILOT_SPP, 5, 8, 16, 31, 32, 100] {
        let output = render_plan(&scene, &adaptive(&scene, spp, 5), "adaptive");
        check_samples_taken("cbox-glass", &output, spp);
        if spp < 32 {
            assert_eq!(
                output.pilot_spp, MIN_PILOT_SPP,
                "{spp} spp: the pilot takes the least it can"
            );
        }
    }
}
