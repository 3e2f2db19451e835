//! Traversal against brute force over the same primitive tests, so any disagreement is the
//! hierarchy's fault (missed boxes, wrong id mapping), not the intersectors'.

use glam::Vec3;

use super::Accel;
use super::prim::PrimInfo;
use super::query::RayQuery;
use super::stack::StackKind;
use crate::sphere::SphereGeom;
use crate::test_rng::TestRng;
use crate::triangle::TriangleCoords;
use crate::{Ray, Shape, Sphere, TriangleMesh};

fn random_scene(rng: &mut TestRng, triangles: usize, spheres: usize) -> Vec<Shape> {
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
            to_local: glam::Mat3::IDENTITY,
        })
    }));
    shapes
}

/// One primitive of the hierarchy, tested alone.
#[derive(Clone, Copy, Debug)]
enum Prim {
    Triangle(TriangleCoords),
    Sphere(SphereGeom),
}

impl Prim {
    /// The single-primitive test (for triangles, the one the packet test must match bit for bit).
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let query = RayQuery::new(ray.origin.into(), ray.dir.into());
        match self {
            Prim::Triangle(tri) => query.shear.intersect(tri, t_max).map(|h| h.t),
            Prim::Sphere(s) => s.intersect(query.origin, query.dir, t_max),
        }
    }
}

/// Every primitive of `accel` with its ids, triangles in packet order, then spheres.
fn primitives(accel: &Accel) -> Vec<(PrimInfo, Prim)> {
    let triangles = accel
        .geometry
        .packets
        .iter()
        .enumerate()
        .flat_map(|(p, packet)| {
            (0..4).map(move |lane| {
                (
                    accel.triangle_infos[4 * p + lane],
                    Prim::Triangle(packet.triangle(lane)),
                )
            })
        });
    let spheres = accel
        .sphere_infos
        .iter()
        .zip(&accel.geometry.spheres)
        .map(|(&info, &s)| (info, Prim::Sphere(s)));
    triangles
        .chain(spheres)
        .filter(|(info, _)| *info != PrimInfo::UNUSED)
        .collect()
}

/// Closest hit over every primitive: its distance.
fn brute_force(prims: &[(PrimInfo, Prim)], ray: &Ray, t_max: f32) -> Option<f32> {
    let mut best = None;
    for (_, prim) in prims {
        if let Some(t) = prim.intersect(ray, best.unwrap_or(t_max)) {
            best = Some(t);
        }
    }
    best
}

/// Checks closest hits and occlusion of `count` random rays against brute force; returns how
/// many hit something.
fn check_against_brute_force(accel: &Accel, rng: &mut TestRng, count: usize, scene: &str) -> usize {
    let rays = (0..count).map(|i| {
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
        (ray, t_max)
    });
    check_rays(accel, rays, scene)
}

