//! Rendering throughput on the scene suite, and of splatting camera samples: the BVH build of
//! every scene, closest-hit and occlusion throughput (rays per second) on the rays a 1-spp
//! render of each scene traces, camera samples splatted per second into a film region, and
//! samples per second of every integrator preset on the Cornell box, and on two threads the
//! Cornell box with and without adaptive sampling (whose uneven per-pixel sample counts test how
//! evenly the threads share a pass).
//!
//! Run with `cargo bench -p render --bench render` (a few minutes); one group with e.g.
//! `cargo bench -p render --bench render -- samples`. Everything but the `two_threads` group runs
//! on one thread, so the figures do not depend on how busy the machine's other cores are; thread
//! scaling is measured by `cargo xtask raycast-limit`.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Duration;

use criterion::{BatchSize, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use geometry::Accel;
use glam::{UVec2, Vec2, Vec3};
use render::driver::RenderOptions;
use render::film::SplatSum;
use render::filter::{Filter, Splatter};
use render::plan::plan_from_flags;
use render::session::{film_filter, render_scene, render_scene_recording};
use sampling::SamplerKind;
use scene::RenderScene;

/// Image size of the Cornell box for the samples-per-second group (pixels per side).
const SAMPLES_RESOLUTION: &str = "64";
/// Samples per pixel per measured render in the samples-per-second group.
const SAMPLES_SPP: u32 = 4;

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

fn load(path: &Path, overrides: &[(&str, &str)]) -> RenderScene {
    let overrides: Vec<(String, String)> = overrides
        .iter()
        .map(|&(k, v)| (k.to_string(), v.to_string()))
        .collect();
    scene::load(path, &overrides).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The suite's scene files, sorted.
fn suite() -> Vec<(String, RenderScene)> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(scenes_dir())
        .expect("the scenes directory")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|f| {
            let name = f.file_stem().expect("a file name").to_string_lossy();
            (name.into_owned(), load(f, &[]))
        })
        .collect()
}

/// A one-thread pool, so figures do not depend on the load of other cores.
fn one_thread() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool")
}

fn scene_bvh(c: &mut Criterion) {
    let pool = one_thread();
    for (name, scene) in suite() {
        let shapes = scene.world.accel().shapes().to_vec();
        let accel = scene.world.accel();
        let plan = plan_from_flags(&scene, &["--spp", "1", "--seed", "7"]).expect("a plan");
        let filter = film_filter(scene.desc.film.filter).expect("the scene's filter");
        let (_, log) = pool
            .install(|| render_scene_recording(&scene, &plan, &filter, &RenderOptions::quiet()))
            .expect("the recording render");

        let mut group = c.benchmark_group(format!("scene_bvh/{name}"));
        group
            .sample_size(10)
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(2));
        group.bench_function("build", |b| {
            b.iter_batched(
                || shapes.clone(),
                |shapes| black_box(Accel::new(shapes)),
                BatchSize::LargeInput,
            )
        });
        group.throughput(Throughput::Elements(log.closest.len() as u64));
        group.bench_function("closest_hit", |b| {
            b.iter(|| {
                log.closest
                    .iter()
                    .filter(|r| accel.intersect(r, f32::INFINITY).is_some())
                    .count()
            })
        });
        group.throughput(Throughput::Elements(log.shadow.len() as u64));
        group.bench_function("occluded", |b| {
            b.iter(|| {
                log.shadow
                    .iter()
                    .filter(|s| accel.occluded(&s.ray, s.t_max))
                    .count()
            })
        });
        group.finish();
    }
}

