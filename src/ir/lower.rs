//! Lowering: checked scene → render IR. Transforms are baked into the
//! primitives, boxes become six quads, meshes are loaded, lights are
//! collected and the BVH is built. Problems found here (an unreadable mesh, a
//! sphere under a non-uniform scale) are diagnostics with the object's span.

use super::cache::LowerCache;
use super::{Prim, Scene};
use crate::check::{self, codes};
use crate::diag::{Diagnostic, Diagnostics};
use crate::geometry::bvh::Bvh;
use crate::geometry::bvh4::Bvh4;
use crate::geometry::shape::Shape;
use crate::geometry::tri4::PackedTriangle;
use crate::geometry::Aabb;
use crate::light::Light;
use crate::material::Material;
use crate::render::camera::Camera;
use glam::{DMat4, DVec3, Vec3};
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

/// Builds the IR; mesh problems and unsupported transforms are diagnostics.
pub fn lower(scene: &check::Scene) -> Result<Scene, Diagnostics> {
    // A one-off compile keeps nothing: no copy of the geometry in a cache.
    lower_cached(scene, &mut LowerCache::one_off())
}

/// Builds the IR, reusing from `cache` the meshes whose files did not change
/// and the whole geometry (primitives and BVH) when no shape, transform,
/// motion or mesh changed: a camera, material or settings edit in `watch`
/// neither reloads meshes nor rebuilds the BVH.
pub fn lower_cached(scene: &check::Scene, cache: &mut LowerCache) -> Result<Scene, Diagnostics> {
    let materials: Vec<Material> = scene.materials.iter().map(Material::from_checked).collect();
    if cache.is_one_off() {
        let geometry = build_geometry(scene, cache)?;
        return Ok(finish(scene, materials, geometry));
    }
    let key = cache.geometry_key(scene);
    // Shared, not copied: materials and lights live outside the geometry.
    let geometry = match cache.reuse_geometry(key) {
        Some(g) => g,
        None => {
            let g = build_geometry(scene, cache)?;
            cache.store_geometry(key, &g);
            g
        }
    };
    Ok(finish(scene, materials, geometry))
}

/// The part of the IR that depends only on shapes, transforms, motion and
/// mesh files; a clone shares it.
#[derive(Debug, Clone)]
pub struct Geometry {
    prims: Arc<Vec<Prim>>,
    normals: Arc<Vec<[Vec3; 3]>>,
    bounds: Aabb,
    wide: Arc<Bvh4>,
    /// Unbounded primitives (planes).
    unbounded: Arc<Vec<u32>>,
    /// The object each primitive came from.
    prim_object: Arc<Vec<u32>>,
}

