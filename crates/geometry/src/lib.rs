//! Rays, bounding boxes, triangle meshes, spheres and the scene's bounding volume hierarchy.
//!
//! All geometry is in world space and in `f32`. [`Accel`] builds one 8-wide BVH (obvhs' PLOC
//! binary BVH, collapsed) over every triangle and sphere of a scene and answers closest-hit
//! ([`Accel::intersect`]) and any-hit ([`Accel::occluded`]) queries without allocating.
//!
//! Robustness, in brief:
//! - triangles are intersected with the watertight test of Woop, Benthin and Wald (2013), so a ray
//!   through a shared edge or vertex of a closed mesh always hits one of its triangles;
//! - spheres use the numerically careful quadratic of Ray Tracing Gems ch. 7, so small spheres far
//!   from the ray origin keep their precision;
//! - BVH boxes are tested with a conservative error margin and a lower bound of `t = 0` (obvhs' own
//!   CWBVH box test uses a fixed lower bound of `1e-4`, which misses nearby surfaces of small
//!   scenes);
//! - every hit point carries a bound on its coordinates' rounding error ([`Hit::p_error`]), and
//!   secondary rays leave surfaces through [`offset_ray_origin`], which moves the point along the
//!   normal by that bound (pbrt-v4's `OffsetRayOrigin`): offsets scale with the scene, however
//!   small or far from the origin; see [`Ray::spawn`] and [`Ray::spawn_to`], and [`SpawnPoint`]
//!   for a point that spawns several rays. Hits closer than the error bound of their own `t`
//!   are not hits.
//!
//! Shapes are never flipped towards the ray: a [`Hit`] reports the geometric normal as the shape
//! defines it, and one-sidedness is the BSDF's business (Mitsuba's convention).
//!
//! ```
//! use geometry::{Accel, Ray, Shape, Sphere};
//! use glam::Vec3;
//!
//! let accel = Accel::new(vec![Shape::Sphere(Sphere {
//!     center: Vec3::ZERO,
//!     radius: 1.0,
//!     flip_normals: false,
//!     to_local: glam::Mat3::IDENTITY,
//! })]);
//! let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z);
//! let hit = accel.intersect(&ray, f32::INFINITY).expect("the ray points at the sphere");
//! assert!((hit.t - 4.0).abs() < 1e-5);
//! assert!(hit.ng.abs_diff_eq(Vec3::Z, 1e-6));
//! ```

#![warn(missing_docs)]

mod aabb;
mod accel;
mod animated_transform;
mod hit;
mod icosphere;
mod mesh;
mod motion;
mod offset;
mod ray;
mod shape;
mod spawn_point;
mod sphere;
#[cfg(test)]
mod test_rng;
mod triangle;
mod triangle4;
mod x4;

pub use aabb::Aabb;
pub use accel::Accel;
pub use animated_transform::{AnimatedTransform, AnimationError};
pub use hit::Hit;
pub use mesh::{MeshError, TriangleMesh};
pub use motion::{Motion, Placement};
pub use offset::{gamma, offset_ray_origin, sphere_point_error, triangle_point_error};
pub use ray::{Ray, SHADOW_EPSILON};
pub use shape::Shape;
pub use spawn_point::SpawnPoint;
pub use sphere::Sphere;
pub use x4::{Rayx4, SpawnPointx4, Vec3x4};
