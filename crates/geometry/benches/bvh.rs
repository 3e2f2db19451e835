//! BVH build time and closest-hit throughput on a ~82k-triangle icosphere, with obvhs' own
//! traversal (non-conservative boxes, Möller–Trumbore) as the point of comparison for what the
//! robustness costs. Kept short: run with `cargo bench -p geometry --bench bvh`.

#[path = "../tests/common/mod.rs"]
mod common;

use std::hint::black_box;
use std::time::Duration;

use common::{Pcg32, icosphere};
use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use geometry::{Accel, Ray, Shape, TriangleMesh};
use glam::Vec3;
use obvhs::BvhBuildParams;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::ray::{Ray as ObvhsRay, RayHit};
use obvhs::triangle::Triangle;

const RAYS: usize = 20_000;

/// Incoherent rays: half from a shell around the sphere towards random points inside it, half
/// from inside it in random directions (all of those hit).
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

fn mesh() -> TriangleMesh {
    icosphere(6)
}

fn build(c: &mut Criterion) {
    let mesh = mesh();
    let mut group = c.benchmark_group("build");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(4));
    group.throughput(Throughput::Elements(mesh.triangle_count() as u64));
    group.bench_function("icosphere_82k", |b| {
        b.iter_batched(
            || vec![Shape::Mesh(mesh.clone())],
            |shapes| black_box(Accel::new(shapes)),
            BatchSize::LargeInput,
        )
    });
    group.finish();
}

fn trace(c: &mut Criterion) {
    let mesh = mesh();
    let rays = rays();
    let accel = Accel::new(vec![Shape::Mesh(mesh.clone())]);
    let tris: Vec<Triangle> = (0..mesh.triangle_count())
        .map(|i| {
            let [v0, v1, v2] = mesh.triangle(i).map(Vec3::into);
            Triangle { v0, v1, v2 }
        })
        .collect();
    let stock = build_cwbvh_from_tris(
        &tris,
        BvhBuildParams::medium_build(),
        &mut Duration::default(),
    );

    let mut group = c.benchmark_group("trace");
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

criterion_group!(benches, build, trace);
criterion_main!(benches);
