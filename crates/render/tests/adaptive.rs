//! Adaptive sampling keeps the image unbiased: with the pilot's samples left out, each pixel's
//! sample count is independent of the samples averaged, so an adaptive render must agree with
//! a plain MIS render (itself checked against the reference integrator in `unbiased.rs`).
//!
//! Per 2 × 2 block and channel a z-test (`common::z_test`) at a family-wise α = 0.01 with Šidák
//! correction over all block-channels; at least 99.75% must pass, as in `unbiased.rs`. Seeds are
//! fixed; a failure prints the scene, worst block, sample counts and seeds.

mod common;

use common::{Target, load_file, mis_power, render, render_plan, scenes_dir, z_test};
use render::technique::{RenderPlan, Transport};
use sampling::sampler::SamplerKind;

const SIZE: u32 = 24;
const ALPHA: f64 = 0.01;
const REQUIRED_PASS_FRACTION: f64 = 0.9975;
const ORACLE_SEED: u32 = 1;
const ADAPTIVE_SEED: u32 = 3;

fn check(name: &str, adaptive_spp: u32, oracle_spp: u32) {
    let scene = load_file(&scenes_dir().join(name), &[], SIZE, SIZE);
    let settings = mis_power(
        common::max_depth(&scene),
        scene.desc.integrator.hide_emitters,
    );
    let oracle = render(
        &scene,
        Transport::Path(settings),
        SamplerKind::Independent,
        oracle_spp,
        ORACLE_SEED,
        &format!("{name} / mis"),
    );
    let plan = RenderPlan {
        adaptive: true,
        ..RenderPlan::fixed_spp(
            Transport::Path(settings),
            SamplerKind::Independent,
            ADAPTIVE_SEED,
            adaptive_spp,
        )
    };
    let output = render_plan(&scene, &plan, &format!("{name} / adaptive"));
    assert_eq!(output.spp, adaptive_spp, "the pilot counts in the budget");
    assert!(output.pilot_spp > 0, "a pilot was rendered");
    let counts: Vec<u32> = output.film.pixels().iter().map(|p| p.count).collect();
    let (fewest, most) = (
        counts.iter().min().copied().unwrap_or(0),
        counts.iter().max().copied().unwrap_or(0),
    );
    assert!(
        most > 2 * fewest,
        "{name}: sample counts {fewest}..{most} are not adaptive"
    );
    let outcome = z_test(&output.film, Target::Film(&oracle), 2, ALPHA);
    println!("figure: {name} / adaptive (pixels {fewest}..{most} samples) vs mis: {outcome}");
    assert!(
        outcome.pass_fraction >= REQUIRED_PASS_FRACTION,
        "{name}: {outcome} (adaptive {adaptive_spp} spp seed {ADAPTIVE_SEED}, mis {oracle_spp} \
         spp seed {ORACLE_SEED}, {SIZE}x{SIZE})"
    );
}

#[test]
fn adaptive_sampling_is_unbiased_with_caustics() {
    check("cbox-glass.xml", 512, 2048);
}

#[test]
fn adaptive_sampling_is_unbiased_with_a_point_light_and_rough_metal() {
    check("pointlight.xml", 512, 2048);
}
