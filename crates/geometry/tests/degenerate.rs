//! Degenerate input: zero-area, duplicate and non-finite triangles, bad spheres, and vertex
//! normals that vanish or disagree with the winding. Nothing may panic or produce NaN, and
//! primitives without a surface are never hit.

mod common;

use common::Pcg32;
use geometry::{Accel, Hit, Ray, Shape, Sphere, TriangleMesh};
use glam::{Vec2, Vec3};

/// Triangles 0 and 5-6 are proper (5 duplicates 0, 6 is 0 reversed); the rest have no area or
/// non-finite vertices.
fn degenerate_mesh() -> TriangleMesh {
    let positions = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        // Collinear with 0 and 1, and a point far to the side on the same line.
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(3.0, 0.0, 0.0),
        Vec3::new(f32::NAN, 0.5, 0.0),
        Vec3::new(2.0, f32::INFINITY, 0.0),
        // Bit-identical copy of vertex 2.
        Vec3::new(0.0, 1.0, 0.0),
    ];
    let indices = vec![
        [0, 1, 2],
        [0, 1, 3], // collinear
        [4, 4, 4], // a point
        [1, 3, 1], // repeated index
        [2, 7, 0], // two coincident vertices
        [0, 1, 7], // duplicate of 0 through the copied vertex
        [0, 2, 1], // 0 reversed
        [0, 5, 1], // NaN vertex
        [0, 6, 1], // infinite vertex
    ];
    TriangleMesh::new(positions, None, None, indices).expect("indices are in range")
}

fn assert_finite(accel: &Accel, hit: &Hit, replay: &str) {
    let finite = hit.t.is_finite()
        && hit.p.is_finite()
        && hit.ng.is_finite()
        && hit.ns.is_finite()
        && hit.bary.is_finite()
        && accel.uv(hit).is_finite();
    assert!(finite, "{replay}: {hit:?}");
}

#[test]
fn only_proper_primitives_are_hit_and_every_field_is_finite() {
    let bad_spheres = [
        Sphere {
            center: Vec3::new(0.5, 0.5, 2.0),
            radius: 0.0,
            flip_normals: false,
            to_local: glam::Mat3::IDENTITY,
        },
        Sphere {
            center: Vec3::new(0.5, 0.5, 2.0),
            radius: -1.0,
            flip_normals: false,
            to_local: glam::Mat3::IDENTITY,
        },
        Sphere {
            center: Vec3::new(f32::NAN, 0.5, 2.0),
            radius: 1.0,
            flip_normals: false,
            to_local: glam::Mat3::IDENTITY,
        },
        Sphere {
            center: Vec3::new(0.5, 0.5, 2.0),
            radius: f32::INFINITY,
            flip_normals: false,
            to_local: glam::Mat3::IDENTITY,
        },
    ];
    let mut shapes = vec![Shape::Mesh(degenerate_mesh())];
    shapes.extend(bad_spheres.map(Shape::Sphere));
    let accel = Accel::new(shapes);
    assert!(accel.bounds().min.is_finite() && accel.bounds().max.is_finite());
    let seed = 21;
    let mut rng = Pcg32::new(seed);
    let mut hits = 0;
    for i in 0..5000 {
        // Aim at the proper triangles' square, at the collinear line, or at the point triangle.
        let target = match i % 3 {
            0 => Vec3::new(rng.f32(), rng.f32(), 0.0),
            1 => Vec3::new(rng.range(1.0, 3.0), 0.0, 0.0),
            _ => Vec3::new(3.0, 0.0, 0.0),
        };
        let origin = target + 2.0 * rng.unit();
        let ray = Ray::new(origin, target - origin);
        let replay = format!("seed {seed}, ray {i}: {ray:?}");
        if let Some(hit) = accel.intersect(&ray, f32::INFINITY) {
            assert_finite(&accel, &hit, &replay);
            assert_eq!(hit.shape, 0, "{replay}: hit a sphere without a surface");
            assert!(
                [0, 5, 6].contains(&hit.prim),
                "{replay}: hit degenerate triangle {}",
                hit.prim
            );
            hits += 1;
        }
        assert_eq!(
            accel.occluded(&ray, f32::INFINITY),
            accel.intersect(&ray, f32::INFINITY).is_some(),
            "{replay}"
        );
    }
    assert!(
        hits > 500,
        "only {hits} hits: the proper triangles are not being exercised"
    );
}

