//! Lowering: checked scene → render IR. Transforms are baked into the
//! primitives, boxes become six quads, meshes are loaded, lights are
//! collected and the BVH is built. Problems found here (an unreadable mesh, a
//! sphere under a non-uniform scale) are diagnostics with the object's span.

pub mod cache;
mod camera;
mod collect;
mod environment;
pub mod fingerprint;
pub mod image;
mod instances;
mod lights;
mod material;
pub mod mesh;
pub use fingerprint::fingerprint;

use crate::accel::bvh::Bvh;
use crate::accel::bvh4::Bvh4;
use crate::accel::numbering::Numbering;
use crate::check;
use crate::check::domain::{self, unit_f32, MAX_MAGNITUDE, MIN_SIZE};
use crate::diag::codes;
use crate::diag::{Diagnostic, Diagnostics};
use crate::geometry::cone::Cone;
use crate::geometry::shape::Shape;
use crate::geometry::texcoord;
use crate::geometry::torus::Torus;
use crate::geometry::Aabb;
use crate::ir::instance::Instances;
use crate::ir::settings::Settings;
use crate::ir::{Prim, Scene};
use crate::light::environment::EnvironmentMap;
use crate::light::selection::{LightSampler, Selectable};
use crate::light::Light;
use crate::material::Material;
use crate::texture::Texture;
use cache::LowerCache;
use camera::lower_camera;
use collect::{Collected, PlainMesh};
use glam::{Affine3A, DMat4, DVec3, Vec2, Vec3};
use image::Images;
use lights::lower_light;
use material::lower_material;
use std::path::PathBuf;
use std::sync::Arc;

fn v3(v: DVec3) -> Vec3 {
    v.as_vec3()
}

