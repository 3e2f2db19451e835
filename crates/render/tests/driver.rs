//! Tests of the render driver: reproducibility across thread counts and pass splits, budgets
//! that stop at pass boundaries, and exclusion of non-finite samples.

use std::sync::Arc;
use std::time::Duration;

use glam::{UVec2, Vec3};
use render::adaptive::{Allocation, PixelCosts};
use render::driver::{
    PassSamples, RenderBudget, RenderOptions, RenderOutput, ResumePoint, StopSignal, render,
    render_blocks, render_pass,
};
use render::film::Film;
use render::tiles::tiles;

/// A hash of (pixel, sample index) to 64 well-mixed bits (SplitMix64's finaliser).
fn hash(pixel: UVec2, index: u32) -> u64 {
    let mut z = (u64::from(pixel.x) << 40) ^ (u64::from(pixel.y) << 20) ^ u64::from(index);
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A deterministic sample whose magnitudes span 2⁻¹⁰ .. 2¹⁰, so that any change in the order
/// of summation would change the sums' low bits. The scratch counter must not matter.
fn deterministic_sample(calls: &mut u64, pixel: UVec2, index: u32) -> Vec3 {
    *calls += 1;
    let h = hash(pixel, index);
    let scale = ((h & 31) as f32 - 10.0).exp2();
    let frac = |shift: u32| ((h >> shift) & 0xffff) as f32 / 65536.0;
    Vec3::new(frac(8), frac(24), frac(40)) * scale
}

/// Renders `budget` with the deterministic sample on a pool of `threads` threads.
fn render_on(threads: usize, budget: RenderBudget, options: RenderOptions) -> RenderOutput {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| render(45, 29, &budget, &options, || 0u64, deterministic_sample))
        .unwrap()
}

#[test]
fn films_are_bit_identical_across_thread_counts_and_tile_sizes() {
    let one = render_on(1, RenderBudget::spp(9), RenderOptions::quiet());
    let two = render_on(2, RenderBudget::spp(9), RenderOptions::quiet());
    let small_tiles = render_on(
        2,
        RenderBudget::spp(9),
        RenderOptions {
            tile_size: Some(5),
            ..RenderOptions::quiet()
        },
    );
    assert_eq!((one.threads, two.threads), (1, 2));
    assert_eq!(one.spp, 9);
    assert_eq!(one.film, two.film);
    assert_eq!(one.film, small_tiles.film);
    assert_eq!(one.film.total_samples(), 45 * 29 * 9);
}

#[test]
fn splitting_samples_into_passes_gives_the_same_bits() {
    let whole = render_on(2, RenderBudget::spp(8), RenderOptions::quiet()).film;
    let mut passes = Film::new(45, 29);
    let all_tiles = tiles(45, 29, 16);
    for (first, spp) in [(0, 1), (1, 2), (3, 5)] {
        render_pass(
            &mut passes,
            &all_tiles,
            PassSamples {
                first,
                count: spp,
                allocation: None,
            },
            &|| 0u64,
            &deterministic_sample,
            None,
            &|_| {},
        );
    }
    assert_eq!(passes, whole);
}

/// A pilot film for a 45 × 29 image whose left third has 9 times the right part's relative
/// variance (so 3 times its samples).
fn uneven_allocation() -> Arc<Allocation> {
    let mut pilot = Film::new(45, 29);
    for y in 0..29 {
        for x in 0..45 {
            let spread = if x < 15 { 3.0 } else { 1.0 };
            for value in [1.0 - 0.1 * spread, 1.0 + 0.1 * spread] {
                pilot.add(UVec2::new(x, y), Vec3::splat(value));
            }
        }
    }
    Arc::new(Allocation::from_pilot(&pilot, &PixelCosts::new(45, 29)))
}

