//! What a mesh file holds once read (`mesh.rs` reads PLY, `obj.rs` OBJ).

use crate::check::{Light, Material};
use glam::{DMat4, Vec2, Vec3, Vec4};
use std::borrow::Cow;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Reads a file a mesh file names (an OBJ's material library, a glTF's
/// buffer; its path resolved against the mesh file's folder), at most the
/// given bytes; the error is a sentence.
pub type LibraryReader<'a> = dyn FnMut(&Path, u64) -> Result<Vec<u8>, String> + 'a;

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
    /// Vertex colours, linear RGB in [0, 1] (empty when the file has none;
    /// white for the vertices of a primitive without).
    pub colors: Vec<Vec3>,
    /// Triangles as vertex indices.
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle, the tangent at each of its corners for normal maps
    /// (xyz along ∂p/∂u, w the bitangent's side: n × t · w points along
    /// +v), from a glTF file's `TANGENT` or generated (MikkTSpace); a zero
    /// w where a triangle has none; empty when no triangle has any.
    pub face_tangents: Vec<[Vec4; 3]>,
    /// Per triangle, its index in `materials` (`u32::MAX`: none); empty
    /// when the file names no material.
    pub face_material: Vec<u32>,
    /// The materials of the OBJ's libraries (`mtllib`), as `tobj` reads them.
    pub materials: Vec<tobj::Material>,
    /// Per material, the library that holds it (an index into
    /// `libraries`): its maps are read relative to that file.
    pub material_libraries: Vec<u32>,
    /// The libraries read (to watch and to revalidate a cached mesh): an
    /// OBJ's `.mtl` files, a glTF's external buffers.
    pub libraries: Vec<PathBuf>,
    /// Why a library could not be read, one sentence each.
    pub library_errors: Vec<String>,
    /// What a scene file (glTF) places: its nodes, primitives and
    /// materials (`None` for OBJ and PLY).
    pub scene: Option<Box<FileScene>>,
}

/// A scene file's structure over the triangles of its [`MeshData`]: each
/// primitive is a part (its own vertices and triangles), each node that
/// places a mesh a placement of that mesh's parts.
#[derive(Debug, Clone, Default)]
pub struct FileScene {
    /// The primitives read.
    pub parts: Vec<Part>,
    /// Every node of the file, by index.
    pub nodes: Vec<FileNode>,
    /// The nodes of its default scene (else its first; none without one).
    pub roots: Vec<u32>,
    /// The file's materials in ptsc's terms (spans set where a statement
    /// places the file).
    pub materials: Vec<Material>,
    /// Their names in the file (empty for a material without one).
    pub material_names: Vec<String>,
    /// The materials of primitives with vertex colours (they multiply
    /// their base colour by them), by index.
    pub colored_materials: Vec<u32>,
    /// Images held inside the file (GLB chunks, data URIs) under the
    /// paths its materials' textures read them by.
    pub embedded: Vec<(PathBuf, Arc<Vec<u8>>)>,
    /// What the file asks that ptsc does not follow, one sentence each.
    pub notes: Vec<String>,
    /// The same, of its materials and images: not said to a statement
    /// that gives its own material.
    pub material_notes: Vec<String>,
}

/// One primitive: its vertices and triangles (ranges in the mesh data;
/// the triangles' indices point into the whole vertex list).
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// The glTF mesh it belongs to.
    pub mesh: u32,
    /// Its vertices.
    pub vertices: Range<u32>,
    /// Its triangles.
    pub triangles: Range<u32>,
    /// Its material (index into [`FileScene::materials`]), if it has one.
    pub material: Option<u32>,
}

/// What a walk of a scene file's nodes places: meshes and lights, each
/// with its node → placement frame transform.
pub type Placing = (Vec<Placed>, Vec<(Light, DMat4)>);

/// A node of a scene file.
#[derive(Debug, Clone, PartialEq)]
pub struct FileNode {
    /// Its name, or `#index`.
    pub name: String,
    /// Node → parent.
    pub local: DMat4,
    /// The mesh it places, if any (and the file has it read).
    pub mesh: Option<u32>,
    /// The light it holds (`KHR_lights_punctual`), in its frame: at the
    /// origin, shining along −z.
    pub light: Option<Light>,
    /// Its children, by index.
    pub children: Vec<u32>,
}