fn build_geometry(scene: &check::Scene, cache: &mut LowerCache) -> Result<Geometry, Diagnostics> {
    let mut diags = Diagnostics::new();
    let mut prims: Vec<Prim> = Vec::new();
    let mut normals: Vec<[Vec3; 3]> = Vec::new();
    // The object each primitive came from, for diagnostics and spans.
    let mut prim_object: Vec<u32> = Vec::new();
    for (o, obj) in scene.objects.iter().enumerate() {
        let m = obj.transform;
        let pt = |p: DVec3| v3(m.transform_point3(p));
        let vec = |v: DVec3| v3(m.transform_vector3(v));
        let velocity = v3(obj.velocity);
        let mut push = |shape: Shape| {
            prims.push(Prim { shape, velocity });
        };
        match &obj.shape {
            check::Shape::Sphere { center, radius } => match uniform_scale(&m) {
                Some(s) => push(Shape::Sphere {
                    center: pt(*center),
                    radius: (radius * s) as f32,
                }),
                None => diags.push(non_uniform(obj.span, "sphere")),
            },
            check::Shape::Disk {
                center,
                normal,
                radius,
            } => match uniform_scale(&m) {
                Some(s) => push(Shape::Disk {
                    center: pt(*center),
                    normal: vec(*normal).normalize(),
                    radius: (radius * s) as f32,
                }),
                None => diags.push(non_uniform(obj.span, "disk")),
            },
            check::Shape::Plane { point, normal } => {
                let n = v3(m.inverse().transpose().transform_vector3(*normal)).normalize();
                push(Shape::Plane {
                    point: pt(*point),
                    normal: n,
                });
            }
            check::Shape::Quad {
                corner,
                edge1,
                edge2,
            } => push(Shape::Quad {
                p: pt(*corner),
                e1: vec(*edge1),
                e2: vec(*edge2),
            }),
            check::Shape::Triangle { v } => {
                let p0 = pt(v[0]);
                push(Shape::Triangle {
                    p0,
                    e1: pt(v[1]) - p0,
                    e2: pt(v[2]) - p0,
                    normals: u32::MAX,
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
                // Six faces with outward normals (e1 × e2 points out).
                let faces = [
                    (lo, ez, ey),
                    (lo + ex, ey, ez),
                    (lo, ex, ez),
                    (lo + ey, ez, ex),
                    (lo, ey, ex),
                    (lo + ez, ex, ey),
                ];
                // A mirroring transform flips the winding; keep normals outward.
                let flip = m.determinant() < 0.0;
                for (c, a, b) in faces {
                    let (a, b) = if flip { (b, a) } else { (a, b) };
                    push(Shape::Quad {
                        p: pt(c),
                        e1: vec(a),
                        e2: vec(b),
                    });
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
                let flip = m.determinant() < 0.0;
                let pos: Vec<Vec3> = data.positions.iter().map(|p| pt(p.as_dvec3())).collect();
                let nm = m.inverse().transpose();
                let use_normals = *smooth && !data.normals.is_empty();
                let vnormals: Vec<Vec3> = if use_normals {
                    data.normals
                        .iter()
                        .map(|n| v3(nm.transform_vector3(n.as_dvec3())).normalize_or_zero())
                        .collect()
                } else {
                    Vec::new()
                };
                let mut degenerate = 0usize;
                prims.reserve(data.triangles.len());
                for t in &data.triangles {
                    let [a, b, c] = if flip { [t[0], t[2], t[1]] } else { *t };
                    let p0 = pos[a as usize];
                    let (e1, e2) = (pos[b as usize] - p0, pos[c as usize] - p0);
                    if e1.cross(e2).length_squared() == 0.0 {
                        degenerate += 1;
                        continue;
                    }
                    let nidx = if use_normals {
                        normals.push([
                            vnormals[a as usize],
                            vnormals[b as usize],
                            vnormals[c as usize],
                        ]);
                        normals.len() as u32 - 1
                    } else {
                        u32::MAX
                    };
                    prims.push(Prim {
                        shape: Shape::Triangle {
                            p0,
                            e1,
                            e2,
                            normals: nidx,
                        },
                        velocity,
                    });
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
                }
            }
        }
        prim_object.resize(prims.len(), o as u32);
    }
    for (i, p) in prims.iter().enumerate() {
        let b = p.shape.bounds();
        let bad = match p.shape {
            Shape::Plane { .. } => !p.shape.normal_at(Vec3::ZERO).is_finite(),
            _ => !(b.min.is_finite() && b.max.is_finite()),
        };
        if bad {
            diags.push(
                Diagnostic::error(
                    codes::NOT_FINITE,
                    "this object's geometry is not finite after its transforms",
                    scene.objects[prim_object[i] as usize].span,
                )
                .with_label("NaN or infinite coordinates")
                .with_help("check the sizes and transforms for overflow"),
            );
            break;
        }
    }
    if diags.has_errors() {
        return Err(diags);
    }
    let mut bvh = build_bvh(&prims, scene.camera.shutter);
    // Store the primitives in the BVH's leaf order (planes last): a leaf's
    // primitives are then contiguous in memory, and the order is the identity.
    let mut permutation = bvh.order.clone();
    permutation.extend(
        (0..prims.len() as u32).filter(|&i| matches!(prims[i as usize].shape, Shape::Plane { .. })),
    );
    // In place: a second copy of a million primitives would double the peak memory.
    permute(&mut prims, &permutation);
    permute(&mut prim_object, &permutation);
    bvh.order = (0..bvh.order.len() as u32).collect();
    let wide = Bvh4::from_binary(&bvh, |i| packed_triangle(&prims[i as usize]));
    // The binary tree is dropped here: only the wide one is traversed.
    // The permutation put the planes last.
    let unbounded = (bvh.order.len() as u32..prims.len() as u32).collect();
    Ok(Geometry {
        prims: Arc::new(prims),
        normals: Arc::new(normals),
        bounds: bvh.bounds(),
        wide: Arc::new(wide),
        unbounded: Arc::new(unbounded),
        prim_object: Arc::new(prim_object),
    })
}

/// Reorders `v` in place so that the new `v[i]` is the old `v[perm[i]]`, by
/// following the permutation's cycles.
fn permute<T>(v: &mut [T], perm: &[u32]) {
    let mut done = vec![false; v.len()];
    for start in 0..v.len() {
        let mut i = start;
        while !done[i] {
            done[i] = true;
            let j = perm[i] as usize;
            if j == start {
                break;
            }
            v.swap(i, j);
            i = j;
        }
    }
}

/// A primitive the wide BVH tests four at a time in a
/// [`Tri4`](crate::geometry::tri4::Tri4): a triangle that does not move;
/// plain when it has no vertex normals.
fn packed_triangle(p: &Prim) -> Option<PackedTriangle> {
    match p.shape {
        Shape::Triangle {
            p0,
            e1,
            e2,
            normals,
        } if p.velocity == Vec3::ZERO => Some(PackedTriangle {
            vertices: [p0, e1, e2],
            plain: normals == u32::MAX,
        }),
        _ => None,
    }
}

/// BVH over bounded primitives, expanded over the shutter for moving ones
/// (planes are kept apart, see [`Scene::unbounded`]).
fn build_bvh(prims: &[Prim], shutter: (f64, f64)) -> Bvh {
    let (t0, t1) = (shutter.0 as f32, shutter.1 as f32);
    let mut bounded = Vec::with_capacity(prims.len());
    let mut boxes = Vec::with_capacity(prims.len());
    for (i, p) in prims.iter().enumerate() {
        if matches!(p.shape, Shape::Plane { .. }) {
            continue;
        }
        let b = p.shape.bounds();
        let b = if p.velocity != Vec3::ZERO {
            let m0 = Aabb {
                min: b.min + p.velocity * t0,
                max: b.max + p.velocity * t0,
            };
            let m1 = Aabb {
                min: b.min + p.velocity * t1,
                max: b.max + p.velocity * t1,
            };
            m0.union(m1)
        } else {
            b
        };
        bounded.push(i as u32);
        boxes.push(b);
    }
    let packable = |j: u32| packed_triangle(&prims[bounded[j as usize] as usize]).is_some();
    let mut bvh = Bvh::build(&boxes, &packable);
    // Map the BVH's order from positions in `bounded` to primitive indices.
    for o in bvh.order.iter_mut() {
        *o = bounded[*o as usize];
    }
    bvh
}

/// Lights, light selection and the camera on top of the geometry.
fn finish(scene: &check::Scene, materials: Vec<Material>, geometry: Geometry) -> Scene {
    let object_spans = scene.objects.iter().map(|o| o.span).collect();
    let object_material: Vec<u32> = scene.objects.iter().map(|o| o.material as u32).collect();
    let Geometry {
        prims,
        prim_object,
        normals,
        bounds,
        wide,
        unbounded,
    } = geometry;

    // Lights: emissive primitives (in order), explicit lights, the background.
    let emissive: Vec<bool> = object_material
        .iter()
        .map(|&m| materials[m as usize].emission != Vec3::ZERO)
        .collect();
    let area_lights: Vec<u32> = (0..prims.len() as u32)
        .filter(|&i| emissive[prim_object[i as usize] as usize])
        .collect();
    let mut lights: Vec<Light> = area_lights
        .iter()
        .map(|&prim| Light::Area { prim })
        .collect();
    for (l, _) in &scene.lights {
        lights.push(match l {
            check::Light::Point {
                position,
                intensity,
            } => Light::Point {
                position: v3(*position),
                intensity: rgb(intensity),
            },
            check::Light::Spot {
                position,
                direction,
                intensity,
                angle,
                falloff,
            } => Light::Spot {
                position: v3(*position),
                direction: v3(*direction),
                intensity: rgb(intensity),
                cos_total: angle.to_radians().cos() as f32,
                cos_falloff: falloff.to_radians().cos() as f32,
            },
            check::Light::Directional {
                direction,
                irradiance,
            } => Light::Directional {
                direction: v3(*direction),
                irradiance: rgb(irradiance),
            },
        });
    }
    let background = rgb(&scene.background);
    let env_light = (background != Vec3::ZERO).then(|| {
        lights.push(Light::Environment {
            radiance: background,
        });
        lights.len() as u32 - 1
    });

    let camera = Camera::new(&scene.camera, scene.render.width, scene.render.height);
    let mut ir = Scene {
        settings: scene.render.clone(),
        camera,
        prims,
        prim_object,
        object_spans,
        object_material,
        wide,
        unbounded,
        materials,
        normals,
        area_lights,
        lights,
        light_pmf: Vec::new(),
        light_cdf: Vec::new(),
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
    let powers: Vec<f32> = ir
        .lights
        .iter()
        .map(|l| l.power(&ir, scene_bounds).max(0.0))
        .collect();
    let total: f32 = powers.iter().sum();
    if total > 0.0 {
        ir.light_pmf = powers.iter().map(|p| p / total).collect();
        let mut acc = 0.0;
        ir.light_cdf = ir
            .light_pmf
            .iter()
            .map(|p| {
                acc += p;
                acc
            })
            .collect();
        *ir.light_cdf.last_mut().unwrap() = 1.0;
    } else {
        ir.lights.clear();
    }
    ir
}

fn rgb(c: &[f64; 3]) -> Vec3 {
    Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32)
}

fn non_uniform(span: crate::span::Span, what: &str) -> Diagnostic {
    Diagnostic::error(
        codes::SINGULAR_TRANSFORM,
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
    use super::permute;

    #[test]
    fn permute_in_place_matches_gathering() {
        let perm = [3u32, 0, 4, 1, 2, 6, 5, 7];
        let old: Vec<u32> = (10..18).collect();
        let mut v = old.clone();
        permute(&mut v, &perm);
        let want: Vec<u32> = perm.iter().map(|&i| old[i as usize]).collect();
        assert_eq!(v, want);
    }
}
