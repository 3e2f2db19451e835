//! Mitsuba's `.serialized` meshes: a little-endian header (format 0x041C, version 3 or 4), then
//! one zlib stream per mesh holding its flags, (version 4) its name, vertex and triangle counts,
//! positions, optional normals, texture coordinates and colours (single or double precision)
//! and 32-bit triangle indices; several meshes are concatenated, and the file ends with each
//! mesh's byte offset (64-bit in version 4, 32-bit in version 3) and their count (32-bit).
//! Colours are skipped, as Mitsuba skips them.
//!
//! Counts are checked against the decompressed data before anything is allocated for them.

use glam::{Vec2, Vec3};

use crate::desc::MeshDesc;

/// The format identifier every mesh's header starts with.
const FORMAT_ID: u16 = 0x041C;
/// Flag: per-vertex normals follow the positions.
const HAS_NORMALS: u32 = 0x0001;
/// Flag: texture coordinates follow.
const HAS_TEXCOORDS: u32 = 0x0002;
/// Flag: vertex colours follow.
const HAS_COLORS: u32 = 0x0008;
/// Flag: vertex data is in double precision (single otherwise).
const DOUBLE_PRECISION: u32 = 0x2000;

/// Reads mesh number `shape_index` (Mitsuba's `shape_index`, from 0) of the file at `path`.
pub(crate) fn read_serialized(
    path: &std::path::Path,
    shape_index: u32,
) -> Result<MeshDesc, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read file: {e}"))?;
    parse_serialized(&bytes, shape_index)
}

/// Parses mesh number `shape_index` of serialized data held in memory.
pub(crate) fn parse_serialized(bytes: &[u8], shape_index: u32) -> Result<MeshDesc, String> {
    let version = header_version(bytes, 0)?;
    let start = if shape_index == 0 {
        0
    } else {
        mesh_offset(bytes, version, shape_index)?
    };
    header_version(bytes, start)?;
    let data = miniz_oxide::inflate::decompress_to_vec_zlib(&bytes[start + 4..])
        .map_err(|e| format!("mesh {shape_index}: corrupt compressed data ({e:?})"))?;
    parse_mesh(&data, version).map_err(|e| format!("mesh {shape_index}: {e}"))
}

/// The version of the header at byte `at`, after checking its format identifier.
fn header_version(bytes: &[u8], at: usize) -> Result<u16, String> {
    let word = |i: usize| {
        bytes
            .get(i..i + 2)
            .map(|b| u16::from_le_bytes([b[0], b[1]]))
            .ok_or("the file ends inside a mesh header")
    };
    if word(at)? != FORMAT_ID {
        return Err(format!(
            "no serialized mesh header at byte {at} (format identifier 0x{:04X}, expected 0x{FORMAT_ID:04X})",
            word(at)?
        ));
    }
    match word(at + 2)? {
        version @ (3 | 4) => Ok(version),
        other => Err(format!("unsupported version {other} (supported: 3, 4)")),
    }
}

/// The byte offset of mesh `shape_index` from the dictionary at the end of the file.
fn mesh_offset(bytes: &[u8], version: u16, shape_index: u32) -> Result<usize, String> {
    let n = bytes.len();
    let count = n
        .checked_sub(4)
        .map(|at| u32::from_le_bytes(bytes[at..].try_into().expect("4 bytes")))
        .ok_or("the file is too short for its mesh dictionary")?;
    if shape_index >= count {
        return Err(format!(
            "shape_index {shape_index} is out of range: the file holds {count} mesh(es)"
        ));
    }
    let entry = if version == 4 { 8 } else { 4 };
    let from_end = entry * (count - shape_index) as usize + 4;
    let at = n
        .checked_sub(from_end)
        .ok_or("the file is too short for its mesh dictionary")?;
    let offset = if version == 4 {
        u64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes"))
    } else {
        u64::from(u32::from_le_bytes(
            bytes[at..at + 4].try_into().expect("4 bytes"),
        ))
    };
    usize::try_from(offset)
        .ok()
        .filter(|&o| o < n)
        .ok_or_else(|| format!("mesh {shape_index}'s offset {offset} lies outside the file"))
}

