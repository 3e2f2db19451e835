//! Motion blur is unbiased: a square area light moving over a diffuse plane, rendered with the
//! shutter open, converges to the time average of the plane's exact radiance, for every
//! configuration of the path integrator, every sampler and the reference integrator; and the
//! stiff cases (a shutter that opens and closes at once, a full turn within the shutter, a light
//! moving 10⁴ times its size, a shutter of 10⁻⁹ far from time 0) and a moving camera converge
//! likewise.
//!
//! **Oracle.** No renderer: the plane (reflectance ρ, normal +z) under a one-sided Lambertian
//! polygon of radiance L has radiance ρ/π · E with E = L/2 · |Σᵢ γᵢ n · (vᵢ × vᵢ₊₁)/|vᵢ × vᵢ₊₁||
//! (Lambert's formula: vᵢ the unit directions to the polygon's corners, γᵢ the angle between
//! consecutive ones). A pixel's expectation is that radiance averaged over the pixel (where the
//! camera's own rays meet the plane, 4 × 4 points) and over the shutter (the light's corners
//! moved as the animation says, at [`Case::time_points`] midpoints). The integrand is smooth, so the
//! quadrature's error (below 1e-5 relative, by halving both grids) is far below the tests'
//! standard errors. The camera sits between the plane and the light, looking down: it sees
//! only the plane, and light leaving the plane upwards meets the light's black back or nothing,
//! so the image is direct light only, at any depth.
//!
//! **Test.** `common::compare::check_unbiased` with the exact image as the oracle: replicates of
//! each configuration (seeds from [`CONFIG_SEED`]) against it on the whole image, 8 × 8 regions
//! and 4 × 4 blocks; family-wise α = 0.01 per scene (Bonferroni over its comparisons, at most
//! [`MAX_COMPARISONS`]). Power: each comparison must also reject the image × 1.005 and a block
//! × 1.05. A failure names the case, the configuration, seeds and samples per pixel.

mod common;

use common::compare::{Replicates, check_unbiased};
use common::{configurations_with, load_xml, mis_power};
use glam::{DVec3, Vec2};
use render::plan::{RenderPlan, Transport};
use sampling::sampler::SamplerKind;
use scene::RenderScene;

/// Image edge, pixels.
const SIZE: u32 = 16;
/// Family-wise significance level of one case's test.
const CASE_ALPHA: f64 = 0.01;
/// The most comparisons one case makes (13 configurations and the reference integrator).
const MAX_COMPARISONS: usize = 14;
/// Significance level of one comparison.
const ALPHA: f64 = CASE_ALPHA / MAX_COMPARISONS as f64;
/// Independent renders of each configuration.
const REPLICATES: u32 = 16;
/// First seed of every configuration's replicates.
const CONFIG_SEED: u32 = 4000;
/// Points per pixel edge the oracle averages over.
const PIXEL_POINTS: u32 = 4;
/// The plane's reflectance.
const ALBEDO: f64 = 0.5;
/// The light's radiance (RGB).
const RADIANCE: [f64; 3] = [1.0, 0.5, 0.25];
/// Where the camera is (world units): between the plane (z = 0) and the light (z = 1).
const CAMERA_Z: f64 = 0.5;

/// One scene: the light's `<animation>` or `<transform>` and the shutter, and where the light's
/// corners are at each shutter fraction.
struct Case {
    name: &'static str,
    /// `shutter_open` and `shutter_close`.
    shutter: [f64; 2],
    /// The light's `to_world` element, placing the rectangle `[-1, 1]²` (facing +z before it).
    to_world: String,
    /// The light's corners (world units) at the shutter fraction `u` ∈ [0, 1].
    corners: Box<dyn Fn(f64) -> [DVec3; 4]>,
    /// The light's radiance is `RADIANCE` times this.
    brightness: f64,
    /// Midpoints of the shutter interval the oracle averages over.
    time_points: u32,
    /// The camera's x at the shutter fraction `u` ∈ [0, 1] (it looks straight down from
    /// z = [`CAMERA_Z`], moving only along x), `None` for one fixed at x = 0.
    camera_x: Option<Box<dyn Fn(f64) -> f64>>,
}

