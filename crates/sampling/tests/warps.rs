//! Every warp: the pdf integrates to 1, agrees with the Jacobian of `sample`, `invert` undoes `sample`,
//! extreme inputs stay finite and inside the domain, and the samples pass a chi-square test.
//!
//! Chi-square tests: α = 0.01, Šidák-corrected over the [`CHI2_TESTS`] tests of this file, fixed seeds.

use glam::{DVec3, Vec2, Vec3};
use proptest::prelude::*;
use sampling::chi2::{Chi2Config, Chi2Domain, chi2_test, integrate_pdf};
use sampling::warp::*;

mod common;

/// The largest `f32` below 1: what a sampler can return at most.
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;
/// Chi-square tests in this file, for the Šidák correction.
const CHI2_TESTS: u32 = 9;

/// A warp onto unit directions, with a pdf per steradian.
struct DirectionWarp {
    name: String,
    sample: Box<dyn Fn(Vec2) -> Vec3>,
    pdf: Box<dyn Fn(Vec3) -> f32>,
    invert: Box<dyn Fn(Vec3) -> Vec2>,
    /// Whether a direction is in the warp's domain (allowing for rounding).
    contains: Box<dyn Fn(Vec3) -> bool>,
}

fn cone(cos_theta_max: f32) -> DirectionWarp {
    DirectionWarp {
        name: format!("uniform cone, cos θ_max = {cos_theta_max}"),
        sample: Box::new(move |u| sample_uniform_cone(u, 1.0 - cos_theta_max)),
        pdf: Box::new(move |w| {
            if w.z >= cos_theta_max {
                uniform_cone_pdf(1.0 - cos_theta_max)
            } else {
                0.0
            }
        }),
        invert: Box::new(move |w| invert_uniform_cone(w, 1.0 - cos_theta_max)),
        contains: Box::new(move |w| w.z >= cos_theta_max - 1e-6),
    }
}

fn direction_warps() -> Vec<DirectionWarp> {
    vec![
        DirectionWarp {
            name: "uniform hemisphere".into(),
            sample: Box::new(sample_uniform_hemisphere),
            pdf: Box::new(|w| {
                if w.z >= 0.0 {
                    uniform_hemisphere_pdf()
                } else {
                    0.0
                }
            }),
            invert: Box::new(invert_uniform_hemisphere),
            contains: Box::new(|w| w.z >= 0.0),
        },
        DirectionWarp {
            name: "cosine hemisphere".into(),
            sample: Box::new(sample_cosine_hemisphere),
            pdf: Box::new(|w| cosine_hemisphere_pdf(w.z)),
            invert: Box::new(invert_cosine_hemisphere),
            contains: Box::new(|w| w.z >= 0.0),
        },
        DirectionWarp {
            name: "uniform sphere".into(),
            sample: Box::new(sample_uniform_sphere),
            pdf: Box::new(|_| uniform_sphere_pdf()),
            invert: Box::new(invert_uniform_sphere),
            contains: Box::new(|_| true),
        },
        cone(0.3),
        cone(-0.6),
        cone(0.97),
    ]
}

/// The unit disc mapped onto [0, 1]² for the unit-square domain: p = 2 q − 1, pdf × 4.
fn disk_pdf_on_square(q: Vec3) -> f32 {
    let p = 2.0 * Vec2::new(q.x, q.y) - Vec2::ONE;
    if p.length_squared() <= 1.0 {
        4.0 * concentric_disk_pdf()
    } else {
        0.0
    }
}

/// Barycentrics (b1, b2) as a point of [0, 1]²: the triangle (0, 0), (1, 0), (0, 1) of area 1/2.
fn triangle_pdf_on_square(q: Vec3) -> f32 {
    if q.x + q.y <= 1.0 {
        uniform_triangle_pdf(0.5)
    } else {
        0.0
    }
}

fn chi2_config(seed: u32) -> Chi2Config {
    Chi2Config {
        seed,
        sample_count: 200_000,
        resolution: 16,
        test_count: CHI2_TESTS,
        ..Chi2Config::default()
    }
}

fn uniform_pair(rng: &mut sampling::Rng) -> Vec2 {
    Vec2::new(rng.next_f32(), rng.next_f32())
}

