//! Every light of the closed set ([`lights::Light::KINDS`]) built from a small scene file, its
//! power and the radiance it sends to a point checked against values worked out by hand. A light
//! added to the set without a case here fails [`every_light_kind_has_a_case`].

mod common;

use std::f32::consts::PI;
use std::sync::OnceLock;

use common::{wrap, write_scene};
use glam::{Vec2, Vec3};
use lights::Light;

/// A light built from XML and what it must do.
struct Case {
    /// The variant of [`Light`] the scene makes.
    kind: &'static str,
    /// The scene's body: the one emitter, and shapes that fix the scene's bounding sphere.
    body: String,
    /// Emitted power, W, mean over RGB.
    power: f32,
    /// Radiance (W m⁻² sr⁻¹, RGB), or for a delta light the `intensity / distance²` term,
    /// arriving at [`PROBE`] from a light sample.
    arriving: Vec3,
}

/// Where the radiance of each case is sampled from, world units: on the +z axis, outside every
/// shape below.
const PROBE: Vec3 = Vec3::new(0.0, 0.0, 2.0);

/// A sphere of radius 1 at the origin (Mitsuba's default sphere): the scene's bounds are then
/// [−1, 1]³ and the radius of the sphere around them, which directional lights and environments
/// count their power over, is √3.
const UNIT_SPHERE: &str = "<shape type=\"sphere\"/>";

/// A 4 × 2 Radiance RGBE image whose every texel is RGB (1, 1, 1): mantissa 128 times
/// 2^(129 − 136).
fn white_rgbe() -> Vec<u8> {
    let mut bytes = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n".to_vec();
    for _ in 0..8 {
        bytes.extend_from_slice(&[128, 128, 128, 129]);
    }
    bytes
}

fn cases() -> Vec<Case> {
    let rgb = Vec3::new(1.0, 2.0, 3.0);
    let mean = 2.0;
    // The sphere around the unit sphere's bounding box, squared.
    let scene_r2 = 3.0;
    let sky = write_scene("light_set_sky.hdr", "");
    std::fs::write(&sky, white_rgbe()).unwrap();
    vec![
        // Mitsuba's rectangle: [−1, 1]² in the z = 0 plane, facing +z; power π · area · L.
        Case {
            kind: "Mesh",
            body: "<shape type=\"rectangle\"><emitter type=\"area\"><rgb name=\"radiance\" \
                   value=\"1, 2, 3\"/></emitter></shape>"
                .to_string(),
            power: PI * 4.0 * mean,
            arriving: rgb,
        },
        // π · 4π r² · L for r = 0.5.
        Case {
            kind: "Sphere",
            body: "<shape type=\"sphere\"><float name=\"radius\" value=\"0.5\"/><emitter \
                   type=\"area\"><rgb name=\"radiance\" value=\"1, 2, 3\"/></emitter></shape>"
                .to_string(),
            power: PI * 4.0 * PI * 0.25 * mean,
            arriving: rgb,
        },
        // The same sphere sliding along x while the shutter is open: a translation keeps its
        // power.
        Case {
            kind: "Moving",
            body: "<shape type=\"sphere\"><float name=\"radius\" value=\"0.5\"/><animation \
                   name=\"to_world\"><transform time=\"0\"/><transform time=\"1\"><translate \
                   x=\"0.5\"/></transform></animation><emitter type=\"area\"><rgb \
                   name=\"radiance\" value=\"1, 2, 3\"/></emitter></shape>"
                .to_string(),
            power: PI * 4.0 * PI * 0.25 * mean,
            arriving: rgb,
        },
        // 4π · I; seen from 2 units away, I / 4.
        Case {
            kind: "Point",
            body: "<emitter type=\"point\"><rgb name=\"intensity\" value=\"1, 2, 3\"/></emitter>"
                .to_string(),
            power: 4.0 * PI * mean,
            arriving: rgb / 4.0,
        },
        // Full intensity up to a 60° cutoff: I times the cone's solid angle 2π (1 − cos 60°) = π.
        Case {
            kind: "Spot",
            body: "<emitter type=\"spot\"><rgb name=\"intensity\" value=\"1, 2, 3\"/><float \
                   name=\"cutoff_angle\" value=\"60\"/><float name=\"beam_width\" value=\"60\"/>\
                   </emitter>"
                .to_string(),
            power: PI * mean,
            arriving: rgb / 4.0,
        },
        // Irradiance E travelling along −z: π r² · E over the scene's cross-section.
        Case {
            kind: "Directional",
            body: format!(
                "{UNIT_SPHERE}<emitter type=\"directional\"><vector name=\"direction\" \
                 value=\"0, 0, -1\"/><rgb name=\"irradiance\" value=\"1, 2, 3\"/></emitter>"
            ),
            power: PI * scene_r2 * mean,
            arriving: rgb,
        },
        // Radiance L from every direction: L · π · π r².
        Case {
            kind: "Environment",
            body: format!(
                "{UNIT_SPHERE}<emitter type=\"constant\"><rgb name=\"radiance\" \
                 value=\"1, 2, 3\"/></emitter>"
            ),
            power: PI * PI * scene_r2 * mean,
            arriving: rgb,
        },
        // A white map times `scale` 2 is a constant environment of radiance 2.
        Case {
            kind: "EnvironmentMap",
            body: format!(
                "{UNIT_SPHERE}<emitter type=\"envmap\"><string name=\"filename\" \
                 value=\"{}\"/><float name=\"scale\" value=\"2\"/></emitter>",
                sky.display()
            ),
            power: PI * PI * scene_r2 * 2.0,
            arriving: Vec3::splat(2.0),
        },
    ]
}

