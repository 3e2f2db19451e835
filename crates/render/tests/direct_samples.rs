//! Mitsuba's `direct` integrator with `emitter_samples` and `bsdf_samples`: with at least one of
//! each, any counts converge to the path tracer's image at depth 2 (the counts change only the
//! noise: each sample is divided by its count, delta lights' included); zero of a kind leaves out
//! what only that kind reaches, delta lights without light samples, what a mirror or glass shows
//! without BSDF samples, in the path tracer and in the reference integrator alike.
//!
//! The z-tests compare blocks of 4 × 4 pixels per channel at a family-wise α = 0.01 with Šidák
//! correction over the block-channels, every one of which must pass; independent samples with
//! fixed seeds; a failure prints the configuration, the worst block, the spp and the seeds.

mod common;

use common::{Target, film_mean, load_xml, mis_power, render, render_plan, z_test};
use integrators::reference::ReferenceSettings;
use integrators::{DirectSamples, Mis, PathSettings};
use render::film::Film;
use render::plan::{Transport, plan_from_flags};
use sampling::sampler::SamplerKind;
use scene::RenderScene;

const SIZE: u32 = 24;
const BLOCK: u32 = 4;
const ALPHA: f64 = 0.01;
const ORACLE_SPP: u32 = 512;
const ORACLE_SEED: u32 = 1;
const SPP: u32 = 128;
const SEED: u32 = 2;

/// A scene with `integrator` lit by a constant sky, an area light and (with `point_light`) a
/// point light, with a mirror and a glass sphere (or, with `black_spheres`, black diffuse ones in
/// their place) on a diffuse floor before a twosided wall.
fn scene(integrator: &str, point_light: bool, black_spheres: bool) -> String {
    let point = if point_light {
        r#"<emitter type="point"><point name="position" value="-1, 2, 1"/><rgb name="intensity" value="5"/></emitter>"#
    } else {
        ""
    };
    let (mirror, glass) = if black_spheres {
        let black = r#"<bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>"#;
        (black, black)
    } else {
        (
            r#"<bsdf type="conductor"/>"#,
            r#"<bsdf type="dielectric"/>"#,
        )
    };
    format!(
        r#"<scene version="3.0.0">
    {integrator}
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, 1, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><rfilter type="box"/></film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="0.3"/></emitter>
    {point}
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate x="1" y="1.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="8"/></emitter>
    </shape>
    <shape type="sphere"><point name="center" value="-0.7, -0.3, 0"/><float name="radius" value="0.5"/>{mirror}</shape>
    <shape type="sphere"><point name="center" value="0.7, -0.3, 0.3"/><float name="radius" value="0.5"/>{glass}</shape>
    <shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/><translate y="-0.8"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.4, 0.3"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="3"/><translate z="-1.5"/></transform>
        <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.5, 0.6"/></bsdf></bsdf></shape>
</scene>
"#
    )
}

/// The `direct` integrator element with the given counts.
fn direct(emitter_samples: u32, bsdf_samples: u32) -> String {
    format!(
        r#"<integrator type="direct"><integer name="emitter_samples" value="{emitter_samples}"/><integer name="bsdf_samples" value="{bsdf_samples}"/></integrator>"#
    )
}

/// The path integrator at depth 2: direct light by the walk, no counts.
const PATH_DEPTH_2: &str =
    r#"<integrator type="path"><integer name="max_depth" value="2"/></integrator>"#;

/// The walk with MIS at depth 2 on `scene`, at the oracle's samples and seed.
fn oracle(scene: &RenderScene) -> Film {
    render(
        scene,
        Transport::Path(mis_power(Some(2), false)),
        SamplerKind::Independent,
        ORACLE_SPP,
        ORACLE_SEED,
        "oracle: path, depth 2, mis power",
    )
}

/// Renders `scene` by `transport` at [`SPP`] and z-tests it against `expected`.
fn assert_agrees(scene: &RenderScene, transport: Transport, expected: &Film, label: &str) {
    let replay = format!(
        "{label}: {SPP} spp seed {SEED} against the oracle's {ORACLE_SPP} spp seed {ORACLE_SEED}, \
         {SIZE}x{SIZE}"
    );
    let film = render(
        scene,
        transport,
        SamplerKind::Independent,
        SPP,
        SEED,
        &replay,
    );
    assert_film_agrees(&film, expected, &replay);
}

/// Every block-channel of `film` passes the z-test against `expected`; `replay` says how to
/// render it again.
fn assert_film_agrees(film: &Film, expected: &Film, replay: &str) {
    let test = z_test(film, Target::Film(expected), BLOCK, ALPHA);
    assert!(
        test.pass_fraction == 1.0,
        "{replay}: {:.2}% of block-channels pass; worst |z| {:.2} > {:.2} at block {} channel {}",
        100.0 * test.pass_fraction,
        test.worst_z,
        test.threshold,
        test.worst_block,
        test.worst_channel
    );
}

/// The path settings for counts `(light, bsdf)` with the given MIS mode.
fn counted(light: u32, bsdf: u32, mis: Mis) -> PathSettings {
    PathSettings {
        mis,
        direct_samples: Some(DirectSamples { light, bsdf }),
        ..mis_power(Some(2), false)
    }
}

