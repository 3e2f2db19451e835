//! Chi-square goodness of fit of every non-delta `Bsdf::sample` against its `pdf_solid_angle`
//! (for a BSDF with a delta lobe too, a plastic, its delta samples count as absorbed),
//! with the shared `sampling::chi2` harness and a fixed seed per case (the harness report, printed
//! on failure, replays it). The family-wise significance level is 0.01 over all [`CASES`] cases of
//! this file, Šidák-corrected by the harness to a per-case level as in Mitsuba's `chi2.py`, so a
//! correct sampler fails somewhere with probability 0.01.
//!
//! The sphere is binned about the +y axis (directions are rotated so that +y becomes the bins'
//! pole): lobes centred in the xz-plane of incidence then sit on the bins' equator, where the
//! bins are narrow in both angles, and the horizon z = 0 falls on bin edges (φ = 0 and ±π).

#[path = "support/fixtures.rs"]
mod fixtures;

use fixtures::{ALPHAS, INCIDENCE_DEGREES, gold, incidence, rough_conductor};
use glam::{Vec2, Vec3};
use materials::{
    Blend, Bsdf, ComplexIor, Diffuse, Microfacet, MicrofacetKind, Plastic, RoughConductor,
    RoughDielectric, RoughPlastic, TwoSided,
};
use sampling::Rng;
use sampling::chi2::{Chi2Config, Chi2Domain, Chi2Outcome, chi2_test};

/// Number of (BSDF, wo) cases tested for goodness of fit in this file.
const CASES: u32 = 43;

/// Family-wise significance level over all cases.
const FAMILY_SIGNIFICANCE: f64 = 0.01;

/// Samples per case.
const SAMPLE_COUNT: u32 = 1_000_000;

/// Rows in cos θ (and half the columns in φ) of the binning grid: 128 × 256 bins, narrow enough
/// (about 0.016 rad) to resolve the α = 0.05 lobes.
const RESOLUTION: u32 = 128;

/// The harness settings of one case: its seed, α = [`FAMILY_SIGNIFICANCE`] shared by [`CASES`] tests.
fn config(seed: u32) -> Chi2Config {
    Chi2Config {
        seed,
        sample_count: SAMPLE_COUNT,
        resolution: RESOLUTION,
        alpha: FAMILY_SIGNIFICANCE,
        test_count: CASES,
        ..Chi2Config::default()
    }
}

/// Rotation taking the local +y axis to the binning pole +z: (x, y, z) ↦ (x, −z, y).
fn to_binning_frame(w: Vec3) -> Vec3 {
    Vec3::new(w.x, -w.z, w.y)
}

/// Inverse of [`to_binning_frame`].
fn from_binning_frame(v: Vec3) -> Vec3 {
    Vec3::new(v.x, v.z, -v.y)
}

/// Runs the chi-square test of `bsdf` at `wo`; returns the outcome for the caller to judge.
fn run(bsdf: &Bsdf, wo: Vec3, seed: u32) -> Chi2Outcome {
    chi2_test(
        Chi2Domain::Sphere,
        |rng: &mut Rng| {
            let u_lobe = rng.next_f32();
            let u_dir = Vec2::new(rng.next_f32(), rng.next_f32());
            bsdf.sample(wo, u_lobe, u_dir)
                .filter(|s| !s.is_delta)
                .map(|s| to_binning_frame(s.wi))
        },
        |v| bsdf.pdf_solid_angle(wo, from_binning_frame(v)),
        &config(seed),
    )
}

/// Asserts that `bsdf` sampled at `wo` matches its pdf, and that the fraction of successful
/// samples matches the pdf's integral (within 5 standard deviations plus quadrature error). The
/// harness tests the absorbed samples too, as one cell among many; this check is sharper.
fn assert_fits(name: &str, bsdf: &Bsdf, wo: Vec3, seed: u32) {
    let outcome = run(bsdf, wo, seed);
    println!("figure: {name}, wo {wo}: {}", outcome.summary());
    assert!(outcome.passed, "{name}, wo {wo}: {outcome}");
    let n = f64::from(outcome.sample_count);
    let valid_fraction = 1.0 - outcome.absorbed_samples as f64 / n;
    let p = outcome.pdf_integral.min(1.0);
    let sigma = (p * (1.0 - p) / n).sqrt();
    assert!(
        (valid_fraction - outcome.pdf_integral).abs() < 5.0 * sigma + 2e-3,
        "{name}, wo {wo}: {valid_fraction} of samples valid but the pdf integrates to {}\n{outcome}",
        outcome.pdf_integral
    );
}

