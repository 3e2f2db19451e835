//! Smooth vertex normals for meshes that have none (Mitsuba's `recompute_vertex_normals`).

use glam::Vec3;

/// Angle-weighted vertex normals (Thürmer and Wüthrich 1998), oriented by the triangles' winding.
/// A vertex that touches no triangle of positive area gets +z, which no ray can see.
pub(crate) fn vertex_normals(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let mut sums = vec![Vec3::ZERO; positions.len()];
    for tri in triangles {
        let p = tri.map(|i| positions[i as usize]);
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        let Some(n) = n.try_normalize() else {
            continue;
        };
        for corner in 0..3 {
            let a = p[(corner + 1) % 3] - p[corner];
            let b = p[(corner + 2) % 3] - p[corner];
            let angle = a.angle_between(b);
            if angle.is_finite() {
                sums[tri[corner] as usize] += n * angle;
            }
        }
    }
    sums.into_iter()
        .map(|n| n.try_normalize().unwrap_or(Vec3::Z))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planar_fan_gets_plane_normal() {
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        let normals = vertex_normals(&positions, &[[0, 1, 2], [0, 2, 3]]);
        for n in normals {
            assert!((n - Vec3::Z).length() < 1e-6);
        }
    }

    #[test]
    fn corner_of_cube_weights_faces_by_angle() {
        // Three right-angled triangles meeting at the origin, one in each coordinate plane with
        // outward (negative) normals: every face contributes the same angle, so the normal is
        // the negative diagonal.
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
        let tris = [[0, 2, 1], [0, 3, 2], [0, 1, 3]];
        let n = vertex_normals(&positions, &tris)[0];
        assert!((n - (-Vec3::ONE).normalize()).length() < 1e-6, "{n}");
    }

    #[test]
    fn isolated_and_degenerate_vertices_get_a_unit_fallback() {
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::new(2.0, 0.0, 0.0), Vec3::Y];
        let normals = vertex_normals(&positions, &[[0, 1, 2]]);
        assert_eq!(normals[3], Vec3::Z);
        assert_eq!(normals[0], Vec3::Z);
    }
}
