//! Rays spawned from surfaces must not hit the surface they leave, and shadow rays between two
//! surface points must see neither end, at unit scale, tiny and huge scales, and far from the
//! origin.

mod common;

use common::{Pcg32, transformed};
use geometry::{Accel, Hit, Ray, Shape, Sphere, TriangleMesh};
use glam::Vec3;

/// A placement of the test objects: uniform scale, then translation.
#[derive(Clone, Copy, Debug)]
struct Placement {
    name: &'static str,
    scale: f32,
    offset: Vec3,
}

const FAR: Vec3 = Vec3::new(1.0e5, 0.5e5, -1.0e5);

const PLACEMENTS: [Placement; 5] = [
    Placement {
        name: "unit",
        scale: 1.0,
        offset: Vec3::ZERO,
    },
    Placement {
        name: "tiny",
        scale: 1e-3,
        offset: Vec3::ZERO,
    },
    Placement {
        name: "huge",
        scale: 1e3,
        offset: Vec3::ZERO,
    },
    Placement {
        name: "far",
        scale: 1.0,
        offset: FAR,
    },
    Placement {
        name: "far and huge",
        scale: 1e3,
        offset: FAR,
    },
];

impl Placement {
    fn point(&self, p: Vec3) -> Vec3 {
        p * self.scale + self.offset
    }

    /// Whether objects of unit size stay much larger than the ray offsets and the rounding of
    /// the test's own points: at 1e5 an offset is about 0.05 units (`offset_bound`) and a point
    /// is rounded by up to 0.004, which the tests' tolerances for grazing rays and close pairs
    /// of points do not allow for.
    fn resolves_interiors(&self) -> bool {
        self.scale > 1e-2 * self.offset.abs().max_element()
    }
}

/// The object under test, alone in its scene: an analytic sphere or an icosphere mesh.
fn objects(placement: &Placement) -> [(&'static str, Shape); 2] {
    [
        (
            "sphere",
            Shape::Sphere(Sphere {
                center: placement.offset,
                radius: placement.scale,
                flip_normals: false,
                to_local: glam::Mat3::IDENTITY,
            }),
        ),
        (
            "mesh",
            Shape::Mesh(transformed(
                &TriangleMesh::icosphere(3),
                placement.scale,
                placement.offset,
            )),
        ),
    ]
}

/// Primary hits on the object from random points outside it.
fn primary_hits<'a>(
    accel: &'a Accel,
    placement: &'a Placement,
    rng: &'a mut Pcg32,
) -> impl Iterator<Item = (Ray, Hit)> + 'a {
    std::iter::from_fn(move || {
        let origin = placement.point(3.0 * rng.unit());
        let ray = Ray::new(origin, placement.point(0.5 * rng.unit()) - origin);
        Some(accel.intersect(&ray, f32::INFINITY).map(|hit| (ray, hit)))
    })
    .flatten()
}

#[test]
fn reflected_rays_never_hit_their_own_convex_surface() {
    for placement in &PLACEMENTS {
        for (object, shape) in objects(placement) {
            let seed = 100;
            let mut rng = Pcg32::new(seed);
            let accel = Accel::new(vec![shape]);
            let mut dirs = Pcg32::new(seed + 1);
            for (i, (ray, hit)) in primary_hits(&accel, placement, &mut rng)
                .take(3000)
                .enumerate()
            {
                // Leave on the side the ray came from; nothing else is in the scene.
                let side = if hit.ng.dot(ray.dir) < 0.0 {
                    hit.ng
                } else {
                    -hit.ng
                };
                let dir = dirs.unit_around(side);
                let spawned = Ray::spawn(hit.p, hit.ng, hit.p_error, dir);
                let again = accel.intersect(&spawned, f32::INFINITY);
                let replay = format!(
                    "{} {object}, seed {seed}, ray {i}: {ray:?} hit {hit:?}, spawned {spawned:?}",
                    placement.name
                );
                assert!(again.is_none(), "{replay}: re-hit {again:?}");
                assert!(
                    !accel.occluded(&spawned, f32::INFINITY),
                    "{replay}: occluded"
                );
            }
        }
    }
}

