//! Properties every BSDF must have: `sample` agrees with `eval`/`pdf_solid_angle`, energy is
//! conserved (white furnace), reflection is reciprocal, one-sided BSDFs are black from behind,
//! and extreme inputs give no NaN or infinity. Random inputs come from fixed seeds.

#[path = "support/fixtures.rs"]
mod fixtures;

use fixtures::{ALPHAS, INCIDENCE_DEGREES, gold, incidence, rough_conductor};
use glam::{Vec2, Vec3};
use materials::LOBE_WEIGHT_FLOOR;
use materials::fresnel::{fresnel_conductor, reflect};
use materials::{
    Blend, Bsdf, BsdfFlags, BsdfSample, ComplexIor, Conductor, Dielectric, Diffuse, Microfacet,
    MicrofacetKind, Plastic, RoughDielectric, RoughPlastic, ThinDielectric, TwoSided,
};
use sampling::Rng;
use sampling::warp::{sample_uniform_sphere, uniform_sphere_pdf};

fn two_sided(inner: Bsdf) -> Bsdf {
    Bsdf::from(TwoSided::new(inner).expect("test BSDF is reflective"))
}

/// The non-delta BSDFs with a name, including rough conductors of both kinds at every test alpha.
fn non_delta_bsdfs() -> Vec<(String, Bsdf)> {
    let mut all = vec![
        (
            "diffuse".to_string(),
            Bsdf::from(Diffuse::new(Vec3::new(0.2, 0.5, 0.9))),
        ),
        (
            "twosided diffuse".to_string(),
            two_sided(Bsdf::from(Diffuse::new(Vec3::new(0.2, 0.5, 0.9)))),
        ),
    ];
    for kind in [MicrofacetKind::Ggx, MicrofacetKind::Beckmann] {
        for alpha in ALPHAS {
            all.push((
                format!("{kind:?} {alpha} gold"),
                rough_conductor(kind, alpha, gold()),
            ));
        }
        all.push((
            format!("twosided {kind:?} 0.3 gold"),
            two_sided(rough_conductor(kind, 0.3, gold())),
        ));
        let distribution = Microfacet::new(kind, 0.2).expect("finite roughness");
        let rough_plastic = RoughPlastic::new(
            distribution,
            1.49,
            1.0,
            Vec3::new(0.8, 0.3, 0.1),
            Vec3::new(1.0, 0.9, 0.8),
            kind == MicrofacetKind::Ggx,
        )
        .expect("valid ior");
        all.push((
            format!("{kind:?} 0.2 rough plastic"),
            Bsdf::from(rough_plastic),
        ));
        all.push((
            format!("twosided diffuse / {kind:?} 0.3 gold"),
            Bsdf::from(
                TwoSided::with_sides(
                    Bsdf::from(Diffuse::new(Vec3::new(0.2, 0.5, 0.9))),
                    rough_conductor(kind, 0.3, gold()),
                )
                .expect("both sides reflect"),
            ),
        ));
    }
    all
}

