//! A sphere mesh generated in code: for tests, benchmarks and scenes that need smooth normals.

use crate::TriangleMesh;
use glam::{Vec2, Vec3};
use std::collections::HashMap;

impl TriangleMesh {
    /// The unit icosphere: an icosahedron whose faces are split `subdivisions` times (4 triangles
    /// each time) and whose vertices are pushed onto the unit sphere; wound outwards, with per-vertex
    /// normals and texture coordinates.
    pub fn icosphere(subdivisions: u32) -> TriangleMesh {
        let t = (1.0 + 5f32.sqrt()) / 2.0;
        let mut positions: Vec<Vec3> = [
            (-1.0, t, 0.0),
            (1.0, t, 0.0),
            (-1.0, -t, 0.0),
            (1.0, -t, 0.0),
            (0.0, -1.0, t),
            (0.0, 1.0, t),
            (0.0, -1.0, -t),
            (0.0, 1.0, -t),
            (t, 0.0, -1.0),
            (t, 0.0, 1.0),
            (-t, 0.0, -1.0),
            (-t, 0.0, 1.0),
        ]
        .iter()
        .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
        .collect();
        let mut indices: Vec<[u32; 3]> = vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        for _ in 0..subdivisions {
            let mut midpoints = HashMap::new();
            let mut midpoint = |a: u32, b: u32, positions: &mut Vec<Vec3>| {
                *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    positions.push((positions[a as usize] + positions[b as usize]).normalize());
                    positions.len() as u32 - 1
                })
            };
            indices = indices
                .iter()
                .flat_map(|&[a, b, c]| {
                    let ab = midpoint(a, b, &mut positions);
                    let bc = midpoint(b, c, &mut positions);
                    let ca = midpoint(c, a, &mut positions);
                    [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
                })
                .collect();
        }
        let uvs = positions.iter().map(|p| Vec2::new(p.x, p.y)).collect();
        let normals = positions.clone();
        TriangleMesh::new(positions, Some(normals), Some(uvs), indices)
            .expect("generated meshes are valid")
    }
}
