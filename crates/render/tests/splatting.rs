//! Splatting camera samples into every pixel a filter wider than a pixel covers
//! (`render::filter::Splatter`): the expected image is the filtered image that filter importance
//! sampling estimates (an analytic step edge, image edges included), the variance per pixel is
//! lower at equal samples, and films are bit-identical across threads, tiles, passes, resumes
//! and merged pieces.

use std::sync::Arc;

use glam::{UVec2, Vec2, Vec3};
use render::adaptive::{Allocation, PixelCosts};
use render::driver::{
    RenderBudget, RenderOptions, RenderOutput, ResumePoint, render_blocks, render_blocks_splatting,
};
use render::film::Film;
use render::filter::{Filter, Splatter};

/// A hash of (pixel, sample index, stream) to 64 well-mixed bits (SplitMix64's finaliser).
fn hash(pixel: UVec2, index: u32, stream: u64) -> u64 {
    let mut z = (u64::from(pixel.x) << 44)
        ^ (u64::from(pixel.y) << 28)
        ^ u64::from(index)
        ^ stream.wrapping_mul(0xd1b5_4a32_d192_ed03);
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Three uniform numbers in `[0, 1)` for (pixel, index, seed).
fn uniforms(pixel: UVec2, index: u32, seed: u64) -> [f32; 3] {
    let h = hash(pixel, index, seed);
    [0, 21, 42].map(|shift| ((h >> shift) & 0x1f_ffff) as f32 / (1u32 << 21) as f32)
}

/// A radiance sample at film position `x`: 1 left of `edge` (pixels) and 0 right of it, times
/// noise of mean 1 (uniform on [0, 2)), so the pixel values are known in closed form.
fn step_sample(position: Vec2, noise: f32, edge: f32) -> Vec3 {
    if position.x < edge {
        Vec3::new(2.0 * noise, 1.0, 0.5)
    } else {
        Vec3::ZERO
    }
}

/// Renders `spp` samples per pixel of `sample(position, noise)` on `threads` threads, splatted
/// with `filter` in blocks of `block`.
#[allow(clippy::too_many_arguments)]
fn render_splatted(
    filter: &Filter,
    (width, height): (u32, u32),
    budget: RenderBudget,
    options: &RenderOptions,
    block: u32,
    threads: usize,
    seed: u64,
    sample: impl Fn(Vec2, f32) -> Vec3 + Sync + Send,
) -> RenderOutput {
    let splatter = Splatter::new(filter, width, height).expect("a filter wider than a pixel");
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        render_blocks_splatting(
            width,
            height,
            &budget,
            options,
            block,
            Some(&splatter),
            || (),
            |_: &mut (),
             pixels: &[UVec2],
             index: u32,
             values: &mut [Vec3],
             positions: &mut [Vec2]| {
                for ((&pixel, value), position) in pixels.iter().zip(values).zip(positions) {
                    let [u, v, noise] = uniforms(pixel, index, seed);
                    *position = Splatter::film_position(pixel, Vec2::new(u, v));
                    *value = sample(*position, noise);
                }
            },
            None,
        )
    })
    .unwrap()
}

/// The filtered value of the step edge at `edge` for a pixel centred at `centre` on an image
/// axis of `size` pixels: `∫ f(x − c) L(x) dx / ∫ f(x − c) dx`, both over the image.
fn step_expected(filter: &Filter, edge: f32, centre: f32, size: u32) -> f64 {
    let cdf = |x: f32| f64::from(filter.signed_cdf_1d(x));
    let mass = cdf(size as f32 - centre) - cdf(-centre);
    (cdf(edge.min(size as f32) - centre) - cdf(-centre)) / mass
}

#[test]
fn the_expected_image_is_the_filtered_step_edge_at_every_pixel() {
    let (width, height) = (16, 5);
    let edge = 6.3;
    for filter in [
        Filter::default(),
        Filter::tent(1.5).unwrap(),
        Filter::mitchell(1.0 / 3.0, 1.0 / 3.0).unwrap(),
        Filter::lanczos(3).unwrap(),
    ] {
        let output = render_splatted(
            &filter,
            (width, height),
            RenderBudget::spp(2048),
            &RenderOptions::quiet(),
            1,
            2,
            1,
            |x, noise| step_sample(x, noise, edge),
        );
        let (image, variance) = (output.film.to_image(), output.film.variance_of_mean_image());
        let mut worst: f64 = 0.0;
        for y in 0..height {
            for x in 0..width {
                let expected = step_expected(&filter, edge, x as f32 + 0.5, width);
                let (value, var) = (image.pixel(x, y), variance.pixel(x, y));
                // The green channel is the step itself, noise-free but for where samples land.
                for (c, scale) in [(0, 1.0), (1, 1.0), (2, 0.5)] {
                    let got = f64::from(value.to_array()[c]);
                    let sigma = f64::from(var.to_array()[c]).sqrt();
                    let z = (got - scale * expected).abs() / (sigma + 1e-6);
                    worst = worst.max(z);
                    assert!(
                        z < 5.0,
                        "{filter:?} pixel ({x}, {y}) channel {c}: {got} against {} (σ {sigma})",
                        scale * expected
                    );
                }
            }
        }
        assert!(
            worst > 0.1,
            "{filter:?}: the test has noise to detect ({worst})"
        );
    }
}

