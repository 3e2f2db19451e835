//! The plastic BSDF: a white base under a clear coating loses no energy (the coating's diffuse
//! transmittance from inside and outside are reciprocal), its diffuse lobe equals Mitsuba's
//! formula with Mitsuba's own fitted diffuse Fresnel reflectance, the lobe choice follows
//! Mitsuba's `specular_sampling_weight`, the specular lobe weighs F · `specular_reflectance`,
//! `nonlinear` changes only the base's internal scattering, and the surface is black from
//! behind. Random choices come from fixed seeds; each count is checked at 5 standard deviations
//! (two-sided p ≈ 6e-7 per count, 12 counts: family-wise below 1e-5).

use glam::{Vec2, Vec3};
use materials::fresnel::fresnel_dielectric;
use materials::{Bsdf, BsdfFlags, MaterialError, Plastic};
use sampling::Rng;
use std::f32::consts::PI;

fn plastic(eta: f32, diffuse: Vec3, specular: Vec3, nonlinear: bool) -> Bsdf {
    Bsdf::from(Plastic::new(eta, 1.0, diffuse, specular, nonlinear).expect("valid ior"))
}

/// The unit direction at `degrees` from +z, turned `phi_degrees` about z.
fn direction(degrees: f32, phi_degrees: f32) -> Vec3 {
    let (theta, phi) = (degrees.to_radians(), phi_degrees.to_radians());
    Vec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

/// ∫ f cos θi dωi over the hemisphere of the diffuse lobe, by the midpoint rule in cos θi
/// (the lobe does not depend on φ).
fn diffuse_albedo(bsdf: &Bsdf, wo: Vec3) -> Vec3 {
    const N: usize = 20_000;
    (0..N)
        .map(|i| {
            let mu = (i as f32 + 0.5) / N as f32;
            let wi = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
            bsdf.eval(wo, wi) * (2.0 * PI * mu / N as f32)
        })
        .sum()
}

/// Mitsuba's `fresnel_diffuse_reflectance` for η < 1 (Egan and Hilgeman's fit), which its
/// `plastic` uses for the coating seen from inside.
fn mitsuba_internal_fdr(eta: f32) -> f32 {
    0.0636 / eta + eta * (eta * -1.4399 + 0.7099) + 0.6681
}

#[test]
fn white_plastic_reflects_all_light() {
    // Specular F(θo) plus the diffuse lobe's albedo: exactly 1 for a white base, at every angle
    // and index, linear or not (with ρ = 1 the two models agree).
    for eta in [1.2_f32, 1.49, 1.9] {
        for nonlinear in [false, true] {
            let bsdf = plastic(eta, Vec3::ONE, Vec3::ONE, nonlinear);
            for degrees in [0.0_f32, 30.0, 60.0, 80.0, 89.0] {
                let wo = direction(degrees, 40.0);
                let fresnel = fresnel_dielectric(wo.z, eta).reflectance;
                let total = Vec3::splat(fresnel) + diffuse_albedo(&bsdf, wo);
                assert!(
                    (total - Vec3::ONE).abs().max_element() < 2e-4,
                    "eta {eta}, nonlinear {nonlinear}, {degrees} degrees: albedo {total}"
                );
            }
        }
    }
}

#[test]
fn diffuse_lobe_is_mitsubas_formula() {
    // f = ρ / (1 − F_dr,int) · (1 − F(θo)) (1 − F(θi)) / (η² π), with Mitsuba's fitted F_dr
    // (within 0.1% of the integral at these indices); nonlinear: ρ / (1 − ρ F_dr,int).
    let rho = Vec3::new(0.8, 0.4, 0.1);
    for eta in [1.33_f32, 1.49] {
        let fdr = mitsuba_internal_fdr(1.0 / eta);
        for nonlinear in [false, true] {
            let bsdf = plastic(eta, rho, Vec3::ONE, nonlinear);
            for (o, i) in [(0.0_f32, 0.0_f32), (30.0, 70.0), (85.0, 10.0)] {
                let (wo, wi) = (direction(o, 0.0), direction(i, 130.0));
                let transmitted = (1.0 - fresnel_dielectric(wo.z, eta).reflectance)
                    * (1.0 - fresnel_dielectric(wi.z, eta).reflectance);
                let base = if nonlinear {
                    rho / (Vec3::ONE - rho * fdr)
                } else {
                    rho / (1.0 - fdr)
                };
                let expected = base * transmitted / (eta * eta * PI);
                let f = bsdf.eval(wo, wi);
                assert!(
                    ((f - expected) / expected).abs().max_element() < 2e-3,
                    "eta {eta}, nonlinear {nonlinear}, wo {o}, wi {i}: {f} against {expected}"
                );
            }
        }
    }
}

#[test]
fn lobe_choice_and_weights_follow_mitsuba() {
    // P(specular) = F w / (F w + (1 − F)(1 − w)), w = mean(specular) / (mean(diffuse) +
    // mean(specular)); the specular sample is the mirror direction with weight
    // F · specular_reflectance / P, the diffuse one has f = eval and pdf = (1 − P) cos θi / π.
    let (eta, diffuse, specular) = (1.49_f32, Vec3::new(0.6, 0.3, 0.3), Vec3::new(0.9, 0.9, 0.6));
    let bsdf = plastic(eta, diffuse, specular, false);
    let w = (specular.element_sum() / 3.0)
        / (diffuse.element_sum() / 3.0 + specular.element_sum() / 3.0);
    let mut rng = Rng::new(23);
    let n = 40_000;
    for degrees in [0.0_f32, 40.0, 70.0, 85.0, 88.0, 89.5] {
        let wo = direction(degrees, 75.0);
        let fresnel = fresnel_dielectric(wo.z, eta).reflectance;
        let p_specular = fresnel * w / (fresnel * w + (1.0 - fresnel) * (1.0 - w));
        let mut specular_count = 0;
        for i in 0..n {
            let (u_lobe, u_dir) = (rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()));
            let s = bsdf
                .sample(wo, u_lobe, u_dir)
                .expect("wo above the surface");
            let replay = format!("{degrees} degrees, sample {i} (seed 23): {s:?}");
            let weight = s.f * s.wi.z / s.pdf_solid_angle;
            if s.is_delta {
                specular_count += 1;
                assert_eq!(s.wi, Vec3::new(-wo.x, -wo.y, wo.z), "{replay}");
                let expected = specular * fresnel / p_specular;
                assert!(
                    ((weight - expected) / expected).abs().max_element() < 1e-4,
                    "{replay}: weight {weight} against {expected}"
                );
            } else {
                let (f, pdf) = bsdf.eval_with_pdf(wo, s.wi);
                assert_eq!((s.f, s.pdf_solid_angle), (f, pdf), "{replay}");
                let expected_pdf = (1.0 - p_specular) * s.wi.z / PI;
                assert!(
                    (pdf - expected_pdf).abs() <= 1e-4 * expected_pdf,
                    "{replay}: pdf {pdf} against {expected_pdf}"
                );
            }
        }
        let expected = f64::from(p_specular) * f64::from(n);
        let sigma = (expected * (1.0 - f64::from(p_specular))).sqrt();
        assert!(
            (f64::from(specular_count) - expected).abs() <= 5.0 * sigma + 1.0,
            "{degrees} degrees: {specular_count} specular of {n}, expected {expected:.0} ± {sigma:.0}"
        );
    }
}