#[test]
fn sample_counts_change_only_the_noise() {
    let dir = tempfile::tempdir().unwrap();
    let walk = load_xml(dir.path(), "walk", &scene(PATH_DEPTH_2, true, false), SIZE);
    let expected = oracle(&walk);
    let counts = load_xml(
        dir.path(),
        "counts",
        &scene(&direct(3, 2), true, false),
        SIZE,
    );

    // What `strata render` does with the file: its counts, and no light tracer at depth 2.
    let plan = plan_from_flags(&counts, &["--spp", &SPP.to_string()]).expect("a plan");
    let Transport::Path(settings) = plan.transport else {
        panic!("auto plans the path tracer, got {:?}", plan.transport);
    };
    assert_eq!(
        settings.direct_samples,
        Some(DirectSamples { light: 3, bsdf: 2 })
    );
    assert!(settings.light_tracing.is_none(), "a caustic needs depth 3");
    let replay = format!(
        "auto with 3 light and 2 BSDF samples, {SPP} spp seed {} against the oracle's \
         {ORACLE_SPP} spp seed {ORACLE_SEED}, {SIZE}x{SIZE}",
        plan.seed
    );
    let planned = render_plan(&counts, &plan, &replay);
    assert_film_agrees(&planned.film, &expected, &replay);

    for (light, bsdf, mis) in [
        (3, 2, Mis::Power),
        (1, 4, Mis::Balance),
        (4, 1, Mis::Off),
        (1, 1, Mis::Power),
    ] {
        let label = format!("{light} light and {bsdf} BSDF samples, {mis:?}");
        assert_agrees(
            &counts,
            Transport::Path(counted(light, bsdf, mis)),
            &expected,
            &label,
        );
    }
}

#[test]
fn no_light_samples_leave_out_the_point_light() {
    let dir = tempfile::tempdir().unwrap();
    let unlit = load_xml(
        dir.path(),
        "unlit",
        &scene(PATH_DEPTH_2, false, false),
        SIZE,
    );
    let expected = oracle(&unlit);
    let counts = load_xml(dir.path(), "bsdf", &scene(&direct(0, 3), true, false), SIZE);
    assert_agrees(
        &counts,
        Transport::Path(counted(0, 3, Mis::Power)),
        &expected,
        "0 light and 3 BSDF samples",
    );
}

#[test]
fn no_bsdf_samples_leave_out_what_mirror_and_glass_show() {
    let dir = tempfile::tempdir().unwrap();
    let black = load_xml(dir.path(), "black", &scene(PATH_DEPTH_2, true, true), SIZE);
    let expected = oracle(&black);
    let counts = load_xml(
        dir.path(),
        "light",
        &scene(&direct(2, 0), true, false),
        SIZE,
    );
    for mis in [Mis::Power, Mis::Off] {
        assert_agrees(
            &counts,
            Transport::Path(counted(2, 0, mis)),
            &expected,
            &format!("2 light and 0 BSDF samples, {mis:?}"),
        );
    }
}

/// The reference integrator takes no light or BSDF samples, but leaves out what zero counts
/// leave out: a point light alone lights nothing without light samples, and a mirror that
/// shows the only area light shows nothing without BSDF samples.
#[test]
fn the_reference_leaves_out_what_zero_counts_leave_out() {
    let dir = tempfile::tempdir().unwrap();
    let camera = r#"<sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 1, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><rfilter type="box"/></film>
    </sensor>"#;
    let floor = |bsdf: &str| {
        format!(
            r#"<shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/></transform>{bsdf}</shape>"#
        )
    };
    let point_lit = |counts: &str| {
        format!(
            r#"<scene version="3.0.0">{counts}{camera}
    <emitter type="point"><point name="position" value="0, 2, 0"/><rgb name="intensity" value="5"/></emitter>
    {}</scene>"#,
            floor(r#"<bsdf type="diffuse"/>"#)
        )
    };
    // The light faces down, above the camera's view: only the mirror floor shows it.
    let mirrored = |counts: &str| {
        format!(
            r#"<scene version="3.0.0">{counts}{camera}
    <shape type="rectangle">
        <transform name="to_world"><scale value="3"/><rotate x="1" angle="90"/><translate y="4" z="-6"/></transform>
        <emitter type="area"><rgb name="radiance" value="4"/></emitter>
    </shape>
    {}</scene>"#,
            floor(r#"<bsdf type="conductor"/>"#)
        )
    };
    for (name, xml, (light, bsdf)) in [
        ("point", point_lit(&direct(0, 1)), (0, 1)),
        ("mirror", mirrored(&direct(1, 0)), (1, 0)),
    ] {
        let scene = load_xml(dir.path(), name, &xml, SIZE);
        let reference = |direct_samples| {
            Transport::Reference(ReferenceSettings {
                max_depth: Some(2),
                hide_emitters: false,
                direct_samples,
                skip_null_vertices: false,
            })
        };
        let counts = Some(DirectSamples { light, bsdf });
        let replay =
            format!("{name}, reference, {light} light and {bsdf} BSDF samples, 16 spp seed {SEED}");
        let left_out = render(
            &scene,
            reference(counts),
            SamplerKind::Independent,
            16,
            SEED,
            &replay,
        );
        assert_eq!(
            film_mean(&left_out),
            0.0,
            "{replay}: the image should be black"
        );
        let all = render(
            &scene,
            reference(None),
            SamplerKind::Independent,
            16,
            SEED,
            &replay,
        );
        assert!(
            film_mean(&all) > 0.0,
            "{replay}: without counts the light should show"
        );
        let path = render(
            &scene,
            Transport::Path(counted(light, bsdf, Mis::Power)),
            SamplerKind::Independent,
            16,
            SEED,
            &replay,
        );
        assert_eq!(
            film_mean(&path),
            0.0,
            "{replay}: the path tracer's image should be black"
        );
    }
}
