//! The environment map: its radiance follows Mitsuba 3's latitude-longitude conventions (texel
//! (j, i) at u = (j + ½)/W, v = i/(H − 1), u = atan2(x, −z)/2π, v = acos(y)/π, bilinear,
//! wrapping in u), `to_world` rotates it and `scale` multiplies it, its samples carry their own
//! radiance and density, every direction with radiance has a positive density while black cells
//! are never sampled, a constant map is a constant environment, and bad images are errors.

use glam::{Mat3, Vec2, Vec3};
use lights::{ConstantEnvironment, EnvironmentMap, EnvironmentMapError, Light};
use sampling::Rng;
use sampling::warp::sample_uniform_sphere;
use std::f32::consts::{PI, TAU};

const W: u32 = 8;
const H: u32 = 5;

/// A texel value that says where it is: (column, row, 1).
fn labelled_texels() -> Vec<Vec3> {
    (0..W * H)
        .map(|k| Vec3::new((k % W) as f32, (k / W) as f32, 1.0))
        .collect()
}

/// The map-frame direction of (u, v) by Mitsuba's `uv_to_direction`.
fn direction(u: f32, v: f32) -> Vec3 {
    let (theta, phi) = (v * PI, u * TAU);
    Vec3::new(
        phi.sin() * theta.sin(),
        theta.cos(),
        -phi.cos() * theta.sin(),
    )
}

fn map(texels: &[Vec3], scale: f32, to_world: Mat3) -> EnvironmentMap {
    EnvironmentMap::new(W, H, texels, scale, to_world, 1.0).expect("valid map")
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 2e-4 * b.abs().max_element().max(1.0)
}

#[test]
fn radiance_follows_mitsubas_texel_layout() {
    let env = map(&labelled_texels(), 1.0, Mat3::IDENTITY);
    // At texel centres (inner rows; the poles are rows 0 and H − 1): the texel itself.
    for i in 1..H - 1 {
        for j in 0..W {
            let (u, v) = ((j as f32 + 0.5) / W as f32, i as f32 / (H - 1) as f32);
            let got = env.radiance(direction(u, v));
            assert!(
                close(got, Vec3::new(j as f32, i as f32, 1.0)),
                "texel ({j}, {i}): {got}"
            );
        }
    }
    // Half-way between two columns and two rows: the mean of the four.
    let got = env.radiance(direction(3.0 / W as f32, 1.5 / (H - 1) as f32));
    assert!(
        close(got, Vec3::new(2.5, 1.5, 1.0)),
        "between texels: {got}"
    );
    // Across the seam at u = 0: half-way between the last column and the first.
    let got = env.radiance(direction(0.0, 2.0 / (H - 1) as f32));
    assert!(
        close(got, Vec3::new(0.5 * (W - 1) as f32, 2.0, 1.0)),
        "at the seam: {got}"
    );
    // Straight up and down: the top and the bottom row (their texels all lie on the pole).
    let up = env.radiance(Vec3::Y);
    let down = env.radiance(-Vec3::Y);
    assert!(
        (up.y - 0.0).abs() < 1e-5 && (down.y - (H - 1) as f32).abs() < 1e-5,
        "{up} {down}"
    );
}

#[test]
fn to_world_rotates_and_scale_multiplies() {
    let rotation = Mat3::from_rotation_z(0.7) * Mat3::from_rotation_x(-1.1);
    let plain = map(&labelled_texels(), 1.0, Mat3::IDENTITY);
    let placed = map(&labelled_texels(), 2.5, rotation);
    let mut rng = Rng::new(81);
    for i in 0..1_000 {
        let d = sample_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
        let (a, b) = (placed.radiance(rotation * d), plain.radiance(d) * 2.5);
        assert!(close(a, b), "direction {i} (seed 81), {d}: {a} against {b}");
        let (pa, pb) = (placed.pdf_li(rotation * d), plain.pdf_li(d));
        assert!(
            (pa - pb).abs() <= 1e-3 * pb,
            "direction {i}: pdf {pa} against {pb}"
        );
    }
}

