//! glTF 2.0 scenes (`.gltf` with external or data-URI buffers, `.glb`):
//! the default scene's node tree with every transform, each mesh read once
//! however many nodes place it, its triangle primitives (positions,
//! normals, the `TEXCOORD_n` its material reads, tangents: the file's or
//! MikkTSpace's where a normal map needs them, `tangents.rs`) and the
//! file's materials (`gltf_material.rs`).
//! The `gltf` crate parses the JSON and the GLB container; buffers are
//! read through the scene's `Files` (the caller's reader) and accessors by
//! our own checked code (`gltf_accessor.rs`); `KHR_lights_punctual` lights
//! become the scene's. What is not followed (skins, morph targets,
//! animations, cameras, points and lines, unknown required extensions) is a
//! note that lowering turns into a warning.
//!
//! Frames: glTF is y-up, right-handed, in metres, as ptsc reads any mesh
//! file (no axis is changed); its texture coordinates have (0, 0) at the
//! image's top-left, ptsc's at the bottom-left: v becomes 1 − v.

use super::gltf_accessor::{self, Buffers};
use super::gltf_buffers::read_buffers;
use super::mesh_data::{FileNode, FileScene, LibraryReader, MeshData, Part};
use crate::check::domain::MAX_RADIANCE;
use crate::check::Light;
use glam::{DMat4, DQuat, DVec3, Vec2, Vec3, Vec4};
use gltf::mesh::Mode;
use gltf::Semantic;
use std::collections::BTreeSet;
use std::path::Path;

/// The extensions ptsc reads (others a file requires are named in a note).
pub const SUPPORTED_EXTENSIONS: [&str; 9] = [
    "KHR_lights_punctual",
    "KHR_materials_clearcoat",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_sheen",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_texture_transform",
    "KHR_mesh_quantization",
];

/// The most vertices a file's meshes may have together.
pub const MAX_VERTICES: usize = 100_000_000;
/// The most triangles a file's meshes may have together (each mesh once).
pub const MAX_TRIANGLES: usize = super::shapes::MAX_PRIMITIVES;

/// The scene of a glTF file's `bytes` (at `path`), its external buffers
/// read by `library`.
pub(super) fn parse_gltf(
    bytes: &[u8],
    path: &Path,
    library: &mut LibraryReader,
) -> Result<MeshData, String> {
    let gltf = gltf::Gltf::from_slice_without_validation(bytes)
        .map_err(|e| format!("cannot read the glTF file: {e}"))?;
    validate(&gltf.document)?;
    let doc = &gltf.document;
    let folder = path.parent().unwrap_or(Path::new(""));
    let mut out = MeshData::default();
    let mut scene = FileScene::default();
    let buffers = read_buffers(doc, gltf.blob.as_deref(), (folder, library), &mut out)?;
    notes_on_the_file(doc, &mut scene.notes);
    scene.nodes = nodes(doc, &mut scene.notes)?;
    super::gltf_nodes::hierarchy(&scene.nodes)?;
    let default = (doc.default_scene()).or_else(|| doc.scenes().next());
    scene.roots = default.map_or(Vec::new(), |s| {
        s.nodes().map(|n| n.index() as u32).collect()
    });
    // Every mesh a node places: `node "Name"` may pick one outside the
    // default scene.
    let meshes: BTreeSet<u32> = scene.nodes.iter().filter_map(|n| n.mesh).collect();
    let mut attributes = Attributes::default();
    for mesh in doc
        .meshes()
        .filter(|m| meshes.contains(&(m.index() as u32)))
    {
        read_mesh(&mesh, &buffers, (&mut out, &mut attributes), &mut scene)?;
    }
    attributes.finish(&mut out);
    if scene.parts.is_empty() {
        return Err("the file's nodes place no triangles".into());
    }
    super::gltf_material::read(doc, path, &buffers, &mut scene);
    out.scene = Some(Box::new(scene));
    Ok(out)
}