/// Every BSDF, delta or not, including near-delta rough conductors (alpha 1e-4).
fn all_bsdfs() -> Vec<(String, Bsdf)> {
    let mut all = non_delta_bsdfs();
    for kind in [MicrofacetKind::Ggx, MicrofacetKind::Beckmann] {
        all.push((
            format!("{kind:?} 1e-4 gold"),
            rough_conductor(kind, 1e-4, gold()),
        ));
    }
    let mirror = Bsdf::from(Conductor::new(ComplexIor::PERFECT_MIRROR, Vec3::ONE));
    all.push(("mirror".to_string(), mirror.clone()));
    all.push(("twosided mirror".to_string(), two_sided(mirror)));
    all.push((
        "gold conductor".to_string(),
        Bsdf::from(Conductor::new(gold(), Vec3::ONE)),
    ));
    let glass = Dielectric::new(1.5, 1.0, Vec3::ONE, Vec3::ONE).expect("valid ior");
    all.push(("glass".to_string(), Bsdf::from(glass)));
    let pane = ThinDielectric::new(1.5, 1.0, Vec3::ONE, Vec3::ONE).expect("valid ior");
    all.push(("thin glass".to_string(), Bsdf::from(pane)));
    let plastic = Bsdf::from(
        Plastic::new(1.49, 1.0, Vec3::new(0.9, 0.4, 0.1), Vec3::ONE, true).expect("valid ior"),
    );
    for kind in [MicrofacetKind::Ggx, MicrofacetKind::Beckmann] {
        for (alpha, eta) in [(0.05, 1.5), (0.3, 1.0 / 1.33), (0.8, 2.4), (1e-4, 1.5)] {
            let distribution = Microfacet::new(kind, alpha).expect("finite roughness");
            let rough_glass = RoughDielectric::new(distribution, eta, 1.0, Vec3::ONE, Vec3::ONE)
                .expect("valid ior");
            all.push((
                format!("rough glass {kind:?} {alpha} eta {eta}"),
                Bsdf::from(rough_glass),
            ));
        }
    }
    let mirror_blend = Blend::new(
        Bsdf::from(Diffuse::new(Vec3::splat(0.6))),
        Bsdf::from(Conductor::new(ComplexIor::PERFECT_MIRROR, Vec3::ONE)),
        0.7,
    )
    .expect("weight in [0, 1]");
    all.push((
        "blend diffuse / mirror".to_string(),
        Bsdf::from(mirror_blend),
    ));
    let glass_blend = Blend::new(
        Bsdf::from(Dielectric::new(1.5, 1.0, Vec3::ONE, Vec3::ONE).expect("valid ior")),
        Bsdf::from(Conductor::new(ComplexIor::PERFECT_MIRROR, Vec3::ONE)),
        0.25,
    )
    .expect("weight in [0, 1]");
    all.push(("blend glass / mirror".to_string(), Bsdf::from(glass_blend)));
    all.push(("plastic".to_string(), plastic.clone()));
    all.push(("twosided plastic".to_string(), two_sided(plastic.clone())));
    all.push((
        "twosided plastic / diffuse".to_string(),
        Bsdf::from(
            TwoSided::with_sides(plastic, Bsdf::from(Diffuse::new(Vec3::splat(0.5))))
                .expect("both sides reflect"),
        ),
    ));
    all
}

/// A random unit direction, uniform over the sphere.
fn random_direction(rng: &mut Rng) -> Vec3 {
    sample_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()))
}

/// A random unit direction (uniform over the sphere), flipped into the upper hemisphere.
fn random_upper_direction(rng: &mut Rng) -> Vec3 {
    let w = random_direction(rng);
    Vec3::new(w.x, w.y, w.z.abs())
}

fn random_u(rng: &mut Rng) -> (f32, Vec2) {
    (rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()))
}

/// The estimator weight f · |cos θi| / pdf of a sample.
fn weight(s: &BsdfSample) -> Vec3 {
    s.f * s.wi.z.abs() / s.pdf_solid_angle
}

fn close(a: f32, b: f32, relative: f32) -> bool {
    (a - b).abs() <= relative * a.abs().max(b.abs()) + 1e-12
}

#[test]
fn lobe_weights_are_positive_everywhere_and_peak_at_the_mirror_direction() {
    // Given only by glossy BSDFs (a twosided one on its glossy side), and then at least the
    // floor in every direction (RIS needs a positive target wherever a light may contribute);
    // for a rough conductor much larger towards the mirror direction than 80 degrees away from
    // it, and within a factor of the true f cos θi there (F and G are left out, both at
    // most 1).
    let mut rng = Rng::new(43);
    for (name, bsdf) in all_bsdfs() {
        let mut given = 0;
        for i in 0..1_000 {
            let (wo, wi) = (random_direction(&mut rng), random_direction(&mut rng));
            let Some(weight) = bsdf.lobe_weight(wo, wi) else {
                continue;
            };
            given += 1;
            assert!(
                bsdf.flags().contains(BsdfFlags::GLOSSY)
                    && weight >= LOBE_WEIGHT_FLOOR
                    && weight.is_finite(),
                "{name}, pair {i} (seed 43), wo {wo}, wi {wi}: {weight}"
            );
        }
        assert_eq!(
            given > 0,
            bsdf.flags().contains(BsdfFlags::GLOSSY),
            "{name}: {given} of 1000 given"
        );
    }
    for alpha in [0.05, 0.2] {
        let bsdf = rough_conductor(MicrofacetKind::Ggx, alpha, gold());
        let wo = incidence(40.0);
        let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
        // Back towards the viewer: 80 degrees from the mirror direction.
        let away = wo;
        let (at_mirror, at_away) = (
            bsdf.lobe_weight(wo, mirror).expect("glossy"),
            bsdf.lobe_weight(wo, away).expect("glossy"),
        );
        assert!(
            at_mirror > 20.0 * at_away,
            "alpha {alpha}: {at_mirror} vs {at_away}"
        );
        let f_cos = bsdf.eval(wo, mirror) * mirror.z;
        let f_cos = (f_cos.x + f_cos.y + f_cos.z) / 3.0;
        assert!(
            f_cos <= at_mirror && at_mirror < 3.0 * f_cos,
            "alpha {alpha}: lobe weight {at_mirror}, f cos {f_cos}"
        );
    }
}

