//! Chi-square goodness of fit of `Light::sample_li` directions against `pdf_li_surface` and
//! `pdf_li_environment` (densities per steradian over wi), and of `LightSelector::select` against
//! its `pmf`, with the shared `sampling::chi2` harness.
//!
//! The surface pdfs take the point of the light a direction hits; the tests find it by tracing wi
//! from the shading point in f64 and pass every hit's point and geometric normal (as the shape
//! reports it: flipped for `flip_normals`). `sample_li` ignores occlusion, so a direction that hits
//! a mesh twice has the sum of both points' densities (the meshes here are planar: one hit at most).
//! A `None` sample (a back-facing point) is absorbed mass, tested against 1 − ∫ pdf.
//!
//! The distant sphere's cone (half-angle 0.005 rad) is far narrower than any affordable bin, so it is
//! tested in a frame whose pole is the cone's axis, with polar angles magnified by [`FAR_ZOOM`]
//! (θ' = k θ) and the pdf multiplied by the Jacobian dω/dω' = sin θ / (k sin θ').
//!
//! Fixed seeds; α = 0.01 over the [`CASES`] cases of this file, Šidák-corrected by the harness. A
//! failure prints the harness report (seed, counts, worst bins) to replay it.

use glam::Mat3;
use glam::{DVec3, Vec2, Vec3};
use lights::{
    ConstantEnvironment, EnvironmentMap, Light, LightSelection, LightSelector, MeshAreaLight,
    PointLight, SphereAreaLight,
};
use sampling::Rng;
use sampling::chi2::{Chi2Config, Chi2Domain, chi2_discrete, chi2_test};
use std::f64::consts::PI;

/// Number of chi-square tests in this file, sharing the family-wise significance level.
const CASES: u32 = 10;

/// Family-wise significance level over all cases.
const FAMILY_SIGNIFICANCE: f64 = 0.01;

/// Polar-angle magnification for the distant sphere: its 0.005 rad cone becomes 1 rad wide.
const FAR_ZOOM: f64 = 200.0;

fn config(seed: u32, sample_count: u32, resolution: u32) -> Chi2Config {
    Chi2Config {
        seed,
        sample_count,
        resolution,
        alpha: FAMILY_SIGNIFICANCE,
        test_count: CASES,
        ..Chi2Config::default()
    }
}

fn u2(rng: &mut Rng) -> Vec2 {
    Vec2::new(rng.next_f32(), rng.next_f32())
}

/// The direction of a light sample from `p`, or `None` when `sample_li` returned none.
fn sample_wi(light: &Light, p: Vec3, rng: &mut Rng) -> Option<Vec3> {
    light.sample_li(p, u2(rng), 0.0).map(|s| s.wi)
}

/// Runs a sphere-domain test of `light` sampled from `p` against `pdf(wi)` and asserts it passes.
fn assert_fits(name: &str, light: &Light, p: Vec3, pdf: impl Fn(Vec3) -> f32, config: &Chi2Config) {
    let outcome = chi2_test(
        Chi2Domain::Sphere,
        |rng| sample_wi(light, p, rng),
        pdf,
        config,
    );
    println!("figure: {name}: {}", outcome.summary());
    assert!(outcome.passed, "{name}: {outcome}");
}

/// Where the ray from `p` along `wi` (any length) first meets the sphere of `center` and `radius`
/// at t > 0 (entering from outside, leaving from inside), with the outward unit normal there.
fn hit_sphere(p: Vec3, wi: DVec3, center: Vec3, radius: f64) -> Option<(Vec3, Vec3)> {
    let (o, d) = (p.as_dvec3() - center.as_dvec3(), wi.normalize());
    let b = o.dot(d);
    let discriminant = b * b - (o.length_squared() - radius * radius);
    if discriminant < 0.0 {
        return None;
    }
    let root = discriminant.sqrt();
    let t = [-b - root, -b + root].into_iter().find(|&t| t > 0.0)?;
    let outward = (o + t * d).normalize();
    let point = center.as_dvec3() + radius * outward;
    Some((point.as_vec3(), outward.as_vec3()))
}

