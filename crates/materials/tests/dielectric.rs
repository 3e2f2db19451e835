//! The smooth dielectric: lobe probabilities follow the Fresnel equations, total internal
//! reflection, refraction by Snell's law, Mitsuba's sample weights (with the 1/η² radiance scale)
//! and energy conservation. Random lobe choices come from fixed seeds.

use glam::{Vec2, Vec3};
use materials::fresnel::fresnel_dielectric;
use materials::{Bsdf, BsdfSample, Dielectric, MaterialError};
use sampling::Rng;

fn glass(eta: f32) -> Bsdf {
    Bsdf::from(Dielectric::new(eta, 1.0, Vec3::ONE, Vec3::ONE).expect("valid ior"))
}

/// The unit direction at `degrees` from +z in the xz-plane, flipped below when `inside`.
fn direction(degrees: f32, inside: bool) -> Vec3 {
    let theta = degrees.to_radians();
    let z = if inside { -theta.cos() } else { theta.cos() };
    Vec3::new(theta.sin(), 0.0, z)
}

fn weight(s: &BsdfSample) -> Vec3 {
    s.f * s.wi.z.abs() / s.pdf_solid_angle
}

fn is_reflection(wo: Vec3, s: &BsdfSample) -> bool {
    wo.z * s.wi.z > 0.0
}

/// Reflectance by the textbook s/p amplitude formulas in f64, written independently of the crate.
fn textbook_fresnel(cos_i: f64, n_i: f64, n_t: f64) -> f64 {
    let sin_t = n_i / n_t * (1.0 - cos_i * cos_i).sqrt();
    if sin_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin_t * sin_t).sqrt();
    let r_s = (n_i * cos_i - n_t * cos_t) / (n_i * cos_i + n_t * cos_t);
    let r_p = (n_t * cos_i - n_i * cos_t) / (n_t * cos_i + n_i * cos_t);
    0.5 * (r_s * r_s + r_p * r_p)
}

#[test]
fn lobe_probabilities_are_the_fresnel_reflectance() {
    let eta = 1.5_f32;
    let bsdf = glass(eta);
    let mut rng = Rng::new(3);
    let n = 40_000;
    for inside in [false, true] {
        for degrees in [0.0_f32, 30.0, 40.0, 60.0, 80.0] {
            let wo = direction(degrees, inside);
            let (n_i, n_t) = if inside { (1.5, 1.0) } else { (1.0, 1.5) };
            let expected = textbook_fresnel(f64::from(wo.z.abs()), n_i, n_t);
            let mut reflected = 0usize;
            for _ in 0..n {
                let s = bsdf
                    .sample(wo, rng.next_f32(), Vec2::ZERO)
                    .expect("dielectric always samples");
                let replay = format!("wo {wo}: {s:?}");
                assert!(s.is_delta, "{replay}");
                let lobe_probability = if is_reflection(wo, &s) {
                    reflected += 1;
                    expected
                } else {
                    1.0 - expected
                };
                assert!(
                    (f64::from(s.pdf_solid_angle) - lobe_probability).abs() < 1e-5,
                    "{replay}"
                );
            }
            // Binomial count of reflections: within 5 standard deviations.
            let sigma = (n as f64 * expected * (1.0 - expected)).sqrt();
            let deviation = (reflected as f64 - n as f64 * expected).abs();
            assert!(
                deviation <= 5.0 * sigma + 1.0,
                "{degrees} degrees, inside {inside}: {reflected} of {n} reflected, expected F = {expected}"
            );
        }
    }
}

#[test]
fn normal_incidence_reflectance_is_closed_form() {
    for eta in [1.33_f32, 1.5, 2.4] {
        let expected = ((eta - 1.0) / (eta + 1.0)).powi(2);
        for wo in [Vec3::Z, -Vec3::Z] {
            let s = glass(eta)
                .sample(wo, 0.0, Vec2::ZERO)
                .expect("dielectric always samples");
            assert_eq!(s.wi, wo, "u_lobe = 0 < F picks the reflection");
            assert!(
                (s.pdf_solid_angle - expected).abs() < 1e-6,
                "eta {eta}: {s:?}"
            );
        }
    }
}