/// One decompressed mesh stream.
fn parse_mesh(data: &[u8], version: u16) -> Result<MeshDesc, String> {
    let mut cursor = Cursor { data, pos: 0 };
    let flags = u32::from_le_bytes(cursor.take(4)?.try_into().expect("4 bytes"));
    if version == 4 {
        let name_length = data[cursor.pos..]
            .iter()
            .position(|&b| b == 0)
            .ok_or("the mesh name is not terminated")?;
        cursor.take(name_length + 1)?;
    }
    let vertex_count = cursor.u64()?;
    let triangle_count = cursor.u64()?;
    let real = if flags & DOUBLE_PRECISION != 0 { 8 } else { 4 };
    let per_vertex = real
        * (3 + 3 * u64::from(flags & HAS_NORMALS != 0)
            + 2 * u64::from(flags & HAS_TEXCOORDS != 0)
            + 3 * u64::from(flags & HAS_COLORS != 0));
    let needed = vertex_count
        .checked_mul(per_vertex)
        .zip(triangle_count.checked_mul(12))
        .and_then(|(v, t)| v.checked_add(t));
    if needed.is_none_or(|needed| needed > (data.len() - cursor.pos) as u64) {
        return Err(format!(
            "{vertex_count} vertices and {triangle_count} triangles do not fit the {} bytes of data",
            data.len()
        ));
    }
    let (vertex_count, triangle_count) = (vertex_count as usize, triangle_count as usize);
    let mut reals = |dim: usize| -> Result<Vec<f32>, String> {
        let bytes = cursor.take(vertex_count * dim * real as usize)?;
        Ok(if real == 8 {
            bytes
                .chunks_exact(8)
                .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")) as f32)
                .collect()
        } else {
            bytes
                .chunks_exact(4)
                .map(|b| f32::from_le_bytes(b.try_into().expect("4 bytes")))
                .collect()
        })
    };
    let vec3s = |v: Vec<f32>| -> Vec<Vec3> { v.chunks_exact(3).map(Vec3::from_slice).collect() };
    let positions = vec3s(reals(3)?);
    let normals = (flags & HAS_NORMALS != 0)
        .then(|| reals(3).map(vec3s))
        .transpose()?;
    let uvs = (flags & HAS_TEXCOORDS != 0)
        .then(|| reals(2).map(|v| v.chunks_exact(2).map(Vec2::from_slice).collect()))
        .transpose()?;
    if flags & HAS_COLORS != 0 {
        reals(3)?;
    }
    if let Some(p) = positions.iter().find(|p| !p.is_finite()) {
        return Err(format!("vertex position {p} is not finite"));
    }
    let triangles = cursor
        .take(triangle_count * 12)?
        .chunks_exact(12)
        .map(|b| {
            let index = |k: usize| u32::from_le_bytes(b[4 * k..4 * k + 4].try_into().expect("4"));
            [index(0), index(1), index(2)]
        })
        .collect::<Vec<_>>();
    if let Some(t) = triangles
        .iter()
        .find(|t| t.iter().any(|&i| i as usize >= vertex_count))
    {
        return Err(format!(
            "triangle {t:?} indexes past the {vertex_count} vertices"
        ));
    }
    Ok(MeshDesc {
        positions,
        normals,
        uvs,
        triangles,
    })
}

