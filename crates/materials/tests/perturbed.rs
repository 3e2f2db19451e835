//! The `normalmap` and `bumpmap` adapters: their frames, Mitsuba 3.9's flip of normals facing
//! away from `wo`, its side test and shadowing term, energy, and a chi-square goodness of fit of
//! their sampling against their pdf. The chi-square cases share a
//! family-wise significance level of 0.01 over [`CASES`] cases (Šidák-corrected by the harness
//! to a per-case level), with fixed seeds; a deliberately wrong pdf must fail.

use glam::{Affine2, Vec2, Vec3};
use materials::{
    AdapterOptions, BitmapTexture, Bsdf, BsdfFlags, BumpMap, Diffuse, Microfacet, MicrofacetKind,
    NormalMap, RoughConductor, SurfacePoint, TextureFilter, TextureWrap,
};
use sampling::Rng;
use sampling::chi2::{Chi2Config, Chi2Domain, Chi2Outcome, chi2_test};
use std::sync::Arc;

/// Number of chi-square cases in this file.
const CASES: u32 = 9;

/// Family-wise significance level over all cases.
const FAMILY_SIGNIFICANCE: f64 = 0.01;

fn config(seed: u32) -> Chi2Config {
    Chi2Config {
        seed,
        sample_count: 500_000,
        resolution: 64,
        alpha: FAMILY_SIGNIFICANCE,
        test_count: CASES,
        ..Chi2Config::default()
    }
}

/// A 2 × 2 bilinear texture of the given texels (row-major, first row at v = 0).
fn texture(texels: [Vec3; 4]) -> Arc<BitmapTexture> {
    let texture = BitmapTexture::new(
        2,
        2,
        texels.to_vec(),
        TextureFilter::Bilinear,
        TextureWrap::Clamp,
        Affine2::IDENTITY,
    );
    Arc::new(texture.expect("valid texels"))
}

/// A flat, unit-parameterised surface point at the centre of the texture.
fn flat_point() -> SurfacePoint {
    SurfacePoint {
        uv: Vec2::splat(0.5),
        dp_du: Vec3::X,
        dp_dv: Vec3::Y,
        ng: Vec3::Z,
    }
}

/// The RGB a normal map stores for the unit normal `n`.
fn encode(n: Vec3) -> Vec3 {
    (n.normalize() + 1.0) * 0.5
}

/// The tilted normal of the normal-map cases: 30° from +z towards +x and a little +y.
fn tilted() -> Vec3 {
    Vec3::new(0.5, 0.1, 0.86).normalize()
}

/// Neither Mitsuba's flip nor its shadowing term: the nested BSDF seen through the frame alone.
const PLAIN: AdapterOptions = AdapterOptions {
    flip_invalid_normals: false,
    shadowing_function: false,
};

/// `nested` under a normal map that tilts the normal to `n`, at a hit.
fn normal_mapped_to(nested: Bsdf, n: Vec3, options: AdapterOptions) -> Bsdf {
    let map = NormalMap::new(nested, texture([encode(n); 4]), options);
    Bsdf::from(map)
        .at_surface(&flat_point())
        .expect("adapters depend on the surface")
}

/// `nested` under a normal map that tilts the normal to [`tilted`], at a hit, with Mitsuba's
/// default options.
fn normal_mapped(nested: Bsdf) -> Bsdf {
    normal_mapped_to(nested, tilted(), AdapterOptions::default())
}

/// Heights 0, 0.6 (first row) and 0.2, 0.8 (second): a slope in both u and v.
fn slope() -> Arc<BitmapTexture> {
    texture([0.0, 0.6, 0.2, 0.8].map(Vec3::splat))
}

/// `nested` under the bump map [`slope`] scaled by `scale`, at a hit, with Mitsuba's default
/// options.
fn bump_mapped(nested: Bsdf, scale: f32) -> Bsdf {
    bump_mapped_with(nested, scale, AdapterOptions::default())
}

/// `nested` under the bump map [`slope`] scaled by `scale`, at a hit.
fn bump_mapped_with(nested: Bsdf, scale: f32, options: AdapterOptions) -> Bsdf {
    let map = BumpMap::new(nested, slope(), scale, options);
    Bsdf::from(map)
        .at_surface(&flat_point())
        .expect("adapters depend on the surface")
}

fn white_diffuse() -> Bsdf {
    Bsdf::from(Diffuse::new(Vec3::ONE))
}

fn ggx(alpha: f32) -> Bsdf {
    let distribution = Microfacet::new(MicrofacetKind::Ggx, alpha).expect("valid alpha");
    Bsdf::from(RoughConductor::new(
        distribution,
        materials::ComplexIor::PERFECT_MIRROR,
        Vec3::ONE,
    ))
}

