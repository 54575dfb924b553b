//! Triangle meshes from Wavefront OBJ (via `tobj`), PLY (`ply.rs`) and glTF
//! files, validated alike.

use crate::source::{Files, MAX_MESH_BYTES};
use std::path::Path;

/// The most bytes a material library (`.mtl`) may hold.
pub const MAX_MTL_BYTES: u64 = 64 << 20;

pub use super::mesh_data::{LibraryReader, MeshData};
pub use super::obj::MAX_LIBRARIES;
use super::ply::parse_ply;

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

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    use crate::lower::ply::ASCII;

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
}
