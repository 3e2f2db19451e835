//! Tests of the reconstruction filters: values against Mitsuba's formulas, inverse-CDF accuracy
//! against numerically integrated CDFs, a chi-square goodness-of-fit test of 2D sampling (by `|f|`
//! for filters with negative lobes), and the signed sample weights' estimates of filtered means.

use glam::{UVec2, Vec2};

use super::Filter;
use sampling::Rng;

/// The filters under test: Mitsuba's six with their defaults plus non-default parameters.
fn filters() -> Vec<(&'static str, Filter)> {
    vec![
        ("box", Filter::Box),
        ("tent r=1", Filter::tent(1.0).unwrap()),
        ("tent r=1.7", Filter::tent(1.7).unwrap()),
        ("gaussian sd=0.5", Filter::gaussian(0.5).unwrap()),
        ("gaussian sd=0.3", Filter::gaussian(0.3).unwrap()),
        ("mitchell", Filter::mitchell(1.0 / 3.0, 1.0 / 3.0).unwrap()),
        ("catmullrom", Filter::catmull_rom()),
        ("lanczos 3", Filter::lanczos(3).unwrap()),
        ("lanczos 1", Filter::lanczos(1).unwrap()),
    ]
}

/// `∫_a^b g(x) dx` by composite two-point Gauss–Legendre quadrature over `n` intervals. It never
/// evaluates at the interval ends, so the box filter's half-open support does not bias it.
fn quadrature(g: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let offset = 0.5 * h / 3f64.sqrt();
    (0..n)
        .map(|i| {
            let mid = a + (i as f64 + 0.5) * h;
            0.5 * h * (g(mid - offset) + g(mid + offset))
        })
        .sum()
}

/// `∫_a^b |f₁(x)| dx` (the sampling density's mass) from `eval_1d` alone.
fn integrate(filter: &Filter, a: f64, b: f64, n: usize) -> f64 {
    quadrature(|x| f64::from(filter.eval_1d(x as f32)).abs(), a, b, n)
}

/// The normalised CDF of `f₁` at `x`, by numerical integration independent of the sampler.
fn numeric_cdf(filter: &Filter, x: f32) -> f64 {
    let r = f64::from(filter.radius());
    integrate(filter, -r, f64::from(x), 4000) / integrate(filter, -r, r, 4000)
}

#[test]
fn values_match_mitsuba_formulas() {
    assert_eq!(Filter::Box.eval_1d(-0.5), 1.0);
    assert_eq!(Filter::Box.eval_1d(0.5), 0.0);
    let tent = Filter::tent(2.0).unwrap();
    assert_eq!(tent.eval_1d(0.5), 0.75);
    assert_eq!(tent.eval_1d(-2.5), 0.0);
    let gauss = Filter::gaussian(0.5).unwrap();
    assert_eq!(gauss.radius(), 2.0);
    // exp(-x²/(2·0.25)) − exp(-8) at x = 0 and x = 0.5.
    assert!((gauss.eval_1d(0.0) - (1.0 - (-8.0f32).exp())).abs() < 1e-6);
    assert!((gauss.eval_1d(0.5) - ((-0.5f32).exp() - (-8.0f32).exp())).abs() < 1e-6);
    assert_eq!(gauss.eval_1d(2.0), 0.0);
    assert_eq!(gauss.eval_1d(-3.0), 0.0);
    assert!(
        (gauss.eval(Vec2::new(0.5, 0.0)) - gauss.eval_1d(0.5) * gauss.eval_1d(0.0)).abs() < 1e-7
    );
    assert_eq!(Filter::default(), gauss);
    // Mitchell–Netravali, B = C = 1/3: (6 − 2B)/6 at 0, (12 − 9B − 6C − 18 + 12B + 6C + 6 − 2B)/6 at
    // 1, and (−7/3·1.5³ + 12·1.5² − 20·1.5 + 32/3)/6 at 1.5, in its negative lobe.
    let mitchell = Filter::mitchell(1.0 / 3.0, 1.0 / 3.0).unwrap();
    assert!((mitchell.eval_1d(0.0) - 8.0 / 9.0).abs() < 1e-6);
    assert!((mitchell.eval_1d(-1.0) - 1.0 / 18.0).abs() < 1e-6);
    let at_1_5 = (-7.0 / 3.0 * 3.375 + 12.0 * 2.25 - 30.0 + 32.0 / 3.0) / 6.0;
    assert!((mitchell.eval_1d(1.5) - at_1_5).abs() < 1e-6 && at_1_5 < 0.0);
    assert_eq!(mitchell.eval_1d(2.0), 0.0);
    assert!(mitchell.has_negative_lobes());
    // The cubic B-spline (B = 1, C = 0) is positive: its samples keep weight 1.
    assert!(!Filter::mitchell(1.0, 0.0).unwrap().has_negative_lobes());
    let catmull_rom = Filter::catmull_rom();
    assert!((catmull_rom.eval_1d(0.0) - 1.0).abs() < 1e-6);
    assert!(catmull_rom.eval_1d(1.0).abs() < 1e-6);
    // Lanczos, 3 lobes: sin(πx) sin(πx/3) / (π² x² / 3); at 1.5, −1 / (π² · 0.75).
    let lanczos = Filter::lanczos(3).unwrap();
    assert_eq!(lanczos.radius(), 3.0);
    assert_eq!(lanczos.eval_1d(0.0), 1.0);
    let expected = -1.0 / (std::f32::consts::PI.powi(2) * 0.75);
    assert!((lanczos.eval_1d(1.5) - expected).abs() < 1e-6);
    assert_eq!(lanczos.eval_1d(3.5), 0.0);
    for (name, filter) in filters() {
        let signed =
            name.starts_with("mitchell") || name.starts_with("catmullrom") || name == "lanczos 3";
        assert_eq!(filter.has_negative_lobes(), signed, "{name}");
    }
}