/// The one light of the scene made from `case`.
fn light_of(case: &Case) -> Light {
    let path = write_scene(&format!("light_set_{}.xml", case.kind), &wrap(&case.body));
    let scene = scene::load(&path, &[]).unwrap_or_else(|e| panic!("{}: {e}", case.kind));
    let lights = scene.world.lights();
    assert_eq!(lights.len(), 1, "{}", case.kind);
    lights[0].clone()
}

/// Every case with its light, made once: the tests run in parallel and would otherwise rewrite
/// the scene files one another reads.
fn built() -> &'static [(Case, Light)] {
    static BUILT: OnceLock<Vec<(Case, Light)>> = OnceLock::new();
    BUILT.get_or_init(|| {
        cases()
            .into_iter()
            .map(|case| {
                let light = light_of(&case);
                (case, light)
            })
            .collect()
    })
}

#[test]
fn every_light_kind_has_a_case() {
    let mut covered: Vec<&str> = built().iter().map(|(case, _)| case.kind).collect();
    let mut kinds = Light::KINDS.to_vec();
    covered.sort_unstable();
    kinds.sort_unstable();
    assert_eq!(
        covered, kinds,
        "each light of the set needs a case in `cases` (and only those)"
    );
}

#[test]
fn lights_built_from_xml_have_their_analytic_power_and_radiance() {
    for (case, light) in built() {
        assert_eq!(light.kind(), case.kind);
        let power = light.power();
        assert!(
            (power - case.power).abs() <= 1e-5 * case.power,
            "{}: power {power} W, expected {} W",
            case.kind,
            case.power
        );
        let sample = light
            .sample_li(PROBE, Vec2::splat(0.5), 0.5)
            .unwrap_or_else(|| panic!("{}: no light reaches {PROBE}", case.kind));
        assert!(
            sample
                .radiance
                .abs_diff_eq(case.arriving, 1e-5 * case.arriving.max_element()),
            "{}: radiance {} arriving at {PROBE}, expected {}",
            case.kind,
            sample.radiance,
            case.arriving
        );
    }
}

/// A ray that meets an area light sees its radiance on the front side only; one that escapes
/// sees the environment's.
#[test]
fn area_lights_emit_on_their_front_side_and_environments_everywhere() {
    for (case, light) in built() {
        let (n, w) = (Vec3::Z, Vec3::new(0.0, 0.6, 0.8));
        let (front, back) = (light.radiance_towards(n, w), light.radiance_towards(n, -w));
        let escaping = light.radiance_from_direction(w);
        let (expected_front, expected_escaping) = if light.is_area() {
            (case.arriving, Vec3::ZERO)
        } else if light.is_environment() {
            (Vec3::ZERO, case.arriving)
        } else {
            assert!(light.is_delta(), "{}", case.kind);
            (Vec3::ZERO, Vec3::ZERO)
        };
        assert_eq!(
            (front, back, escaping),
            (expected_front, Vec3::ZERO, expected_escaping),
            "{}",
            case.kind
        );
    }
}