/// Unit direction at `degrees` from +z in the xz-plane (towards −x, away from the tilt, so
/// about 30° further from the normal-mapped normal).
fn incidence(degrees: f32) -> Vec3 {
    let theta = degrees.to_radians();
    Vec3::new(-theta.sin(), 0.0, theta.cos())
}

/// Chi-square of `sample`'s directions against `pdf` at `wo`.
fn run(sampled: &Bsdf, claimed: &Bsdf, wo: Vec3, seed: u32) -> Chi2Outcome {
    chi2_test(
        Chi2Domain::Sphere,
        |rng: &mut Rng| {
            let u_lobe = rng.next_f32();
            let u_dir = Vec2::new(rng.next_f32(), rng.next_f32());
            sampled.sample(wo, u_lobe, u_dir).map(|s| s.wi)
        },
        |wi| claimed.pdf_solid_angle(wo, wi),
        &config(seed),
    )
}

#[test]
fn normal_map_sampling_matches_pdf() {
    for (i, (name, bsdf)) in [
        ("diffuse", normal_mapped(white_diffuse())),
        ("GGX 0.3", normal_mapped(ggx(0.3))),
    ]
    .into_iter()
    .enumerate()
    {
        // At 75° `wo` is below the tilted normal: the flipped frame is sampled.
        for (j, degrees) in [20.0, 50.0, 75.0].into_iter().enumerate() {
            let outcome = run(
                &bsdf,
                &bsdf,
                incidence(degrees),
                100 + 10 * i as u32 + j as u32,
            );
            assert!(outcome.passed, "normalmap {name} at {degrees}°: {outcome}");
        }
    }
}

#[test]
fn bump_map_sampling_matches_pdf() {
    for (i, (name, bsdf)) in [
        ("diffuse", bump_mapped(white_diffuse(), 0.5)),
        ("GGX 0.3", bump_mapped(ggx(0.3), 0.5)),
    ]
    .into_iter()
    .enumerate()
    {
        let outcome = run(&bsdf, &bsdf, incidence(60.0), 200 + i as u32);
        assert!(outcome.passed, "bumpmap {name}: {outcome}");
    }
    // The bump normal leans towards −x (see the gradient test): a `wo` 75° towards +x is below
    // it, so the flipped frame is sampled.
    let bsdf = bump_mapped(white_diffuse(), 0.5);
    let wo = Vec3::new(75f32.to_radians().sin(), 0.0, 75f32.to_radians().cos());
    let outcome = run(&bsdf, &bsdf, wo, 210);
    assert!(outcome.passed, "bumpmap diffuse, flipped: {outcome}");
}

/// The test above could not fail if the harness accepted any pdf: claiming the unperturbed
/// diffuse density for the normal-mapped one's samples must be rejected.
#[test]
fn chi_square_rejects_the_unperturbed_pdf() {
    let sampled = normal_mapped(white_diffuse());
    let outcome = run(&sampled, &white_diffuse(), incidence(20.0), 300);
    assert!(!outcome.passed, "unperturbed pdf accepted: {outcome}");
}

#[test]
fn a_flat_normal_map_and_a_flat_bump_map_change_nothing() {
    let nested = ggx(0.3);
    let options = AdapterOptions::default();
    let flat = NormalMap::new(
        nested.clone(),
        texture([Vec3::new(0.5, 0.5, 1.0); 4]),
        options,
    );
    let flat = Bsdf::from(flat).at_surface(&flat_point()).unwrap();
    let level = BumpMap::new(nested.clone(), texture([Vec3::splat(0.3); 4]), 5.0, options);
    let level = Bsdf::from(level).at_surface(&flat_point()).unwrap();
    let (wo, wi) = (incidence(30.0), Vec3::new(0.4, 0.2, 0.8).normalize());
    for bsdf in [&flat, &level] {
        assert_eq!(bsdf.eval_with_pdf(wo, wi), nested.eval_with_pdf(wo, wi));
    }
}

