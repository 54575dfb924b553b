//! Checked objects → the renderer's primitives, with every problem a shape
//! can have once its transforms are applied: a round shape under an uneven
//! scale, a mesh file that cannot be read or has no area, an object beyond
//! f32's range or too small for it. Gathering finds them all and builds
//! nothing: `check` runs it as `render` does (the BVH is built after, by
//! [`super::geometry`]).

use super::cache::LowerCache;
use super::collect::{Collected, PlainMesh};
use super::mesh::MeshData;
use crate::check;
use crate::check::domain::{self, unit_f32, MAX_MAGNITUDE, MIN_SIZE};
use crate::diag::codes;
use crate::diag::{Diagnostic, Diagnostics};
use crate::geometry::round::similarity_scale;
use crate::geometry::shape::Shape;
use crate::geometry::texcoord;
use crate::geometry::Aabb;
use crate::ir::Prim;
use crate::source::Files;
use glam::{DMat4, DVec3, Vec2, Vec3, Vec4};
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

/// The primitives of a list of objects (the scene's, or a group's in its
/// frame), before the BVH orders them.
#[derive(Debug, Default)]
pub struct Gathered {
    /// The primitives.
    pub prims: Collected,
    /// Vertex normals of mesh triangles with attributes (zero: flat).
    pub normals: Vec<[Vec3; 3]>,
    /// Their vertex texture coordinates, by the same index.
    pub uvs: Vec<[Vec2; 3]>,
    /// Their corner tangents for normal maps, by the same index (see
    /// [`crate::ir::Scene::tangents`]).
    pub tangents: Vec<[Vec4; 3]>,
    /// Their vertex colours, by the same index (white where none).
    pub colors: Vec<[Vec3; 3]>,
    /// The mesh objects whose files have no texture coordinates.
    pub meshes_without_uvs: Vec<u32>,
    /// The shutter interval the primitives are bounded over.
    pub shutter: (f32, f32),
}

impl Gathered {
    /// Adds the vertex attributes of a mesh triangle of vertices `t` (in
    /// the file's order) from its mesh's `normals` and `uvs` (either may be
    /// empty) and its corner `tangents`; returns their index, or
    /// `u32::MAX` when the mesh has none.
    fn attributes(
        &mut self,
        t: [u32; 3],
        (normals, uvs, colors): (&[Vec3], &[glam::Vec2], &[Vec3]),
        tangents: Option<[Vec4; 3]>,
    ) -> u32 {
        if normals.is_empty() && uvs.is_empty() && colors.is_empty() && tangents.is_none() {
            return u32::MAX;
        }
        if !colors.is_empty() {
            (self.colors).resize(self.normals.len(), [Vec3::ONE; 3]);
            self.colors.push(t.map(|i| colors[i as usize]));
        }
        if let Some(tangents) = tangents {
            // Earlier triangles without tangents: none (w = 0).
            (self.tangents).resize(self.normals.len(), [Vec4::ZERO; 3]);
            self.tangents.push(tangents);
        }
        // A zero normal is flat shading.
        self.normals.push(match normals.is_empty() {
            false => t.map(|i| normals[i as usize]),
            true => [Vec3::ZERO; 3],
        });
        if !uvs.is_empty() {
            // Earlier triangles without UVs keep their barycentrics.
            (self.uvs).resize(self.normals.len() - 1, texcoord::TRIANGLE_DEFAULT);
            self.uvs.push(t.map(|i| uvs[i as usize]));
        }
        self.normals.len() as u32 - 1
    }

    /// The bounds of every bounded primitive over the shutter.
    pub fn bounds(&self) -> Aabb {
        (0..self.prims.len() as u32)
            .map(|i| self.prims.bounds(i, self.shutter))
            .fold(Aabb::EMPTY, Aabb::union)
    }
}

/// The most primitives a scene (or a group's prototype) may make, a mesh
/// triangle counting one: about 4 GB once built (docs/language.md, "Limits").
pub const MAX_PRIMITIVES: usize = 50_000_000;

