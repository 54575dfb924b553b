//! Placing a glTF file's scene: a mesh statement naming a `.gltf` or
//! `.glb` file becomes one object per primitive of each node that places a
//! mesh, at the statement's transform times the node's. A mesh placed by
//! several nodes (at the scene's top level) is stored once: its primitives
//! become a group and each node a placement of it, which lowering shares
//! (`instances.rs`). The file's materials are mapped once per file unless
//! the statement gives a material; what the file asks that ptsc does not
//! follow is one warning each at the statement. Images held inside the
//! file are served to lowering from memory (`Embedded`).

use super::cache::LowerCache;
use super::mesh_data::{is_gltf, FileScene, MeshData, Placed as PlacedNode, Placing};
use super::shapes::{read_mesh, MeshReads};
use crate::check::{self, Group, Instance, Object};
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::source::files::Stamp;
use crate::source::{Files, ReadError};
use crate::span::Span;
use glam::DMat4;
use std::collections::HashMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The scene with its glTF mesh statements placed (`None`: it has none
/// that could be read), and the images inside those files.
pub struct Placed {
    /// The scene with the files' objects, groups and placements.
    pub scene: Option<check::Scene>,
    /// The images held inside the files, by the path their textures read.
    pub embedded: Embedded,
    /// A `node` the file does not have, a default scene without triangles.
    pub errors: Diagnostics,
}

/// `scene` with every readable glTF mesh statement replaced by the file's
/// objects (and groups for its shared meshes); the notes on each file are
/// warnings in `warnings`. A file that cannot be read is left as it is:
/// the gathering reports it.
pub fn place(
    scene: &check::Scene,
    (cache, files, reads): (&mut LowerCache, &dyn Files, &mut MeshReads),
    warnings: &mut Diagnostics,
) -> Placed {
    let mut placing = Gathering {
        warned: Default::default(),
        out: None,
        materials: HashMap::new(),
        embedded: HashMap::new(),
    };
    let mut errors = Diagnostics::new();
    let gltf = |o: &Object| matches!(&o.shape, check::Shape::Mesh { path, group: None, .. } if is_gltf(path));
    let mut read = |path: &Path| read_mesh(reads, (&mut *cache, files), path).ok();
    for (o, object) in scene.objects.iter().enumerate() {
        let data = gltf(object)
            .then(|| object_path(object))
            .and_then(&mut read);
        let Some(data) = data.filter(|d| d.scene.is_some()) else {
            if let Some(out) = placing.out.as_mut() {
                out.objects.push(object.clone());
            }
            continue;
        };
        let out = placing.out.get_or_insert_with(|| check::Scene {
            objects: scene.objects[..o].to_vec(),
            ..scene.clone()
        });
        let Some((nodes, lights)) = placements(object, &data, &mut errors) else {
            continue;
        };
        for (light, m) in &lights {
            let light = light.placed(&(object.transform * *m));
            out.lights.push((light, object.span));
        }
        let materials = placing.materials.entry(object_path(object).to_path_buf());
        let first = matches!(materials, std::collections::hash_map::Entry::Vacant(_));
        let given = Some(object.material) != out.default_material;
        warn(
            object,
            &data,
            (first, !given, &mut placing.warned),
            warnings,
        );
        let mapped = materials.or_insert_with(|| map_materials(&data, object.span, out));
        let mapped = swapped(mapped, object, &data, warnings);
        place_top_level(object, (&data, &nodes), &mapped, out);
        placing
            .embedded
            .extend(embedded_of(&data, object_path(object)));
    }
    for g in 0..scene.groups.len() {
        for (k, object) in scene.groups[g].objects.iter().enumerate() {
            let Some(data) = gltf(object)
                .then(|| object_path(object))
                .and_then(&mut read)
            else {
                continue;
            };
            if data.scene.is_none() {
                continue;
            }
            let out = placing.out.get_or_insert_with(|| scene.clone());
            let Some((nodes, lights)) = placements(object, &data, &mut errors) else {
                out.groups[g].objects[k].shape = placeholder();
                continue;
            };
            // A group's lights are placed by the checker, before files are
            // read: a file's lights inside a group are not placed.
            if let (false, check::Shape::Mesh { path_span, .. }) =
                (lights.is_empty(), &object.shape)
            {
                warnings.push(
                    Diagnostic::warning(
                        codes::NO_EFFECT,
                        format!("the {} lights of `{}` are not placed: it is inside a group", lights.len(), object_named(object)),
                        *path_span,
                    )
                    .with_label("lights left out")
                    .with_help("place the file outside the group for its lights, or write them in the scene"),
                );
            }
            let path = object_path(object).to_path_buf();
            let first = !placing.materials.contains_key(&path);
            let unmaterialled = scene.groups[g].unmaterialled.get(k) == Some(&true);
            warn(
                object,
                &data,
                (first, unmaterialled, &mut placing.warned),
                warnings,
            );
            if first {
                let mapped = map_materials(&data, object.span, out);
                placing.materials.insert(path.clone(), mapped);
            }
            let mapped = swapped(&placing.materials[&path], object, &data, warnings);
            place_in_group(out, (g, k), (&data, &nodes, &mapped), unmaterialled);
            placing.embedded.extend(embedded_of(&data, &path));
        }
    }
    if let Some(out) = placing.out.as_mut() {
        for group in &mut out.groups {
            // Emptied slots (a statement replaced by its file's objects).
            let keep: Vec<bool> = (group.objects.iter()).map(|o| !is_placeholder(o)).collect();
            let mut flags = keep.iter();
            group.objects.retain(|_| *flags.next().unwrap_or(&true));
            let mut flags = keep.iter();
            group
                .unmaterialled
                .retain(|_| *flags.next().unwrap_or(&true));
        }
    }
    Placed {
        scene: placing.out,
        embedded: Embedded {
            held: placing.embedded,
        },
        errors,
    }
}

/// The nodes the statement `object` places of its file: the default
/// scene's, or its `node`'s subtree; `None`, with an error, when there are
/// none.
fn placements(object: &Object, data: &MeshData, errors: &mut Diagnostics) -> Option<Placing> {
    let (
        Some(scene),
        check::Shape::Mesh {
            named,
            path_span,
            node,
            ..
        },
    ) = (&data.scene, &object.shape)
    else {
        return None;
    };
    let name = node.as_ref().map(|(name, _)| name.as_str());
    let span = node.as_ref().map_or(*path_span, |(_, span)| *span);
    let result = scene.placements(name);
    match result {
        Ok(placed) => Some(placed),
        Err(e) => {
            errors.push(
                Diagnostic::error(codes::MESH_FILE, format!("cannot place `{named}`"), span)
                    .with_label(e)
                    .with_help(match name {
                        Some(_) => "name a node of the file that holds meshes (`node \"Name\"`), or leave `node` out to place its default scene",
                        None => "a glTF scene's nodes form a tree of meshes; the Khronos glTF validator tells what else is wrong with the file, or `node \"Name\"` places one part of it",
                    }),
            );
            None
        }
    }
}

/// What placing gathers.
struct Gathering {
    /// The files whose materials' notes were given (once, at the first
    /// statement that uses the file's materials).
    warned: std::collections::HashSet<PathBuf>,
    out: Option<check::Scene>,
    /// Per file, the scene's index of each of its materials.
    materials: HashMap<PathBuf, Vec<usize>>,
    embedded: HashMap<PathBuf, (Arc<Vec<u8>>, PathBuf)>,
}

/// The file a mesh object reads.
fn object_path(object: &Object) -> &Path {
    match &object.shape {
        check::Shape::Mesh { path, .. } => path,
        _ => Path::new(""),
    }
}

/// The file a mesh object reads, as the scene writes it (for messages).
fn object_named(object: &Object) -> &str {
    match &object.shape {
        check::Shape::Mesh { named, .. } => named,
        _ => "",
    }
}

/// The file's notes as warnings at the statement: its general ones at the
/// file's `first` statement, its materials' at the first that uses them
/// (a statement that gives a material does not), listed in `warned`.
fn warn(
    object: &Object,
    data: &MeshData,
    (first, uses_materials, warned): (bool, bool, &mut std::collections::HashSet<PathBuf>),
    warnings: &mut Diagnostics,
) {
    let (
        Some(scene),
        check::Shape::Mesh {
            path,
            named,
            path_span,
            ..
        },
    ) = (&data.scene, &object.shape)
    else {
        return;
    };
    let materials = uses_materials && warned.insert(path.clone());
    let general = scene.notes.iter().filter(|_| first);
    for note in general.chain(scene.material_notes.iter().filter(|_| materials)) {
        warnings.push(
            Diagnostic::warning(
                codes::NO_EFFECT,
                format!("`{named}`: {note}"),
                *path_span,
            )
            .with_label("not followed")
            .with_help(
                "the rest of the file is placed; see docs/language.md, \"Models from glTF files\"",
            ),
        );
    }
}

/// The file's materials added to `out` (their spans the statement's).
fn map_materials(data: &MeshData, span: Span, out: &mut check::Scene) -> Vec<usize> {
    let Some(scene) = &data.scene else {
        return Vec::new();
    };
    (scene.materials.iter())
        .map(|m| {
            let mut m = m.clone();
            m.span = span;
            for (_, t) in &mut m.textures {
                t.span = span;
                if let check::TextureKind::Image { path_span, .. } = &mut t.kind {
                    *path_span = span;
                }
            }
            out.materials.push(m);
            out.materials.len() - 1
        })
        .collect()
}

/// The scene's materials of the file's (`mapped`) with those the statement
/// `object` replaces by name (`materials { … }`); a name the file does not
/// have is a warning.
fn swapped(
    mapped: &[usize],
    object: &Object,
    data: &MeshData,
    warnings: &mut Diagnostics,
) -> Vec<usize> {
    let (Some(scene), check::Shape::Mesh { swaps, named, .. }) = (&data.scene, &object.shape)
    else {
        return mapped.to_vec();
    };
    if swaps.is_empty() {
        return mapped.to_vec();
    }
    let names = scene.material_names.iter().map(String::as_str);
    super::swaps::warn_unmatched(swaps, names, named, warnings);
    (mapped.iter().zip(&scene.material_names))
        .map(|(&m, name)| super::swaps::replacing(swaps, name).unwrap_or(m))
        .collect()
}

/// The objects of the parts of `mesh`, in the mesh's frame, with their
/// materials: the statement's `given`, else the file's, else `default`.
fn parts_of(
    object: &Object,
    (scene, mesh): (&FileScene, u32),
    mapped: &[usize],
    given: Option<usize>,
) -> Vec<Object> {
    let check::Shape::Mesh {
        path,
        named,
        path_span,
        smooth,
        ..
    } = &object.shape
    else {
        return Vec::new();
    };
    (scene.parts.iter().enumerate())
        .filter(|(_, p)| p.mesh == mesh)
        .map(|(k, part)| Object {
            shape: check::Shape::Mesh {
                path: path.clone(),
                named: named.clone(),
                path_span: *path_span,
                smooth: *smooth,
                node: None,
                group: Some(k as u32),
                swaps: Vec::new(),
            },
            material: given
                .or_else(|| part.material.and_then(|m| mapped.get(m as usize).copied()))
                .unwrap_or(object.material),
            transform: DMat4::IDENTITY,
            velocity: object.velocity,
            span: object.span,
        })
        .collect()
}

/// Places the file of the top-level `object` into `out`: a mesh placed
/// once as objects, a mesh placed by several nodes as a group placed by
/// each.
fn place_top_level(
    object: &Object,
    (data, nodes): (&MeshData, &[PlacedNode]),
    mapped: &[usize],
    out: &mut check::Scene,
) {
    let Some(scene) = &data.scene else {
        return;
    };
    let given = (Some(object.material) != out.default_material).then_some(object.material);
    let mut uses: HashMap<u32, usize> = HashMap::new();
    for p in nodes {
        *uses.entry(p.mesh).or_default() += 1;
    }
    let mut groups: HashMap<u32, usize> = HashMap::new();
    for placed in nodes {
        let transform = object.transform * placed.transform;
        if uses[&placed.mesh] < 2 {
            let parts = parts_of(object, (scene, placed.mesh), mapped, given);
            out.objects
                .extend(parts.into_iter().map(|o| Object { transform, ..o }));
            continue;
        }
        let group = *groups.entry(placed.mesh).or_insert_with(|| {
            let objects = parts_of(object, (scene, placed.mesh), mapped, given);
            out.groups.push(Group {
                name: format!("{}#{}", object_path(object).display(), placed.mesh),
                unmaterialled: vec![false; objects.len()],
                placed_objects: objects.len() as u64,
                objects,
                instances: Vec::new(),
                lights: Vec::new(),
                placed_lights: 0,
                span: object.span,
            });
            out.groups.len() - 1
        });
        out.instances.push(Instance {
            group,
            transform,
            material: None,
            velocity: object.velocity,
            span: object.span,
        });
    }
}

/// Places the file of object `k` of group `g` into that group as objects
/// (each node's copy of its mesh); the statement's slot is left as a
/// placeholder for `place` to remove.
fn place_in_group(
    out: &mut check::Scene,
    (g, k): (usize, usize),
    (data, nodes, mapped): (&MeshData, &[PlacedNode], &[usize]),
    unmaterialled: bool,
) {
    let Some(scene) = &data.scene else {
        return;
    };
    let object = out.groups[g].objects[k].clone();
    let given = (!unmaterialled).then_some(object.material);
    for placed in nodes {
        let parts = parts_of(&object, (scene, placed.mesh), mapped, given);
        for part in parts {
            // A part without a material of its own takes the instance's.
            let takes_instances = unmaterialled && part.material == object.material;
            let group = &mut out.groups[g];
            group.objects.push(Object {
                transform: object.transform * placed.transform,
                ..part
            });
            group.unmaterialled.push(takes_instances);
        }
    }
    out.groups[g].objects[k].shape = placeholder();
}

/// The shape a placed statement's slot holds until removed.
fn placeholder() -> check::Shape {
    check::Shape::Mesh {
        path: PathBuf::new(),
        named: String::new(),
        path_span: Span::default(),
        smooth: false,
        node: None,
        group: Some(u32::MAX),
        swaps: Vec::new(),
    }
}

/// Whether `object` is a removed statement's slot.
fn is_placeholder(object: &Object) -> bool {
    object.shape == placeholder()
}

/// The images inside the file at `path`, by the paths their textures read.
fn embedded_of<'a>(
    data: &'a MeshData,
    path: &'a Path,
) -> impl Iterator<Item = (PathBuf, (Arc<Vec<u8>>, PathBuf))> + 'a {
    (data.scene.iter().flat_map(|s| &s.embedded))
        .map(move |(inside, bytes)| (inside.clone(), (bytes.clone(), path.to_path_buf())))
}

