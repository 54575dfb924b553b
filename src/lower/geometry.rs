//! Gathered primitives → the geometry the renderer traverses: the BVH
//! (binned SAH, collapsed to 4 wide, triangles and quads packed in blocks),
//! the primitives' final numbers and their records in leaf order.

use super::shapes::Gathered;
use crate::accel::bvh::Bvh;
use crate::accel::bvh4::Bvh4;
use crate::accel::numbering::Numbering;
use crate::accel::tri4::MAX_PACKED;
use crate::geometry::Aabb;
use crate::ir::Prim;
use glam::{Vec2, Vec3, Vec4};
use std::sync::Arc;

/// The part of the IR that depends only on shapes, transforms, motion and
/// mesh files; a clone shares it.
#[derive(Debug, Clone)]
pub struct Geometry {
    /// The records of the primitives that need one, in leaf order, then
    /// the planes.
    pub prims: Arc<Vec<Prim>>,
    /// Vertex normals of mesh triangles with attributes.
    pub normals: Arc<Vec<[Vec3; 3]>>,
    /// Their vertex texture coordinates.
    pub uvs: Arc<Vec<[Vec2; 3]>>,
    /// Their corner tangents for normal maps.
    pub tangents: Arc<Vec<[Vec4; 3]>>,
    /// Their vertex colours.
    pub colors: Arc<Vec<[Vec3; 3]>>,
    /// Bounds of the bounded primitives over the shutter.
    pub bounds: Aabb,
    /// The BVH.
    pub wide: Arc<Bvh4>,
    /// Unbounded primitives (planes).
    pub unbounded: Arc<Vec<u32>>,
    /// The object each primitive came from.
    pub prim_object: Arc<Vec<u32>>,
    /// The mesh objects whose files have no texture coordinates.
    pub meshes_without_uvs: Arc<Vec<u32>>,
}

/// Builds the BVH over gathered primitives and numbers them.
pub fn build(gathered: Gathered) -> Geometry {
    let Gathered {
        mut prims,
        normals,
        uvs,
        tangents,
        colors,
        meshes_without_uvs,
        shutter,
    } = gathered;
    let n = prims.len();
    let boxes: Vec<Aabb> = (0..n as u32).map(|i| prims.bounds(i, shutter)).collect();
    let mut bvh = Bvh::build(&boxes, &|i| prims.packable(i));
    drop(boxes);
    // The wide tree numbers primitives by their place in the binary tree's
    // order: a leaf's primitives are consecutive. The binary tree is dropped
    // before the blocks are filled: the load's peak memory is there.
    let mut wide = Bvh4::from_binary(&bvh);
    let bounds = bvh.bounds();
    let order = std::mem::take(&mut bvh.order);
    drop(bvh);
    // Blocks number their lanes below the flag bits: a scene of more
    // primitives keeps every one as a record.
    if n < MAX_PACKED as usize {
        wide.pack_triangles(|place| prims.packed(order[place as usize]));
    }
    let planes = std::mem::take(&mut prims.planes);
    let numbering = Numbering::new(&wide, n, planes.len());
    // Records in leaf order, so that a leaf's are contiguous in memory; the
    // planes after them; then the plain triangles, which have none.
    let mut records = Vec::with_capacity(numbering.plain_from as usize);
    for (place, &u) in order.iter().enumerate() {
        if !numbering.is_plain(place as u32) {
            records.push(prims.record(u));
        }
    }
    let bounded_records = records.len() as u32;
    let objects = prims.into_objects();
    let mut prim_object = vec![0u32; (numbering.plain_from + numbering.plain) as usize];
    for (place, &u) in order.iter().enumerate() {
        if !numbering.is_plain(place as u32) {
            prim_object[numbering.record_id(place as u32) as usize] = objects.of(u);
        }
    }
    wide.renumber(
        |place| numbering.record_id(place),
        numbering.plain_from,
        |place, id| prim_object[id as usize] = objects.of(order[place as usize]),
    );
    for (plane, o) in planes {
        prim_object[records.len()] = o;
        records.push(plane);
    }
    let unbounded = (bounded_records..numbering.plain_from).collect();
    Geometry {
        prims: Arc::new(records),
        normals: Arc::new(normals),
        uvs: Arc::new(uvs),
        tangents: Arc::new(tangents),
        colors: Arc::new(colors),
        bounds,
        wide: Arc::new(wide),
        unbounded: Arc::new(unbounded),
        prim_object: Arc::new(prim_object),
        meshes_without_uvs: Arc::new(meshes_without_uvs),
    }
}