#[test]
fn total_internal_reflection_beyond_the_critical_angle() {
    let eta = 1.5_f32;
    let critical_degrees = (1.0 / eta).asin().to_degrees();
    let bsdf = glass(eta);
    for degrees in [critical_degrees + 0.1, 60.0, 89.9] {
        let wo = direction(degrees, true);
        assert_eq!(fresnel_dielectric(wo.z, eta).reflectance, 1.0);
        for u_lobe in [0.0, 0.5, 1.0 - f32::EPSILON / 2.0] {
            let s = bsdf.sample(wo, u_lobe, Vec2::ZERO).expect("TIR reflects");
            assert!(
                is_reflection(wo, &s),
                "{degrees} degrees, u {u_lobe}: {s:?}"
            );
            assert_eq!(s.pdf_solid_angle, 1.0);
            assert!((weight(&s) - Vec3::ONE).abs().max_element() < 1e-5);
            assert_eq!(s.eta, 1.0);
        }
    }
    // Just inside the critical angle, some light still leaves.
    let wo = direction(critical_degrees - 0.5, true);
    let s = bsdf
        .sample(wo, 0.999, Vec2::ZERO)
        .expect("dielectric always samples");
    assert!(!is_reflection(wo, &s), "{s:?}");
}

#[test]
fn nearly_index_matched_interface_transmits_almost_everything() {
    let eta = 1.0001_f32;
    let bsdf = glass(eta);
    for inside in [false, true] {
        for degrees in [0.0, 45.0, 80.0] {
            let wo = direction(degrees, inside);
            let f = fresnel_dielectric(wo.z, eta).reflectance;
            let (n_i, n_t) = if inside { (1.0001, 1.0) } else { (1.0, 1.0001) };
            let textbook = textbook_fresnel(f64::from(wo.z.abs()), n_i, n_t);
            assert!(
                (f64::from(f) - textbook).abs() < 1e-7,
                "{degrees} degrees: F = {f}"
            );
            assert!(f < 1e-5, "{degrees} degrees: F = {f}");
            let s = bsdf
                .sample(wo, 0.5, Vec2::ZERO)
                .expect("dielectric always samples");
            assert!(!is_reflection(wo, &s));
            assert!(s.wi.dot(-wo) > 1.0 - 1e-6, "nearly straight through: {s:?}");
            assert!(s.pdf_solid_angle > 1.0 - 1e-5);
        }
    }
    // Exactly matched: no reflection at all, even for u_lobe = 0.
    let s = glass(1.0)
        .sample(direction(30.0, false), 0.0, Vec2::ZERO)
        .expect("transmits");
    assert_eq!(s.pdf_solid_angle, 1.0);
    assert!((s.wi + direction(30.0, false)).length() < 1e-6);
}

#[test]
fn refraction_obeys_snell_and_reports_the_crossed_index() {
    let eta = 1.5_f32;
    let bsdf = glass(eta);
    for inside in [false, true] {
        for degrees in [10.0_f32, 30.0, 40.0] {
            let wo = direction(degrees, inside);
            let s = bsdf
                .sample(wo, 0.999, Vec2::ZERO)
                .expect("dielectric always samples");
            assert!(!is_reflection(wo, &s), "{s:?}");
            let (n_i, n_t) = if inside { (eta, 1.0) } else { (1.0, eta) };
            let sin_i = degrees.to_radians().sin();
            let sin_t = (s.wi.x * s.wi.x + s.wi.y * s.wi.y).sqrt();
            assert!((n_i * sin_i - n_t * sin_t).abs() < 1e-5, "{s:?}");
            assert!(s.wi.x * wo.x < 0.0, "the refracted ray continues forward");
            assert!(
                (s.eta - n_t / n_i).abs() < 1e-6,
                "eta {} vs {}",
                s.eta,
                n_t / n_i
            );
        }
    }
}

#[test]
fn sample_weights_follow_mitsuba_with_radiance_scaling() {
    let eta = 1.5_f32;
    let reflectance = Vec3::new(0.9, 0.5, 0.2);
    let transmittance = Vec3::new(0.3, 0.6, 1.0);
    let bsdf = Bsdf::from(Dielectric::new(eta, 1.0, reflectance, transmittance).expect("valid"));
    for inside in [false, true] {
        let wo = direction(20.0, inside);
        let reflected = bsdf
            .sample(wo, 0.0, Vec2::ZERO)
            .expect("reflects for u = 0");
        assert!(is_reflection(wo, &reflected));
        assert!((weight(&reflected) - reflectance).abs().max_element() < 1e-5);
        assert_eq!(reflected.eta, 1.0);

        let refracted = bsdf
            .sample(wo, 0.999, Vec2::ZERO)
            .expect("refracts for u near 1");
        assert!(!is_reflection(wo, &refracted));
        // Radiance entering the glass is compressed by 1/η², leaving it expanded by η².
        let scale = if inside { eta * eta } else { 1.0 / (eta * eta) };
        let expected = transmittance * scale;
        assert!(
            (weight(&refracted) - expected).abs().max_element() < 1e-5,
            "inside {inside}: {} vs {expected}",
            weight(&refracted)
        );
    }
}