#[test]
fn eval_with_pdf_is_eval_and_pdf_to_the_bit() {
    // Directions over the whole sphere (above, below, grazing), so every early return is taken.
    let mut rng = Rng::new(41);
    for (name, bsdf) in all_bsdfs() {
        for i in 0..2_000 {
            let (wo, wi) = (random_direction(&mut rng), random_direction(&mut rng));
            let (f, pdf) = bsdf.eval_with_pdf(wo, wi);
            let (f_alone, pdf_alone) = (bsdf.eval(wo, wi), bsdf.pdf_solid_angle(wo, wi));
            assert!(
                f.to_array().map(f32::to_bits) == f_alone.to_array().map(f32::to_bits)
                    && pdf.to_bits() == pdf_alone.to_bits(),
                "{name}, pair {i} (seed 41), wo {wo}, wi {wi}: ({f}, {pdf}) against \
                 ({f_alone}, {pdf_alone})"
            );
        }
    }
}

#[test]
fn sample_value_and_pdf_equal_eval_and_pdf() {
    let mut rng = Rng::new(2024);
    for (name, bsdf) in non_delta_bsdfs() {
        let mut sampled = 0;
        for trial in 0..20_000 {
            let mut wo = random_upper_direction(&mut rng);
            if name.starts_with("twosided") && trial % 2 == 1 {
                wo.z = -wo.z;
            }
            let (u_lobe, u_dir) = random_u(&mut rng);
            let Some(s) = bsdf.sample(wo, u_lobe, u_dir) else {
                continue;
            };
            sampled += 1;
            let replay = format!("{name}: wo {wo}, u_lobe {u_lobe}, u_dir {u_dir}, sample {s:?}");
            assert!(!s.is_delta, "{replay}");
            assert_eq!(s.eta, 1.0, "{replay}");
            let f = bsdf.eval(wo, s.wi);
            for c in 0..3 {
                assert!(close(s.f[c], f[c], 2e-3), "{replay}: eval {f}");
            }
            let pdf = bsdf.pdf_solid_angle(wo, s.wi);
            assert!(close(s.pdf_solid_angle, pdf, 2e-3), "{replay}: pdf {pdf}");
            assert!(
                s.wi.z * wo.z > 0.0,
                "{replay}: reflection must stay on wo's side"
            );
        }
        assert!(
            sampled > 15_000,
            "{name}: only {sampled} of 20000 samples succeeded"
        );
    }
}

#[test]
fn delta_bsdfs_have_zero_eval_and_pdf() {
    let mut rng = Rng::new(5);
    for (name, bsdf) in all_bsdfs()
        .into_iter()
        .filter(|(_, b)| b.flags().is_delta())
    {
        assert!(bsdf.flags().contains(BsdfFlags::DELTA), "{name}");
        for _ in 0..1000 {
            let wo = random_upper_direction(&mut rng);
            let (u_lobe, u_dir) = random_u(&mut rng);
            let s = bsdf
                .sample(wo, u_lobe, u_dir)
                .expect("delta BSDFs reflect every wo above");
            assert!(s.is_delta, "{name}");
            assert_eq!(bsdf.eval(wo, s.wi), Vec3::ZERO, "{name}");
            assert_eq!(bsdf.pdf_solid_angle(wo, s.wi), 0.0, "{name}");
        }
    }
}

/// Mean and standard error of `n` samples of an RGB estimator (per channel).
fn mean_and_error(n: usize, mut estimate: impl FnMut() -> Vec3) -> (Vec3, Vec3) {
    let (mut sum, mut sum2) = (Vec3::ZERO, Vec3::ZERO);
    for _ in 0..n {
        let x = estimate();
        sum += x;
        sum2 += x * x;
    }
    let mean = sum / n as f32;
    let variance = (sum2 / n as f32 - mean * mean).max(Vec3::ZERO);
    (mean, (variance / n as f32).map(f32::sqrt))
}