/// The corners of the rectangle of half-edges `half_x × half_y` centred at `center`, turned by
/// `angle` (radians) about its own vertical axis.
fn rectangle(center: DVec3, half_x: f64, half_y: f64, angle: f64) -> [DVec3; 4] {
    let (s, c) = angle.sin_cos();
    [
        (-half_x, -half_y),
        (-half_x, half_y),
        (half_x, half_y),
        (half_x, -half_y),
    ]
    .map(|(x, y)| center + DVec3::new(c * x - s * y, s * x + c * y, 0.0))
}

/// The operations of one keyframe: the rectangle `[-1, 1]²` scaled to `half_x × half_y`, turned
/// to face down (−z), turned by `degrees` about its own vertical axis, and moved to `(x, 0, 1)`.
/// (Between keyframes the translation moves in a straight line and the rotation turns, as in
/// pbrt's `AnimatedTransform`: an object spins about its own origin.)
fn keyframe_ops(half_x: f64, half_y: f64, x: f64, degrees: f64) -> String {
    format!(
        r#"<scale x="{half_x}" y="{half_y}"/><rotate x="1" angle="180"/><rotate z="1" angle="{degrees}"/><translate x="{x}" z="1"/>"#
    )
}

/// The light sliding from x = −0.5 to 0.5 over keyframes at `times`.
fn sliding(name: &'static str, shutter: [f64; 2], times: [f64; 2]) -> Case {
    let half = 0.25;
    Case {
        name,
        shutter,
        to_world: format!(
            r#"<animation name="to_world"><transform time="{}">{}</transform><transform time="{}">{}</transform></animation>"#,
            times[0],
            keyframe_ops(half, half, -0.5, 0.0),
            times[1],
            keyframe_ops(half, half, 0.5, 0.0),
        ),
        corners: Box::new(move |u| {
            let t = shutter[0] + u * (shutter[1] - shutter[0]);
            let s = ((t - times[0]) / (times[1] - times[0])).clamp(0.0, 1.0);
            rectangle(DVec3::new(-0.5 + s, 0.0, 1.0), half, half, 0.0)
        }),
        brightness: 1.0,
        time_points: 256,
        camera_x: None,
    }
}

/// The scene file of `case`.
fn scene_xml(case: &Case) -> String {
    let [open, close] = case.shutter;
    let [r, g, b] = RADIANCE.map(|c| c * case.brightness);
    format!(
        r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="3"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="90"/>
        <float name="shutter_open" value="{open}"/>
        <float name="shutter_close" value="{close}"/>
        {}
        <film type="hdrfilm"><rfilter type="box"/></film>
    </sensor>
    <shape type="rectangle">
        <transform name="to_world"><scale value="10"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="{ALBEDO}"/></bsdf>
    </shape>
    <shape type="rectangle">
        {}
        <emitter type="area"><rgb name="radiance" value="{r}, {g}, {b}"/></emitter>
    </shape>
</scene>
"#,
        camera_to_world(case),
        case.to_world
    )
}