#[test]
fn reflected_plus_transmitted_energy_is_one() {
    let eta = 1.5_f32;
    let bsdf = glass(eta);
    let mut rng = Rng::new(4);
    for inside in [false, true] {
        for degrees in [0.0_f32, 35.0, 41.0, 70.0, 89.0] {
            let wo = direction(degrees, inside);
            let n = 20_000;
            let (mut energy, mut radiance) = (0.0_f64, 0.0_f64);
            for _ in 0..n {
                let s = bsdf
                    .sample(wo, rng.next_f32(), Vec2::ZERO)
                    .expect("always samples");
                let w = weight(&s);
                assert_eq!(w.x, w.z, "white multipliers give grey weights");
                radiance += f64::from(w.x) / f64::from(n);
                // Undo the radiance scale η_ti² = 1/eta² to count energy.
                let e = if is_reflection(wo, &s) {
                    w.x
                } else {
                    w.x * s.eta * s.eta
                };
                energy += f64::from(e) / f64::from(n);
            }
            assert!(
                (energy - 1.0).abs() < 1e-5,
                "{degrees}, inside {inside}: {energy}"
            );
            // In radiance units the expectation is F + (1 − F) η_ti², computed independently.
            let (n_i, n_t) = if inside { (1.5, 1.0) } else { (1.0, 1.5) };
            let f = textbook_fresnel(f64::from(wo.z.abs()), n_i, n_t);
            let scale = (n_i / n_t).powi(2);
            let expected = f + (1.0 - f) * scale;
            // The lobe choice is random, so the mean is within binomial noise of the expectation.
            let sigma = (f * (1.0 - f) / f64::from(n)).sqrt() * (1.0 - scale).abs();
            assert!(
                (radiance - expected).abs() <= 5.0 * sigma + 1e-5,
                "{degrees}, inside {inside}: {radiance} vs {expected}"
            );
        }
    }
}

#[test]
fn invalid_indices_are_errors() {
    for (int_ior, ext_ior) in [
        (-1.5, 1.0),
        (1.5, 0.0),
        (f32::NAN, 1.0),
        (1.5, f32::INFINITY),
    ] {
        let result = Dielectric::new(int_ior, ext_ior, Vec3::ONE, Vec3::ONE);
        assert!(
            matches!(result, Err(MaterialError::InvalidIor { .. })),
            "{int_ior}/{ext_ior}"
        );
    }
    let defaults = Dielectric::new(
        Dielectric::DEFAULT_INT_IOR,
        Dielectric::DEFAULT_EXT_IOR,
        Vec3::ONE,
        Vec3::ONE,
    )
    .expect("Mitsuba's defaults are valid");
    assert!((defaults.eta() - 1.5046 / 1.000_277).abs() < 1e-6);
}

/// `delta_lobes` lists the lobes `sample` chooses among, as `sample` gives them: reflection with
/// probability R and refraction with 1 − R (their probabilities sum to one), one on each side;
/// beyond the critical angle only the reflection, with probability 1; each equal to what
/// `sample` returns at a lobe choice that selects it.
#[test]
fn delta_lobes_are_the_lobes_sample_chooses_among() {
    let bsdf = glass(1.5);
    for (degrees, inside) in [
        (0.0, false),
        (30.0, false),
        (80.0, false),
        (20.0, true),
        (60.0, true),
    ] {
        let wo = direction(degrees, inside);
        let lobes: Vec<BsdfSample> = bsdf.delta_lobes(wo).into_iter().flatten().collect();
        let total: f32 = lobes.iter().map(|l| l.pdf_solid_angle).sum();
        assert!(
            (total - 1.0).abs() < 1e-5,
            "{degrees}° inside {inside}: probabilities {total}"
        );
        let r = fresnel_dielectric(wo.z, 1.5).reflectance;
        let expected = if r < 1.0 { 2 } else { 1 };
        assert_eq!(
            lobes.len(),
            expected,
            "{degrees}° inside {inside}: {lobes:?}"
        );
        let reflection = lobes
            .iter()
            .find(|l| is_reflection(wo, l))
            .expect("a reflection");
        assert!((reflection.pdf_solid_angle - r).abs() < 1e-6);
        assert_eq!(Some(*reflection), bsdf.sample(wo, 0.5 * r, Vec2::ZERO));
        if let Some(refraction) = lobes.iter().find(|l| !is_reflection(wo, l)) {
            let u = r + 0.5 * (1.0 - r);
            assert_eq!(Some(*refraction), bsdf.sample(wo, u, Vec2::ZERO));
        }
    }
}