/// ∫ f cos θi dωi estimated through `sample` (importance sampling). Transmitted samples are
/// divided by the radiance scale η_ti² = 1 / eta², so the result is the energy scattered.
fn furnace_by_sampling(bsdf: &Bsdf, wo: Vec3, n: usize, rng: &mut Rng) -> (Vec3, Vec3) {
    mean_and_error(n, || {
        let (u_lobe, u_dir) = random_u(rng);
        match bsdf.sample(wo, u_lobe, u_dir) {
            Some(s) if s.wi.z * wo.z < 0.0 => weight(&s) * s.eta * s.eta,
            Some(s) => weight(&s),
            None => Vec3::ZERO,
        }
    })
}

/// ∫ f cos θi dωi estimated through `eval` with uniformly distributed directions.
fn furnace_by_eval(bsdf: &Bsdf, wo: Vec3, n: usize, rng: &mut Rng) -> (Vec3, Vec3) {
    mean_and_error(n, || {
        let wi = sample_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
        bsdf.eval(wo, wi) * wi.z.abs() / uniform_sphere_pdf()
    })
}

#[test]
fn white_furnace_conserves_energy() {
    let mut rng = Rng::new(77);
    for (name, bsdf) in all_bsdfs() {
        for degrees in [0.0, 45.0, 85.0, 89.0] {
            let wo = incidence(degrees);
            let (mean, error) = furnace_by_sampling(&bsdf, wo, 20_000, &mut rng);
            assert!(
                mean.max_element() <= 1.0 + 5.0 * error.max_element() + 1e-4,
                "{name} at {degrees} degrees: albedo {mean} ± {error} exceeds 1"
            );
        }
    }
}

#[test]
fn white_furnace_is_exactly_one_for_lossless_bsdfs() {
    let mut rng = Rng::new(78);
    let lossless = [
        ("white diffuse", Bsdf::from(Diffuse::new(Vec3::ONE))),
        (
            "twosided white diffuse",
            two_sided(Bsdf::from(Diffuse::new(Vec3::ONE))),
        ),
        (
            "mirror",
            Bsdf::from(Conductor::new(ComplexIor::PERFECT_MIRROR, Vec3::ONE)),
        ),
        (
            "glass",
            Bsdf::from(Dielectric::new(1.5, 1.0, Vec3::ONE, Vec3::ONE).expect("valid ior")),
        ),
        (
            "thin glass",
            Bsdf::from(ThinDielectric::new(1.5, 1.0, Vec3::ONE, Vec3::ONE).expect("valid ior")),
        ),
    ];
    for (name, bsdf) in lossless {
        for degrees in INCIDENCE_DEGREES {
            let above = incidence(degrees);
            for wo in [above, Vec3::new(above.x, above.y, -above.z)] {
                if wo.z < 0.0 && !name.starts_with("twosided") && !name.ends_with("glass") {
                    continue;
                }
                let (mean, _) = furnace_by_sampling(&bsdf, wo, 10_000, &mut rng);
                assert!(
                    (mean - Vec3::ONE).abs().max_element() < 1e-4,
                    "{name} at wo {wo}: albedo {mean}"
                );
            }
        }
    }
    // The same for diffuse through eval, which does not share code with sample.
    let white = Bsdf::from(Diffuse::new(Vec3::ONE));
    let (mean, error) = furnace_by_eval(&white, incidence(30.0), 200_000, &mut rng);
    assert!(
        (mean - Vec3::ONE).abs().max_element() < 5.0 * error.max_element(),
        "diffuse via eval: {mean} ± {error}"
    );
}

/// ∫ f cos by `eval` and by `sample` are independent estimates of the same albedo.
#[test]
fn albedo_by_eval_agrees_with_albedo_by_sampling() {
    let mut rng = Rng::new(79);
    for kind in [MicrofacetKind::Ggx, MicrofacetKind::Beckmann] {
        for alpha in [0.3, 0.8] {
            let bsdf = rough_conductor(kind, alpha, gold());
            for degrees in INCIDENCE_DEGREES {
                let wo = incidence(degrees);
                let (a, ea) = furnace_by_sampling(&bsdf, wo, 100_000, &mut rng);
                let (b, eb) = furnace_by_eval(&bsdf, wo, 400_000, &mut rng);
                let bound = 5.0 * (ea * ea + eb * eb).map(f32::sqrt);
                assert!(
                    (a - b).abs().cmple(bound).all(),
                    "{kind:?} {alpha} at {degrees} degrees: sampled {a} ± {ea}, eval {b} ± {eb}"
                );
            }
        }
    }
}

