//! What lowering may keep between two compiles of the same scene (for
//! `watch`): loaded meshes and texture images, keyed by path and content,
//! and the whole geometry
//! (primitives and BVH), keyed by a hash of everything it depends on.

use super::mesh::{self, MeshData};
use super::Geometry;
use crate::check;
use crate::source::files::Stamp;
use crate::source::Files;
use glam::DVec3;
use std::collections::hash_map::DefaultHasher;
use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Meshes and geometry kept from earlier compiles.
#[derive(Default)]
pub struct LowerCache {
    /// A single compile (`ptsc render`): nothing is kept for a next one, so
    /// neither the geometry key nor mesh content hashes are computed.
    one_off: bool,
    meshes: HashMap<PathBuf, CachedMesh>,
    geometry: Option<(u64, Geometry)>,
    /// Mesh files read and parsed so far (a cache hit does not count).
    pub mesh_loads: usize,
    /// Texture images, kept while their files are unchanged.
    pub images: super::image::Images,
    /// BVHs built so far.
    pub bvh_builds: usize,
}

struct CachedMesh {
    /// Length and modification time: when both match, the file is not read.
    stamp: Option<Stamp>,
    /// Hash of the file's bytes: a touched but unchanged file is not re-parsed.
    content: u64,
    /// The stamps of its material libraries when read: a library changed
    /// alone makes the mesh read again.
    libraries: Vec<Option<Stamp>>,
    data: Arc<MeshData>,
}

fn hash_bytes(bytes: &[u8]) -> u64 {
    let mut h = DefaultHasher::new();
    bytes.hash(&mut h);
    h.finish()
}

impl LowerCache {
    /// A cache for a single compile: it keeps no copy of the geometry and
    /// hashes nothing.
    pub fn one_off() -> Self {
        LowerCache {
            one_off: true,
            ..Default::default()
        }
    }

    /// Whether this cache serves a single compile.
    pub fn is_one_off(&self) -> bool {
        self.one_off
    }

    /// The mesh at `path`, parsed once per content.
    pub fn mesh(&mut self, files: &dyn Files, path: &Path) -> Result<Arc<MeshData>, String> {
        let now = files.stamp(path);
        let libraries_unchanged = |c: &CachedMesh| {
            (c.data.libraries.iter())
                .zip(&c.libraries)
                .all(|(p, stamp)| stamp.is_some() && files.stamp(p) == *stamp)
        };
        if let Some(c) = self.meshes.get(path) {
            if c.stamp == now && now.is_some() && libraries_unchanged(c) {
                return Ok(c.data.clone());
            }
        }
        let bytes = mesh::read(files, path)?;
        let parse = |bytes: &[u8]| mesh::parse_with(path, bytes, &mut mesh::library_reader(files));
        if self.one_off {
            self.mesh_loads += 1;
            return parse(&bytes).map(Arc::new);
        }
        let content = hash_bytes(&bytes);
        if let Some(c) = self.meshes.get_mut(path) {
            if c.content == content && libraries_unchanged(c) {
                c.stamp = now;
                return Ok(c.data.clone());
            }
        }
        let data = Arc::new(parse(&bytes)?);
        let libraries = data.libraries.iter().map(|p| files.stamp(p)).collect();
        self.mesh_loads += 1;
        self.meshes.insert(
            path.to_path_buf(),
            CachedMesh {
                stamp: now,
                content,
                libraries,
                data: data.clone(),
            },
        );
        Ok(data)
    }

    /// A hash of everything the geometry depends on: every object's shape,
    /// transform, motion and mesh content, and the shutter. Materials, the
    /// camera (but its shutter), lights and settings are left out, and so are
    /// source spans, so that edits elsewhere in the file keep the geometry.
    pub fn geometry_key(&mut self, files: &dyn Files, scene: &check::Scene) -> u64 {
        let mut h = DefaultHasher::new();
        let number = |x: f64, h: &mut DefaultHasher| x.to_bits().hash(h);
        let points = |ps: &[DVec3], h: &mut DefaultHasher| {
            ps.iter()
                .flat_map(|p| p.to_array())
                .for_each(|x| x.to_bits().hash(h))
        };
        number(scene.camera.shutter.0, &mut h);
        number(scene.camera.shutter.1, &mut h);
        for obj in &scene.objects {
            // A cut-out object's primitives stay out of the BVH's blocks.
            scene.materials[obj.material].is_cut_out().hash(&mut h);
            // A mesh keeps its file's vertex colours where they are read.
            scene.materials[obj.material].vertex_color.hash(&mut h);
            obj.transform
                .to_cols_array()
                .into_iter()
                .for_each(|x| number(x, &mut h));
            points(&[obj.velocity], &mut h);
            std::mem::discriminant(&obj.shape).hash(&mut h);
            match &obj.shape {
                check::Shape::Sphere { center, radius } => {
                    points(&[*center], &mut h);
                    number(*radius, &mut h);
                }
                check::Shape::Disk {
                    center,
                    normal,
                    radius,
                } => {
                    points(&[*center, *normal], &mut h);
                    number(*radius, &mut h);
                }
                check::Shape::Plane { point, normal } => points(&[*point, *normal], &mut h),
                check::Shape::Quad {
                    corner,
                    edge1,
                    edge2,
                } => points(&[*corner, *edge1, *edge2], &mut h),
                check::Shape::Triangle { v } => points(v, &mut h),
                check::Shape::Box { min, max } => points(&[*min, *max], &mut h),
                check::Shape::Round(round) => round.hash_key(&mut h),
                check::Shape::Mesh {
                    path,
                    smooth,
                    group,
                    ..
                } => {
                    path.hash(&mut h);
                    smooth.hash(&mut h);
                    group.hash(&mut h);
                    // The content, through the mesh cache (a missing file hashes
                    // as such and fails later, in lowering, with a diagnostic).
                    match self.mesh(files, path) {
                        Ok(_) => self.meshes[path.as_path()].content.hash(&mut h),
                        Err(e) => e.hash(&mut h),
                    }
                }
            }
        }
        h.finish()
    }