fn check_rough_conductor(kind: MicrofacetKind, alpha: f32, seed_base: u32) {
    // The pdf does not depend on the Fresnel term; a coloured one exercises the full sample path.
    let bsdf = rough_conductor(kind, alpha, gold());
    for (i, degrees) in INCIDENCE_DEGREES.iter().enumerate() {
        let name = format!("{kind:?} alpha {alpha} at {degrees} degrees");
        assert_fits(&name, &bsdf, incidence(*degrees), seed_base + i as u32);
    }
}

#[test]
fn diffuse_sampling_matches_pdf() {
    let bsdf = Bsdf::from(Diffuse::new(Vec3::splat(0.7)));
    for (i, degrees) in INCIDENCE_DEGREES.iter().enumerate() {
        assert_fits(
            &format!("diffuse at {degrees} degrees"),
            &bsdf,
            incidence(*degrees),
            10 + i as u32,
        );
    }
}

#[test]
fn two_sided_diffuse_from_below_matches_pdf() {
    let inner = Bsdf::from(Diffuse::new(Vec3::splat(0.7)));
    let bsdf = Bsdf::from(TwoSided::new(inner).expect("diffuse is reflective"));
    for (i, degrees) in INCIDENCE_DEGREES.iter().enumerate() {
        let above = incidence(*degrees);
        let below = Vec3::new(above.x, above.y, -above.z);
        assert_fits(
            &format!("twosided diffuse at {degrees} degrees below"),
            &bsdf,
            below,
            20 + i as u32,
        );
    }
}

#[test]
fn two_sided_rough_conductor_from_below_matches_pdf() {
    let inner = rough_conductor(MicrofacetKind::Ggx, 0.3, ComplexIor::PERFECT_MIRROR);
    let bsdf = Bsdf::from(TwoSided::new(inner).expect("conductor is reflective"));
    let below = Vec3::new(incidence(45.0).x, 0.0, -incidence(45.0).z);
    assert_fits("twosided GGX 0.3 at 45 degrees below", &bsdf, below, 30);
}

#[test]
fn two_sided_with_a_rough_back_from_below_matches_pdf() {
    let front = Bsdf::from(Diffuse::new(Vec3::splat(0.7)));
    let back = rough_conductor(MicrofacetKind::Beckmann, 0.3, ComplexIor::PERFECT_MIRROR);
    let bsdf = Bsdf::from(TwoSided::with_sides(front, back).expect("both reflect"));
    let below = Vec3::new(incidence(60.0).x, 0.0, -incidence(60.0).z);
    assert_fits(
        "twosided diffuse / Beckmann 0.3 at 60 degrees below",
        &bsdf,
        below,
        31,
    );
}

#[test]
fn plastic_diffuse_lobe_matches_pdf() {
    // At 80 degrees the coating reflects a third of the light and the specular lobe takes
    // over half the samples, so the diffuse lobe's share (1 − P) is tested where it moves.
    let plastic = Plastic::new(1.49, 1.0, Vec3::new(0.7, 0.2, 0.2), Vec3::ONE, false);
    let bsdf = Bsdf::from(plastic.expect("valid ior"));
    for (i, degrees) in [30.0_f32, 80.0].iter().enumerate() {
        assert_fits(
            &format!("plastic at {degrees} degrees"),
            &bsdf,
            incidence(*degrees),
            40 + i as u32,
        );
    }
}

/// A rough dielectric of `kind`, `alpha` and relative index `eta` (clear).
fn rough_glass(kind: MicrofacetKind, alpha: f32, eta: f32) -> Bsdf {
    let distribution = Microfacet::new(kind, alpha).expect("finite roughness");
    let glass = RoughDielectric::new(distribution, eta, 1.0, Vec3::ONE, Vec3::ONE);
    Bsdf::from(glass.expect("valid ior"))
}