#[test]
fn chi_square_for_every_direction_warp() {
    for (seed, warp) in direction_warps().iter().enumerate() {
        let outcome = chi2_test(
            Chi2Domain::Sphere,
            |rng| Some((warp.sample)(uniform_pair(rng))),
            &warp.pdf,
            &chi2_config(seed as u32),
        );
        println!("figure: {}: {}", warp.name, outcome.summary());
        assert!(outcome.passed, "{}: {outcome}", warp.name);
    }
}

#[test]
fn chi_square_for_the_concentric_disk() {
    let outcome = chi2_test(
        Chi2Domain::UnitSquare,
        |rng| {
            let p = sample_concentric_disk(uniform_pair(rng));
            Some(((p + Vec2::ONE) * 0.5).extend(0.0))
        },
        disk_pdf_on_square,
        &chi2_config(100),
    );
    assert!(outcome.passed, "{outcome}");
}

#[test]
fn chi_square_for_the_triangle() {
    let outcome = chi2_test(
        Chi2Domain::UnitSquare,
        |rng| {
            let b = sample_uniform_triangle(uniform_pair(rng));
            Some(Vec3::new(b.y, b.z, 0.0))
        },
        triangle_pdf_on_square,
        &chi2_config(101),
    );
    assert!(outcome.passed, "{outcome}");
}

#[test]
fn pdfs_of_parameterless_warps_integrate_to_one() {
    for warp in direction_warps() {
        let integral = integrate_pdf(Chi2Domain::Sphere, &warp.pdf, 16);
        assert!((integral - 1.0).abs() < 0.01, "{}: {integral}", warp.name);
    }
    let disk = integrate_pdf(Chi2Domain::UnitSquare, disk_pdf_on_square, 32);
    assert!((disk - 1.0).abs() < 0.01, "disk: {disk}");
    let triangle = integrate_pdf(Chi2Domain::UnitSquare, triangle_pdf_on_square, 32);
    assert!((triangle - 1.0).abs() < 0.01, "triangle: {triangle}");
}

/// |∂w/∂u₁ × ∂w/∂u₂| by central differences: the area (or solid angle) per unit of u-area.
fn jacobian(map: impl Fn(Vec2) -> DVec3, u: Vec2, h: f32) -> f64 {
    let du = |axis: Vec2| {
        let forward = map(u + h * axis);
        let backward = map(u - h * axis);
        (forward - backward) / (2.0 * f64::from(h))
    };
    du(Vec2::X).cross(du(Vec2::Y)).length()
}

/// Circular distance between two azimuth fractions in [0, 1).
fn wrapped_distance(a: f32, b: f32) -> f32 {
    let d = (a - b).abs();
    d.min(1.0 - d)
}

fn edge_or_inner() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0_f32),
        Just(ONE_MINUS_EPSILON),
        Just(0.5_f32),
        0.0_f32..1.0
    ]
}

fn interior() -> impl Strategy<Value = Vec2> {
    (0.02_f32..0.98, 0.02_f32..0.98).prop_map(|(x, y)| Vec2::new(x, y))
}

fn any_u() -> impl Strategy<Value = Vec2> {
    (0.0_f32..1.0, 0.0_f32..1.0).prop_map(|(x, y)| Vec2::new(x, y))
}