/// `pdf_li_surface` of the sphere light at the point wi hits, or 0 where it misses. The sphere is
/// traced with its radius scaled by 1 + `rim_slack`.
fn sphere_pdf(light: &Light, sphere: &SphereAreaLight, p: Vec3, wi: DVec3, rim_slack: f64) -> f32 {
    let radius = f64::from(sphere.radius) * (1.0 + rim_slack);
    hit_sphere(p, wi, sphere.center, radius).map_or(0.0, |(point, outward)| {
        let normal = if sphere.flip_normals {
            -outward
        } else {
            outward
        };
        light.pdf_li_surface(p, point, normal, 0.0)
    })
}

/// The sum of `pdf_li_surface` over every point of `triangles` the ray from `p` along wi hits
/// (Möller–Trumbore in f64), each with its triangle's geometric normal (p1 − p0) × (p2 − p0).
fn mesh_pdf(light: &Light, triangles: &[[Vec3; 3]], p: Vec3, wi: Vec3) -> f32 {
    let (o, d) = (p.as_dvec3(), wi.as_dvec3());
    triangles
        .iter()
        .filter_map(|t| {
            let [p0, p1, p2] = t.map(Vec3::as_dvec3);
            let (e1, e2) = (p1 - p0, p2 - p0);
            let q = d.cross(e2);
            let det = e1.dot(q);
            if det.abs() < 1e-12 {
                return None;
            }
            let s = o - p0;
            let u = s.dot(q) / det;
            let r = s.cross(e1);
            let v = d.dot(r) / det;
            let t = e2.dot(r) / det;
            let inside = u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0;
            inside.then(|| {
                let normal = e1.cross(e2).normalize().as_vec3();
                light.pdf_li_surface(p, (o + t * d).as_vec3(), normal, 0.0)
            })
        })
        .sum()
}

/// The two triangles of the square centred at `c` with half-edges `u` and `v` (orthogonal, of
/// equal length), both facing u × v.
fn square(c: Vec3, u: Vec3, v: Vec3) -> Vec<[Vec3; 3]> {
    vec![
        [c - u - v, c + u - v, c + u + v],
        [c - u - v, c + u + v, c - u + v],
    ]
}

#[test]
fn sphere_light_near_outside_matches_pdf() {
    // Radius 1 at distance 1.5: a cone of half-angle 41.8°, resolved by the default grid.
    let p = Vec3::new(0.3, -0.2, 0.1);
    let sphere = SphereAreaLight {
        center: p + 1.5 * Vec3::new(1.0, -2.0, 2.0).normalize(),
        radius: 1.0,
        flip_normals: false,
        radiance: Vec3::ONE,
    };
    let light = Light::Sphere(sphere);
    assert_fits(
        "sphere radius 1 at distance 1.5",
        &light,
        p,
        |wi| sphere_pdf(&light, &sphere, p, wi.as_dvec3(), 0.0),
        &config(1, 500_000, 32),
    );
}

/// Magnifies the polar angle of the unit `w` about +z by `zoom`; NaN (outside the test's domain)
/// where the magnified angle would pass π.
fn magnify(w: DVec3, zoom: f64) -> Vec3 {
    let r = w.x.hypot(w.y);
    let theta = zoom * r.atan2(w.z);
    if theta > PI {
        return Vec3::NAN;
    }
    let (x, y) = if r > 0.0 {
        (w.x / r, w.y / r)
    } else {
        (1.0, 0.0)
    };
    DVec3::new(x * theta.sin(), y * theta.sin(), theta.cos()).as_vec3()
}

