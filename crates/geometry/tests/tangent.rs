//! `Accel::dp_du`: the surface tangent an anisotropic BSDF's frame starts from, against
//! derivatives worked out by hand from each shape's parameterisation.

use geometry::{Accel, Ray, Shape, Sphere, TriangleMesh};
use glam::{Mat3, Vec2, Vec3};

/// The triangle (0,0,0), (2,0,0), (0,1,0) in the plane z = 0 with texture coordinates `uvs`,
/// hit from above at (0.3, 0.2).
fn triangle_tangent(uvs: Option<Vec<Vec2>>) -> Vec3 {
    let positions = vec![Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::Y];
    let mesh = TriangleMesh::new(positions, None, uvs, vec![[0, 1, 2]]).expect("valid");
    let accel = Accel::new(vec![Shape::Mesh(mesh)]);
    let ray = Ray::new(Vec3::new(0.3, 0.2, 1.0), Vec3::NEG_Z);
    let hit = accel.intersect(&ray, f32::INFINITY).expect("the triangle");
    accel.dp_du(&hit)
}

#[test]
fn mesh_tangent_is_the_derivative_by_u() {
    // u is 0 at p0 and p1 and 1 at p2, one unit along +y from p0: dp/du = +y whatever v does.
    let uvs = vec![Vec2::ZERO, Vec2::new(0.0, 1.0), Vec2::new(1.0, 0.0)];
    let dp_du = triangle_tangent(Some(uvs));
    assert!(dp_du.abs_diff_eq(Vec3::Y, 1e-6), "dp/du = {dp_du}");
    // u = x / 4 + y / 2 (uv1 = (0.5, 0), uv2 = (0.5, 1)), v = y: at fixed v, u grows by 1/4 per
    // unit of x, so dp/du = (4, 0, 0).
    let uvs = vec![Vec2::ZERO, Vec2::new(0.5, 0.0), Vec2::new(0.5, 1.0)];
    let dp_du = triangle_tangent(Some(uvs));
    assert!(
        dp_du.abs_diff_eq(Vec3::new(4.0, 0.0, 0.0), 1e-5),
        "dp/du = {dp_du}"
    );
}

#[test]
fn mesh_tangent_without_coordinates_is_the_first_edge_and_none_when_degenerate() {
    assert_eq!(triangle_tangent(None), Vec3::new(2.0, 0.0, 0.0));
    assert_eq!(triangle_tangent(Some(vec![Vec2::ONE; 3])), Vec3::ZERO);
}

#[test]
fn sphere_tangent_turns_about_its_own_pole() {
    // A sphere whose pole (local +z) is turned to world (0, 0.6, 0.8)-ish by a rotation about x:
    // rotating a point about the pole by dφ moves it by dφ · pole × (p − centre).
    let to_world = Mat3::from_rotation_x(-0.6435);
    let center = Vec3::new(1.0, 2.0, -3.0);
    let sphere = Sphere {
        center,
        radius: 0.5,
        flip_normals: false,
        to_local: to_world.transpose(),
    };
    let pole = to_world * Vec3::Z;
    let accel = Accel::new(vec![Shape::Sphere(sphere)]);
    for origin in [Vec3::new(1.3, 2.1, 0.0), Vec3::new(0.7, 2.3, 0.0)] {
        let ray = Ray::new(origin, Vec3::NEG_Z);
        let hit = accel.intersect(&ray, f32::INFINITY).expect("the sphere");
        let dp_du = accel.dp_du(&hit);
        let expected = pole.cross(hit.p - center) / sphere.radius;
        assert!(
            dp_du.abs_diff_eq(expected, 1e-4),
            "at {}: dp/du {dp_du}, expected the direction of {expected}",
            hit.p
        );
    }
}
