//! Triangle meshes in world space.

use std::fmt;

use glam::{Vec2, Vec3};

/// An indexed triangle mesh in world space (the scene loader applies `to_world` before handing
/// it over).
///
/// Triangles face the side of `(p1 - p0) x (p2 - p0)`; nothing here flips them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    /// Vertex positions in world space.
    pub positions: Vec<Vec3>,
    /// Optional unit vertex normals in world space, one per position.
    pub normals: Option<Vec<Vec3>>,
    /// Optional vertex texture coordinates, one per position.
    pub uvs: Option<Vec<Vec2>>,
    /// Vertex indices of each triangle, in winding order.
    pub indices: Vec<[u32; 3]>,
}

/// Why a [`TriangleMesh`] is malformed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MeshError {
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The offending vertex index.
        index: u32,
        /// The number of vertices.
        vertex_count: usize,
    },
    /// An attribute array does not have one entry per vertex.
    AttributeLength {
        /// `"normals"` or `"uvs"`.
        attribute: &'static str,
        /// Its length.
        len: usize,
        /// The number of vertices.
        vertex_count: usize,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshError::IndexOutOfRange {
                triangle,
                index,
                vertex_count,
            } => write!(
                f,
                "triangle {triangle} uses vertex {index}, but the mesh has {vertex_count} vertices"
            ),
            MeshError::AttributeLength {
                attribute,
                len,
                vertex_count,
            } => write!(
                f,
                "the mesh has {len} {attribute} for {vertex_count} vertices"
            ),
        }
    }
}

impl std::error::Error for MeshError {}

impl TriangleMesh {
    /// A mesh from its parts, checked with [`TriangleMesh::validate`].
    pub fn new(
        positions: Vec<Vec3>,
        normals: Option<Vec<Vec3>>,
        uvs: Option<Vec<Vec2>>,
        indices: Vec<[u32; 3]>,
    ) -> Result<Self, MeshError> {
        let mesh = Self {
            positions,
            normals,
            uvs,
            indices,
        };
        mesh.validate()?;
        Ok(mesh)
    }

    /// Checks that every index names a vertex and every attribute has one entry per vertex.
    /// [`crate::Accel::new`] requires this to hold.
    pub fn validate(&self) -> Result<(), MeshError> {
        let vertex_count = self.positions.len();
        let attributes = [
            ("normals", self.normals.as_ref().map(Vec::len)),
            ("uvs", self.uvs.as_ref().map(Vec::len)),
        ];
        for (attribute, len) in attributes {
            if let Some(len) = len.filter(|&len| len != vertex_count) {
                return Err(MeshError::AttributeLength {
                    attribute,
                    len,
                    vertex_count,
                });
            }
        }
        for (triangle, tri) in self.indices.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= vertex_count) {
                return Err(MeshError::IndexOutOfRange {
                    triangle,
                    index,
                    vertex_count,
                });
            }
        }
        Ok(())
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    /// The three vertex positions of triangle `i`, in winding order.
    pub fn triangle(&self, i: usize) -> [Vec3; 3] {
        self.indices[i].map(|v| self.positions[v as usize])
    }

    /// Area of triangle `i` in world units squared (zero for a degenerate triangle).
    pub fn triangle_area(&self, i: usize) -> f32 {
        let [p0, p1, p2] = self.triangle(i);
        0.5 * (p1 - p0).cross(p2 - p0).length()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad() -> TriangleMesh {
        TriangleMesh::new(
            vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::new(1.0, 2.0, 0.0),
                Vec3::new(0.0, 2.0, 0.0),
            ],
            None,
            None,
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .expect("valid quad")
    }

    #[test]
    fn areas_and_triangles() {
        let m = quad();
        assert_eq!(m.triangle_count(), 2);
        assert_eq!(
            m.triangle(1),
            [
                Vec3::ZERO,
                Vec3::new(1.0, 2.0, 0.0),
                Vec3::new(0.0, 2.0, 0.0)
            ]
        );
        assert_eq!(m.triangle_area(0) + m.triangle_area(1), 2.0);
    }

    #[test]
    fn validation_catches_bad_indices_and_attribute_lengths() {
        let mut m = quad();
        m.indices.push([0, 4, 1]);
        assert_eq!(
            m.validate(),
            Err(MeshError::IndexOutOfRange {
                triangle: 2,
                index: 4,
                vertex_count: 4
            })
        );
        let mut m = quad();
        m.uvs = Some(vec![Vec2::ZERO; 3]);
        assert!(matches!(
            m.validate(),
            Err(MeshError::AttributeLength {
                attribute: "uvs",
                len: 3,
                ..
            })
        ));
    }
}
