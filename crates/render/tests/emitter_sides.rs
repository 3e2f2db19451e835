//! Which side of a smooth-shaded emitter the camera sees: Mitsuba 3's area emitters emit on the
//! side of the shading frame, so where a mesh's vertex normals tilt away from its geometric
//! normal, a grazing view from behind the triangle's plane can see it emit and a grazing view
//! from in front may not. Strata follows that for emission seen from the camera directly (or
//! through delta bounces), which no other strategy samples.
//!
//! The emitter is a square in the plane z = 0 (geometric normal +z) whose vertex normals all
//! lean towards +y, `normalize(0, 1, 0.2)`. A camera at (0, 5, -0.5) sees the square from
//! 5.7° behind its plane but in front of the shading normal; one at (0, -5, 0.5) from 5.7° in
//! front of the plane but behind the shading normal. Each image is the emitter alone, filling
//! the view, so its exact value is the radiance or zero in every pixel.

mod common;

use common::{NEAR_CLIP, Target, load_xml, mis_power, render, scene_xml, z_test};
use glam::{UVec2, Vec3};
use integrators::reference::ReferenceSettings;
use render::plan::Transport;
use sampling::sampler::SamplerKind;

const RADIANCE: f32 = 3.0;

/// The emitter alone, seen from (0, `camera_y`, `camera_z`) with a 1° field of view.
fn scene(camera_y: f32, camera_z: f32) -> String {
    let camera =
        format!(r#"<lookat origin="0, {camera_y}, {camera_z}" target="0, 0, 0" up="0, 0, 1"/>"#);
    let body = format!(
        r#"    <shape type="obj">
        <string name="filename" value="leaning.obj"/>
        <emitter type="area"><rgb name="radiance" value="{RADIANCE}"/></emitter>
    </shape>"#
    );
    scene_xml(1, false, &camera, 1.0, NEAR_CLIP, &body)
}

const OBJ: &str = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0 0.98058068 0.19611614\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n";

#[test]
fn smooth_emitters_seen_directly_emit_on_their_shading_side() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("leaning.obj"), OBJ).unwrap();
    for (camera, expected) in [((5.0, -0.5), RADIANCE), ((-5.0, 0.5), 0.0)] {
        let scene = load_xml(dir.path(), "scene", &scene(camera.0, camera.1), 8);
        let transports = [
            (
                "reference",
                Transport::Reference(ReferenceSettings {
                    max_depth: Some(1),
                    hide_emitters: false,
                    direct_samples: None,
                    skip_null_vertices: false,
                }),
            ),
            ("mis", Transport::Path(mis_power(Some(1), false))),
        ];
        for (label, transport) in transports {
            let replay = format!(
                "{label}, camera at y {}, z {}, 16 spp, seed 3",
                camera.0, camera.1
            );
            let film = render(&scene, transport, SamplerKind::Independent, 16, 3, &replay);
            let exact = |_: UVec2| Vec3::splat(expected);
            let test = z_test(&film, Target::Exact(&exact), 4, 0.01);
            assert_eq!(test.pass_fraction, 1.0, "{replay}: {test}");
            let centre = film.pixel_value(UVec2::splat(4));
            assert_eq!(centre, Vec3::splat(expected), "{replay}");
        }
    }
}