#[test]
fn smooth_rough_conductor_loses_little_energy() {
    // Single-scattering microfacet models lose energy to masking, but little when smooth.
    let mut rng = Rng::new(80);
    for kind in [MicrofacetKind::Ggx, MicrofacetKind::Beckmann] {
        let bsdf = rough_conductor(kind, 0.05, ComplexIor::PERFECT_MIRROR);
        let (mean, _) = furnace_by_sampling(&bsdf, incidence(30.0), 20_000, &mut rng);
        assert!(mean.min_element() > 0.99, "{kind:?} 0.05: albedo {mean}");
        let rough = rough_conductor(kind, 0.8, ComplexIor::PERFECT_MIRROR);
        let (rough_mean, _) = furnace_by_sampling(&rough, incidence(30.0), 20_000, &mut rng);
        assert!(
            rough_mean.max_element() < mean.min_element(),
            "{kind:?}: rough {rough_mean}"
        );
    }
}

#[test]
fn reflection_is_reciprocal() {
    let mut rng = Rng::new(11);
    let bsdfs: Vec<_> = non_delta_bsdfs()
        .into_iter()
        .filter(|(name, _)| !name.starts_with("twosided"))
        .collect();
    for (name, bsdf) in bsdfs {
        for _ in 0..5_000 {
            let wo = random_upper_direction(&mut rng);
            let wi = random_upper_direction(&mut rng);
            let (a, b) = (bsdf.eval(wo, wi), bsdf.eval(wi, wo));
            for c in 0..3 {
                assert!(
                    close(a[c], b[c], 1e-4),
                    "{name}: f({wo}, {wi}) = {a}, f({wi}, {wo}) = {b}"
                );
            }
        }
    }
}

#[test]
fn one_sided_bsdfs_are_black_from_behind() {
    let mut rng = Rng::new(12);
    let one_sided = all_bsdfs().into_iter().filter(|(name, b)| {
        !name.starts_with("twosided") && !b.flags().contains(BsdfFlags::TRANSMISSION)
    });
    for (name, bsdf) in one_sided {
        for _ in 0..500 {
            let above = random_upper_direction(&mut rng);
            let below = Vec3::new(above.x, above.y, -above.z);
            let other = random_upper_direction(&mut rng);
            let (u_lobe, u_dir) = random_u(&mut rng);
            assert!(
                bsdf.sample(below, u_lobe, u_dir).is_none(),
                "{name}: sampled from below"
            );
            assert_eq!(bsdf.eval(below, other), Vec3::ZERO, "{name}");
            assert_eq!(
                bsdf.eval(above, Vec3::new(other.x, other.y, -other.z)),
                Vec3::ZERO,
                "{name}"
            );
            assert_eq!(bsdf.pdf_solid_angle(below, other), 0.0, "{name}");
        }
    }
}

#[test]
fn two_sided_mirrors_the_inner_bsdf_below_the_surface() {
    let mut rng = Rng::new(13);
    let inner = rough_conductor(MicrofacetKind::Ggx, 0.3, gold());
    let bsdf = two_sided(inner.clone());
    let flip = |w: Vec3| Vec3::new(w.x, w.y, -w.z);
    for _ in 0..1000 {
        let wo = random_upper_direction(&mut rng);
        let wi = random_upper_direction(&mut rng);
        assert_eq!(bsdf.eval(wo, wi), inner.eval(wo, wi));
        assert_eq!(bsdf.eval(flip(wo), flip(wi)), inner.eval(wo, wi));
        assert_eq!(
            bsdf.pdf_solid_angle(flip(wo), flip(wi)),
            inner.pdf_solid_angle(wo, wi)
        );
        assert_eq!(
            bsdf.eval(flip(wo), wi),
            Vec3::ZERO,
            "no transmission through twosided"
        );
        let (u_lobe, u_dir) = random_u(&mut rng);
        let below = bsdf.sample(flip(wo), u_lobe, u_dir);
        let above = inner.sample(wo, u_lobe, u_dir);
        assert_eq!(below.map(|s| flip(s.wi)), above.map(|s| s.wi));
    }
    let glass = Dielectric::new(1.5, 1.0, Vec3::ONE, Vec3::ONE).expect("valid ior");
    assert!(TwoSided::new(Bsdf::from(glass)).is_err());
    assert!(
        two_sided(Bsdf::from(Conductor::new(gold(), Vec3::ONE)))
            .flags()
            .is_delta()
    );
}

