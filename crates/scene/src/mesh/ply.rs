//! A PLY reader for triangle and polygon meshes: ascii, binary_little_endian and
//! binary_big_endian; vertex `x y z`, optional `nx ny nz` and texture coordinates (`u v`, `s t`,
//! `texture_u texture_v` or `texture_s texture_t`); faces as a `vertex_indices` (or
//! `vertex_index`) list, polygons split into triangle fans. Other elements and properties are
//! skipped.
//!
//! The header's element counts are checked against the file size before anything is allocated,
//! so a corrupt or hostile header cannot make the reader allocate more than the file justifies.

use glam::{Vec2, Vec3};

use crate::desc::MeshDesc;

/// Reads the PLY file at `path`.
pub(crate) fn read_ply(path: &std::path::Path) -> Result<MeshDesc, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read file: {e}"))?;
    parse_ply(&bytes)
}

/// Parses PLY data held in memory.
pub(crate) fn parse_ply(bytes: &[u8]) -> Result<MeshDesc, String> {
    let header = parse_header(bytes)?;
    let body = &bytes[header.body_start..];
    check_size(&header, body.len())?;
    let mut reader = match header.format {
        Format::Ascii => Reader::Ascii(AsciiReader::new(body)?),
        Format::BinaryLittleEndian => Reader::Binary {
            data: body,
            pos: 0,
            big_endian: false,
        },
        Format::BinaryBigEndian => Reader::Binary {
            data: body,
            pos: 0,
            big_endian: true,
        },
    };
    let vertex_count = header
        .elements
        .iter()
        .find(|e| e.name == "vertex")
        .map_or(0, |e| e.count);
    if u32::try_from(vertex_count).is_err() {
        return Err(format!("too many vertices ({vertex_count})"));
    }
    for name in ["vertex", "face"] {
        if header.elements.iter().filter(|e| e.name == name).count() > 1 {
            return Err(format!("more than one \"{name}\" element"));
        }
    }
    let mut mesh = MeshDesc::default();
    for element in &header.elements {
        match element.name.as_str() {
            "vertex" => read_vertices(element, &mut reader, &mut mesh)?,
            "face" => read_faces(element, &mut reader, vertex_count, &mut mesh)?,
            _ => skip_element(element, &mut reader)?,
        }
    }
    reader.finish()?;
    Ok(mesh)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Ascii,
    BinaryLittleEndian,
    BinaryBigEndian,
}

/// A PLY scalar type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &str) -> Option<Self> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

#[derive(Debug, Clone)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Debug, Clone)]
struct Property {
    name: String,
    kind: Kind,
}

#[derive(Debug, Clone)]
struct Element {
    name: String,
    count: usize,
    properties: Vec<Property>,
}

impl Element {
    fn scalar_index(&self, name: &str) -> Result<Option<usize>, String> {
        match self.properties.iter().position(|p| p.name == name) {
            None => Ok(None),
            Some(i) => match self.properties[i].kind {
                Kind::Scalar(_) => Ok(Some(i)),
                Kind::List { .. } => Err(format!(
                    "property \"{name}\" of element \"{}\" must be a scalar, not a list",
                    self.name
                )),
            },
        }
    }

    /// Indices of a pair of scalar properties, if both exist.
    fn pair(&self, a: &str, b: &str) -> Result<Option<(usize, usize)>, String> {
        Ok(match (self.scalar_index(a)?, self.scalar_index(b)?) {
            (Some(i), Some(j)) => Some((i, j)),
            _ => None,
        })
    }
}

struct Header {
    format: Format,
    elements: Vec<Element>,
    body_start: usize,
}

/// Longest header accepted, in bytes.
const MAX_HEADER_BYTES: usize = 1 << 20;

