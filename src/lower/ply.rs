//! PLY meshes (ASCII, binary little and big endian): our own reader, as the
//! format is small and we want exact control over its errors and memory.
//! Vertices with optional normals, texture coordinates (under the names
//! exporters use) and colours; faces of three or more vertices, fanned
//! into triangles.

use super::mesh_data::MeshData;
use glam::{Vec2, Vec3};

/// The most vertices one face may list.
const MAX_FACE_VERTICES: f64 = 1024.0;

/// Parses a PLY file from memory.
pub fn parse_ply(bytes: &[u8]) -> Result<MeshData, String> {
    let (format, elements, start) = header(bytes)?;
    let data = &bytes[start..];
    let ascii_text;
    let mut r = Reader {
        data,
        pos: 0,
        format,
        tokens: None,
    };
    if format == Format::Ascii {
        ascii_text = std::str::from_utf8(data).map_err(|_| "the ASCII PLY data is not text")?;
        r.tokens = Some(ascii_text.split_ascii_whitespace());
    }
    let mut out = MeshData::default();
    for el in &elements {
        // Guard against absurd counts before allocating: an entry takes at
        // least its scalars' bytes (binary) or two bytes per value (ASCII:
        // a digit and a blank).
        let least: usize = (el.props.iter())
            .map(|p| match (format, p) {
                (Format::Ascii, _) => 2,
                (_, Prop::Scalar(_, t)) | (_, Prop::List(_, t, _)) => t.size(),
            })
            .sum();
        if el.count.saturating_mul(least) > data.len() {
            return Err(format!(
                "element `{}` claims {} entries, more than the file holds",
                el.name, el.count
            ));
        }
        if !el.props.is_empty() {
            read_element(el, &mut r, &mut out)?;
        }
    }
    Ok(out)
}

/// The header's format, its elements, and where the data starts.
fn header(bytes: &[u8]) -> Result<(Format, Vec<Element>, usize), String> {
    let header_end = (bytes.windows(10))
        .position(|w| w == b"end_header")
        .ok_or("not a PLY file: no `end_header`")?;
    // A `comment` or `obj_info` line in Latin-1 does not make the file
    // unreadable: the words ptsc reads are ASCII.
    let header = String::from_utf8_lossy(&bytes[..header_end]);
    let mut lines = header.lines();
    if lines.next().map(str::trim) != Some("ply") {
        return Err("not a PLY file: it does not start with `ply`".into());
    }
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    for line in lines {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.as_slice() {
            ["format", f, _] => {
                format = Some(match *f {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::Le,
                    "binary_big_endian" => Format::Be,
                    other => return Err(format!("unknown PLY format `{other}`")),
                })
            }
            ["element", "vertex", _] if elements.iter().any(|e| e.name == "vertex") => {
                return Err("the PLY header declares `element vertex` twice".into());
            }
            ["element", name, count] => elements.push(Element {
                name: name.to_string(),
                count: (count.parse()).map_err(|_| format!("bad element count `{count}`"))?,
                props: Vec::new(),
            }),
            ["property", "list", c, t, name] => {
                let c = Scalar::parse(c).ok_or("bad PLY list type")?;
                let t = Scalar::parse(t).ok_or("bad PLY list type")?;
                let el = elements.last_mut().ok_or("property before element")?;
                el.props.push(Prop::List(name.to_string(), c, t));
            }
            ["property", t, name] => {
                let t = Scalar::parse(t).ok_or_else(|| format!("unknown PLY type `{t}`"))?;
                let el = elements.last_mut().ok_or("property before element")?;
                el.props.push(Prop::Scalar(name.to_string(), t));
            }
            _ => {}
        }
    }
    let format = format.ok_or("the PLY header has no `format` line")?;
    // Data starts after the newline that ends `end_header`.
    let mut start = header_end + 10;
    while start < bytes.len() && (bytes[start] == b'\r' || bytes[start] == b'\n') {
        start += 1;
        if bytes[start - 1] == b'\n' {
            break;
        }
    }
    Ok((format, elements, start))
}

/// Where a vertex element keeps what ptsc reads: the indices of its
/// properties.
struct VertexColumns {
    position: [usize; 3],
    normal: Option<[usize; 3]>,
    uv: Option<[usize; 2]>,
    color: Option<[usize; 3]>,
}

impl VertexColumns {
    /// The columns of `el`, a vertex element.
    fn of(el: &Element) -> Result<VertexColumns, String> {
        let idx =
            |n: &str| (el.props.iter()).position(|p| matches!(p, Prop::Scalar(s, _) if s == n));
        let three = |[a, b, c]: [&str; 3]| Some([idx(a)?, idx(b)?, idx(c)?]);
        let position = three(["x", "y", "z"]).ok_or("the PLY vertices have no x, y, z")?;
        // Texture coordinates go by several names in the wild.
        let uv = [
            ("u", "v"),
            ("s", "t"),
            ("texture_u", "texture_v"),
            ("texture_s", "texture_t"),
        ]
        .iter()
        .find_map(|(u, v)| Some([idx(u)?, idx(v)?]));
        // Colours, by the names exporters use (Blender, MeshLab: `red`).
        let color = [["red", "green", "blue"], ["r", "g", "b"]]
            .into_iter()
            .find_map(three);
        Ok(VertexColumns {
            position,
            normal: three(["nx", "ny", "nz"]),
            uv,
            color,
        })
    }

