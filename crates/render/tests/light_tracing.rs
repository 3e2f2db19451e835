//! Caustics by light tracing agree with the path tracer where the path tracer finds them easily:
//! a large light above a glass sphere, a glass slab, a mirror sphere and a rough-metal floor in
//! a diffuse room, so the caustics (on the floor and, through the mirror, on the walls) are
//! bright and the path tracer with MIS converges on them at a modest sample count. The light
//! tracer's share of each pixel has its own variance estimate in the film, so the z-test covers
//! both estimators.
//!
//! Per 2 × 2 block and channel a z-test (`common::z_test`) at a family-wise α = 0.01 with Šidák
//! correction over all block-channels; at least 99.75% must pass, as in `unbiased.rs`. Seeds
//! are fixed; a failure prints the worst block, sample counts and seeds. A test of the image
//! means catches a wrong overall scale of the splats (which the per-block test sees only as
//! many slightly high blocks).

mod common;

use common::{Target, film_mean, load_xml, mis_power, render, z_test};
use glam::UVec2;
use integrators::{LightTracing, PathSettings};
use render::plan::{Transport, plan_from_flags};
use sampling::sampler::SamplerKind;
use sampling::ztest::{sidak_alpha, two_sided_threshold};

const SIZE: u32 = 24;
const ALPHA: f64 = 0.01;
const REQUIRED_PASS_FRACTION: f64 = 0.9975;
const PATH_SEED: u32 = 1;
const LIGHT_TRACING_SEED: u32 = 2;
const PATH_SPP: u32 = 1024;
const LIGHT_TRACING_SPP: u32 = 512;

const SCENE: &str = r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="6"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="60"/>
        <transform name="to_world">
            <lookat origin="0, 0.3, 0.95" target="0, -0.6, -0.2" up="0, 1, 0"/>
        </transform>
        <film type="hdrfilm">
            <integer name="width" value="24"/>
            <integer name="height" value="24"/>
            <rfilter type="box"/>
        </film>
    </sensor>
    <shape type="cube">
        <boolean name="flip_normals" value="true"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.5, 0.4"/></bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world">
            <scale x="0.6" y="0.6" z="1"/>
            <rotate x="1" angle="90"/>
            <translate y="0.99"/>
        </transform>
        <emitter type="area"><rgb name="radiance" value="4, 4, 3"/></emitter>
    </shape>
    <shape type="sphere">
        <point name="center" value="-0.35, -0.55, -0.3"/>
        <float name="radius" value="0.3"/>
        <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf>
    </shape>
    <shape type="sphere">
        <point name="center" value="0.4, -0.6, -0.5"/>
        <float name="radius" value="0.25"/>
        <bsdf type="conductor"/>
    </shape>
    <shape type="cube">
        <transform name="to_world">
            <scale x="0.25" y="0.03" z="0.2"/>
            <translate x="0.3" y="-0.2" z="0.1"/>
        </transform>
        <bsdf type="dielectric"><float name="int_ior" value="1.33"/></bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world">
            <scale value="0.99"/>
            <rotate x="1" angle="-90"/>
            <translate y="-0.99"/>
        </transform>
        <bsdf type="roughconductor"><float name="alpha" value="0.3"/></bsdf>
    </shape>
</scene>
"#;

#[test]
fn light_traced_caustics_agree_with_the_path_tracer() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let scene = load_xml(dir.path(), "caustics", SCENE, SIZE);
    let mis = mis_power(common::max_depth(&scene), false);
    let path = render(
        &scene,
        Transport::Path(mis),
        SamplerKind::Independent,
        PATH_SPP,
        PATH_SEED,
        "path tracer",
    );
    let traced = render(
        &scene,
        Transport::Path(PathSettings {
            light_tracing: Some(LightTracing::SPARSE),
            ..mis
        }),
        SamplerKind::Independent,
        LIGHT_TRACING_SPP,
        LIGHT_TRACING_SEED,
        "light tracing",
    );
    assert_eq!(
        traced.light_paths(),
        u64::from(SIZE * SIZE * LIGHT_TRACING_SPP / LightTracing::SPARSE_SAMPLES_PER_PATH),
        "one light path per {} pixel samples",
        LightTracing::SPARSE_SAMPLES_PER_PATH
    );
    let outcome = z_test(&traced, Target::Film(&path), 2, ALPHA);
    let (mean_traced, mean_path) = (film_mean(&traced), film_mean(&path));
    let difference = (mean_traced - mean_path) / mean_path;
    println!(
        "figure: light tracing vs path tracing: {outcome}; image means {mean_traced:.5} and {mean_path:.5} ({:+.2}%)",
        100.0 * difference
    );
    let replay = format!(
        "light tracing {LIGHT_TRACING_SPP} spp seed {LIGHT_TRACING_SEED}, path tracing \
         {PATH_SPP} spp seed {PATH_SEED}, {SIZE}x{SIZE}"
    );
    assert!(
        outcome.pass_fraction >= REQUIRED_PASS_FRACTION,
        "{outcome} ({replay})"
    );
    assert!(
        difference.abs() < 0.01,
        "image means differ by {:.2}% ({replay})",
        100.0 * difference
    );
}

