//! The stiff and extreme suite: scenes at the edges of floating point and of the estimators,
//! each checked for NaN and infinite samples (every render helper asserts there are none), for
//! energy gain, and against an exact answer or a non-extreme twin.
//!
//! Statistical comparisons are per-block z-tests (`common::z_test`) at a family-wise α = 0.01
//! with Šidák correction over the blocks and channels of one image, requiring 99.75% of them to
//! pass; every failure message names the scene, configuration, spp and seed to replay it.
//! Scenes are written as Mitsuba 3 XML into a temporary folder, so each is also a scene file
//! one can render in Mitsuba.

mod common;

use common::{
    Configuration, NEAR_CLIP, Target, ZTest, configurations, film_mean, load_xml, mis_power,
    render, scene_xml, z_test, z_test_correlated,
};
use geometry::TriangleMesh;
use glam::{UVec2, Vec2, Vec3};
use integrators::RussianRoulette;
use render::film::Film;
use render::plan::Transport;
use sampling::sampler::SamplerKind;
use scene::RenderScene;
use std::path::Path;

const SIZE: u32 = 32;
const ALPHA: f64 = 0.01;
const REQUIRED_PASS_FRACTION: f64 = 0.9975;
/// A closed diffuse room, the cube [-1, 1]³ seen from inside, with a square light of edge
/// `light_edge` and `radiance` facing down from just under the ceiling, a diffuse sphere on the
/// floor and a camera near the front wall; `transform` (Mitsuba transform elements) is applied
/// after everything else to every shape, and to the camera's position (Mitsuba's cameras may not
/// scale).
fn room(light_edge: f32, radiance: f32, hide_emitters: bool, transform: &Transform) -> String {
    let transform_xml = transform.xml();
    let half = light_edge / 2.0;
    let body = format!(
        r#"    <shape type="cube">
        <boolean name="flip_normals" value="true"/>
        <transform name="to_world">{transform_xml}</transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.5, 0.4"/></bsdf>
    </shape>
    <shape type="sphere">
        <point name="center" value="0.3, -0.6, -0.3"/>
        <float name="radius" value="0.4"/>
        <transform name="to_world">{transform_xml}</transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.6, 0.3"/></bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world">
            <scale x="{half}" y="{half}" z="1"/>
            <rotate x="1" angle="90"/>
            <translate y="0.99"/>
            {transform_xml}
        </transform>
        <emitter type="area"><rgb name="radiance" value="{radiance}"/></emitter>
    </shape>"#
    );
    let (origin, target) = (
        transform.apply(Vec3::new(0.0, 0.0, 0.95)),
        transform.apply(Vec3::new(0.0, -0.1, -1.0)),
    );
    let camera = format!(
        r#"<lookat origin="{}, {}, {}" target="{}, {}, {}" up="0, 1, 0"/>"#,
        origin.x, origin.y, origin.z, target.x, target.y, target.z
    );
    // The near clip plane scales with the room.
    let near_clip = NEAR_CLIP * transform.scale;
    scene_xml(6, hide_emitters, &camera, 70.0, near_clip, &body)
}

/// A similarity transform of the whole room: a uniform scale, then a translation.
#[derive(Clone, Copy)]
struct Transform {
    scale: f32,
    translation: Vec3,
}

impl Transform {
    /// The identity.
    const NONE: Transform = Transform {
        scale: 1.0,
        translation: Vec3::ZERO,
    };

    /// As Mitsuba transform elements.
    fn xml(&self) -> String {
        let t = self.translation;
        format!(
            r#"<scale value="{}"/><translate x="{}" y="{}" z="{}"/>"#,
            self.scale, t.x, t.y, t.z
        )
    }

    /// Where it takes the point `p`.
    fn apply(&self, p: Vec3) -> Vec3 {
        p * self.scale + self.translation
    }
}

/// A configuration-free render: MIS with the power heuristic at the scene's depth, roulette on.
fn mis(scene: &RenderScene) -> Transport {
    Transport::Path(integrators::PathSettings {
        russian_roulette: Some(RussianRoulette { start_depth: 3 }),
        ..mis_power(
            common::max_depth(scene),
            scene.desc.integrator.hide_emitters,
        )
    })
}