fn parse_header(bytes: &[u8]) -> Result<Header, String> {
    let mut pos = 0;
    let mut next_line = || -> Result<(usize, String), String> {
        let rest = &bytes[pos..];
        let end = rest
            .iter()
            .position(|&b| b == b'\n')
            .ok_or("header is not terminated by \"end_header\"")?;
        let line = std::str::from_utf8(&rest[..end])
            .map_err(|_| "header is not ASCII text")?
            .trim_end_matches('\r')
            .to_string();
        pos += end + 1;
        if pos > MAX_HEADER_BYTES {
            return Err("header longer than 1 MiB".to_string());
        }
        Ok((pos, line))
    };
    let (_, magic) = next_line()?;
    if magic.trim() != "ply" {
        return Err("not a PLY file (first line is not \"ply\")".to_string());
    }
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        let (end, line) = next_line()?;
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            [] => {}
            ["end_header"] => {
                let format = format.ok_or("header has no \"format\" line")?;
                return Ok(Header {
                    format,
                    elements,
                    body_start: end,
                });
            }
            ["comment", ..] | ["obj_info", ..] => {}
            ["format", kind, version] => {
                if *version != "1.0" {
                    return Err(format!("unsupported PLY version \"{version}\""));
                }
                format = Some(match *kind {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::BinaryLittleEndian,
                    "binary_big_endian" => Format::BinaryBigEndian,
                    other => return Err(format!("unknown PLY format \"{other}\"")),
                });
            }
            ["element", name, count] => {
                let count = count
                    .parse::<usize>()
                    .map_err(|_| format!("bad element count \"{count}\""))?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    properties: Vec::new(),
                });
            }
            ["property", "list", count, item, name] => {
                let element = elements
                    .last_mut()
                    .ok_or("\"property\" before any \"element\"")?;
                let count = Scalar::parse(count).ok_or(format!("unknown type \"{count}\""))?;
                let item = Scalar::parse(item).ok_or(format!("unknown type \"{item}\""))?;
                if !count.is_integer() {
                    return Err(format!("list \"{name}\" has a non-integer count type"));
                }
                element.properties.push(Property {
                    name: name.to_string(),
                    kind: Kind::List { count, item },
                });
            }
            ["property", ty, name] => {
                let element = elements
                    .last_mut()
                    .ok_or("\"property\" before any \"element\"")?;
                let ty = Scalar::parse(ty).ok_or(format!("unknown type \"{ty}\""))?;
                element.properties.push(Property {
                    name: name.to_string(),
                    kind: Kind::Scalar(ty),
                });
            }
            _ => return Err(format!("unexpected header line \"{line}\"")),
        }
    }
}

/// Rejects headers whose element counts cannot fit in the body (before any allocation).
fn check_size(header: &Header, body_len: usize) -> Result<(), String> {
    let mut minimum: u128 = 0;
    for element in &header.elements {
        if element.properties.is_empty() && element.count > 0 {
            return Err(format!("element \"{}\" has no properties", element.name));
        }
        // Smallest possible encoding of one element: fixed sizes in binary (empty lists),
        // one character plus a separator per value in ascii.
        let per_item: u128 = element
            .properties
            .iter()
            .map(|p| match (header.format, &p.kind) {
                (Format::Ascii, _) => 2,
                (_, Kind::Scalar(s)) => s.size() as u128,
                (_, Kind::List { count, .. }) => count.size() as u128,
            })
            .sum();
        minimum += per_item * element.count as u128;
    }
    let available = body_len as u128 + u128::from(header.format == Format::Ascii);
    if minimum > available {
        return Err(format!(
            "header promises more data than the file holds (at least {minimum} bytes needed, {body_len} present)"
        ));
    }
    Ok(())
}