#[test]
fn rough_dielectric_sampling_matches_pdf() {
    // Reflection and refraction together over the whole sphere, from outside and from inside
    // (at 60 degrees from inside glass of index 1.5, beyond the critical angle of 41.8 degrees,
    // most microfacets reflect totally), for both distributions.
    let below = |degrees: f32| {
        let w = incidence(degrees);
        Vec3::new(w.x, w.y, -w.z)
    };
    let cases = [
        (
            "GGX 0.3, eta 1.5, 30 degrees above",
            MicrofacetKind::Ggx,
            0.3,
            1.5,
            incidence(30.0),
        ),
        (
            "GGX 0.3, eta 1.5, 60 degrees below",
            MicrofacetKind::Ggx,
            0.3,
            1.5,
            below(60.0),
        ),
        (
            "GGX 0.1, eta 1.33, 80 degrees above",
            MicrofacetKind::Ggx,
            0.1,
            1.33,
            incidence(80.0),
        ),
        (
            "Beckmann 0.1, eta 1.5, 45 degrees above",
            MicrofacetKind::Beckmann,
            0.1,
            1.5,
            incidence(45.0),
        ),
        (
            "Beckmann 0.5, eta 1.5, 20 degrees below",
            MicrofacetKind::Beckmann,
            0.5,
            1.5,
            below(20.0),
        ),
        (
            "Beckmann 0.3, eta 1/1.5, 10 degrees above",
            MicrofacetKind::Beckmann,
            0.3,
            1.0 / 1.5,
            incidence(10.0),
        ),
    ];
    for (i, (name, kind, alpha, eta, wo)) in cases.into_iter().enumerate() {
        assert_fits(name, &rough_glass(kind, alpha, eta), wo, 50 + i as u32);
    }
}

#[test]
fn rough_plastic_sampling_matches_pdf() {
    // The mixture of the glossy and the diffuse lobe, near normal and at a grazing angle where
    // the coating reflects most of the light and the glossy lobe takes most samples.
    for (i, (kind, alpha, degrees)) in [
        (MicrofacetKind::Ggx, 0.2_f32, 30.0_f32),
        (MicrofacetKind::Beckmann, 0.1, 75.0),
    ]
    .into_iter()
    .enumerate()
    {
        let distribution = Microfacet::new(kind, alpha).expect("finite roughness");
        let plastic =
            RoughPlastic::new(distribution, 1.49, 1.0, Vec3::splat(0.4), Vec3::ONE, false);
        assert_fits(
            &format!("{kind:?} {alpha} rough plastic at {degrees} degrees"),
            &Bsdf::from(plastic.expect("valid ior")),
            incidence(degrees),
            60 + i as u32,
        );
    }
}

#[test]
fn blend_sampling_matches_pdf() {
    // A diffuse base blended with a glossy GGX metal (the mixture density), and with a plastic,
    // whose mirror samples count as absorbed.
    let diffuse = || Bsdf::from(Diffuse::new(Vec3::splat(0.5)));
    let glossy = rough_conductor(MicrofacetKind::Ggx, 0.15, ComplexIor::PERFECT_MIRROR);
    let plastic = Plastic::new(1.49, 1.0, Vec3::splat(0.3), Vec3::ONE, false).expect("valid ior");
    let cases = [
        (
            "blend diffuse / GGX 0.15",
            Blend::new(diffuse(), glossy, 0.4),
            45.0_f32,
        ),
        (
            "blend diffuse / plastic",
            Blend::new(diffuse(), Bsdf::from(plastic), 0.6),
            75.0,
        ),
    ];
    for (i, (name, blend, degrees)) in cases.into_iter().enumerate() {
        let bsdf = Bsdf::from(blend.expect("weight in [0, 1]"));
        assert_fits(
            &format!("{name} at {degrees} degrees"),
            &bsdf,
            incidence(degrees),
            70 + i as u32,
        );
    }
}