/// What one object's shapes make: where they go and the objects out of
/// range or too small so far (one diagnostic each, for the first).
struct Gathering<'a> {
    out: Gathered,
    out_of_range: Option<usize>,
    too_small: Option<usize>,
    /// The primitives the objects make (counted before any is made).
    wanted: u64,
    /// The meshes read so far by path: an object copied by many
    /// placements reads its file once.
    meshes: MeshReads,
    /// Whether each object's material reads vertex colours (empty: none
    /// does): an OBJ's or PLY's colours are kept only for those.
    colored_objects: Vec<bool>,
    /// The world vertices of meshes split by their materials, by path and
    /// transform: one copy for all the groups.
    positions: HashMap<(PathBuf, [u64; 16]), Arc<Vec<Vec3>>>,
    diags: Diagnostics,
    cache: &'a mut LowerCache,
    files: &'a dyn Files,
}

/// Mesh files read in one compile, by path: each is read once, whoever
/// asks first (the split by an OBJ's materials, then the gathering).
pub type MeshReads = HashMap<PathBuf, Result<Arc<MeshData>, String>>;

/// The mesh at `path` from `reads`, read through `cache` the first time.
/// The error for the mesh file at `path` (written `named` at `span`)
/// that cannot be read or parsed (`why`): lowering's, and the compile
/// driver's for a scene with other errors, word for word.
pub fn unloadable_mesh(
    (path, named, span): (&std::path::Path, &str, crate::span::Span),
    why: String,
) -> Diagnostic {
    Diagnostic::error(codes::MESH_FILE, format!("cannot load mesh `{named}`"), span)
        .with_label(why)
        .with_help(match super::mesh_data::is_gltf(path) {
            true => "ptsc reads glTF 2.0 (a .gltf with its buffers beside it or inside it, or a .glb); the Khronos glTF validator tells what else is wrong with the file",
            false => "meshes are OBJ, PLY or glTF files with at least one triangle",
        })
}

pub fn read_mesh(
    reads: &mut MeshReads,
    (cache, files): (&mut LowerCache, &dyn Files),
    path: &std::path::Path,
) -> Result<Arc<MeshData>, String> {
    if let Some(read) = reads.get(path) {
        return read.clone();
    }
    let read = cache.mesh(files, path);
    reads.insert(path.to_path_buf(), read.clone());
    read
}

/// The primitives of `objects` over the shutter interval, or every problem
/// they have; the meshes already in `reads` are not read again.
pub fn gather(
    objects: &[check::Object],
    (t0, t1): (f64, f64),
    (cache, files): (&mut LowerCache, &dyn Files),
    reads: MeshReads,
    (cut_objects, colored_objects): (Vec<bool>, Vec<bool>),
) -> Result<Gathered, Diagnostics> {
    let mut g = Gathering {
        out: Gathered {
            shutter: (t0 as f32, t1 as f32),
            ..Gathered::default()
        },
        out_of_range: None,
        too_small: None,
        wanted: 0,
        meshes: reads,
        colored_objects,
        positions: HashMap::new(),
        diags: Diagnostics::new(),
        cache,
        files,
    };
    // Counted before anything is made: past the limit, nothing is.
    if let Some(o) = g.count(objects) {
        g.diags.push(too_many(objects[o].span, g.wanted));
        return Err(g.diags);
    }
    g.out.prims.cut_objects = cut_objects;
    for (o, obj) in objects.iter().enumerate() {
        g.object(o, obj);
    }
    if let Some(o) = g.out_of_range {
        g.diags.push(out_of_range(objects[o].span));
    }
    if let Some(o) = g.too_small {
        g.diags.push(
            Diagnostic::error(
                codes::DEGENERATE,
                "this object is too small for the renderer's 32-bit floats",
                objects[o].span,
            )
            .with_label("its area rounds to zero")
            .with_help(format!(
                "give it sizes of at least {} after its transforms",
                domain::number(MIN_SIZE)
            )),
        );
    }
    if g.diags.has_errors() {
        return Err(g.diags);
    }
    Ok(g.out)
}

