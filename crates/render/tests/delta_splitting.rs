//! Delta splitting takes the lobe choice's variance out of the highlights of glass and plastic.
//! (That it keeps the image is `unbiased.rs`'s "delta splitting" configuration, against the
//! reference integrator on the glass box, plastic, blends and textured blends.)
//!
//! **Scene.** A smooth plastic ball and a glass pane facing the camera, lit only by a small,
//! bright sphere light beside the camera, whose reflections in both are smaller than a pixel:
//! highlights a path finds only by choosing the delta lobe (a few paths in a hundred on glass),
//! which light sampling and the light tracer cannot reach. Nothing else in the image is noisy
//! but the ball's diffuse base, lit by light samples.
//!
//! **Test.** [`REPLICATES`] independent renders with splitting and twice that many without
//! (seeds from [`SPLIT_SEED`] and [`PLAIN_SEED`]); the spread of each set's image means gives
//! the relative standard error of one render's image mean. Splitting passes when its error is
//! at most [`MAX_ERROR_RATIO`] of the first plain set's: measured 0.07–0.09 over four seed sets
//! (the variance 120–200× lower). **Power:** the same check of the second plain set against
//! the first, an input without the gain, must fail: measured 0.85–1.13 over the same four.
//! The bound lies far from both: the plain sets' heavy tails (one highlight sample in a
//! render can be most of its error) make their ratio spread far more than a normal sample's.

mod common;

use common::compare::Replicates;
use common::{load_xml, mis_power, scene_xml};
use integrators::PathSettings;
use render::plan::{RenderPlan, Transport};
use sampling::sampler::SamplerKind;

/// Independent renders of each set.
const REPLICATES: u32 = 64;
/// Samples per pixel of each render.
const SPP: u32 = 32;
/// Image edge, pixels.
const SIZE: u32 = 24;
/// First seed of the renders with splitting.
const SPLIT_SEED: u32 = 500;
/// First seed of the renders without (two sets, one after the other).
const PLAIN_SEED: u32 = 900;
/// The largest ratio of the image mean's relative standard error with splitting to without
/// that passes.
const MAX_ERROR_RATIO: f64 = 0.5;

/// The scene of the module documentation (the camera looks down −z from z = 4).
fn scene_body() -> &'static str {
    r#"
    <shape type="sphere">
        <point name="center" value="-0.5, 0, 0"/><float name="radius" value="0.45"/>
        <bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.2, 0.3, 0.5"/></bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.4"/><translate x="0.5"/></transform>
        <bsdf type="dielectric"/>
    </shape>
    <shape type="sphere">
        <point name="center" value="0.6, 0.2, 4"/><float name="radius" value="0.12"/>
        <emitter type="area"><rgb name="radiance" value="100"/></emitter>
    </shape>
"#
}

fn renders(splitting: bool, first_seed: u32) -> Replicates {
    let dir = tempfile::tempdir().expect("temporary directory");
    let xml = scene_xml(
        4,
        false,
        r#"<lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/>"#,
        40.0,
        common::NEAR_CLIP,
        scene_body(),
    );
    let scene = load_xml(dir.path(), "glass-and-plastic", &xml, SIZE);
    let settings = PathSettings {
        delta_splitting: splitting,
        ..mis_power(Some(4), false)
    };
    let label = if splitting { "delta splitting" } else { "mis" };
    Replicates::render(
        &scene,
        label,
        first_seed..first_seed + REPLICATES,
        SPP,
        |seed| RenderPlan::fixed_spp(Transport::Path(settings), SamplerKind::Sobol, seed, SPP),
    )
}

/// The ratio of `a`'s relative standard error of the image mean to `b`'s, printed.
fn error_ratio(a: &Replicates, b: &Replicates) -> f64 {
    let ratio = a.image_relative_error() / b.image_relative_error();
    println!(
        "figure: glass-and-plastic: relative standard error of the image mean, {} {:.3}%, {} \
         {:.3}%, ratio {ratio:.2}",
        a.label,
        100.0 * a.image_relative_error(),
        b.label,
        100.0 * b.image_relative_error()
    );
    ratio
}

#[test]
fn splitting_quiets_the_highlights() {
    let split = renders(true, SPLIT_SEED);
    let plain = renders(false, PLAIN_SEED);
    let other_plain = renders(false, PLAIN_SEED + REPLICATES);
    let ratio = error_ratio(&split, &plain);
    assert!(
        ratio <= MAX_ERROR_RATIO,
        "delta splitting left {ratio:.2} of the image mean's relative standard error (at most \
         {MAX_ERROR_RATIO}); replay: {}; {}",
        split.replay(),
        plain.replay()
    );
    let power = error_ratio(&other_plain, &plain);
    assert!(
        power > MAX_ERROR_RATIO,
        "the check passed renders without splitting ({power:.2}): it has no power; replay: {}; {}",
        other_plain.replay(),
        plain.replay()
    );
}
