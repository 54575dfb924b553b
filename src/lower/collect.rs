//! Primitives as lowering collects them, before the BVH fixes their order.
//!
//! Most shapes become 64-byte [`Prim`] records, but a plain mesh triangle
//! (static, without vertex normals) is kept as its mesh's three vertex
//! indices: 12 bytes instead of 64. Such triangles end in
//! [`Tri4`](crate::accel::tri4::Tri4) blocks of the wide BVH, which hold
//! all that rendering needs of them, so most of them never get a record at
//! all (see [`super::lower`]): on the 1M-triangle benchmark mesh this is what
//! keeps the peak memory near 100 bytes per triangle.
//!
//! Bounded primitives are numbered records first, then the meshes'
//! triangles; planes are kept apart.

use crate::accel::tri4::PackedTriangle;
use crate::geometry::shape::Shape;
use crate::geometry::Aabb;
use crate::ir::Prim;
use glam::Vec3;

/// The triangles of one mesh that need no record.
#[derive(Debug)]
pub struct PlainMesh {
    /// Vertex positions in world space (shared by the material groups of
    /// one mesh statement: `lower::obj_materials`).
    pub positions: std::sync::Arc<Vec<Vec3>>,
    /// Triangles as indices into `positions`, wound as rendered (a
    /// mirroring transform already flipped), none degenerate.
    pub triangles: Vec<[u32; 3]>,
    /// Whether a mirroring transform flipped the triangles (their edges
    /// are stored swapped: see [`Shape::own_uv`]).
    pub swapped: bool,
    /// The object the mesh came from.
    pub object: u32,
}

/// Every primitive of a scene, numbered as the BVH build sees them.
#[derive(Debug, Default)]
pub struct Collected {
    /// Bounded primitives that need a record (numbers `0..records.len()`).
    pub records: Vec<Prim>,
    /// The object each record came from.
    pub record_object: Vec<u32>,
    /// Plain mesh triangles, numbered after the records, mesh after mesh.
    pub meshes: Vec<PlainMesh>,
    /// Where each mesh of `meshes` starts, counted from the first mesh
    /// triangle (records may still be pushed after a mesh).
    mesh_first: Vec<u32>,
    /// Unbounded primitives (planes) and their objects, outside the numbering.
    pub planes: Vec<(Prim, u32)>,
    /// Whether each object is cut out (`ir::cutout`; empty: none is): its
    /// primitives keep records and stay out of the blocks, whose test
    /// cannot ask for their opacity.
    pub cut_objects: Vec<bool>,
}

impl Collected {
    /// Adds a record of `object`; planes go apart.
    pub fn push(&mut self, prim: Prim, object: u32) {
        if matches!(prim.shape, Shape::Plane { .. }) {
            self.planes.push((prim, object));
        } else {
            self.records.push(prim);
            self.record_object.push(object);
        }
    }

    /// Adds the plain triangles of a mesh.
    pub fn push_mesh(&mut self, mesh: PlainMesh) {
        let first = self.meshes.iter().map(|m| m.triangles.len()).sum::<usize>();
        self.mesh_first.push(first as u32);
        self.meshes.push(mesh);
    }

    /// The number of bounded primitives.
    pub fn len(&self) -> usize {
        self.records.len() + self.meshes.iter().map(|m| m.triangles.len()).sum::<usize>()
    }

    /// Whether `object` is cut out.
    fn is_cut(&self, object: u32) -> bool {
        self.cut_objects.get(object as usize) == Some(&true)
    }

    /// Mesh triangle `i` (a number at or after the records): its mesh and
    /// `[p0, e1, e2]` (as stored), computed exactly as a record of it would be.
    fn mesh_triangle(&self, i: u32) -> (&PlainMesh, [Vec3; 3]) {
        let i = i - self.records.len() as u32;
        let m = self.mesh_first.partition_point(|&f| f <= i) - 1;
        let mesh = &self.meshes[m];
        let [a, b, c] = mesh.triangles[(i - self.mesh_first[m]) as usize];
        let p0 = mesh.positions[a as usize];
        let e1 = mesh.positions[b as usize] - p0;
        let e2 = mesh.positions[c as usize] - p0;
        (mesh, [p0, e1, e2])
    }

    /// Primitive `i` as a record (made on the spot for a mesh triangle).
    pub fn record(&self, i: u32) -> Prim {
        match self.records.get(i as usize) {
            Some(p) => p.clone(),
            None => {
                let (mesh, vertices) = self.mesh_triangle(i);
                let [p0, e1, e2] = vertices;
                Prim {
                    shape: Shape::Triangle {
                        p0,
                        e1,
                        e2,
                        attributes: u32::MAX,
                        swapped: mesh.swapped,
                    },
                    velocity: Vec3::ZERO,
                }
            }
        }
    }