/// The error of a scene making more than [`MAX_PRIMITIVES`] (`wanted`),
/// at the object that crossed the limit.
fn too_many(span: crate::span::Span, wanted: u64) -> Diagnostic {
    Diagnostic::error(
        codes::TOO_MANY_PRIMITIVES,
        format!(
            "the scene makes {} primitives (a mesh triangle counts one), more than the {} the renderer holds",
            crate::diag::group_digits(wanted),
            crate::diag::group_digits(MAX_PRIMITIVES as u64)
        ),
        span,
    )
    .with_label("the limit is crossed here")
    .with_help("a group placed many times is shared, not copied, except its planes and emissive objects: keep large meshes out of those, or use fewer copies")
}

/// The error of an object that leaves f32's range after its transforms.
fn out_of_range(span: crate::span::Span) -> Diagnostic {
    Diagnostic::error(
        codes::OUT_OF_RANGE,
        format!(
            "this object reaches beyond ±{} after its transforms and motion",
            domain::number(MAX_MAGNITUDE)
        ),
        span,
    )
    .with_label(format!("coordinates beyond ±{}", domain::number(MAX_MAGNITUDE)))
    .with_help("the renderer computes in 32-bit floats; check the sizes, transforms and velocity (times the shutter) for overflow")
}

impl Gathering<'_> {
    /// Adds primitive `shape` of object `o`, moving at `velocity`.
    fn push(&mut self, o: usize, shape: Shape, velocity: Vec3) {
        match representable(&shape, velocity, self.out.shutter) {
            Representable::Yes => {}
            Representable::OutOfRange => {
                self.out_of_range.get_or_insert(o);
            }
            Representable::TooSmall => {
                self.too_small.get_or_insert(o);
            }
        }
        self.out.prims.push(Prim { shape, velocity }, o as u32);
    }

    /// The vertices `positions` of the mesh at `path` under `m`: computed
    /// once for the material groups of one statement (`shared`), each a
    /// part of the same mesh.
    fn world_positions(
        &mut self,
        path: &std::path::Path,
        m: &glam::DMat4,
        positions: &[Vec3],
        shared: bool,
    ) -> Arc<Vec<Vec3>> {
        let key = (path.to_path_buf(), m.to_cols_array().map(f64::to_bits));
        if let Some(pos) = self.positions.get(&key).filter(|_| shared) {
            return pos.clone();
        }
        let pos: Arc<Vec<Vec3>> = Arc::new(
            (positions.iter())
                .map(|p| m.transform_point3(p.as_dvec3()).as_vec3())
                .collect(),
        );
        if shared {
            self.positions.insert(key, pos.clone());
        }
        pos
    }

    /// The mesh at `path`, read once per compile.
    fn read_mesh(&mut self, path: &std::path::Path) -> Result<Arc<MeshData>, String> {
        read_mesh(&mut self.meshes, (self.cache, self.files), path)
    }

    /// Counts the primitives `objects` make into `wanted` (a mesh its
    /// triangles, a box its six faces); the first object past
    /// [`MAX_PRIMITIVES`], if one is.
    fn count(&mut self, objects: &[check::Object]) -> Option<usize> {
        let mut first_past = None;
        for (o, obj) in objects.iter().enumerate() {
            self.wanted += match &obj.shape {
                check::Shape::Mesh { path, group, .. } => {
                    (self.read_mesh(path)).map_or(0, |d| d.count(*group) as u64)
                }
                check::Shape::Box { .. } => 6,
                _ => 1,
            };
            if self.wanted > MAX_PRIMITIVES as u64 {
                first_past.get_or_insert(o);
            }
        }
        first_past
    }

    /// Adds the primitives of object `o`.
    fn object(&mut self, o: usize, obj: &check::Object) {
        let m = obj.transform;
        let pt = |p: DVec3| m.transform_point3(p).as_vec3();
        let vec = |v: DVec3| m.transform_vector3(v).as_vec3();
        let velocity = obj.velocity.as_vec3();
        // A mirroring transform turns `e1 × e2` inwards: quads and
        // triangles keep their outward side with their edges swapped
        // (`Shape::own_uv`).
        let flip = m.determinant() < 0.0;
        let mut shapes: Vec<Shape> = Vec::new();
        match &obj.shape {
            check::Shape::Mesh {
                path,
                named,
                path_span,
                smooth,
                group,
                ..
            } => return self.mesh(o, obj, (path, named, *path_span), (*smooth, *group)),
            check::Shape::Plane { point, normal } => shapes.push(Shape::Plane {
                point: pt(*point),
                normal: unit_f32(m.inverse().transpose().transform_vector3(*normal)),
            }),
            check::Shape::Quad {
                corner,
                edge1,
                edge2,
            } => shapes.push(parallelogram(pt(*corner), vec(*edge1), vec(*edge2), flip)),
            check::Shape::Triangle { v } => {
                let p0 = pt(v[0]);
                let (e1, e2) = (pt(v[1]) - p0, pt(v[2]) - p0);
                // As a parallelogram: swapped under a mirror (see `flip`).
                let (e1, e2) = if flip { (e2, e1) } else { (e1, e2) };
                shapes.push(Shape::Triangle {
                    p0,
                    e1,
                    e2,
                    attributes: u32::MAX,
                    swapped: flip,
                })
            }
            check::Shape::Box { min, max } => {
                for (c, a, b) in box_faces(*min, *max) {
                    shapes.push(parallelogram(pt(c), vec(a), vec(b), flip));
                }
            }
            check::Shape::Round(round) => {
                if round.place(&m, &mut shapes).is_err() {
                    self.diags.push(check::non_uniform(obj.span, round.name()));
                }
            }
            round => match similarity_scale(&m) {
                Some(s) => round_shapes(round, &m, s, &mut shapes),
                None => {
                    let what = obj.shape.round_kind().unwrap_or("shape");
                    self.diags.push(check::non_uniform(obj.span, what));
                }
            },
        }
        for shape in shapes {
            self.push(o, shape, velocity);
        }
    }

    /// Adds the triangles of mesh object `o` read from `path` (written
    /// `named` at `path_span`), with their vertex normals when `smooth`.
    fn mesh(
        &mut self,
        o: usize,
        obj: &check::Object,
        (path, named, path_span): (&std::path::Path, &str, crate::span::Span),
        (smooth, group): (bool, Option<u32>),
    ) {
        let data = match self.read_mesh(path) {
            Ok(d) => d,
            Err(e) => {
                self.diags
                    .push(unloadable_mesh((path, named, path_span), e));
                return;
            }
        };
        let m = obj.transform;
        let velocity = obj.velocity.as_vec3();
        let flip = m.determinant() < 0.0;
        let view = data.view(group);
        let shared = group.is_some() && !view.part;
        let pos = self.world_positions(path, &m, view.positions, shared);
        // The vertices' box, where the motion takes it: as the other shapes.
        let reach = pos.iter().fold(Aabb::EMPTY, |b, p| b.grow(*p));
        if !within_domain(reach, velocity, self.out.shutter) {
            self.out_of_range.get_or_insert(o);
        }
        let nm = m.inverse().transpose();
        let use_normals = smooth && !view.normals.is_empty();
        let vnormals: Vec<Vec3> = match use_normals {
            true => (view.normals.iter())
                .map(|n| unit_f32(nm.transform_vector3(n.as_dvec3())))
                .collect(),
            false => Vec::new(),
        };
        let use_uvs = !view.uvs.is_empty();
        // Tangents move as the surface's directions; a mirror turns the
        // bitangent's side.
        let side = if flip { -1.0 } else { 1.0 };
        let tangent = |c: Vec4| match c.w {
            0.0 => Vec4::ZERO,
            w => unit_f32(m.transform_vector3(c.truncate().as_dvec3())).extend(w * side),
        };
        let use_tangents = view.tangents.len() == view.triangles.len() && !view.tangents.is_empty();
        if !use_uvs {
            self.out.meshes_without_uvs.push(o as u32);
        }
        // A static mesh without vertex attributes keeps its triangles
        // as vertex indices: most of them will never need a record.
        // A glTF's materials ask for its colours themselves.
        let wanted = self.colored_objects.get(o) == Some(&true) || super::mesh_data::is_gltf(path);
        let use_colors =
            wanted && view.colors.len() == view.positions.len() && !view.colors.is_empty();
        let colors = if use_colors { view.colors } else { &[] };
        let plain =
            !use_normals && !use_uvs && !use_tangents && !use_colors && velocity == Vec3::ZERO;
        let mut kept: Vec<[u32; 3]> = Vec::new();
        if plain {
            kept.reserve_exact(view.triangles.len());
        } else {
            self.out.prims.records.reserve(view.triangles.len());
        }
        let mut degenerate = 0usize;
        let mut total = 0usize;
        for (k, t) in view.triangles.iter().enumerate() {
            total += 1;
            // Stored wound as rendered; vertex attributes stay in the
            // file's order (`Shape::own_uv` reads them so).
            let [a, b, c] = if flip { [t[0], t[2], t[1]] } else { *t };
            let p0 = pos[a as usize];
            let (e1, e2) = (pos[b as usize] - p0, pos[c as usize] - p0);
            if e1.cross(e2).length_squared() == 0.0 {
                degenerate += 1;
                continue;
            }
            if plain {
                kept.push([a, b, c]);
                continue;
            }
            let tangents = (view.tangents.get(k))
                .filter(|_| use_tangents)
                .map(|c| c.map(tangent));
            let attributes = self
                .out
                .attributes(*t, (&vnormals, view.uvs, colors), tangents);
            let shape = Shape::Triangle {
                p0,
                e1,
                e2,
                attributes,
                swapped: flip,
            };
            self.out.prims.push(Prim { shape, velocity }, o as u32);
        }
        if degenerate == total {
            self.diags.push(
                Diagnostic::error(
                    codes::DEGENERATE,
                    "every triangle of this mesh has zero area",
                    path_span,
                )
                .with_label(crate::diag::count(
                    degenerate as u64,
                    "degenerate triangle",
                    "degenerate triangles",
                ))
                .with_help("check the mesh file and the transform's scale"),
            );
        } else if plain {
            // The file's data is dropped here (a one-off compile keeps no
            // copy): only the world-space vertices and the kept triangles
            // stay.
            self.out.prims.push_mesh(PlainMesh {
                positions: pos,
                triangles: kept,
                object: o as u32,
                swapped: flip,
            });
        }
    }
}