fn samples(c: &mut Criterion) {
    let pool = one_thread();
    let res = SAMPLES_RESOLUTION;
    let scene = load(
        &scenes_dir().join("cbox.xml"),
        &[("res", res), ("spp", "4")],
    );
    let filter = film_filter(scene.desc.film.filter).expect("the scene's filter");
    let pixels = u64::from(scene.desc.film.width) * u64::from(scene.desc.film.height);
    let mut group = c.benchmark_group("samples/cbox");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    group.throughput(Throughput::Elements(pixels * u64::from(SAMPLES_SPP)));
    let spp = SAMPLES_SPP.to_string();
    for integrator in ["reference", "nee", "mis", "ris", "auto"] {
        for sampler in SamplerKind::ALL.map(SamplerKind::name) {
            if sampler != "independent" && integrator != "auto" {
                continue;
            }
            let flags = [
                "--integrator",
                integrator,
                "--sampler",
                sampler,
                "--spp",
                &spp,
            ];
            let plan = plan_from_flags(&scene, &flags).expect("a plan");
            group.bench_function(BenchmarkId::new(integrator, sampler), |b| {
                b.iter(|| {
                    pool.install(|| render_scene(&scene, &plan, &filter, &RenderOptions::quiet()))
                        .expect("the render")
                })
            });
        }
    }
    group.finish();
}

/// Camera samples splatted per second, the film's share of each sample's cost: a sample's
/// weights for every pixel that Mitsuba's default gaussian (and a Mitchell filter, with negative
/// lobes) reaches, added to a 64 × 64 region's [`SplatSum`]s, at positions spread over the
/// region by a fixed sequence.
fn splat(c: &mut Criterion) {
    const SIZE: u32 = 64;
    const SAMPLES: u32 = 4096;
    let mut group = c.benchmark_group("splat");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2));
    group.throughput(Throughput::Elements(u64::from(SAMPLES)));
    let filters = [
        ("gaussian", Filter::gaussian(0.5).expect("a gaussian")),
        (
            "mitchell",
            Filter::mitchell(1.0 / 3.0, 1.0 / 3.0).expect("a Mitchell filter"),
        ),
    ];
    for (name, filter) in filters {
        let splatter = Splatter::new(&filter, SIZE, SIZE).expect("a filter wider than a pixel");
        // A low-discrepancy walk over the region: golden-ratio steps on both axes.
        let positions: Vec<(Vec2, UVec2)> = (0..SAMPLES)
            .map(|i| {
                let u = Vec2::new(
                    (i as f32 * 0.618_034).fract(),
                    (i as f32 * 0.754_877_7).fract(),
                ) * SIZE as f32;
                (u, u.as_uvec2())
            })
            .collect();
        let value = Vec3::new(0.3, 0.5, 0.7);
        let mut sums = vec![SplatSum::default(); (SIZE * SIZE) as usize];
        group.bench_function(name, |b| {
            b.iter(|| {
                for &(film, pixel) in &positions {
                    splatter.splat(film, pixel, |first, weight_y, weights_x| {
                        let start = (first.y * SIZE + first.x) as usize;
                        let row_value = value * weight_y;
                        for (sum, &weight_x) in sums[start..].iter_mut().zip(weights_x) {
                            sum.add_weighted(row_value, weight_x);
                        }
                    });
                }
                black_box(&mut sums);
            })
        });
    }
    group.finish();
}

/// Samples per second on two threads, the Cornell box at its own 128 × 128 and 32 spp, with
/// `auto` and the Sobol sampler, with and without adaptive sampling: with the same samples traced
/// (the pilot's included), the two differ by how well the threads share each pass's tiles.
fn two_threads(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .expect("a two-thread pool");
    let scene = load(&scenes_dir().join("cbox.xml"), &[]);
    let filter = film_filter(scene.desc.film.filter).expect("the scene's filter");
    let spp = 32;
    let pixels = u64::from(scene.desc.film.width) * u64::from(scene.desc.film.height);
    let mut group = c.benchmark_group("two_threads/cbox");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    group.throughput(Throughput::Elements(pixels * spp));
    let spp = spp.to_string();
    for (name, adaptive) in [("sobol", false), ("sobol_adaptive", true)] {
        let mut flags = vec!["--sampler", "sobol", "--spp", &spp];
        if adaptive {
            flags.push("--adaptive");
        }
        let plan = plan_from_flags(&scene, &flags).expect("a plan");
        group.bench_function(name, |b| {
            b.iter(|| {
                pool.install(|| render_scene(&scene, &plan, &filter, &RenderOptions::quiet()))
                    .expect("the render")
            })
        });
    }
    group.finish();
}

criterion_group!(benches, scene_bvh, samples, splat, two_threads);
criterion_main!(benches);
