//! The scene's bounding volume hierarchy over all shapes.

mod build;
mod collapse;
mod moving;
mod node;
mod prim;
mod query;
mod stack;
mod walk;

use glam::{Vec2, Vec3, Vec3A};

use crate::{Aabb, Hit, Motion, Ray, Shape, Sphere};
use moving::MovingShape;
use node::Node;
use prim::{Found, Geometry, PrimInfo, direction_of};
use query::RayQuery;
use stack::{ArrayStack, FIXED_STACK, SMALL_STACK, StackKind};

/// An 8-wide BVH over every triangle and sphere of a scene, owning the shapes: obvhs' binary BVH
/// (built by PLOC) collapsed to nodes that test eight uncompressed child boxes at once. Queries
/// do not allocate (except on pathologically deep trees, see below) and may run from many
/// threads at once.
///
/// Triangles with no area or a non-finite vertex, and spheres with a non-positive or non-finite
/// radius or centre, are left out: rays never hit them.
pub struct Accel {
    shapes: Vec<Shape>,
    /// The hierarchy, root first (empty when there are no primitives).
    nodes: Vec<Node>,
    /// Triangle packets and spheres, which leaves refer to.
    geometry: Geometry,
    /// Ids and normals of the triangles: lane `l` of packet `p` at `4 p + l`.
    triangle_infos: Vec<PrimInfo>,
    /// Ids of the spheres, by sphere index.
    sphere_infos: Vec<PrimInfo>,
    bounds: Aabb,
    /// The traversal stack the tree needs: small for small scenes, on the heap (allocated per
    /// query, sized to `stack_need`) for trees too deep for the fixed stack.
    stack: StackKind,
    stack_need: usize,
    /// Shapes that move during the shutter, numbered after the static ones.
    moving: Vec<MovingShape>,
}

impl Accel {
    /// Builds the hierarchy over `shapes` (any number, including none).
    ///
    /// # Panics
    /// If a mesh fails [`crate::TriangleMesh::validate`]; the scene loader checks meshes when it
    /// creates them.
    pub fn new(shapes: Vec<Shape>) -> Accel {
        let built = build::build(&shapes);
        Accel {
            shapes,
            nodes: built.nodes,
            geometry: built.geometry,
            triangle_infos: built.triangle_infos,
            sphere_infos: built.sphere_infos,
            bounds: built.bounds,
            stack: StackKind::for_need(built.stack_need),
            stack_need: built.stack_need,
            moving: Vec::new(),
        }
    }

    /// The hierarchy over the static `shapes` with the shapes in `moving` (object space, each
    /// with its motion during the shutter) after them: shape `shapes.len() + i` of a [`Hit`] is
    /// `moving[i]`.
    pub fn with_moving(shapes: Vec<Shape>, moving: Vec<(Shape, Motion)>) -> Accel {
        let mut accel = Accel::new(shapes);
        accel.moving = moving
            .into_iter()
            .map(|(shape, motion)| MovingShape::new(shape, motion))
            .collect();
        accel
    }

    /// How many shapes there are, static and moving.
    pub fn shape_count(&self) -> usize {
        self.shapes.len() + self.moving.len()
    }

    /// Whether some shape moves during the shutter, so rays need a time.
    pub fn has_motion(&self) -> bool {
        self.moving.iter().any(|m| m.motion.moves())
    }

    /// Shape `id` (numbered as in [`Hit::shape`]) in its own space, with its motion if it moves.
    pub fn shape(&self, id: u32) -> (&Shape, Option<&Motion>) {
        match self.shapes.get(id as usize) {
            Some(shape) => (shape, None),
            None => {
                let moving = &self.moving[id as usize - self.shapes.len()];
                (moving.shape(), Some(&moving.motion))
            }
        }
    }

    /// The static shapes, in the order given to [`Accel::new`] ([`Hit::shape`] indexes this,
    /// then the moving shapes).
    pub fn shapes(&self) -> &[Shape] {
        &self.shapes
    }

    /// World-space bounds of everything a ray can hit ([`Aabb::EMPTY`] for an empty scene),
    /// moving shapes over the whole shutter.
    pub fn bounds(&self) -> Aabb {
        self.moving
            .iter()
            .fold(self.bounds, |b, moving| b.union(moving.swept))
    }