/// The primitives of a sphere or disk under the similarity `m` of scale
/// `s` (the registry's round shapes place themselves).
fn round_shapes(shape: &check::Shape, m: &DMat4, s: f64, out: &mut Vec<Shape>) {
    let pt = |p: DVec3| m.transform_point3(p).as_vec3();
    match shape {
        check::Shape::Sphere { center, radius } => out.push(Shape::Sphere {
            center: pt(*center),
            radius: (radius * s) as f32,
        }),
        check::Shape::Disk {
            center,
            normal,
            radius,
        } => out.push(Shape::Disk {
            center: pt(*center),
            normal: unit_f32(m.transform_vector3(*normal)),
            radius: (radius * s) as f32,
        }),
        // Not round: gathered by `Gathering::object`.
        _ => {}
    }
}

/// A box's six faces `(corner, e1, e2)` with outward normals (e1 × e2
/// points out), each seen upright from outside: e1 to the right, e2 up
/// (the top's up is −z, the bottom's +z), so that a texture's (u, v) runs
/// along them (see geometry::texcoord).
fn box_faces(lo: DVec3, hi: DVec3) -> [(DVec3, DVec3, DVec3); 6] {
    let d = hi - lo;
    let (ex, ey, ez) = (
        DVec3::new(d.x, 0.0, 0.0),
        DVec3::new(0.0, d.y, 0.0),
        DVec3::new(0.0, 0.0, d.z),
    );
    [
        (lo, ez, ey),            // −x
        (lo + ex + ez, -ez, ey), // +x
        (lo, ex, ez),            // −y
        (lo + ey + ez, ex, -ez), // +y
        (lo + ex, -ex, ey),      // −z
        (lo + ez, ex, ey),       // +z
    ]
}