    /// Adds the vertex whose values are `vals` (of `el`'s properties).
    fn push(&self, el: &Element, vals: &[f64], out: &mut MeshData) {
        let v3 = |[a, b, c]: [usize; 3]| Vec3::new(vals[a] as f32, vals[b] as f32, vals[c] as f32);
        out.positions.push(v3(self.position));
        if let Some(n) = self.normal {
            out.normals.push(v3(n));
        }
        if let Some([u, v]) = self.uv {
            out.uvs.push(Vec2::new(vals[u] as f32, vals[v] as f32));
        }
        if let Some(channels) = self.color {
            let color = channels.map(|k| match &el.props[k] {
                Prop::Scalar(_, t) => vertex_color(vals[k], *t),
                Prop::List(..) => 1.0,
            });
            out.colors.push(Vec3::from_array(color));
        }
    }
}

/// Reads the `el.count` entries of `el`: vertices and faces go to `out`,
/// other elements are read past.
fn read_element(el: &Element, r: &mut Reader, out: &mut MeshData) -> Result<(), String> {
    let vertex = match el.name == "vertex" {
        true => Some(VertexColumns::of(el)?),
        false => None,
    };
    if let Some(v) = &vertex {
        out.positions.reserve(el.count);
        if v.uv.is_some() {
            out.uvs.reserve(el.count);
        }
    }
    let is_face = el.name == "face";
    if is_face {
        out.triangles.reserve(el.count);
    }
    // Which of its lists are a face's vertices: decided once, not per face.
    let corners: Vec<bool> = (el.props.iter())
        .map(|p| {
            is_face
                && matches!(p, Prop::List(n, ..) if n == "vertex_indices" || n == "vertex_index")
        })
        .collect();
    let mut vals = vec![0.0f64; el.props.len()];
    let mut list: Vec<u32> = Vec::new();
    for entry in 0..el.count {
        for (k, p) in el.props.iter().enumerate() {
            match p {
                Prop::Scalar(_, t) => vals[k] = r.read(*t)?,
                Prop::List(_, c, t) => {
                    read_list(r, (*c, *t), &mut list)?;
                    if corners[k] {
                        fan(entry, &list, out)?;
                    }
                }
            }
        }
        if let Some(v) = &vertex {
            v.push(el, &vals, out);
        }
    }
    Ok(())
}

/// Reads a list of (`count`, `item`) types into `list`, as vertex indices.
fn read_list(
    r: &mut Reader,
    (count, item): (Scalar, Scalar),
    list: &mut Vec<u32>,
) -> Result<(), String> {
    let n = r.read(count)?;
    if n.fract() != 0.0 {
        return Err(format!("a list has {n} entries, not a whole number"));
    }
    if !(0.0..=MAX_FACE_VERTICES).contains(&n) {
        return Err(format!("a face has {n} vertices"));
    }
    list.clear();
    for _ in 0..n as usize {
        list.push(index(r.read(item)?)?);
    }
    Ok(())
}

/// Adds face `entry` (its vertex indices `list`) as a fan of triangles. A
/// face of fewer than three vertices is an error, as in an OBJ file: it
/// would render as nothing, and a file of them is not a surface.
fn fan(entry: usize, list: &[u32], out: &mut MeshData) -> Result<(), String> {
    if list.len() < 3 {
        let has = crate::diag::count(list.len() as u64, "vertex", "vertices");
        return Err(format!(
            "face {entry} (counted from 0) has {has} (a face needs at least 3)"
        ));
    }
    for j in 1..list.len() - 1 {
        out.triangles.push([list[0], list[j], list[j + 1]]);
    }
    Ok(())
}

#[derive(Clone, Copy, PartialEq)]
enum Format {
    Ascii,
    Le,
    Be,
}

#[derive(Clone, Copy, PartialEq, Debug)]
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
    fn parse(s: &str) -> Option<Scalar> {
        Some(match s {
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
}

enum Prop {
    Scalar(String, Scalar),
    List(String, Scalar, Scalar),
}

struct Element {
    name: String,
    count: usize,
    props: Vec<Prop>,
}

/// Reads values of one element from binary or ASCII data.
struct Reader<'a> {
    data: &'a [u8],
    pos: usize,
    format: Format,
    tokens: Option<std::str::SplitAsciiWhitespace<'a>>,
}

impl Reader<'_> {
    fn read(&mut self, t: Scalar) -> Result<f64, String> {
        if self.format == Format::Ascii {
            let tok = self
                .tokens
                .as_mut()
                .unwrap()
                .next()
                .ok_or("the PLY data ends early")?;
            return tok
                .parse::<f64>()
                .map_err(|_| format!("`{tok}` is not a number"));
        }
        let n = t.size();
        let b = self
            .data
            .get(self.pos..self.pos + n)
            .ok_or("the PLY data ends early")?;
        self.pos += n;
        let mut a = [0u8; 8];
        a[..n].copy_from_slice(b);
        if self.format == Format::Be {
            a[..n].reverse();
        }
        Ok(match t {
            Scalar::I8 => a[0] as i8 as f64,
            Scalar::U8 => a[0] as f64,
            Scalar::I16 => i16::from_le_bytes([a[0], a[1]]) as f64,
            Scalar::U16 => u16::from_le_bytes([a[0], a[1]]) as f64,
            Scalar::I32 => i32::from_le_bytes([a[0], a[1], a[2], a[3]]) as f64,
            Scalar::U32 => u32::from_le_bytes([a[0], a[1], a[2], a[3]]) as f64,
            Scalar::F32 => f32::from_le_bytes([a[0], a[1], a[2], a[3]]) as f64,
            Scalar::F64 => f64::from_le_bytes(a),
        })
    }
}