    /// The closest surface along `ray` with `0 < t < t_max`, if any.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.intersect_wide(ray.origin.into(), ray.dir.into(), t_max, ray.time)
            .map(|hit| hit.into_hit(ray.time))
    }

    /// `found`, or the closest hit of a moving shape before it (and before `t_max`), for the
    /// ray from `origin` in the unit direction `dir` at `time`.
    #[inline(never)]
    fn closest_moving(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        t_max: f32,
        time: f32,
        found: Option<WideHit>,
    ) -> Option<WideHit> {
        let ray = Ray {
            origin: origin.into(),
            dir: dir.into(),
            time,
        };
        let first = self.shapes.len() as u32;
        let mut closest = None;
        let mut t_max = found.as_ref().map_or(t_max, |hit| hit.t);
        for (i, moving) in self.moving.iter().enumerate() {
            if let Some(hit) = moving.intersect(&ray, t_max, first + i as u32) {
                t_max = hit.t;
                closest = Some(hit);
            }
        }
        closest.map(WideHit::from_hit).or(found)
    }

    /// [`Accel::intersect`] for the ray from `origin` in the unit direction `dir` at `time`.
    /// Moving shapes are tried here, after the static ones, rather than in the caller: a
    /// branch there between two hits would make the caller copy its hit through memory (10%
    /// of a static Cornell box's samples per second).
    #[inline(never)]
    fn intersect_wide(&self, origin: Vec3A, dir: Vec3A, t_max: f32, time: f32) -> Option<WideHit> {
        let found = if self.nodes.is_empty() || t_max.is_nan() || t_max <= 0.0 {
            None
        } else {
            let query = RayQuery::new(origin, dir);
            let (nodes, geometry) = (&self.nodes[..], &self.geometry);
            let found = match self.stack {
                StackKind::Small => {
                    let mut stack = ArrayStack::<_, SMALL_STACK>::new();
                    walk::closest(nodes, geometry, &mut stack, &query, t_max)
                }
                StackKind::Fixed => {
                    let mut stack = ArrayStack::<_, FIXED_STACK>::new();
                    walk::closest(nodes, geometry, &mut stack, &query, t_max)
                }
                StackKind::Heap => {
                    let mut stack = Vec::with_capacity(self.stack_need);
                    walk::closest(nodes, geometry, &mut stack, &query, t_max)
                }
            };
            found.map(|found| self.surface_hit(origin.into(), dir.into(), found))
        };
        if self.moving.is_empty() {
            return found;
        }
        self.closest_moving(origin, dir, t_max, time, found)
    }

    /// True when some surface lies along `ray` with `0 < t < t_max`.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.occluded_wide(ray.origin.into(), ray.dir.into(), t_max)
            || (!self.moving.is_empty() && self.occluded_moving(ray, t_max))
    }

    /// Whether a moving shape blocks `ray` before `t_max`.
    #[inline(never)]
    fn occluded_moving(&self, ray: &Ray, t_max: f32) -> bool {
        self.moving.iter().any(|m| m.occluded(ray, t_max))
    }

    /// [`Accel::occluded`] by static shapes only for the ray from `origin` in the unit
    /// direction `dir`, both given as 16-byte vectors (as [`crate::Rayx4::lanes`] makes them),
    /// so that a caller holding rays in that form hands them over in registers. Such rays have
    /// no time: a caller must not use it where something moves ([`Accel::has_motion`]).
    #[inline(never)]
    pub fn occluded_wide(&self, origin: Vec3A, dir: Vec3A, t_max: f32) -> bool {
        if self.nodes.is_empty() || t_max.is_nan() || t_max <= 0.0 {
            return false;
        }
        let query = RayQuery::new(origin, dir);
        let (nodes, geometry) = (&self.nodes[..], &self.geometry);
        match self.stack {
            StackKind::Small => {
                let mut stack = ArrayStack::<_, SMALL_STACK>::new();
                walk::any(nodes, geometry, &mut stack, &query, t_max)
            }
            StackKind::Fixed => {
                let mut stack = ArrayStack::<_, FIXED_STACK>::new();
                walk::any(nodes, geometry, &mut stack, &query, t_max)
            }
            StackKind::Heap => {
                let mut stack = Vec::with_capacity(self.stack_need);
                walk::any(nodes, geometry, &mut stack, &query, t_max)
            }
        }
    }

    /// Surface coordinates of `hit`, a hit this hierarchy returned: the mesh's interpolated
    /// texture coordinates, or the barycentric coordinates `(b1, b2)` of `p1` and `p2` when it has
    /// none; for a sphere `(phi / 2pi, theta / pi)` with `phi` measured from +x towards +y and
    /// `theta` from +z. Computed on request, since shading without textures never asks (a
    /// sphere's costs an `atan2` and an `acos`).
    pub fn uv(&self, hit: &Hit) -> Vec2 {
        match self.shape(hit.shape) {
            (Shape::Mesh(mesh), _) => {
                let b = hit.bary;
                mesh.uvs.as_ref().map_or(Vec2::new(b.y, b.z), |uv| {
                    let [i0, i1, i2] = mesh.indices[hit.prim as usize].map(|i| i as usize);
                    uv[i0] * b.x + uv[i1] * b.y + uv[i2] * b.z
                })
            }
            (Shape::Sphere(sphere), motion) => {
                let ng = motion.map_or(hit.ng, |m| m.at(hit.time).normal_to_object(hit.ng));
                let outward = if sphere.flip_normals { -ng } else { ng };
                Sphere::uv(sphere.to_local * outward)
            }
        }
    }

    /// The surface's first tangent direction at `hit` (world space, not normalised; zero where
    /// it has none), Mitsuba's ∂p/∂u: for a mesh with texture coordinates the derivative of
    /// position by u over the triangle (none where its coordinates are degenerate), for one
    /// without `p1 − p0` (the barycentric parameterisation), for a sphere the direction of
    /// growing φ about its own z axis (zero at the poles). A shading frame for anisotropic BSDFs
    /// starts from it; computed on request.
    pub fn dp_du(&self, hit: &Hit) -> Vec3 {
        let (shape, motion) = self.shape(hit.shape);
        let ng = motion.map_or(hit.ng, |m| m.at(hit.time).normal_to_object(hit.ng));
        let local = match shape {
            Shape::Mesh(mesh) => {
                let [i0, i1, i2] = mesh.indices[hit.prim as usize].map(|i| i as usize);
                let p = &mesh.positions;
                let (dp0, dp1) = (p[i1] - p[i0], p[i2] - p[i0]);
                match &mesh.uvs {
                    None => dp0,
                    Some(uv) => {
                        let (duv0, duv1) = (uv[i1] - uv[i0], uv[i2] - uv[i0]);
                        let det = duv0.x * duv1.y - duv0.y * duv1.x;
                        if det == 0.0 {
                            return Vec3::ZERO;
                        }
                        (duv1.y * dp0 - duv0.y * dp1) / det
                    }
                }
            }
            Shape::Sphere(sphere) => {
                let outward = if sphere.flip_normals { -ng } else { ng };
                let local = sphere.to_local * outward;
                sphere.to_local.transpose() * Vec3::new(-local.y, local.x, 0.0)
            }
        };
        motion.map_or(local, |m| moving::vector_at(m, hit, local))
    }

    /// ∂p/∂u and ∂p/∂v at `hit` (world units per unit of u and of v, the parameterisation of
    /// [`Self::uv`]), as Mitsuba's `dp_du` and `dp_dv`, for perturbing shading frames (bump
    /// maps): for a mesh with texture coordinates the derivatives over the triangle (both zero
    /// where its coordinates are degenerate), for one without `p1 − p0` and `p2 − p0`; for a
    /// sphere 2πr times the direction of growing φ and πr times that of growing θ (zero at the
    /// poles, where they have none); moved with a moving shape to the hit's time. Computed on
    /// request.
    pub fn dp_duv(&self, hit: &Hit) -> [Vec3; 2] {
        let (shape, motion) = self.shape(hit.shape);
        let local = match shape {
            Shape::Mesh(mesh) => {
                let [i0, i1, i2] = mesh.indices[hit.prim as usize].map(|i| i as usize);
                let p = &mesh.positions;
                let (dp0, dp1) = (p[i1] - p[i0], p[i2] - p[i0]);
                match &mesh.uvs {
                    None => [dp0, dp1],
                    Some(uv) => {
                        let (duv0, duv1) = (uv[i1] - uv[i0], uv[i2] - uv[i0]);
                        let det = duv0.x * duv1.y - duv0.y * duv1.x;
                        if det == 0.0 {
                            return [Vec3::ZERO; 2];
                        }
                        [
                            (duv1.y * dp0 - duv0.y * dp1) / det,
                            (duv0.x * dp1 - duv1.x * dp0) / det,
                        ]
                    }
                }
            }
            Shape::Sphere(sphere) => {
                let ng = motion.map_or(hit.ng, |m| m.at(hit.time).normal_to_object(hit.ng));
                let outward = if sphere.flip_normals { -ng } else { ng };
                let local = sphere.to_local * outward;
                let sin_theta = local.truncate().length();
                if sin_theta == 0.0 {
                    return [Vec3::ZERO; 2];
                }
                let (cos_phi, sin_phi) = (local.x / sin_theta, local.y / sin_theta);
                let to_world = sphere.to_local.transpose();
                let r = sphere.radius;
                [
                    to_world * (std::f32::consts::TAU * r * Vec3::new(-local.y, local.x, 0.0)),
                    to_world
                        * (std::f32::consts::PI
                            * r
                            * Vec3::new(local.z * cos_phi, local.z * sin_phi, -sin_theta)),
                ]
            }
        };
        local.map(|v| motion.map_or(v, |m| moving::vector_at(m, hit, v)))
    }

    fn surface_hit(&self, origin: Vec3, dir: Vec3, found: Found) -> WideHit {
        match found {
            Found::Triangle { packet, lane, hit } => {
                let info = self.triangle_infos[4 * packet + lane];
                let Shape::Mesh(mesh) = &self.shapes[info.shape as usize] else {
                    unreachable!("triangle {packet}:{lane} of a shape that is not a mesh")
                };
                let b = hit.bary;
                let p = self.geometry.packets[packet].point(lane, b);
                let [i0, i1, i2] = mesh.indices[info.prim as usize].map(|i| i as usize);
                let ns = mesh
                    .normals
                    .as_ref()
                    .and_then(|n| direction_of(n[i0] * b.x + n[i1] * b.y + n[i2] * b.z))
                    .map_or(info.ng, |ns| if ns.dot(info.ng) < 0.0 { -ns } else { ns });
                WideHit {
                    t: hit.t,
                    p: p.into(),
                    p_error: info.p_error.into(),
                    ng: info.ng.into(),
                    ns: ns.into(),
                    bary: b.into(),
                    ids: WideHit::ids(info.shape, info.prim),
                }
            }
            Found::Sphere { index, t } => {
                let info = self.sphere_infos[index];
                let Shape::Sphere(sphere) = &self.shapes[info.shape as usize] else {
                    unreachable!("sphere {index} of a shape that is not a sphere")
                };
                let geom = &self.geometry.spheres[index];
                // The computed point only lands on the centre when the radius is below the float
                // spacing at that position; the normal then faces the ray.
                let outward = direction_of(origin + t * dir - sphere.center).unwrap_or(-dir);
                let p = Vec3::from(geom.center) + geom.radius * outward;
                let ng = if sphere.flip_normals {
                    -outward
                } else {
                    outward
                };
                WideHit {
                    t,
                    p: p.into(),
                    p_error: info.p_error.into(),
                    ng: ng.into(),
                    ns: ng.into(),
                    bary: Vec3A::ZERO,
                    ids: WideHit::ids(info.shape, 0),
                }
            }
        }
    }
}

