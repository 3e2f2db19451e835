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
use integrators::PathSettings;
use render::technique::{Transport, plan_from_flags};
use sampling::sampler::SamplerKind;

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
            light_tracing: true,
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

#[test]
fn auto_traces_caustics_where_they_apply_unless_the_render_is_saved() {
    let load = |name: &str| {
        scene::load(&common::scenes_dir().join(name), &[]).unwrap_or_else(|e| panic!("{e}"))
    };
    let traced = |scene: &scene::RenderScene, flags: &[&str]| match plan_from_flags(scene, flags)
        .expect("a plan")
        .transport
    {
        Transport::Path(settings) => settings.light_tracing,
        Transport::Reference(_) => false,
    };
    let glass = load("cbox-glass.xml");
    assert!(traced(&glass, &[]), "auto on glass");
    assert!(!traced(&glass, &["--state", "s.state"]), "auto, saved");
    assert!(!traced(&glass, &["--integrator", "mis"]), "mis");
    assert!(traced(&glass, &["--integrator", "mis", "--light-tracing"]));
    assert!(
        !traced(&load("cbox.xml"), &[]),
        "no delta BSDF: nothing to trace"
    );
}