/// Asserts a z-test passed, printing its figure.
fn assert_passes(outcome: ZTest, what: &str) {
    println!("figure: {what}: {outcome}");
    assert!(
        outcome.pass_fraction >= REQUIRED_PASS_FRACTION,
        "{what}: {outcome}"
    );
}

/// Every configuration (and the reference integrator) on `scene` against the exact image `exact`.
fn every_configuration_is_exact(scene: &RenderScene, name: &str, spp: u32, exact: Vec3) {
    let mut runs = vec![(
        "reference",
        common::reference(scene),
        SamplerKind::Independent,
        false,
    )];
    let base = mis_power(
        common::max_depth(scene),
        scene.desc.integrator.hide_emitters,
    );
    for Configuration {
        label,
        settings,
        sampler,
    } in configurations(base)
    {
        let correlated = settings.path_reuse.is_some();
        runs.push((label, Transport::Path(settings), sampler, correlated));
    }
    runs.push((
        "auto-like: mis + roulette",
        mis(scene),
        SamplerKind::Independent,
        false,
    ));
    let seed = 7;
    for (label, transport, sampler, correlated) in runs {
        let what = format!("{name} / {label} ({spp} spp, seed {seed})");
        let film = render(scene, transport, sampler, spp, seed, &what);
        let test = if correlated {
            z_test_correlated
        } else {
            z_test
        };
        assert_passes(test(&film, Target::Exact(&|_| exact), 2, ALPHA), &what);
    }
}

/// A constant white sky of radiance 1.
const WHITE_SKY: &str =
    r#"    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>"#;

/// A camera at distance 4 on +z looking at the origin.
const FRONT_CAMERA: &str = r#"<lookat origin="0.3, 0.5, 4" target="0, 0, 0" up="0, 1, 0"/>"#;

#[test]
fn albedo_one_sphere_in_a_white_sky_is_white_for_every_configuration() {
    // A convex white diffuse object under a uniform sky reflects exactly the sky: every pixel
    // is 1 whatever the depth, and roulette's survival max(throughput) stays 1.
    let dir = tempfile::tempdir().unwrap();
    let body = format!(
        r#"{WHITE_SKY}
    <shape type="sphere"><float name="radius" value="1"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="1"/></bsdf></shape>"#
    );
    let xml = scene_xml(-1, false, FRONT_CAMERA, 40.0, NEAR_CLIP, &body);
    let scene = load_xml(dir.path(), "white-sphere", &xml, SIZE);
    every_configuration_is_exact(&scene, "albedo-1 sphere", 64, Vec3::ONE);
}

#[test]
fn back_of_a_two_sided_surface_shows_its_back_bsdf_for_every_configuration() {
    // Mitsuba's twosided with two BSDFs: a black front and, behind it, a white diffuse (then a
    // perfect mirror) back. Seen from behind under a uniform white sky the flat back reflects
    // exactly the sky, so every pixel is 1; the front's BSDF on the back would make it black.
    let dir = tempfile::tempdir().unwrap();
    let camera = r#"<lookat origin="0.3, 0.5, -4" target="0, 0, 0" up="0, 1, 0"/>"#;
    for (name, back) in [
        (
            "diffuse",
            r#"<bsdf type="diffuse"><rgb name="reflectance" value="1"/></bsdf>"#,
        ),
        (
            "mirror",
            r#"<bsdf type="conductor"><string name="material" value="none"/></bsdf>"#,
        ),
    ] {
        let body = format!(
            r#"{WHITE_SKY}
    <shape type="rectangle">
        <transform name="to_world"><scale value="3"/></transform>
        <bsdf type="twosided">
            <bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>
            {back}
        </bsdf>
    </shape>"#
        );
        let xml = scene_xml(-1, false, camera, 40.0, NEAR_CLIP, &body);
        let scene = load_xml(dir.path(), &format!("twosided-{name}"), &xml, SIZE);
        every_configuration_is_exact(&scene, &format!("twosided {name} back"), 16, Vec3::ONE);
    }
}

/// The radiance of the emitting sphere inside which [`furnace`]'s camera sits.
const FURNACE_RADIANCE: Vec3 = Vec3::new(0.25, 0.5, 1.0);

