//! BVH build time and ray traversal throughput on the 1,003,520-triangle mesh
//! of `../shared/bench` (scene `mesh`). Run: `cargo bench --bench bvh`.
//!
//! - `build`: binned SAH build over the mesh's triangle bounds, on the global
//!   rayon pool (`RAYON_NUM_THREADS=2` for the 2-thread figure).
//! - `incoherent`: closest hits of rays with random origins inside the mesh's
//!   bounds and uniformly random directions, one thread (Mrays/s per core,
//!   comparable with Embree's incoherent-ray figure).
//! - `primary`: closest hits of the camera's rays (coherent), one thread.
//! - `shadow`: any-hit queries on the incoherent rays, one thread.
//! - `surface`: closest hits of rays that leave the points the camera's rays
//!   hit, sampled from their (grey diffuse) material as a path's first
//!   bounce is (the rays where ptsc trails Mitsuba's packets most, see
//!   docs/performance.md), one thread.
//! - `surface_shadow`: any-hit queries from the same points to points on
//!   the mesh scene's light (a quad above the blob), one thread.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::Vec3;
use ptsc::accel::bvh::Bvh;
use ptsc::compile::{compile_str, Options};
use ptsc::geometry::{offset_origin, shape::Shape, Aabb, Ray};
use ptsc::ir::Scene;
use std::path::{Path, PathBuf};

fn mesh_path() -> Option<PathBuf> {
    match ptsc::bench_data::ensure_mesh_blob(Path::new(env!("CARGO_MANIFEST_DIR"))) {
        Ok(p) => Some(p),
        Err(e) => {
            eprintln!("bvh bench skipped: cannot write the mesh blob: {e}");
            None
        }
    }
}

const RAYS: usize = 100_000;

fn load_scene() -> Option<Scene> {
    let path = mesh_path()?;
    let text = format!(
        "camera {{ position <0, 2, 5.5> look_at <0, 1, 0> fov 35 }}\n\
         mesh {{ file {:?} }}\n",
        path.to_str()?
    );
    compile_str(Path::new("bench.pts"), &text, Options::default()).ir
}

/// xorshift32 in [0, 1): deterministic rays, no dependency on the renderer's sampler.
fn uniform(state: &mut u32) -> f32 {
    *state ^= *state << 13;
    *state ^= *state >> 17;
    *state ^= *state << 5;
    (*state >> 8) as f32 / (1u32 << 24) as f32
}

fn incoherent_rays(scene: &Scene) -> Vec<Ray> {
    let b = scene.bounds;
    let mut s = 0x9e37_79b9;
    (0..RAYS)
        .map(|_| {
            let o = b.min
                + (b.max - b.min) * Vec3::new(uniform(&mut s), uniform(&mut s), uniform(&mut s));
            let z = 1.0 - 2.0 * uniform(&mut s);
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = std::f32::consts::TAU * uniform(&mut s);
            Ray::new(o, Vec3::new(r * phi.cos(), r * phi.sin(), z), 0.0)
        })
        .collect()
}

fn primary_rays() -> Vec<Ray> {
    // The mesh scene's camera: position <0, 2, 5.5>, look_at <0, 1, 0>, 35° vertical.
    let eye = Vec3::new(0.0, 2.0, 5.5);
    let forward = (Vec3::new(0.0, 1.0, 0.0) - eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let half = (35f32.to_radians() / 2.0).tan();
    let side = (RAYS as f32).sqrt() as usize;
    (0..side * side)
        .map(|i| {
            let (x, y) = ((i % side) as f32 + 0.5, (i / side) as f32 + 0.5);
            let (u, v) = (
                (2.0 * x / side as f32 - 1.0) * half,
                (1.0 - 2.0 * y / side as f32) * half,
            );
            Ray::new(eye, (forward + u * right + v * up).normalize(), 0.0)
        })
        .collect()
}

/// Rays leaving the surface points the camera's rays hit: sampled from the
/// surface's material as the path integrator does (closest-hit rays), and
/// toward points on the mesh scene's light with the distance to them
/// (shadow rays).
fn surface_rays(scene: &Scene, primary: &[Ray]) -> (Vec<Ray>, Vec<(Ray, f32)>) {
    let mut s = 0x2545_f491;
    let mut bounce = Vec::new();
    let mut shadow = Vec::new();
    for ray in primary {
        let Some(hit) = scene.intersect(ray, 0.0, f32::INFINITY) else {
            continue;
        };
        let u = glam::Vec2::new(uniform(&mut s), uniform(&mut s));
        let material = scene.material_of(hit.prim);
        if let Some(bs) = material.sample(-ray.d, hit.n_shading, uniform(&mut s), u) {
            let d = bs.wi;
            bounce.push(Ray::new(offset_origin(hit.p, hit.n_geo, d), d, 0.0));
        }
        // The light of examples/bench/mesh.pts: corner <-2.5, 4.5, 0>,
        // edges <2, 0, 0> and <0, 0, 2>.
        let q = Vec3::new(-2.5 + 2.0 * uniform(&mut s), 4.5, 2.0 * uniform(&mut s));
        let to = q - hit.p;
        let dist = to.length();
        let d = to / dist;
        shadow.push((Ray::new(offset_origin(hit.p, hit.n_geo, d), d, 0.0), dist));
    }
    (bounce, shadow)
}

fn bench(c: &mut Criterion) {
    let Some(scene) = load_scene() else {
        return;
    };
    // The triangles' boxes, as lowering computes them (the scene keeps no
    // per-triangle record of a flat mesh).
    let mesh = ptsc::lower::mesh::load(&ptsc::source::Disk, &mesh_path().expect("made above"))
        .expect("the mesh loads");
    let bounds: Vec<Aabb> = mesh
        .triangles
        .iter()
        .map(|t| {
            let [p0, p1, p2] = t.map(|i| mesh.positions[i as usize]);
            Shape::flat_triangle([p0, p1 - p0, p2 - p0]).bounds()
        })
        .collect();
    let mut g = c.benchmark_group("bvh_mesh_1M");
    g.sample_size(10);
    g.throughput(Throughput::Elements(bounds.len() as u64));
    // Every primitive of the mesh is a static triangle, packed in blocks.
    g.bench_function("build", |b| b.iter(|| Bvh::build(&bounds, &|_| true)));

    let incoherent = incoherent_rays(&scene);
    let primary = primary_rays();
    let (surface, surface_shadow) = surface_rays(&scene, &primary);
    // Rays that leave a surface start at the integrators' T_MIN.
    for (name, rays, t_min) in [
        ("incoherent", &incoherent, 0.0),
        ("primary", &primary, 0.0),
        ("surface", &surface, 1e-5),
    ] {
        g.throughput(Throughput::Elements(rays.len() as u64));
        g.bench_function(name, |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| scene.intersect(r, t_min, f32::INFINITY).is_some())
                    .count()
            })
        });
    }
    g.throughput(Throughput::Elements(incoherent.len() as u64));
    g.bench_function("shadow", |b| {
        b.iter(|| {
            incoherent
                .iter()
                .filter(|r| scene.occluded(r, 0.0, f32::INFINITY))
                .count()
        })
    });
    g.throughput(Throughput::Elements(surface_shadow.len() as u64));
    g.bench_function("surface_shadow", |b| {
        b.iter(|| {
            surface_shadow
                .iter()
                .filter(|(r, dist)| scene.occluded(r, 1e-5, dist * (1.0 - 1e-4)))
                .count()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