/// Mitsuba's `twosided` with two BSDFs: the front one above the surface, the back one
/// (mirrored) below; delta only where a delta side is seen.
#[test]
fn two_sided_with_two_bsdfs_uses_the_back_one_below_the_surface() {
    let mut rng = Rng::new(15);
    let front = Bsdf::from(Diffuse::new(Vec3::new(0.2, 0.5, 0.9)));
    let back = rough_conductor(MicrofacetKind::Beckmann, 0.2, gold());
    let bsdf = Bsdf::from(TwoSided::with_sides(front.clone(), back.clone()).expect("reflective"));
    let flip = |w: Vec3| Vec3::new(w.x, w.y, -w.z);
    for _ in 0..1000 {
        let wo = random_upper_direction(&mut rng);
        let wi = random_upper_direction(&mut rng);
        assert_eq!(bsdf.eval(wo, wi), front.eval(wo, wi));
        assert_eq!(bsdf.pdf_solid_angle(wo, wi), front.pdf_solid_angle(wo, wi));
        assert_eq!(bsdf.eval(flip(wo), flip(wi)), back.eval(wo, wi));
        assert_eq!(
            bsdf.pdf_solid_angle(flip(wo), flip(wi)),
            back.pdf_solid_angle(wo, wi)
        );
        let (u_lobe, u_dir) = random_u(&mut rng);
        assert_eq!(
            bsdf.sample(flip(wo), u_lobe, u_dir).map(|s| flip(s.wi)),
            back.sample(wo, u_lobe, u_dir).map(|s| s.wi)
        );
        assert_eq!(
            bsdf.sample(wo, u_lobe, u_dir).map(|s| s.wi),
            front.sample(wo, u_lobe, u_dir).map(|s| s.wi)
        );
    }
    let mirror = Bsdf::from(Conductor::new(gold(), Vec3::ONE));
    let mixed = TwoSided::with_sides(front.clone(), mirror.clone()).expect("reflective");
    assert!(!Bsdf::from(mixed.clone()).flags().is_delta());
    assert!(Bsdf::from(mixed.clone()).flags().contains(BsdfFlags::DELTA));
    assert_eq!(mixed.facing(Vec3::Z).0, &front);
    assert_eq!(mixed.facing(Vec3::NEG_Z), (&mirror, true));
    let glass = Bsdf::from(Dielectric::new(1.5, 1.0, Vec3::ONE, Vec3::ONE).expect("valid ior"));
    assert!(TwoSided::with_sides(front, glass).is_err());
}

#[test]
fn near_zero_roughness_approaches_the_smooth_conductor() {
    let smooth = Bsdf::from(Conductor::new(gold(), Vec3::ONE));
    for kind in [MicrofacetKind::Ggx, MicrofacetKind::Beckmann] {
        let rough = rough_conductor(kind, 1e-4, gold());
        let mut rng = Rng::new(14);
        for degrees in [0.0, 30.0, 60.0, 80.0] {
            let wo = incidence(degrees);
            let mirror = smooth
                .sample(wo, 0.5, Vec2::splat(0.5))
                .expect("mirror reflects");
            let (mut near_mirror, mut mean_weight) = (0, Vec3::ZERO);
            for _ in 0..1000 {
                let (u_lobe, u_dir) = random_u(&mut rng);
                let s = rough
                    .sample(wo, u_lobe, u_dir)
                    .unwrap_or_else(|| panic!("{kind:?} at {degrees}: u {u_dir} gave no sample"));
                let replay = format!("{kind:?} at {degrees} degrees, u {u_dir}: {s:?}");
                assert!(s.f.is_finite() && s.pdf_solid_angle.is_finite(), "{replay}");
                assert!(weight(&s).max_element() <= 1.0, "{replay}");
                mean_weight += weight(&s) / 1000.0;
                // Within 0.01 rad of the mirror direction; GGX's long tail leaves a few out.
                if s.wi.dot(reflect(wo)) > (0.01_f32).cos() {
                    near_mirror += 1;
                }
            }
            let difference = (mean_weight - weight(&mirror)).abs().max_element();
            assert!(
                difference < 2e-3,
                "{kind:?} at {degrees}: mean weight {mean_weight}, mirror {}",
                weight(&mirror)
            );
            assert!(
                near_mirror >= 990,
                "{kind:?} at {degrees}: {near_mirror} of 1000 near the mirror"
            );
        }
    }
    let expected = fresnel_conductor(1.0, gold());
    let normal = smooth
        .sample(Vec3::Z, 0.0, Vec2::ZERO)
        .expect("mirror reflects");
    assert!((weight(&normal) - expected).abs().max_element() < 1e-6);
}