/// The camera inside an emitting diffuse sphere of `reflectance`, at `max_depth`.
fn furnace(dir: &Path, name: &str, reflectance: f32, max_depth: i32) -> RenderScene {
    let body = format!(
        r#"    <shape type="sphere"><float name="radius" value="1"/>
        <boolean name="flip_normals" value="true"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="{reflectance}"/></bsdf>
        <emitter type="area"><rgb name="radiance" value="0.25, 0.5, 1"/></emitter></shape>"#
    );
    let camera = r#"<lookat origin="0.2, 0.1, 0" target="0, 0, -1" up="0, 1, 0"/>"#;
    let xml = scene_xml(max_depth, false, camera, 60.0, NEAR_CLIP, &body);
    load_xml(dir, name, &xml, SIZE)
}

#[test]
fn albedo_zero_furnace_shows_only_emission() {
    // Inside an emitting sphere of albedo 0 every pixel is exactly its radiance.
    let dir = tempfile::tempdir().unwrap();
    let scene = furnace(dir.path(), "black-furnace", 0.0, -1);
    every_configuration_is_exact(&scene, "albedo-0 furnace", 16, FURNACE_RADIANCE);
}

#[test]
fn grey_furnace_sums_the_bounces_for_every_configuration() {
    // Inside an emitting sphere of albedo ½ with `max_depth` 5, emission is found at each of the
    // five vertices, each bounce keeping half: every pixel is Le (1 + ½ + ¼ + ⅛ + 1/16). Every
    // first and second vertex is diffuse and sees every other, so path reuse shares all of them.
    let dir = tempfile::tempdir().unwrap();
    let scene = furnace(dir.path(), "grey-furnace", 0.5, 5);
    let bounces: f32 = (0..5).map(|k| 0.5_f32.powi(k)).sum();
    every_configuration_is_exact(&scene, "albedo-½ furnace", 64, FURNACE_RADIANCE * bounces);
}

/// A tilted glass slab with index of refraction `ior` in a white sky, seen from outside.
fn glass_slab(dir: &Path, ior: f32) -> RenderScene {
    let body = format!(
        r#"{WHITE_SKY}
    <shape type="cube">
        <transform name="to_world">
            <scale x="1" y="1" z="0.15"/>
            <rotate x="1" angle="35"/>
            <rotate y="1" angle="20"/>
        </transform>
        <bsdf type="dielectric"><float name="int_ior" value="{ior}"/>
            <float name="ext_ior" value="1"/></bsdf>
    </shape>"#
    );
    let xml = scene_xml(-1, false, FRONT_CAMERA, 40.0, NEAR_CLIP, &body);
    load_xml(dir, &format!("slab-{ior}"), &xml, SIZE)
}

#[test]
fn glass_slabs_are_invisible_in_a_white_sky() {
    // A lossless dielectric in a uniform sky returns exactly the sky along every path, however
    // often the path is totally internally reflected inside the slab (index 1.5 and 4) or how
    // close to 1 the index is (1.0001).
    let dir = tempfile::tempdir().unwrap();
    for ior in [1.5, 1.0001, 4.0] {
        let scene = glass_slab(dir.path(), ior);
        every_configuration_is_exact(&scene, &format!("glass slab, ior {ior}"), 32, Vec3::ONE);
    }
}

#[test]
fn radiance_1e6_scales_the_image_by_1e6() {
    // Emission enters no sampling decision with one light, so the same seed traces the same
    // paths and the image scales exactly (up to f32 rounding).
    let dir = tempfile::tempdir().unwrap();
    let base = load_xml(
        dir.path(),
        "room",
        &room(0.5, 4.0, false, &Transform::NONE),
        SIZE,
    );
    let bright = load_xml(
        dir.path(),
        "room-1e6",
        &room(0.5, 4e6, false, &Transform::NONE),
        SIZE,
    );
    let spp = 16;
    let a = render(&base, mis(&base), SamplerKind::Stratified, spp, 3, "room").to_image();
    let b = render(
        &bright,
        mis(&bright),
        SamplerKind::Stratified,
        spp,
        3,
        "room 1e6",
    )
    .to_image();
    let mut worst = 0.0_f32;
    for (x, y) in a.data.iter().zip(&b.data) {
        let relative = ((*y / 1e6 - *x).abs() / x.abs().max(Vec3::splat(1e-6))).max_element();
        worst = worst.max(relative);
    }
    println!("figure: radiance 1e6: largest relative difference from 1e6 × the image {worst:.2e}");
    assert!(
        worst < 1e-4,
        "radiance 1e6 ({spp} spp, seed 3): worst relative difference {worst}"
    );
}