/// Reads the decompressed stream front to back.
struct Cursor<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Cursor<'a> {
    /// The next `n` bytes, or an error when the data ends first.
    fn take(&mut self, n: usize) -> Result<&'a [u8], String> {
        let bytes = self
            .data
            .get(self.pos..self.pos + n)
            .ok_or("the mesh data ends early")?;
        self.pos += n;
        Ok(bytes)
    }

    /// The next little-endian 64-bit integer.
    fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_le_bytes(
            self.take(8)?.try_into().expect("8 bytes"),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One mesh stream as Mitsuba writes it (before compression).
    fn stream(
        flags: u32,
        name: &str,
        positions: &[[f64; 3]],
        extra: &[f64],
        tris: &[[u32; 3]],
    ) -> Vec<u8> {
        let mut out = flags.to_le_bytes().to_vec();
        out.extend(name.as_bytes());
        out.push(0);
        out.extend((positions.len() as u64).to_le_bytes());
        out.extend((tris.len() as u64).to_le_bytes());
        let double = flags & DOUBLE_PRECISION != 0;
        for &x in positions.iter().flatten().chain(extra) {
            if double {
                out.extend(x.to_le_bytes());
            } else {
                out.extend((x as f32).to_le_bytes());
            }
        }
        for i in tris.iter().flatten() {
            out.extend(i.to_le_bytes());
        }
        out
    }

    /// A file of `meshes` (streams) in `version`, with its dictionary.
    fn file(version: u16, meshes: &[Vec<u8>]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut offsets = Vec::new();
        for mesh in meshes {
            offsets.push(out.len() as u64);
            out.extend(FORMAT_ID.to_le_bytes());
            out.extend(version.to_le_bytes());
            out.extend(miniz_oxide::deflate::compress_to_vec_zlib(mesh, 6));
        }
        for offset in &offsets {
            if version == 4 {
                out.extend(offset.to_le_bytes());
            } else {
                out.extend((*offset as u32).to_le_bytes());
            }
        }
        out.extend((meshes.len() as u32).to_le_bytes());
        out
    }

    const TRIANGLE: [[f64; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

    #[test]
    fn reads_normals_and_texture_coordinates_in_single_precision() {
        let normals_and_uvs = [
            0.0, 0.0, 1.0, 0.0, 0.6, 0.8, 0.0, 0.0, 1.0, 0.5, 0.25, 1.0, 0.0, 0.0, 1.0,
        ];
        let data = file(
            4,
            &[stream(
                HAS_NORMALS | HAS_TEXCOORDS | 0x1000,
                "tri",
                &TRIANGLE,
                &normals_and_uvs,
                &[[0, 1, 2]],
            )],
        );
        let mesh = parse_serialized(&data, 0).unwrap();
        assert_eq!(mesh.positions, vec![Vec3::ZERO, Vec3::X, Vec3::Y]);
        assert_eq!(mesh.normals.unwrap()[1], Vec3::new(0.0, 0.6, 0.8));
        assert_eq!(
            mesh.uvs.unwrap(),
            vec![
                Vec2::new(0.5, 0.25),
                Vec2::new(1.0, 0.0),
                Vec2::new(0.0, 1.0)
            ]
        );
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn finds_later_meshes_through_the_dictionary_in_both_versions() {
        let colours = [1.0; 9];
        let second = [[2.0, 0.0, 0.0], [3.0, 0.0, 0.0], [2.0, 5.0, 0.0]];
        for version in [3, 4] {
            let name = if version == 4 { "second" } else { "" };
            let mut first = stream(0x1000, "", &TRIANGLE, &[], &[[0, 1, 2]]);
            if version == 3 {
                first.remove(4);
            }
            let mut other = stream(
                HAS_COLORS | DOUBLE_PRECISION,
                name,
                &second,
                &colours,
                &[[2, 1, 0]],
            );
            if version == 3 {
                other.remove(4);
            }
            let data = file(version, &[first, other]);
            let mesh = parse_serialized(&data, 1).unwrap();
            assert_eq!(
                mesh.positions[2],
                Vec3::new(2.0, 5.0, 0.0),
                "version {version}"
            );
            assert_eq!(mesh.triangles, vec![[2, 1, 0]]);
            assert!(mesh.normals.is_none() && mesh.uvs.is_none());
            assert_eq!(parse_serialized(&data, 0).unwrap().positions[1], Vec3::X);
            let err = parse_serialized(&data, 2).unwrap_err();
            assert!(err.contains("holds 2 mesh(es)"), "{err}");
        }
    }

    #[test]
    fn bad_files_are_errors() {
        let fails_with = |bytes: &[u8], expected: &str| {
            let err = parse_serialized(bytes, 0).unwrap_err();
            assert!(err.contains(expected), "{err} (expected {expected:?})");
        };
        let good = file(4, &[stream(0x1000, "", &TRIANGLE, &[], &[[0, 1, 2]])]);
        let mut wrong_id = good.clone();
        wrong_id[0] = 0;
        fails_with(&wrong_id, "format identifier");
        let mut wrong_version = good.clone();
        wrong_version[2] = 9;
        fails_with(&wrong_version, "version 9");
        fails_with(&good[..good.len() - 20], "corrupt");
        let past_end = file(4, &[stream(0x1000, "", &TRIANGLE, &[], &[[0, 1, 3]])]);
        fails_with(&past_end, "indexes past");
        let mut huge = stream(0x1000, "", &TRIANGLE, &[], &[[0, 1, 2]]);
        huge[5..13].copy_from_slice(&u64::MAX.to_le_bytes());
        fails_with(&file(4, &[huge]), "do not fit");
    }
}
