//! Per-call cost of the RNG, every warp and every sampler. `cargo bench -p sampling` (about 40 s).

use criterion::{Criterion, criterion_group, criterion_main};
use glam::{UVec2, Vec2, Vec3};
use sampling::warp::*;
use sampling::{AnySampler, Rng, Sampler, SamplerKind};
use std::hint::black_box;
use std::time::Duration;

fn rng(c: &mut Criterion) {
    let mut group = c.benchmark_group("rng");
    let mut rng = Rng::new(1);
    group.bench_function("next_u32", |b| b.iter(|| black_box(rng.next_u32())));
    group.bench_function("next_f32", |b| b.iter(|| black_box(rng.next_f32())));
    group.bench_function("next_below_1000", |b| {
        b.iter(|| black_box(rng.next_below(black_box(1000))))
    });
    let mut index = 0_u32;
    group.bench_function("for_sample", |b| {
        b.iter(|| {
            index = index.wrapping_add(1);
            black_box(Rng::for_sample(UVec2::new(index & 255, 7), index, 3))
        })
    });
    group.finish();
}

/// 1024 uniform points, so a warp's benchmark measures the warp rather than the generator.
fn points() -> Vec<Vec2> {
    let mut rng = Rng::new(9);
    (0..1024)
        .map(|_| Vec2::new(rng.next_f32(), rng.next_f32()))
        .collect()
}

fn bench_warp<T>(c: &mut Criterion, name: &str, warp: impl Fn(Vec2) -> T) {
    let us = points();
    let mut i = 0;
    c.bench_function(name, |b| {
        b.iter(|| {
            i = (i + 1) & 1023;
            black_box(warp(black_box(us[i])))
        })
    });
}

fn warps(c: &mut Criterion) {
    bench_warp(c, "warp/uniform_hemisphere", sample_uniform_hemisphere);
    bench_warp(c, "warp/cosine_hemisphere", sample_cosine_hemisphere);
    bench_warp(c, "warp/uniform_sphere", sample_uniform_sphere);
    bench_warp(c, "warp/concentric_disk", sample_concentric_disk);
    bench_warp(c, "warp/uniform_triangle", sample_uniform_triangle);
    bench_warp(c, "warp/uniform_cone", |u| sample_uniform_cone(u, 0.1));
    bench_warp(c, "warp/invert_cosine_hemisphere", |u| {
        invert_cosine_hemisphere(Vec3::new(u.x - 0.5, u.y - 0.5, 0.5).normalize())
    });
}

fn samplers(c: &mut Criterion) {
    for kind in SamplerKind::ALL {
        let name = kind.name();
        let mut group = c.benchmark_group(format!("sampler/{name}"));
        let mut sampler = AnySampler::new(kind, 1, 16);
        let mut n = 0_u32;
        group.bench_function("start_plus_pixel_2d", |b| {
            b.iter(|| {
                n = n.wrapping_add(1);
                sampler.start_pixel_sample(UVec2::new((n >> 4) & 511, n >> 13), n & 15);
                black_box(sampler.next_2d())
            })
        });
        // Later dimensions of one sample (their cost does not depend on the dimension's number).
        sampler.start_pixel_sample(UVec2::new(3, 4), 5);
        group.bench_function("next_1d", |b| b.iter(|| black_box(sampler.next_1d())));
        group.bench_function("next_2d", |b| b.iter(|| black_box(sampler.next_2d())));
        group.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .measurement_time(Duration::from_secs(1))
        .warm_up_time(Duration::from_millis(300))
        .sample_size(30);
    targets = rng, warps, samplers
}
criterion_main!(benches);