#[test]
fn a_light_of_1e_6_of_the_room_area_lights_it_like_a_larger_one() {
    // The room's surface is 24; a light of edge 0.0049 has 2.4e-5 of the area, 1e-6 of it, and
    // 1e4 times the radiance of the 0.5-edge twin, so the same power. With emitters hidden the
    // images differ only by the twin's larger black patch on the ceiling and its softer
    // shadows: the image means agree within 3% (measured 0.5% when written), and in the tiny
    // light's own image light-only and MIS sampling agree block by block.
    let dir = tempfile::tempdir().unwrap();
    let edge = (24.0e-6_f32).sqrt();
    let radiance = 4.0 * 0.25 / (edge * edge);
    let twin = load_xml(
        dir.path(),
        "room",
        &room(0.5, 4.0, true, &Transform::NONE),
        SIZE,
    );
    let tiny = load_xml(
        dir.path(),
        "room-tiny",
        &room(edge, radiance, true, &Transform::NONE),
        SIZE,
    );
    let spp = 256;
    let tiny_mis = render(
        &tiny,
        mis(&tiny),
        SamplerKind::Independent,
        spp,
        5,
        "tiny light",
    );
    let twin_mis = render(&twin, mis(&twin), SamplerKind::Independent, spp, 6, "twin");
    let (m_tiny, m_twin) = (film_mean(&tiny_mis), film_mean(&twin_mis));
    let difference = (m_tiny - m_twin) / m_twin;
    println!(
        "figure: tiny light: image mean {m_tiny:.4}, twin {m_twin:.4} ({:+.2}%)",
        100.0 * difference
    );
    assert!(
        difference.abs() < 0.03,
        "tiny light mean {m_tiny}, twin {m_twin} ({spp} spp, seeds 5, 6)"
    );
    let light_only = integrators::PathSettings {
        mis: integrators::Mis::Off,
        ..mis_power(common::max_depth(&tiny), true)
    };
    let film = render(
        &tiny,
        Transport::Path(light_only),
        SamplerKind::Independent,
        spp,
        7,
        "tiny light, light-only",
    );
    assert_passes(
        z_test(&film, Target::Film(&tiny_mis), 2, ALPHA),
        &format!("tiny light: light-only (seed 7) vs MIS (seed 5), {spp} spp"),
    );
}

#[test]
fn translating_by_1e5_and_scaling_by_1e_3_and_1e3_change_nothing() {
    // Radiance does not depend on where the room is or on its size (a pinhole camera moved and
    // scaled with it sees the same picture), so each transformed room must match the original
    // within noise. Far from the origin f32 positions are spaced 0.008 apart: the ray offsets
    // must scale with the coordinates, and the room's geometry moves by that much.
    let dir = tempfile::tempdir().unwrap();
    let spp = 128;
    let base = load_xml(
        dir.path(),
        "room",
        &room(0.5, 4.0, false, &Transform::NONE),
        SIZE,
    );
    let reference = render(&base, mis(&base), SamplerKind::Independent, spp, 11, "room");
    for (name, transform) in [
        (
            "translated by 1e5",
            Transform {
                scale: 1.0,
                translation: Vec3::new(1e5, -1e5, 1e5),
            },
        ),
        (
            "scaled by 1e-3",
            Transform {
                scale: 1e-3,
                translation: Vec3::ZERO,
            },
        ),
        (
            "scaled by 1e3",
            Transform {
                scale: 1e3,
                translation: Vec3::ZERO,
            },
        ),
    ] {
        let scene = load_xml(
            dir.path(),
            &format!("room-moved-{}", transform.scale),
            &room(0.5, 4.0, false, &transform),
            SIZE,
        );
        let what = format!("room {name} (seed 12) vs room (seed 11), {spp} spp");
        let film = render(
            &scene,
            mis(&scene),
            SamplerKind::Independent,
            spp,
            12,
            &what,
        );
        assert_passes(z_test(&film, Target::Film(&reference), 2, ALPHA), &what);
    }
}