#[test]
fn sampling_estimates_the_albedo() {
    // The mean sample weight is the albedo F(θo) · specular + diffuse albedo (5 sigma per
    // channel and angle; the specular multiplier is tinted so a weight on the wrong lobe shows).
    let (eta, diffuse, specular) = (1.6_f32, Vec3::new(0.2, 0.7, 0.4), Vec3::new(1.0, 0.5, 0.8));
    let bsdf = plastic(eta, diffuse, specular, true);
    let mut rng = Rng::new(29);
    let n = 100_000;
    for degrees in [10.0_f32, 60.0, 86.0] {
        let wo = direction(degrees, 10.0);
        let expected =
            specular * fresnel_dielectric(wo.z, eta).reflectance + diffuse_albedo(&bsdf, wo);
        let (mut sum, mut sum2) = (Vec3::ZERO, Vec3::ZERO);
        for _ in 0..n {
            let (u_lobe, u_dir) = (rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()));
            let s = bsdf
                .sample(wo, u_lobe, u_dir)
                .expect("wo above the surface");
            let weight = s.f * s.wi.z / s.pdf_solid_angle;
            sum += weight;
            sum2 += weight * weight;
        }
        let mean = sum / n as f32;
        let sigma = ((sum2 / n as f32 - mean * mean) / n as f32).map(f32::sqrt);
        assert!(
            ((mean - expected).abs() - 5.0 * sigma).max_element() <= 1e-5,
            "{degrees} degrees (seed 29): {mean} ± {sigma} against {expected}"
        );
    }
}