/// The uniform scale factor of a similarity transform, or `None` if the
/// linear part shears or scales unevenly.
fn uniform_scale(m: &DMat4) -> Option<f64> {
    let (x, y, z) = (
        m.x_axis.truncate(),
        m.y_axis.truncate(),
        m.z_axis.truncate(),
    );
    let s = x.length();
    let ok = (y.length() - s).abs() <= 1e-9 * s.max(1.0)
        && (z.length() - s).abs() <= 1e-9 * s.max(1.0)
        && x.dot(y).abs() <= 1e-9 * s * s
        && y.dot(z).abs() <= 1e-9 * s * s
        && x.dot(z).abs() <= 1e-9 * s * s;
    ok.then_some(s)
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
fn within_domain(b: Aabb, velocity: Vec3, (t0, t1): (f32, f32)) -> bool {
    let limit = (MAX_MAGNITUDE * (1.0 + 1e-6)) as f32;
    [t0, t1].iter().all(|&t| {
        let (lo, hi) = (b.min + velocity * t, b.max + velocity * t);
        lo.is_finite() && hi.is_finite() && lo.abs().max(hi.abs()).max_element() <= limit
    })
}

/// Builds the IR; mesh problems and unsupported transforms are diagnostics.
/// `adjust` edits the settings before anything depends on them (the command
/// line's `--spp`, `--resolution`, …). With a cache kept between compiles
/// (see [`LowerCache`]) the meshes whose files did not change are reused,
/// and the whole geometry (primitives and BVH) when no shape, transform,
/// motion or mesh changed: a camera, material or settings edit in `watch`
/// neither reloads meshes nor rebuilds the BVH.
/// [`LowerCache::one_off`] keeps nothing.
/// Warnings (a texture in (u, v) on a mesh without UVs) are pushed onto
/// `warnings`.
pub fn lower(
    scene: &check::Scene,
    adjust: &dyn Fn(&mut Settings),
    cache: &mut LowerCache,
    warnings: &mut Diagnostics,
) -> Result<Scene, Diagnostics> {
    // Placements of groups placed once become the scene's objects; the
    // others share their group's prototype.
    let original = scene;
    let split = instances::split(original);
    let scene = split.scene.as_ref().unwrap_or(original);
    let mut settings = scene.render.settings.clone();
    adjust(&mut settings);
    let (mut textures, mut diags) = (Vec::new(), Diagnostics::new());
    let mut one_off_images = Images::default();
    let images = if cache.is_one_off() {
        &mut one_off_images
    } else {
        &mut cache.images
    };
    let mut coats = material::Coats::default();
    let materials: Vec<Material> = (scene.materials.iter())
        .map(|m| lower_material(m, &mut textures, images, &mut coats, &mut diags))
        .collect();
    let environment = (scene.environment.as_ref())
        .and_then(|e| environment::lower_environment(e, images, &mut diags, warnings));
    images.keep_only_used();
    if diags.has_errors() {
        return Err(diags);
    }
    let materials = (materials, textures);
    let placed = match split.shared.is_empty() {
        true => Instances::default(),
        false => instances::build(original, &split.shared, cache)?,
    };
    let geometry = if cache.is_one_off() {
        build_geometry(scene, cache)?
    } else {
        let key = cache.geometry_key(scene);
        // Shared, not copied: materials and lights live outside the geometry.
        match cache.reuse_geometry(key) {
            Some(g) => g,
            None => {
                let g = build_geometry(scene, cache)?;
                cache.store_geometry(key, &g);
                g
            }
        }
    };
    warn_missing_texcoords(scene, &geometry, warnings);
    Ok(finish(
        scene,
        settings,
        materials,
        geometry,
        environment,
        placed,
    ))
}

/// Warns about each mesh without texture coordinates whose material has
/// a texture that reads them.
fn warn_missing_texcoords(scene: &check::Scene, geometry: &Geometry, warnings: &mut Diagnostics) {
    for &o in geometry.meshes_without_uvs.iter() {
        let object = &scene.objects[o as usize];
        let material = &scene.materials[object.material];
        let Some((_, texture)) =
            (material.textures.iter()).find(|(_, t)| t.space == check::TextureSpace::Uv)
        else {
            continue;
        };
        let check::Shape::Mesh { path_span, .. } = &object.shape else {
            continue;
        };
        warnings.push(
            Diagnostic::warning(
                codes::NO_TEXCOORDS,
                "this mesh has no texture coordinates for its texture to read",
                *path_span,
            )
            .with_label("no `vt` (OBJ) or `u v` (PLY) in this file")
            .with_secondary(texture.span, "this texture reads (u, v)")
            .with_help(
                "each triangle reads its own barycentrics instead; export the mesh with UVs, or give the texture `space object`",
            ),
        );
    }
}

/// The files a checked scene names besides its sources: the meshes and
/// texture images it reads, and the image its `render { output … }` asks
/// for.
pub fn named_files(scene: &check::Scene) -> (Vec<PathBuf>, Option<PathBuf>) {
    let meshes = (scene.objects.iter())
        .chain(scene.groups.iter().flat_map(|g| &g.objects))
        .filter_map(|o| match &o.shape {
            check::Shape::Mesh { path, .. } => Some(path.clone()),
            _ => None,
        })
        .chain(scene.materials.iter().flat_map(|m| {
            m.textures.iter().filter_map(|(_, t)| match &t.kind {
                check::TextureKind::Image { path, .. } => Some(path.clone()),
                _ => None,
            })
        }))
        .chain(scene.environment.iter().map(|e| e.path.clone()))
        .collect();
    (meshes, scene.render.output.clone())
}

/// The part of the IR that depends only on shapes, transforms, motion and
/// mesh files; a clone shares it.
#[derive(Debug, Clone)]
pub struct Geometry {
    prims: Arc<Vec<Prim>>,
    normals: Arc<Vec<[Vec3; 3]>>,
    uvs: Arc<Vec<[Vec2; 3]>>,
    bounds: Aabb,
    wide: Arc<Bvh4>,
    /// Unbounded primitives (planes).
    unbounded: Arc<Vec<u32>>,
    /// The object each primitive came from.
    prim_object: Arc<Vec<u32>>,
    /// The mesh objects whose files have no texture coordinates.
    meshes_without_uvs: Arc<Vec<u32>>,
}

fn build_geometry(scene: &check::Scene, cache: &mut LowerCache) -> Result<Geometry, Diagnostics> {
    build_objects(&scene.objects, scene.camera.shutter, cache)
}

/// The primitives and BVH of `objects` (the scene's, or a group's in the
/// group's frame) over the shutter interval.
fn build_objects(
    objects: &[check::Object],
    (t0, t1): (f64, f64),
    cache: &mut LowerCache,
) -> Result<Geometry, Diagnostics> {
    let mut diags = Diagnostics::new();
    let mut prims = Collected::default();
    let mut normals: Vec<[Vec3; 3]> = Vec::new();
    let mut uvs: Vec<[Vec2; 3]> = Vec::new();
    // The first object whose geometry leaves the numeric domain after its
    // transforms and motion, and the first too small for f32.
    let mut out_of_range: Option<usize> = None;
    let mut too_small: Option<usize> = None;
    let mut meshes_without_uvs = Vec::new();
    let shutter = (t0 as f32, t1 as f32);
    for (o, obj) in objects.iter().enumerate() {
        let m = obj.transform;
        let pt = |p: DVec3| v3(m.transform_point3(p));
        let vec = |v: DVec3| v3(m.transform_vector3(v));
        let velocity = v3(obj.velocity);
        // A mirroring transform turns `e1 × e2` inwards: quads and
        // triangles keep their outward side with their edges swapped
        // (`Shape::own_uv`).
        let flip = m.determinant() < 0.0;
        let mut push = |shape: Shape| {
            match representable(&shape, velocity, shutter) {
                Representable::Yes => {}
                Representable::OutOfRange => {
                    out_of_range.get_or_insert(o);
                }
                Representable::TooSmall => {
                    too_small.get_or_insert(o);
                }
            }
            prims.push(Prim { shape, velocity }, o as u32);
        };
        match &obj.shape {
            check::Shape::Sphere { center, radius } => match uniform_scale(&m) {
                Some(s) => push(Shape::Sphere {
                    center: pt(*center),
                    radius: (radius * s) as f32,
                }),
                None => diags.push(non_uniform(obj.span, "sphere")),
            },
            check::Shape::Cone {
                base,
                top,
                base_radius,
                top_radius,
                open,
            } => match uniform_scale(&m) {
                Some(s) => round_solid(
                    pt(*base),
                    pt(*top),
                    [base_radius * s, top_radius * s],
                    *open,
                    &mut push,
                ),
                None => diags.push(non_uniform(
                    obj.span,
                    obj.shape.round_kind().unwrap_or("cone"),
                )),
            },
            check::Shape::Torus {
                center,
                axis,
                major,
                minor,
            } => match uniform_scale(&m) {
                Some(s) => push(Shape::Torus(Torus {
                    center: pt(*center),
                    axis: unit_f32(m.transform_vector3(*axis)),
                    major: (major * s) as f32,
                    minor: (minor * s) as f32,
                })),
                None => diags.push(non_uniform(obj.span, "torus")),
            },
            check::Shape::Disk {
                center,
                normal,
                radius,
            } => match uniform_scale(&m) {
                Some(s) => push(Shape::Disk {
                    center: pt(*center),
                    normal: unit_f32(m.transform_vector3(*normal)),
                    radius: (radius * s) as f32,
                }),
                None => diags.push(non_uniform(obj.span, "disk")),
            },
            check::Shape::Plane { point, normal } => {
                let n = unit_f32(m.inverse().transpose().transform_vector3(*normal));
                push(Shape::Plane {
                    point: pt(*point),
                    normal: n,
                });
            }
            check::Shape::Quad {
                corner,
                edge1,
                edge2,
            } => push(parallelogram(pt(*corner), vec(*edge1), vec(*edge2), flip)),
            check::Shape::Triangle { v } => {
                let p0 = pt(v[0]);
                let (e1, e2) = (pt(v[1]) - p0, pt(v[2]) - p0);
                // As a parallelogram: swapped under a mirror (see `flip`).
                let (e1, e2) = if flip { (e2, e1) } else { (e1, e2) };
                push(Shape::Triangle {
                    p0,
                    e1,
                    e2,
                    attributes: u32::MAX,
                    swapped: flip,
                })
            }
            check::Shape::Box { min, max } => {
                let (lo, hi) = (*min, *max);
                let d = hi - lo;
                let (ex, ey, ez) = (
                    DVec3::new(d.x, 0.0, 0.0),
                    DVec3::new(0.0, d.y, 0.0),
                    DVec3::new(0.0, 0.0, d.z),
                );
                // Six faces with outward normals (e1 × e2 points out), each
                // seen upright from outside: e1 to the right, e2 up (the
                // top's up is −z, the bottom's +z), so that a texture's
                // (u, v) runs along them (see geometry::texcoord).
                let faces = [
                    (lo, ez, ey),            // −x
                    (lo + ex + ez, -ez, ey), // +x
                    (lo, ex, ez),            // −y
                    (lo + ey + ez, ex, -ez), // +y
                    (lo + ex, -ex, ey),      // −z
                    (lo + ez, ex, ey),       // +z
                ];
                for (c, a, b) in faces {
                    push(parallelogram(pt(c), vec(a), vec(b), flip));
                }
            }
            check::Shape::Mesh {
                path,
                path_span,
                smooth,
            } => {
                let data = match cache.mesh(path) {
                    Ok(d) => d,
                    Err(e) => {
                        diags.push(
                            Diagnostic::error(
                                codes::MESH_FILE,
                                format!("cannot load mesh `{}`", path.display()),
                                *path_span,
                            )
                            .with_label(e)
                            .with_help("meshes are OBJ or PLY files with at least one triangle"),
                        );
                        continue;
                    }
                };
                let pos: Vec<Vec3> = data.positions.iter().map(|p| pt(p.as_dvec3())).collect();
                // The vertices' box, where the motion takes it: as the other shapes.
                let reach = pos.iter().fold(Aabb::EMPTY, |b, p| b.grow(*p));
                if !within_domain(reach, velocity, shutter) {
                    out_of_range.get_or_insert(o);
                }
                let nm = m.inverse().transpose();
                let use_normals = *smooth && !data.normals.is_empty();
                let vnormals: Vec<Vec3> = if use_normals {
                    data.normals
                        .iter()
                        .map(|n| unit_f32(nm.transform_vector3(n.as_dvec3())))
                        .collect()
                } else {
                    Vec::new()
                };
                let use_uvs = !data.uvs.is_empty();
                if !use_uvs {
                    meshes_without_uvs.push(o as u32);
                }
                // A static mesh without vertex attributes keeps its triangles
                // as vertex indices: most of them will never need a record.
                let plain = !use_normals && !use_uvs && velocity == Vec3::ZERO;
                let mut kept: Vec<[u32; 3]> = Vec::new();
                if plain {
                    kept.reserve_exact(data.triangles.len());
                } else {
                    prims.records.reserve(data.triangles.len());
                }
                let mut degenerate = 0usize;
                for t in &data.triangles {
                    // Stored wound as rendered; vertex attributes stay in
                    // the file's order (`Shape::own_uv` reads them so).
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
                    let nidx = if use_normals || use_uvs {
                        // A zero normal is flat shading.
                        normals.push(if use_normals {
                            t.map(|i| vnormals[i as usize])
                        } else {
                            [Vec3::ZERO; 3]
                        });
                        if use_uvs {
                            // Earlier triangles without UVs keep their barycentrics.
                            uvs.resize(normals.len() - 1, texcoord::TRIANGLE_DEFAULT);
                            uvs.push(t.map(|i| data.uvs[i as usize]));
                        }
                        normals.len() as u32 - 1
                    } else {
                        u32::MAX
                    };
                    let shape = Shape::Triangle {
                        p0,
                        e1,
                        e2,
                        attributes: nidx,
                        swapped: flip,
                    };
                    prims.push(Prim { shape, velocity }, o as u32);
                }
                if degenerate == data.triangles.len() {
                    diags.push(
                        Diagnostic::error(
                            codes::DEGENERATE,
                            "every triangle of this mesh has zero area",
                            *path_span,
                        )
                        .with_label(format!("{degenerate} degenerate triangles"))
                        .with_help("check the mesh file and the transform's scale"),
                    );
                } else if plain {
                    // The file's data is dropped here (a one-off compile
                    // keeps no copy): only the world-space vertices and the
                    // kept triangles stay.
                    prims.push_mesh(PlainMesh {
                        positions: pos,
                        triangles: kept,
                        object: o as u32,
                        swapped: flip,
                    });
                }
            }
        }
    }
    if let Some(o) = out_of_range {
        diags.push(
            Diagnostic::error(
                codes::OUT_OF_RANGE,
                format!(
                    "this object reaches beyond ±{} after its transforms and motion",
                    domain::number(MAX_MAGNITUDE)
                ),
                objects[o].span,
            )
            .with_label(format!("coordinates beyond ±{}", domain::number(MAX_MAGNITUDE)))
            .with_help("the renderer computes in 32-bit floats; check the sizes, transforms and velocity (times the shutter) for overflow"),
        );
    }
    if let Some(o) = too_small {
        diags.push(
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
    if diags.has_errors() {
        return Err(diags);
    }
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
    wide.pack_triangles(|place| prims.packed(order[place as usize]));
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
    Ok(Geometry {
        prims: Arc::new(records),
        normals: Arc::new(normals),
        uvs: Arc::new(uvs),
        bounds,
        wide: Arc::new(wide),
        unbounded: Arc::new(unbounded),
        prim_object: Arc::new(prim_object),
        meshes_without_uvs: Arc::new(meshes_without_uvs),
    })
}

/// Lights, light selection and the camera on top of the geometry.
fn finish(
    scene: &check::Scene,
    settings: Settings,
    (materials, textures): (Vec<Material>, Vec<Texture>),
    geometry: Geometry,
    environment: Option<Arc<EnvironmentMap>>,
    placed: Instances,
) -> Scene {
    let object_spans = scene.objects.iter().map(|o| o.span).collect();
    let object_material: Vec<u32> = scene.objects.iter().map(|o| o.material as u32).collect();
    let object_from_world = object_frames(scene);
    let Geometry {
        prims,
        prim_object,
        normals,
        uvs,
        bounds,
        wide,
        unbounded,
        ..
    } = geometry;

    // Lights: emissive primitives (in order), explicit lights, the background.
    let emissive: Vec<bool> = object_material
        .iter()
        .map(|&m| materials[m as usize].emission != Vec3::ZERO)
        .collect();
    let area_lights: Vec<u32> = (0..prim_object.len() as u32)
        .filter(|&i| emissive[prim_object[i as usize] as usize])
        .collect();
    // A plain triangle or quad has no record: its light takes the shape
    // from its block (emission is a material's, so this is not part of the
    // geometry).
    let mut plain_lights: Vec<(u32, Shape)> = Vec::new();
    if area_lights
        .last()
        .is_some_and(|&p| p as usize >= prims.len())
    {
        plain_lights = wide
            .plain_shapes()
            .filter(|&(p, _)| emissive[prim_object[p as usize] as usize])
            .collect();
        plain_lights.sort_unstable_by_key(|&(p, _)| p);
    }
    let mut plain_lights = plain_lights.into_iter();
    let mut lights: Vec<Light> = area_lights
        .iter()
        .map(|&prim| match prims.get(prim as usize) {
            Some(p) => Light::Area {
                prim,
                shape: p.shape,
                velocity: p.velocity,
            },
            None => {
                let (p, shape) = plain_lights
                    .next()
                    .expect("every plain primitive is in a block");
                debug_assert_eq!(p, prim);
                Light::Area {
                    prim,
                    shape,
                    velocity: Vec3::ZERO,
                }
            }
        })
        .collect();
    lights.extend(scene.lights.iter().map(|(l, _)| lower_light(l)));
    let background = rgb(&scene.background);
    let env_light = match (environment, &scene.environment, &scene.sky) {
        (_, _, Some(sky)) => environment::lower_sky(sky),
        (Some(map), Some(e), _) => Some(Light::Environment {
            radiance: rgb(&e.intensity),
            map: Some(map),
        }),
        _ => (background != Vec3::ZERO).then_some(Light::Environment {
            map: None,
            radiance: background,
        }),
    }
    .filter(|l| !matches!(l, Light::Environment { radiance, .. } if *radiance == Vec3::ZERO))
    .map(|l| {
        lights.push(l);
        lights.len() as u32 - 1
    });

    let camera = lower_camera(&scene.camera, settings.width, settings.height);
    let shutter = (scene.camera.shutter.0 as f32, scene.camera.shutter.1 as f32);
    let bounds = bounds.union(instances::bounds(&placed, shutter));
    let mut ir = Scene {
        instances: Arc::new(placed),
        settings,
        camera,
        prims,
        prim_object,
        object_spans,
        object_material,
        object_from_world,
        wide,
        unbounded,
        materials,
        textures,
        normals,
        uvs,
        area_lights,
        lights,
        light_sampler: LightSampler::default(),
        background,
        env_light,
        bounds,
    };
    let scene_bounds = if bounds.min.is_finite() {
        bounds.grow(v3(scene.camera.position))
    } else {
        Aabb {
            min: Vec3::splat(-1.0),
            max: Vec3::ONE,
        }
    };
    let powers: Vec<f64> = ir
        .lights
        .iter()
        .map(|l| l.power(|prim| ir.material_of(prim), scene_bounds))
        .collect();
    let shutter = ir.camera.shutter();
    let selectable: Vec<Selectable> = ir
        .lights
        .iter()
        .map(|l| l.selectable(|prim| ir.material_of(prim), shutter))
        .collect();
    match LightSampler::new(ir.settings.light_selection, &selectable, &powers) {
        Some(sampler) => ir.light_sampler = sampler,
        None => {
            // No light with power: none to sample, none to look up.
            ir.lights.clear();
            ir.area_lights.clear();
            ir.env_light = None;
        }
    }
    ir
}

fn rgb(c: &[f64; 3]) -> Vec3 {
    Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32)
}

/// The world → object transforms of the objects that are not at the
/// identity, by object number (for texture coordinates and patterns).
fn object_frames(scene: &check::Scene) -> Vec<(u32, Affine3A)> {
    scene
        .objects
        .iter()
        .enumerate()
        .filter(|(_, o)| o.transform != DMat4::IDENTITY)
        .map(|(i, o)| {
            let inverse = o.transform.inverse();
            (i as u32, Affine3A::from_mat4(inverse.as_mat4()))
        })
        .collect()
}

/// A cylinder or cone from `base` to `top` (world space) with the radii at
/// each end: its lateral surface and, unless `open`, the disks that close
/// it (a radius of 0 closes itself).
fn round_solid(base: Vec3, top: Vec3, radii: [f64; 2], open: bool, push: &mut impl FnMut(Shape)) {
    let along = top - base;
    let height = along.length();
    let axis = along / height;
    let [r0, r1] = radii.map(|r| r as f32);
    push(Shape::Cone(Cone {
        base,
        axis,
        height,
        r0,
        r1,
    }));
    if open {
        return;
    }
    for (center, normal, radius) in [(base, -axis, r0), (top, axis, r1)] {
        if radius > 0.0 {
            push(Shape::Disk {
                center,
                normal,
                radius,
            });
        }
    }
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

fn non_uniform(span: crate::span::Span, what: &str) -> Diagnostic {
    Diagnostic::error(
        codes::NON_UNIFORM_SCALE,
        format!("a {what} takes only uniform scaling"),
        span,
    )
    .with_label("this object is scaled unevenly or sheared")
    .with_help(format!(
        "scale the {what} by a single number, or use a mesh for ellipsoids"
    ))
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