#[test]
fn transmitted_rays_cross_to_the_far_side() {
    for placement in PLACEMENTS.iter().filter(|p| p.resolves_interiors()) {
        for (object, shape) in objects(placement) {
            let seed = 200;
            let mut rng = Pcg32::new(seed);
            let accel = Accel::new(vec![shape]);
            let mut dirs = Pcg32::new(seed + 1);
            for (i, (ray, hit)) in primary_hits(&accel, placement, &mut rng)
                .take(3000)
                .enumerate()
            {
                let inward = if hit.ng.dot(ray.dir) < 0.0 {
                    -hit.ng
                } else {
                    hit.ng
                };
                let dir = dirs.unit_around(inward);
                let spawned = Ray::spawn(hit.p, hit.ng, hit.p_error, dir);
                let replay = format!(
                    "{} {object}, seed {seed}, ray {i}: {ray:?} hit {hit:?}, spawned {spawned:?}",
                    placement.name
                );
                let exit = accel.intersect(&spawned, f32::INFINITY).unwrap_or_else(|| {
                    panic!("{replay}: left a closed surface without crossing it")
                });
                if object == "mesh" {
                    assert_ne!(
                        exit.prim, hit.prim,
                        "{replay}: re-hit its own triangle at t = {}",
                        exit.t
                    );
                } else {
                    // The chord from a sphere point along a direction at angle theta to the
                    // normal is 2 r cos(theta).
                    let chord = 2.0 * placement.scale * dir.dot(inward);
                    assert!(
                        exit.t > 0.5 * chord,
                        "{replay}: exit at t = {} for chord {chord}",
                        exit.t
                    );
                }
            }
        }
    }
}

/// Two 2x2 quads facing each other across a gap of 1 (before placement): `z = 0` facing +z and
/// `z = 1` facing -z, plus a small blocker quad in between at `z = 0.5`, `|x|, |y| <= 0.25`.
fn facing_quads(placement: &Placement) -> [TriangleMesh; 3] {
    let quad = |z: f32, half: f32, up: bool| {
        let corners = [(-half, -half), (half, -half), (half, half), (-half, half)];
        let positions = corners
            .map(|(x, y)| placement.point(Vec3::new(x, y, z)))
            .to_vec();
        let indices = if up {
            vec![[0, 1, 2], [0, 2, 3]]
        } else {
            vec![[0, 2, 1], [0, 3, 2]]
        };
        TriangleMesh::new(positions, None, None, indices).expect("valid quad")
    };
    [
        quad(0.0, 1.0, true),
        quad(1.0, 1.0, false),
        quad(0.5, 0.25, true),
    ]
}

/// An upper bound on how far `offset_ray_origin` moves `p` whose coordinates' error bound is
/// `p_error`: `|n| · p_error ≤ |p_error|` along the unit normal, and then a unit in the last
/// place of each coordinate.
fn offset_bound(p: Vec3, p_error: Vec3) -> f32 {
    p_error.length() + 2.0 * f32::EPSILON * p.abs().max_element()
}

/// A uniformly chosen point on `mesh` (by triangle, then barycentrics), its normal and its
/// coordinates' error bound.
fn point_on(mesh: &TriangleMesh, rng: &mut Pcg32) -> (Vec3, Vec3, Vec3) {
    let [p0, p1, p2] = mesh.triangle(rng.below(mesh.triangle_count()));
    let b = rng.barycentric();
    (
        b.x * p0 + b.y * p1 + b.z * p2,
        (p1 - p0).cross(p2 - p0).normalize(),
        geometry::triangle_point_error([p0, p1, p2]),
    )
}