/// Checks closest hits and occlusion of `rays` (with their `t_max`) against brute force;
/// returns how many hit something.
fn check_rays(accel: &Accel, rays: impl IntoIterator<Item = (Ray, f32)>, scene: &str) -> usize {
    let prims = primitives(accel);
    let mut hits = 0;
    for (i, (ray, t_max)) in rays.into_iter().enumerate() {
        let expected = brute_force(&prims, &ray, t_max);
        let replay = format!("{scene}, ray {i}: {ray:?}, t_max {t_max}");
        match (expected, accel.intersect(&ray, t_max)) {
            (None, None) => {}
            (Some(t), Some(got)) => {
                assert_eq!(got.t.to_bits(), t.to_bits(), "{replay}");
                // Coincident primitives tie; the reported one must itself be hit at that t.
                let (_, reported) = prims
                    .iter()
                    .find(|(info, _)| (info.shape, info.prim) == (got.shape, got.prim))
                    .expect("the reported primitive exists");
                let own = reported.intersect(&ray, t_max).map(f32::to_bits);
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
    let mut rng = TestRng(0x5eed_0001);
    let accel = Accel::new(random_scene(&mut rng, 3000, 60));
    assert_ne!(accel.stack, StackKind::Heap);
    let hits = check_against_brute_force(&accel, &mut rng, 4000, "random soup");
    // The scene is dense enough that most rays hit something; a broken test would see none.
    assert!(hits > 2000, "only {hits} of 4000 rays hit");
}

#[test]
fn every_stack_size_matches_brute_force() {
    let mut rng = TestRng(0x5eed_0002);
    let small = Accel::new(random_scene(&mut rng, 300, 20));
    assert_eq!(
        small.stack,
        StackKind::Small,
        "stack need {}",
        small.stack_need
    );
    let hits = check_against_brute_force(&small, &mut rng, 2000, "small scene");
    assert!(hits > 200, "only {hits} of 2000 rays hit");
    let large = Accel::new(random_scene(&mut rng, 200_000, 0));
    assert_eq!(
        large.stack,
        StackKind::Fixed,
        "stack need {}",
        large.stack_need
    );
    let hits = check_against_brute_force(&large, &mut rng, 200, "large scene");
    assert!(hits > 100, "only {hits} of 200 rays hit");
}

#[test]
fn coincident_primitives_build_fast_and_traverse_correctly() {
    // Thousands of identical boxes made obvhs' PLOC build a chain (quadratic time, and a tree
    // deeper than its traversal stack); the tie-breaking pads and the heap stack handle it.
    let mut rng = TestRng(7);
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
            to_local: glam::Mat3::IDENTITY,
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
    let mut rng = TestRng(11);
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
        "stack need {} fits the fixed stack; pick a deeper case",
        accel.stack_need
    );
    check_against_brute_force(&accel, &mut rng, 50, "deep tree");
    let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), Vec3::NEG_Z);
    assert_eq!(accel.intersect(&ray, f32::INFINITY).map(|h| h.t), Some(1.0));
}

#[test]
fn primitive_order_is_a_permutation() {
    let mut rng = TestRng(3);
    let accel = Accel::new(random_scene(&mut rng, 500, 20));
    let mut seen: Vec<(u32, u32)> = primitives(&accel)
        .iter()
        .map(|(i, _)| (i.shape, i.prim))
        .collect();
    seen.sort_unstable();
    let expected: Vec<(u32, u32)> = (0..500)
        .map(|p| (0, p))
        .chain((1..21).map(|s| (s, 0)))
        .collect();
    assert_eq!(seen, expected);
    assert_eq!(accel.triangle_infos.len(), 4 * accel.geometry.packets.len());
    assert_eq!(accel.sphere_infos.len(), accel.geometry.spheres.len());
}

/// Axis-aligned unit squares (two triangles each) on the planes `x, y, z = k / 4`, several of
/// them sharing planes and edges, plus a few random triangles and spheres: the case where rays
/// run along box faces and start on them.
fn grid_scene(rng: &mut TestRng) -> Vec<Shape> {
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for axis in 0..3 {
        for k in -4..=4 {
            for (a, b) in [(-1.0, -1.0), (0.0, -1.0), (-1.0, 0.0), (0.0, 0.0)] {
                if rng.f32() < 0.3 {
                    continue;
                }
                let corner = |u: f32, v: f32| {
                    let mut p = [0.0; 3];
                    p[axis] = k as f32 / 4.0;
                    p[(axis + 1) % 3] = a + u;
                    p[(axis + 2) % 3] = b + v;
                    Vec3::from(p)
                };
                let base = positions.len() as u32;
                positions.extend([
                    corner(0.0, 0.0),
                    corner(1.0, 0.0),
                    corner(1.0, 1.0),
                    corner(0.0, 1.0),
                ]);
                indices.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
            }
        }
    }
    let mut shapes = vec![Shape::Mesh(
        TriangleMesh::new(positions, None, None, indices).expect("valid"),
    )];
    shapes.extend(random_scene(rng, 40, 5));
    shapes
}