#[test]
fn a_plane_seen_at_grazing_angles_reflects_the_sky_exactly() {
    // A diffuse plane of albedo 0.5 that sees only a white sky has radiance 0.5 everywhere. The
    // camera, 1 cm above a plane 20 km wide, looks 5.1° down with a 10° field of view: its top
    // row meets the plane 0.1° from the horizon, its bottom row 6 cm away (beyond the camera's
    // 1 cm near clip plane, Mitsuba's default).
    let dir = tempfile::tempdir().unwrap();
    let body = format!(
        r#"{WHITE_SKY}
    <shape type="rectangle">
        <transform name="to_world"><scale value="1e4"/><rotate x="1" angle="-90"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>
    </shape>"#
    );
    let pitch = 5.1_f32.to_radians();
    let camera = format!(
        r#"<lookat origin="0, 1e-2, 0" target="0, {}, -1" up="0, 1, 0"/>"#,
        1e-2 - pitch.tan()
    );
    let xml = scene_xml(-1, false, &camera, 10.0, NEAR_CLIP, &body);
    let scene = load_xml(dir.path(), "grazing-plane", &xml, SIZE);
    every_configuration_is_exact(&scene, "grazing plane", 32, Vec3::splat(0.5));
}

/// [`TriangleMesh::icosphere`] with `subdivisions` as OBJ text, with its vertex normals.
fn icosphere_obj(subdivisions: u32) -> String {
    let mesh = TriangleMesh::icosphere(subdivisions);
    let normals = mesh
        .normals
        .as_ref()
        .expect("the icosphere has vertex normals");
    let mut obj = String::new();
    for (p, n) in mesh.positions.iter().zip(normals) {
        obj += &format!("v {} {} {}\nvn {} {} {}\n", p.x, p.y, p.z, n.x, n.y, n.z);
    }
    for [a, b, c] in &mesh.indices {
        obj += &format!("f {0}//{0} {1}//{1} {2}//{2}\n", a + 1, b + 1, c + 1);
    }
    obj
}

#[test]
fn a_smooth_normal_mesh_gains_no_energy_at_its_silhouette() {
    // A white icosphere with interpolated normals in a white sky: the analytic sphere's image is
    // exactly 1, and the mesh's may only be darker, where shading and geometric normals
    // disagree at grazing angles near the silhouette. No block may be significantly above 1 (a
    // one-sided z-test at the suite's level), and the image mean stays within 2% of 1.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("sphere.obj"), icosphere_obj(2)).unwrap();
    let body = format!(
        r#"{WHITE_SKY}
    <shape type="obj"><string name="filename" value="sphere.obj"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="1"/></bsdf></shape>"#
    );
    let xml = scene_xml(-1, false, FRONT_CAMERA, 40.0, NEAR_CLIP, &body);
    let scene = load_xml(dir.path(), "smooth-mesh", &xml, SIZE);
    let base = mis_power(None, false);
    for Configuration {
        label,
        settings,
        sampler,
    } in configurations(base)
    {
        let what = format!("smooth mesh / {label} (64 spp, seed 9)");
        let correlated = settings.path_reuse.is_some();
        let film = render(&scene, Transport::Path(settings), sampler, 64, 9, &what);
        let brightest = brightest_block_z(&film, Vec3::ONE, correlated);
        let mean = film_mean(&film);
        println!("figure: {what}: image mean {mean:.4}, largest block z above 1: {brightest:.2}");
        let limit = sampling::ztest::two_sided_threshold(sampling::ztest::sidak_alpha(
            ALPHA,
            (SIZE * SIZE / 4 * 3) as usize,
        ));
        assert!(
            brightest < limit,
            "{what}: a block is {brightest:.1} standard errors above 1"
        );
        assert!((mean - 1.0).abs() < 0.02, "{what}: image mean {mean}");
    }
}