#[test]
fn delta_lobe_alone_is_the_specular_reflection() {
    let (eta, specular) = (1.49_f32, Vec3::new(0.5, 1.0, 0.25));
    let bsdf = plastic(eta, Vec3::splat(0.5), specular, false);
    for degrees in [0.0_f32, 45.0, 89.0] {
        let wo = direction(degrees, 200.0);
        let s = bsdf.sample_delta(wo, 0.99).expect("wo above the surface");
        assert!(s.is_delta && s.pdf_solid_angle == 1.0, "{s:?}");
        let weight = s.f * s.wi.z / s.pdf_solid_angle;
        let expected = specular * fresnel_dielectric(wo.z, eta).reflectance;
        assert!(
            ((weight - expected) / expected).abs().max_element() < 1e-5,
            "{degrees} degrees: {weight} against {expected}"
        );
    }
    assert!(
        bsdf.flags().contains(BsdfFlags::MIXED)
            && bsdf.flags().contains(BsdfFlags::DELTA)
            && !bsdf.flags().is_delta()
    );
    assert!(
        bsdf.flags().contains(BsdfFlags::LOBE_CHOICE)
            && !bsdf.flags().contains(BsdfFlags::TRANSMISSION)
            && !bsdf.flags().contains(BsdfFlags::GLOSSY)
    );
}

#[test]
fn diffuse_lobe_is_reciprocal() {
    let bsdf = plastic(1.7, Vec3::new(0.3, 0.6, 0.9), Vec3::ONE, true);
    let mut rng = Rng::new(31);
    for i in 0..2_000 {
        let mut random_above = || {
            let w =
                sampling::warp::sample_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
            Vec3::new(w.x, w.y, w.z.abs())
        };
        let (wo, wi) = (random_above(), random_above());
        let (a, b) = (bsdf.eval(wo, wi), bsdf.eval(wi, wo));
        assert!(
            (a - b).abs().max_element() <= 1e-6 * a.max_element(),
            "pair {i} (seed 31): f({wo}, {wi}) = {a}, reversed {b}"
        );
    }
}

#[test]
fn black_from_behind() {
    let bsdf = plastic(1.49, Vec3::splat(0.5), Vec3::ONE, false);
    let below = Vec3::new(0.3, 0.0, -0.9).normalize();
    let above = Vec3::new(-0.2, 0.5, 0.8).normalize();
    assert_eq!(bsdf.sample(below, 0.0, Vec2::splat(0.5)), None);
    assert_eq!(bsdf.sample(below, 0.99, Vec2::splat(0.5)), None);
    assert_eq!(bsdf.sample_delta(below, 0.5), None);
    for (wo, wi) in [(below, above), (above, below), (below, below)] {
        assert_eq!(bsdf.eval_with_pdf(wo, wi), (Vec3::ZERO, 0.0));
    }
}

#[test]
fn equal_indices_leave_the_bare_base() {
    // No coating to speak of: no specular lobe and the base's own Lambertian reflection.
    let rho = Vec3::new(0.9, 0.5, 0.2);
    let bsdf = Bsdf::from(Plastic::new(1.3, 1.3, rho, Vec3::ONE, false).expect("valid ior"));
    let (wo, wi) = (direction(50.0, 0.0), direction(20.0, 90.0));
    assert!(((bsdf.eval(wo, wi) - rho / PI).abs()).max_element() < 1e-7);
    let s = bsdf.sample(wo, 0.0, Vec2::new(0.3, 0.6)).expect("above");
    assert!(!s.is_delta);
}

#[test]
fn invalid_indices_are_errors() {
    for (int_ior, ext_ior, name) in [
        (0.0, 1.0, "int_ior"),
        (f32::NAN, 1.0, "int_ior"),
        (1.5, -1.0, "ext_ior"),
    ] {
        match Plastic::new(int_ior, ext_ior, Vec3::splat(0.5), Vec3::ONE, false) {
            Err(MaterialError::InvalidIor { name: n, .. }) => assert_eq!(n, name),
            other => panic!("{int_ior}/{ext_ior}: {other:?}"),
        }
    }
}

/// `delta_lobes` gives the coat alone, as `sample` gives it when its lobe choice selects the
/// coat, with the probability of that choice: `sample` takes the coat below it and the diffuse
/// lobe above. Nothing from below the surface, where the plastic is black.
#[test]
fn delta_lobes_are_the_coat_with_its_choice_probability() {
    let bsdf = plastic(1.49, Vec3::new(0.2, 0.3, 0.5), Vec3::ONE, false);
    for degrees in [0.0_f32, 40.0, 85.0] {
        let theta = degrees.to_radians();
        let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
        let [coat, none] = bsdf.delta_lobes(wo);
        assert!(none.is_none());
        let coat = coat.expect("a coat above the surface");
        let p = coat.pdf_solid_angle;
        assert!(p > 0.0 && p < 1.0, "{degrees}°: probability {p}");
        assert_eq!(Some(coat), bsdf.sample(wo, 0.5 * p, Vec2::splat(0.3)));
        let above = bsdf
            .sample(wo, p + 0.5 * (1.0 - p), Vec2::splat(0.3))
            .expect("diffuse");
        assert!(
            !above.is_delta,
            "{degrees}°: the choice above {p} took a delta lobe"
        );
    }
    assert_eq!(bsdf.delta_lobes(Vec3::new(0.0, 0.6, -0.8)), [None, None]);
}
