//! Descriptions of shapes in the scene frame (world space translated so that the camera sits at
//! the origin, see [`crate::SceneDesc`]).

use glam::{Mat3, Vec2, Vec3};

use super::material::AreaEmitterDesc;

/// A triangle mesh, placed in the scene frame (see [`crate::SceneDesc`]), or in its file's own
/// coordinates as [`crate::parse_obj`] and [`crate::parse_ply`] return it.
///
/// The winding order defines the geometric normal: `(p1 - p0) × (p2 - p0)` points to the front
/// side. `to_world` and `flip_normals` are already applied: a mirroring transform or
/// `flip_normals` (but not both) reverses the winding, so the geometric normal and the vertex
/// normals always agree in orientation (Mitsuba's current `Mesh` convention).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MeshDesc {
    /// Vertex positions (world units).
    pub positions: Vec<Vec3>,
    /// Unit vertex normals for smooth shading, one per position (transformed by the
    /// inverse transpose of `to_world`). `None` means flat shading with the geometric normal:
    /// `face_normals="true"`, and the flat canonical shapes (rectangle, cube, disk).
    pub normals: Option<Vec<Vec3>>,
    /// Texture coordinates, one per position, when the source has them.
    pub uvs: Option<Vec<Vec2>>,
    /// Triangles as indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
}

/// A sphere (`<shape type="sphere">`) in the scene frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereDesc {
    /// Centre, relative to the camera (world units).
    pub center: Vec3,
    /// Radius, world units, positive.
    pub radius: f32,
    /// Whether the normals point inwards (`flip_normals`), which also turns the front side of a
    /// one-sided BSDF or area light inwards.
    pub flip_normals: bool,
    /// The rotation from world directions to the sphere's own frame (the inverse of its
    /// `to_world`'s rotation), in which Mitsuba defines its surface coordinates.
    pub to_local: Mat3,
}

/// The geometry of a shape.
#[derive(Debug, Clone, PartialEq)]
pub enum Geometry {
    /// Triangles: `obj`, `ply`, `rectangle`, `cube` and `disk`.
    Mesh(MeshDesc),
    /// An analytic sphere.
    Sphere(SphereDesc),
}

/// One `<shape>`.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeDesc {
    /// The Mitsuba plugin name it came from (`obj`, `ply`, `rectangle`, `cube`, `disk`, `sphere`).
    pub plugin: String,
    /// The `id` attribute.
    pub id: Option<String>,
    /// The geometry, in the scene frame.
    pub geometry: Geometry,
    /// Index into [`crate::SceneDesc::bsdfs`].
    pub bsdf: usize,
    /// The area light on this shape, if any.
    pub emitter: Option<AreaEmitterDesc>,
    /// For a shape that moves (an `<animation>` as its `to_world`, Strata's extension for
    /// motion blur): its object-to-scene-frame transform over time, and `geometry` is in
    /// object space. `None` for a static shape, whose `geometry` is in the scene frame.
    pub motion: Option<geometry::AnimatedTransform>,
}
