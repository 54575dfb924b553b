//! Lowering: checked scene → render IR. Transforms are baked into the
//! primitives, boxes become six quads, meshes are loaded, lights are
//! collected and the BVH is built. Problems found here (an unreadable mesh, a
//! sphere under a non-uniform scale) are diagnostics with the object's span.

pub mod cache;
mod camera;
mod collect;
pub mod decode;
mod environment;
pub mod fingerprint;
mod geometry;
pub mod gltf;
mod gltf_accessor;
mod gltf_buffers;
mod gltf_material;
mod gltf_nodes;
mod gltf_place;
pub mod image;
mod instances;
mod lights;
mod material;
mod media;
pub mod mesh;
mod mesh_data;
pub mod mtl;
mod obj;
mod obj_faces;
mod obj_lines;
mod obj_materials;
mod ply;
mod shapes;
mod swaps;
mod tangents;
pub use fingerprint::fingerprint;

use crate::check;
use crate::diag::codes;
use crate::diag::{Diagnostic, Diagnostics};
use crate::geometry::shape::Shape;
use crate::geometry::Aabb;
use crate::ir::cutout::{Cutouts, Opacity};
use crate::ir::instance::Instances;
use crate::ir::settings::Settings;
use crate::ir::Scene;
use crate::light::environment::EnvironmentMap;
use crate::light::selection::{LightSampler, Selectable};
use crate::light::{Emitter, Light};
use crate::material::Material;
use crate::source::Files;
use crate::texture::Texture;
use cache::LowerCache;
use camera::lower_camera;
pub use geometry::Geometry;
use glam::{Affine3A, DMat4, DVec3, Vec3};
use image::Images;
use lights::lower_light;
use material::lower_material;
use shapes::Gathered;
use std::path::PathBuf;
use std::sync::Arc;

fn v3(v: DVec3) -> Vec3 {
    v.as_vec3()
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
    (cache, files): (&mut LowerCache, &dyn Files),
    warnings: &mut Diagnostics,
) -> Result<Scene, Diagnostics> {
    let coats = material::Coats::default();
    let reading = (cache, files, coats);
    read_and_prepare(scene, adjust, reading, warnings, |flat, prepared, cache| {
        prepared.map(|p| p.build(flat, cache))
    })
}

/// Every problem [`lower`] would find in `scene`, found the same way
/// (images and meshes read, every primitive made in f32) without building
/// anything: what `ptsc check` and an editor report, so that they and
/// `render` give one verdict.
pub fn validate(
    scene: &check::Scene,
    (cache, files): (&mut LowerCache, &dyn Files),
    warnings: &mut Diagnostics,
) -> Diagnostics {
    let reading = (cache, files, material::Coats::for_checking());
    read_and_prepare(scene, &|_| {}, reading, warnings, |_, prepared, _| {
        prepared.err().unwrap_or_default()
    })
}

/// The problems lowering would find in the files that a scene with errors
/// names (`unbuilt`: its check built no scene, so [`validate`] does not
/// run): its images read and decoded and its meshes read and parsed, as
/// lowering reads them, and only the files' own errors kept. The compile
/// driver reports them beside the check's, so that a corrupt image or
/// mesh shows at once, not after every other mistake is fixed.
pub fn validate_files(
    unbuilt: &check::unbuilt::Unbuilt,
    (cache, files): (&mut LowerCache, &dyn Files),
) -> Diagnostics {
    let mut diags = Diagnostics::new();
    let looks = (&unbuilt.materials[..], unbuilt.environment.as_ref());
    let coats = &mut material::Coats::for_checking();
    read_looks(
        looks,
        (&mut *cache, files, coats),
        &mut diags,
        &mut Diagnostics::new(),
    );
    for (path, named, span) in &unbuilt.meshes {
        if let Err(why) = cache.mesh(files, path) {
            diags.push(shapes::unloadable_mesh((path, named, *span), why));
        }
    }
    diags
        .items
        .retain(|d| [codes::IMAGE_FILE, codes::MESH_FILE].contains(&d.code));
    diags
}

