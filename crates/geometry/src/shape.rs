//! The closed set of shapes a scene is made of.

use crate::{Aabb, Sphere, TriangleMesh};

/// A shape of the scene. Rectangles, cubes and disks arrive as meshes (the scene loader converts
/// them); spheres stay analytic.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A triangle mesh in world space.
    Mesh(TriangleMesh),
    /// An analytic sphere.
    Sphere(Sphere),
}

impl Shape {
    /// World-space bounds of the shape ([`Aabb::EMPTY`] for a mesh without triangles).
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Mesh(mesh) => Aabb::from_points(
                mesh.indices
                    .iter()
                    .flatten()
                    .map(|&i| mesh.positions[i as usize]),
            ),
            Shape::Sphere(sphere) => sphere.bounds(),
        }
    }

    /// Total surface area in world units squared.
    pub fn area(&self) -> f32 {
        match self {
            Shape::Mesh(mesh) => (0..mesh.triangle_count())
                .map(|i| mesh.triangle_area(i))
                .sum(),
            Shape::Sphere(sphere) => sphere.area(),
        }
    }
}