impl FileScene {
    /// What the statement places of the file: the default scene's nodes
    /// in the file's frame, or node `name`'s subtree in the node's (its
    /// own transform left out); the error is a sentence (no such node, a
    /// node reached twice, nothing placed).
    pub fn placements(&self, name: Option<&str>) -> Result<Placing, String> {
        let starts: Vec<(u32, DMat4)> = match name {
            None => (self.roots.iter())
                .filter_map(|&k| Some((k, self.nodes.get(k as usize)?.local)))
                .collect(),
            Some(name) => {
                let k = (self.nodes.iter().position(|n| n.name == name)).ok_or_else(|| {
                    let mut names: Vec<&str> = self.nodes.iter().map(|n| n.name.as_str()).collect();
                    names.truncate(12);
                    format!(
                        "the file has no node `{name}` (its nodes: {})",
                        names.join(", ")
                    )
                })?;
                vec![(k as u32, DMat4::IDENTITY)]
            }
        };
        let with_parts: std::collections::BTreeSet<u32> =
            self.parts.iter().map(|p| p.mesh).collect();
        let mut seen = vec![false; self.nodes.len()];
        let mut stack: Vec<(u32, DMat4)> = starts.into_iter().rev().collect();
        let (mut out, mut lights) = (Vec::new(), Vec::new());
        // Each node once: the file's nodes are trees (`gltf_nodes`), so a
        // node reached twice is one a scene lists twice.
        while let Some((k, transform)) = stack.pop() {
            let node = (self.nodes.get(k as usize)).ok_or("a child index past the nodes")?;
            if std::mem::replace(&mut seen[k as usize], true) {
                return Err(format!(
                    "node `{}` is placed twice: the scene lists it twice, or lists it and a node above it (a scene lists the roots of its trees)",
                    node.name
                ));
            }
            if let Some(light) = &node.light {
                lights.push((light.clone(), transform));
            }
            if let Some(mesh) = node.mesh.filter(|m| with_parts.contains(m)) {
                let node = node.name.clone();
                out.push(Placed {
                    mesh,
                    transform,
                    node,
                });
            }
            let children = node.children.iter().rev();
            stack.extend(
                children.filter_map(|&c| Some((c, transform * self.nodes.get(c as usize)?.local))),
            );
        }
        match (out.is_empty(), name) {
            (true, Some(name)) => Err(format!("node `{name}` and its children place no triangles")),
            (true, None) => Err("the file's default scene places no triangles".into()),
            (false, _) => Ok((out, lights)),
        }
    }
}

/// A node that places a mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    /// The mesh (as [`Part::mesh`]).
    pub mesh: u32,
    /// Node → file frame: the node's and its ancestors' transforms.
    pub transform: DMat4,
    /// The node's name, or `#index`.
    pub node: String,
}

impl MeshData {
    /// The vertices and triangles of part `group` of a scene file, or of
    /// material group `group` of an OBJ (every vertex), or all: the
    /// positions, normals and texture coordinates the triangles' indices
    /// point into.
    pub fn view(&self, group: Option<u32>) -> MeshView<'_> {
        let part = (self.scene.as_ref()).and_then(|s| s.parts.get(group? as usize));
        let Some(part) = part else {
            let material = |k: usize| self.face_material.get(k).copied().unwrap_or(u32::MAX);
            let (triangles, tangents) = match group {
                None => (
                    Cow::Borrowed(&self.triangles[..]),
                    Cow::Borrowed(&self.face_tangents[..]),
                ),
                Some(g) => {
                    let kept = |k: &usize| material(*k) == g;
                    let indices = (0..self.triangles.len()).filter(kept);
                    let tangents = (0..self.face_tangents.len()).filter(kept);
                    (
                        indices.map(|k| self.triangles[k]).collect(),
                        tangents.map(|k| self.face_tangents[k]).collect(),
                    )
                }
            };
            return MeshView {
                positions: &self.positions,
                normals: &self.normals,
                uvs: &self.uvs,
                colors: &self.colors,
                triangles,
                tangents,
                part: false,
            };
        };
        let v = part.vertices.start as usize..part.vertices.end as usize;
        let base = part.vertices.start;
        MeshView {
            positions: self.positions.get(v.clone()).unwrap_or(&[]),
            normals: self.normals.get(v.clone()).unwrap_or(&[]),
            uvs: self.uvs.get(v.clone()).unwrap_or(&[]),
            colors: self.colors.get(v.clone()).unwrap_or(&[]),
            triangles: (self.triangles[part.triangles.start as usize..part.triangles.end as usize])
                .iter()
                .map(|t| t.map(|i| i - base))
                .collect(),
            tangents: Cow::Borrowed(
                (self.face_tangents)
                    .get(part.triangles.start as usize..part.triangles.end as usize)
                    .unwrap_or(&[]),
            ),
            part: true,
        }
    }

    /// How many triangles [`MeshData::view`] of `group` has.
    pub fn count(&self, group: Option<u32>) -> usize {
        match (self.scene.as_ref()).and_then(|s| s.parts.get(group? as usize)) {
            Some(part) => part.triangles.len(),
            None => match group {
                Some(g) => (self.face_material.iter()).filter(|&&m| m == g).count(),
                None => self.triangles.len(),
            },
        }
    }
}

/// Part of a mesh: its triangles with indices into its own vertex lists.
#[derive(Debug)]
pub struct MeshView<'a> {
    /// Vertex positions.
    pub positions: &'a [Vec3],
    /// Vertex normals (empty: none).
    pub normals: &'a [Vec3],
    /// Vertex texture coordinates (empty: none).
    pub uvs: &'a [Vec2],
    /// Vertex colours (empty: none).
    pub colors: &'a [Vec3],
    /// Triangles as indices into the lists above.
    pub triangles: Cow<'a, [[u32; 3]]>,
    /// Each triangle's corner tangents (empty: none; see
    /// [`MeshData::face_tangents`]).
    pub tangents: Cow<'a, [[Vec4; 3]]>,
    /// Whether it is a scene file's part (its own vertices), not all the
    /// file's vertices.
    pub part: bool,
}

/// Whether `path` names a glTF file (`.gltf` or `.glb`).
pub fn is_gltf(path: &Path) -> bool {
    let ext = path.extension().and_then(|e| e.to_str());
    ext.is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}
