//! What a scene with errors still names for lowering to read: its
//! materials (and their images), its environment map and its mesh files.
//! The check builds no scene then, so lowering does not run; the compile
//! driver reads these files all the same (`lower::validate_files`), so that
//! a corrupt image or mesh is reported beside the scene's other mistakes,
//! not only once they are fixed.

use super::scene::{Environment, Group, Material, Object, Shape};
use crate::span::Span;
use std::path::PathBuf;

/// The files a scene with errors names, as far as its check went.
#[derive(Debug, Default)]
pub struct Unbuilt {
    /// Its materials, whose image textures lowering would read.
    pub materials: Vec<Material>,
    /// Its environment map.
    pub environment: Option<Environment>,
    /// Its mesh files: each resolved path, the name as the scene writes it,
    /// and where it is written; once per place.
    pub meshes: Vec<(PathBuf, String, Span)>,
}

impl Unbuilt {
    /// Takes what a checked scene names for lowering to read (it will not
    /// be built): its `materials`, its `environment`, the mesh files of
    /// its `objects` and of its `groups`' objects.
    pub(super) fn take(
        materials: &mut Vec<Material>,
        environment: &mut Option<Environment>,
        (objects, groups): (&[Object], &[Group]),
    ) -> Unbuilt {
        let grouped = groups.iter().flat_map(|g| g.objects.iter());
        let mut meshes: Vec<(PathBuf, String, Span)> = (objects.iter().chain(grouped))
            .filter_map(mesh_file)
            .collect();
        meshes.sort_by_key(|(_, _, span)| (span.file.0, span.start));
        meshes.dedup_by_key(|(_, _, span)| *span);
        Unbuilt {
            materials: std::mem::take(materials),
            environment: environment.take(),
            meshes,
        }
    }
}

/// The mesh file `object` is read from, if it is a mesh.
fn mesh_file(object: &Object) -> Option<(PathBuf, String, Span)> {
    match &object.shape {
        Shape::Mesh {
            path,
            named,
            path_span,
            ..
        } => Some((path.clone(), named.clone(), *path_span)),
        _ => None,
    }
}