#[test]
fn anisotropic_roughness_sampling_matches_pdf() {
    // Stretched lobes seen from an azimuth between the two tangents (where neither width is the
    // lobe's), for a conductor of both distributions and for glass from outside and inside.
    let oblique = |degrees: f32, below: bool| {
        let theta = degrees.to_radians();
        let phi = 0.6_f32;
        let z = if below { -theta.cos() } else { theta.cos() };
        Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), z)
    };
    let cases = [
        (MicrofacetKind::Ggx, (0.1, 0.4), None, 40.0, false),
        (MicrofacetKind::Ggx, (0.5, 0.15), None, 75.0, false),
        (MicrofacetKind::Beckmann, (0.4, 0.1), None, 40.0, false),
        (MicrofacetKind::Beckmann, (0.15, 0.5), None, 75.0, false),
        (MicrofacetKind::Ggx, (0.1, 0.4), Some(1.5), 40.0, false),
        (MicrofacetKind::Beckmann, (0.4, 0.15), Some(1.5), 30.0, true),
    ];
    for (i, (kind, (alpha_u, alpha_v), eta, degrees, below)) in cases.into_iter().enumerate() {
        let distribution =
            Microfacet::anisotropic(kind, alpha_u, alpha_v).expect("finite roughness");
        let bsdf = match eta {
            None => Bsdf::from(RoughConductor::new(distribution, gold(), Vec3::ONE)),
            Some(eta) => Bsdf::from(
                RoughDielectric::new(distribution, eta, 1.0, Vec3::ONE, Vec3::ONE)
                    .expect("valid ior"),
            ),
        };
        let name = format!("{kind:?} alpha ({alpha_u}, {alpha_v}), eta {eta:?}, {degrees} degrees");
        assert_fits(&name, &bsdf, oblique(degrees, below), 300 + i as u32);
    }
}

#[test]
fn ggx_alpha_005_sampling_matches_pdf() {
    check_rough_conductor(MicrofacetKind::Ggx, ALPHAS[0], 100);
}

#[test]
fn ggx_alpha_03_sampling_matches_pdf() {
    check_rough_conductor(MicrofacetKind::Ggx, ALPHAS[1], 110);
}

#[test]
fn ggx_alpha_08_sampling_matches_pdf() {
    check_rough_conductor(MicrofacetKind::Ggx, ALPHAS[2], 120);
}

#[test]
fn beckmann_alpha_005_sampling_matches_pdf() {
    check_rough_conductor(MicrofacetKind::Beckmann, ALPHAS[0], 200);
}

#[test]
fn beckmann_alpha_03_sampling_matches_pdf() {
    check_rough_conductor(MicrofacetKind::Beckmann, ALPHAS[1], 210);
}

#[test]
fn beckmann_alpha_08_sampling_matches_pdf() {
    check_rough_conductor(MicrofacetKind::Beckmann, ALPHAS[2], 220);
}

/// The harness must reject samplers that do not match their pdf, or the tests above prove nothing.
#[test]
fn harness_rejects_mismatched_pdfs() {
    let wo = incidence(45.0);
    let sampled = rough_conductor(MicrofacetKind::Ggx, 0.3, ComplexIor::PERFECT_MIRROR);
    let claimed = rough_conductor(MicrofacetKind::Ggx, 0.32, ComplexIor::PERFECT_MIRROR);
    let config = config(7);
    let outcome = chi2_test(
        Chi2Domain::Sphere,
        |rng: &mut Rng| {
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            sampled.sample(wo, 0.5, u).map(|s| to_binning_frame(s.wi))
        },
        |v| claimed.pdf_solid_angle(wo, from_binning_frame(v)),
        &config,
    );
    assert!(
        !outcome.passed && outcome.p_value < config.alpha_corrected(),
        "alpha 0.30 vs 0.32 not detected: {outcome}"
    );
    assert!(outcome.statistic > f64::from(outcome.dof), "{outcome}");

    // Samples where the claimed pdf is zero must fail outright.
    let diffuse = Bsdf::from(Diffuse::new(Vec3::ONE));
    let outcome = chi2_test(
        Chi2Domain::Sphere,
        |rng: &mut Rng| {
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            diffuse
                .sample(wo, 0.5, u)
                .map(|s| Vec3::new(s.wi.x, s.wi.y, -s.wi.z))
        },
        |v| diffuse.pdf_solid_angle(wo, v),
        &config,
    );
    assert!(
        !outcome.passed && outcome.zero_pdf_samples > 0,
        "samples below the horizon not detected: {outcome}"
    );
}