/// The `gltf` crate's checks of the JSON (every index in range, every
/// required field there), less the bounds (`min`, `max`) that the
/// specification asks of positions (ptsc computes its own, and exporters
/// leave them out) and the refusal of required extensions it does not know
/// (a warning instead: the rest of the file is placed).
fn validate(doc: &gltf::Document) -> Result<(), String> {
    use gltf::json::validation::{Error, Validate};
    let root = doc.as_json();
    // The crate's own check of positions indexes the accessors unchecked
    // (gltf-json 1.4.1, mesh.rs): attributes are checked first.
    let accessors = root.accessors.len();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for primitive in &mesh.primitives {
            if let Some(bad) = (primitive.attributes.values()).find(|a| a.value() >= accessors) {
                return Err(format!(
                    "the glTF file is not valid: mesh {m} names accessor {}, but the file has {accessors}",
                    bad.value()
                ));
            }
        }
    }
    let mut errors = Vec::new();
    root.validate(root, gltf::json::Path::new, &mut |path, error| {
        let path = path().to_string();
        let bounds = path.ends_with(".min") || path.ends_with(".max");
        // A required extension ptsc does not read is a note (`notes_on_the_file`).
        let required = path.starts_with("extensionsRequired");
        if !(bounds && matches!(error, Error::Missing)
            || required && matches!(error, Error::Unsupported))
        {
            errors.push(format!("{path}: {error}"));
        }
    });
    match errors.is_empty() {
        true => Ok(()),
        false => Err(format!(
            "the glTF file is not valid: {}{}",
            errors[..errors.len().min(3)].join("; "),
            if errors.len() > 3 { "; …" } else { "" }
        )),
    }
}

/// Notes on what the file holds that ptsc does not follow.
fn notes_on_the_file(doc: &gltf::Document, notes: &mut Vec<String>) {
    for name in doc.extensions_required() {
        if !SUPPORTED_EXTENSIONS.contains(&name) {
            notes.push(format!("it requires the extension `{name}`, which ptsc does not read: what it changes is missing"));
        }
    }
    if doc.animations().len() > 0 {
        notes.push("its animations are not played: the scene is in its rest pose".into());
    }
    if doc.cameras().len() > 0 {
        notes.push("its cameras are not used: the scene's `camera` is".into());
    }
}

/// Every node of the file with its own transform, mesh, light and
/// children; a skinned one is noted.
fn nodes(doc: &gltf::Document, notes: &mut Vec<String>) -> Result<Vec<FileNode>, String> {
    let lights = lights(doc);
    (doc.nodes())
        .map(|node| {
            let name = node_name(&node);
            if node.skin().is_some() {
                notes.push(format!(
                    "node `{name}` is skinned: its mesh is placed in its bind pose"
                ));
            }
            let json = &doc.as_json().nodes[node.index()];
            let light = (json.extensions.as_ref())
                .and_then(|e| e.khr_lights_punctual.as_ref())
                .and_then(|l| lights.get(l.light.value()).cloned().flatten());
            Ok(FileNode {
                local: local_transform(&node.transform(), &name)?,
                mesh: node.mesh().map(|m| m.index() as u32),
                light,
                children: node.children().map(|c| c.index() as u32).collect(),
                name,
            })
        })
        .collect()
}

/// The file's lights (`KHR_lights_punctual`) as ptsc's, by index, each in
/// its node's frame (at the origin, shining along −z): a point light's
/// intensity in candela and a directional light's in lux are read as
/// ptsc's intensity (W/sr) and irradiance (W/m²) times the colour, as
/// renderers that take glTF's photometric numbers for radiometric ones do
/// (no 683 lm/W: a lamp of 100 cd lights a room as 100 W/sr does in ptsc).
/// A light of an unknown type is `None`. Read from the JSON: the crate's
/// `Light::kind` unwraps a spot light's missing cone.
fn lights(doc: &gltf::Document) -> Vec<Option<Light>> {
    use gltf::json::extensions::scene::khr_lights_punctual::Type;
    use gltf::json::validation::Checked;
    let Some(ext) =
        (doc.as_json().extensions.as_ref()).and_then(|e| e.khr_lights_punctual.as_ref())
    else {
        return Vec::new();
    };
    let finite = |x: f32, default: f64| match x.is_finite() && x >= 0.0 {
        true => x as f64,
        false => default,
    };
    (ext.lights.iter())
        .map(|l| {
            let strength = finite(l.intensity, 1.0);
            let power = l
                .color
                .map(|c| (finite(c, 0.0) * strength).min(MAX_RADIANCE));
            let down = DVec3::NEG_Z;
            Some(match l.type_ {
                Checked::Valid(Type::Point) => Light::Point {
                    position: DVec3::ZERO,
                    intensity: power,
                },
                Checked::Valid(Type::Spot) => {
                    let (inner, outer) =
                        (l.spot.as_ref()).map_or((0.0, std::f64::consts::FRAC_PI_4), |s| {
                            (
                                finite(s.inner_cone_angle, 0.0),
                                finite(s.outer_cone_angle, 0.785),
                            )
                        });
                    let angle = outer.to_degrees().clamp(0.01, 90.0);
                    Light::Spot {
                        position: DVec3::ZERO,
                        direction: down,
                        intensity: power,
                        angle,
                        hotspot: inner.to_degrees().clamp(0.0, angle),
                    }
                }
                Checked::Valid(Type::Directional) => Light::Directional {
                    direction: down,
                    irradiance: power,
                },
                Checked::Invalid => return None,
            })
        })
        .collect()
}