/// The inverse of [`magnify`], with the Jacobian dω / dω' = sin θ / (zoom · sin θ') of the map.
fn demagnify(w: Vec3, zoom: f64) -> (DVec3, f64) {
    let w = w.as_dvec3();
    let r = w.x.hypot(w.y);
    let theta_zoomed = r.atan2(w.z);
    let theta = theta_zoomed / zoom;
    let (x, y) = if r > 0.0 {
        (w.x / r, w.y / r)
    } else {
        (1.0, 0.0)
    };
    let jacobian = if theta_zoomed > 1e-9 {
        theta.sin() / (zoom * theta_zoomed.sin())
    } else {
        1.0 / (zoom * zoom)
    };
    (
        DVec3::new(x * theta.sin(), y * theta.sin(), theta.cos()),
        jacobian,
    )
}

/// How much the distant sphere is enlarged when the test traces it: f32 directions are rounded by
/// about 6e-8 rad, 1.2e-5 of its cone's half-angle, so that a few of 500 000 samples land a hair
/// outside the exact cone. The slack adds 2e-4 to the pdf's integral, spread over the rim bins.
const FAR_RIM_SLACK: f64 = 1e-4;

#[test]
fn sphere_light_far_outside_matches_pdf_in_a_magnified_cone_frame() {
    // Radius 0.05 at distance 10: half-angle 0.005 rad, 1 rad after magnification by FAR_ZOOM.
    let p = Vec3::new(-1.0, 0.5, 2.0);
    let axis = Vec3::new(2.0, 1.0, -2.0).normalize();
    let sphere = SphereAreaLight {
        center: p + 10.0 * axis,
        radius: 0.05,
        flip_normals: false,
        radiance: Vec3::ONE,
    };
    let light = Light::Sphere(sphere);
    // An orthonormal frame (s, t, n) about the cone's axis, in f64 so that the test adds no rounding.
    let n = axis.as_dvec3().normalize();
    let (s, t) = n.any_orthonormal_pair();
    let outcome = chi2_test(
        Chi2Domain::Sphere,
        |rng| {
            sample_wi(&light, p, rng).map(|wi| {
                let wi = wi.as_dvec3();
                magnify(DVec3::new(wi.dot(s), wi.dot(t), wi.dot(n)), FAR_ZOOM)
            })
        },
        |w| {
            let (local, jacobian) = demagnify(w, FAR_ZOOM);
            let wi = local.x * s + local.y * t + local.z * n;
            (f64::from(sphere_pdf(&light, &sphere, p, wi, FAR_RIM_SLACK)) * jacobian) as f32
        },
        &config(2, 500_000, 32),
    );
    assert!(
        outcome.passed,
        "sphere radius 0.05 at distance 10: {outcome}"
    );
}

#[test]
fn sphere_light_seen_from_inside_matches_pdf() {
    // Inside an inward-emitting sphere, off centre so that the density varies with direction.
    let sphere = SphereAreaLight {
        center: Vec3::new(0.1, -0.2, 0.3),
        radius: 2.0,
        flip_normals: true,
        radiance: Vec3::ONE,
    };
    let p = sphere.center + Vec3::new(1.2, 0.6, -0.5);
    let light = Light::Sphere(sphere);
    assert_fits(
        "inward sphere from inside",
        &light,
        p,
        |wi| sphere_pdf(&light, &sphere, p, wi.as_dvec3(), 0.0),
        &config(3, 500_000, 32),
    );
}

#[test]
fn square_mesh_light_at_an_oblique_angle_matches_pdf() {
    // A unit square 1.2 away along +x, tilted 60° from facing the shading point.
    let p = Vec3::ZERO;
    let (s, c) = 60.0_f32.to_radians().sin_cos();
    let triangles = square(
        Vec3::new(1.2, 0.0, 0.0),
        Vec3::new(0.0, 0.5, 0.0),
        0.5 * Vec3::new(s, 0.0, -c),
    );
    assert!(
        (triangles[0][1] - triangles[0][0])
            .cross(triangles[0][2] - triangles[0][0])
            .dot(p - triangles[0][0])
            > 0.0,
        "the square's front faces the shading point"
    );
    let light =
        Light::Mesh(MeshAreaLight::new(triangles.clone(), Vec3::ONE).expect("the square has area"));
    assert_fits(
        "square mesh light",
        &light,
        p,
        |wi| mesh_pdf(&light, &triangles, p, wi),
        &config(4, 500_000, 32),
    );
}

