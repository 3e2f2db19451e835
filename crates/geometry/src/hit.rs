//! The record of a ray hitting a surface.

use glam::Vec3;

/// Where a ray hit a surface, as returned by [`crate::Accel::intersect`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the (unit) ray direction, in world units.
    pub t: f32,
    /// Hit point in world space, on the surface (re-projected, not `origin + t * dir`).
    pub p: Vec3,
    /// A bound on the rounding error of each coordinate of `p` (world units): the exact surface
    /// point lies within `p ± p_error`. Rays leaving `p` start that far off the surface
    /// ([`crate::offset_ray_origin`]).
    pub p_error: Vec3,
    /// Unit geometric normal as the shape defines it: for a mesh triangle `(p1 - p0) x (p2 - p0)`,
    /// for a sphere outward (inward with `flip_normals`). Never flipped towards the ray.
    pub ng: Vec3,
    /// Unit shading normal: the interpolated vertex normals when the mesh has them, else `ng`.
    /// Always in the same hemisphere as `ng`.
    pub ns: Vec3,
    /// Barycentric coordinates `(b0, b1, b2)`: the weights of the triangle's vertices `p0`, `p1`,
    /// `p2` at the hit (zero for a sphere). [`crate::Accel::uv`] turns them into surface
    /// coordinates.
    pub bary: Vec3,
    /// When the ray that found it was traced, a fraction of the shutter interval
    /// ([`crate::Ray::time`]): rays leaving the point ([`crate::SpawnPoint::of`]) keep it.
    pub time: f32,
    /// Index of the shape in the list given to [`crate::Accel::new`].
    pub shape: u32,
    /// Index of the triangle within its mesh (always 0 for a sphere).
    pub prim: u32,
}
