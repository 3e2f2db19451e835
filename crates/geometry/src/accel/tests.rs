//! Traversal against brute force over the same primitive tests, so any disagreement is the
//! hierarchy's fault (missed boxes, wrong id mapping), not the intersectors'.

use glam::Vec3;

use super::Accel;
use super::prim::PrimHit;
use super::query::RayQuery;
use super::walk::StackKind;
use crate::{Ray, Shape, Sphere, TriangleMesh};

/// xorshift64*, enough for reproducible inputs here.
struct Rng(u64);

impl Rng {
    fn f32(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32 / (1u64 << 24) as f32
    }
    fn vec(&mut self) -> Vec3 {
        Vec3::new(self.f32(), self.f32(), self.f32()) * 2.0 - 1.0
    }
}

fn random_scene(rng: &mut Rng, triangles: usize, spheres: usize) -> Vec<Shape> {
    let positions: Vec<Vec3> = (0..triangles)
        .flat_map(|_| {
            let c = rng.vec();
            [c, c + 0.2 * rng.vec(), c + 0.2 * rng.vec()]
        })
        .collect();
    let indices = (0..triangles as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    let mut shapes = vec![Shape::Mesh(
        TriangleMesh::new(positions, None, None, indices).expect("valid"),
    )];
    shapes.extend((0..spheres).map(|_| {
        Shape::Sphere(Sphere {
            center: rng.vec(),
            radius: 0.02 + 0.1 * rng.f32(),
            flip_normals: false,
        })
    }));
    shapes
}

/// Closest hit over every primitive, `(BVH-order id, hit)`.
fn brute_force(accel: &Accel, ray: &Ray, t_max: f32) -> Option<(usize, PrimHit)> {
    let query = RayQuery::new(ray.origin.into(), ray.dir.into());
    let mut best: Option<(usize, PrimHit)> = None;
    for (id, geom) in accel.geoms.iter().enumerate() {
        let limit = best.map_or(t_max, |(_, h)| h.t());
        if let Some(hit) = geom.intersect(&query, limit) {
            best = Some((id, hit));
        }
    }
    best
}

/// Checks closest hits and occlusion of `count` rays against brute force.
fn check_against_brute_force(accel: &Accel, rng: &mut Rng, count: usize, scene: &str) -> usize {
    let mut hits = 0;
    for i in 0..count {
        // Half the rays start outside the scene, half inside it; some have a finite t_max.
        let origin = if i % 2 == 0 {
            3.0 * rng.vec().normalize()
        } else {
            rng.vec()
        };
        let ray = Ray::new(origin, rng.vec() - 0.5 * origin);
        let t_max = if i % 3 == 0 {
            2.0 * rng.f32()
        } else {
            f32::INFINITY
        };
        let expected = brute_force(accel, &ray, t_max);
        let replay = format!("{scene}, ray {i}: {ray:?}, t_max {t_max}");
        match (expected, accel.intersect(&ray, t_max)) {
            (None, None) => {}
            (Some((_, hit)), Some(got)) => {
                assert_eq!(got.t.to_bits(), hit.t().to_bits(), "{replay}");
                // Coincident primitives tie; the reported one must itself be hit at that t.
                let query = RayQuery::new(ray.origin.into(), ray.dir.into());
                let reported = accel
                    .infos
                    .iter()
                    .position(|info| (info.shape, info.prim) == (got.shape, got.prim))
                    .expect("the reported primitive exists");
                let own = accel.geoms[reported]
                    .intersect(&query, t_max)
                    .map(|h| h.t().to_bits());
                assert_eq!(own, Some(got.t.to_bits()), "{replay}");
                hits += 1;
            }
            (e, g) => panic!("{replay}: brute force {e:?}, BVH {g:?}"),
        }
        assert_eq!(accel.occluded(&ray, t_max), expected.is_some(), "{replay}");
    }
    hits
}

#[test]
fn closest_hit_and_occlusion_match_brute_force() {
    let mut rng = Rng(0x5eed_0001);
    let accel = Accel::new(random_scene(&mut rng, 3000, 60));
    assert_ne!(accel.stack, StackKind::Heap);
    let hits = check_against_brute_force(&accel, &mut rng, 4000, "random soup");
    // The scene is dense enough that most rays hit something; a broken test would see none.
    assert!(hits > 2000, "only {hits} of 4000 rays hit");
}

#[test]
fn every_stack_size_matches_brute_force() {
    let mut rng = Rng(0x5eed_0002);
    let small = Accel::new(random_scene(&mut rng, 300, 20));
    assert_eq!(small.stack, StackKind::Small, "depth {}", small.depth);
    let hits = check_against_brute_force(&small, &mut rng, 2000, "small scene");
    assert!(hits > 200, "only {hits} of 2000 rays hit");
    let large = Accel::new(random_scene(&mut rng, 200_000, 0));
    assert_eq!(large.stack, StackKind::Fixed, "depth {}", large.depth);
    let hits = check_against_brute_force(&large, &mut rng, 200, "large scene");
    assert!(hits > 100, "only {hits} of 200 rays hit");
}

#[test]
fn coincident_primitives_build_fast_and_traverse_correctly() {
    // Thousands of identical boxes made obvhs' PLOC build a chain (quadratic time, and a tree
    // deeper than its traversal stack); the tie-breaking pads and the heap stack handle it.
    let mut rng = Rng(7);
    let mut shapes = random_scene(&mut rng, 300, 5);
    shapes.push(Shape::Mesh(
        TriangleMesh::new(
            vec![
                Vec3::new(-0.5, -0.5, 0.2),
                Vec3::new(0.5, -0.5, 0.2),
                Vec3::new(0.0, 0.5, 0.2),
            ],
            None,
            None,
            vec![[0, 1, 2]; 20_000],
        )
        .expect("valid"),
    ));
    shapes.extend((0..2000).map(|_| {
        Shape::Sphere(Sphere {
            center: Vec3::new(0.3, 0.3, -0.3),
            radius: 0.1,
            flip_normals: false,
        })
    }));
    let start = std::time::Instant::now();
    let accel = Accel::new(shapes);
    assert!(
        start.elapsed().as_secs_f32() < 5.0,
        "build took {:?}",
        start.elapsed()
    );
    let hits = check_against_brute_force(&accel, &mut rng, 300, "coincident primitives");
    assert!(hits > 30, "only {hits} of 300 rays hit");
}

#[test]
fn deep_trees_use_the_heap_stack() {
    let mut rng = Rng(11);
    let shapes = vec![Shape::Mesh(
        TriangleMesh::new(
            vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            None,
            None,
            vec![[0, 1, 2]; 60_000],
        )
        .expect("valid"),
    )];
    let accel = Accel::new(shapes);
    assert_eq!(
        accel.stack,
        StackKind::Heap,
        "depth {} fits the fixed stack; pick a deeper case",
        accel.depth
    );
    check_against_brute_force(&accel, &mut rng, 50, "deep tree");
    let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), Vec3::NEG_Z);
    assert_eq!(accel.intersect(&ray, f32::INFINITY).map(|h| h.t), Some(1.0));
}

#[test]
fn primitive_order_is_a_permutation() {
    let mut rng = Rng(3);
    let accel = Accel::new(random_scene(&mut rng, 500, 20));
    let mut seen: Vec<(u32, u32)> = accel.infos.iter().map(|i| (i.shape, i.prim)).collect();
    seen.sort_unstable();
    let expected: Vec<(u32, u32)> = (0..500)
        .map(|p| (0, p))
        .chain((1..21).map(|s| (s, 0)))
        .collect();
    assert_eq!(seen, expected);
    assert_eq!(accel.geoms.len(), accel.infos.len());
}
