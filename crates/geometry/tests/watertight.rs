//! Rays aimed exactly at the shared edges and vertices of closed meshes, from inside, must hit.
//! A non-watertight triangle test lets some of them slip through the crack between two triangles
//! (obvhs' Möller–Trumbore loses about one in a million from the back side).

mod common;

use common::{Pcg32, subdivided_cube, transformed};
use geometry::{Accel, Ray, Shape, TriangleMesh};
use glam::Vec3;

/// Shoots `rays` rays from random points inside the closed convex `mesh` (within `inner_radius`
/// of `center`) at its vertices, at points on its edges, and at the middle of its edges; all must
/// hit, at the point aimed at.
fn shoot_at_edges(mesh: TriangleMesh, center: Vec3, inner_radius: f32, rays: usize, seed: u64) {
    let mut rng = Pcg32::new(seed);
    let accel = Accel::new(vec![Shape::Mesh(mesh.clone())]);
    let scale = accel.bounds().diagonal().max_element();
    for i in 0..rays {
        let [a, b, c] =
            mesh.indices[rng.below(mesh.indices.len())].map(|v| mesh.positions[v as usize]);
        let target = match i % 3 {
            0 => [a, b, c][rng.below(3)],
            1 => a.lerp(b, 0.5),
            _ => b.lerp(c, rng.f32()),
        };
        let origin = center + inner_radius * rng.unit() * rng.f32();
        let ray = Ray::new(origin, target - origin);
        let hit = accel.intersect(&ray, f32::INFINITY);
        let replay = format!("seed {seed}, ray {i}: {ray:?} aimed at {target}");
        let hit = hit.unwrap_or_else(|| panic!("{replay}: escaped the closed mesh"));
        // Relative to the mesh's size, plus a few ulps of its position.
        let tolerance = 1e-4 * scale + 8.0 * f32::EPSILON * target.abs().max_element();
        assert!(
            hit.p.distance(target) < tolerance,
            "{replay}: hit {} instead",
            hit.p
        );
        assert!(
            accel.occluded(&ray, f32::INFINITY),
            "{replay}: occlusion escaped"
        );
    }
}

#[test]
fn subdivided_cube_has_no_cracks() {
    shoot_at_edges(subdivided_cube(6), Vec3::ZERO, 0.9, 30_000, 1);
}

#[test]
fn moved_and_scaled_cube_has_no_cracks() {
    let offset = Vec3::new(3.3, -170.0, 12.5);
    shoot_at_edges(
        transformed(&subdivided_cube(4), 0.01, offset),
        offset,
        0.009,
        20_000,
        2,
    );
}

#[test]
fn icosphere_has_no_cracks() {
    // The icosphere's faces lie at least cos(half the icosahedron's edge angle) from its centre.
    shoot_at_edges(TriangleMesh::icosphere(3), Vec3::ZERO, 0.7, 30_000, 3);
}

#[test]
fn large_moved_icosphere_has_no_cracks() {
    let offset = Vec3::new(-2.0e3, 5.0e2, 1.0e3);
    shoot_at_edges(
        transformed(&TriangleMesh::icosphere(2), 100.0, offset),
        offset,
        70.0,
        20_000,
        4,
    );
}
