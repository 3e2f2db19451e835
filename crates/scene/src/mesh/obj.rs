//! A Wavefront OBJ reader with Mitsuba's semantics: the whole file is one mesh (groups and
//! objects are not split), a vertex is a distinct `v/vt/vn` index triple, polygons are split into
//! triangle fans, and statements other than `v`, `vt`, `vn` and `f` (groups, smoothing groups,
//! materials, lines, points) do not affect the geometry.

use std::collections::HashMap;

use glam::{Vec2, Vec3};

use crate::desc::MeshDesc;

/// Reads the OBJ file at `path`. `flip_tex_coords` replaces v by 1 − v (Mitsuba's default for OBJ).
pub(crate) fn read_obj(path: &std::path::Path, flip_tex_coords: bool) -> Result<MeshDesc, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read file: {e}"))?;
    parse_obj(&bytes, flip_tex_coords)
}

/// Parses OBJ data held in memory. Errors start with `line N:`.
pub(crate) fn parse_obj(bytes: &[u8], flip_tex_coords: bool) -> Result<MeshDesc, String> {
    let text = String::from_utf8_lossy(bytes);
    let mut reader = ObjReader::default();
    for (index, line) in text.lines().enumerate() {
        reader
            .line(line)
            .map_err(|e| format!("line {}: {e}", index + 1))?;
    }
    Ok(reader.finish(flip_tex_coords))
}

/// A face corner: indices into the file's `v`, `vt` and `vn` lists.
type Corner = (u32, Option<u32>, Option<u32>);

#[derive(Default)]
struct ObjReader {
    positions: Vec<Vec3>,
    uvs: Vec<Vec2>,
    normals: Vec<Vec3>,
    /// Mesh vertex of each distinct corner, in order of first use.
    vertex_of: HashMap<Corner, u32>,
    corners: Vec<Corner>,
    triangles: Vec<[u32; 3]>,
}

impl ObjReader {
    fn line(&mut self, line: &str) -> Result<(), String> {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let [x, y, z] = numbers(&mut words, 3, 3)?;
                self.positions.push(Vec3::new(x, y, z));
            }
            Some("vn") => {
                let [x, y, z] = numbers(&mut words, 3, 3)?;
                self.normals.push(Vec3::new(x, y, z));
            }
            Some("vt") => {
                let [u, v, _] = numbers(&mut words, 1, 3)?;
                self.uvs.push(Vec2::new(u, v));
            }
            Some("f") => self.face(words)?,
            _ => {}
        }
        Ok(())
    }

    fn face<'a>(&mut self, words: impl Iterator<Item = &'a str>) -> Result<(), String> {
        let mut polygon = Vec::new();
        for word in words {
            let mut parts = word.split('/');
            let position = parts.next().unwrap_or_default();
            let uv = parts.next().filter(|s| !s.is_empty());
            let normal = parts.next().filter(|s| !s.is_empty());
            if parts.next().is_some() {
                return Err(format!("malformed face corner \"{word}\""));
            }
            let corner = (
                resolve(position, self.positions.len(), "vertex")?,
                uv.map(|s| resolve(s, self.uvs.len(), "texture coordinate"))
                    .transpose()?,
                normal
                    .map(|s| resolve(s, self.normals.len(), "normal"))
                    .transpose()?,
            );
            let next = self.corners.len() as u32;
            let vertex = *self.vertex_of.entry(corner).or_insert(next);
            if vertex == next {
                self.corners.push(corner);
            }
            polygon.push(vertex);
        }
        if polygon.len() < 3 {
            return Err(format!("face with {} vertices", polygon.len()));
        }
        for k in 1..polygon.len() - 1 {
            self.triangles
                .push([polygon[0], polygon[k], polygon[k + 1]]);
        }
        Ok(())
    }

    /// The mesh; normals and uvs are kept only when every vertex has one.
    fn finish(self, flip_tex_coords: bool) -> MeshDesc {
        let all_uvs = self.corners.iter().all(|c| c.1.is_some());
        let all_normals = self.corners.iter().all(|c| c.2.is_some());
        MeshDesc {
            positions: self
                .corners
                .iter()
                .map(|c| self.positions[c.0 as usize])
                .collect(),
            normals: all_normals.then(|| {
                self.corners
                    .iter()
                    .map(|c| self.normals[c.2.unwrap_or_default() as usize])
                    .collect()
            }),
            uvs: all_uvs.then(|| {
                self.corners
                    .iter()
                    .map(|c| {
                        let uv = self.uvs[c.1.unwrap_or_default() as usize];
                        if flip_tex_coords {
                            Vec2::new(uv.x, 1.0 - uv.y)
                        } else {
                            uv
                        }
                    })
                    .collect()
            }),
            triangles: self.triangles,
        }
    }
}