#[test]
fn an_allocation_gives_each_pixel_its_own_sample_count_whatever_the_threads() {
    let allocation = uneven_allocation();
    let options = RenderOptions {
        allocation: Some(allocation.clone()),
        ..RenderOptions::quiet()
    };
    let one = render_on(1, RenderBudget::spp(12), options.clone());
    let two = render_on(2, RenderBudget::spp(12), options);
    assert_eq!(one.film, two.film);
    let (left, right) = (UVec2::new(2, 10), UVec2::new(40, 10));
    let (n_left, n_right) = (one.film.pixel(left).count, one.film.pixel(right).count);
    assert_eq!(n_left, allocation.samples(left, 12));
    assert_eq!(n_right, allocation.samples(right, 12));
    assert!(
        n_left >= 2 * n_right,
        "left {n_left} samples, right {n_right}"
    );
    // The pixel is the mean of exactly its own first n samples.
    let expected = (0..n_left)
        .map(|i| deterministic_sample(&mut 0, left, i))
        .sum::<Vec3>()
        / n_left as f32;
    let got = one.film.to_image().pixel(2, 10);
    assert!((got - expected).abs().max_element() <= 1e-6 * expected.max_element());
    // About the budget's mean number of samples per pixel overall.
    let mean = one.film.total_samples() as f64 / (45.0 * 29.0);
    assert!((mean - 12.0).abs() < 0.5, "mean {mean} samples per pixel");
}

/// Renders `budget` by `block × block` blocks on `threads` threads: each value is the
/// deterministic sample of its pixel plus 2⁻¹² times the sum of the others of its call, so it
/// depends on which pixels are taken together. Checks on the way that every call's pixels lie
/// in one image-aligned block, in row order.
fn render_blocks_on(
    threads: usize,
    block: u32,
    budget: RenderBudget,
    options: RenderOptions,
) -> RenderOutput {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let sample_block = |calls: &mut u64, pixels: &[UVec2], index: u32, values: &mut [Vec3]| {
        assert!(!pixels.is_empty() && pixels.len() <= (block * block) as usize);
        assert!(
            pixels.iter().all(|p| *p / block == pixels[0] / block),
            "{pixels:?}"
        );
        assert!(
            pixels
                .windows(2)
                .all(|w| (w[0].y, w[0].x) < (w[1].y, w[1].x))
        );
        let own: Vec<Vec3> = pixels
            .iter()
            .map(|&p| deterministic_sample(calls, p, index))
            .collect();
        let total: Vec3 = own.iter().sum();
        for (value, own) in values.iter_mut().zip(&own) {
            *value = *own + (total - *own) * (-12.0_f32).exp2();
        }
    };
    pool.install(|| {
        render_blocks(
            45,
            29,
            &budget,
            &options,
            block,
            || 0u64,
            sample_block,
            None,
        )
    })
    .unwrap()
}

#[test]
fn blocks_of_one_pixel_are_the_per_pixel_render() {
    let options = RenderOptions {
        allocation: Some(uneven_allocation()),
        ..RenderOptions::quiet()
    };
    let pixels = render_on(2, RenderBudget::spp(7), options.clone());
    let blocks = render_blocks_on(2, 1, RenderBudget::spp(7), options);
    assert_eq!(pixels.film, blocks.film);
}

#[test]
fn block_renders_are_bit_identical_across_threads_tiles_and_passes() {
    for block in [2, 4] {
        let allocation = uneven_allocation();
        let with = |tile_size, allocation: &Option<Arc<Allocation>>| RenderOptions {
            tile_size,
            allocation: allocation.clone(),
            ..RenderOptions::quiet()
        };
        for allocation in [None, Some(allocation.clone())] {
            let one = render_blocks_on(1, block, RenderBudget::spp(9), with(None, &allocation));
            let two = render_blocks_on(2, block, RenderBudget::spp(9), with(None, &allocation));
            // Tiles of 5 are rounded up to a multiple of the block.
            let odd = render_blocks_on(2, block, RenderBudget::spp(9), with(Some(5), &allocation));
            assert_eq!(
                one.film, two.film,
                "{block}x{block} blocks, 1 and 2 threads"
            );
            assert_eq!(one.film, odd.film, "{block}x{block} blocks, tiles of 5");
            // A pixel has exactly its own samples, the allocation's count of them.
            let pixel = UVec2::new(2, 10);
            let expected = allocation.as_ref().map_or(9, |a| a.samples(pixel, 9));
            assert_eq!(one.film.pixel(pixel).count, expected);
        }
        // A block's pixels are taken together: the values differ from one pixel at a time.
        let single = render_on(1, RenderBudget::spp(9), RenderOptions::quiet());
        let blocks = render_blocks_on(1, block, RenderBudget::spp(9), RenderOptions::quiet());
        assert_ne!(single.film, blocks.film);
    }
}