/// A node's name, or `#index` when it has none.
fn node_name(node: &gltf::Node) -> String {
    match node.name() {
        Some(name) => name.chars().take(80).collect(),
        None => format!("#{}", node.index()),
    }
}

/// A node's transform to its parent's frame: its matrix, or translation ·
/// rotation · scale (glTF 2.0 §5.25) in f64.
pub fn local_transform(t: &gltf::scene::Transform, name: &str) -> Result<DMat4, String> {
    let m = match t {
        gltf::scene::Transform::Matrix { matrix } => {
            DMat4::from_cols_array_2d(&matrix.map(|c| c.map(f64::from)))
        }
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            let q = DQuat::from_array(rotation.map(f64::from));
            if q.length_squared().is_nan() || q.length_squared() <= 0.0 {
                return Err(format!("node `{name}` has a rotation of length 0"));
            }
            DMat4::from_scale_rotation_translation(
                DVec3::from_array(scale.map(f64::from)),
                q.normalize(),
                DVec3::from_array(translation.map(f64::from)),
            )
        }
    };
    if !m.is_finite() {
        return Err(format!("node `{name}` has a transform that is not finite"));
    }
    Ok(m)
}

/// The vertex attributes read so far, one per vertex whether a primitive
/// has them or not (zero normals shade flat, zero texture coordinates).
#[derive(Default)]
struct Attributes {
    any_normals: bool,
    any_uvs: bool,
    any_tangents: bool,
    any_colors: bool,
}

impl Attributes {
    /// Drops the lists no primitive gave.
    fn finish(self, out: &mut MeshData) {
        if !self.any_normals {
            out.normals.clear();
        }
        if !self.any_tangents {
            out.face_tangents.clear();
        }
        if !self.any_colors {
            out.colors.clear();
        }
        if !self.any_uvs {
            out.uvs.clear();
        }
    }
}