#[test]
fn bump_map_normal_follows_the_height_gradient() {
    // Bilinear heights at the centre: ∂h/∂u = 2 × mean(0.6 − 0, 0.8 − 0.2) = 1.2 and
    // ∂h/∂v = 2 × mean(0.2 − 0, 0.8 − 0.6) = 0.4 (two texels per unit), luminance of grey = grey.
    let gradient = slope().luminance_gradient(Vec2::splat(0.5));
    assert!(
        (gradient - Vec2::new(1.2, 0.4)).abs().max_element() < 1e-5,
        "{gradient}"
    );
    let map = BumpMap::new(white_diffuse(), slope(), 0.5, AdapterOptions::default());
    let n = map.normal(&flat_point());
    let expected = Vec3::new(-0.6, -0.2, 1.0).normalize();
    assert!(
        (n - expected).abs().max_element() < 1e-5,
        "{n} vs {expected}"
    );
    // Turned to the geometric normal's side when the parameterisation is mirrored.
    let mirrored = SurfacePoint {
        dp_dv: -Vec3::Y,
        ..flat_point()
    };
    assert!(map.normal(&mirrored).z > 0.0);
    // Nearest filtering has no gradient (Mitsuba's), so no perturbation.
    let nearest = BitmapTexture::new(
        2,
        2,
        vec![Vec3::ZERO, Vec3::ONE, Vec3::ONE, Vec3::ZERO],
        TextureFilter::Nearest,
        TextureWrap::Repeat,
        Affine2::IDENTITY,
    )
    .unwrap();
    assert_eq!(nearest.luminance_gradient(Vec2::splat(0.3)), Vec2::ZERO);
}

#[test]
fn directions_changing_sides_scatter_nothing() {
    // The tilted normal leans towards +x: a direction just above the shading horizon on the −x
    // side is below the perturbed one, and one just below on the +x side is above it.
    let bsdf = normal_mapped(white_diffuse());
    let wo = Vec3::new(0.3, 0.0, 0.95).normalize();
    let grazing = Vec3::new(-0.99, 0.0, 0.1).normalize();
    assert_eq!(bsdf.eval_with_pdf(wo, grazing), (Vec3::ZERO, 0.0));
    let under = Vec3::new(0.99, 0.0, -0.1).normalize();
    assert_eq!(bsdf.eval_with_pdf(wo, under), (Vec3::ZERO, 0.0));
    // No sample lands on the wrong side of either normal.
    let mut rng = Rng::new(5);
    for _ in 0..10_000 {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        if let Some(s) = bsdf.sample(wo, rng.next_f32(), u) {
            assert!(s.wi.z > 0.0 && s.wi.dot(tilted()) > 0.0, "{s:?}");
        }
    }
}

/// White furnace, without the shadowing term: under a white Lambertian every sample's weight
/// f · |cos θi| / pdf is the nested BSDF's, exactly 1, and agrees with `eval` and `pdf`; the mean
/// weight over all draws (failed draws count 0) is the fraction kept, never above 1: no energy
/// is created, and what Mitsuba's side test removes is lost, not moved.
#[test]
fn white_furnace_weights_are_one_and_energy_is_not_gained() {
    for bsdf in [
        normal_mapped_to(white_diffuse(), tilted(), PLAIN),
        bump_mapped_with(white_diffuse(), 0.5, PLAIN),
    ] {
        assert!(
            bsdf.flags()
                .contains(BsdfFlags::AT_SURFACE | BsdfFlags::DIFFUSE)
        );
        // 40° away from the tilt: about 70° from the perturbed normals.
        let wo = incidence(40.0);
        let mut rng = Rng::new(9);
        let (n, mut total) = (100_000, 0.0_f64);
        for _ in 0..n {
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            let Some(s) = bsdf.sample(wo, rng.next_f32(), u) else {
                continue;
            };
            let weight = s.f * s.wi.z.abs() / s.pdf_solid_angle;
            assert!((weight - Vec3::ONE).abs().max_element() < 1e-4, "{weight}");
            // eval turns the direction back into the perturbed frame: a rounding error of about
            // 1e-7 in the perturbed cosine, which f divides by the shading one.
            let (f, pdf) = bsdf.eval_with_pdf(wo, s.wi);
            let tolerance = 1e-6 / s.wi.z.abs();
            assert!((f - s.f).abs().max_element() <= tolerance, "{f} {s:?}");
            assert!((pdf - s.pdf_solid_angle).abs() <= 1e-6, "{pdf} {s:?}");
            total += f64::from(weight.x);
        }
        let albedo = total / f64::from(n);
        assert!(albedo > 0.8 && albedo <= 1.0, "albedo {albedo}");
    }
}

/// Mitsuba's shadowing term for the normal n and the direction w, both unit, from its formula:
/// 2 / (1 + √(1 + α² tan²θw)), α² = min(tan²θn / 8, 1).
fn shadowing(n: Vec3, w: Vec3) -> f32 {
    let tan2 = |v: Vec3| (1.0 - v.z * v.z) / (v.z * v.z);
    let alpha2 = (0.125 * tan2(n)).min(1.0);
    2.0 / (1.0 + (1.0 + alpha2 * tan2(w)).sqrt())
}

