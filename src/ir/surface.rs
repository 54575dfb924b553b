//! What the scene knows about a point of a surface beyond its hit: texture
//! coordinates and their derivatives, the point in its object's frame, and
//! the material its textures make there (colours, numbers and the bent
//! shading normal).

use super::instance::{Placement, NO_INSTANCE};
use super::{Hit, Prim, Scene};
use crate::geometry::shape::Shape;
use crate::geometry::texcoord;
use crate::material::{Input, Kind, Material, NormalInput, Textured};
use crate::texture::shading_normal;
use crate::texture::ShadingPoint;
use glam::{Affine3A, Vec2, Vec3};

/// `d` in the frame of a plane with normal `n` (any length): x and z from
/// [`texcoord::axis_frame`] of the unit normal (for +y, x along +x and z
/// along −z), y along the normal; and the length of `n`.
fn in_plane(d: Vec3, n: Vec3) -> (Vec3, f32) {
    let scale = n.length();
    let (x, z) = texcoord::axis_frame(n / scale);
    (Vec3::new(d.dot(x), d.dot(n) / scale, d.dot(z)), scale)
}

/// Where a hit's surface is described: see [`Scene::frame`].
struct Frame<'a> {
    /// The primitive's record (`None`: a plain triangle).
    record: Option<&'a Prim>,
    /// The point at rest, in the record's frame.
    p: Vec3,
    /// The record's frame → the object's (`None`: the identity).
    from_space: Option<Affine3A>,
    /// The placement whose prototype holds the record, if any.
    placement: Option<&'a Placement>,
    /// The vertex texture coordinates the record's `attributes` index.
    uvs: &'a [[Vec2; 3]],
    /// The corner tangents the record's `attributes` index.
    tangents: &'a [[glam::Vec4; 3]],
    /// The vertex colours the record's `attributes` index.
    colors: &'a [[Vec3; 3]],
}

impl Frame<'_> {
    /// A vector of the record's frame in the object's.
    fn object_vector(&self, v: Vec3) -> Vec3 {
        self.from_space.map_or(v, |m| m.transform_vector3(v))
    }

    /// A vector of the record's frame in the world's.
    fn world_vector(&self, v: Vec3) -> Vec3 {
        self.placement
            .map_or(v, |pl| pl.world_from_group.transform_vector3(v))
    }

    /// A world vector in the record's frame.
    fn space_vector(&self, v: Vec3) -> Vec3 {
        self.placement
            .map_or(v, |pl| pl.group_from_world.transform_vector3(v))
    }
}

/// Vectors given in the frame of [`in_plane`] for the unit axis `n` (x, y
/// along `n`, z), back in the frame `n` is given in.
fn from_axis_frame(n: Vec3) -> impl Fn(Vec3) -> Vec3 {
    let (x, z) = texcoord::axis_frame(n);
    move |v: Vec3| v.x * x + v.y * n + v.z * z
}

/// The world length of the step along a surface over which a bump map's
/// slope is measured, at a point `p`: small against patterns' features,
/// large against f32's spacing of coordinates there.
fn bump_step(p: Vec3) -> f32 {
    1e-3 * (p.abs().max_element() * 1e-3).max(1.0)
}

impl Scene {
    /// A textured material's parameters evaluated at a hit seen from `wo`;
    /// a normal or bump map sets the hit's shading normal.
    #[inline(never)]
    pub(super) fn textured_material(
        &self,
        t: &Textured,
        hit: &mut Hit,
        wo: Vec3,
        time: f32,
    ) -> Material {
        let at = self.shading_point(hit, time);
        let mut params = t.params.clone();
        for &(input, i) in &t.inputs {
            let texture = &self.textures[i as usize];
            match input {
                Input::Diffuse => params.diffuse = texture.eval(&at),
                Input::Reflection => params.reflection = texture.eval(&at),
                Input::Absorption => params.absorption = texture.eval(&at),
                Input::Emission => params.emission = texture.eval(&at),
                Input::Gloss => params.gloss = texture.eval_scalar(&at).clamp(0.0, 1.0),
                Input::Transmission => {
                    params.transmission = texture.eval_scalar(&at).clamp(0.0, 1.0)
                }
                Input::Metallic => {
                    if let Kind::Principled(p) = &mut params.kind {
                        p.metallic = texture.eval_scalar(&at).clamp(0.0, 1.0);
                    }
                }
            }
        }
        if t.vertex_color {
            params.diffuse *= self.vertex_color(hit, time);
        }
        if let Some(coats) = &t.coats {
            params.kind = Kind::Plastic(coats.at(params.gloss));
        }
        if let Some(normal) = t.normal {
            let ns = self.bent_normal(normal, hit, &at, time);
            hit.n_shading = shading_normal::facing(ns, hit.n_geo, wo);
            hit.bent = true;
        }
        let mut material = Material::new(&params);
        if t.tangent {
            material.tangent = self.derivatives(hit, time).0;
        }
        material
    }