/// Reads the triangle primitives of `mesh` into `out` as parts of `scene`.
fn read_mesh(
    mesh: &gltf::Mesh,
    buffers: &Buffers,
    (out, attributes): (&mut MeshData, &mut Attributes),
    scene: &mut FileScene,
) -> Result<(), String> {
    let name = mesh
        .name()
        .map_or(format!("#{}", mesh.index()), str::to_string);
    for primitive in mesh.primitives() {
        let mode = primitive.mode();
        if matches!(
            mode,
            Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip
        ) {
            scene.notes.push(format!(
                "mesh `{name}` has {mode:?} primitives: only triangles are rendered"
            ));
            continue;
        }
        if primitive.morph_targets().len() > 0 {
            scene.notes.push(format!(
                "mesh `{name}` has morph targets: its base shape is rendered"
            ));
        }
        // A hostile file can point many primitives at one huge accessor:
        // the counts its accessors claim are checked before they are read.
        let (vertices, triangles) = claimed(&primitive, mode);
        if out.positions.len() + vertices > MAX_VERTICES
            || out.triangles.len() + triangles > MAX_TRIANGLES
        {
            return Err(format!(
                "its meshes have more than {} vertices or {} triangles",
                crate::diag::group_digits(MAX_VERTICES as u64),
                crate::diag::group_digits(MAX_TRIANGLES as u64)
            ));
        }
        // The coordinates its material's textures read (`TEXCOORD_1`
        // for a model whose second set holds them).
        let set = match primitive.material().index() {
            Some(_) => super::gltf_material::uv_set(&primitive.material()),
            None => 0,
        };
        let read = read_primitive(&primitive, buffers, (mode, set));
        let (positions, normals, uvs, triangles, tangents) =
            read.map_err(|e| format!("mesh `{name}`: {e}"))?;
        let colors = vertex_colors(&primitive, buffers, positions.len())
            .map_err(|e| format!("mesh `{name}`: {e}"))?;
        if triangles.is_empty() {
            scene
                .notes
                .push(format!("mesh `{name}` has a primitive without a triangle"));
            continue;
        }
        let base = out.positions.len() as u32;
        let start = out.triangles.len() as u32;
        let count = positions.len();
        out.positions
            .extend(positions.iter().map(|p| Vec3::from_array(*p)));
        attributes.any_normals |= normals.is_some();
        match normals {
            Some(n) => out.normals.extend(n.iter().map(|n| Vec3::from_array(*n))),
            None => out.normals.resize(out.positions.len(), Vec3::ZERO),
        }
        attributes.any_uvs |= uvs.is_some();
        match uvs {
            Some(uv) => out
                .uvs
                .extend(uv.iter().map(|[u, v]| Vec2::new(*u, 1.0 - v))),
            None => out.uvs.resize(out.positions.len(), Vec2::ZERO),
        }
        let start_vertex = base as usize;
        let vertices = (
            &out.positions[start_vertex..],
            &out.normals[start_vertex..],
            &out.uvs[start_vertex..],
        );
        let wants = primitive.material().normal_texture().is_some();
        let corners = corner_tangents(vertices, &triangles, tangents, wants);
        attributes.any_tangents |= corners.is_some();
        let corners = corners.unwrap_or_else(|| vec![[Vec4::ZERO; 3]; triangles.len()]);
        attributes.any_colors |= colors.is_some();
        match colors {
            Some(c) => {
                out.colors.resize(start_vertex, Vec3::ONE);
                out.colors.extend(c);
                if let Some(m) = primitive.material().index() {
                    scene.colored_materials.push(m as u32);
                }
            }
            None => out.colors.resize(out.positions.len(), Vec3::ONE),
        }
        out.face_tangents
            .resize(out.triangles.len(), [Vec4::ZERO; 3]);
        out.face_tangents.extend(corners);
        out.triangles
            .extend(triangles.iter().map(|t| t.map(|i| base + i)));
        scene.parts.push(Part {
            mesh: mesh.index() as u32,
            vertices: base..base + count as u32,
            triangles: start..out.triangles.len() as u32,
            material: primitive.material().index().map(|m| m as u32),
        });
    }
    Ok(())
}

/// A primitive's positions, normals, texture coordinates, triangles
/// (indices into its own vertices, each checked) and tangents.
type Primitive = (
    Vec<[f32; 3]>,
    Option<Vec<[f32; 3]>>,
    Option<Vec<[f32; 2]>>,
    Vec<[u32; 3]>,
    Option<Vec<[f32; 4]>>,
);

/// A primitive's `COLOR_0` (RGB or RGBA of floats or normalised
/// integers; the alpha is not read), each within [0, 1], for its `count`
/// vertices; `None` without.
fn vertex_colors(
    p: &gltf::Primitive,
    buffers: &Buffers,
    count: usize,
) -> Result<Option<Vec<Vec3>>, String> {
    let Some(a) = p.get(&Semantic::Colors(0)) else {
        return Ok(None);
    };
    let rgb: Vec<[f32; 3]> = match a.dimensions() {
        gltf::accessor::Dimensions::Vec4 => (gltf_accessor::floats::<4>(&a, buffers, "colours")?)
            .into_iter()
            .map(|[r, g, b, _]| [r, g, b])
            .collect(),
        _ => gltf_accessor::floats::<3>(&a, buffers, "colours")?,
    };
    if rgb.len() != count {
        return Err(format!(
            "the primitive has {} colours for {count} positions",
            rgb.len()
        ));
    }
    let unit = |c: f32| {
        if c.is_finite() {
            c.clamp(0.0, 1.0)
        } else {
            0.0
        }
    };
    Ok(Some(
        rgb.into_iter()
            .map(|c| Vec3::from_array(c.map(unit)))
            .collect(),
    ))
}

