//! Wavefront OBJ through `tobj`: positions, normals, texture coordinates,
//! and each face's material from the `mtllib` libraries the file names
//! (read through the scene's files by the caller's reader).

use super::mesh_data::{LibraryReader, MeshData};
use glam::{Vec2, Vec3};
use std::path::{Path, PathBuf};

/// The most material libraries (`mtllib`) an OBJ may name: each is read
/// once per name, and a hostile file could name one a million times.
pub const MAX_LIBRARIES: usize = 16;

/// How `tobj` reads an OBJ for ptsc: faces as triangles, one index per
/// vertex (the tests that locate `tobj`'s errors load with these too).
pub(super) fn tobj_options() -> tobj::LoadOptions {
    tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    }
}

/// The mesh of an OBJ file's bytes, its libraries read by `library`
/// relative to `folder`.
pub(super) fn parse_obj(
    bytes: &[u8],
    folder: &Path,
    library: &mut LibraryReader,
) -> Result<MeshData, String> {
    let opts = tobj_options();
    // Material libraries are read through `library` (the scene's files);
    // one that cannot be read leaves its faces without a material.
    // (tobj asks through an `Fn`: the reader and the lists are borrowed
    // mutably inside.)
    let reader = std::cell::RefCell::new(library);
    let libraries = std::cell::RefCell::new(Vec::new());
    let library_errors = std::cell::RefCell::new(Vec::new());
    // `tobj` appends each library's materials in turn: the owners line up.
    let owners = std::cell::RefCell::new(Vec::new());
    // A byte that is not UTF-8 (a Latin-1 comment or name from an older
    // exporter) would fail `tobj`'s whole read: it becomes U+FFFD, as in
    // the libraries (`mtl::readable`); the lines keep their numbers.
    let text = String::from_utf8_lossy(bytes);
    // The lines are read by ptsc's rules (`obj_lines`, a pass over every
    // line: 9 % of checking a 1M-triangle OBJ) only where the file may
    // hold what `tobj` reads otherwise: an `l` line (a line that starts
    // with `l` or a blank), or (looked for after `tobj`) a face of fewer
    // than three vertices.
    let may_have_polylines = text.starts_with(|c: char| c == 'l' || c.is_ascii_whitespace())
        || ["\nl", "\n ", "\n\t"].iter().any(|p| text.contains(p));
    let read = match may_have_polylines {
        true => super::obj_lines::faces_and_polylines(&text)?,
        false => std::borrow::Cow::Borrowed(&*text),
    };
    let polylines = matches!(read, std::borrow::Cow::Owned(_));
    let mut cursor = std::io::Cursor::new(read.as_bytes());
    let (models, materials) = tobj::load_obj_buf(&mut cursor, &opts, |name| {
        let path = folder.join(name);
        let failed = |e: String| {
            (library_errors.borrow_mut()).push(format!("cannot read `{}`: {e}", name.display()));
        };
        if libraries.borrow().len() >= MAX_LIBRARIES {
            if libraries.borrow().len() == MAX_LIBRARIES {
                failed(format!(
                    "the file names more than {MAX_LIBRARIES} material libraries"
                ));
                libraries.borrow_mut().push(PathBuf::new());
            }
            return Err(tobj::LoadError::OpenFileFailed);
        }
        libraries.borrow_mut().push(path.clone());
        let limit = super::mesh::MAX_MTL_BYTES;
        let text = (reader.borrow_mut())(&path, limit).map_err(|e| {
            failed(e);
            tobj::LoadError::OpenFileFailed
        })?;
        let (text, dropped) = super::mtl::readable(&text);
        for line in dropped {
            failed(format!(
                "its line `{line}` is not a colour ptsc reads (three numbers, or one)"
            ));
        }
        let owner = libraries.borrow().len() as u32 - 1;
        tobj::load_mtl_buf(&mut std::io::Cursor::new(text))
            .inspect(|(read, _)| {
                owners
                    .borrow_mut()
                    .extend(std::iter::repeat_n(owner, read.len()))
            })
            .inspect_err(|e| failed(e.to_string()))
    })
    .map_err(|e| {
        let at = (super::obj_faces::locate(bytes, &e))
            .or_else(|| super::obj_lines::locate_vertex(&text, Some(&e)));
        match at {
            Some(at) => format!("cannot read the OBJ file: {e} at {at}"),
            None => format!("cannot read the OBJ file: {e}"),
        }
    })?;
    let (mut libraries, library_errors) = (libraries.into_inner(), library_errors.into_inner());
    libraries.retain(|p| !p.as_os_str().is_empty());
    let materials = materials.unwrap_or_default();
    let mut out = MeshData::default();
    for m in models {
        let base = out.positions.len() as u32;
        let mesh = m.mesh;
        out.positions.extend(
            mesh.positions
                .chunks_exact(3)
                .map(|c| Vec3::new(c[0], c[1], c[2])),
        );
        if !mesh.normals.is_empty() && mesh.normals.len() == mesh.positions.len() {
            out.normals.extend(
                mesh.normals
                    .chunks_exact(3)
                    .map(|c| Vec3::new(c[0], c[1], c[2])),
            );
        }
        // `v x y z r g b` (an extension Blender and MeshLab write): the
        // sRGB a viewer shows, decoded.
        if mesh.vertex_color.len() == mesh.positions.len() {
            let decode = |c: f32| crate::texture::image::srgb_to_linear(c.clamp(0.0, 1.0));
            out.colors.extend(
                (mesh.vertex_color.chunks_exact(3))
                    .map(|c| Vec3::new(decode(c[0]), decode(c[1]), decode(c[2]))),
            );
        }
        // `vt` has (0, 0) at the image's bottom-left, as ptsc.
        if 3 * mesh.texcoords.len() == 2 * mesh.positions.len() {
            out.uvs.extend(
                mesh.texcoords
                    .chunks_exact(2)
                    .map(|c| Vec2::new(c[0], c[1])),
            );
        }
        let before = out.triangles.len();
        out.triangles.extend(
            mesh.indices
                .chunks_exact(3)
                .map(|c| [base + c[0], base + c[1], base + c[2]]),
        );
        let id = (mesh.material_id)
            .filter(|&i| i < materials.len())
            .map_or(u32::MAX, |i| i as u32);
        out.face_material.resize(before, u32::MAX);
        out.face_material.resize(out.triangles.len(), id);
    }
    // `tobj` makes a face of one or two vertices a triangle that repeats
    // one: only then are the faces counted, for the line to blame.
    let repeats = |t: &[u32; 3]| t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if !may_have_polylines && out.triangles.iter().any(repeats) {
        super::obj_lines::faces_and_polylines(&text)?;
    }
    if out.triangles.is_empty() && polylines {
        return Err("the mesh has no faces, only lines (`l`), which have no surface".into());
    }
    // `tobj` reads `nan` and `inf`; the line is looked for only then.
    let finite = out.positions.iter().all(|p| p.is_finite());
    if !(finite && out.uvs.iter().all(|uv| uv.is_finite())) {
        if let Some(at) = super::obj_lines::locate_vertex(&text, None) {
            return Err(format!("cannot read the OBJ file at {at}"));
        }
    }
    if out.face_material.iter().all(|&m| m == u32::MAX) {
        out.face_material.clear();
    }
    out.materials = materials;
    out.material_libraries = owners.into_inner();
    out.libraries = libraries;
    out.library_errors = library_errors;
    // Attributes only when every object of the file has them.
    if out.normals.len() != out.positions.len() {
        out.normals.clear();
    }
    if out.uvs.len() != out.positions.len() {
        out.uvs.clear();
    }
    if out.colors.len() != out.positions.len() {
        out.colors.clear();
    }
    Ok(out)
}