    /// The shading normal a normal or bump map gives at a hit.
    fn bent_normal(&self, normal: NormalInput, hit: &Hit, at: &ShadingPoint, time: f32) -> Vec3 {
        let n = hit.n_shading;
        let (dpdu, dpdv) = self.derivatives(hit, time);
        match normal {
            NormalInput::Map { texture, scale } => {
                let texel = self.textures[texture as usize].eval(at);
                match self.corner_tangent(hit, time) {
                    Some(tangent) => shading_normal::mapped_normal_along(texel, scale, n, tangent),
                    None => shading_normal::mapped_normal(texel, scale, n, dpdu),
                }
            }
            NormalInput::Bump { texture, height } => {
                let texture = &self.textures[texture as usize];
                let h0 = texture.eval_scalar(at);
                let frame = self.frame(hit, time);
                // World vectors into the object's frame.
                let to_object = |v: Vec3| frame.object_vector(frame.space_vector(v));
                // The height's slope along u and along v: one step of
                // `bump_step` world units each way, moving every
                // coordinate the texture might read.
                let slope = |dpd: Vec3, duv: Vec2| {
                    let len = dpd.length();
                    if !(len > 0.0 && len.is_finite()) {
                        return 0.0;
                    }
                    let step = bump_step(hit.p) / len;
                    let moved = step * dpd;
                    let shifted = ShadingPoint {
                        uv: at.uv + step * duv,
                        object: at.object + to_object(moved),
                        world: at.world + moved,
                    };
                    height * (texture.eval_scalar(&shifted) - h0) / step
                };
                let dh_du = slope(dpdu, Vec2::X);
                let dh_dv = slope(dpdv, Vec2::Y);
                shading_normal::bumped_normal(n, dpdu, dpdv, dh_du, dh_dv)
            }
        }
    }

    /// The vertex colour at a hit: its mesh triangle's corners'
    /// interpolated, white where it has none.
    fn vertex_color(&self, hit: &Hit, time: f32) -> Vec3 {
        let frame = self.frame(hit, time);
        let Some(Prim {
            shape: Shape::Triangle { attributes, .. },
            ..
        }) = frame.record
        else {
            return Vec3::ONE;
        };
        let Some(c) = frame.colors.get(*attributes as usize) else {
            return Vec3::ONE;
        };
        let (u, v) = (hit.uv.x, hit.uv.y);
        (1.0 - u - v) * c[0] + u * c[1] + v * c[2]
    }

    /// The tangent a mesh triangle's corners give at a hit (their own, a
    /// file's or MikkTSpace's, interpolated) in the world, and the side of
    /// its bitangent (±1); `None` where the triangle has none.
    fn corner_tangent(&self, hit: &Hit, time: f32) -> Option<(Vec3, f32)> {
        let frame = self.frame(hit, time);
        let Some(Prim {
            shape: Shape::Triangle { attributes, .. },
            ..
        }) = frame.record
        else {
            return None;
        };
        let corners = frame.tangents.get(*attributes as usize)?;
        if corners[0].w == 0.0 {
            return None;
        }
        let (u, v) = (hit.uv.x, hit.uv.y);
        let t = (1.0 - u - v) * corners[0].truncate()
            + u * corners[1].truncate()
            + v * corners[2].truncate();
        let t = frame.world_vector(t);
        // A mirroring placement turns the bitangent's side, as a mirroring
        // transform of the mesh did when it was read.
        let mirrored = frame
            .placement
            .is_some_and(|p| p.world_from_group.matrix3.determinant() < 0.0);
        let side = if mirrored {
            -corners[0].w
        } else {
            corners[0].w
        };
        (t != Vec3::ZERO && t.is_finite()).then_some((t, side))
    }

    /// Where textures are evaluated at a hit at `time`: its texture
    /// coordinates, the point in its object's frame (at time 0) and in the
    /// world.
    pub fn shading_point(&self, hit: &Hit, time: f32) -> ShadingPoint {
        let frame = self.frame(hit, time);
        ShadingPoint {
            uv: self.texcoords(hit, time),
            object: frame
                .from_space
                .map_or(frame.p, |m| m.transform_point3(frame.p)),
            world: hit.p,
        }
    }