/// The materials (with their opacities and the textures both read) and
/// the environment map of a scene: every image read, through `cache`'s
/// images (or for this compile alone), each file once. Problems go to
/// `diags`, notes to `warnings`. What [`prepare`] and [`validate_files`]
/// share.
fn read_looks(
    (materials, environment): (&[check::Material], Option<&check::Environment>),
    (cache, files, coats): (&mut LowerCache, &dyn Files, &mut material::Coats),
    diags: &mut Diagnostics,
    warnings: &mut Diagnostics,
) -> (Looks, Option<Arc<EnvironmentMap>>) {
    let mut textures = Vec::new();
    let mut one_off_images = Images::default();
    let images = if cache.is_one_off() {
        &mut one_off_images
    } else {
        &mut cache.images
    };
    let lowered: Vec<Material> = (materials.iter())
        .map(|m| lower_material(m, &mut textures, (images, files), coats, diags))
        .collect();
    let opacities = (materials.iter())
        .map(|m| material::lower_opacity(m, &mut textures, (images, files), diags))
        .collect();
    let environment = environment
        .and_then(|e| environment::lower_environment(e, (images, files), diags, warnings));
    images.keep_only_used();
    ((lowered, opacities, textures), environment)
}

/// A scene's materials, their opacities and the textures they read.
type Looks = (Vec<Material>, Vec<Option<Opacity>>, Vec<Texture>);

/// What [`lower`] and [`validate`] share: glTF files become their objects
/// and placements (each mesh file read once: the reads go on to the
/// gathering), placements of groups placed once become the scene's objects
/// (the others share their group's prototype), meshes without a material
/// take their OBJ file's, and everything is read and checked
/// ([`prepare`]); then `finish` gets the flat scene and what was prepared
/// or every problem found.
fn read_and_prepare<R>(
    scene: &check::Scene,
    adjust: &dyn Fn(&mut Settings),
    (cache, files, coats): (&mut LowerCache, &dyn Files, material::Coats),
    warnings: &mut Diagnostics,
    finish: impl FnOnce(&check::Scene, Result<Prepared, Diagnostics>, &mut LowerCache) -> R,
) -> R {
    let mut reads = shapes::MeshReads::new();
    let placed = gltf_place::place(scene, (cache, files, &mut reads), warnings);
    let scene = placed.scene.as_ref().unwrap_or(scene);
    let over = placed.embedded.over(files);
    let files: &dyn Files = if placed.embedded.is_empty() {
        files
    } else {
        &over
    };
    // An OBJ's materials inside a group, before the group is placed.
    let grouped = obj_materials::expand_groups(scene, (cache, files, &mut reads), warnings);
    let scene = grouped.as_ref().unwrap_or(scene);
    let split = instances::split(scene);
    let flat = split.scene.as_ref().unwrap_or(scene);
    let expanded = obj_materials::expand(flat, (cache, files, &mut reads), warnings);
    let flat = expanded.as_ref().unwrap_or(flat);
    let reading = (&mut *cache, files, coats, reads);
    let prepared = prepare(scene, flat, &split, adjust, reading, warnings);
    let mut errors = placed.errors;
    let prepared = match prepared {
        Ok(prepared) if !errors.has_errors() => Ok(prepared),
        Ok(_) => Err(errors),
        Err(more) => {
            errors.extend(more);
            Err(errors)
        }
    };
    finish(flat, prepared, cache)
}

/// The scene's geometry before the BVH: kept from an earlier compile, or
/// gathered now.
enum Shapes {
    /// Kept by `watch`'s cache (the same shapes, transforms and meshes).
    Kept(Geometry),
    /// Gathered; the key to keep it under once built (not for a one-off
    /// compile).
    Gathered(Gathered, Option<u64>),
}

/// Everything lowering reads and checks, before it builds: past this point
/// no problem can be found.
struct Prepared {
    settings: Settings,
    materials: Looks,
    environment: Option<Arc<EnvironmentMap>>,
    shapes: Shapes,
    placements: instances::Gathered,
}