/// The tangents at the corners of a primitive's `triangles` over its
/// `vertices` (positions, normals and ptsc's texture coordinates, zero
/// where the file has none): the file's `TANGENT`, else, when its material
/// `wants` them (a normal map), MikkTSpace's; `None` without.
fn corner_tangents(
    (positions, normals, uvs): (&[Vec3], &[Vec3], &[Vec2]),
    triangles: &[[u32; 3]],
    file: Option<Vec<[f32; 4]>>,
    wants: bool,
) -> Option<Vec<[Vec4; 3]>> {
    if let Some(file) = file {
        // The sign alone of w counts (the specification asks ±1).
        let corner = |i: u32| {
            let [x, y, z, w] = file[i as usize];
            Vec4::new(x, y, z, if w < 0.0 { -1.0 } else { 1.0 })
        };
        return Some(triangles.iter().map(|t| t.map(corner)).collect());
    }
    let has = |v: &[Vec3]| v.iter().any(|n| *n != Vec3::ZERO);
    if !wants || !has(normals) || uvs.iter().all(|uv| *uv == Vec2::ZERO) {
        return None;
    }
    super::tangents::generate(positions, normals, uvs, triangles)
}

/// The vertices and triangles primitive `p` of `mode` claims (its
/// accessors' counts), before any is read.
fn claimed(p: &gltf::Primitive, mode: Mode) -> (usize, usize) {
    let vertices = p.get(&Semantic::Positions).map_or(0, |a| a.count());
    let corners = p.indices().map_or(vertices, |a| a.count());
    let triangles = match mode {
        Mode::TriangleStrip | Mode::TriangleFan => corners.saturating_sub(2),
        _ => corners / 3,
    };
    (vertices, triangles)
}

/// Reads one primitive of `mode` (triangles, a strip or a fan), its
/// texture coordinates from `TEXCOORD_<set>`.
fn read_primitive(
    p: &gltf::Primitive,
    buffers: &Buffers,
    (mode, set): (Mode, u32),
) -> Result<Primitive, String> {
    let position = p
        .get(&Semantic::Positions)
        .ok_or("a primitive without positions")?;
    let positions = gltf_accessor::floats::<3>(&position, buffers, "positions")?;
    let count = positions.len();
    let same_count = |what: &str, n: usize| match n == count {
        true => Ok(()),
        false => Err(format!(
            "the primitive has {n} {what} for {count} positions"
        )),
    };
    let normals = match p.get(&Semantic::Normals) {
        Some(a) => Some(gltf_accessor::floats::<3>(&a, buffers, "normals")?),
        None => None,
    };
    let uvs = match p.get(&Semantic::TexCoords(set)) {
        Some(a) => Some(gltf_accessor::floats::<2>(
            &a,
            buffers,
            "texture coordinates",
        )?),
        None => None,
    };
    let tangents = match p.get(&Semantic::Tangents) {
        Some(a) => Some(gltf_accessor::floats::<4>(&a, buffers, "tangents")?),
        None => None,
    };
    if let Some(t) = &tangents {
        same_count("tangents", t.len())?;
    }
    if let Some(n) = &normals {
        same_count("normals", n.len())?;
    }
    if let Some(uv) = &uvs {
        same_count("texture coordinates", uv.len())?;
    }
    let indices = match p.indices() {
        Some(a) => gltf_accessor::indices(&a, buffers)?,
        None => (0..count as u32).collect(),
    };
    if let Some(bad) = indices.iter().find(|&&i| i as usize >= count) {
        let has = crate::diag::count(count as u64, "vertex", "vertices");
        return Err(format!("an index is {bad}, but the primitive has {has}"));
    }
    let triangles = match mode {
        Mode::TriangleStrip => (0..indices.len().saturating_sub(2))
            .map(|k| match k % 2 {
                0 => [indices[k], indices[k + 1], indices[k + 2]],
                _ => [indices[k + 1], indices[k], indices[k + 2]],
            })
            .collect(),
        Mode::TriangleFan => (1..indices.len().saturating_sub(1))
            .map(|k| [indices[0], indices[k], indices[k + 1]])
            .collect(),
        _ => indices
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect(),
    };
    Ok((positions, normals, uvs, triangles, tangents))
}

#[cfg(test)]
#[path = "gltf_tests.rs"]
mod tests;