    /// The frame a hit's surface is described in: its primitive's record
    /// (`None`: a plain triangle), the point at rest in the record's frame
    /// (the world's, or a prototype's for a placed group), the transform
    /// from that frame to the object's and the placement, if any.
    fn frame(&self, hit: &Hit, time: f32) -> Frame<'_> {
        if hit.instance == NO_INSTANCE {
            let record = self.prims.get(hit.prim as usize);
            let velocity = record.map_or(Vec3::ZERO, |p| p.velocity);
            return Frame {
                record,
                p: hit.p - velocity * time,
                from_space: self.from_world(hit.prim).copied(),
                placement: None,
                uvs: &self.uvs,
                tangents: &self.tangents,
                colors: &self.colors,
            };
        }
        let placement = &self.instances.placements[hit.instance as usize];
        let prototype = &self.instances.prototypes[placement.prototype as usize];
        let record = prototype.prims.get(hit.prim as usize);
        let velocity = record.map_or(Vec3::ZERO, |p| p.velocity);
        let p = placement
            .group_from_world
            .transform_point3(hit.p - placement.velocity * time);
        Frame {
            record,
            p: p - velocity * time,
            from_space: prototype.object_from_group(hit.prim).copied(),
            placement: Some(placement),
            uvs: &prototype.uvs,
            tangents: &prototype.tangents,
            colors: &prototype.colors,
        }
    }

    /// The radiance primitive `prim` emits towards `wo` from its point `p`
    /// (at `time`) with surface parameters `uv` and geometric normal `n`:
    /// its material's emission, read from its texture there if it has one.
    // Inlined into light sampling: the constant case costs what reading
    // the material's emission did (out of line it added 3 % to cornell's
    // instructions); the textured case stays out of line.
    #[inline(always)]
    pub fn emitted_at(&self, prim: u32, p: Vec3, uv: Vec2, n: Vec3, wo: Vec3, time: f32) -> Vec3 {
        let m = self.material_of(prim);
        match &m.textured {
            None => m.emitted(wo, n),
            Some(t) => self.textured_emission(m, t, prim, [p, n, wo], uv, time),
        }
    }

    /// The mean luminance of the radiance emissive primitive `prim` (of
    /// shape `shape`) sends from its front over its surface: its
    /// material's emission, or for a textured emitter the average of
    /// `samples` stratified points (jittered by a fixed hash, so that the
    /// estimate is deterministic), floored at a thousandth of its brightest
    /// colour so that a light never weighs nothing.
    pub fn mean_emission(&self, prim: u32, shape: &Shape, samples: u32) -> f64 {
        let m = self.material_of(prim);
        let lum = |c: Vec3| crate::light::luminance(c) as f64;
        let textured = m.textured.as_ref();
        if !textured.is_some_and(|t| t.inputs.iter().any(|(i, _)| *i == Input::Emission)) {
            return lum(m.emission);
        }
        let side = (samples as f64).sqrt().ceil().max(1.0) as u32;
        let mut sum = 0.0;
        for k in 0..side * side {
            let jitter = |salt: u32| {
                let h = (k ^ salt.wrapping_mul(0x9e37_79b9)).wrapping_mul(0x85eb_ca6b);
                let h = (h ^ (h >> 13)).wrapping_mul(0xc2b2_ae35);
                (h ^ (h >> 16)) as f32 / 4_294_967_296.0
            };
            let u = Vec2::new(
                ((k % side) as f32 + jitter(1)) / side as f32,
                ((k / side) as f32 + jitter(2)) / side as f32,
            );
            let (p, n, uv) = shape.sample_area(u.min(Vec2::splat(1.0 - f32::EPSILON)));
            sum += lum(self.emitted_at(prim, p, uv, n, n, 0.0));
        }
        (sum / (side * side) as f64).max(1e-3 * lum(m.emission))
    }

    /// [`Scene::emitted_at`] for a material with textures: `[p, n, wo]` are
    /// the point, its normal and the direction of the light.
    #[inline(never)]
    fn textured_emission(
        &self,
        m: &Material,
        t: &Textured,
        prim: u32,
        [p, n, wo]: [Vec3; 3],
        uv: Vec2,
        time: f32,
    ) -> Vec3 {
        if !t.inputs.iter().any(|&(input, _)| input == Input::Emission) {
            return m.emitted(wo, n);
        }
        let mut hit = Hit {
            t: 0.0,
            p,
            n_geo: n,
            n_shading: n,
            bent: false,
            prim,
            instance: NO_INSTANCE,
            uv,
        };
        self.textured_material(t, &mut hit, wo, time).emitted(wo, n)
    }

    /// The shape of the plain triangle or quad a hit is on, from the block
    /// of the BVH (the scene's or the placed prototype's) that holds it.
    fn plain_shape(&self, hit: &Hit) -> Option<Shape> {
        let wide = if hit.instance == NO_INSTANCE {
            &self.wide
        } else {
            let placement = &self.instances.placements[hit.instance as usize];
            &self.instances.prototypes[placement.prototype as usize].wide
        };
        Some(wide.plain_lane(hit.prim)?.shape())
    }

    /// The world → object transform of primitive `prim`'s object (`None`:
    /// the identity).
    pub fn from_world(&self, prim: u32) -> Option<&Affine3A> {
        let object = self.prim_object[prim as usize];
        let i = self
            .object_from_world
            .binary_search_by_key(&object, |&(o, _)| o)
            .ok()?;
        Some(&self.object_from_world[i].1)
    }

    /// The texture coordinates of a hit at `time` (see
    /// [`crate::geometry::texcoord`] for each shape's convention).
    pub fn texcoords(&self, hit: &Hit, time: f32) -> Vec2 {
        let frame = self.frame(hit, time);
        let Some(record) = frame.record else {
            // A plain triangle: static, no vertex attributes.
            return hit.uv;
        };
        // The point where the primitive is at time 0, then in its object's frame.
        let p = frame.p;
        let direction = |v: Vec3| frame.object_vector(v);
        match record.shape {
            Shape::Triangle { attributes, .. } => match frame.uvs.get(attributes as usize) {
                Some(&vertex_uvs) => texcoord::triangle(hit.uv, vertex_uvs),
                None => hit.uv,
            },
            Shape::Quad { .. } => hit.uv,
            Shape::Sphere { center, .. } => {
                texcoord::sphere(direction(p - center).normalize_or(Vec3::Y))
            }
            Shape::Disk {
                center,
                normal,
                radius,
            } => {
                // In the object's frame (a similarity: lengths scale by
                // |direction(normal)|, the same along every axis).
                let n = direction(normal);
                let (local, scale) = in_plane(direction(p - center), n);
                texcoord::disk(local, radius * scale)
            }
            Shape::Plane { point, normal } => {
                let (local, _) = in_plane(direction(p - point), direction(normal));
                texcoord::plane(local, 1.0)
            }
            Shape::Round(r) => {
                let (origin, axis) = r.uv_frame();
                let (local, scale) = in_plane(direction(p - origin), direction(axis));
                r.texcoord(local, scale)
            }
        }
    }

    /// How the point of a hit at `time` moves with its texture coordinates,
    /// (∂p/∂u, ∂p/∂v) in the world: the tangents that normal and bump maps
    /// are laid along.
    pub fn derivatives(&self, hit: &Hit, time: f32) -> (Vec3, Vec3) {
        let frame = self.frame(hit, time);
        let shape = match frame.record {
            Some(record) => record.shape,
            // A plain triangle or quad: its block holds it.
            None => match self.plain_shape(hit) {
                Some(shape) => shape,
                None => return crate::geometry::orthonormal_basis(hit.n_geo),
            },
        };
        let p = frame.p;
        let direction = |v: Vec3| frame.object_vector(v);
        // Object-frame vectors back to the world.
        let to_world = |v: Vec3| {
            let v = match frame.from_space {
                Some(m) => m.matrix3.inverse() * v,
                None => v,
            };
            frame.world_vector(v)
        };
        // Vectors of the record's frame to the world.
        let space_to_world = |v: Vec3| frame.world_vector(v);
        match shape {
            Shape::Triangle { attributes, .. } => {
                let (e1, e2) = shape.own_edges().expect("a triangle's edges");
                let (du, dv) = frame
                    .uvs
                    .get(attributes as usize)
                    .and_then(|&uvs| texcoord::triangle_derivatives(e1, e2, uvs))
                    .unwrap_or((e1, e2));
                (space_to_world(du), space_to_world(dv))
            }
            Shape::Quad { .. } => {
                let (e1, e2) = shape.own_edges().expect("a quad's edges");
                (space_to_world(e1), space_to_world(e2))
            }
            Shape::Sphere { center, .. } => {
                let (dpdu, dpdv) = texcoord::sphere_derivatives(direction(p - center));
                (to_world(dpdu), to_world(dpdv))
            }
            Shape::Disk { normal, radius, .. } => {
                let n = direction(normal);
                let scale = n.length();
                let (x, z) = texcoord::axis_frame(n / scale);
                let d = 2.0 * radius * scale;
                (to_world(d * x), to_world(d * z))
            }
            Shape::Plane { normal, .. } => {
                let n = direction(normal);
                let (x, z) = texcoord::axis_frame(n / n.length());
                (to_world(x), to_world(z))
            }
            Shape::Round(r) => {
                let (origin, axis) = r.uv_frame();
                let n = direction(axis);
                let (local, scale) = in_plane(direction(p - origin), n);
                let (dpdu, dpdv) = r.texcoord_derivatives(local, scale);
                let back = from_axis_frame(n / scale);
                (to_world(back(dpdu)), to_world(back(dpdv)))
            }
        }
    }
}