#[test]
fn film_positions_are_offsets_from_the_pixel_centre() {
    let pixel = UVec2::new(3, 7);
    let (width, height) = (16, 16);
    assert_eq!(
        Filter::Box.sample_film_position(pixel, Vec2::new(0.0, 0.75), width, height),
        Vec2::new(3.0, 7.75)
    );
    let tent = Filter::tent(1.0).unwrap();
    assert_eq!(
        tent.sample_film_position(pixel, Vec2::splat(0.5), width, height),
        Vec2::new(3.5, 7.5)
    );
    // Tent radius 1, u = 0.125: x = √0.25 − 1 = −0.5.
    assert_eq!(
        tent.sample_film_position(pixel, Vec2::new(0.125, 0.5), width, height),
        Vec2::new(3.0, 7.5)
    );
}

/// `cdf_1d` is the integral of `f₁` (numerically, independent of the table) and exactly 0 and 1
/// beyond the support, which keeps sampling away from the image's edges bit for bit untruncated.
#[test]
fn cdf_1d_integrates_the_filter() {
    for (name, filter) in filters() {
        let r = filter.radius();
        assert_eq!(filter.cdf_1d(-r), 0.0, "{name}");
        assert_eq!(filter.cdf_1d(r), 1.0, "{name}");
        assert_eq!(filter.cdf_1d(-r - 3.0), 0.0, "{name}");
        assert_eq!(filter.cdf_1d(r + 3.0), 1.0, "{name}");
        for k in 1..100 {
            let x = -r + 2.0 * r * k as f32 / 100.0;
            let numeric = numeric_cdf(&filter, x);
            assert!(
                (f64::from(filter.cdf_1d(x)) - numeric).abs() < 2e-5,
                "{name}: CDF({x}) = {} against {numeric}",
                filter.cdf_1d(x)
            );
        }
    }
}