/// With the shadowing term each sample's weight is the nested one times G(wi) (Mitsuba's
/// sample weight), which `eval` agrees with, and the density is unchanged.
#[test]
fn shadowing_scales_weights_by_the_terminator_term() {
    let shadowed = normal_mapped_to(
        white_diffuse(),
        tilted(),
        AdapterOptions {
            flip_invalid_normals: false,
            shadowing_function: true,
        },
    );
    let plain = normal_mapped_to(white_diffuse(), tilted(), PLAIN);
    let wo = incidence(20.0);
    let mut rng = Rng::new(13);
    let mut smallest = 1.0_f32;
    for _ in 0..10_000 {
        let (u_lobe, u) = (rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()));
        let (Some(s), Some(p)) = (shadowed.sample(wo, u_lobe, u), plain.sample(wo, u_lobe, u))
        else {
            continue;
        };
        assert_eq!(s.wi, p.wi);
        assert_eq!(s.pdf_solid_angle, p.pdf_solid_angle);
        let g = shadowing(tilted(), s.wi);
        assert!((s.f - p.f * g).abs().max_element() <= 1e-6 * p.f.max_element());
        let (f, pdf) = shadowed.eval_with_pdf(wo, s.wi);
        assert!(
            (f - s.f).abs().max_element() <= 1e-6 / s.wi.z.abs(),
            "{f} {s:?}"
        );
        assert_eq!(pdf, shadowed.pdf_solid_angle(wo, s.wi));
        smallest = smallest.min(g);
    }
    // Grazing directions are shadowed noticeably (α² = tan²30° / 8 ≈ 0.04).
    assert!(smallest < 0.9, "{smallest}");
}

/// Mitsuba's flip: where `wo` is below the perturbed normal (−nx, −ny, nz) is used instead, so
/// the adapter equals a normal map of the mirrored normal there, and is not black; without the
/// flip a diffuse nested BSDF sees `wo` from below and scatters nothing.
#[test]
fn normals_facing_away_from_wo_are_flipped() {
    let n = tilted();
    let mirrored = Vec3::new(-n.x, -n.y, n.z);
    let flipping = normal_mapped_to(
        white_diffuse(),
        n,
        AdapterOptions {
            flip_invalid_normals: true,
            shadowing_function: false,
        },
    );
    let mirrored_map = normal_mapped_to(white_diffuse(), mirrored, PLAIN);
    let not_flipping = normal_mapped_to(white_diffuse(), n, PLAIN);
    // 75° towards −x: about 105° from the tilted normal, 45° from the mirrored one.
    let wo = incidence(75.0);
    assert!(wo.dot(n) < 0.0 && wo.dot(mirrored) > 0.0);
    let wi = Vec3::new(0.3, 0.4, 0.8).normalize();
    let flipped = flipping.eval_with_pdf(wo, wi);
    assert!(flipped.0.max_element() > 0.0 && flipped.1 > 0.0);
    assert_eq!(flipped, mirrored_map.eval_with_pdf(wo, wi));
    assert_eq!(not_flipping.eval_with_pdf(wo, wi).0, Vec3::ZERO);
    // Above the tilted normal nothing is flipped.
    let wo = incidence(-20.0);
    assert_eq!(
        flipping.eval_with_pdf(wo, wi),
        not_flipping.eval_with_pdf(wo, wi)
    );
}

/// The map's normal is relative to Mitsuba's shading frame, whose first tangent is ∂p/∂u made
/// perpendicular to the shading normal, not to the local frame's arbitrary tangents: with ∂p/∂u
/// along local +y (and a normal part, which does not count), a texel tilting towards the
/// tangent tilts the normal towards +y.
#[test]
fn normal_map_tangents_follow_dp_du() {
    let map = NormalMap::new(
        white_diffuse(),
        texture([encode(tilted()); 4]),
        AdapterOptions::default(),
    );
    let point = SurfacePoint {
        dp_du: Vec3::new(0.0, 2.0, 0.7),
        dp_dv: Vec3::new(-1.0, 0.0, 0.0),
        ..flat_point()
    };
    let n = map.normal(&point);
    // tilted() = (0.5, 0.1, 0.86) in (s, t, n) = (+y, −x, +z).
    let expected = Vec3::new(-0.1, 0.5, 0.86).normalize();
    assert!(
        (n - expected).abs().max_element() < 1e-5,
        "{n} vs {expected}"
    );
    assert!((map.normal(&flat_point()) - tilted()).abs().max_element() < 1e-5);
}
