//! Spot and directional lights: the spot's falloff follows Mitsuba's profile (full beam, linear
//! ramp in angle, nothing past the cutoff) under a rotated, uniformly scaled frame, its power is the
//! falloff integrated over the sphere (checked by a midpoint sum over θ), and a directional
//! light gives the same irradiance from every point along one direction, at infinity.

use glam::{Mat3, Vec3};
use lights::{DirectionalLight, Light, SpotLight};
use std::f32::consts::PI;

/// A frame whose third column is `axis`, scaled uniformly by 3 (which the falloff, measured on
/// normalised directions, must ignore).
fn aimed(axis: Vec3) -> Mat3 {
    let z = axis.normalize();
    let x = z.any_orthonormal_vector();
    3.0 * Mat3::from_cols(x, z.cross(x), z)
}

#[test]
fn spot_falloff_is_full_then_linear_in_angle_then_zero() {
    let axis = Vec3::new(0.3, -1.0, 0.2).normalize();
    let spot = SpotLight::new(Vec3::ZERO, aimed(axis), Vec3::ONE, 30.0, 10.0).expect("valid");
    let at = |degrees: f32| {
        let side = axis.any_orthonormal_vector();
        let t = degrees.to_radians();
        spot.falloff(axis * t.cos() + side * t.sin())
    };
    for (degrees, expected) in [
        (0.0, 1.0),
        (9.9, 1.0),
        (15.0, 0.75),
        (20.0, 0.5),
        (29.0, 0.05),
        (30.5, 0.0),
        (90.0, 0.0),
        (180.0, 0.0),
    ] {
        let falloff = at(degrees);
        assert!(
            (falloff - expected).abs() < 2e-3,
            "{degrees} degrees: falloff {falloff}, expected {expected}"
        );
    }
    // The light towards a point on the axis at distance 2: intensity / 4, pointing back.
    let sample = Light::Spot(spot)
        .sample_li(2.0 * axis, glam::Vec2::ZERO, 0.0)
        .expect("lit");
    assert!((sample.radiance - Vec3::splat(0.25)).abs().max_element() < 1e-6);
    assert!((sample.wi + axis).length() < 1e-6 && sample.is_delta);
    assert!(
        Light::Spot(spot)
            .sample_li(-axis, glam::Vec2::ZERO, 0.0)
            .is_none()
    );
}

#[test]
fn spot_power_is_the_falloff_integrated_over_the_sphere() {
    for (cutoff, beam) in [
        (20.0_f32, 15.0_f32),
        (45.0, 0.0),
        (30.0, 30.0),
        (20.0, 60.0),
        (120.0, 40.0),
    ] {
        let spot = SpotLight::new(Vec3::ZERO, Mat3::IDENTITY, Vec3::splat(2.0), cutoff, beam)
            .expect("valid");
        // Midpoint rule over θ of 2π falloff(θ) sin θ, in f64.
        let n = 200_000;
        let mut integral = 0.0_f64;
        for i in 0..n {
            let theta = (f64::from(i) + 0.5) / f64::from(n) * std::f64::consts::PI;
            let d = Vec3::new(theta.sin() as f32, 0.0, theta.cos() as f32);
            integral += f64::from(spot.falloff(d)) * theta.sin();
        }
        integral *= 2.0 * std::f64::consts::PI * std::f64::consts::PI / f64::from(n);
        let power = f64::from(spot.power());
        assert!(
            (power - 2.0 * integral).abs() < 1e-3 * power,
            "cutoff {cutoff}, beam {beam}: power {power}, integral × intensity {}",
            2.0 * integral
        );
    }
    let invalid = [(0.0, 0.0), (181.0, 10.0), (20.0, -1.0), (f32::NAN, 1.0)];
    for (cutoff, beam) in invalid {
        assert!(SpotLight::new(Vec3::ZERO, Mat3::IDENTITY, Vec3::ONE, cutoff, beam).is_none());
    }
    assert!(SpotLight::new(Vec3::ZERO, Mat3::ZERO, Vec3::ONE, 20.0, 10.0).is_none());
}

#[test]
fn directional_light_is_the_same_from_everywhere_at_infinity() {
    let light = DirectionalLight::new(Vec3::new(0.0, -2.0, 0.0), Vec3::new(1.0, 2.0, 3.0), 5.0)
        .expect("non-zero direction");
    for p in [Vec3::ZERO, Vec3::new(1e4, -3.0, 7.0)] {
        let s = light.sample_li(p);
        assert_eq!(s.wi, Vec3::Y);
        assert_eq!(s.radiance, Vec3::new(1.0, 2.0, 3.0));
        assert!(s.distance.is_infinite() && s.is_delta && s.pdf_solid_angle == 1.0);
    }
    assert!((light.power() - PI * 25.0 * 2.0).abs() < 1e-4);
    let as_light = Light::Directional(light);
    assert!(as_light.is_delta() && as_light.bounding_sphere().is_none());
    // Irradiance on a surface tilted 60 degrees from the light: half.
    let n = Vec3::new(3.0_f32.sqrt() / 2.0, 0.5, 0.0);
    assert!((as_light.irradiance_estimate(Vec3::ZERO, n) - 1.0).abs() < 1e-6);
    assert!(DirectionalLight::new(Vec3::ZERO, Vec3::ONE, 1.0).is_none());
}
