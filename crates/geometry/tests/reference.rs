//! The hierarchy against an independent double-precision reference (Möller–Trumbore and the
//! textbook quadratic in `f64`), and the fields of the hit records it returns.

mod common;

use common::{Pcg32, transformed, triangle_soup};
use geometry::{Accel, Hit, Ray, Shape, Sphere, TriangleMesh};
use glam::{Vec2, Vec3};

/// Closest hit in `f64`: `(t, shape, prim, margin)`, where `margin` is how far inside its
/// primitive the ray passes (smallest barycentric, or `1 - |closest approach| / r` for spheres),
/// so rays that graze an edge can be told apart.
fn reference(shapes: &[Shape], ray: &Ray) -> Option<(f64, u32, u32, f64)> {
    let o = ray.origin.as_dvec3();
    let d = ray.dir.as_dvec3();
    let mut best: Option<(f64, u32, u32, f64)> = None;
    let mut consider = |t: f64, shape: usize, prim: usize, margin: f64| {
        if t > 0.0 && best.is_none_or(|b| t < b.0) {
            best = Some((t, shape as u32, prim as u32, margin));
        }
    };
    for (s, shape) in shapes.iter().enumerate() {
        match shape {
            Shape::Mesh(mesh) => {
                for i in 0..mesh.triangle_count() {
                    let [p0, p1, p2] = mesh.triangle(i).map(|p| p.as_dvec3());
                    let (e1, e2) = (p1 - p0, p2 - p0);
                    let pv = d.cross(e2);
                    let det = e1.dot(pv);
                    if det == 0.0 {
                        continue;
                    }
                    let tv = o - p0;
                    let u = tv.dot(pv) / det;
                    let qv = tv.cross(e1);
                    let v = d.dot(qv) / det;
                    if u >= 0.0 && v >= 0.0 && u + v <= 1.0 {
                        consider(e2.dot(qv) / det, s, i, u.min(v).min(1.0 - u - v));
                    }
                }
            }
            Shape::Sphere(sphere) => {
                let oc = o - sphere.center.as_dvec3();
                let r = sphere.radius as f64;
                let b = oc.dot(d);
                let disc = b * b - (oc.length_squared() - r * r);
                if disc >= 0.0 {
                    let margin = 1.0 - (oc - b * d).length() / r;
                    let (t0, t1) = (-b - disc.sqrt(), -b + disc.sqrt());
                    consider(if t0 > 0.0 { t0 } else { t1 }, s, 0, margin);
                }
            }
        }
    }
    best
}

fn random_scene(rng: &mut Pcg32) -> Vec<Shape> {
    let mut shapes = vec![Shape::Mesh(triangle_soup(rng, 2000, 0.25))];
    shapes.extend((0..40).map(|i| {
        Shape::Sphere(Sphere {
            center: rng.in_cube(),
            radius: rng.range(0.02, 0.15),
            flip_normals: i % 2 == 1,
            to_local: glam::Mat3::IDENTITY,
        })
    }));
    shapes.push(Shape::Mesh(transformed(
        &TriangleMesh::icosphere(2),
        0.3,
        Vec3::new(0.2, -0.4, 0.1),
    )));
    shapes
}

/// Checks the fields of `hit` that do not depend on which primitive won.
fn check_hit_fields(accel: &Accel, ray: &Ray, hit: &Hit, replay: &str) {
    let shapes = accel.shapes();
    let uv = accel.uv(hit);
    assert!(
        hit.p.abs_diff_eq(ray.at(hit.t), 1e-4),
        "{replay}: p {} vs ray at t {}",
        hit.p,
        ray.at(hit.t)
    );
    assert!(
        (hit.ng.length() - 1.0).abs() < 1e-5,
        "{replay}: |ng| {}",
        hit.ng.length()
    );
    assert!(
        (hit.ns.length() - 1.0).abs() < 1e-5,
        "{replay}: |ns| {}",
        hit.ns.length()
    );
    assert!(
        hit.ns.dot(hit.ng) >= 0.0,
        "{replay}: ns {} against ng {}",
        hit.ns,
        hit.ng
    );
    match &shapes[hit.shape as usize] {
        Shape::Mesh(mesh) => {
            let [p0, p1, p2] = mesh.triangle(hit.prim as usize);
            let winding = (p1 - p0).cross(p2 - p0).normalize();
            assert!(
                hit.ng.abs_diff_eq(winding, 1e-4),
                "{replay}: ng {} vs winding {winding}",
                hit.ng
            );
            match &mesh.uvs {
                None => {
                    let b = hit.bary;
                    assert!(b.min_element() >= -1e-6, "{replay}: barycentrics {b}");
                    assert!(
                        (b.element_sum() - 1.0).abs() < 1e-5,
                        "{replay}: barycentrics {b}"
                    );
                    assert_eq!(
                        uv,
                        Vec2::new(b.y, b.z),
                        "{replay}: uv without texture coordinates"
                    );
                    let p = b.x * p0 + b.y * p1 + b.z * p2;
                    assert!(
                        p.abs_diff_eq(hit.p, 1e-5),
                        "{replay}: barycentrics {b} give {p}, not {}",
                        hit.p
                    );
                }
                // The icosphere's texture coordinates are its vertices' (x, y), and its vertex
                // normals point away from its centre.
                Some(_) => {
                    assert!(
                        uv.abs_diff_eq(Vec2::new(hit.p.x - 0.2, hit.p.y + 0.4) / 0.3, 1e-4),
                        "{replay}"
                    );
                    let radial = (hit.p - Vec3::new(0.2, -0.4, 0.1)).normalize();
                    assert!(
                        hit.ns.dot(radial) > 0.999,
                        "{replay}: ns {} vs radial {radial}",
                        hit.ns
                    );
                }
            }
        }
        Shape::Sphere(sphere) => {
            let outward = (hit.p - sphere.center) / sphere.radius;
            assert!(
                (outward.length() - 1.0).abs() < 1e-5,
                "{replay}: p off the sphere"
            );
            let expected = if sphere.flip_normals {
                -outward
            } else {
                outward
            };
            assert!(
                hit.ng.abs_diff_eq(expected, 1e-4),
                "{replay}: ng {} vs {expected}",
                hit.ng
            );
            assert_eq!(hit.ns, hit.ng);
            assert!(
                uv.abs_diff_eq(Sphere::uv(outward), 1e-4),
                "{replay}: uv {uv} vs {}",
                Sphere::uv(outward)
            );
        }
    }
}