/// Reads and checks everything `flat` (the scene with its placements
/// sorted out of `original`; `shared` the placements of shared groups)
/// needs: materials and their images (plastics' coats from `coats`), the
/// environment, every primitive of the scene and of the shared groups.
/// Every problem of all of them, or what the build needs.
fn prepare(
    original: &check::Scene,
    flat: &check::Scene,
    split: &instances::Split,
    adjust: &dyn Fn(&mut Settings),
    (cache, files, mut coats, reads): (
        &mut LowerCache,
        &dyn Files,
        material::Coats,
        shapes::MeshReads,
    ),
    warnings: &mut Diagnostics,
) -> Result<Prepared, Diagnostics> {
    let mut settings = flat.render.settings.clone();
    adjust(&mut settings);
    let mut diags = Diagnostics::new();
    let looks = (&flat.materials[..], flat.environment.as_ref());
    let (materials, environment) = read_looks(
        looks,
        (&mut *cache, files, &mut coats),
        &mut diags,
        warnings,
    );
    let placements =
        instances::gather(original, split, (cache, files)).map_err(|d| diags.extend(d));
    let key = (!cache.is_one_off()).then(|| cache.geometry_key(files, flat));
    let shapes = match key.and_then(|k| cache.reuse_geometry(k)) {
        // Shared, not copied: materials and lights live outside the geometry.
        Some(g) => Ok(Shapes::Kept(g)),
        None => shapes::gather(
            &flat.objects,
            flat.camera.shutter,
            (cache, files),
            reads,
            (
                objects_where(flat, check::Material::is_cut_out),
                objects_where(flat, |m| m.vertex_color),
            ),
        )
        .map(|g| Shapes::Gathered(g, key))
        .map_err(|d| diags.extend(d)),
    };
    if diags.has_errors() {
        return Err(diags);
    }
    let (Ok(shapes), Ok(placements)) = (shapes, placements) else {
        unreachable!("a failed gathering adds its errors");
    };
    let without_uvs = match &shapes {
        Shapes::Kept(g) => &g.meshes_without_uvs[..],
        Shapes::Gathered(g, _) => &g.meshes_without_uvs[..],
    };
    warn_missing_texcoords(flat, without_uvs, warnings);
    Ok(Prepared {
        settings,
        materials,
        environment,
        shapes,
        placements,
    })
}

impl Prepared {
    /// The IR of the scene `flat` prepared: the BVHs, lights and camera.
    fn build(self, flat: &check::Scene, cache: &mut LowerCache) -> Scene {
        let geometry = match self.shapes {
            Shapes::Kept(g) => g,
            Shapes::Gathered(gathered, key) => {
                let g = geometry::build(gathered);
                if let Some(key) = key {
                    cache.store_geometry(key, &g);
                }
                g
            }
        };
        let placed = instances::build(self.placements, cache);
        finish(
            flat,
            self.settings,
            self.materials,
            geometry,
            self.environment,
            placed,
        )
    }
}

/// The opacities of the materials that some surface uses (objects, groups'
/// objects, placements): a scene cuts nothing out unless a surface is cut
/// out (a glTF file's materials replaced by the scene's are unused).
fn used_opacities(
    mut opacities: Vec<Option<Opacity>>,
    object_material: &[u32],
    placed: &Instances,
) -> Vec<Option<Opacity>> {
    let mut used = vec![false; opacities.len()];
    let prototypes = placed.prototypes.iter().flat_map(|p| &p.object_material);
    let placements = placed.placements.iter().map(|p| &p.material);
    for &m in object_material.iter().chain(prototypes).chain(placements) {
        if let Some(u) = used.get_mut(m as usize) {
            *u = true;
        }
    }
    for (o, u) in opacities.iter_mut().zip(used) {
        if !u {
            *o = None;
        }
    }
    opacities
}

/// Whether each object of `scene` has a material with `property` (cut
/// out, vertex colours); empty when none has.
fn objects_where(scene: &check::Scene, property: impl Fn(&check::Material) -> bool) -> Vec<bool> {
    let cut: Vec<bool> = (scene.objects.iter())
        .map(|o| property(&scene.materials[o.material]))
        .collect();
    match cut.contains(&true) {
        true => cut,
        false => Vec::new(),
    }
}