#[test]
fn unequal_sample_counts_in_whole_rounds_keep_the_expected_image() {
    // A pilot whose noise grows to the right, so the shares do too (1/4 to 4 of the mean).
    let (width, height) = (16, 5);
    let edge = 6.3;
    let mut pilot = Film::new(width, height);
    for y in 0..height {
        for x in 0..width {
            let spread = 0.1 + 0.3 * x as f32;
            for v in [1.0 - spread, 1.0 + spread] {
                pilot.add(UVec2::new(x, y), Vec3::splat(v));
            }
        }
    }
    let allocation = Allocation::from_pilot(&pilot, &PixelCosts::new(width, height)).in_rounds();
    let counts: Vec<u32> = (0..width)
        .map(|x| allocation.per_round(UVec2::new(x, 0)).unwrap())
        .collect();
    assert!(
        counts[0] < counts[width as usize - 1],
        "the test needs unequal counts: {counts:?}"
    );
    let options = RenderOptions {
        allocation: Some(Arc::new(allocation)),
        ..RenderOptions::quiet()
    };
    let filter = Filter::default();
    let output = render_splatted(
        &filter,
        (width, height),
        RenderBudget::spp(2048),
        &options,
        1,
        2,
        3,
        |x, noise| step_sample(x, noise, edge),
    );
    let (image, variance) = (output.film.to_image(), output.film.variance_of_mean_image());
    for y in 0..height {
        for x in 0..width {
            let expected = step_expected(&filter, edge, x as f32 + 0.5, width);
            let got = f64::from(image.pixel(x, y).x);
            let sigma = f64::from(variance.pixel(x, y).x).sqrt();
            assert!(
                (got - expected).abs() < 5.0 * sigma + 1e-6,
                "pixel ({x}, {y}): {got} against {expected} (σ {sigma})"
            );
        }
    }
}

/// Per pixel, the variance over `replicates` of the red channel of the images `render(seed)`
/// makes, averaged over the pixels at least `margin` from the image's edges; and the mean of
/// the films' own variance estimates there.
fn replicate_variance(
    replicates: u64,
    (width, height): (u32, u32),
    margin: u32,
    render: impl Fn(u64) -> Film,
) -> (f64, f64) {
    let films: Vec<Film> = (0..replicates).map(&render).collect();
    let (mut empirical, mut estimated, mut pixels) = (0.0, 0.0, 0.0);
    for y in margin..height - margin {
        for x in margin..width - margin {
            let values: Vec<f64> = films
                .iter()
                .map(|f| f64::from(f.pixel_value(UVec2::new(x, y)).x))
                .collect();
            let mean = values.iter().sum::<f64>() / values.len() as f64;
            empirical += values.iter().map(|v| (v - mean).powi(2)).sum::<f64>()
                / (values.len() as f64 - 1.0);
            estimated += films
                .iter()
                .map(|f| f64::from(f.pixel_variance(UVec2::new(x, y)).x))
                .sum::<f64>()
                / values.len() as f64;
            pixels += 1.0;
        }
    }
    (empirical / pixels, estimated / pixels)
}