/// The same room through a thin lens (aperture radius 0.2, focused at 0.6, in front of the
/// caustics, which blur over several pixels): light paths connect to the camera through a
/// sampled point of the aperture, the path tracer's rays start from one. Per 2 × 2 block and
/// channel the z-test of `light_traced_caustics_agree_with_the_path_tracer`, and the image means
/// within 1%. Projecting connections as a pinhole would (ignoring the focus plane) fails it
/// (|z| 14).
#[test]
fn light_traced_caustics_agree_with_the_path_tracer_through_a_thin_lens() {
    let dir = tempfile::tempdir().expect("temporary directory");
    // The light faces up and emits down, from its flipped side: the path tracer meets its
    // emission against its geometric normal, and both sides must take the emitting one.
    let xml = SCENE
        .replace(
            r#"<sensor type="perspective">"#,
            r#"<sensor type="thinlens">
        <float name="aperture_radius" value="0.2"/>
        <float name="focus_distance" value="0.6"/>"#,
        )
        .replace(
            r#"<rotate x="1" angle="90"/>
            <translate y="0.99"/>
        </transform>"#,
            r#"<rotate x="1" angle="-90"/>
            <translate y="0.99"/>
        </transform>
        <boolean name="flip_normals" value="true"/>"#,
        );
    assert!(xml.contains("flip_normals\" value=\"true\"/>\n        <emitter"));
    let scene = load_xml(dir.path(), "thin-lens", &xml, SIZE);
    assert!(scene.camera.has_lens());
    let mis = mis_power(common::max_depth(&scene), false);
    let path = render(
        &scene,
        Transport::Path(mis),
        SamplerKind::Independent,
        PATH_SPP,
        PATH_SEED,
        "path tracer",
    );
    let traced = render(
        &scene,
        Transport::Path(PathSettings {
            light_tracing: Some(LightTracing::DENSE),
            ..mis
        }),
        SamplerKind::Independent,
        LIGHT_TRACING_SPP,
        LIGHT_TRACING_SEED,
        "light tracing",
    );
    assert_eq!(
        traced.light_paths(),
        u64::from(SIZE * SIZE * LIGHT_TRACING_SPP),
        "one light path per pixel sample"
    );
    let outcome = z_test(&traced, Target::Film(&path), 2, ALPHA);
    let (mean_traced, mean_path) = (film_mean(&traced), film_mean(&path));
    let difference = (mean_traced - mean_path) / mean_path;
    println!(
        "figure: thin lens: light tracing vs path tracing: {outcome}; image means {mean_traced:.5} and {mean_path:.5} ({:+.2}%)",
        100.0 * difference
    );
    let replay = format!(
        "thin lens: light tracing {LIGHT_TRACING_SPP} spp seed {LIGHT_TRACING_SEED}, path \
         tracing {PATH_SPP} spp seed {PATH_SEED}, {SIZE}x{SIZE}"
    );
    assert!(
        outcome.pass_fraction >= REQUIRED_PASS_FRACTION,
        "{outcome} ({replay})"
    );
    assert!(
        difference.abs() < 0.01,
        "image means differ by {:.2}% ({replay})",
        100.0 * difference
    );
}

/// Light-tracing renders per filter in the wide-filter test, and their samples per pixel.
const FILTER_RENDERS: u32 = 8;
const FILTER_RENDER_SPP: u32 = 64;
/// Block edge of the wide-filter test, in pixels (a few filter radii).
const FILTER_BLOCK: u32 = 4;
/// Least design effect of the wide filters' light tracing (see the test).
const MIN_DESIGN_EFFECT: f64 = 1.2;