/// Warns about each mesh without texture coordinates whose material has
/// a texture that reads them.
fn warn_missing_texcoords(
    scene: &check::Scene,
    meshes_without_uvs: &[u32],
    warnings: &mut Diagnostics,
) {
    for &o in meshes_without_uvs {
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

/// The data files a checked scene reads, in order (its objects' meshes,
/// its groups' meshes, its materials' images, its environment map), each
/// with the most bytes its reader takes.
fn data_files(scene: &check::Scene) -> Vec<(PathBuf, u64)> {
    let meshes = (scene.objects.iter())
        .chain(scene.groups.iter().flat_map(|g| &g.objects))
        .filter_map(|o| match &o.shape {
            check::Shape::Mesh { path, .. } => Some((path.clone(), crate::source::MAX_MESH_BYTES)),
            _ => None,
        });
    let images = scene.materials.iter().flat_map(|m| {
        m.textures.iter().filter_map(|(_, t)| match &t.kind {
            check::TextureKind::Image { path, .. } => Some((path.clone(), image::MAX_IMAGE_BYTES)),
            _ => None,
        })
    });
    let environment = (scene.environment.iter()).map(|e| (e.path.clone(), image::MAX_IMAGE_BYTES));
    meshes.chain(images).chain(environment).collect()
}

/// Lights, light selection and the camera on top of the geometry.
fn finish(
    scene: &check::Scene,
    settings: Settings,
    (materials, opacities, textures): (Vec<Material>, Vec<Option<Opacity>>, Vec<Texture>),
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
        tangents,
        colors,
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
            Some(p) => Light::area(prim, p.shape, p.velocity),
            None => {
                let (p, shape) = plain_lights
                    .next()
                    .expect("every plain primitive is in a block");
                debug_assert_eq!(p, prim);
                Light::area(prim, shape, Vec3::ZERO)
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
    let opacities = used_opacities(opacities, &object_material, &placed);
    let mut ir = Scene {
        cutouts: Cutouts::of(opacities).map(Arc::new),
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
        tangents,
        colors,
        area_lights,
        lights,
        light_sampler: LightSampler::default(),
        light_powers: Vec::new(),
        background,
        env_light,
        bounds,
        atmosphere: None,
        camera_media: Default::default(),
        volumetric: false,
    };
    let scene_bounds = if bounds.min.is_finite() {
        bounds.grow(v3(scene.camera.position))
    } else {
        Aabb {
            min: Vec3::splat(-1.0),
            max: Vec3::ONE,
        }
    };
    let emitters = emitters(&ir);
    let powers: Vec<f64> = (ir.lights.iter().zip(&emitters))
        .map(|(l, &e)| l.power(e, scene_bounds))
        .collect();
    let shutter = ir.camera.shutter();
    let selectable: Vec<Selectable> = (ir.lights.iter().zip(&emitters))
        .map(|(l, &e)| l.selectable(e, shutter))
        .collect();
    match LightSampler::new(ir.settings.light_selection, &selectable, &powers) {
        Some(sampler) => {
            ir.light_sampler = sampler;
            ir.light_powers = powers;
        }
        None => {
            // No light with power: none to sample, none to look up.
            ir.lights.clear();
            ir.area_lights.clear();
            ir.env_light = None;
        }
    }
    media::place_media(&mut ir, scene, scene_bounds);
    ir
}

/// Points at which all textured emitters' mean emission is read in all
/// (each reads at most 1,024, and one when there are more than 2²⁰).
const EMISSION_SAMPLES: u32 = 1 << 20;

/// What each light emits as light selection weighs it (see [`Emitter`]):
/// an area light's mean emission over its surface, read from its texture
/// when it has one.
fn emitters(ir: &Scene) -> Vec<Emitter> {
    let textured = (ir.lights.iter())
        .filter(
            |l| matches!(l, Light::Area { prim, .. } if ir.material_of(*prim).textured.is_some()),
        )
        .count() as u32;
    let samples = (EMISSION_SAMPLES / textured.max(1)).clamp(1, 1024);
    (ir.lights.iter())
        .map(|l| match l {
            Light::Area { prim, shape, .. } => Emitter {
                radiance: ir.mean_emission(*prim, shape, samples),
                two_sided: ir.material_of(*prim).two_sided,
            },
            _ => Emitter::default(),
        })
        .collect()
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
