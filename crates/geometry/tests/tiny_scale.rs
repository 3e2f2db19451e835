//! A scene scaled by 1e-3, where surfaces lie 5e-5 from the ray origin. obvhs' own CWBVH box
//! test starts every box at `t = 1e-4` and would miss all of these. And the same scene scaled by
//! 1e-4 with a gap of 1e-7, a thousandth of its size, which a fixed offset near the origin (the
//! 1.5e-5 of Wächter and Binder's `float_scale`) would jump.

mod common;

use common::{Pcg32, subdivided_cube, transformed};
use geometry::{Accel, Ray, Shape, TriangleMesh};
use glam::Vec3;

const SCALE: f32 = 1e-3;
const GAP: f32 = 5e-5;

/// A cube of half-size 1e-3 at the origin and, `GAP` above its top face, a facing 2e-3 square.
fn scene() -> Accel {
    scene_of(SCALE, GAP)
}

/// A cube of half-size `scale` at the origin and, `gap` above its top face, a facing square of
/// side `2 scale`.
fn scene_of(scale: f32, gap: f32) -> Accel {
    let cube = transformed(&subdivided_cube(3), scale, Vec3::ZERO);
    let z = scale + gap;
    let lid = TriangleMesh::new(
        [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .map(|(x, y)| Vec3::new(x * scale, y * scale, z))
            .to_vec(),
        None,
        None,
        vec![[0, 2, 1], [0, 3, 2]],
    )
    .expect("valid");
    Accel::new(vec![Shape::Mesh(cube), Shape::Mesh(lid)])
}

#[test]
fn axis_aligned_ray_hits_a_face_5e5_away() {
    let accel = scene();
    let ray = Ray::new(
        Vec3::new(0.3 * SCALE, -0.2 * SCALE, SCALE + GAP),
        Vec3::NEG_Z,
    );
    let hit = accel
        .intersect(&ray, f32::INFINITY)
        .expect("the cube's top face is 5e-5 below");
    assert_eq!(hit.shape, 0);
    assert!((hit.t - GAP).abs() < 1e-9, "t = {}", hit.t);
    assert_eq!(hit.ng, Vec3::Z);
    assert!(accel.occluded(&ray, 2.0 * GAP));
    assert!(!accel.occluded(&ray, 0.5 * GAP));
}

#[test]
fn oblique_rays_hit_faces_5e5_away() {
    let seed = 9;
    let mut rng = Pcg32::new(seed);
    let accel = scene();
    for i in 0..2000 {
        // A point on the top face, a little inside its edges, and a direction into the face.
        let on_face = Vec3::new(
            rng.range(-0.9, 0.9) * SCALE,
            rng.range(-0.9, 0.9) * SCALE,
            SCALE,
        );
        let dir = -rng.unit_around(Vec3::Z);
        if dir.z > -0.2 {
            continue;
        }
        let origin = on_face - dir * (GAP / -dir.z);
        let ray = Ray::new(origin, dir);
        let replay = format!("seed {seed}, ray {i}: {ray:?}");
        let hit = accel
            .intersect(&ray, f32::INFINITY)
            .unwrap_or_else(|| panic!("{replay}: missed"));
        let expected = GAP / -dir.z;
        assert!(
            (hit.t - expected).abs() < 1e-4 * expected,
            "{replay}: t {} vs {expected}",
            hit.t
        );
        assert!(
            hit.p.distance(on_face) < 1e-8,
            "{replay}: hit {} vs {on_face}",
            hit.p
        );
    }
}

#[test]
fn spawned_rays_cross_a_5e5_gap() {
    spawned_rays_cross(SCALE, GAP, 10);
}

#[test]
fn spawned_rays_cross_a_thousandth_of_a_scene_scaled_by_1e_minus_4() {
    spawned_rays_cross(1e-4, 1e-7, 11);
}

/// Rays through the lid of [`scene_of`] onto the cube, spawned from the lid, and back up,
/// spawned from the cube, meet the next surface across the gap.
fn spawned_rays_cross(scale: f32, gap: f32, seed: u64) {
    let mut rng = Pcg32::new(seed);
    let accel = scene_of(scale, gap);
    for i in 0..2000 {
        let from = Vec3::new(
            rng.range(-0.8, 0.8) * scale,
            rng.range(-0.8, 0.8) * scale,
            3.0 * scale,
        );
        let down = Ray::new(from, Vec3::new(0.0, 0.0, -1.0) + 0.05 * rng.in_cube());
        let replay = format!("scale {scale}, gap {gap}, seed {seed}, ray {i}: {down:?}");
        // Through the lid (from above, its back) onto the cube's top face.
        let lid = accel
            .intersect(&down, f32::INFINITY)
            .unwrap_or_else(|| panic!("{replay}: missed the lid"));
        assert_eq!(lid.shape, 1, "{replay}");
        let below = Ray::spawn(lid.p, lid.ng, lid.p_error, down.dir);
        let top = accel
            .intersect(&below, f32::INFINITY)
            .unwrap_or_else(|| panic!("{replay}: missed the cube"));
        assert_eq!((top.shape, top.ng), (0, Vec3::Z), "{replay}");
        // Bounce straight back up: the lid is the next surface, less than the gap away.
        let up = Ray::spawn(top.p, top.ng, top.p_error, Vec3::Z);
        let back = accel
            .intersect(&up, f32::INFINITY)
            .unwrap_or_else(|| panic!("{replay}: missed the lid again"));
        assert_eq!(back.shape, 1, "{replay}");
        assert!(
            back.t > 0.0 && back.t < gap,
            "{replay}: lid at t = {}",
            back.t
        );
    }
}