/// Directions at which numerical trouble is likely: normal, grazing, exactly tangent, below.
fn extreme_directions() -> Vec<Vec3> {
    let mut dirs = vec![
        Vec3::Z,
        Vec3::new(1.0, 0.0, 1e-6).normalize(),
        Vec3::new(0.6, 0.8, 1e-6).normalize(),
        Vec3::new(1e-6, 0.0, 1.0).normalize(),
        Vec3::X,
        incidence(89.99),
    ];
    let below: Vec<Vec3> = dirs.iter().map(|w| Vec3::new(w.x, w.y, -w.z)).collect();
    dirs.extend(below);
    dirs
}

#[test]
fn extreme_inputs_give_finite_results() {
    let edge = [0.0, 0.5, 1.0 - f32::EPSILON / 2.0];
    let dirs = extreme_directions();
    for (name, bsdf) in all_bsdfs() {
        for &wo in &dirs {
            for &u_lobe in &edge {
                for &ux in &edge {
                    for &uy in &edge {
                        let u_dir = Vec2::new(ux, uy);
                        let replay = format!("{name}: wo {wo}, u_lobe {u_lobe}, u_dir {u_dir}");
                        if let Some(s) = bsdf.sample(wo, u_lobe, u_dir) {
                            assert!(
                                s.f.is_finite() && s.f.min_element() >= 0.0,
                                "{replay}: {s:?}"
                            );
                            assert!(
                                s.pdf_solid_angle.is_finite() && s.pdf_solid_angle > 0.0,
                                "{replay}: {s:?}"
                            );
                            assert!((s.wi.length() - 1.0).abs() < 1e-4, "{replay}: {s:?}");
                            assert!(weight(&s).is_finite(), "{replay}: {s:?}");
                            assert!(s.eta.is_finite() && s.eta > 0.0, "{replay}: {s:?}");
                        }
                    }
                }
            }
            for &wi in &dirs {
                let f = bsdf.eval(wo, wi);
                let pdf = bsdf.pdf_solid_angle(wo, wi);
                let replay = format!("{name}: wo {wo}, wi {wi}");
                assert!(f.is_finite() && f.min_element() >= 0.0, "{replay}: f {f}");
                assert!(pdf.is_finite() && pdf >= 0.0, "{replay}: pdf {pdf}");
            }
        }
    }
}

#[test]
fn albedo_hints_match_simple_cases() {
    let diffuse = Bsdf::from(Diffuse::new(Vec3::new(0.1, 0.2, 0.3)));
    assert_eq!(diffuse.albedo_hint(), Vec3::new(0.1, 0.2, 0.3));
    let mirror = Bsdf::from(Conductor::new(ComplexIor::PERFECT_MIRROR, Vec3::splat(0.5)));
    assert!(
        (mirror.albedo_hint() - Vec3::splat(0.5))
            .abs()
            .max_element()
            < 1e-6
    );
    let glass = Bsdf::from(Dielectric::new(1.5, 1.0, Vec3::ONE, Vec3::ONE).expect("valid ior"));
    assert!((glass.albedo_hint() - Vec3::ONE).abs().max_element() < 1e-6);
    let distr = Microfacet::new(MicrofacetKind::Beckmann, 0.2).expect("finite alpha");
    let gold_rough = Bsdf::from(materials::RoughConductor::new(distr, gold(), Vec3::ONE));
    assert!(
        (gold_rough.albedo_hint() - fresnel_conductor(1.0, gold()))
            .abs()
            .max_element()
            < 1e-6
    );
    assert_eq!(
        two_sided(diffuse.clone()).albedo_hint(),
        diffuse.albedo_hint()
    );
}