/// Near the image's edges a pixel's camera samples stay inside the image, distributed as the
/// filter restricted to it (Mitsuba's films sample only the image): chi-square at significance
/// 0.001 per filter and corner pixel, against the truncated filter's bin masses; away from the
/// edges the film position is the untruncated one, bit for bit.
#[test]
fn film_positions_near_the_edges_follow_the_filter_inside_the_image() {
    let (width, height) = (5, 4);
    for (seed, (name, filter)) in filters().into_iter().enumerate() {
        for pixel in [UVec2::new(0, 0), UVec2::new(4, 3), UVec2::new(1, 2)] {
            let centre = pixel.as_vec2() + Vec2::splat(0.5);
            let (chi2, critical) = chi_square_truncated(&filter, pixel, width, height, seed as u32);
            assert!(
                chi2 < critical,
                "{name}, pixel {pixel}: chi2 = {chi2:.1} exceeds the 0.001 critical value \
                 {critical:.1} (replay: sampling::Rng seed {seed}, {CHI2_SAMPLES} samples)"
            );
            let mut rng = Rng::new(seed as u32);
            for _ in 0..1000 {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                let p = filter.sample_film_position(pixel, u, width, height);
                assert!(
                    p.x >= 0.0 && p.x < width as f32 && p.y >= 0.0 && p.y < height as f32,
                    "{name}, pixel {pixel}, u {u}: film position {p} outside the image"
                );
                let far = filter.sample_film_position(pixel + UVec2::splat(20), u, 64, 64);
                assert_eq!(far, centre + Vec2::splat(20.0) + filter.sample(u), "{name}");
            }
        }
    }
}

/// Chi-square of `pixel`'s film positions in a `width × height` image against the filter
/// restricted to the image, per axis bins of the offsets inside it.
fn chi_square_truncated(
    filter: &Filter,
    pixel: UVec2,
    width: u32,
    height: u32,
    seed: u32,
) -> (f64, f64) {
    const BINS: usize = 16;
    let centre = pixel.as_vec2() + Vec2::splat(0.5);
    let r = filter.radius();
    // Per axis: the offsets inside both the support and the image, their bins and masses.
    let axis = |c: f32, size: u32| {
        let (lo, hi) = ((-r).max(-c), r.min(size as f32 - c));
        let edges: Vec<f64> = (0..=BINS)
            .map(|i| f64::from(lo) + f64::from(hi - lo) * i as f64 / BINS as f64)
            .collect();
        let total = integrate(filter, edges[0], edges[BINS], 4800);
        let masses: Vec<f64> = edges
            .windows(2)
            .map(|e| integrate(filter, e[0], e[1], 200) / total)
            .collect();
        (lo, hi, masses)
    };
    let (x_lo, x_hi, x_mass) = axis(centre.x, width);
    let (y_lo, y_hi, y_mass) = axis(centre.y, height);
    let bin =
        |v: f32, lo: f32, hi: f32| (((v - lo) / (hi - lo) * BINS as f32) as usize).min(BINS - 1);
    let mut counts = vec![0u64; BINS * BINS];
    let mut rng = Rng::new(seed);
    for _ in 0..CHI2_SAMPLES {
        let p = filter.sample_film_position(
            pixel,
            Vec2::new(rng.next_f32(), rng.next_f32()),
            width,
            height,
        ) - centre;
        counts[bin(p.y, y_lo, y_hi) * BINS + bin(p.x, x_lo, x_hi)] += 1;
    }
    chi_square_of_counts(&counts, &x_mass, &y_mass)
}

#[test]
fn invalid_parameters_are_errors() {
    for bad in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        assert!(Filter::tent(bad).is_err(), "tent radius {bad}");
        assert!(Filter::gaussian(bad).is_err(), "gaussian stddev {bad}");
    }
    let message = Filter::gaussian(-2.0).unwrap_err().to_string();
    assert!(
        message.contains("gaussian stddev") && message.contains("-2"),
        "{message}"
    );
    for lobes in [0, 17] {
        let message = Filter::lanczos(lobes).unwrap_err().to_string();
        assert!(message.contains("lanczos lobes"), "{message}");
    }
    let message = Filter::mitchell(f32::NAN, 0.0).unwrap_err().to_string();
    assert!(message.contains("mitchell B must be finite"), "{message}");
}

/// `sample_1d` inverts the CDF: the numerically integrated CDF at the sample equals `u`
/// (exact for box and tent, within the tabulation error for the gaussian).
#[test]
fn sample_1d_inverts_the_cdf() {
    for (name, filter) in filters() {
        let r = filter.radius();
        for k in 0..=200 {
            let u = (k as f32 / 200.0).min(1.0 - f32::EPSILON / 2.0);
            let x = filter.sample_1d(u);
            assert!(
                (-r..=r).contains(&x),
                "{name}: u={u} gave x={x} outside ±{r}"
            );
            let cdf = numeric_cdf(&filter, x);
            assert!(
                (cdf - f64::from(u)).abs() < 2e-5,
                "{name}: u={u}, x={x}, CDF(x)={cdf}"
            );
        }
    }
}

