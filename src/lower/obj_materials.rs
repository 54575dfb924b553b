//! The materials an OBJ file brings: a mesh statement that names no
//! material takes its file's (`usemtl` groups over `mtllib` libraries,
//! mapped by `mtl.rs`), one object per material group, at the top level of
//! the scene or inside a group; a material in the scene overrides them all,
//! `materials { … }` some by name. What cannot be followed is a warning at
//! the mesh statement.

use super::cache::LowerCache;
use super::mtl;
use super::shapes::{read_mesh, MeshReads};
use crate::check;
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::source::Files;
use std::collections::{BTreeSet, HashMap};
use std::path::PathBuf;

/// Per OBJ file and the materials its statement replaces, the scene's
/// material for each of its material groups: a file placed many times (a
/// loop of copies) maps its materials and warns once.
type Mapped = HashMap<(PathBuf, Vec<(String, usize)>), Vec<(u32, usize)>>;

/// `scene` with each mesh that names no material split by its file's
/// materials (`None`: no mesh brings any); the warnings go to `warnings`.
/// A mesh that cannot be read is left as it is (lowering reports it).
/// The meshes read go to `reads`, for the gathering to use.
pub fn expand(
    scene: &check::Scene,
    (cache, files, reads): (&mut LowerCache, &dyn Files, &mut MeshReads),
    warnings: &mut Diagnostics,
) -> Option<check::Scene> {
    let default = scene.default_material?;
    // Made at the first mesh that brings materials (a scene without one
    // copies nothing): the objects so far, then each kept or split.
    let mut out: Option<check::Scene> = None;
    let mut mapped = Mapped::new();
    for (o, object) in scene.objects.iter().enumerate() {
        let parts = match &object.shape {
            check::Shape::Mesh { group: None, .. } if object.material == default => {
                let target = (&mut out, &mut mapped);
                split(object, (scene, o), (cache, files, reads), warnings, target)
            }
            _ => None,
        };
        match (parts, out.as_mut()) {
            (Some(parts), Some(target)) => target.objects.extend(parts),
            (None, Some(target)) => target.objects.push(object.clone()),
            _ => {}
        }
    }
    out
}

/// `scene` with each mesh inside a group that names no material split by
/// its file's materials (`None`: none brings any), before the groups are
/// placed: a part of a file's material keeps it under every placement,
/// the faces without one take the placement's material as the statement
/// did. The warnings go to `warnings`.
pub fn expand_groups(
    scene: &check::Scene,
    (cache, files, reads): (&mut LowerCache, &dyn Files, &mut MeshReads),
    warnings: &mut Diagnostics,
) -> Option<check::Scene> {
    let mut out: Option<check::Scene> = None;
    let mut mapped = Mapped::new();
    let everything = scene.objects.len();
    for (g, group) in scene.groups.iter().enumerate() {
        let mut objects = Vec::with_capacity(group.objects.len());
        let mut unmaterialled = Vec::with_capacity(group.objects.len());
        let mut changed = false;
        for (k, object) in group.objects.iter().enumerate() {
            let takes_placements = group.unmaterialled.get(k) == Some(&true);
            let parts = match &object.shape {
                check::Shape::Mesh { group: None, .. } if takes_placements => {
                    let target = (&mut out, &mut mapped);
                    let reading = (&mut *cache, files, &mut *reads);
                    split(object, (scene, everything), reading, warnings, target)
                }
                _ => None,
            };
            match parts {
                Some(parts) => {
                    changed = true;
                    for part in parts {
                        unmaterialled.push(part.material == object.material);
                        objects.push(part);
                    }
                }
                None => {
                    unmaterialled.push(takes_placements);
                    objects.push(object.clone());
                }
            }
        }
        if let (true, Some(target)) = (changed, out.as_mut()) {
            target.groups[g].objects = objects;
            target.groups[g].unmaterialled = unmaterialled;
        }
    }
    out
}