/// A point of every primitive of `accel` (a random point of a triangle, a pole of a sphere).
fn surface_points(accel: &Accel, rng: &mut TestRng) -> Vec<Vec3> {
    primitives(accel)
        .iter()
        .map(|(_, prim)| match prim {
            Prim::Triangle(tri) => {
                let (u, v) = (rng.f32(), rng.f32());
                let (u, v) = if u + v > 1.0 {
                    (1.0 - u, 1.0 - v)
                } else {
                    (u, v)
                };
                tri.point(Vec3::new(1.0 - u - v, u, v))
            }
            Prim::Sphere(s) => Vec3::from(s.center) + Vec3::Z * s.radius,
        })
        .collect()
}

#[test]
fn rays_from_surfaces_match_brute_force() {
    let mut rng = TestRng(0x5eed_0003);
    let accel = Accel::new(grid_scene(&mut rng));
    let points = surface_points(&accel, &mut rng);
    let rays: Vec<(Ray, f32)> = (0..3000)
        .map(|i| {
            let origin = points[i % points.len()];
            let t_max = if i % 4 == 0 { rng.f32() } else { f32::INFINITY };
            (Ray::new(origin, rng.vec()), t_max)
        })
        .collect();
    let hits = check_rays(&accel, rays, "rays from surfaces");
    assert!(hits > 1500, "only {hits} of 3000 rays hit");
}

#[test]
fn axis_parallel_and_grazing_rays_match_brute_force() {
    let mut rng = TestRng(0x5eed_0004);
    let accel = Accel::new(grid_scene(&mut rng));
    let axes = [
        Vec3::X,
        Vec3::NEG_X,
        Vec3::Y,
        Vec3::NEG_Y,
        Vec3::Z,
        Vec3::NEG_Z,
    ];
    let mut rays = Vec::new();
    for i in 0..4000 {
        // Origins on the grid planes (often on square edges too), or anywhere.
        let snap = |x: f32, rng: &mut TestRng| {
            if rng.f32() < 0.6 {
                (x * 4.0).round() / 4.0
            } else {
                x
            }
        };
        let raw = 1.5 * rng.vec();
        let origin = Vec3::new(
            snap(raw.x, &mut rng),
            snap(raw.y, &mut rng),
            snap(raw.z, &mut rng),
        );
        let dir = if i % 2 == 0 {
            axes[i % 6]
        } else {
            // In a coordinate plane: grazing the squares of that plane when the origin is on it.
            let mut d = rng.vec();
            d[i % 3] = 0.0;
            if d == Vec3::ZERO { Vec3::X } else { d }
        };
        let t_max = if i % 5 == 0 {
            2.0 * rng.f32()
        } else {
            f32::INFINITY
        };
        rays.push((Ray::new(origin, dir), t_max));
    }
    let hits = check_rays(&accel, rays, "axis-parallel and grazing rays");
    assert!(hits > 1000, "only {hits} of 4000 rays hit");
}

#[test]
fn t_max_right_at_the_hit_matches_brute_force() {
    let mut rng = TestRng(0x5eed_0005);
    let accel = Accel::new(grid_scene(&mut rng));
    let mut checked = 0;
    for i in 0..2000 {
        let ray = Ray::new(1.5 * rng.vec(), rng.vec());
        let Some(hit) = accel.intersect(&ray, f32::INFINITY) else {
            continue;
        };
        checked += 1;
        let replay = format!("ray {i}: {ray:?}, t {}", hit.t);
        // The range is open: at `t_max = t` the hit itself is out.
        assert!(accel.intersect(&ray, hit.t).is_none(), "{replay}");
        assert!(!accel.occluded(&ray, hit.t), "{replay}");
        let limits = [
            hit.t.next_down(),
            hit.t,
            hit.t.next_up(),
            hit.t * (1.0 + 1e-6),
        ];
        check_rays(&accel, limits.map(|t_max| (ray, t_max)), &replay);
        let slack = accel.intersect(&ray, 2.0 * hit.t).map(|h| h.t.to_bits());
        assert_eq!(slack, Some(hit.t.to_bits()), "{replay}");
    }
    assert!(checked > 800, "only {checked} of 2000 rays hit");
}