#[test]
fn sample_1d_is_monotonic() {
    for (name, filter) in filters() {
        let mut previous = f32::NEG_INFINITY;
        for k in 0..10_000 {
            let x = filter.sample_1d(k as f32 / 10_000.0);
            assert!(x >= previous, "{name}: not monotonic at step {k}");
            previous = x;
        }
    }
}

/// Upper quantile of the chi-square distribution with `dof` degrees of freedom at significance
/// `alpha`, by the Wilson–Hilferty cube approximation (relative error below 1% for dof ≥ 10).
fn chi2_critical(dof: usize, z_alpha: f64) -> f64 {
    let k = dof as f64;
    let c = 2.0 / (9.0 * k);
    k * (1.0 - c + z_alpha * c.sqrt()).powi(3)
}

/// Chi-square statistic and its critical value at significance 0.001 for 2D offsets drawn by
/// `sample` (from a `sampling::Rng` seeded with `seed`) against the bin probabilities of `filter`,
/// integrated from `eval_1d` on a 24×24 grid over the support. Bins expecting fewer than 5
/// samples are pooled into one.
fn chi_square(filter: &Filter, sample: impl Fn(Vec2) -> Vec2, seed: u32) -> (f64, f64) {
    const BINS: usize = 24;
    let r = f64::from(filter.radius());
    let edge = |i: usize| -r + 2.0 * r * i as f64 / BINS as f64;
    let total = integrate(filter, -r, r, 4800);
    let marginal: Vec<f64> = (0..BINS)
        .map(|i| integrate(filter, edge(i), edge(i + 1), 200) / total)
        .collect();

    let mut counts = vec![0u64; BINS * BINS];
    let mut rng = Rng::new(seed);
    let bin = |x: f32| (((f64::from(x) + r) / (2.0 * r) * BINS as f64) as usize).min(BINS - 1);
    for _ in 0..CHI2_SAMPLES {
        let p = sample(Vec2::new(rng.next_f32(), rng.next_f32()));
        counts[bin(p.y) * BINS + bin(p.x)] += 1;
    }

    chi_square_of_counts(&counts, &marginal, &marginal)
}

/// The chi-square statistic of `counts` (row-major, `y_mass.len()` rows of `x_mass.len()` cells,
/// [`CHI2_SAMPLES`] in all) against the product of the per-axis bin masses, cells expecting
/// fewer than 5 pooled into one, and its critical value at significance 0.001.
fn chi_square_of_counts(counts: &[u64], x_mass: &[f64], y_mass: &[f64]) -> (f64, f64) {
    const Z_ALPHA_0_001: f64 = 3.090;
    let (mut chi2, mut cells, mut pooled_observed, mut pooled_expected) = (0.0, 0usize, 0.0, 0.0);
    for (j, &py) in y_mass.iter().enumerate() {
        for (i, &px) in x_mass.iter().enumerate() {
            let expected = px * py * CHI2_SAMPLES as f64;
            let observed = counts[j * x_mass.len() + i] as f64;
            if expected < 5.0 {
                pooled_expected += expected;
                pooled_observed += observed;
            } else {
                chi2 += (observed - expected).powi(2) / expected;
                cells += 1;
            }
        }
    }
    if pooled_expected > 0.0 {
        chi2 += (pooled_observed - pooled_expected).powi(2) / pooled_expected;
        cells += 1;
    }
    (chi2, chi2_critical(cells - 1, Z_ALPHA_0_001))
}

/// Samples per chi-square test.
const CHI2_SAMPLES: usize = 200_000;

/// Sampled 2D offsets follow the normalised filter: chi-square at significance 0.001 per filter.
#[test]
fn sampled_offsets_follow_the_normalised_filter() {
    for (seed, (name, filter)) in filters().into_iter().enumerate() {
        let (chi2, critical) = chi_square(&filter, |u| filter.sample(u), seed as u32);
        assert!(
            chi2 < critical,
            "{name}: chi2 = {chi2:.1} exceeds the 0.001 critical value {critical:.1} \
             (replay: sampling::Rng seed {seed}, {CHI2_SAMPLES} samples)"
        );
    }
}