/// The largest z = (block mean − `ceiling`) / standard error over 2 × 2 blocks and channels;
/// with `correlated` pixels (path reuse) the block's variance is bounded by (Σ √var)², as in
/// `common::z_test_correlated`.
fn brightest_block_z(film: &Film, ceiling: Vec3, correlated: bool) -> f64 {
    let mut worst = f64::MIN;
    for by in 0..film.height() / 2 {
        for bx in 0..film.width() / 2 {
            for c in 0..3 {
                let (mut excess, mut variance, mut deviation) = (0.0, 1e-24_f64, 0.0_f64);
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let pixel = film.pixel(UVec2::new(2 * bx + dx, 2 * by + dy));
                    excess += f64::from(pixel.mean()[c] - ceiling[c]);
                    let pixel_variance = f64::from(pixel.variance_of_mean()[c]);
                    if correlated {
                        deviation += pixel_variance.sqrt();
                    } else {
                        variance += pixel_variance;
                    }
                }
                variance += deviation * deviation;
                let rounding = 1e-5 * 4.0 * f64::from(ceiling[c]);
                worst = worst.max(excess / (variance + rounding * rounding).sqrt());
            }
        }
    }
    worst
}

/// A sphere of `bsdf` in the room's light, seen close up.
fn sphere_in_room(dir: &Path, name: &str, bsdf: &str) -> RenderScene {
    let xml = room(0.5, 4.0, false, &Transform::NONE).replace(
        r#"<bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.6, 0.3"/></bsdf>"#,
        bsdf,
    );
    load_xml(dir, name, &xml, SIZE)
}

/// GGX at α = 1e-4 reflects like the mirror with MIS and with BSDF sampling alone. (Light
/// sampling alone is not compared: it finds the 1e-4 lobe about once in 10⁷ samples, so its
/// image lacks the reflected light at any affordable count, which is what MIS is for.)
#[test]
fn ggx_of_roughness_1e_4_matches_the_mirror() {
    let dir = tempfile::tempdir().unwrap();
    let mirror = sphere_in_room(
        dir.path(),
        "mirror",
        r#"<bsdf type="conductor"><string name="material" value="none"/></bsdf>"#,
    );
    let rough = sphere_in_room(
        dir.path(),
        "ggx-1e-4",
        r#"<bsdf type="roughconductor"><string name="material" value="none"/>
            <string name="distribution" value="ggx"/><float name="alpha" value="1e-4"/></bsdf>"#,
    );
    let spp = 256;
    let reference = render(
        &mirror,
        mis(&mirror),
        SamplerKind::Independent,
        spp,
        21,
        "mirror",
    );
    for (label, settings) in [
        ("mis", mis_power(common::max_depth(&rough), false)),
        (
            "bsdf-only",
            integrators::PathSettings {
                sample_lights: false,
                mis: integrators::Mis::Off,
                ..mis_power(common::max_depth(&rough), false)
            },
        ),
    ] {
        let what = format!("GGX alpha 1e-4 / {label} (seed 23) vs mirror (seed 21), {spp} spp");
        let film = render(
            &rough,
            Transport::Path(settings),
            SamplerKind::Independent,
            spp,
            23,
            &what,
        );
        assert_passes(z_test(&film, Target::Film(&reference), 2, ALPHA), &what);
    }
}

