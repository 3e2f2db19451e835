//! Wavefront OBJ loading through `tobj`: all groups merged into one mesh, polygons split into
//! triangle fans, materials (`mtllib`, `usemtl`) ignored as Mitsuba ignores them.

use std::io::{BufRead, Read};

use glam::{Vec2, Vec3};

use crate::desc::MeshDesc;

/// Reads the OBJ file at `path`. `flip_tex_coords` replaces v by 1 − v (Mitsuba's default for OBJ).
pub(crate) fn read_obj(path: &std::path::Path, flip_tex_coords: bool) -> Result<MeshDesc, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read file: {e}"))?;
    parse_obj(&bytes, flip_tex_coords)
}

/// Parses OBJ data held in memory.
pub(crate) fn parse_obj(bytes: &[u8], flip_tex_coords: bool) -> Result<MeshDesc, String> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = LineCountingReader {
        rest: bytes,
        newlines: 0,
        ends_with_newline: true,
    };
    // tobj is third-party code fed with arbitrary files: a panic inside it becomes an error.
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        tobj::load_obj_buf(&mut reader, &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
    }));
    let models = match result {
        Ok(Ok((models, _materials))) => models,
        Ok(Err(e)) => return Err(format!("line {}: {e}", reader.current_line())),
        Err(_) => {
            return Err(format!(
                "line {}: the OBJ parser failed",
                reader.current_line()
            ));
        }
    };
    merge(models, flip_tex_coords)
}

/// Concatenates the models of an OBJ file. Normals and uvs are kept only if every model has one
/// per vertex; otherwise normals are left to be computed and uvs dropped.
fn merge(models: Vec<tobj::Model>, flip_tex_coords: bool) -> Result<MeshDesc, String> {
    let total: usize = models.iter().map(|m| m.mesh.positions.len() / 3).sum();
    if u32::try_from(total).is_err() {
        return Err(format!("too many vertices ({total})"));
    }
    let all_have = |len: fn(&tobj::Mesh) -> usize, dim: usize| {
        models
            .iter()
            .all(|m| len(&m.mesh) == m.mesh.positions.len() / 3 * dim)
    };
    let has_normals = all_have(|m| m.normals.len(), 3);
    let has_uvs = all_have(|m| m.texcoords.len(), 2);
    let mut mesh = MeshDesc {
        normals: has_normals.then(Vec::new),
        uvs: has_uvs.then(Vec::new),
        ..Default::default()
    };
    for model in models {
        let m = model.mesh;
        let base = mesh.positions.len() as u32;
        let count = m.positions.len() / 3;
        mesh.positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        if let Some(normals) = mesh.normals.as_mut() {
            normals.extend(
                m.normals
                    .chunks_exact(3)
                    .map(|n| Vec3::new(n[0], n[1], n[2])),
            );
        }
        if let Some(uvs) = mesh.uvs.as_mut() {
            uvs.extend(
                m.texcoords
                    .chunks_exact(2)
                    .map(|t| Vec2::new(t[0], if flip_tex_coords { 1.0 - t[1] } else { t[1] })),
            );
        }
        for tri in m.indices.chunks_exact(3) {
            if tri.iter().any(|&i| i as usize >= count) {
                return Err(format!(
                    "a face refers to vertex {} of a group with {count} vertices",
                    tri.iter().max().copied().unwrap_or_default()
                ));
            }
            mesh.triangles
                .push([base + tri[0], base + tri[1], base + tri[2]]);
        }
    }
    if let Some(bad) = mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(format!("vertex {} has a non-finite position", bad + 1));
    }
    Ok(mesh)
}

/// A `BufRead` over a byte slice that counts the lines handed out, so that parse errors can
/// name a line.
struct LineCountingReader<'a> {
    rest: &'a [u8],
    newlines: usize,
    ends_with_newline: bool,
}

impl LineCountingReader<'_> {
    /// 1-based number of the line read last.
    fn current_line(&self) -> usize {
        self.newlines + usize::from(!self.ends_with_newline)
    }
}

impl Read for LineCountingReader<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = buf.len().min(self.rest.len());
        buf[..n].copy_from_slice(&self.rest[..n]);
        self.consume(n);
        Ok(n)
    }
}

impl BufRead for LineCountingReader<'_> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        Ok(self.rest)
    }

    fn consume(&mut self, amount: usize) {
        let (used, rest) = self.rest.split_at(amount.min(self.rest.len()));
        if let Some(&last) = used.last() {
            self.newlines += used.iter().filter(|&&b| b == b'\n').count();
            self.ends_with_newline = last == b'\n';
        }
        self.rest = rest;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quad_with_uvs_and_normals() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";
        let mesh = parse_obj(text.as_bytes(), true).unwrap();
        assert_eq!(mesh.triangles.len(), 2);
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.normals.as_ref().unwrap().len(), 4);
        let uvs = mesh.uvs.as_ref().unwrap();
        // flip_tex_coords: the vertex with vt 0 0 gets v = 1.
        let i = mesh
            .positions
            .iter()
            .position(|p| *p == Vec3::ZERO)
            .unwrap();
        assert_eq!(uvs[i], Vec2::new(0.0, 1.0));
        for tri in &mesh.triangles {
            let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
            assert!((b - a).cross(c - a).z > 0.0);
        }
    }

    #[test]
    fn groups_are_merged_with_offsets() {
        let text =
            "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no b\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 4 5 6\n";
        let mesh = parse_obj(text.as_bytes(), true).unwrap();
        assert_eq!(mesh.triangles.len(), 2);
        let second = mesh.triangles[1].map(|i| mesh.positions[i as usize]);
        assert!(second.iter().all(|p| p.z == 1.0));
    }

    #[test]
    fn errors_name_the_line() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 x 0\nf 1 2 3\n";
        let err = parse_obj(text.as_bytes(), true).unwrap_err();
        assert!(err.starts_with("line 4:"), "{err}");
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9";
        let err = parse_obj(text.as_bytes(), true).unwrap_err();
        assert!(err.starts_with("line 4:"), "{err}");
    }

    #[test]
    fn malformed_input_is_an_error() {
        for text in [
            "f 0 0 0\n",
            "f -5 1 2\n",
            "v 1 2\nf 1 1 1\n",
            "f\n",
            "vt\nvn\nv\n",
        ] {
            let result = parse_obj(text.as_bytes(), true);
            assert!(result.is_err(), "accepted {text:?}: {result:?}");
        }
    }

    #[test]
    fn partial_normals_are_dropped_for_recomputation() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 2 3\n";
        let mesh = parse_obj(text.as_bytes(), true).unwrap();
        assert_eq!(mesh.triangles.len(), 2);
        assert!(mesh.normals.is_none());
    }
}