/// The same test rejects a wrong distribution of the same support (tent samples against the
/// gaussian's bins), so it has the power to catch a wrong sampler.
#[test]
fn chi_square_rejects_a_wrong_distribution() {
    let tent = Filter::tent(2.0).unwrap();
    let gauss = Filter::gaussian(0.5).unwrap();
    let (chi2, critical) = chi_square(&gauss, |u| tent.sample(u), 7);
    assert!(
        chi2 > 10.0 * critical,
        "chi2 = {chi2:.1}, critical {critical:.1}"
    );
}

/// The density the light tracer splats with is the sampler's: integrating `pdf_1d` up to
/// `sample_1d(u)` gives back `u` (so it also integrates to 1), and it is zero outside the radius.
#[test]
fn pdf_is_the_density_of_the_sampled_offsets() {
    for (name, filter) in filters() {
        let r = f64::from(filter.radius());
        let cdf = |x: f64| {
            let n = 4000;
            let h = (x + r) / n as f64;
            let offset = 0.5 * h / 3f64.sqrt();
            let f = |t: f64| f64::from(filter.pdf_1d(t as f32));
            (0..n)
                .map(|i| {
                    let mid = -r + (i as f64 + 0.5) * h;
                    0.5 * h * (f(mid - offset) + f(mid + offset))
                })
                .sum::<f64>()
        };
        assert!((cdf(r) - 1.0).abs() < 1e-4, "{name}: total {}", cdf(r));
        for u in [0.01, 0.1, 0.25, 0.5, 0.7, 0.93, 0.999] {
            let x = f64::from(filter.sample_1d(u as f32));
            assert!(
                (cdf(x) - u).abs() < 2e-4,
                "{name}: CDF of the density at sample_1d({u}) = {x} is {}",
                cdf(x)
            );
        }
        assert_eq!(filter.pdf_1d(filter.radius() + 0.01), 0.0, "{name}");
        assert_eq!(filter.pdf_1d(-filter.radius() - 0.01), 0.0, "{name}");
        let offset = Vec2::new(0.3 * filter.radius(), -0.2 * filter.radius());
        assert_eq!(
            filter.pdf(offset),
            filter.pdf_1d(offset.x) * filter.pdf_1d(offset.y),
            "{name}"
        );
    }
}

/// `for_each_pixel_at` visits exactly the pixels a brute-force scan of the image finds with a
/// non-zero `pixel_weight`, once each and with that weight, for film positions inside, on pixel
/// borders and beyond the image's edges (which reach no pixel); with the box filter that is the
/// containing pixel. Away from the edges the weight is the filter divided by its integral: the
/// sampling density for filters without negative lobes, and within 1e-4 (relative to the peak)
/// of `f(x) f(y) / (∫f)²` by quadrature for the others.
#[test]
fn film_positions_reach_the_pixels_whose_samples_land_there() {
    let (width, height) = (7, 5);
    let mut rng = Rng::new(21);
    for (name, filter) in filters() {
        for case in 0..300 {
            let film = match case % 3 {
                0 => Vec2::new(rng.next_f32() * 7.0, rng.next_f32() * 5.0),
                1 => Vec2::new((case % 8) as f32, (case % 6) as f32),
                _ => Vec2::new(rng.next_f32() * 13.0 - 3.0, rng.next_f32() * 11.0 - 3.0),
            };
            let mut visited = Vec::new();
            filter.for_each_pixel_at(film, width, height, |pixel, weight| {
                visited.push((pixel, weight));
            });
            let expected: Vec<(UVec2, f32)> = (0..height)
                .flat_map(|y| (0..width).map(move |x| UVec2::new(x, y)))
                .filter_map(|pixel| {
                    let weight = filter.pixel_weight(film, pixel, width, height);
                    (weight != 0.0).then_some((pixel, weight))
                })
                .collect();
            let inside = film.cmpge(Vec2::ZERO).all() && film.x < 7.0 && film.y < 5.0;
            assert!(
                inside || visited.is_empty(),
                "{name}, film position {film}: {visited:?}"
            );
            // Away from the edges the weight is the untruncated filter over its integral.
            for &(pixel, weight) in &visited {
                let centre = pixel.as_vec2() + Vec2::splat(0.5);
                let clear = centre.cmpge(Vec2::splat(filter.radius())).all()
                    && centre.x + filter.radius() <= 7.0
                    && centre.y + filter.radius() <= 5.0;
                if !clear {
                    continue;
                }
                let offset = film - centre;
                if filter.has_negative_lobes() {
                    let expected = f64::from(filter.eval(offset)) / signed_total(&filter).powi(2);
                    let peak = 1.0 / signed_total(&filter).powi(2);
                    assert!(
                        (f64::from(weight) - expected).abs() < 1e-4 * peak,
                        "{name}, {film}, {pixel}: weight {weight} against {expected}"
                    );
                } else {
                    assert_eq!(weight, filter.pdf(offset), "{name}, {film}, {pixel}");
                }
            }
            assert_eq!(visited, expected, "{name}, film position {film}");
            if name == "box" && film.cmpge(Vec2::ZERO).all() && film.x < 7.0 && film.y < 5.0 {
                assert_eq!(visited, vec![(film.floor().as_uvec2(), 1.0)], "{film}");
            }
        }
    }
}