#[test]
fn triangle_fan_light_with_a_back_facing_triangle_matches_pdf() {
    // A planar fan of five unequal triangles in a plane tilted 50°; the third is wound backwards, so
    // its samples face away and are absorbed (`None`), a known part of the mass.
    let p = Vec3::new(-0.3, 0.2, 0.1);
    let centre = Vec3::new(1.0, -0.3, 0.4);
    let (s, c) = 50.0_f32.to_radians().sin_cos();
    let (u, v) = (Vec3::Y, Vec3::new(s, 0.0, -c));
    let rim: Vec<Vec3> = [
        (0.0, 0.8),
        (50.0, 0.5),
        (80.0, 0.9),
        (150.0, 0.6),
        (220.0, 0.7),
        (300.0, 0.4),
    ]
    .into_iter()
    .map(|(degrees, radius): (f32, f32)| {
        let (sin, cos) = degrees.to_radians().sin_cos();
        centre + radius * (cos * u + sin * v)
    })
    .collect();
    let triangles: Vec<[Vec3; 3]> = (0..5)
        .map(|i| {
            if i == 2 {
                [centre, rim[i + 1], rim[i]]
            } else {
                [centre, rim[i], rim[i + 1]]
            }
        })
        .collect();
    assert!(
        u.cross(v).dot(p - centre) > 0.0,
        "the fan's front faces the shading point"
    );
    let light =
        Light::Mesh(MeshAreaLight::new(triangles.clone(), Vec3::ONE).expect("the fan has area"));
    let outcome = chi2_test(
        Chi2Domain::Sphere,
        |rng| sample_wi(&light, p, rng),
        |wi| mesh_pdf(&light, &triangles, p, wi),
        &config(5, 500_000, 32),
    );
    assert!(outcome.passed, "triangle fan: {outcome}");
    assert!(
        outcome.absorbed_samples > 10_000 && outcome.pdf_integral < 0.98,
        "the back-facing triangle absorbs samples: {outcome}"
    );
}

#[test]
fn constant_environment_matches_pdf() {
    let light = Light::Environment(ConstantEnvironment {
        radiance: Vec3::splat(0.5),
        scene_radius: 3.0,
    });
    let p = Vec3::new(4.0, -2.0, 1.0);
    assert_fits(
        "constant environment",
        &light,
        p,
        |wi| light.pdf_li_environment(wi),
        &config(6, 200_000, 16),
    );
}

/// A 16 × 9 map: a dim sky with a bright 1-texel sun, a black band and a brighter horizon row.
fn sky_texels() -> Vec<Vec3> {
    let (w, h) = (16, 9);
    (0..w * h)
        .map(|k| {
            let (i, j) = (k / w, k % w);
            match (i, j) {
                (2, 11) => Vec3::new(40.0, 35.0, 30.0),
                (6, _) => Vec3::ZERO,
                (4, _) => Vec3::new(1.0, 0.8, 0.6),
                _ => Vec3::new(0.1, 0.2, 0.4 + 0.02 * j as f32),
            }
        })
        .collect()
}

