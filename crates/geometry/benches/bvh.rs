//! BVH build time and closest-hit / occlusion throughput (rays per second) on icospheres of
//! about 82k and 1.3M triangles, with obvhs' own traversal (non-conservative boxes,
//! Möller–Trumbore) as the point of comparison for what the robustness costs.
//!
//! Run with `cargo bench -p geometry --bench bvh` (about two minutes); one case with e.g.
//! `cargo bench -p geometry --bench bvh -- trace/1m`. Throughputs are on one thread.

#[path = "../tests/common/mod.rs"]
mod common;

use std::hint::black_box;
use std::time::Duration;

use common::Pcg32;
use criterion::{BatchSize, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use geometry::{Accel, Ray, Shape, TriangleMesh};
use glam::Vec3;
use obvhs::BvhBuildParams;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::ray::{Ray as ObvhsRay, RayHit};
use obvhs::triangle::Triangle;

/// Rays per measured iteration.
const RAYS: usize = 20_000;

/// The meshes: (name subdivision level). Level 6 has 81,920 triangles, level 8
/// has 1,310,720.
const MESHES: [(&str, u32); 2] = [("82k", 6), ("1m", 8)];

/// Incoherent rays: half from a shell around the unit sphere towards random points inside it,
/// half from inside it in random directions (all of those hit).
fn rays() -> Vec<Ray> {
    let mut rng = Pcg32::new(1);
    (0..RAYS)
        .map(|i| {
            if i % 2 == 0 {
                let origin = 3.0 * rng.unit();
                Ray::new(origin, 0.9 * rng.unit() * rng.f32() - origin)
            } else {
                Ray::new(0.9 * rng.unit() * rng.f32(), rng.unit())
            }
        })
        .collect()
}

fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("build");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    for (name, level) in MESHES {
        let mesh = TriangleMesh::icosphere(level);
        group.throughput(Throughput::Elements(mesh.triangle_count() as u64));
        group.bench_function(BenchmarkId::new("icosphere", name), |b| {
            b.iter_batched(
                || vec![Shape::Mesh(mesh.clone())],
                |shapes| black_box(Accel::new(shapes)),
                BatchSize::LargeInput,
            )
        });
    }
    group.finish();
}

/// obvhs' stock CWBVH over the same triangles, for comparison.
fn stock_bvh(mesh: &TriangleMesh) -> (obvhs::cwbvh::CwBvh, Vec<Triangle>) {
    let tris: Vec<Triangle> = (0..mesh.triangle_count())
        .map(|i| {
            let [v0, v1, v2] = mesh.triangle(i).map(Vec3::into);
            Triangle { v0, v1, v2 }
        })
        .collect();
    let bvh = build_cwbvh_from_tris(
        &tris,
        BvhBuildParams::medium_build(),
        &mut Duration::default(),
    );
    (bvh, tris)
}

fn trace(c: &mut Criterion) {
    let rays = rays();
    for (name, level) in MESHES {
        let mesh = TriangleMesh::icosphere(level);
        let accel = Accel::new(vec![Shape::Mesh(mesh.clone())]);
        let (stock, tris) = stock_bvh(&mesh);

        let mut group = c.benchmark_group(format!("trace/{name}"));
        group
            .sample_size(10)
            .warm_up_time(Duration::from_secs(1))
            .measurement_time(Duration::from_secs(3));
        group.throughput(Throughput::Elements(RAYS as u64));
        group.bench_function("closest_hit", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| accel.intersect(r, f32::INFINITY).is_some())
                    .count()
            })
        });
        group.bench_function("occluded", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| accel.occluded(r, f32::INFINITY))
                    .count()
            })
        });
        group.bench_function("obvhs_stock_closest_hit", |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| {
                        let ray = ObvhsRay::new_inf(r.origin.into(), r.dir.into());
                        let mut hit = RayHit::none();
                        stock.ray_traverse(ray, &mut hit, |ray, id| {
                            tris[stock.primitive_indices[id] as usize].intersect(ray)
                        })
                    })
                    .count()
            })
        });
        group.finish();
    }
}

criterion_group!(benches, build, trace);
criterion_main!(benches);
