//! The blend BSDF: at weight 0 and 1 it is its first and second BSDF, in between their linear
//! blend; its samples of a delta lobe come as often as the blend's share of it and keep the
//! lobe's weight, so a blend of lossless BSDFs is lossless sample by sample; the delta lobes
//! alone weigh their share. Random numbers come from fixed seeds; the lobe counts are checked at
//! 5 standard deviations (two-sided p ≈ 6e-7 each, 4 counts).

use glam::{Vec2, Vec3};
use materials::{
    Blend, Bsdf, BsdfFlags, ComplexIor, Conductor, Diffuse, MaterialError, Microfacet,
    MicrofacetKind, RoughConductor,
};
use sampling::Rng;

fn mirror() -> Bsdf {
    Bsdf::from(Conductor::new(ComplexIor::PERFECT_MIRROR, Vec3::ONE))
}

fn glossy() -> Bsdf {
    let distribution = Microfacet::new(MicrofacetKind::Ggx, 0.3).expect("finite roughness");
    Bsdf::from(RoughConductor::new(
        distribution,
        ComplexIor::PERFECT_MIRROR,
        Vec3::new(1.0, 0.8, 0.6),
    ))
}

fn direction(degrees: f32, phi: f32) -> Vec3 {
    let (t, p) = (degrees.to_radians(), phi.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

#[test]
fn blend_is_linear_in_its_weight() {
    let diffuse = Bsdf::from(Diffuse::new(Vec3::new(0.7, 0.3, 0.1)));
    let (wo, wi) = (direction(30.0, 0.0), direction(40.0, 170.0));
    let (f0, p0) = diffuse.eval_with_pdf(wo, wi);
    let (f1, p1) = glossy().eval_with_pdf(wo, wi);
    for weight in [0.0_f32, 0.25, 0.5, 1.0] {
        let blend = Bsdf::from(Blend::new(diffuse.clone(), glossy(), weight).expect("valid"));
        let (f, p) = blend.eval_with_pdf(wo, wi);
        let (fe, pe) = (
            f0 * (1.0 - weight) + f1 * weight,
            p0 * (1.0 - weight) + p1 * weight,
        );
        assert!(
            (f - fe).abs().max_element() <= 1e-6 * fe.max_element(),
            "{weight}: {f} {fe}"
        );
        assert!((p - pe).abs() <= 1e-6 * pe, "{weight}: {p} {pe}");
    }
    let first = Bsdf::from(Blend::new(diffuse.clone(), glossy(), 0.0).expect("valid"));
    assert_eq!(first.eval(wo, wi), diffuse.eval(wo, wi));
    let second = Bsdf::from(Blend::new(diffuse, glossy(), 1.0).expect("valid"));
    assert_eq!(second.eval(wo, wi), glossy().eval(wo, wi));
}

#[test]
fn delta_lobe_comes_as_often_as_its_share_and_keeps_its_weight() {
    // White diffuse and a perfect mirror, both lossless: every sample's weight is exactly 1,
    // and the mirror is sampled with probability 1 − w.
    let mut rng = Rng::new(91);
    let n = 40_000;
    for weight in [0.2_f32, 0.7] {
        let white = Bsdf::from(Diffuse::new(Vec3::ONE));
        let blend = Bsdf::from(Blend::new(mirror(), white, weight).expect("valid"));
        assert!(
            blend.flags().contains(BsdfFlags::DELTA)
                && blend.flags().contains(BsdfFlags::MIXED)
                && !blend.flags().is_delta()
        );
        for degrees in [10.0_f32, 70.0] {
            let wo = direction(degrees, 30.0);
            let mut mirrored = 0;
            for i in 0..n {
                let (u_lobe, u_dir) = (rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()));
                let s = blend.sample(wo, u_lobe, u_dir).expect("wo above");
                let w = s.f * s.wi.z / s.pdf_solid_angle;
                assert!(
                    (w - Vec3::ONE).abs().max_element() < 1e-4,
                    "weight {weight}, {degrees} degrees, sample {i} (seed 91): {s:?} weighs {w}"
                );
                if s.is_delta {
                    mirrored += 1;
                    assert_eq!(s.wi, Vec3::new(-wo.x, -wo.y, wo.z));
                }
            }
            let expected = f64::from(1.0 - weight) * f64::from(n);
            let sigma = (expected * f64::from(weight)).sqrt();
            assert!(
                (f64::from(mirrored) - expected).abs() <= 5.0 * sigma,
                "weight {weight}, {degrees} degrees: {mirrored} mirror samples, expected {expected}"
            );
        }
        let alone = blend
            .sample_delta(direction(50.0, 0.0), 0.5)
            .expect("a mirror lobe");
        let w = alone.f * alone.wi.z / alone.pdf_solid_angle;
        assert!(
            (w - Vec3::splat(1.0 - weight)).abs().max_element() < 1e-5,
            "{w}"
        );
    }
}

#[test]
fn two_deltas_blend_into_a_delta() {
    let tinted = Bsdf::from(Conductor::new(ComplexIor::PERFECT_MIRROR, Vec3::splat(0.5)));
    let blend = Bsdf::from(Blend::new(mirror(), tinted, 0.5).expect("valid"));
    assert!(blend.flags().is_delta());
    let wo = direction(20.0, 0.0);
    let mut rng = Rng::new(92);
    let mut total = Vec3::ZERO;
    let n = 10_000;
    for _ in 0..n {
        let s = blend
            .sample(wo, rng.next_f32(), Vec2::ZERO)
            .expect("wo above");
        assert!(s.is_delta);
        total += s.f * s.wi.z / s.pdf_solid_angle;
    }
    // Half the samples weigh 1, half 0.5: the mean is 0.75 within the binomial's noise.
    let mean = total / n as f32;
    assert!((mean - Vec3::splat(0.75)).abs().max_element() < 5.0 * 0.25 / (n as f32).sqrt());
}

#[test]
fn weight_outside_the_unit_interval_is_an_error() {
    for weight in [-0.1_f32, 1.5, f32::NAN] {
        match Blend::new(mirror(), glossy(), weight) {
            Err(MaterialError::InvalidBlendWeight { .. }) => {}
            other => panic!("weight {weight}: {other:?}"),
        }
    }
}