#[test]
fn environment_map_matches_pdf() {
    // The map's own frame and a rotated one (a quarter turn about x and a tilt about y), so
    // that the poles and the seam at u = 0 lie where the sphere's bins do not expect them.
    let rotated = Mat3::from_rotation_y(0.4) * Mat3::from_rotation_x(std::f32::consts::FRAC_PI_2);
    for (i, (name, to_world)) in [
        ("environment map", Mat3::IDENTITY),
        ("rotated map", rotated),
    ]
    .into_iter()
    .enumerate()
    {
        let map = EnvironmentMap::new(16, 9, &sky_texels(), 1.5, to_world, 2.0).expect("valid");
        let light = Light::EnvironmentMap(map);
        assert_fits(
            name,
            &light,
            Vec3::new(1.0, 2.0, -3.0),
            |wi| light.pdf_li_environment(wi),
            &config(11 + i as u32, 1_000_000, 64),
        );
    }
}

/// Lights whose powers span nearly three orders of magnitude (0.06 W to 49 W), one of them black (power 0).
fn lights_of_varying_power() -> Vec<Light> {
    let sphere = |radius: f32, radiance: f32| {
        Light::Sphere(SphereAreaLight {
            center: Vec3::ZERO,
            radius,
            flip_normals: false,
            radiance: Vec3::splat(radiance),
        })
    };
    let quad = square(Vec3::Z, 0.5 * Vec3::X, 0.5 * Vec3::Y);
    vec![
        sphere(0.5, 1.0),
        sphere(0.1, 20.0),
        Light::Mesh(MeshAreaLight::new(quad, Vec3::new(1.0, 3.0, 5.0)).expect("unit square")),
        Light::Point(PointLight {
            position: Vec3::ONE,
            intensity: Vec3::splat(0.005),
        }),
        sphere(1.0, 0.0),
        Light::Environment(ConstantEnvironment {
            radiance: Vec3::splat(0.2),
            scene_radius: 5.0,
        }),
    ]
}

/// Checks `selector`'s pmf against `expected`, and its `select` against its pmf by chi-square.
fn assert_selects(name: &str, selector: &LightSelector, expected: &[f64], seed: u32) {
    for (i, &e) in expected.iter().enumerate() {
        let pmf = f64::from(selector.pmf(i));
        assert!(
            (pmf - e).abs() <= 1e-6 * e.max(1e-3),
            "{name}: pmf({i}) = {pmf}, expected {e}"
        );
    }
    let outcome = chi2_discrete(
        expected.len(),
        |rng| {
            let (index, probability) = selector.select(rng.next_f32());
            assert_eq!(
                probability,
                selector.pmf(index),
                "{name}: select's probability"
            );
            Some(index)
        },
        |i| f64::from(selector.pmf(i)),
        &config(seed, 1_000_000, 1), // The resolution is unused by chi2_discrete.
    );
    println!("figure: {name}: {}", outcome.summary());
    assert!(outcome.passed, "{name}: {outcome}");
}

#[test]
fn power_selection_matches_its_pmf_and_is_proportional_to_power() {
    let lights = lights_of_varying_power();
    let powers: Vec<f64> = lights.iter().map(|l| f64::from(l.power())).collect();
    assert_eq!(powers[4], 0.0, "the black sphere has no power");
    let total: f64 = powers.iter().sum();
    let expected: Vec<f64> = powers.iter().map(|p| p / total).collect();
    let selector = LightSelector::new(&lights, &vec![1.0; lights.len()], LightSelection::Power)
        .expect("lights exist");
    assert_selects("power selection", &selector, &expected, 7);
}

#[test]
fn uniform_selection_matches_its_pmf() {
    let lights = lights_of_varying_power();
    let expected = vec![1.0 / lights.len() as f64; lights.len()];
    let selector = LightSelector::new(&lights, &vec![1.0; lights.len()], LightSelection::Uniform)
        .expect("lights exist");
    assert_selects("uniform selection", &selector, &expected, 8);
}