#[test]
fn splatting_the_gaussian_has_about_a_third_of_the_variance_of_importance_sampling_it() {
    let size = (24, 12);
    let spp = 8;
    let filter = Filter::default();
    // Path noise that dominates: radiance 10 with probability 1/10, else 0 (mean 1, variance
    // 9) everywhere.
    let noise = |_: Vec2, noise: f32| Vec3::splat(if noise < 0.1 { 10.0 } else { 0.0 });
    let (splat, splat_estimate) = replicate_variance(40, size, 2, |seed| {
        render_splatted(
            &filter,
            size,
            RenderBudget::spp(spp),
            &RenderOptions::quiet(),
            1,
            2,
            seed,
            noise,
        )
        .film
    });
    let (importance, _) = replicate_variance(40, size, 2, |seed| {
        render_blocks(
            size.0,
            size.1,
            &RenderBudget::spp(spp),
            &RenderOptions::quiet(),
            1,
            || (),
            |_: &mut (), pixels: &[UVec2], index: u32, values: &mut [Vec3]| {
                let [u, v, n] = uniforms(pixels[0], index, seed);
                let x = filter.sample_film_position(pixels[0], Vec2::new(u, v), size.0, size.1);
                values[0] = noise(x, n);
            },
            None,
        )
        .unwrap()
        .film
    });
    // One sample's variance 9 over 8 samples with importance sampling. Splatted, a sample
    // `w L` at a uniform position has the variance `E[L²] ∫f² − E[L]² Σ_q W_q²` summed over the
    // pixels q, with ∫f² = 1/(4πσ²) ≈ 0.318 (σ = 0.5 pixels, ignoring the truncation) and
    // Σ W_q² ≈ (0.683² + 2 · 0.157²)² ≈ 0.266: (10 · 0.318 − 0.266) / 9 ≈ 0.32 of it. (With
    // noise of variance 1/3 and mean 1, 0.47: the weights' own spread matters where the path
    // noise does not dominate.)
    let ratio = splat / importance;
    assert!(
        (importance - 9.0 / 8.0).abs() < 0.2 * 9.0 / 8.0,
        "importance sampling's variance {importance}"
    );
    assert!(
        (0.26..0.39).contains(&ratio),
        "splatted variance {splat} against {importance}: ratio {ratio}"
    );
    assert!(
        (splat_estimate / splat - 1.0).abs() < 0.2,
        "the film's variance estimate {splat_estimate} against the replicates' {splat}"
    );
}

/// A sample whose magnitudes span 2⁻¹⁰ .. 2¹⁰, so that any change in the order of summation
/// would change the sums' low bits.
fn wide_sample(x: Vec2, noise: f32) -> Vec3 {
    let scale = ((noise * 21.0).floor() - 10.0).exp2();
    Vec3::new(x.x.fract(), noise, x.y.fract() * 0.3) * scale
}

#[test]
fn splatted_films_are_bit_identical_across_threads_tiles_blocks_passes_and_pieces() {
    let size = (37, 19);
    let filter = Filter::default();
    let run = |budget: RenderBudget, options: &RenderOptions, block: u32, threads: usize| {
        render_splatted(
            &filter,
            size,
            budget,
            options,
            block,
            threads,
            7,
            wide_sample,
        )
    };
    let quiet = RenderOptions::quiet();
    for block in [1, 4] {
        let whole = run(RenderBudget::spp(12), &quiet, block, 1).film;
        assert!(whole.filtered().is_some());
        let two = run(RenderBudget::spp(12), &quiet, block, 2).film;
        assert_eq!(whole, two, "block {block}: 1 thread against 2");
        let small_tiles = RenderOptions {
            tile_size: Some(4),
            ..RenderOptions::quiet()
        };
        assert_eq!(
            whole,
            run(RenderBudget::spp(12), &small_tiles, block, 2).film,
            "block {block}: tiles of 4"
        );
        // Stopped after 5 samples and resumed to 12.
        let head = run(RenderBudget::spp(5), &quiet, block, 2);
        let resume = |film: Film, spp: u32| RenderOptions {
            resume: Some(Arc::new(ResumePoint {
                film,
                spp,
                passes: 1,
                non_finite: Default::default(),
            })),
            ..RenderOptions::quiet()
        };
        let resumed = run(
            RenderBudget::spp(12),
            &resume(head.film.clone(), 5),
            block,
            2,
        );
        assert_eq!(whole, resumed.film, "block {block}: resumed");
        // Samples 5..12 rendered on their own (`--samples 5..12`) and merged with 0..5.
        let tail = run(
            RenderBudget::spp(12),
            &resume(Film::splatting(size.0, size.1), 5),
            block,
            1,
        );
        let mut merged = tail.film.clone();
        merged.merge(&head.film).unwrap();
        // Exact sums merge exactly (the samples' f64 sums of squares only to rounding).
        assert_eq!(merged.filtered(), whole.filtered(), "block {block}: merged");
        for (a, b) in merged.pixels().iter().zip(whole.pixels()) {
            assert_eq!((a.sum, a.count), (b.sum, b.count), "block {block}: merged");
        }
        assert_eq!(merged.to_image(), whole.to_image());
    }
}
