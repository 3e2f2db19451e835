//! Mitsuba's built-in shapes as object-space triangle meshes.

use std::f64::consts::TAU;

use glam::{Vec2, Vec3};

use crate::desc::MeshDesc;

/// Number of rim vertices of the triangulated disk.
pub(crate) const DISK_SEGMENTS: u32 = 128;

/// Number of facets around the triangulated cylinder.
pub(crate) const CYLINDER_SEGMENTS: u32 = 256;

/// `rectangle`: [-1, 1]² in the z = 0 plane facing +z, uv = ((x + 1) / 2, (y + 1) / 2).
pub(crate) fn rectangle() -> MeshDesc {
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    MeshDesc {
        positions: corners.iter().map(|&(x, y)| Vec3::new(x, y, 0.0)).collect(),
        normals: None,
        uvs: Some(
            corners
                .iter()
                .map(|&(x, y)| Vec2::new((x + 1.0) / 2.0, (y + 1.0) / 2.0))
                .collect(),
        ),
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    }
}

/// `cube`: [-1, 1]³ with outward faces, 4 vertices and 2 triangles per face, each face's uv
/// covering [0, 1]².
pub(crate) fn cube() -> MeshDesc {
    let mut mesh = MeshDesc::default();
    let mut uvs = Vec::new();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            // u × v = n for the outward normal n = sign · e_axis.
            let n = Vec3::AXES[axis] * sign;
            let u = Vec3::AXES[(axis + 1) % 3] * sign;
            let v = Vec3::AXES[(axis + 2) % 3];
            let base = mesh.positions.len() as u32;
            for (du, dv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                mesh.positions.push(n + u * du + v * dv);
                uvs.push(Vec2::new((du + 1.0) / 2.0, (dv + 1.0) / 2.0));
            }
            mesh.triangles
                .extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
        }
    }
    mesh.uvs = Some(uvs);
    mesh
}

/// `disk`: the unit disk in the z = 0 plane facing +z, as a fan of [`DISK_SEGMENTS`] triangles.
///
/// The rim radius is enlarged slightly so that the polygon's area equals π, the disk's area:
/// an emitting disk then has exactly Mitsuba's power. No uv coordinates (Mitsuba's disk uses polar
/// ones, which a fan cannot interpolate).
pub(crate) fn disk() -> MeshDesc {
    let n = f64::from(DISK_SEGMENTS);
    let step = TAU / n;
    let radius = (TAU / (n * step.sin())).sqrt();
    let mut positions = vec![Vec3::ZERO];
    positions.extend((0..DISK_SEGMENTS).map(|i| {
        let phi = step * f64::from(i);
        Vec3::new(
            (radius * phi.cos()) as f32,
            (radius * phi.sin()) as f32,
            0.0,
        )
    }));
    let triangles = (0..DISK_SEGMENTS)
        .map(|i| [0, 1 + i, 1 + (i + 1) % DISK_SEGMENTS])
        .collect();
    MeshDesc {
        positions,
        normals: None,
        uvs: None,
        triangles,
    }
}

/// `cylinder`: the unit cylinder around the z axis from z = 0 to z = 1, without caps, normals
/// pointing out, as [`CYLINDER_SEGMENTS`] quads with radial vertex normals and uv =
/// (φ / 2π, z) (a seam of duplicated vertices at φ = 0).
///
/// The facets' radius is enlarged slightly so that the polygon's perimeter equals 2π, the
/// circle's: the lateral area, and so an emitting cylinder's power, is Mitsuba's; the facets
/// stray from the true surface by at most about 7.5e-5 of the radius.
pub(crate) fn cylinder() -> MeshDesc {
    let n = f64::from(CYLINDER_SEGMENTS);
    let step = TAU / n;
    let radius = (step / 2.0) / (step / 2.0).sin();
    let mut mesh = MeshDesc::default();
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    for i in 0..=CYLINDER_SEGMENTS {
        let phi = step * f64::from(i);
        let (x, y) = (phi.cos(), phi.sin());
        for z in [0.0, 1.0] {
            mesh.positions
                .push(Vec3::new((radius * x) as f32, (radius * y) as f32, z));
            normals.push(Vec3::new(x as f32, y as f32, 0.0));
            uvs.push(Vec2::new((f64::from(i) / n) as f32, z));
        }
    }
    for i in 0..CYLINDER_SEGMENTS {
        let (bottom, top, next_bottom, next_top) = (2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3);
        // Counter-clockwise seen from outside: the facet's normal points away from the axis.
        mesh.triangles
            .extend([[bottom, next_bottom, next_top], [bottom, next_top, top]]);
    }
    mesh.normals = Some(normals);
    mesh.uvs = Some(uvs);
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area_and_normal_sum(mesh: &MeshDesc) -> (f32, Vec3) {
        let mut area = 0.0;
        let mut sum = Vec3::ZERO;
        for tri in &mesh.triangles {
            let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
            let cross = (b - a).cross(c - a);
            area += cross.length() / 2.0;
            sum += cross / 2.0;
        }
        (area, sum)
    }

    #[test]
    fn rectangle_faces_plus_z_with_area_four() {
        let (area, sum) = area_and_normal_sum(&rectangle());
        assert!((area - 4.0).abs() < 1e-6);
        assert!((sum - Vec3::new(0.0, 0.0, 4.0)).length() < 1e-6);
    }

    #[test]
    fn cube_faces_point_outwards() {
        let mesh = cube();
        assert_eq!(mesh.triangles.len(), 12);
        let (area, _) = area_and_normal_sum(&mesh);
        assert!((area - 24.0).abs() < 1e-5);
        for tri in &mesh.triangles {
            let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
            let n = (b - a).cross(c - a).normalize();
            let centroid = (a + b + c) / 3.0;
            // Outward: the normal is the axis the centroid sits on.
            assert!(n.dot(centroid) > 0.6, "{n} at {centroid}");
            for p in [a, b, c] {
                assert_eq!(p.abs(), Vec3::ONE);
            }
        }
    }

    #[test]
    fn cylinder_has_the_lateral_area_and_faces_outwards() {
        let mesh = cylinder();
        let (area, sum) = area_and_normal_sum(&mesh);
        assert!((area - std::f32::consts::TAU).abs() < 1e-4, "{area}");
        assert!(sum.length() < 1e-4, "a closed band's normals cancel: {sum}");
        for tri in &mesh.triangles {
            let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
            let n = (b - a).cross(c - a).normalize();
            let centroid = (a + b + c) / 3.0;
            let radial = Vec3::new(centroid.x, centroid.y, 0.0).normalize();
            assert!(n.dot(radial) > 0.999, "{n} at {centroid}");
        }
        let normals = mesh.normals.as_ref().expect("radial normals");
        for (p, n) in mesh.positions.iter().zip(normals) {
            assert!((Vec3::new(p.x, p.y, 0.0).normalize() - *n).length() < 1e-5);
            assert!(p.z == 0.0 || p.z == 1.0);
        }
    }

    #[test]
    fn disk_has_area_pi_and_faces_plus_z() {
        let mesh = disk();
        let (area, sum) = area_and_normal_sum(&mesh);
        assert!((area - std::f32::consts::PI).abs() < 1e-5, "{area}");
        assert!((sum.z - area).abs() < 1e-5);
        let max_r = mesh
            .positions
            .iter()
            .map(|p| p.length())
            .fold(0.0, f32::max);
        assert!((max_r - 1.0).abs() < 1e-3);
    }
}