#[test]
fn a_point_light_1e_4_above_a_plane_lights_it_as_the_inverse_square_law_says() {
    // A diffuse plane (albedo 0.5) under a point light of intensity 1 at height h = 1e-4 has
    // radiance (0.5 / π) h / r³ at distance r from the light. The camera looks straight down
    // from height 1; each pixel's exact value is that radiance averaged over the pixel (box
    // filter), integrated here on a 16 × 16 grid. Pixels within 3 of the spike are left out of
    // the comparison (the grid cannot integrate the spike) but must still be finite.
    let dir = tempfile::tempdir().unwrap();
    let h = 1e-4_f64;
    let body = r#"    <emitter type="point"><point name="position" value="0.013, 1e-4, 0.007"/>
        <rgb name="intensity" value="1"/></emitter>
    <shape type="rectangle">
        <transform name="to_world"><scale value="10"/><rotate x="1" angle="-90"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>
    </shape>"#;
    let camera = r#"<lookat origin="0, 1, 0" target="0, 0, 0" up="0, 0, -1"/>"#;
    let xml = scene_xml(2, false, camera, 30.0, NEAR_CLIP, body);
    let scene = load_xml(dir.path(), "point-light", &xml, SIZE);
    // Positions as the scene holds them: relative to the camera, at the origin.
    let light = match scene.desc.emitters[0] {
        scene::EmitterDesc::Point { position, .. } => position.as_dvec3(),
        _ => unreachable!("the scene's one emitter is the point light"),
    };
    let plane_y = light.y - h;
    let radiance = |film: Vec2| {
        let ray = scene.camera.generate_ray(film, Vec2::ZERO).ray;
        let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
        let p = o + d * ((plane_y - o.y) / d.y);
        let r = (p - light).length();
        0.5 / std::f64::consts::PI * h / (r * r * r)
    };
    let spike = {
        let mut best = (f64::MIN, UVec2::ZERO);
        for y in 0..SIZE {
            for x in 0..SIZE {
                let value = radiance(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
                if value > best.0 {
                    best = (value, UVec2::new(x, y));
                }
            }
        }
        best.1
    };
    // Stratified film positions: the only noise is the radiance's variation over each pixel.
    let spp = 256;
    let film = render(
        &scene,
        mis(&scene),
        SamplerKind::Stratified,
        spp,
        31,
        "point light",
    );
    let mut worst = (0.0_f64, UVec2::ZERO);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let pixel = UVec2::new(x, y);
            let mean = f64::from(film.pixel(pixel).mean().x);
            assert!(mean.is_finite(), "pixel {pixel}: {mean}");
            if (pixel.as_ivec2() - spike.as_ivec2()).abs().max_element() <= 3 {
                continue;
            }
            let mut exact = 0.0;
            for j in 0..16 {
                for i in 0..16 {
                    let offset = Vec2::new(i as f32 + 0.5, j as f32 + 0.5) / 16.0;
                    exact += radiance(pixel.as_vec2() + offset) / 256.0;
                }
            }
            let relative = (mean - exact).abs() / exact;
            if relative > worst.0 {
                worst = (relative, pixel);
            }
        }
    }
    println!(
        "figure: point light 1e-4 above a plane: largest relative error {:.2e} at pixel {} (spike at {spike})",
        worst.0, worst.1
    );
    assert!(
        worst.0 < 0.01,
        "pixel {}: relative error {} ({spp} spp, seed 31)",
        worst.1,
        worst.0
    );
}

#[test]
fn degenerate_and_duplicate_triangles_change_nothing() {
    // A quad floor as a mesh, once plain and once with zero-area triangles (a repeated vertex,
    // three collinear vertices) and a second copy of both its triangles: the same image.
    let dir = tempfile::tempdir().unwrap();
    let quad = "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 0 0\nv 0.5 0 0.5\n";
    std::fs::write(
        dir.path().join("plain.obj"),
        format!("{quad}f 1 4 3\nf 1 3 2\n"),
    )
    .unwrap();
    std::fs::write(
        dir.path().join("messy.obj"),
        format!("{quad}f 1 4 3\nf 1 3 2\nf 1 1 3\nf 1 5 3\nf 5 6 3\nf 1 4 3\nf 1 3 2\n"),
    )
    .unwrap();
    let scene_with = |mesh: &str| {
        let body = format!(
            r#"    <emitter type="constant"><rgb name="radiance" value="0.2"/></emitter>
    <shape type="obj"><string name="filename" value="{mesh}.obj"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.7"/></bsdf></shape>
    <shape type="sphere"><point name="center" value="0, 1, 0"/><float name="radius" value="0.2"/>
        <emitter type="area"><rgb name="radiance" value="20"/></emitter></shape>"#
        );
        let camera = r#"<lookat origin="0, 2, 2.5" target="0, 0, 0" up="0, 1, 0"/>"#;
        load_xml(
            dir.path(),
            mesh,
            &scene_xml(4, false, camera, 45.0, NEAR_CLIP, &body),
            SIZE,
        )
    };
    let (plain, messy) = (scene_with("plain"), scene_with("messy"));
    let spp = 128;
    let reference = render(
        &plain,
        mis(&plain),
        SamplerKind::Independent,
        spp,
        41,
        "plain",
    );
    let what =
        format!("degenerate and duplicate triangles (seed 42) vs plain (seed 41), {spp} spp");
    let film = render(
        &messy,
        mis(&messy),
        SamplerKind::Independent,
        spp,
        42,
        &what,
    );
    assert_passes(z_test(&film, Target::Film(&reference), 2, ALPHA), &what);
}