/// A vertex index read from a PLY list: a whole number in `0..2^32`.
fn index(x: f64) -> Result<u32, String> {
    if x < 0.0 {
        Err(format!(
            "a face refers to vertex {x}: indices are not negative"
        ))
    } else if x.fract() != 0.0 || x > u32::MAX as f64 {
        Err(format!(
            "a face refers to vertex {x}: indices are whole numbers below 2^32"
        ))
    } else {
        Ok(x as u32)
    }
}

/// A PLY vertex colour channel as linear [0, 1]: whole numbers (`uchar`, as
/// exporters write them) are the 8- or 16-bit sRGB a viewer shows, decoded;
/// floating-point ones are taken as linear already.
fn vertex_color(value: f64, t: Scalar) -> f32 {
    let most = match t {
        Scalar::F32 | Scalar::F64 => return value.clamp(0.0, 1.0) as f32,
        Scalar::U16 | Scalar::I16 => 65535.0,
        Scalar::U32 | Scalar::I32 => u32::MAX as f64,
        Scalar::U8 | Scalar::I8 => 255.0,
    };
    crate::texture::image::srgb_to_linear((value / most).clamp(0.0, 1.0) as f32)
}

/// A quad of four vertices in ASCII, for the tests here and in `mesh.rs`.
#[cfg(test)]
pub(super) const ASCII: &str = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn ascii_quad_becomes_two_triangles() {
        let m = parse_ply(ASCII.as_bytes()).unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn binary_both_endians() {
        for (fmt, be) in [("binary_little_endian", false), ("binary_big_endian", true)] {
            let mut b = format!("ply\nformat {fmt} 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n").into_bytes();
            for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
                b.extend(if be { v.to_be_bytes() } else { v.to_le_bytes() });
            }
            b.push(3);
            for i in [0i32, 1, 2] {
                b.extend(if be { i.to_be_bytes() } else { i.to_le_bytes() });
            }
            let m = parse_ply(&b).unwrap();
            assert_eq!(m.positions[1], Vec3::X);
            assert_eq!(m.triangles, vec![[0, 1, 2]]);
        }
    }

    #[test]
    fn broken_ply_is_an_error_not_a_panic() {
        assert!(parse_ply(b"garbage").is_err());
        assert!(parse_ply(&ASCII.as_bytes()[..ASCII.len() - 6]).is_err());
        let huge = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        assert!(parse_ply(huge.as_bytes()).is_err());
        // ASCII counts are bounded by the data too (a reservation of 6 GB
        // before reading a byte of it).
        let huge = "ply\nformat ascii 1.0\nelement vertex 400000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n";
        assert!(parse_ply(huge.as_bytes())
            .unwrap_err()
            .contains("more than the file holds"));
        let empty_elements = "ply\nformat ascii 1.0\nelement nothing 4000000000\nend_header\n";
        assert!(parse_ply(empty_elements.as_bytes()).is_ok());
    }

    #[test]
    fn indices_and_counts_are_whole_numbers() {
        let with_face = |face: &str| ASCII.replace("4 0 1 2 3", face);
        let e = parse_ply(with_face("3 0 -1 2").as_bytes()).unwrap_err();
        assert!(e.contains("not negative"), "{e}");
        let e = parse_ply(with_face("3 0 1.5 2").as_bytes()).unwrap_err();
        assert!(e.contains("whole numbers"), "{e}");
        let e = parse_ply(with_face("3.5 0 1 2").as_bytes()).unwrap_err();
        assert!(e.contains("not a whole number"), "{e}");
        let e = parse_ply(with_face("3 0 1 5000000000").as_bytes()).unwrap_err();
        assert!(e.contains("below 2^32"), "{e}");
    }

    #[test]
    fn a_face_of_fewer_than_three_vertices_is_named() {
        for (face, has) in [
            ("2 0 1", "2 vertices"),
            ("1 3", "1 vertex"),
            ("0", "0 vertices"),
        ] {
            let text = ASCII.replace("element face 1", "element face 2") + face + "\n";
            let e = parse_ply(text.as_bytes()).unwrap_err();
            assert_eq!(
                e,
                format!("face 1 (counted from 0) has {has} (a face needs at least 3)")
            );
        }
    }
}