/// The same room through Mitsuba's default gaussian filter, a tent of radius 1.5, and the
/// Mitchell–Netravali and Lanczos filters with their negative lobes: a light path splats into
/// every pixel whose camera samples reach its film position, weighted by the filter over its
/// integral (signed), and camera samples carry the sign of the filter where they land. Neighbouring pixels then share splats, so a block's variance is
/// more than the sum of the film's per-pixel estimates: it is scaled by a design effect pooled
/// over the image, the spread of the block means of independent light-tracing renders against
/// those estimates (as `cargo xtask crosscheck` does for Mitsuba's splatting). Then per 4 × 4
/// block and channel a z-test at a family-wise α = 0.01 with Šidák correction, and the image
/// means within 1%. The design effect itself must exceed 1.2 (measured 1.50 for the gaussian,
/// 1.98 for the tent, 1.33 for Mitchell): splatting into the containing pixel only, as for the
/// box filter, leaves neighbours uncorrelated and gives 1.00, which the block test at this size
/// cannot tell from the filtered image. Lanczos' negative lobes correlate neighbours negatively
/// as much as its central lobe does positively (1.04), so for it only the agreement is tested.
#[test]
fn light_traced_caustics_agree_with_the_path_tracer_through_wide_filters() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let filters = [
        ("gaussian", r#"<rfilter type="gaussian"/>"#, true),
        (
            "tent",
            r#"<rfilter type="tent"><float name="radius" value="1.5"/></rfilter>"#,
            true,
        ),
        ("mitchell", r#"<rfilter type="mitchell"/>"#, true),
        ("lanczos", r#"<rfilter type="lanczos"/>"#, false),
    ];
    for (name, filter, positively_shared) in filters {
        let xml = SCENE.replace(r#"<rfilter type="box"/>"#, filter);
        let scene = load_xml(dir.path(), name, &xml, SIZE);
        let mis = mis_power(common::max_depth(&scene), false);
        let path = render(
            &scene,
            Transport::Path(mis),
            SamplerKind::Independent,
            PATH_SPP,
            PATH_SEED,
            "path tracer",
        );
        let traced: Vec<_> = (0..FILTER_RENDERS)
            .map(|k| {
                render(
                    &scene,
                    Transport::Path(PathSettings {
                        light_tracing: Some(LightTracing::SPARSE),
                        ..mis
                    }),
                    SamplerKind::Independent,
                    FILTER_RENDER_SPP,
                    LIGHT_TRACING_SEED + k,
                    "light tracing",
                )
            })
            .collect();
        let replay = format!(
            "{name} filter: light tracing {FILTER_RENDERS} renders of {FILTER_RENDER_SPP} spp,              seeds {LIGHT_TRACING_SEED}..; path tracing {PATH_SPP} spp seed {PATH_SEED}, {SIZE}x{SIZE}"
        );
        let blocks = block_statistics(&path, &traced);
        let (spread, estimated) = blocks.iter().fold((0.0, 0.0), |(s, e), b| {
            (s + b.traced_spread, e + b.traced_estimate)
        });
        let design_effect = (spread / estimated).max(1.0);
        let tests = blocks.len();
        let threshold = two_sided_threshold(sidak_alpha(ALPHA, tests));
        let (worst, worst_at) = blocks
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let rounding = 1e-5 * b.path_mean.abs();
                let variance =
                    design_effect * b.traced_estimate + b.path_variance + rounding * rounding;
                (
                    (b.traced_mean - b.path_mean).abs() / variance.sqrt().max(1e-30),
                    i,
                )
            })
            .fold((0.0_f64, 0), |acc, z| if z.0 > acc.0 { z } else { acc });
        let failed = blocks
            .iter()
            .filter(|b| {
                let rounding = 1e-5 * b.path_mean.abs();
                let variance =
                    design_effect * b.traced_estimate + b.path_variance + rounding * rounding;
                (b.traced_mean - b.path_mean).abs() > threshold * variance.sqrt()
            })
            .count();
        let traced_mean = traced.iter().map(film_mean).sum::<f64>() / f64::from(FILTER_RENDERS);
        let path_mean = film_mean(&path);
        let difference = (traced_mean - path_mean) / path_mean;
        println!(
            "figure: {name} filter: design effect {design_effect:.2}, {failed} of {tests} block-channels beyond |z| {threshold:.2}, worst |z| {worst:.2} (block-channel {worst_at}); image means {traced_mean:.5} and {path_mean:.5} ({:+.2}%)",
            100.0 * difference
        );
        assert!(
            (tests - failed) as f64 / tests as f64 >= REQUIRED_PASS_FRACTION,
            "{failed} of {tests} block-channels differ, worst |z| {worst:.2} at block-channel {worst_at} ({replay})"
        );
        assert!(
            difference.abs() < 0.01,
            "image means differ by {:.2}% ({replay})",
            100.0 * difference
        );
        assert!(
            !positively_shared || spread / estimated > MIN_DESIGN_EFFECT,
            "design effect {:.2}: light paths' splats are not shared by neighbouring pixels \
             ({replay})",
            spread / estimated
        );
    }
}

/// One block-channel of the wide-filter test.
struct BlockStatistics {
    path_mean: f64,
    /// The path tracer's variance of the block mean, from its independent pixels.
    path_variance: f64,
    /// The mean over the light-tracing renders of their block means.
    traced_mean: f64,
    /// The variance of `traced_mean` from the renders' spread (correlations included).
    traced_spread: f64,
    /// The variance of `traced_mean` from the films' per-pixel estimates (as if independent).
    traced_estimate: f64,
}

/// Per [`FILTER_BLOCK`]² block and channel, block (row-major) then channel order.
fn block_statistics(
    path: &render::film::Film,
    traced: &[render::film::Film],
) -> Vec<BlockStatistics> {
    let pixels_per_block = f64::from(FILTER_BLOCK * FILTER_BLOCK);
    let block_sum = |film: &render::film::Film, origin: UVec2, c: usize, variance: bool| {
        let mut sum = 0.0;
        for dy in 0..FILTER_BLOCK {
            for dx in 0..FILTER_BLOCK {
                let pixel = origin + UVec2::new(dx, dy);
                let value = if variance {
                    film.pixel_variance(pixel)[c]
                } else {
                    film.pixel_value(pixel)[c]
                };
                sum += f64::from(value);
            }
        }
        sum
    };
    let renders = traced.len() as f64;
    let mut out = Vec::new();
    for by in 0..SIZE / FILTER_BLOCK {
        for bx in 0..SIZE / FILTER_BLOCK {
            let origin = UVec2::new(bx, by) * FILTER_BLOCK;
            for c in 0..3 {
                let means: Vec<f64> = traced
                    .iter()
                    .map(|f| block_sum(f, origin, c, false) / pixels_per_block)
                    .collect();
                let traced_mean = means.iter().sum::<f64>() / renders;
                let spread =
                    means.iter().map(|m| (m - traced_mean).powi(2)).sum::<f64>() / (renders - 1.0);
                let estimate = traced
                    .iter()
                    .map(|f| block_sum(f, origin, c, true))
                    .sum::<f64>()
                    / renders
                    / (pixels_per_block * pixels_per_block);
                out.push(BlockStatistics {
                    path_mean: block_sum(path, origin, c, false) / pixels_per_block,
                    path_variance: block_sum(path, origin, c, true)
                        / (pixels_per_block * pixels_per_block),
                    traced_mean,
                    traced_spread: spread / renders,
                    traced_estimate: estimate / renders,
                });
            }
        }
    }
    out
}

#[test]
fn auto_traces_caustics_where_they_apply() {
    let load = |name: &str| {
        scene::load(&common::scenes_dir().join(name), &[]).unwrap_or_else(|e| panic!("{e}"))
    };
    let traced = |scene: &scene::RenderScene, flags: &[&str]| match plan_from_flags(scene, flags)
        .expect("a plan")
        .transport
    {
        Transport::Path(settings) => settings.light_tracing.is_some(),
        Transport::Reference(_) => false,
    };
    let glass = load("cbox-glass.xml");
    assert!(traced(&glass, &[]), "auto on glass");
    assert!(traced(&glass, &["--state", "s.state"]), "auto, saved");
    assert!(!traced(&glass, &["--integrator", "mis"]), "mis");
    assert!(traced(&glass, &["--integrator", "mis", "--light-tracing"]));
    assert!(
        !traced(&load("cbox.xml"), &[]),
        "no delta BSDF: nothing to trace"
    );
    // An orthographic camera sees each point along one direction only: nothing connects to it.
    let path = common::scenes_dir().join("cbox-glass.xml");
    let text = std::fs::read_to_string(&path).expect("readable");
    let sensor = text
        .find("<sensor type=\"perspective\">")
        .expect("a perspective sensor");
    let fov_end = text[sensor..].find("/>").expect("its fov") + sensor + 2;
    let orthographic = format!(
        "{}<sensor type=\"orthographic\">{}",
        &text[..sensor],
        &text[fov_end..]
    );
    let desc = scene::parse_bytes(orthographic.as_bytes(), &path, &[]).expect("parses");
    let orthographic = scene::build(desc).expect("builds");
    assert!(!orthographic.camera.connects());
    assert!(
        !traced(&orthographic, &[]),
        "auto with an orthographic camera"
    );
    assert!(!traced(&orthographic, &["--light-tracing"]));
}