#[test]
fn samples_carry_their_radiance_and_density() {
    let env = map(&labelled_texels(), 1.0, Mat3::from_rotation_y(0.3));
    let mut rng = Rng::new(82);
    let p = Vec3::new(3.0, -1.0, 2.0);
    for i in 0..10_000 {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let Some(s) = env.sample_li(p, u) else {
            continue;
        };
        let replay = format!("sample {i} (seed 82), u {u}: {s:?}");
        assert!((s.wi.length() - 1.0).abs() < 1e-5, "{replay}");
        assert!(close(s.radiance, env.radiance(s.wi)), "{replay}");
        let pdf = env.pdf_li(s.wi);
        assert!(
            (s.pdf_solid_angle - pdf).abs() <= 2e-3 * pdf,
            "{replay}: pdf {pdf}"
        );
        assert!(s.distance.is_infinite() && !s.is_delta, "{replay}");
    }
}

#[test]
fn lit_directions_have_density_and_black_cells_are_never_sampled() {
    // The upper half of the map is black (rows 0–2: the cells between them too), the rest lit.
    let texels: Vec<Vec3> = (0..W * H)
        .map(|k| {
            if k / W <= 2 {
                Vec3::ZERO
            } else {
                Vec3::splat(0.5)
            }
        })
        .collect();
    let env = map(&texels, 1.0, Mat3::IDENTITY);
    let mut rng = Rng::new(83);
    for i in 0..20_000 {
        let d = sample_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
        if env.radiance(d).max_element() > 0.0 {
            assert!(
                env.pdf_li(d) > 0.0,
                "direction {i} (seed 83), {d}: lit but pdf 0"
            );
        }
        if let Some(s) = env.sample_li(Vec3::ZERO, Vec2::new(rng.next_f32(), rng.next_f32())) {
            assert!(
                s.radiance.max_element() > 0.0,
                "sample {i} (seed 83) is black: {s:?}"
            );
            // Cells are bounded by rows 2 and 3 at v = 0.5: nothing is sampled above it.
            assert!(s.wi.y <= 1e-5, "sample {i}: {s:?}");
        }
    }
}

#[test]
fn constant_map_is_a_constant_environment() {
    let radiance = Vec3::new(0.2, 0.5, 0.8);
    let env = EnvironmentMap::new(
        W,
        H,
        &vec![radiance; (W * H) as usize],
        1.0,
        Mat3::IDENTITY,
        3.0,
    )
    .expect("valid");
    let constant = ConstantEnvironment {
        radiance,
        scene_radius: 3.0,
    };
    let (map_light, constant_light) = (Light::EnvironmentMap(env), Light::Environment(constant));
    let d = Vec3::new(0.3, -0.4, 0.866).normalize();
    assert!(close(map_light.radiance_from_direction(d), radiance));
    assert!(((map_light.power() - constant_light.power()) / constant_light.power()).abs() < 1e-5);
    let p = Vec3::ZERO;
    let (a, b) = (
        map_light.irradiance_estimate(p, Vec3::Y),
        constant_light.irradiance_estimate(p, Vec3::Y),
    );
    assert!((a - b).abs() < 1e-5 * b, "{a} against {b}");
    // The density integrates to one over the sphere (midpoint rule in (u, v)).
    let (nu, nv) = (400, 400);
    let mut integral = 0.0_f64;
    for a in 0..nu {
        for b in 0..nv {
            let (u, v) = ((a as f32 + 0.5) / nu as f32, (b as f32 + 0.5) / nv as f32);
            let jacobian = 2.0 * PI * PI * (v * PI).sin();
            integral += f64::from(map_light.pdf_li_environment(direction(u, v)) * jacobian)
                / f64::from(nu * nv);
        }
    }
    assert!(
        (integral - 1.0).abs() < 2e-3,
        "pdf integrates to {integral}"
    );
}

