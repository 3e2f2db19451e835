//! Cost of `Bsdf::sample` and of `eval` + `pdf_solid_angle` per BSDF, at 45° incidence.
//! Run with `cargo bench -p materials --bench bsdf`.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::{Vec2, Vec3};
use materials::{
    Bsdf, ComplexIor, Conductor, Dielectric, Diffuse, Microfacet, MicrofacetKind, RoughConductor,
};
use sampling::Rng;
use std::hint::black_box;

fn bsdfs() -> Vec<(&'static str, Bsdf)> {
    let gold = ComplexIor::new(
        Vec3::new(0.143, 0.374, 1.442),
        Vec3::new(3.983, 2.385, 1.603),
    );
    let rough = |kind| {
        let distribution = Microfacet::new(kind, 0.3).expect("finite alpha");
        Bsdf::from(RoughConductor::new(distribution, gold, Vec3::ONE))
    };
    vec![
        ("diffuse", Bsdf::from(Diffuse::new(Vec3::splat(0.5)))),
        ("conductor", Bsdf::from(Conductor::new(gold, Vec3::ONE))),
        ("rough_ggx", rough(MicrofacetKind::Ggx)),
        ("rough_beckmann", rough(MicrofacetKind::Beckmann)),
        (
            "dielectric",
            Bsdf::from(Dielectric::new(1.5, 1.0, Vec3::ONE, Vec3::ONE).expect("valid ior")),
        ),
    ]
}

fn bench(c: &mut Criterion) {
    let theta = 45_f32.to_radians();
    let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
    for (name, bsdf) in bsdfs() {
        let mut rng = Rng::new(1);
        c.bench_function(&format!("sample/{name}"), |b| {
            b.iter(|| {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                black_box(bsdf.sample(black_box(wo), rng.next_f32(), u))
            })
        });
        let mut rng = Rng::new(2);
        c.bench_function(&format!("eval_pdf/{name}"), |b| {
            b.iter(|| {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                let wi = sampling::warp::sample_cosine_hemisphere(u);
                black_box((bsdf.eval(wo, wi), bsdf.pdf_solid_angle(wo, wi)))
            })
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