/// `∫ f₁` over the support by quadrature, signed.
fn signed_total(filter: &Filter) -> f64 {
    let r = f64::from(filter.radius());
    quadrature(|x| f64::from(filter.eval_1d(x as f32)), -r, r, 4800)
}

/// Camera samples with their weights estimate a pixel's filtered mean of a test image `g`,
/// `∫ f g / ∫ f` over the offsets inside the image, for a pixel away from the edges and for one
/// at a corner (where the filter is cut by two edges): the mean of `weight · g` over 400,000
/// samples (fixed seeds) lies within 5 standard errors of the quadrature value. The weights are
/// 1 for filters without negative lobes.
#[test]
fn sample_weights_estimate_the_filtered_mean() {
    const SAMPLES: usize = 400_000;
    let (width, height) = (9, 8);
    // A smooth test image with a slope and a bump, in film coordinates.
    let g = |p: Vec2| 1.0 + 0.3 * f64::from(p.x) + (f64::from(p.y) - 1.0).powi(2);
    for (seed, (name, filter)) in filters().into_iter().enumerate() {
        for pixel in [UVec2::new(4, 4), UVec2::new(0, 0)] {
            let centre = pixel.as_vec2() + Vec2::splat(0.5);
            let r = f64::from(filter.radius());
            let f = |x: f64| f64::from(filter.eval_1d(x as f32));
            let (x_lo, x_hi) = (
                (-r).max(-f64::from(centre.x)),
                r.min(f64::from(width) - f64::from(centre.x)),
            );
            let (y_lo, y_hi) = (
                (-r).max(-f64::from(centre.y)),
                r.min(f64::from(height) - f64::from(centre.y)),
            );
            // g is a sum of separable terms; integrate each against f(x) f(y).
            let cx = f64::from(centre.x);
            let cy = f64::from(centre.y);
            let ix = |k: i32| quadrature(|x| f(x) * (cx + x).powi(k), x_lo, x_hi, 4000);
            let iy = |k: i32| quadrature(|y| f(y) * (cy + y - 1.0).powi(k), y_lo, y_hi, 4000);
            let expected = (ix(0) * iy(0) + 0.3 * ix(1) * iy(0) + ix(0) * iy(2)) / (ix(0) * iy(0));
            let mut rng = Rng::new(100 + seed as u32);
            let (mut sum, mut sum_sq) = (0.0, 0.0);
            for _ in 0..SAMPLES {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                let film = filter.sample_film_position(pixel, u, width, height);
                let value = f64::from(filter.sample_weight(film, pixel, width, height)) * g(film);
                sum += value;
                sum_sq += value * value;
            }
            let mean = sum / SAMPLES as f64;
            let error = ((sum_sq / SAMPLES as f64 - mean * mean) / SAMPLES as f64).sqrt();
            assert!(
                (mean - expected).abs() < 5.0 * error + 1e-4 * expected,
                "{name}, pixel {pixel}: mean {mean} ± {error} against {expected} \
                 (replay: sampling::Rng seed {}, {SAMPLES} samples)",
                100 + seed
            );
        }
    }
}