#[test]
fn rays_along_and_through_degenerate_triangles_miss() {
    let accel = Accel::new(vec![Shape::Mesh(degenerate_mesh())]);
    let rays = [
        // Down onto the collinear triangle's line, beyond the proper triangle.
        Ray::new(Vec3::new(2.5, 0.0, 1.0), Vec3::NEG_Z),
        // Along the line itself.
        Ray::new(Vec3::new(5.0, 0.0, 0.0), Vec3::NEG_X),
        // Through the point triangle.
        Ray::new(Vec3::new(3.0, 0.0, 1.0), Vec3::NEG_Z),
    ];
    for ray in rays {
        let hit = accel.intersect(&ray, f32::INFINITY);
        assert!(
            hit.is_none_or(|h| h.prim == 0 || h.prim == 5 || h.prim == 6),
            "{ray:?}: {hit:?}"
        );
        if let Some(hit) = hit {
            assert_finite(&accel, &hit, &format!("{ray:?}"));
        }
    }
    // Aimed at the proper triangle's interior, the duplicates are hit at the same t.
    let ray = Ray::new(Vec3::new(0.25, 0.25, 1.0), Vec3::NEG_Z);
    let hit = accel
        .intersect(&ray, f32::INFINITY)
        .expect("the proper triangle");
    assert_eq!(hit.t, 1.0);
    assert!([0, 5, 6].contains(&hit.prim));
    let expected_ng = if hit.prim == 6 { Vec3::NEG_Z } else { Vec3::Z };
    assert_eq!(hit.ng, expected_ng);
}

#[test]
fn shading_normals_fall_back_and_follow_the_geometric_side() {
    // Vertex normals: zero at two vertices and pointing against the winding at the third, on a
    // triangle wound towards +z; a second triangle with normals opposite to its winding.
    let positions = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(1.0, 0.0, -1.0),
        Vec3::new(0.0, 1.0, -1.0),
    ];
    let normals = vec![
        Vec3::ZERO,
        Vec3::ZERO,
        Vec3::ZERO,
        Vec3::NEG_Z,
        Vec3::NEG_Z,
        Vec3::NEG_Z,
    ];
    let uvs = vec![Vec2::ZERO, Vec2::X, Vec2::Y, Vec2::ZERO, Vec2::X, Vec2::Y];
    let mesh = TriangleMesh::new(
        positions,
        Some(normals),
        Some(uvs),
        vec![[0, 1, 2], [3, 4, 5]],
    )
    .expect("valid");
    let accel = Accel::new(vec![Shape::Mesh(mesh)]);
    let ray = Ray::new(Vec3::new(0.2, 0.3, 1.0), Vec3::NEG_Z);
    let top = accel.intersect(&ray, f32::INFINITY).expect("top triangle");
    assert_eq!(
        (top.prim, top.ng, top.ns),
        (0, Vec3::Z, Vec3::Z),
        "zero normals fall back to ng"
    );
    assert!(accel.uv(&top).abs_diff_eq(Vec2::new(0.2, 0.3), 1e-6));
    let below = Ray::spawn(top.p, top.ng, top.p_error, Vec3::NEG_Z);
    let bottom = accel
        .intersect(&below, f32::INFINITY)
        .expect("bottom triangle");
    assert_eq!((bottom.prim, bottom.ng), (1, Vec3::Z));
    assert_eq!(
        bottom.ns,
        Vec3::Z,
        "normals against the winding are turned to ng's side"
    );
}