    /// The cached geometry, if it was built for `key`.
    pub fn reuse_geometry(&self, key: u64) -> Option<Geometry> {
        match &self.geometry {
            Some((k, g)) if *k == key => Some(g.clone()),
            _ => None,
        }
    }

    /// Keeps `geometry` for the next compile.
    pub fn store_geometry(&mut self, key: u64, geometry: &Geometry) {
        self.bvh_builds += 1;
        self.geometry = Some((key, geometry.clone()));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::check_str;
    use crate::lower::lower;

    fn lower_text(dir: &Path, text: &str, cache: &mut LowerCache) -> crate::ir::Scene {
        let c = check_str(&dir.join("s.pts"), text);
        lower(
            c.scene.as_ref().unwrap(),
            &|_| {},
            (cache, &crate::source::Disk),
            &mut Default::default(),
        )
        .unwrap()
    }

    #[test]
    fn only_geometry_edits_rebuild_and_only_mesh_edits_reload() {
        let dir = tempfile::tempdir().unwrap();
        let obj = dir.path().join("t.obj");
        std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        let scene = |fov: u32, colour: f32, x: f32| {
            format!(
                "camera {{ position <0, 0, 5> look_at <0, 0, 0> fov {fov} }}\n\
                 background rgb 1\n\
                 mesh {{ file \"t.obj\" material {{ diffuse rgb {colour} }} }}\n\
                 sphere {{ center <{x}, 0, 0> radius 1 }}\n"
            )
        };
        let mut cache = LowerCache::default();
        let a = lower_text(dir.path(), &scene(40, 0.5, 2.0), &mut cache);
        assert_eq!((cache.mesh_loads, cache.bvh_builds), (1, 1));
        // Camera and material edits: nothing reloaded or rebuilt, yet the
        // new material is used.
        let b = lower_text(dir.path(), &scene(30, 0.9, 2.0), &mut cache);
        assert_eq!((cache.mesh_loads, cache.bvh_builds), (1, 1));
        assert!(
            std::sync::Arc::ptr_eq(&a.prims, &b.prims) && std::sync::Arc::ptr_eq(&a.wide, &b.wide),
            "the geometry is shared, not copied"
        );
        // The mesh is object 0; its one triangle is plain (no record).
        let triangle = (0..b.prim_object.len() as u32)
            .find(|&i| b.prim_object[i as usize] == 0)
            .unwrap();
        assert!(triangle as usize >= b.prims.len());
        assert!((a.material_of(triangle).diffuse.x - 0.5).abs() < 1e-6);
        assert!((b.material_of(triangle).diffuse.x - 0.9).abs() < 1e-6);
        // A moved sphere: new BVH, same mesh.
        lower_text(dir.path(), &scene(30, 0.9, 3.0), &mut cache);
        assert_eq!((cache.mesh_loads, cache.bvh_builds), (1, 2));
        // Rewriting the mesh with the same bytes: no reload; new bytes: reload.
        std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        lower_text(dir.path(), &scene(30, 0.9, 3.0), &mut cache);
        assert_eq!((cache.mesh_loads, cache.bvh_builds), (1, 2));
        std::fs::write(&obj, "v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n").unwrap();
        lower_text(dir.path(), &scene(30, 0.9, 3.0), &mut cache);
        assert_eq!((cache.mesh_loads, cache.bvh_builds), (2, 3));
        // A material cut out: its triangle leaves the blocks (a new BVH),
        // and a ray through it passes.
        let cut =
            scene(30, 0.9, 3.0).replace("rgb 0.9 }", "rgb 0.9 opacity 0 opacity_cutoff 0.5 }");
        let c = lower_text(dir.path(), &cut, &mut cache);
        assert_eq!((cache.mesh_loads, cache.bvh_builds), (2, 4));
        assert_eq!(
            c.prims.len(),
            c.prim_object.len(),
            "every primitive has a record"
        );
        let ray = crate::geometry::Ray::new(glam::Vec3::new(0.2, 0.2, 5.0), -glam::Vec3::Z, 0.0);
        assert!(c.intersect(&ray, 1e-4, f32::INFINITY).is_none());
        let d = lower_text(dir.path(), &scene(30, 0.9, 3.0), &mut cache);
        assert_eq!(cache.bvh_builds, 5);
        assert!(d.intersect(&ray, 1e-4, f32::INFINITY).is_some());
    }
}