/// Selection weights (Mitsuba's `sampling_weight`) multiply the pmf: alone with uniform
/// selection, times power with power selection.
#[test]
fn selection_weights_scale_the_pmf() {
    let lights = lights_of_varying_power();
    let weights: Vec<f32> = (0..lights.len()).map(|i| 1.0 + 2.0 * i as f32).collect();
    let normalise = |values: Vec<f64>| {
        let total: f64 = values.iter().sum();
        values.into_iter().map(|v| v / total).collect::<Vec<f64>>()
    };
    let by_weight = normalise(weights.iter().map(|&w| f64::from(w)).collect());
    let selector =
        LightSelector::new(&lights, &weights, LightSelection::Uniform).expect("lights exist");
    assert_selects("uniform selection, weighted", &selector, &by_weight, 9);
    let by_power = normalise(
        lights
            .iter()
            .zip(&weights)
            .map(|(l, &w)| f64::from(l.power()) * f64::from(w))
            .collect(),
    );
    let selector =
        LightSelector::new(&lights, &weights, LightSelection::Power).expect("lights exist");
    assert_selects("power selection, weighted", &selector, &by_power, 10);
}

/// A light of weight 0 (one light sampling leaves to BSDF samples) is never chosen and has pmf
/// 0, in every mode; the others keep their proportions; with no light of positive weight there
/// is no selector.
#[test]
fn lights_of_weight_zero_are_never_selected() {
    let lights = lights_of_varying_power();
    let skipped = 1;
    let weights: Vec<f32> = (0..lights.len())
        .map(|i| if i == skipped { 0.0 } else { 1.0 })
        .collect();
    let sampled: Vec<u32> = (0..lights.len() as u32)
        .filter(|&i| i as usize != skipped)
        .collect();
    let uniform: Vec<f64> = (0..lights.len())
        .map(|i| {
            if i == skipped {
                0.0
            } else {
                1.0 / (lights.len() - 1) as f64
            }
        })
        .collect();
    let selector =
        LightSelector::new(&lights, &weights, LightSelection::Uniform).expect("lights exist");
    assert_selects(
        "uniform selection, one light left out",
        &selector,
        &uniform,
        11,
    );
    for selection in [
        LightSelection::Uniform,
        LightSelection::Power,
        LightSelection::Ris { candidates: 4 },
        LightSelection::All,
    ] {
        let selector = LightSelector::new(&lights, &weights, selection).expect("lights exist");
        assert_eq!(selector.pmf(skipped), 0.0, "{selection:?}");
        assert!(selector.pmf(0) > 0.0, "{selection:?}");
        // Every light but the black sphere (no power) is sampled.
        let expected: Vec<u32> = match selection {
            LightSelection::Power | LightSelection::Ris { .. } => sampled
                .iter()
                .copied()
                .filter(|&i| lights[i as usize].power() > 0.0)
                .collect(),
            _ => sampled.clone(),
        };
        assert_eq!(selector.sampled(), expected, "{selection:?}");
        for k in 0..4096 {
            let u = (k as f32 + 0.5) / 4096.0;
            let (index, pmf) = selector.select(u);
            assert_ne!(index, skipped, "{selection:?}, u {u}");
            // `All` samples every light (pmf 1) and chooses, when asked, uniformly.
            if selection != LightSelection::All {
                assert_eq!(pmf, selector.pmf(index), "{selection:?}, u {u}");
            }
        }
    }
    let none = vec![0.0; lights.len()];
    assert!(LightSelector::new(&lights, &none, LightSelection::Power).is_none());
}

/// The compensated map (its excess over its mean, what light sampling under MIS samples)
/// samples directions by the density it reports.
#[test]
fn compensated_environment_map_matches_pdf() {
    let map = EnvironmentMap::new(16, 9, &sky_texels(), 1.5, Mat3::from_rotation_y(0.4), 2.0)
        .expect("valid");
    let light = Light::EnvironmentMap(map)
        .compensated()
        .expect("a sun above the mean");
    assert_fits(
        "compensated environment map",
        &light,
        Vec3::new(1.0, 2.0, -3.0),
        |wi| light.pdf_li_environment(wi),
        &config(13, 1_000_000, 64),
    );
}
