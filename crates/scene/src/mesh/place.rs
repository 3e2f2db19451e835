//! Puts an object-space mesh into world space: `to_world`, `flip_normals` and shading normals.

use glam::{DMat3, DMat4, Vec3};

use super::normals::vertex_normals;
use crate::desc::MeshDesc;

/// How the placed mesh is shaded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Shading {
    /// No vertex normals: the geometric normal everywhere (`face_normals`, flat canonical shapes).
    Flat,
    /// Vertex normals: the mesh's own, or angle-weighted ones computed in world space when it has
    /// none (as Mitsuba does).
    Smooth,
}

/// How the winding of a placed mesh answers a mirroring `to_world`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mirroring {
    /// Reversed, so the geometric normals keep their side: Mitsuba's analytic shapes (rectangle,
    /// disk, cylinder), whose normals it transforms, and instances, whose normals it transforms
    /// by the instance's inverse transpose.
    KeepsSides,
    /// Kept, so the geometric normals (the triangles' cross products) and the normals computed
    /// from them change side: Mitsuba's mesh files (`obj`, `ply`, `serialized`), whose positions
    /// it transforms and whose face normals it then takes from the transformed triangles. Unless
    /// the mesh is shaded by vertex normals of its own: Mitsuba transforms those by the inverse
    /// transpose and shades by them, so their side stays, and the winding is reversed to keep the
    /// geometric normals with them (a hit's shading normal is kept on its geometric normal's
    /// side).
    TurnsSides,
}