/// The compensated map (light sampling under MIS): only cells whose brightest texel exceeds
/// the mean radiance are sampled, its density still integrates to one, its radiance is the
/// map's, and its power is that of the excess. A constant map has none and is left to BSDF
/// samples.
#[test]
fn the_compensated_map_samples_only_what_exceeds_the_mean() {
    // A dim sky (0.1) with one bright texel (row 2, column 5): the mean lies between them.
    let mut texels = vec![Vec3::splat(0.1); (W * H) as usize];
    texels[(2 * W + 5) as usize] = Vec3::splat(50.0);
    let env = map(&texels, 1.0, Mat3::IDENTITY);
    let mean = env.mean_radiance();
    assert!(mean > 0.1 && mean < 50.0, "mean {mean}");
    let light = Light::EnvironmentMap(env.clone());
    assert!(!light.left_to_bsdf_samples());
    let compensated = light.compensated().expect("a texel above the mean");
    // Away from the bright texel's four cells (rows 1–2, columns 4–5) the density is zero;
    // on them positive; the radiance is the map's everywhere.
    let (nu, nv) = (400, 400);
    let mut integral = 0.0_f64;
    for a in 0..nu {
        for b in 0..nv {
            let (u, v) = ((a as f32 + 0.5) / nu as f32, (b as f32 + 0.5) / nv as f32);
            let d = direction(u, v);
            let pdf = compensated.pdf_li_environment(d);
            let (x, y) = (u * W as f32 - 0.5, v * (H - 1) as f32);
            let near_sun = (4.0..6.0).contains(&x) && (1.0..3.0).contains(&y);
            assert_eq!(pdf > 0.0, near_sun, "u {u}, v {v}: pdf {pdf}");
            assert_eq!(
                compensated.radiance_from_direction(d),
                light.radiance_from_direction(d)
            );
            let jacobian = 2.0 * PI * PI * (v * PI).sin();
            integral += f64::from(pdf * jacobian) / f64::from(nu * nv);
        }
    }
    assert!(
        (integral - 1.0).abs() < 2e-3,
        "pdf integrates to {integral}"
    );
    assert!(
        compensated.power() > 0.0 && compensated.power() < light.power(),
        "{} against {}",
        compensated.power(),
        light.power()
    );
    // A constant map has nothing above its mean.
    let constant = Light::EnvironmentMap(map(
        &vec![Vec3::splat(0.3); (W * H) as usize],
        1.0,
        Mat3::IDENTITY,
    ));
    assert!(constant.compensated().is_none());
    assert!(constant.left_to_bsdf_samples());
}

#[test]
fn bad_images_are_errors() {
    let texels = labelled_texels();
    assert_eq!(
        EnvironmentMap::new(1, 40, &texels, 1.0, Mat3::IDENTITY, 1.0).err(),
        Some(EnvironmentMapError::BadSize {
            width: 1,
            height: 40
        })
    );
    assert_eq!(
        EnvironmentMap::new(W, H + 1, &texels, 1.0, Mat3::IDENTITY, 1.0).err(),
        Some(EnvironmentMapError::BadSize {
            width: W,
            height: H + 1
        })
    );
    let mut bad = texels.clone();
    bad[(2 * W + 3) as usize] = Vec3::new(0.0, f32::NAN, 0.0);
    assert_eq!(
        EnvironmentMap::new(W, H, &bad, 1.0, Mat3::IDENTITY, 1.0).err(),
        Some(EnvironmentMapError::BadTexel { x: 3, y: 2 })
    );
    bad[(2 * W + 3) as usize] = Vec3::new(0.0, -1.0, 0.0);
    assert!(EnvironmentMap::new(W, H, &bad, 1.0, Mat3::IDENTITY, 1.0).is_err());
    assert_eq!(
        EnvironmentMap::new(W, H, &texels, -2.0, Mat3::IDENTITY, 1.0).err(),
        Some(EnvironmentMapError::BadScale)
    );
    assert_eq!(
        EnvironmentMap::new(W, H, &texels, 1.0, Mat3::ZERO, 1.0).err(),
        Some(EnvironmentMapError::BadTransform)
    );
}
