//! What a mesh file holds once read (`mesh.rs` reads PLY, `obj.rs` OBJ).

use glam::{Vec2, Vec3};
use std::path::{Path, PathBuf};

/// Reads a material library an OBJ names (its path resolved against the
/// OBJ's folder); the error is a sentence.
pub type LibraryReader<'a> = dyn FnMut(&Path) -> Result<Vec<u8>, String> + 'a;

/// Triangles with optional per-vertex normals and texture coordinates.
#[derive(Debug, Clone, Default)]
pub struct MeshData {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Vertex normals (empty when the file has none).
    pub normals: Vec<Vec3>,
    /// Vertex texture coordinates, (0, 0) at an image's bottom-left (empty
    /// when the file has none).
    pub uvs: Vec<Vec2>,
    /// Triangles as vertex indices.
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle, its index in `materials` (`u32::MAX`: none); empty
    /// when the file names no material.
    pub face_material: Vec<u32>,
    /// The materials of the OBJ's libraries (`mtllib`), as `tobj` reads them.
    pub materials: Vec<tobj::Material>,
    /// The libraries read (to watch and to revalidate a cached mesh).
    pub libraries: Vec<PathBuf>,
    /// Why a library could not be read, one sentence each.
    pub library_errors: Vec<String>,
}
