//! The thin dielectric: its reflectance is the sum of the slab's internal reflections (checked
//! against the series summed term by term with textbook Fresnel), transmission leaves straight
//! through without an index crossed, Mitsuba's sample weights are the specular multipliers, and
//! both sides behave alike. Random lobe choices come from fixed seeds; each count is checked at
//! 5 standard deviations (two-sided p ≈ 6e-7 per count, 20 counts: family-wise below 1.2e-5).

use glam::{Vec2, Vec3};
use materials::{Bsdf, BsdfFlags, BsdfSample, MaterialError, ThinDielectric};
use sampling::Rng;

fn pane(eta: f32, reflectance: Vec3, transmittance: Vec3) -> Bsdf {
    Bsdf::from(ThinDielectric::new(eta, 1.0, reflectance, transmittance).expect("valid ior"))
}

/// The unit direction at `degrees` from +z, turned `phi_degrees` about z, flipped below when
/// `below`.
fn direction(degrees: f32, phi_degrees: f32, below: bool) -> Vec3 {
    let (theta, phi) = (degrees.to_radians(), phi_degrees.to_radians());
    let z = if below { -theta.cos() } else { theta.cos() };
    Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), z)
}

fn weight(s: &BsdfSample) -> Vec3 {
    s.f * s.wi.z.abs() / s.pdf_solid_angle
}

/// One interface's reflectance by the textbook s/p amplitudes in f64, from outside (index 1)
/// into the pane (index `n`); inside the pane the same angle pair gives the same value.
fn interface_reflectance(cos_i: f64, n: f64) -> f64 {
    let sin_t = (1.0 - cos_i * cos_i).sqrt() / n;
    let cos_t = (1.0 - sin_t * sin_t).sqrt();
    let r_s = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    let r_p = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    0.5 * (r_s * r_s + r_p * r_p)
}

/// The slab's reflectance by summing the light that leaves its near side after 0, 2, 4, …
/// internal bounces: R + T R T + T R R R T + …, term by term.
fn slab_reflectance(cos_i: f64, n: f64) -> f64 {
    let r = interface_reflectance(cos_i, n);
    let t = 1.0 - r;
    let (mut sum, mut inside) = (r, t);
    for _ in 0..400 {
        // Light inside travelling to the far side: it reflects there, comes back, and part leaves.
        inside *= r;
        sum += inside * t;
        inside *= r;
    }
    sum
}

#[test]
fn lobe_probabilities_are_the_summed_internal_reflections() {
    let eta = 1.5_f32;
    let bsdf = pane(eta, Vec3::ONE, Vec3::ONE);
    let mut rng = Rng::new(11);
    let n = 40_000;
    for below in [false, true] {
        for degrees in [0.0_f32, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0] {
            let wo = direction(degrees, 20.0, below);
            let expected = slab_reflectance(f64::from(wo.z.abs()), f64::from(eta));
            let mut reflected = 0usize;
            for _ in 0..n {
                let s = bsdf
                    .sample(wo, rng.next_f32(), Vec2::ZERO)
                    .expect("a pane always samples");
                let replay = format!("wo {wo}, {degrees} degrees, below {below}: {s:?}");
                let lobe = if s.wi.z * wo.z > 0.0 {
                    reflected += 1;
                    expected
                } else {
                    1.0 - expected
                };
                assert!(
                    (f64::from(s.pdf_solid_angle) - lobe).abs() < 2e-5,
                    "{replay}"
                );
            }
            let sigma = (n as f64 * expected * (1.0 - expected)).sqrt();
            let deviation = (reflected as f64 - n as f64 * expected).abs();
            assert!(
                deviation <= 5.0 * sigma + 1.0,
                "{degrees} degrees, below {below}: {reflected} of {n} reflected, expected {expected}"
            );
        }
    }
}

#[test]
fn transmission_goes_straight_through_and_reflection_mirrors() {
    let bsdf = pane(1.33, Vec3::ONE, Vec3::ONE);
    for below in [false, true] {
        for (degrees, phi) in [(10.0, 0.0), (50.0, 130.0), (80.0, 250.0)] {
            let wo = direction(degrees, phi, below);
            let reflection = bsdf.sample(wo, 0.0, Vec2::ZERO).expect("reflects");
            let transmission = bsdf.sample(wo, 0.999_999, Vec2::ZERO).expect("transmits");
            let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
            assert!((reflection.wi - mirror).length() < 1e-6, "{reflection:?}");
            assert_eq!(transmission.wi, -wo, "{transmission:?}");
            for s in [reflection, transmission] {
                assert!(s.is_delta && s.eta == 1.0, "{s:?}");
            }
        }
    }
}

#[test]
fn sample_weights_are_the_specular_multipliers() {
    let reflectance = Vec3::new(0.9, 0.5, 0.2);
    let transmittance = Vec3::new(0.1, 0.6, 0.8);
    let bsdf = pane(1.5, reflectance, transmittance);
    for degrees in [0.0_f32, 40.0, 88.0] {
        let wo = direction(degrees, 0.0, false);
        let r = bsdf.sample(wo, 0.0, Vec2::ZERO).expect("reflects");
        let t = bsdf.sample(wo, 0.999_999, Vec2::ZERO).expect("transmits");
        assert!(
            (weight(&r) - reflectance).abs().max_element() < 1e-5,
            "{r:?}"
        );
        assert!(
            (weight(&t) - transmittance).abs().max_element() < 1e-5,
            "{t:?}"
        );
    }
    // Every direction pair is a delta: nothing to evaluate.
    let (wo, wi) = (direction(30.0, 0.0, false), direction(30.0, 180.0, false));
    assert_eq!(bsdf.eval(wo, wi), Vec3::ZERO);
    assert_eq!(bsdf.pdf_solid_angle(wo, wi), 0.0);
    assert!(
        bsdf.flags().is_delta()
            && bsdf.flags().contains(BsdfFlags::TRANSMISSION)
            && bsdf.flags().contains(BsdfFlags::LOBE_CHOICE)
    );
}

#[test]
fn matched_indices_make_the_pane_invisible_and_grazing_light_reflects() {
    let invisible = pane(1.0, Vec3::ONE, Vec3::ONE);
    let wo = direction(60.0, 45.0, false);
    let s = invisible.sample(wo, 0.0, Vec2::ZERO).expect("transmits");
    assert_eq!((s.wi, s.pdf_solid_angle), (-wo, 1.0));
    // Near grazing the single interface reflects almost everything, and the slab more so.
    let glass = ThinDielectric::new(1.5, 1.0, Vec3::ONE, Vec3::ONE).expect("valid");
    let cos = 89.9_f32.to_radians().cos();
    let (single, slab) = (
        interface_reflectance(f64::from(cos), 1.5),
        glass.reflectance(cos),
    );
    assert!(f64::from(slab) > single && slab < 1.0, "{single} {slab}");
}

#[test]
fn invalid_indices_are_errors() {
    for (int_ior, ext_ior) in [
        (-1.5, 1.0),
        (1.5, 0.0),
        (f32::NAN, 1.0),
        (1.5, f32::INFINITY),
    ] {
        let result = ThinDielectric::new(int_ior, ext_ior, Vec3::ONE, Vec3::ONE);
        assert!(
            matches!(result, Err(MaterialError::InvalidIor { .. })),
            "{int_ior} {ext_ior}: {result:?}"
        );
    }
}