    /// Whether [`Collected::packed`] gives primitive `i` a block lane (without
    /// gathering a mesh triangle's vertices, which the build does not need).
    pub fn packable(&self, i: u32) -> bool {
        match self.records.get(i as usize) {
            Some(p) => !self.is_cut(self.record_object[i as usize]) && packed_record(p).is_some(),
            None => self.cut_objects.is_empty() || !self.is_cut(self.mesh_triangle(i).0.object),
        }
    }

    /// Primitive `i` packed for a [`Tri4`](crate::accel::tri4::Tri4)
    /// block, if it is a static triangle or quad.
    pub fn packed(&self, i: u32) -> Option<PackedTriangle> {
        if !self.packable(i) {
            return None;
        }
        match self.records.get(i as usize) {
            Some(p) => packed_record(p),
            None => {
                let (mesh, vertices) = self.mesh_triangle(i);
                Some(PackedTriangle {
                    vertices,
                    plain: true,
                    quad: false,
                    swapped: mesh.swapped,
                })
            }
        }
    }

    /// The bounds of primitive `i` over the shutter interval `(t0, t1)`.
    pub fn bounds(&self, i: u32, (t0, t1): (f32, f32)) -> Aabb {
        let Some(p) = self.records.get(i as usize) else {
            return Shape::flat_triangle(self.mesh_triangle(i).1).bounds();
        };
        let b = p.shape.bounds();
        if p.velocity == Vec3::ZERO {
            return b;
        }
        let at = |t: f32| Aabb {
            min: b.min + p.velocity * t,
            max: b.max + p.velocity * t,
        };
        at(t0).union(at(t1))
    }
}

/// The object each primitive came from, without the vertices.
#[derive(Debug)]
pub struct Objects {
    /// Per record.
    record_object: Vec<u32>,
    /// Per mesh: where it starts after the records, and its object.
    meshes: Vec<(u32, u32)>,
}

impl Collected {
    /// The object each primitive came from; the meshes' vertices are freed
    /// (the records and planes must have been taken out before).
    pub fn into_objects(self) -> Objects {
        let records = self.records.len() as u32;
        let meshes = self.mesh_first.iter().zip(&self.meshes);
        Objects {
            meshes: meshes.map(|(&f, m)| (records + f, m.object)).collect(),
            record_object: self.record_object,
        }
    }
}

impl Objects {
    /// The object primitive `i` came from.
    pub fn of(&self, i: u32) -> u32 {
        match self.record_object.get(i as usize) {
            Some(&o) => o,
            None => self.meshes[self.meshes.partition_point(|&(f, _)| f <= i) - 1].1,
        }
    }
}

/// A record that the wide BVH can test four at a time in a block: a triangle
/// or a parallelogram that does not move; plain when its vertices describe
/// it completely (no vertex normals).
fn packed_record(p: &Prim) -> Option<PackedTriangle> {
    if p.velocity != Vec3::ZERO {
        return None;
    }
    PackedTriangle::of(&p.shape)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere(x: f32) -> Prim {
        Prim {
            shape: Shape::Sphere {
                center: Vec3::new(x, 0.0, 0.0),
                radius: 1.0,
            },
            velocity: Vec3::ZERO,
        }
    }

    #[test]
    fn numbers_records_then_mesh_after_mesh() {
        let mut c = Collected::default();
        c.push(sphere(0.0), 0);
        let plane = Prim {
            shape: Shape::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            },
            velocity: Vec3::ZERO,
        };
        c.push(plane, 1);
        let square = |object, z| PlainMesh {
            positions: std::sync::Arc::new(vec![
                Vec3::new(0.0, 0.0, z),
                Vec3::new(1.0, 0.0, z),
                Vec3::new(1.0, 1.0, z),
                Vec3::new(0.0, 1.0, z),
            ]),
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            object,
            swapped: false,
        };
        c.push_mesh(square(2, 5.0));
        c.push_mesh(square(3, 7.0));
        c.push(sphere(9.0), 4);
        // Records are numbered first even when pushed after a mesh.
        assert_eq!(c.len(), 6);
        assert_eq!(c.planes.len(), 1);
        assert!(c.packed(0).is_none() && !c.packable(0));
        assert!((1..6).all(|i| c.packable(i) == c.packed(i).is_some()));
        let t = c.packed(5).unwrap();
        assert!(t.plain);
        let p = Vec3::new(0.0, 0.0, 7.0);
        assert_eq!(t.vertices, [p, Vec3::new(1.0, 1.0, 7.0) - p, Vec3::Y]);
        assert_eq!(c.bounds(5, (0.0, 1.0)).max, Vec3::new(1.0, 1.0, 7.0));
        match c.record(3).shape {
            Shape::Triangle { p0, attributes, .. } => {
                assert_eq!((p0, attributes), (Vec3::new(0.0, 0.0, 5.0), u32::MAX))
            }
            s => panic!("{s:?}"),
        }
        let objects = c.into_objects();
        let objects: Vec<u32> = (0..6).map(|i| objects.of(i)).collect();
        assert_eq!(objects, [0, 4, 2, 2, 3, 3]);
    }
}