#[test]
fn shadow_rays_between_facing_quads_see_only_the_blocker() {
    for placement in PLACEMENTS.iter().filter(|p| p.resolves_interiors()) {
        let seed = 300;
        let mut rng = Pcg32::new(seed);
        let [bottom, top, blocker] = facing_quads(placement);
        let open = Accel::new(vec![Shape::Mesh(bottom.clone()), Shape::Mesh(top.clone())]);
        let blocked = Accel::new(vec![
            Shape::Mesh(bottom.clone()),
            Shape::Mesh(top.clone()),
            Shape::Mesh(blocker),
        ]);
        let mut crossings = 0;
        for i in 0..3000 {
            let (p, n, e) = point_on(&bottom, &mut rng);
            let (q, m, f) = point_on(&top, &mut rng);
            let (ray, t_max) = Ray::spawn_to(p, n, e, q, m, f);
            let replay = format!(
                "{}, seed {seed}, pair {i}: {p} -> {q}, ray {ray:?}, t_max {t_max}",
                placement.name
            );
            let slack = offset_bound(p, e) + offset_bound(q, f);
            let shortened = p.distance(q) * (1.0 - geometry::SHADOW_EPSILON);
            assert!(
                t_max <= p.distance(q) && t_max > shortened - 2.0 * slack,
                "{replay}: wrong length"
            );
            assert!(
                !open.occluded(&ray, t_max),
                "{replay}: blocked by {:?}",
                open.intersect(&ray, t_max)
            );
            // Where the segment crosses z = 0.5, in double precision and unit coordinates.
            let to_unit = |v: Vec3| ((v - placement.offset) / placement.scale).as_dvec3();
            let mid = (to_unit(p) + to_unit(q)) * 0.5;
            let inside = mid.x.abs().max(mid.y.abs());
            // The offsets tilt the ray a little: leave out segments that graze the blocker's edge.
            if (inside - 0.25).abs() > 1e-3 + 2.0 * slack as f64 / placement.scale as f64 {
                assert_eq!(
                    blocked.occluded(&ray, t_max),
                    inside < 0.25,
                    "{replay}: blocker crossing at {mid}"
                );
                crossings += (inside < 0.25) as usize;
            }
        }
        assert!(
            crossings > 50,
            "{}: only {crossings} rays crossed the blocker",
            placement.name
        );
    }
}

#[test]
fn shadow_rays_inside_a_sphere_see_nothing() {
    for placement in PLACEMENTS.iter().filter(|p| p.resolves_interiors()) {
        let seed = 400;
        let mut rng = Pcg32::new(seed);
        let sphere = Sphere {
            center: placement.offset,
            radius: placement.scale,
            flip_normals: true,
            to_local: glam::Mat3::IDENTITY,
        };
        let accel = Accel::new(vec![Shape::Sphere(sphere)]);
        for i in 0..3000 {
            let (a, b) = (rng.unit(), rng.unit());
            let (p, q) = (placement.point(a), placement.point(b));
            // Computed as a centre plus a radius times a unit vector, as a sphere's points are.
            let e = geometry::sphere_point_error(sphere.center, sphere.radius);
            let (ray, t_max) = Ray::spawn_to(p, sphere.normal(p), e, q, sphere.normal(q), e);
            let replay = format!(
                "{}, seed {seed}, pair {i}: {p} -> {q}, ray {ray:?}, t_max {t_max}",
                placement.name
            );
            assert!(!accel.occluded(&ray, t_max), "{replay}: blocked");
            // The same segment run past its end does meet the sphere, at the target.
            let hit = accel
                .intersect(&ray, f32::INFINITY)
                .unwrap_or_else(|| panic!("{replay}: no far side"));
            // The offsets tilt the ray; along a grazing chord that moves the far-side hit by the
            // offsets divided by the sine of the grazing angle.
            let sine = ray.dir.dot(sphere.normal(q)).abs();
            let tolerance =
                4.0 * (offset_bound(p, e) + offset_bound(q, e)) / sine + 1e-5 * placement.scale;
            assert!(
                hit.p.distance(q) < tolerance,
                "{replay}: far side at {}",
                hit.p
            );
        }
    }
}