fn read_vertices(
    element: &Element,
    reader: &mut Reader,
    mesh: &mut MeshDesc,
) -> Result<(), String> {
    let position = (
        element.scalar_index("x")?,
        element.scalar_index("y")?,
        element.scalar_index("z")?,
    );
    let (Some(x), Some(y), Some(z)) = position else {
        return Err("vertex element lacks x, y or z".to_string());
    };
    let normal = match (
        element.scalar_index("nx")?,
        element.scalar_index("ny")?,
        element.scalar_index("nz")?,
    ) {
        (Some(a), Some(b), Some(c)) => Some((a, b, c)),
        _ => None,
    };
    let mut uv = None;
    for (u, v) in [
        ("u", "v"),
        ("s", "t"),
        ("texture_u", "texture_v"),
        ("texture_s", "texture_t"),
    ] {
        if uv.is_none() {
            uv = element.pair(u, v)?;
        }
    }
    // The size check above bounds `count` by the file size, so reserving is safe.
    mesh.positions.reserve(element.count);
    let mut normals = normal.map(|_| Vec::with_capacity(element.count));
    let mut uvs = uv.map(|_| Vec::with_capacity(element.count));
    let mut row = vec![0.0f64; element.properties.len()];
    for index in 0..element.count {
        for (slot, property) in row.iter_mut().zip(&element.properties) {
            *slot = match property.kind {
                Kind::Scalar(s) => reader.read(s)?,
                Kind::List { count, item } => {
                    let n = reader.read_count(count)?;
                    for _ in 0..n {
                        reader.read(item)?;
                    }
                    0.0
                }
            };
        }
        let p = Vec3::new(row[x] as f32, row[y] as f32, row[z] as f32);
        if !p.is_finite() {
            return Err(format!("vertex {index} has a non-finite position"));
        }
        mesh.positions.push(p);
        if let (Some(out), Some((a, b, c))) = (normals.as_mut(), normal) {
            out.push(Vec3::new(row[a] as f32, row[b] as f32, row[c] as f32));
        }
        if let (Some(out), Some((u, v))) = (uvs.as_mut(), uv) {
            out.push(Vec2::new(row[u] as f32, row[v] as f32));
        }
    }
    mesh.normals = normals;
    mesh.uvs = uvs;
    Ok(())
}

fn read_faces(
    element: &Element,
    reader: &mut Reader,
    vertex_count: usize,
    mesh: &mut MeshDesc,
) -> Result<(), String> {
    let list = element
        .properties
        .iter()
        .position(|p| p.name == "vertex_indices" || p.name == "vertex_index")
        .ok_or("face element has no vertex_indices list")?;
    let mut polygon: Vec<u32> = Vec::new();
    for face in 0..element.count {
        for (i, property) in element.properties.iter().enumerate() {
            match property.kind {
                Kind::Scalar(s) if i != list => {
                    reader.read(s)?;
                }
                Kind::Scalar(_) => return Err("vertex_indices must be a list".to_string()),
                Kind::List { count, item } => {
                    let n = reader.read_count(count)?;
                    if i != list {
                        for _ in 0..n {
                            reader.read(item)?;
                        }
                        continue;
                    }
                    if !item.is_integer() {
                        return Err("vertex indices must have an integer type".to_string());
                    }
                    polygon.clear();
                    for _ in 0..n {
                        let v = reader.read(item)?;
                        if v < 0.0 || v >= vertex_count as f64 {
                            return Err(format!(
                                "face {face} uses vertex {v}, but there are only {vertex_count} vertices"
                            ));
                        }
                        polygon.push(v as u32);
                    }
                    if polygon.len() < 3 {
                        return Err(format!("face {face} has fewer than 3 vertices"));
                    }
                    for k in 1..polygon.len() - 1 {
                        mesh.triangles
                            .push([polygon[0], polygon[k], polygon[k + 1]]);
                    }
                }
            }
        }
    }
    Ok(())
}

fn skip_element(element: &Element, reader: &mut Reader) -> Result<(), String> {
    for _ in 0..element.count {
        for property in &element.properties {
            match property.kind {
                Kind::Scalar(s) => {
                    reader.read(s)?;
                }
                Kind::List { count, item } => {
                    let n = reader.read_count(count)?;
                    for _ in 0..n {
                        reader.read(item)?;
                    }
                }
            }
        }
    }
    Ok(())
}

/// Whitespace-separated tokens of an ascii body.
struct AsciiReader<'a> {
    tokens: std::str::SplitAsciiWhitespace<'a>,
}

impl<'a> AsciiReader<'a> {
    fn new(body: &'a [u8]) -> Result<Self, String> {
        let text = std::str::from_utf8(body).map_err(|_| "ascii body is not text")?;
        Ok(Self {
            tokens: text.split_ascii_whitespace(),
        })
    }
}

