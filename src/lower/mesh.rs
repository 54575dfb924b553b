//! Triangle meshes from Wavefront OBJ (via `tobj`) and PLY (ASCII, binary
//! little and big endian; our own reader: the format is small and we want
//! exact control over errors and memory).

use crate::source::{Files, MAX_MESH_BYTES};
use glam::{Vec2, Vec3};
use std::path::Path;

/// The most bytes a material library (`.mtl`) may hold.
pub const MAX_MTL_BYTES: u64 = 64 << 20;

pub use super::mesh_data::{LibraryReader, MeshData};
pub use super::obj::MAX_LIBRARIES;

/// Reads an OBJ or PLY file and an OBJ's material libraries; the error is
/// a sentence for a diagnostic.
pub fn load(files: &dyn Files, path: &Path) -> Result<MeshData, String> {
    parse_with(path, &read(files, path)?, &mut library_reader(files))
}

/// Reads material libraries through `files`, at most [`MAX_MTL_BYTES`].
pub fn library_reader(files: &dyn Files) -> impl FnMut(&Path, u64) -> Result<Vec<u8>, String> + '_ {
    move |path: &Path, limit: u64| files.read(path, limit).map_err(|e| e.to_string())
}

/// The bytes of a mesh file, at most [`MAX_MESH_BYTES`].
pub fn read(files: &dyn Files, path: &Path) -> Result<Vec<u8>, String> {
    (files.read(path, MAX_MESH_BYTES)).map_err(|e| format!("cannot read the file: {e}"))
}

/// Parses the bytes of an OBJ or PLY file (the format follows `path`'s
/// extension) and validates the result, reading no material library.
pub fn parse(path: &Path, bytes: &[u8]) -> Result<MeshData, String> {
    parse_with(path, bytes, &mut |_, _| Err("not read".to_string()))
}

/// [`parse`], an OBJ's material libraries read by `library`.
pub fn parse_with(
    path: &Path,
    bytes: &[u8],
    library: &mut LibraryReader,
) -> Result<MeshData, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let folder = path.parent().unwrap_or(Path::new(""));
    let mesh = match ext.as_deref() {
        Some("obj") => super::obj::parse_obj(bytes, folder, library)?,
        Some("ply") => parse_ply(bytes)?,
        Some("gltf" | "glb") => super::gltf::parse_gltf(bytes, path, library)?,
        _ => return Err("unknown mesh format (expected .obj, .ply, .gltf or .glb)".into()),
    };
    if mesh.triangles.is_empty() {
        return Err("the mesh has no triangles".into());
    }
    let n = mesh.positions.len() as u32;
    if let Some(bad) = mesh.triangles.iter().flatten().find(|&&i| i >= n) {
        let has = crate::diag::count(n, "vertex", "vertices");
        return Err(format!(
            "a face refers to vertex {bad}, but the mesh has {has}"
        ));
    }
    if mesh.positions.iter().any(|p| !p.is_finite()) {
        return Err("a vertex position is not a finite number".into());
    }
    if mesh.uvs.iter().any(|uv| !uv.is_finite()) {
        return Err("a texture coordinate is not a finite number".into());
    }
    if !mesh.uvs.is_empty() && mesh.uvs.len() != mesh.positions.len() {
        return Err(format!(
            "the file has {} for {}",
            count(mesh.uvs.len(), "texture coordinate", "texture coordinates"),
            count(mesh.positions.len(), "vertex", "vertices"),
        ));
    }
    // Normals go with positions one to one (the renderer indexes both by
    // vertex), or there are none.
    if !mesh.normals.is_empty() && mesh.normals.len() != mesh.positions.len() {
        return Err(format!(
            "the file has {} for {}",
            count(mesh.normals.len(), "vertex normal", "vertex normals"),
            count(mesh.positions.len(), "vertex", "vertices"),
        ));
    }
    Ok(mesh)
}

