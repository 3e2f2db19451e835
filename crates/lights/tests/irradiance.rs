//! Light sampling checked against closed-form irradiance: E[L cos θ / pdf] must equal the
//! analytic irradiance, which fails if a sampler and its pdf disagree or lose mass.
//!
//! Fixed seeds; each estimate uses enough samples that its relative standard error is below
//! 0.3%, and the tolerance is 1.5% (five standard errors). Failures print the seed.

use glam::{Vec2, Vec3};
use lights::{Light, MeshAreaLight, SphereAreaLight};
use sampling::Rng;
use std::f32::consts::PI;

const SAMPLES: u32 = 200_000;
const TOLERANCE: f64 = 0.015;

/// Monte Carlo irradiance at `p` with normal `n` from `light`, plus a check that every sample's
/// pdf matches `pdf_li_surface` for the same point.
fn estimate_irradiance(light: &Light, p: Vec3, n: Vec3, seed: u32) -> f64 {
    let mut rng = Rng::new(seed);
    let mut sum = 0.0_f64;
    for i in 0..SAMPLES {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let Some(s) = light.sample_li(p, u, 0.0) else {
            continue;
        };
        let cos = n.dot(s.wi).max(0.0);
        assert!(s.pdf_solid_angle > 0.0 && s.pdf_solid_angle.is_finite());
        let pdf_again = light.pdf_li_surface(p, s.p_light, s.n_light, 0.0);
        assert!(
            (pdf_again - s.pdf_solid_angle).abs() <= 1e-3 * s.pdf_solid_angle,
            "seed {seed}, sample {i}: sampled pdf {} but pdf_li_surface {pdf_again}",
            s.pdf_solid_angle
        );
        sum += f64::from(s.radiance.x * cos / s.pdf_solid_angle);
    }
    sum / f64::from(SAMPLES)
}

fn assert_close(estimate: f64, expected: f64, what: &str, seed: u32) {
    let relative = (estimate - expected).abs() / expected;
    assert!(
        relative < TOLERANCE,
        "{what} (seed {seed}): estimated {estimate}, analytic {expected}, relative error {relative}"
    );
}

fn sphere_light(center: Vec3, radius: f32) -> Light {
    Light::Sphere(SphereAreaLight {
        center,
        radius,
        flip_normals: false,
        radiance: Vec3::ONE,
    })
}

#[test]
fn sphere_light_irradiance_matches_pi_sin2_theta_max() {
    // A point facing the centre of a sphere of radiance 1 receives π sin²θ_max.
    for (seed, (radius, distance)) in [(1.0_f32, 3.0_f32), (0.5, 0.6), (1e-3, 10.0)]
        .into_iter()
        .enumerate()
    {
        let light = sphere_light(Vec3::new(0.0, 0.0, distance), radius);
        let expected = f64::from(PI) * f64::from(radius / distance).powi(2);
        let estimate = estimate_irradiance(&light, Vec3::ZERO, Vec3::Z, seed as u32);
        assert_close(estimate, expected, "sphere light", seed as u32);
    }
}

#[test]
fn sphere_light_seen_from_inside_gives_pi() {
    // Inside a sphere emitting inwards with radiance 1, every direction carries 1: E = π.
    let light = Light::Sphere(SphereAreaLight {
        center: Vec3::new(0.1, -0.2, 0.3),
        radius: 2.0,
        flip_normals: true,
        radiance: Vec3::ONE,
    });
    let estimate = estimate_irradiance(&light, Vec3::ZERO, Vec3::Z, 7);
    assert_close(estimate, f64::from(PI), "inward sphere", 7);
}

/// Form factor from a point to a rectangle w × l whose corner lies on the point's normal at
/// height h, parallel to the point's tangent plane.
fn corner_rectangle_form_factor(w: f64, l: f64, h: f64) -> f64 {
    let (a, b) = (w / h, l / h);
    let sa = (1.0 + a * a).sqrt();
    let sb = (1.0 + b * b).sqrt();
    (a / sa * (b / sa).atan() + b / sb * (a / sb).atan()) / (2.0 * std::f64::consts::PI)
}

