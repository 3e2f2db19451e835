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

/// `cube`: [-1, 1]³ with outward faces in Mitsuba's layout, so that textures land where
/// Mitsuba puts them: per face (bottom, top, +x, +z, −x, −z) 4 vertices with uv (0, 1), (1, 1),
/// (1, 0), (0, 0) and the triangles (0, 1, 2), (3, 0, 2); a face's point is n + (2u − 1) U +
/// (2v − 1) V for its normal n and the directions U, V of [`CUBE_FACES`].
pub(crate) fn cube() -> MeshDesc {
    let mut mesh = MeshDesc::default();
    let mut uvs = Vec::new();
    for [n, u_dir, v_dir] in CUBE_FACES {
        let base = mesh.positions.len() as u32;
        for uv in [Vec2::new(0.0, 1.0), Vec2::ONE, Vec2::X, Vec2::ZERO] {
            let (du, dv) = (2.0 * uv.x - 1.0, 2.0 * uv.y - 1.0);
            mesh.positions.push(n + u_dir * du + v_dir * dv);
            uvs.push(uv);
        }
        mesh.triangles
            .extend([[base, base + 1, base + 2], [base + 3, base, base + 2]]);
    }
    mesh.uvs = Some(uvs);
    mesh
}

/// The cube's faces as Mitsuba orders them: outward normal, and the directions in which u and v
/// grow.
const CUBE_FACES: [[Vec3; 3]; 6] = [
    [Vec3::NEG_Y, Vec3::Z, Vec3::X],
    [Vec3::Y, Vec3::NEG_X, Vec3::NEG_Z],
    [Vec3::X, Vec3::Y, Vec3::NEG_Z],
    [Vec3::Z, Vec3::Y, Vec3::X],
    [Vec3::NEG_X, Vec3::Y, Vec3::Z],
    [Vec3::NEG_Z, Vec3::NEG_Y, Vec3::X],
];

/// `disk`: the unit disk in the z = 0 plane facing +z, as a fan of [`DISK_SEGMENTS`] triangles.
///
/// The rim radius is enlarged slightly so that the polygon's area equals π, the disk's area:
/// an emitting disk then has exactly Mitsuba's power. Surface coordinates are Mitsuba's polar
/// ones, u = r and v = atan2(y, x) / 2π in (−½, ½], interpolated over each triangle: the rim
/// vertex at φ = π appears twice (v = ½ and −½) and each triangle has its own centre vertex
/// (u = 0, v of the triangle's middle angle). Interpolation strays from the exact coordinates
/// by under 3e-4 in u, and in v by under 1/256 only near the centre, where v turns fastest.
pub(crate) fn disk() -> MeshDesc {
    let n = f64::from(DISK_SEGMENTS);
    let step = TAU / n;
    let radius = (TAU / (n * step.sin())).sqrt();
    let rim = |i: u32| {
        let phi = step * f64::from(i);
        Vec3::new(
            (radius * phi.cos()) as f32,
            (radius * phi.sin()) as f32,
            0.0,
        )
    };
    // v of rim vertex i, on the side of the seam at φ = π that the triangle starting at
    // vertex `first` lies on.
    let v_of = |i: u32, first: u32| {
        let turns = f64::from(i % DISK_SEGMENTS) / n;
        let past_seam = if first >= DISK_SEGMENTS / 2 {
            turns >= 0.5
        } else {
            turns > 0.5
        };
        (if past_seam { turns - 1.0 } else { turns }) as f32
    };
    let mut mesh = MeshDesc::default();
    let mut uvs = Vec::new();
    for i in 0..DISK_SEGMENTS {
        let base = mesh.positions.len() as u32;
        let (v0, v1) = (v_of(i, i), v_of(i + 1, i));
        mesh.positions
            .extend([Vec3::ZERO, rim(i), rim((i + 1) % DISK_SEGMENTS)]);
        uvs.extend([
            Vec2::new(0.0, 0.5 * (v0 + v1)),
            Vec2::new(1.0, v0),
            Vec2::new(1.0, v1),
        ]);
        mesh.triangles.push([base, base + 1, base + 2]);
    }
    mesh.uvs = Some(uvs);
    mesh
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

    /// The uv of the cube's point `p` on the face that `p` lies on, interpolated as a hit's.
    fn cube_uv_at(p: Vec3) -> Vec2 {
        let mesh = cube();
        let uvs = mesh.uvs.as_ref().unwrap();
        for tri in &mesh.triangles {
            let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
            let n = (b - a).cross(c - a);
            let area = |x: Vec3, y: Vec3, z: Vec3| (y - x).cross(z - x).dot(n) / n.length_squared();
            let bary = [area(p, b, c), area(a, p, c), area(a, b, p)];
            if (p - a).dot(n).abs() < 1e-6 && bary.iter().all(|&w| w >= -1e-6) {
                return tri
                    .iter()
                    .zip(bary)
                    .map(|(&i, w)| uvs[i as usize] * w)
                    .sum();
            }
        }
        panic!("{p} is not on the cube");
    }

    #[test]
    fn cube_uvs_are_mitsubas() {
        // Mitsuba 3.9.1 (scalar_rgb): `si.uv` of rays hitting its cube at each point, one per face.
        let mitsuba = [
            (Vec3::new(0.5, -1.0, 0.25), Vec2::new(0.625, 0.75)),
            (Vec3::new(0.3, 1.0, -0.6), Vec2::new(0.35, 0.8)),
            (Vec3::new(1.0, 0.2, 0.7), Vec2::new(0.6, 0.15)),
            (Vec3::new(-1.0, -0.4, 0.1), Vec2::new(0.3, 0.55)),
            (Vec3::new(0.1, 0.8, 1.0), Vec2::new(0.9, 0.55)),
            (Vec3::new(-0.7, 0.2, -1.0), Vec2::new(0.4, 0.15)),
        ];
        for (p, uv) in mitsuba {
            let got = cube_uv_at(p);
            assert!(
                (got - uv).abs().max_element() < 1e-5,
                "{got} at {p}, Mitsuba {uv}"
            );
        }
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

    /// The interpolated surface coordinates match Mitsuba's (r, atan2(y, x) / 2π) on both sides
    /// of the seam at φ = π and away from the centre.
    #[test]
    fn disk_uv_is_polar_as_mitsuba_has_it() {
        let mesh = disk();
        let uvs = mesh.uvs.as_ref().unwrap();
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|i| i as usize);
            for (b1, b2) in [(0.45, 0.45), (0.3, 0.5), (0.7, 0.1)] {
                let b0 = 1.0 - b1 - b2;
                let p = mesh.positions[a] * b0 + mesh.positions[b] * b1 + mesh.positions[c] * b2;
                let uv = uvs[a] * b0 + uvs[b] * b1 + uvs[c] * b2;
                let exact = Vec2::new(p.truncate().length(), p.y.atan2(p.x) / TAU as f32);
                assert!(
                    (uv - exact).abs().max_element() < 1e-3,
                    "triangle {t}: {uv} against {exact}"
                );
            }
        }
    }
}