/// The material groups of the mesh `object` (the `o`th of `scene`) as
/// objects, their materials added to `out` (made, with the objects before
/// `o`, if not yet) unless `mapped` has them; `None` when its file brings
/// no material.
fn split(
    object: &check::Object,
    (scene, o): (&check::Scene, usize),
    reading: (&mut LowerCache, &dyn Files, &mut MeshReads),
    warnings: &mut Diagnostics,
    (out, mapped): (&mut Option<check::Scene>, &mut Mapped),
) -> Option<Vec<check::Object>> {
    let check::Shape::Mesh {
        path,
        named,
        path_span,
        smooth,
        swaps,
        ..
    } = &object.shape
    else {
        return None;
    };
    let key = (
        path.clone(),
        (swaps.iter())
            .map(|s| (s.name.clone(), s.material))
            .collect(),
    );
    if !mapped.contains_key(&key) {
        let groups = map_file(object, reading, warnings, (scene, o, out))?;
        mapped.insert(key.clone(), groups);
    }
    let groups = mapped.get(&key)?;
    if groups.is_empty() {
        return None;
    }
    let parts = groups.iter().map(|&(group, material)| check::Object {
        shape: check::Shape::Mesh {
            path: path.clone(),
            named: named.clone(),
            path_span: *path_span,
            smooth: *smooth,
            node: None,
            group: Some(group),
            swaps: Vec::new(),
        },
        material,
        ..object.clone()
    });
    Some(parts.collect())
}

/// The material groups of the mesh file of `object` and the scene's
/// material of each (added to `out`, made from `scene`'s first `o` objects
/// if not yet); empty when the file brings no material, `None` when it
/// cannot be read. Warns about its libraries and what its materials ask
/// that ptsc cannot follow.
fn map_file(
    object: &check::Object,
    (cache, files, reads): (&mut LowerCache, &dyn Files, &mut MeshReads),
    warnings: &mut Diagnostics,
    (scene, o, out): (&check::Scene, usize, &mut Option<check::Scene>),
) -> Option<Vec<(u32, usize)>> {
    let check::Shape::Mesh {
        path,
        named,
        path_span,
        swaps,
        ..
    } = &object.shape
    else {
        return None;
    };
    let data = read_mesh(reads, (cache, files), path).ok()?;
    let names = data.materials.iter().map(|m| m.name.as_str());
    super::swaps::warn_unmatched(swaps, names, named, warnings);
    for error in &data.library_errors {
        warnings.push(
            Diagnostic::warning(
                codes::MESH_FILE,
                format!("a material library of `{named}` could not be read in full"),
                *path_span,
            )
            .with_label(error.clone())
            .with_help("faces whose material is not read are grey; put the `.mtl` file beside the OBJ and check it, or give the mesh a `material`"),
        );
    }
    if data.face_material.is_empty() {
        return Some(Vec::new());
    }
    let target = out.get_or_insert_with(|| check::Scene {
        objects: scene.objects[..o].to_vec(),
        ..scene.clone()
    });
    let folder = path.parent().unwrap_or(std::path::Path::new(""));
    let used: BTreeSet<u32> = data.face_material.iter().copied().collect();
    let mut groups = Vec::with_capacity(used.len());
    for group in used {
        let file_material = data.materials.get(group as usize);
        let replaced = file_material.and_then(|m| super::swaps::replacing(swaps, &m.name));
        let material = match (file_material, replaced) {
            (_, Some(scene_material)) => scene_material,
            (Some(m), None) => {
                // Always found (`MeshData::material_libraries`); the OBJ's
                // folder otherwise, as a library beside it.
                let library = (data.material_libraries.get(group as usize))
                    .and_then(|&k| data.libraries.get(k as usize))
                    .cloned()
                    .unwrap_or_else(|| folder.join("?.mtl"));
                let mapped = mtl::material(m, &library, *path_span);
                for note in &mapped.left_out {
                    warnings.push(
                        Diagnostic::warning(
                            codes::NO_EFFECT,
                            format!("material `{}` of `{named}`: {note}", m.name),
                            *path_span,
                        )
                        .with_label("left out")
                        .with_help("replace it (`materials { \"Name\" my_material }`) or give the mesh a `material`"),
                    );
                }
                target.materials.push(mapped.material);
                target.materials.len() - 1
            }
            // Faces without a `usemtl`: the default grey.
            (None, None) => object.material,
        };
        groups.push((group, material));
    }
    Some(groups)
}