enum Reader<'a> {
    Ascii(AsciiReader<'a>),
    Binary {
        data: &'a [u8],
        pos: usize,
        big_endian: bool,
    },
}

impl Reader<'_> {
    /// Reads one value of type `ty` as f64 (exact for every PLY integer type).
    fn read(&mut self, ty: Scalar) -> Result<f64, String> {
        match self {
            Reader::Ascii(ascii) => {
                let token = ascii
                    .tokens
                    .next()
                    .ok_or("file ends in the middle of the data")?;
                if ty.is_integer() {
                    let v: i64 = token
                        .parse()
                        .map_err(|_| format!("\"{token}\" is not an integer"))?;
                    Ok(v as f64)
                } else {
                    token
                        .parse::<f64>()
                        .map_err(|_| format!("\"{token}\" is not a number"))
                }
            }
            Reader::Binary {
                data,
                pos,
                big_endian,
            } => {
                let size = ty.size();
                let bytes = data
                    .get(*pos..*pos + size)
                    .ok_or("file ends in the middle of the data")?;
                *pos += size;
                let mut buf = [0u8; 8];
                buf[..size].copy_from_slice(bytes);
                if *big_endian {
                    buf[..size].reverse();
                }
                Ok(match ty {
                    Scalar::I8 => f64::from(buf[0] as i8),
                    Scalar::U8 => f64::from(buf[0]),
                    Scalar::I16 => f64::from(i16::from_le_bytes([buf[0], buf[1]])),
                    Scalar::U16 => f64::from(u16::from_le_bytes([buf[0], buf[1]])),
                    Scalar::I32 => f64::from(i32::from_le_bytes([buf[0], buf[1], buf[2], buf[3]])),
                    Scalar::U32 => f64::from(u32::from_le_bytes([buf[0], buf[1], buf[2], buf[3]])),
                    Scalar::F32 => f64::from(f32::from_le_bytes([buf[0], buf[1], buf[2], buf[3]])),
                    Scalar::F64 => f64::from_le_bytes(buf),
                })
            }
        }
    }

    /// Reads a list length.
    fn read_count(&mut self, ty: Scalar) -> Result<usize, String> {
        let n = self.read(ty)?;
        if n < 0.0 {
            return Err(format!("negative list length {n}"));
        }
        Ok(n as usize)
    }

    /// Fails when data is left over after the last element.
    fn finish(self) -> Result<(), String> {
        let trailing = match self {
            Reader::Ascii(mut ascii) => ascii.tokens.next().is_some(),
            Reader::Binary { data, pos, .. } => pos != data.len(),
        };
        if trailing {
            return Err("unexpected data after the last element".to_string());
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_quad_becomes_two_triangles() {
        let text = "ply\nformat ascii 1.0\ncomment hi\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
        let mesh = parse_ply(text.as_bytes()).unwrap();
        assert_eq!(mesh.positions.len(), 4);
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert!(mesh.normals.is_none() && mesh.uvs.is_none());
    }

    #[test]
    fn huge_counts_are_rejected_before_allocation() {
        let text = "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n\0\0\0\0";
        let err = parse_ply(text.as_bytes()).unwrap_err();
        assert!(err.contains("more data than the file holds"), "{err}");
        let text = "ply\nformat ascii 1.0\nelement vertex 18446744073709551615\nproperty float x\nend_header\n1\n";
        assert!(parse_ply(text.as_bytes()).is_err());
    }

    #[test]
    fn malformed_files_are_errors() {
        for text in [
            "",
            "plx\n",
            "ply\nformat ascii 1.0\n",
            "ply\nformat ascii 2.0\nend_header\n",
            "ply\nformat ascii 1.0\nproperty float x\nend_header\n",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2\n",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3 4\n",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 nan 3\n",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1 0 0 0 1 0\n3 0 1 3\n",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1 0 0 0 1 0\n2 0 1\n",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nproperty float z\nend_header\n1 2\n",
            "ply\nformat ascii 1.0\nelement junk 1000000000000\nend_header\n",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 1 1\n",
        ] {
            assert!(parse_ply(text.as_bytes()).is_err(), "accepted: {text:?}");
        }
    }
}