proptest! {
    #![proptest_config(common::fixed_seed(256))]

    #[test]
    fn direction_warps_agree_with_their_jacobian(u in interior(), cos_max in -0.99_f32..0.99) {
        let mut warps = direction_warps();
        warps.push(cone(cos_max));
        for warp in &warps {
            let w = (warp.sample)(u);
            let area = jacobian(|v| (warp.sample)(v).as_dvec3(), u, 1e-3);
            // Solid angle per unit u-area times the density per steradian must be 1.
            let product = area * f64::from((warp.pdf)(w));
            prop_assert!((product - 1.0).abs() < 0.01, "{} at {u}: pdf × |J| = {product}", warp.name);
        }
    }

    #[test]
    fn planar_warps_agree_with_their_jacobian(u in interior()) {
        // The concentric map has kinks on the square's diagonals; differences must not straddle them.
        let o = 2.0 * u - Vec2::ONE;
        prop_assume!((o.x.abs() - o.y.abs()).abs() > 0.01);
        let disk = |v: Vec2| sample_concentric_disk(v).extend(0.0).as_dvec3();
        let product = jacobian(disk, u, 1e-3) * f64::from(concentric_disk_pdf());
        prop_assert!((product - 1.0).abs() < 0.01, "disk at {u}: pdf × |J| = {product}");

        // Barycentrics onto the triangle (0, 0), (3, 0), (1, 2) of area 3.
        let (a, b, c) = (DVec3::ZERO, DVec3::new(3.0, 0.0, 0.0), DVec3::new(1.0, 2.0, 0.0));
        let triangle = |v: Vec2| {
            let bary = sample_uniform_triangle(v).as_dvec3();
            a * bary.x + b * bary.y + c * bary.z
        };
        let product = jacobian(triangle, u, 1e-3) * f64::from(uniform_triangle_pdf(3.0));
        prop_assert!((product - 1.0).abs() < 0.01, "triangle at {u}: pdf × |J| = {product}");
    }

    #[test]
    fn extreme_inputs_give_finite_values_inside_the_domain(
        x in edge_or_inner(), y in edge_or_inner(), cos_max in -1.0_f32..0.999,
    ) {
        let u = Vec2::new(x, y);
        let mut warps = direction_warps();
        warps.push(cone(cos_max));
        for warp in &warps {
            let w = (warp.sample)(u);
            let pdf = (warp.pdf)(w);
            prop_assert!(w.is_finite(), "{} at {u}: {w}", warp.name);
            prop_assert!((w.length() - 1.0).abs() < 1e-6, "{} at {u}: |w| = {}", warp.name, w.length());
            prop_assert!((warp.contains)(w), "{} at {u}: {w} outside the domain", warp.name);
            prop_assert!(pdf > 0.0 && pdf.is_finite(), "{} at {u}: pdf {pdf}", warp.name);
        }
        let p = sample_concentric_disk(u);
        prop_assert!(p.is_finite() && p.length() <= 1.0 + 1e-6, "disk at {u}: {p}");
        let b = sample_uniform_triangle(u);
        prop_assert!(b.is_finite() && b.min_element() >= 0.0, "triangle at {u}: {b}");
        prop_assert!((b.element_sum() - 1.0).abs() < 1e-6, "triangle at {u}: {b}");
        prop_assert!(uniform_triangle_pdf(0.25) == 4.0);
    }

    #[test]
    fn invert_undoes_sample(u in any_u(), cos_max in -0.99_f32..0.999) {
        let mut warps = direction_warps();
        warps.push(cone(cos_max));
        for warp in &warps {
            let w = (warp.sample)(u);
            let back = (warp.invert)(w);
            // In direction space the round trip holds everywhere.
            let again = (warp.sample)(back);
            prop_assert!((again - w).length() < 1e-4, "{} at {u}: {w} -> {back} -> {again}", warp.name);
            // The azimuth is undefined at the poles, where the sin θ of the direction vanishes.
            let sin_theta = w.truncate().length();
            prop_assert!(sin_theta < 1e-3 || wrapped_distance(back.y, u.y) < 1e-4,
                "{} at {u}: azimuth came back as {}", warp.name, back.y);
        }
        // θ parameters: exactly recoverable wherever cos θ depends smoothly on u.x.
        prop_assert!((invert_uniform_hemisphere(sample_uniform_hemisphere(u)).x - u.x).abs() < 1e-6);
        prop_assert!((invert_cosine_hemisphere(sample_cosine_hemisphere(u)).x - u.x).abs() < 1e-5);
        prop_assert!((invert_uniform_sphere(sample_uniform_sphere(u)).x - u.x).abs() < 1e-5);
        let gap = 1.0 - cos_max;
        let cone_back = invert_uniform_cone(sample_uniform_cone(u, gap), gap);
        prop_assert!((cone_back.x - u.x).abs() < 2e-4, "cone {cos_max} at {u}: {cone_back}");

        let p = sample_concentric_disk(u);
        let back = invert_concentric_disk(p);
        prop_assert!(p.length() < 1e-3 || (back - u).length() < 1e-4, "disk at {u}: {p} -> {back}");
        let b = sample_uniform_triangle(u);
        let back = invert_uniform_triangle(b);
        prop_assert!((back.x - u.x).abs() < 1e-5, "triangle at {u}: {b} -> {back}");
        prop_assert!(u.x < 1e-3 || (back.y - u.y).abs() < 1e-4, "triangle at {u}: {b} -> {back}");
    }
}