#[test]
fn allocated_passes_give_the_same_bits_as_one_pass() {
    let allocation = uneven_allocation();
    let whole = render_on(
        2,
        RenderBudget::spp(8),
        RenderOptions {
            allocation: Some(allocation.clone()),
            ..RenderOptions::quiet()
        },
    )
    .film;
    let mut passes = Film::new(45, 29);
    let all_tiles = tiles(45, 29, 16);
    for (first, count) in [(0, 1), (1, 2), (3, 5)] {
        render_pass(
            &mut passes,
            &all_tiles,
            PassSamples {
                first,
                count,
                allocation: Some(&allocation),
            },
            &|| 0u64,
            &deterministic_sample,
            None,
            &|_| {},
        );
    }
    assert_eq!(passes, whole);
}

#[test]
fn the_image_is_the_mean_of_each_pixels_samples() {
    let output = render_on(2, RenderBudget::spp(3), RenderOptions::quiet());
    let pixel = UVec2::new(44, 28);
    let expected = (0..3)
        .map(|i| deterministic_sample(&mut 0, pixel, i))
        .sum::<Vec3>()
        / 3.0;
    let got = output.film.to_image().pixel(44, 28);
    assert!(
        (got - expected).abs().max_element() <= 1e-6 * expected.max_element(),
        "{got} vs {expected}"
    );
}