/// A [`Hit`] as the traversal hands it to [`Accel::intersect`], laid out so that each field is
/// written by one store as wide as the caller's loads of it: its vectors padded to 16 bytes, the
/// shape and primitive indices one 64-bit word (a `Vec3` is stored as 8 + 4 bytes, and a load
/// spanning two stores cannot be forwarded from the store buffer).
struct WideHit {
    t: f32,
    p: Vec3A,
    p_error: Vec3A,
    ng: Vec3A,
    ns: Vec3A,
    bary: Vec3A,
    /// The shape index in the low 32 bits, the primitive index in the high 32.
    ids: u64,
}

impl WideHit {
    /// `shape` and `prim` packed into [`WideHit::ids`].
    #[inline(always)]
    fn ids(shape: u32, prim: u32) -> u64 {
        u64::from(shape) | (u64::from(prim) << 32)
    }

    /// The record of `hit`.
    fn from_hit(hit: Hit) -> WideHit {
        WideHit {
            t: hit.t,
            p: hit.p.into(),
            p_error: hit.p_error.into(),
            ng: hit.ng.into(),
            ns: hit.ns.into(),
            bary: hit.bary.into(),
            ids: WideHit::ids(hit.shape, hit.prim),
        }
    }

    /// The [`Hit`] this record holds, found by a ray at `time`.
    #[inline(always)]
    fn into_hit(self, time: f32) -> Hit {
        Hit {
            time,
            t: self.t,
            p: self.p.into(),
            p_error: self.p_error.into(),
            ng: self.ng.into(),
            ns: self.ns.into(),
            bary: self.bary.into(),
            shape: self.ids as u32,
            prim: (self.ids >> 32) as u32,
        }
    }
}

#[cfg(test)]
mod tests;