/// `n` things, singular for one.
fn count(n: usize, one: &str, many: &str) -> String {
    crate::diag::count(n as u64, one, many)
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

/// Parses a PLY file from memory.
pub fn parse_ply(bytes: &[u8]) -> Result<MeshData, String> {
    let header_end = bytes
        .windows(10)
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
                count: count
                    .parse()
                    .map_err(|_| format!("bad element count `{count}`"))?,
                props: Vec::new(),
            }),
            ["property", "list", c, t, name] => {
                let (c, t) = (
                    Scalar::parse(c).ok_or("bad PLY list type")?,
                    Scalar::parse(t).ok_or("bad PLY list type")?,
                );
                elements
                    .last_mut()
                    .ok_or("property before element")?
                    .props
                    .push(Prop::List(name.to_string(), c, t));
            }
            ["property", t, name] => {
                let t = Scalar::parse(t).ok_or_else(|| format!("unknown PLY type `{t}`"))?;
                elements
                    .last_mut()
                    .ok_or("property before element")?
                    .props
                    .push(Prop::Scalar(name.to_string(), t));
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
        let least: usize = el
            .props
            .iter()
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
        if el.props.is_empty() {
            continue;
        }
        let idx = |n: &str| {
            el.props
                .iter()
                .position(|p| matches!(p, Prop::Scalar(s, _) if s == n))
        };
        let (ix, iy, iz) = (idx("x"), idx("y"), idx("z"));
        let (inx, iny, inz) = (idx("nx"), idx("ny"), idx("nz"));
        // Texture coordinates go by several names in the wild.
        let iuv = [
            ("u", "v"),
            ("s", "t"),
            ("texture_u", "texture_v"),
            ("texture_s", "texture_t"),
        ]
        .iter()
        .find_map(|(u, v)| Some((idx(u)?, idx(v)?)));
        // Colours, by the names exporters use (Blender, MeshLab: `red`).
        let irgb = [("red", "green", "blue"), ("r", "g", "b")]
            .iter()
            .find_map(|(r, g, b)| Some([idx(r)?, idx(g)?, idx(b)?]));
        let is_vertex = el.name == "vertex";
        let is_face = el.name == "face";
        if is_vertex {
            if ix.is_none() || iy.is_none() || iz.is_none() {
                return Err("the PLY vertices have no x, y, z".into());
            }
            out.positions.reserve(el.count);
        }
        let has_normals = is_vertex && inx.is_some() && iny.is_some() && inz.is_some();
        if is_vertex && iuv.is_some() {
            out.uvs.reserve(el.count);
        }
        if is_face {
            out.triangles.reserve(el.count);
        }
        let mut vals = vec![0.0f64; el.props.len()];
        let mut list: Vec<u32> = Vec::new();
        for _ in 0..el.count {
            for (k, p) in el.props.iter().enumerate() {
                match p {
                    Prop::Scalar(_, t) => vals[k] = r.read(*t)?,
                    Prop::List(name, c, t) => {
                        let n = r.read(*c)?;
                        if n.fract() != 0.0 {
                            return Err(format!("a list has {n} entries, not a whole number"));
                        }
                        if !(0.0..=1024.0).contains(&n) {
                            return Err(format!("a face has {n} vertices"));
                        }
                        list.clear();
                        for _ in 0..n as usize {
                            list.push(index(r.read(*t)?)?);
                        }
                        if is_face
                            && (name == "vertex_indices" || name == "vertex_index")
                            && list.len() >= 3
                        {
                            for j in 1..list.len() - 1 {
                                out.triangles.push([list[0], list[j], list[j + 1]]);
                            }
                        }
                    }
                }
            }
            if is_vertex {
                out.positions.push(Vec3::new(
                    vals[ix.unwrap()] as f32,
                    vals[iy.unwrap()] as f32,
                    vals[iz.unwrap()] as f32,
                ));
                if has_normals {
                    out.normals.push(Vec3::new(
                        vals[inx.unwrap()] as f32,
                        vals[iny.unwrap()] as f32,
                        vals[inz.unwrap()] as f32,
                    ));
                }
                if let Some((iu, iv)) = iuv {
                    out.uvs.push(Vec2::new(vals[iu] as f32, vals[iv] as f32));
                }
                if let Some(channels) = irgb {
                    let color = channels.map(|k| match &el.props[k] {
                        Prop::Scalar(_, t) => vertex_color(vals[k], *t),
                        Prop::List(..) => 1.0,
                    });
                    out.colors.push(Vec3::from_array(color));
                }
            }
        }
    }
    Ok(out)
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

#[cfg(test)]
mod tests {
    use super::*;

    const ASCII: &str = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";

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
    fn latin1_comments_and_names_are_read() {
        // As exporters on Windows write them: `Cr\xe9\xe9` is not UTF-8.
        let obj = b"# Cr\xe9\xe9 par Blender\no caf\xe9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let m = parse(Path::new("t.obj"), obj).unwrap();
        assert_eq!(m.triangles, [[0, 1, 2]]);
        let ply = ASCII.replace("format ascii 1.0\n", "format ascii 1.0\ncomment \u{1}\n");
        let mut bytes = ply.into_bytes();
        let at = bytes.iter().position(|&b| b == 1).unwrap();
        bytes[at] = 0xe9;
        assert_eq!(parse_ply(&bytes).unwrap().triangles.len(), 2);
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
    fn texture_coordinates_from_obj_and_every_ply_naming() {
        let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.1 0.2\nvt 0.9 0.2\nvt 0.1 0.8\nf 1/1 2/2 3/3\n";
        let m = parse(Path::new("t.obj"), obj).unwrap();
        assert_eq!(
            m.uvs,
            [
                Vec2::new(0.1, 0.2),
                Vec2::new(0.9, 0.2),
                Vec2::new(0.1, 0.8)
            ]
        );
        let m = parse(Path::new("t.obj"), b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert!(m.uvs.is_empty());
        for (u, v) in [
            ("u", "v"),
            ("s", "t"),
            ("texture_u", "texture_v"),
            ("texture_s", "texture_t"),
        ] {
            let ply = format!(
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                 property float z\nproperty float {u}\nproperty float {v}\nelement face 1\n\
                 property list uchar int vertex_indices\nend_header\n\
                 0 0 0 0.1 0.2\n1 0 0 0.9 0.2\n0 1 0 0.1 0.8\n3 0 1 2\n"
            );
            let m = parse(Path::new("t.ply"), ply.as_bytes()).unwrap();
            assert_eq!(m.uvs[1], Vec2::new(0.9, 0.2), "{u} {v}");
        }
        // Not finite, or not one per vertex: an error, not a panic later.
        let nan = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 nan 0\n1 0 0 0 0\n0 1 0 0 0\n3 0 1 2\n";
        assert!(parse(Path::new("t.ply"), nan.as_bytes())
            .unwrap_err()
            .contains("texture coordinate"));
        let twice = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        assert!(parse(Path::new("t.ply"), twice.as_bytes()).is_err());
    }

    #[test]
    fn one_vertex_element_and_normals_for_every_vertex() {
        // Found by the ply fuzz target: normals for some vertices only.
        let twice = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 0 0 1\n1 0 0\n0 1 0\n3 0 1 2\n";
        let e = parse_ply(twice.as_bytes()).unwrap_err();
        assert!(e.contains("twice"), "{e}");
        // An OBJ's normals are per vertex after tobj's single indexing.
        let e = parse(
            Path::new("m.obj"),
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n",
        );
        assert!(e.is_ok_and(|m| m.normals.len() == 3));
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
}