#[test]
fn time_budget_stops_at_a_pass_boundary_after_the_time_is_spent() {
    // Each sample sleeps 1 ms: about 16 ms per sample per pixel on one thread for 4×4 pixels.
    let budget = RenderBudget::seconds(0.1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let output = pool
        .install(|| {
            render(
                4,
                4,
                &budget,
                &RenderOptions::quiet(),
                || (),
                |_, _, _| {
                    std::thread::sleep(Duration::from_millis(1));
                    Vec3::ONE
                },
            )
        })
        .unwrap();
    assert!(
        output.seconds >= 0.1,
        "stopped after {} s, before the budget",
        output.seconds
    );
    assert!(
        output.passes >= 2 && output.spp >= 2,
        "{} passes, {} spp",
        output.passes,
        output.spp
    );
    assert!(
        output.spp < 100,
        "{} spp cannot fit in 0.1 s at 1 ms per sample",
        output.spp
    );
    for y in 0..4 {
        for x in 0..4 {
            assert_eq!(
                output.film.pixel(UVec2::new(x, y)).count,
                output.spp,
                "pixel ({x}, {y})"
            );
        }
    }
}

#[test]
fn sample_limit_stops_a_timed_render_first() {
    let budget = RenderBudget {
        max_spp: Some(5),
        max_seconds: Some(60.0),
    };
    let output = render_on(2, budget, RenderOptions::quiet());
    assert_eq!(output.spp, 5);
    assert_eq!(output.film.total_samples(), 45 * 29 * 5);
    assert!(output.seconds < 60.0);
}

#[test]
fn zero_samples_render_nothing_and_unbounded_budgets_are_refused() {
    let output = render_on(1, RenderBudget::spp(0), RenderOptions::quiet());
    assert_eq!(
        (output.spp, output.passes, output.film.total_samples()),
        (0, 0, 0)
    );
    let unbounded = render(
        2,
        2,
        &RenderBudget::default(),
        &RenderOptions::quiet(),
        || (),
        |_, _, _| Vec3::ONE,
    );
    assert!(unbounded.is_err());
}

#[test]
fn non_finite_samples_are_counted_and_left_out() {
    let sample = |_: &mut (), pixel: UVec2, index: u32| -> Vec3 {
        match (pixel.x, index % 4) {
            (0, 1) => Vec3::new(1.0, f32::NAN, 0.0),
            (0, 2) => Vec3::new(f32::INFINITY, 0.0, 0.0),
            (1, 3) => Vec3::new(f32::NEG_INFINITY, f32::NAN, 0.0),
            _ => Vec3::splat(index as f32),
        }
    };
    let output = render(
        2,
        1,
        &RenderBudget::spp(8),
        &RenderOptions::quiet(),
        || (),
        sample,
    )
    .unwrap();
    // Pixel 0: NaN at indices 1, 5 and infinity at 2, 6. Pixel 1: NaN (with infinity) at 3, 7.
    assert_eq!((output.non_finite.nan, output.non_finite.inf), (4, 2));
    assert_eq!(output.film.pixel(UVec2::new(0, 0)).count, 4);
    assert_eq!(output.film.pixel(UVec2::new(1, 0)).count, 6);
    let image = output.film.to_image();
    assert_eq!(
        image.pixel(0, 0),
        Vec3::splat([0.0, 3.0, 4.0, 7.0].iter().sum::<f32>() / 4.0)
    );
    assert_eq!(
        image.pixel(1, 0),
        Vec3::splat([0.0, 1.0, 2.0, 4.0, 5.0, 6.0].iter().sum::<f32>() / 6.0)
    );
    assert!(image.data.iter().all(|p| p.is_finite()));
}

#[test]
fn resuming_continues_the_sample_indices_to_the_same_bits() {
    let whole = render_on(2, RenderBudget::spp(8), RenderOptions::quiet());
    let first = render_on(1, RenderBudget::spp(3), RenderOptions::quiet());
    let resume = ResumePoint {
        film: first.film,
        spp: first.spp,
        passes: first.passes,
        non_finite: first.non_finite,
    };
    let options = RenderOptions {
        resume: Some(Arc::new(resume)),
        ..RenderOptions::quiet()
    };
    let resumed = render_on(2, RenderBudget::spp(8), options);
    assert_eq!((resumed.spp, resumed.resumed_spp), (8, 3));
    assert!(resumed.passes > first.passes);
    assert_eq!(
        resumed.film, whole.film,
        "3 + 5 samples must equal 8 in one go"
    );
}

#[test]
fn resuming_a_film_of_another_size_is_refused() {
    let options = RenderOptions {
        resume: Some(Arc::new(ResumePoint {
            film: Film::new(4, 4),
            spp: 1,
            passes: 1,
            non_finite: Default::default(),
        })),
        ..RenderOptions::quiet()
    };
    let result = render(
        5,
        4,
        &RenderBudget::spp(2),
        &options,
        || (),
        |_, _, _| Vec3::ONE,
    );
    assert!(
        result
            .unwrap_err()
            .to_string()
            .contains("4x4 pixels but the image is 5x4")
    );
}

#[test]
fn a_stop_signal_ends_the_render_at_a_pass_boundary_with_whole_pixels() {
    let stop = StopSignal::new();
    let options = RenderOptions {
        stop: Some(stop.clone()),
        ..RenderOptions::quiet()
    };
    // The signal is raised while the first pass (1 sample per pixel) runs; that pass finishes.
    let output = render(
        6,
        5,
        &RenderBudget::spp(1000),
        &options,
        || (),
        |_, _, index| {
            if index == 0 {
                stop.raise();
            }
            Vec3::splat(index as f32 + 1.0)
        },
    )
    .unwrap();
    assert!(output.interrupted);
    assert_eq!((output.spp, output.passes), (1, 1));
    assert_eq!(
        output.film.total_samples(),
        30,
        "every pixel has its sample"
    );
    assert!(output.film.to_image().data.iter().all(|&p| p == Vec3::ONE));

    let uninterrupted = render(
        2,
        2,
        &RenderBudget::spp(3),
        &RenderOptions::quiet(),
        || (),
        |_, _, _| Vec3::ONE,
    );
    assert!(!uninterrupted.unwrap().interrupted);
}