/// Applies `to_world` to `mesh` (positions by the matrix, normals by its inverse transpose),
/// reverses the winding when `flip_normals` is set, or when the transform mirrors and `mirroring`
/// keeps sides (but not both), negates given normals for `flip_normals`, and fills in normals for
/// smooth shading.
///
/// `to_world` must be invertible. Fails when a placed position is not finite in `f32`.
pub(crate) fn place(
    mut mesh: MeshDesc,
    to_world: &DMat4,
    flip_normals: bool,
    shading: Shading,
    mirroring: Mirroring,
) -> Result<MeshDesc, String> {
    for p in &mut mesh.positions {
        let placed = to_world.transform_point3(p.as_dvec3()).as_vec3();
        if !placed.is_finite() {
            return Err(format!("vertex {p} is not finite after applying to_world"));
        }
        *p = placed;
    }

    let linear = DMat3::from_mat4(*to_world);
    let keeps_sides = match mirroring {
        Mirroring::KeepsSides => true,
        Mirroring::TurnsSides => shading == Shading::Smooth && mesh.normals.is_some(),
    };
    let mirrored = linear.determinant() < 0.0 && keeps_sides;
    if mirrored != flip_normals {
        for tri in &mut mesh.triangles {
            tri.swap(0, 2);
        }
    }

    mesh.normals = match (shading, mesh.normals.take()) {
        (Shading::Flat, _) => None,
        (Shading::Smooth, None) => Some(vertex_normals(&mesh.positions, &mesh.triangles)),
        (Shading::Smooth, Some(given)) => {
            let normal_matrix = linear.inverse().transpose();
            let sign = if flip_normals { -1.0 } else { 1.0 };
            let transformed: Vec<Option<Vec3>> = given
                .iter()
                .map(|n| {
                    (normal_matrix * n.as_dvec3())
                        .try_normalize()
                        .map(|n| (n * sign).as_vec3())
                })
                .collect();
            // Zero or invalid normals in the file fall back to computed ones.
            let fallback = transformed
                .iter()
                .any(Option::is_none)
                .then(|| vertex_normals(&mesh.positions, &mesh.triangles));
            Some(
                transformed
                    .into_iter()
                    .enumerate()
                    .map(|(i, n)| n.unwrap_or_else(|| fallback.as_ref().map_or(Vec3::Z, |f| f[i])))
                    .collect(),
            )
        }
    };
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn triangle(normals: bool) -> MeshDesc {
        MeshDesc {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            normals: normals.then(|| vec![Vec3::Z; 3]),
            uvs: None,
            triangles: vec![[0, 1, 2]],
        }
    }

    fn geometric_normal(mesh: &MeshDesc) -> Vec3 {
        let [a, b, c] = mesh.triangles[0].map(|i| mesh.positions[i as usize]);
        (b - a).cross(c - a).normalize()
    }

    #[test]
    fn nonuniform_scale_uses_inverse_transpose_for_normals() {
        let mut mesh = triangle(true);
        mesh.normals = Some(vec![Vec3::new(1.0, 1.0, 0.0).normalize(); 3]);
        let m = DMat4::from_scale(DVec3::new(2.0, 1.0, 1.0));
        let placed = place(mesh, &m, false, Shading::Smooth, Mirroring::KeepsSides).unwrap();
        // The plane x + y = c becomes x/2 + y = c', whose normal is (0.5, 1, 0) normalised.
        let expected = Vec3::new(0.5, 1.0, 0.0).normalize();
        assert!((placed.normals.unwrap()[0] - expected).length() < 1e-6);
        assert_eq!(placed.positions[1], Vec3::new(2.0, 0.0, 0.0));
    }

    #[test]
    fn mirroring_reverses_winding_so_normals_agree() {
        let m = DMat4::from_scale(DVec3::new(-1.0, 1.0, 1.0));
        let placed = place(
            triangle(true),
            &m,
            false,
            Shading::Smooth,
            Mirroring::KeepsSides,
        )
        .unwrap();
        let n = placed.normals.as_ref().unwrap()[0];
        assert!((n - Vec3::Z).length() < 1e-6);
        assert!((geometric_normal(&placed) - Vec3::Z).length() < 1e-6);
    }

    #[test]
    fn mesh_files_keep_their_winding_when_mirrored() {
        let m = DMat4::from_scale(DVec3::new(-1.0, 1.0, 1.0));
        let turns = Mirroring::TurnsSides;
        // Face normals and computed normals turn, as Mitsuba's taken from the placed triangles.
        let flat = place(triangle(true), &m, false, Shading::Flat, turns).unwrap();
        assert!((geometric_normal(&flat) + Vec3::Z).length() < 1e-6);
        let computed = place(triangle(false), &m, false, Shading::Smooth, turns).unwrap();
        assert_eq!(computed.normals.unwrap(), vec![-Vec3::Z; 3]);
        // Given normals keep their side, and the triangle turns back to agree with them.
        let given = place(triangle(true), &m, false, Shading::Smooth, turns).unwrap();
        assert!((given.normals.as_ref().unwrap()[0] - Vec3::Z).length() < 1e-6);
        assert!((geometric_normal(&given) - Vec3::Z).length() < 1e-6);
    }

    #[test]
    fn flip_normals_turns_both_normals_around() {
        let placed = place(
            triangle(true),
            &DMat4::IDENTITY,
            true,
            Shading::Smooth,
            Mirroring::KeepsSides,
        )
        .unwrap();
        assert!((placed.normals.as_ref().unwrap()[0] + Vec3::Z).length() < 1e-6);
        assert!((geometric_normal(&placed) + Vec3::Z).length() < 1e-6);
        let m = DMat4::from_scale(DVec3::new(1.0, 1.0, -1.0));
        let placed = place(
            triangle(false),
            &m,
            true,
            Shading::Flat,
            Mirroring::KeepsSides,
        )
        .unwrap();
        // Mirroring z turns the triangle to face -z; flip_normals turns it back to +z.
        assert!((geometric_normal(&placed) - Vec3::Z).length() < 1e-6);
        assert!(placed.normals.is_none());
    }

    #[test]
    fn missing_normals_are_computed_for_smooth_shading() {
        let placed = place(
            triangle(false),
            &DMat4::IDENTITY,
            false,
            Shading::Smooth,
            Mirroring::KeepsSides,
        )
        .unwrap();
        assert_eq!(placed.normals.unwrap(), vec![Vec3::Z; 3]);
    }

    #[test]
    fn zero_normals_fall_back_to_computed_ones() {
        let mut mesh = triangle(true);
        mesh.normals = Some(vec![Vec3::ZERO, Vec3::Z, Vec3::Z]);
        let placed = place(
            mesh,
            &DMat4::IDENTITY,
            false,
            Shading::Smooth,
            Mirroring::KeepsSides,
        )
        .unwrap();
        assert_eq!(placed.normals.unwrap()[0], Vec3::Z);
    }

    #[test]
    fn overflow_to_infinity_is_an_error() {
        let m = DMat4::from_scale(DVec3::splat(1e39));
        assert!(
            place(
                triangle(false),
                &m,
                false,
                Shading::Flat,
                Mirroring::KeepsSides
            )
            .is_err()
        );
    }
}