/// Between `min` and `max` finite numbers (missing ones are 0); extra values are ignored.
fn numbers<'a>(
    words: &mut impl Iterator<Item = &'a str>,
    min: usize,
    max: usize,
) -> Result<[f32; 3], String> {
    let mut out = [0.0; 3];
    for (i, slot) in out.iter_mut().enumerate().take(max) {
        match words.next() {
            Some(word) => {
                *slot = word
                    .parse::<f32>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| format!("\"{word}\" is not a finite number"))?;
            }
            None if i < min => return Err(format!("expected at least {min} numbers")),
            None => break,
        }
    }
    Ok(out)
}

/// A 1-based (or negative, counting back from the end) OBJ index into a list of `count` items.
fn resolve(text: &str, count: usize, what: &str) -> Result<u32, String> {
    let index: i64 = text
        .parse()
        .map_err(|_| format!("bad {what} index \"{text}\""))?;
    let resolved = if index < 0 {
        count as i64 + index
    } else {
        index - 1
    };
    if index == 0 || resolved < 0 || resolved >= count as i64 {
        return Err(format!(
            "{what} index {index} is out of range (there are {count} so far)"
        ));
    }
    u32::try_from(resolved).map_err(|_| format!("{what} index {index} is too large"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quad_with_uvs_and_normals() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";
        let mesh = parse_obj(text.as_bytes(), true).unwrap();
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.normals.as_ref().unwrap(), &vec![Vec3::Z; 4]);
        // flip_tex_coords: vt 0 0 becomes (0, 1).
        assert_eq!(mesh.uvs.as_ref().unwrap()[0], Vec2::new(0.0, 1.0));
    }

    #[test]
    fn groups_share_vertices_and_negative_indices_count_back() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\ng a\nf 1 2 3\ng b\nv 0 0 1\nf -4 -2 -1\n";
        let mesh = parse_obj(text.as_bytes(), true).unwrap();
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(mesh.positions[3], Vec3::Z);
    }

    #[test]
    fn distinct_index_triples_are_distinct_vertices() {
        let text =
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 -1\nf 1//1 2//1 3//1\nf 1//2 3//2 2//2\n";
        let mesh = parse_obj(text.as_bytes(), true).unwrap();
        assert_eq!(mesh.positions.len(), 6);
    }

    #[test]
    fn partial_normals_or_uvs_are_dropped() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1\nf 1 2 3\n";
        let mesh = parse_obj(text.as_bytes(), true).unwrap();
        assert_eq!(mesh.triangles.len(), 2);
        assert!(mesh.normals.is_none());
        assert!(mesh.uvs.is_none());
    }

    #[test]
    fn errors_name_the_line() {
        for (text, line) in [
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 x 0\nf 1 2 3\n", 4),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9", 4),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2", 5),
            ("f 0 0 0\n", 1),
            ("v 0 0 0\nf -5 1 1\n", 2),
            ("v 1 2\n", 1),
            ("v 0 0 inf\n", 1),
            ("v 0 0 0\nf 1/1 1/1 1/1\n", 2),
            ("v 0 0 0\nf 1/1/1/1 1 1\n", 2),
        ] {
            let err = parse_obj(text.as_bytes(), true).unwrap_err();
            assert!(err.starts_with(&format!("line {line}:")), "{text:?}: {err}");
        }
    }

    #[test]
    fn other_statements_are_ignored() {
        let text = "# c\nmtllib a.mtl\no x\ns 1\nusemtl m\nv 0 0 0 1\nv 1 0 0\nv 0 1 0\nl 1 2\np 1\nf 1 2 3\n";
        let mesh = parse_obj(text.as_bytes(), true).unwrap();
        assert_eq!(mesh.triangles.len(), 1);
    }
}