/// The scene's files with the images held inside glTF files served from
/// memory (a file's stamp is the glTF file's: it changes with it).
pub struct Embedded {
    held: HashMap<PathBuf, (Arc<Vec<u8>>, PathBuf)>,
}

impl Embedded {
    /// Whether no image is held.
    pub fn is_empty(&self) -> bool {
        self.held.is_empty()
    }

    /// `files` with the held images over it.
    pub fn over<'a>(&'a self, files: &'a dyn Files) -> Over<'a> {
        Over {
            held: &self.held,
            files,
        }
    }
}

/// [`Embedded`] over the scene's files.
pub struct Over<'a> {
    held: &'a HashMap<PathBuf, (Arc<Vec<u8>>, PathBuf)>,
    files: &'a dyn Files,
}

impl Files for Over<'_> {
    fn read(&self, path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
        match self.held.get(path) {
            Some((bytes, _)) if bytes.len() as u64 > limit => Err(ReadError::TooLarge {
                limit,
                size: bytes.len() as u64,
            }),
            Some((bytes, _)) => Ok(bytes.to_vec()),
            None => self.files.read(path, limit),
        }
    }

    fn open(&self, path: &Path, limit: u64) -> Result<Box<dyn Read + '_>, ReadError> {
        match self.held.get(path) {
            Some(_) => Ok(Box::new(std::io::Cursor::new(self.read(path, limit)?))),
            None => self.files.open(path, limit),
        }
    }

    fn exists(&self, path: &Path) -> Result<(), ReadError> {
        match self.held.contains_key(path) {
            true => Ok(()),
            false => self.files.exists(path),
        }
    }

    fn canonical(&self, path: &Path) -> PathBuf {
        match self.held.contains_key(path) {
            true => path.to_path_buf(),
            false => self.files.canonical(path),
        }
    }

    fn stamp(&self, path: &Path) -> Option<Stamp> {
        match self.held.get(path) {
            Some((_, file)) => self.files.stamp(file),
            None => self.files.stamp(path),
        }
    }
}
