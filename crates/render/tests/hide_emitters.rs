//! `hide_emitters` as Mitsuba 3 has it: camera rays pass through area emitters and show what lies
//! behind them.
//!
//! The scene is a diffuse wall lit by a point light between it and the rest, seen through one or
//! two one-sided area emitters that face the camera (their backs face the wall, so they light
//! nothing the camera sees) and have no BSDF (Mitsuba gives them a black one). With `max_depth`
//! 2 the reference integrator's every estimate is the point light's direct light at the wall, the
//! same with the emitters as without them, so its renders with and without them draw the same
//! sampler numbers and differ only by the rounding of the camera rays restarted behind each
//! emitter. An integrator that stopped at a hidden emitter would show its black BSDF instead.

mod common;

use common::{NEAR_CLIP, Target, load_xml, mis_power, render, scene_xml, z_test};
use glam::{UVec2, Vec3};
use integrators::reference::ReferenceSettings;
use render::film::Film;
use render::plan::Transport;
use sampling::sampler::SamplerKind;
use scene::RenderScene;

const SIZE: u32 = 16;
const SPP: u32 = 32;
const SEED: u32 = 7;

/// The wall and its point light, with `emitters` camera-facing emitting rectangles in front,
/// `hide_emitters` as given.
fn scene(emitters: usize, hide_emitters: bool) -> String {
    let rectangles: String = (0..emitters)
        .map(|i| {
            let z = 1.0 + 0.5 * i as f32;
            format!(
                r#"    <shape type="rectangle">
        <transform name="to_world"><scale value="0.6"/><translate z="{z}"/></transform>
        <emitter type="area"><rgb name="radiance" value="5"/></emitter>
    </shape>
"#
            )
        })
        .collect();
    let body = format!(
        r#"    <emitter type="point"><point name="position" value="0.5, 2, 0.5"/><rgb name="intensity" value="20"/></emitter>
    <shape type="rectangle">
        <transform name="to_world"><scale value="3"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>
    </shape>
{rectangles}"#
    );
    let camera = r#"<lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/>"#;
    scene_xml(2, hide_emitters, camera, 30.0, NEAR_CLIP, &body)
}

/// `scene` rendered by `transport` with independent samples at [`SPP`] and [`SEED`].
fn render_at(scene: &RenderScene, transport: Transport, replay: &str) -> Film {
    render(
        scene,
        transport,
        SamplerKind::Independent,
        SPP,
        SEED,
        replay,
    )
}

/// The largest relative difference between the two films' pixels, and where it is.
fn largest_difference(a: &Film, b: &Film) -> (f32, UVec2) {
    let mut worst = (0.0, UVec2::ZERO);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let pixel = UVec2::new(x, y);
            let (va, vb) = (a.pixel_value(pixel), b.pixel_value(pixel));
            let relative = ((va - vb).abs() / vb.abs().max(Vec3::splat(1e-6))).max_element();
            if relative > worst.0 {
                worst = (relative, pixel);
            }
        }
    }
    worst
}

#[test]
fn hidden_emitters_show_what_lies_behind_them() {
    let dir = tempfile::tempdir().unwrap();
    let bare = load_xml(dir.path(), "bare", &scene(0, true), SIZE);
    let reference = |hide_emitters| {
        Transport::Reference(ReferenceSettings {
            max_depth: Some(2),
            hide_emitters,
            direct_samples: None,
            skip_null_vertices: false,
        })
    };
    let expected = render_at(&bare, reference(true), "reference, no emitters");
    for emitters in [1, 2] {
        let hidden = load_xml(dir.path(), "hidden", &scene(emitters, true), SIZE);
        let replay = format!("{emitters} emitter(s), {SPP} spp, seed {SEED}");

        // The reference integrator finds the same wall points with the same numbers.
        let film = render_at(&hidden, reference(true), &replay);
        let (difference, pixel) = largest_difference(&film, &expected);
        assert!(
            difference < 1e-4,
            "reference, {replay}: pixel {pixel} differs by {difference} from the scene without emitters"
        );

        // The path tracer also chooses among the emitters for next event estimation (they face
        // away from the wall and give nothing), so its image is noisy: a z-test per 4 × 4 block and
        // channel against the exact image, family-wise α = 0.01 with Šidák correction.
        let film = render_at(&hidden, Transport::Path(mis_power(Some(2), true)), &replay);
        let test = z_test(&film, Target::Film(&expected), 4, 0.01);
        assert_eq!(test.pass_fraction, 1.0, "mis, {replay}: {test}");

        // The emitters are in view: shown, the centre pixel is their radiance.
        let shown = load_xml(dir.path(), "shown", &scene(emitters, false), SIZE);
        let centre =
            render_at(&shown, reference(false), &replay).pixel_value(UVec2::splat(SIZE / 2));
        assert!(
            (centre - Vec3::splat(5.0)).abs().max_element() < 1e-5,
            "{replay}: the emitter shown gives {centre} at the centre"
        );
    }
}