/// The camera's `to_world`: fixed at x = 0, or sliding from `camera_x(0)` to `camera_x(1)`
/// over the shutter (two keyframes at its ends).
fn camera_to_world(case: &Case) -> String {
    let lookat = |x: f64| {
        format!(r#"<lookat origin="{x}, 0, {CAMERA_Z}" target="{x}, 0, 0" up="0, 1, 0"/>"#)
    };
    match &case.camera_x {
        None => format!(r#"<transform name="to_world">{}</transform>"#, lookat(0.0)),
        Some(x) => {
            let [open, close] = case.shutter;
            format!(
                r#"<animation name="to_world"><transform time="{open}">{}</transform><transform time="{close}">{}</transform></animation>"#,
                lookat(x(0.0)),
                lookat(x(1.0))
            )
        }
    }
}

/// Irradiance at `p` (normal +z) from a Lambertian polygon of unit radiance with `corners`.
fn irradiance(p: DVec3, corners: &[DVec3; 4]) -> f64 {
    let dirs = corners.map(|q| (q - p).normalize());
    let mut sum = 0.0;
    for i in 0..4 {
        let (a, b) = (dirs[i], dirs[(i + 1) % 4]);
        let cross = a.cross(b);
        let length = cross.length();
        if length > 0.0 {
            sum += a.dot(b).clamp(-1.0, 1.0).acos() * cross.z / length;
        }
    }
    0.5 * sum.abs()
}

/// The exact image of `case` on `scene` (positions relative to the camera, as the scene holds
/// them): each pixel's radiance averaged over the pixel and the shutter.
fn exact_image(scene: &RenderScene, case: &Case) -> Vec<DVec3> {
    // Where the camera is at each time: the scene is placed relative to where it is when the
    // shutter opens, and a moving camera only slides, so its rays are the opening ones moved.
    let camera_at =
        |u: f64| DVec3::new(case.camera_x.as_ref().map_or(0.0, |x| x(u)), 0.0, CAMERA_Z);
    let times: Vec<([DVec3; 4], DVec3)> = (0..case.time_points)
        .map(|k| {
            let u = (f64::from(k) + 0.5) / f64::from(case.time_points);
            ((case.corners)(u), camera_at(u))
        })
        .collect();
    let mut image = Vec::new();
    for y in 0..SIZE {
        for x in 0..SIZE {
            let mut sum = 0.0;
            for j in 0..PIXEL_POINTS {
                for i in 0..PIXEL_POINTS {
                    let offset = (Vec2::new(i as f32, j as f32) + 0.5) / PIXEL_POINTS as f32;
                    let film = Vec2::new(x as f32, y as f32) + offset;
                    let ray = scene.camera.generate_ray(film, Vec2::ZERO).ray;
                    let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
                    for (corners, camera) in &times {
                        let o = o + *camera;
                        let p = o + d * (-o.z / d.z);
                        sum += irradiance(p, corners);
                    }
                }
            }
            let mean = sum / f64::from(PIXEL_POINTS * PIXEL_POINTS * case.time_points);
            let radiance = ALBEDO / std::f64::consts::PI * mean * case.brightness;
            image.push(DVec3::from_array(RADIANCE) * radiance);
        }
    }
    image
}

/// One configuration: label, transport, sampler, samples per pixel.
type Config = (String, Transport, SamplerKind, u32);

/// Checks `case` with `configurations`, each of which must see the biases `common::compare::POWER`.
fn check_case(case: &Case, configurations: &[Config]) {
    assert!(configurations.len() <= MAX_COMPARISONS);
    let dir = tempfile::tempdir().expect("temporary folder");
    let scene = load_xml(dir.path(), case.name, &scene_xml(case), SIZE);
    let exact = Replicates::exact("exact", SIZE, SIZE, exact_image(&scene, case));
    let mut failures = Vec::new();
    for (label, transport, sampler, spp) in configurations {
        let seeds = CONFIG_SEED..CONFIG_SEED + REPLICATES;
        let replicates = Replicates::render(&scene, label, seeds, *spp, |seed| {
            RenderPlan::fixed_spp(*transport, *sampler, seed, *spp)
        });
        if let Err(failure) = check_unbiased(case.name, &replicates, &exact, ALPHA) {
            failures.push(failure);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every configuration of the path integrator (Sobol), every sampler, and the reference.
fn every_configuration(scene_spp: u32) -> Vec<Config> {
    let base = mis_power(Some(3), false);
    let mut list: Vec<_> = configurations_with(base, SamplerKind::Sobol)
        .into_iter()
        .filter(|c| {
            ![
                "light tracing",
                "mis power uniform selection",
                "mis power every light",
            ]
            .contains(&c.label)
        })
        .map(|c| {
            // BSDF sampling alone finds the light by chance: it needs many more samples for the
            // same standard error; light sampling without MIS is as good as with it here.
            let spp = if c.settings.sample_lights {
                scene_spp
            } else {
                64 * scene_spp
            };
            (
                c.label.to_string(),
                Transport::Path(c.settings),
                c.sampler,
                spp,
            )
        })
        .collect();
    list.push((
        "reference".to_string(),
        Transport::Reference(integrators::reference::ReferenceSettings {
            max_depth: Some(3),
            hide_emitters: false,
            direct_samples: None,
            skip_null_vertices: false,
        }),
        SamplerKind::Independent,
        256 * scene_spp,
    ));
    list
}

/// The main case, every configuration.
#[test]
fn a_sliding_light_blurs_to_its_time_average() {
    let case = sliding("sliding", [0.0, 1.0], [0.0, 1.0]);
    check_case(&case, &every_configuration(64));
}

/// MIS with Sobol and with independent numbers: the stiff cases' configurations.
fn mis_configurations(spp: u32) -> Vec<Config> {
    let mis = Transport::Path(mis_power(Some(3), false));
    vec![
        ("mis power sobol".to_string(), mis, SamplerKind::Sobol, spp),
        (
            "mis power independent".to_string(),
            mis,
            SamplerKind::Independent,
            spp,
        ),
    ]
}

/// A shutter that opens and closes at once sees the light where it is then (no blur, no time
/// dimension); a shutter of 1e-9 at time 1e3 blurs as one of length 1 at time 0.
#[test]
fn zero_and_tiny_shutters() {
    let instant = sliding("instant", [0.3, 0.3], [0.0, 1.0]);
    check_case(&instant, &mis_configurations(64));
    let tiny = sliding("tiny-shutter", [1e3, 1e3 + 1e-9], [1e3, 1e3 + 1e-9]);
    check_case(&tiny, &mis_configurations(64));
}

/// A light spinning a full turn about its own axis within the shutter (three segments of 120°:
/// slerp takes the shorter arc, so a full turn needs at least three), and a light 0.02 wide
/// crossing 200 units (10⁴ times its size) within the shutter.
#[test]
fn a_full_turn_and_a_long_flight() {
    let keyframes: String = (0..4)
        .map(|k| {
            format!(
                r#"<transform time="{}">{}</transform>"#,
                f64::from(k) / 3.0,
                keyframe_ops(0.3, 0.1, 0.35, 120.0 * f64::from(k))
            )
        })
        .collect();
    let turn = Case {
        name: "full-turn",
        shutter: [0.0, 1.0],
        to_world: format!(r#"<animation name="to_world">{keyframes}</animation>"#),
        corners: Box::new(|u| {
            rectangle(
                DVec3::new(0.35, 0.0, 1.0),
                0.3,
                0.1,
                std::f64::consts::TAU * u,
            )
        }),
        brightness: 1.0,
        time_points: 256,
        camera_x: None,
    };
    check_case(&turn, &mis_configurations(64));
    let half = 0.01;
    let flight = Case {
        name: "long-flight",
        shutter: [0.0, 1.0],
        to_world: format!(
            r#"<animation name="to_world"><transform time="0">{}</transform><transform time="1">{}</transform></animation>"#,
            keyframe_ops(half, half, -100.0, 0.0),
            keyframe_ops(half, half, 100.0, 0.0),
        ),
        corners: Box::new(move |u| {
            rectangle(DVec3::new(-100.0 + 200.0 * u, 0.0, 1.0), half, half, 0.0)
        }),
        brightness: 1e4,
        time_points: 8192,
        camera_x: None,
    };
    // Most times see the light far away: Sobol's stratified time finds the near passes evenly,
    // independent times far less so, and need 16 times the samples for the same power (their
    // image's standard error at 1024 spp was 0.43%, Sobol's at 2048 0.009%).
    let [sobol, independent] = <[Config; 2]>::try_from(mis_configurations(2048)).expect("two");
    check_case(
        &flight,
        &[sobol, (independent.0, independent.1, independent.2, 32768)],
    );
}

/// A camera sliding 0.6 along x under a fixed light: the plane's lit spot smears across the
/// image.
#[test]
fn a_moving_camera_blurs_what_it_sees() {
    let fixed = |name, shutter| Case {
        camera_x: Some(Box::new(|u: f64| -0.3 + 0.6 * u)),
        corners: Box::new(|_| rectangle(DVec3::new(0.0, 0.0, 1.0), 0.25, 0.25, 0.0)),
        to_world: format!(
            r#"<transform name="to_world">{}</transform>"#,
            keyframe_ops(0.25, 0.25, 0.0, 0.0)
        ),
        ..sliding(name, shutter, [0.0, 1.0])
    };
    check_case(&fixed("moving-camera", [0.0, 1.0]), &mis_configurations(64));
}