/// Whether a primitive survives f32 ([`representable`]).
enum Representable {
    Yes,
    /// Beyond ±[`MAX_MAGNITUDE`] (or not finite) somewhere in the shutter interval.
    OutOfRange,
    /// An area that rounds to zero.
    TooSmall,
}

/// Checks a primitive against the numeric domain the checker enforces on
/// the file's numbers, after transforms and motion: every coordinate within
/// ±[`MAX_MAGNITUDE`] over the shutter interval, an area above zero.
fn representable(shape: &Shape, velocity: Vec3, shutter: (f32, f32)) -> Representable {
    if let Shape::Plane { point, normal } = *shape {
        let ok = normal.is_finite()
            && normal != Vec3::ZERO
            && within_domain(
                Aabb {
                    min: point,
                    max: point,
                },
                velocity,
                shutter,
            );
        return if ok {
            Representable::Yes
        } else {
            Representable::OutOfRange
        };
    }
    if !within_domain(shape.bounds(), velocity, shutter) {
        return Representable::OutOfRange;
    }
    let area = shape.area();
    if area > 0.0 && area.is_finite() {
        Representable::Yes
    } else {
        Representable::TooSmall
    }
}

/// Whether `b`, moved by `velocity` over the shutter interval, stays within
/// ±[`MAX_MAGNITUDE`] (a hair more: the limit itself rounds in f32).
pub(super) fn within_domain(b: Aabb, velocity: Vec3, (t0, t1): (f32, f32)) -> bool {
    let limit = (MAX_MAGNITUDE * (1.0 + 1e-6)) as f32;
    [t0, t1].iter().all(|&t| {
        let (lo, hi) = (b.min + velocity * t, b.max + velocity * t);
        lo.is_finite() && hi.is_finite() && lo.abs().max(hi.abs()).max_element() <= limit
    })
}

/// The parallelogram `p + s·e1 + t·e2`, stored with its edges swapped when
/// `flip` (a mirroring transform: see [`Shape::own_uv`]).
fn parallelogram(p: Vec3, e1: Vec3, e2: Vec3, flip: bool) -> Shape {
    let (e1, e2) = if flip { (e2, e1) } else { (e1, e2) };
    Shape::Quad {
        p,
        e1,
        e2,
        swapped: flip,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn geometry_is_checked_in_f32_over_the_shutter() {
        let unit = Shape::Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        };
        let still = (0.0, 0.0);
        assert!(matches!(
            representable(&unit, Vec3::ZERO, still),
            Representable::Yes
        ));
        // Moving out of range by the end of the shutter interval.
        assert!(matches!(
            representable(&unit, Vec3::new(2e9, 0.0, 0.0), (0.0, 1.0)),
            Representable::OutOfRange
        ));
        let tiny = Shape::quad(
            Vec3::ZERO,
            Vec3::new(1e-30, 0.0, 0.0),
            Vec3::new(0.0, 1e-30, 0.0),
        );
        assert!(matches!(
            representable(&tiny, Vec3::ZERO, still),
            Representable::TooSmall
        ));
    }
}
