//! Scene generators, a small random number generator and transforms shared by the tests (and
//! the benchmark).
#![allow(dead_code)] // Each test binary uses a different subset.

use std::collections::HashMap;

use geometry::TriangleMesh;
use glam::Vec3;

/// PCG32 (O'Neill), enough for reproducible test inputs.
pub struct Pcg32 {
    state: u64,
}

impl Pcg32 {
    /// A generator for `seed`.
    pub fn new(seed: u64) -> Self {
        let mut rng = Self {
            state: seed.wrapping_add(0x853c_49e6_748f_ea9b),
        };
        rng.next_u32();
        rng
    }

    /// Uniform 32-bit integer.
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }

    /// Uniform in `[0, 1)`.
    pub fn f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.f32()
    }

    /// Uniform integer in `0..n`.
    pub fn below(&mut self, n: usize) -> usize {
        ((self.next_u32() as u64 * n as u64) >> 32) as usize
    }

    /// Uniform point in the cube `[-1, 1)^3`.
    pub fn in_cube(&mut self) -> Vec3 {
        Vec3::new(
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
        )
    }

    /// Uniform unit vector.
    pub fn unit(&mut self) -> Vec3 {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, std::f32::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    /// Uniform unit vector in the hemisphere around `n`.
    pub fn unit_around(&mut self, n: Vec3) -> Vec3 {
        let d = self.unit();
        if d.dot(n) < 0.0 { -d } else { d }
    }

    /// Uniform barycentric coordinates.
    pub fn barycentric(&mut self) -> Vec3 {
        let (a, b) = (self.f32(), self.f32());
        let (a, b) = if a + b > 1.0 {
            (1.0 - a, 1.0 - b)
        } else {
            (a, b)
        };
        Vec3::new(1.0 - a - b, a, b)
    }
}

/// An indexed mesh from a triangle list, merging vertices with identical bits.
fn indexed(triangles: impl IntoIterator<Item = [Vec3; 3]>) -> TriangleMesh {
    let mut positions = Vec::new();
    let mut lookup = HashMap::new();
    let indices = triangles
        .into_iter()
        .map(|tri| {
            tri.map(|p| {
                *lookup
                    .entry(p.to_array().map(f32::to_bits))
                    .or_insert_with(|| {
                        positions.push(p);
                        positions.len() as u32 - 1
                    })
            })
        })
        .collect();
    TriangleMesh::new(positions, None, None, indices).expect("generated meshes are valid")
}

/// The closed cube `[-1, 1]^3`, each face split into `n x n` quads (two triangles each), wound
/// so that `(p1 - p0) x (p2 - p0)` points outwards. Vertices on shared edges are computed by the
/// same expression on every face, so they are bitwise identical.
pub fn subdivided_cube(n: u32) -> TriangleMesh {
    let grid = |i: u32| -1.0 + 2.0 * i as f32 / n as f32;
    let mut tris = Vec::new();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let point = |i: u32, j: u32| {
                let mut p = [0.0; 3];
                p[axis] = sign;
                p[(axis + 1) % 3] = grid(i);
                p[(axis + 2) % 3] = grid(j);
                Vec3::from_array(p)
            };
            for i in 0..n {
                for j in 0..n {
                    let (a, b, c, d) = (
                        point(i, j),
                        point(i + 1, j),
                        point(i + 1, j + 1),
                        point(i, j + 1),
                    );
                    if sign > 0.0 {
                        tris.push([a, b, c]);
                        tris.push([a, c, d]);
                    } else {
                        tris.push([a, c, b]);
                        tris.push([a, d, c]);
                    }
                }
            }
        }
    }
    indexed(tris)
}

/// `mesh` scaled by `scale` about the origin, then translated by `offset` (normals unchanged).
pub fn transformed(mesh: &TriangleMesh, scale: f32, offset: Vec3) -> TriangleMesh {
    TriangleMesh {
        positions: mesh.positions.iter().map(|&p| p * scale + offset).collect(),
        ..mesh.clone()
    }
}

/// `count` random triangles with vertices in `[-1, 1)^3` and edges up to about `size`.
pub fn triangle_soup(rng: &mut Pcg32, count: usize, size: f32) -> TriangleMesh {
    let positions = (0..count)
        .flat_map(|_| {
            let c = rng.in_cube();
            [c, c + size * rng.in_cube(), c + size * rng.in_cube()]
        })
        .collect();
    let indices = (0..count as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    TriangleMesh::new(positions, None, None, indices).expect("generated meshes are valid")
}