#[test]
fn closest_hits_agree_with_double_precision_reference() {
    let seed = 20240601;
    let mut rng = Pcg32::new(seed);
    let shapes = random_scene(&mut rng);
    let accel = Accel::new(shapes.clone());
    let (mut hits, mut grazing) = (0, 0);
    let rays = 4000;
    for i in 0..rays {
        let origin = if i % 2 == 0 {
            3.0 * rng.unit()
        } else {
            rng.in_cube()
        };
        let ray = Ray::new(origin, rng.in_cube() - 0.5 * origin);
        let replay = format!("seed {seed}, ray {i}: {ray:?}");
        let expected = reference(&shapes, &ray);
        let got = accel.intersect(&ray, f32::INFINITY);
        // Rays within 1e-5 (relative) of an edge or a sphere's silhouette may go either way.
        if expected.is_some_and(|e| e.3 < 1e-5) {
            grazing += 1;
            continue;
        }
        match (expected, got) {
            (None, None) => {}
            (Some((t, shape, prim, _)), Some(hit)) => {
                let t_err = (hit.t as f64 - t).abs();
                assert!(
                    t_err <= 1e-5 * t.max(1.0),
                    "{replay}: t {} vs reference {t}",
                    hit.t
                );
                // Different primitives may only be reported when they are hit at the same t.
                if (hit.shape, hit.prim) != (shape, prim) {
                    assert!(
                        t_err <= 1e-6 * t.max(1.0),
                        "{replay}: hit {hit:?}, reference {shape}/{prim} at {t}"
                    );
                }
                check_hit_fields(&accel, &ray, &hit, &replay);
                hits += 1;
            }
            (e, g) => panic!("{replay}: reference {e:?}, hierarchy {g:?}"),
        }
    }
    assert!(
        hits > rays / 2,
        "only {hits} of {rays} rays hit: the scene is not being exercised"
    );
    assert!(
        grazing < rays / 100,
        "{grazing} grazing rays: the margin test is too loose"
    );
}

#[test]
fn occlusion_agrees_with_closest_hit() {
    let seed = 77;
    let mut rng = Pcg32::new(seed);
    let accel = Accel::new(random_scene(&mut rng));
    let (mut blocked, rays) = (0, 3000);
    for i in 0..rays {
        let ray = Ray::new(rng.in_cube() * 1.5, rng.unit());
        let t_max = if i % 4 == 0 {
            f32::INFINITY
        } else {
            rng.range(0.0, 2.0)
        };
        let hit = accel.intersect(&ray, t_max);
        assert!(
            hit.is_none_or(|h| h.t > 0.0 && h.t < t_max),
            "seed {seed}, ray {i}: {hit:?}"
        );
        let occluded = accel.occluded(&ray, t_max);
        assert_eq!(
            occluded,
            hit.is_some(),
            "seed {seed}, ray {i}: {ray:?}, t_max {t_max}"
        );
        blocked += occluded as usize;
    }
    assert!(
        blocked > rays / 5 && blocked < rays * 4 / 5,
        "{blocked} of {rays} blocked"
    );
}

#[test]
fn empty_scenes_miss_everything() {
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    let empty_mesh = Shape::Mesh(TriangleMesh::default());
    for shapes in [vec![], vec![empty_mesh]] {
        let accel = Accel::new(shapes.clone());
        assert_eq!(accel.shapes(), &shapes[..]);
        assert!(accel.intersect(&ray, f32::INFINITY).is_none());
        assert!(!accel.occluded(&ray, f32::INFINITY));
        assert!(accel.bounds().is_empty());
    }
}

#[test]
fn bounds_cover_every_shape() {
    let mut rng = Pcg32::new(5);
    let shapes = random_scene(&mut rng);
    let accel = Accel::new(shapes.clone());
    for shape in &shapes {
        let b = shape.bounds();
        assert!(accel.bounds().contains(b.min) && accel.bounds().contains(b.max));
    }
}

#[test]
fn accel_can_be_shared_between_threads() {
    fn shareable<T: Send + Sync>() {}
    shareable::<Accel>();
    let accel = Accel::new(vec![Shape::Sphere(Sphere {
        center: Vec3::ZERO,
        radius: 1.0,
        flip_normals: false,
        to_local: glam::Mat3::IDENTITY,
    })]);
    let hits: Vec<bool> = std::thread::scope(|scope| {
        let workers: Vec<_> = [Vec3::X, Vec3::Y]
            .map(|d| {
                let accel = &accel;
                scope.spawn(move || {
                    accel
                        .intersect(&Ray::new(-3.0 * d, d), f32::INFINITY)
                        .is_some()
                })
            })
            .into_iter()
            .collect();
        workers
            .into_iter()
            .map(|w| w.join().expect("worker"))
            .collect()
    });
    assert_eq!(hits, [true, true]);
}