#[test]
fn square_light_irradiance_matches_form_factor() {
    // A square of half-size s at height h, facing down, centred above the point.
    let (s, h) = (0.5_f32, 1.0_f32);
    let c = [
        Vec3::new(-s, -s, h),
        Vec3::new(s, -s, h),
        Vec3::new(s, s, h),
        Vec3::new(-s, s, h),
    ];
    // Wound so that the normal points down (-z), towards the receiver.
    let triangles = vec![[c[0], c[2], c[1]], [c[0], c[3], c[2]]];
    let light = Light::Mesh(MeshAreaLight::new(triangles, Vec3::ONE).expect("non-degenerate"));
    let expected = 4.0
        * std::f64::consts::PI
        * corner_rectangle_form_factor(f64::from(s), f64::from(s), f64::from(h));
    let estimate = estimate_irradiance(&light, Vec3::ZERO, Vec3::Z, 11);
    assert_close(estimate, expected, "square light", 11);
}

#[test]
fn back_side_of_a_mesh_light_is_dark() {
    let triangles = vec![[
        Vec3::new(-1.0, -1.0, 1.0),
        Vec3::new(1.0, -1.0, 1.0),
        Vec3::new(0.0, 1.0, 1.0),
    ]];
    // Normal +z: facing away from a receiver at the origin.
    let light = Light::Mesh(MeshAreaLight::new(triangles, Vec3::ONE).expect("non-degenerate"));
    let mut rng = Rng::new(3);
    for _ in 0..1000 {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        assert!(light.sample_li(Vec3::ZERO, u, 0.0).is_none());
    }
}

#[test]
fn degenerate_mesh_light_is_rejected_not_nan() {
    let p = Vec3::new(1.0, 2.0, 3.0);
    assert!(MeshAreaLight::new(vec![[p, p, p]], Vec3::ONE).is_none());
    assert!(MeshAreaLight::new(vec![], Vec3::ONE).is_none());
}

#[test]
fn tiny_far_sphere_stays_finite_at_u_extremes() {
    let light = sphere_light(Vec3::new(1e3, 0.0, 0.0), 1e-3);
    let one_minus = 1.0 - f32::EPSILON / 2.0;
    for u in [
        Vec2::ZERO,
        Vec2::new(one_minus, one_minus),
        Vec2::new(0.5, one_minus),
    ] {
        let s = light
            .sample_li(Vec3::ZERO, u, 0.0)
            .expect("the sphere is visible");
        assert!(
            s.wi.is_finite() && (s.wi.length() - 1.0).abs() < 1e-4,
            "{s:?}"
        );
        assert!(
            s.pdf_solid_angle.is_finite() && s.pdf_solid_angle > 0.0,
            "{s:?}"
        );
        assert!(s.wi.x > 0.999_999, "sample left the cone: {s:?}");
    }
}

#[test]
fn irradiance_estimate_is_exact_facing_a_sphere_and_never_zero_where_light_arrives() {
    // Facing the centre, power / (4π d²) is exactly π sin²θ_max for a sphere of radiance 1.
    for (radius, distance) in [(1.0_f32, 3.0_f32), (1e-3, 10.0)] {
        let light = sphere_light(Vec3::new(0.0, 0.0, distance), radius);
        let estimate = light.irradiance_estimate(Vec3::ZERO, Vec3::Z);
        let exact = PI * (radius / distance).powi(2);
        assert!(
            (estimate - exact).abs() < 1e-4 * exact,
            "{estimate} vs {exact}"
        );
    }
    // Lights just above the tangent plane, on either side, must keep a positive estimate
    // wherever some of their directions have a non-zero cosine (resampling needs it).
    let mut rng = Rng::new(5);
    for _ in 0..1000 {
        let center = Vec3::new(
            rng.next_f32() - 0.5,
            rng.next_f32() - 0.5,
            rng.next_f32() - 0.5,
        ) * 4.0;
        let radius = 0.5 * rng.next_f32();
        let light = sphere_light(center, radius);
        let n = Vec3::Z;
        let sample = light.sample_li(Vec3::ZERO, Vec2::new(rng.next_f32(), rng.next_f32()), 0.0);
        if let Some(sample) = sample
            && sample.wi.dot(n).abs() > 0.0
        {
            assert!(
                light.irradiance_estimate(Vec3::ZERO, n) > 0.0,
                "centre {center}, radius {radius}: light arrives but the estimate is 0"
            );
        }
    }
    let environment = Light::Environment(lights::ConstantEnvironment {
        radiance: Vec3::splat(2.0),
        scene_radius: 10.0,
    });
    assert!((environment.irradiance_estimate(Vec3::ZERO, Vec3::Z) - 2.0 * PI).abs() < 1e-5);
}