/// The narrow cones that once failed to integrate to one, before the quadrature subdivided
/// adaptively.
#[test]
fn narrow_cone_pdfs_integrate_to_one() {
    for cos_max in [0.878293_f32, 0.965_730_97] {
        let integral = integrate_pdf(Chi2Domain::Sphere, &cone(cos_max).pdf, 8);
        assert!(
            (integral - 1.0).abs() < 0.01,
            "cos θ_max {cos_max}: {integral}"
        );
    }
}

/// Cones far narrower than `f32` resolves as cos θ_max (a sphere of radius 10⁻⁴ seen from 10
/// units: 1 − cos θ_max = 5·10⁻¹¹) still sample over their whole angle, stay inside it, and
/// invert: the warp takes 1 − cos θ_max, never forming cos θ_max.
#[test]
fn very_narrow_cones_sample_and_invert() {
    for one_minus_cos_max in [5e-11_f32, 1e-7, 1e-4] {
        let sin2_max = one_minus_cos_max * (2.0 - one_minus_cos_max);
        for (i, &x) in [0.0_f32, 0.25, 0.5, 0.999].iter().enumerate() {
            let u = Vec2::new(x, 0.1 + 0.2 * i as f32);
            let w = sample_uniform_cone(u, one_minus_cos_max);
            let sin2 = w.x * w.x + w.y * w.y;
            // The drawn sin²θ is u.x of the cone's (1 − cos θ grows linearly in u.x).
            assert!(
                (sin2 - x * sin2_max).abs() <= 1e-3 * sin2_max,
                "1 − cos θ_max = {one_minus_cos_max}, u = {u}: sin²θ {sin2} of {sin2_max}"
            );
            let back = invert_uniform_cone(w, one_minus_cos_max);
            assert!(
                (back.x - x).abs() < 1e-3,
                "1 − cos θ_max = {one_minus_cos_max}, u = {u}: inverted to {back}"
            );
        }
    }
}

proptest! {
    #![proptest_config(common::fixed_seed(16))]

    #[test]
    fn cone_pdf_integrates_to_one(cos_max in -0.99_f32..0.99) {
        let integral = integrate_pdf(Chi2Domain::Sphere, &cone(cos_max).pdf, 8);
        prop_assert!((integral - 1.0).abs() < 0.01, "cos θ_max {cos_max}: {integral}");
    }

    #[test]
    fn triangle_pdf_integrates_to_one_over_any_triangle(
        v in prop::array::uniform6(0.0_f32..1.0),
    ) {
        let (a, b, c) = (Vec2::new(v[0], v[1]), Vec2::new(v[2], v[3]), Vec2::new(v[4], v[5]));
        let area = 0.5 * (b - a).perp_dot(c - a).abs();
        // The quadrature resolves an edge only to within its bins (1/16 wide): a sliver thinner
        // than two bins can fall between a bin's nodes (v = [0.397, 0.619, 0.944, 0.581, 0,
        // 0.571], 0.044 thick, integrated to 0.985).
        let longest_edge = (b - a).length().max((c - b).length()).max((a - c).length());
        prop_assume!(area > 0.02 && 2.0 * area / longest_edge > 2.0 / 16.0);
        let pdf = uniform_triangle_pdf(area);
        // The density 1 / area over the triangle's points, tested by the signs of edge functions.
        let inside = |q: Vec3| {
            let q = q.truncate();
            let e = [(b - a).perp_dot(q - a), (c - b).perp_dot(q - b), (a - c).perp_dot(q - c)];
            if e.iter().all(|&x| x >= 0.0) || e.iter().all(|&x| x <= 0.0) { pdf } else { 0.0 }
        };
        let integral = integrate_pdf(Chi2Domain::UnitSquare, inside, 16);
        prop_assert!((integral - 1.0).abs() < 0.01, "area {area}: {integral}");
    }
}
