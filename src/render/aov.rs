//! Arbitrary output variables (`--aov`): per pixel, what a denoiser or a
//! compositor wants beside the image — the albedo and the normal of the
//! first surface that is not a perfect mirror or glass (seen through those,
//! as Open Image Denoise asks), its distance and position, the object hit,
//! and the samples the pixel got. They are written as channels of the
//! EXR's one part (`albedo.R`, `normal.X`, …, see [`Aov::channels`]).
//!
//! The geometric AOVs are averaged over [`AOV_SAMPLES`] camera rays per
//! pixel at the beauty render's first sample positions (a pure function of
//! the seed and the pixel, like every sample): anti-aliased as the image
//! is, for a fraction of its cost.

use crate::geometry::Ray;
use crate::integrator::T_MIN;
use crate::ir::Scene;
use crate::render::film::Film;
use crate::sampling::sampler::Draws;
use glam::Vec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// An output variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Aov {
    /// The reflectance of the first non-specular surface, RGB in [0, 1].
    Albedo,
    /// Its shading normal in world space, raw in [-1, 1] (not the
    /// `0.5 + 0.5 n` of `--integrator normals`).
    Normal,
    /// The distance along the camera ray to the first surface (0: none).
    Depth,
    /// The first surface's point in world space.
    Position,
    /// The index of the object first hit, in source order (−1: none), from
    /// the pixel's first sample.
    Object,
    /// The samples the pixel's colour has.
    Samples,
    /// The variance of the pixel's colour (of its mean, per channel),
    /// estimated from the half images of its even and odd samples:
    /// ((even mean − odd mean) / 2)², unbiased but of few degrees of
    /// freedom (average it over a window for a smooth map). The render
    /// keeps the half images for it.
    Variance,
}

named_values!(Aov {
    "albedo" => Albedo,
    "normal" => Normal,
    "depth" => Depth,
    "position" => Position,
    "object" => Object,
    "samples" => Samples,
    "variance" => Variance,
});

impl Aov {
    /// The EXR channels it writes (Open Image Denoise's and Blender's names
    /// for the layers, with their usual channel letters).
    pub fn channels(self) -> &'static [&'static str] {
        match self {
            Aov::Albedo => &["albedo.R", "albedo.G", "albedo.B"],
            Aov::Normal => &["normal.X", "normal.Y", "normal.Z"],
            Aov::Depth => &["depth.Z"],
            Aov::Position => &["position.X", "position.Y", "position.Z"],
            Aov::Object => &["object.id"],
            Aov::Samples => &["samples.count"],
            Aov::Variance => &["variance.R", "variance.G", "variance.B"],
        }
    }
}

/// Camera rays per pixel for the geometric AOVs.
pub const AOV_SAMPLES: u32 = 16;

/// Perfect mirrors and glass followed to the surface seen through them.
const SPECULAR_BOUNCES: u32 = 8;

/// What one camera ray finds for the AOVs.
#[derive(Debug, Clone, Copy, Default)]
struct FirstSurface {
    albedo: Vec3,
    normal: Vec3,
    position: Vec3,
    depth: f32,
    object: Option<u32>,
}

/// The first non-specular surface along `ray` (through up to
/// [`SPECULAR_BOUNCES`] perfect mirrors and glass, and through `type none`
/// boundaries, which are not surfaces); its depth is the first hit's
/// distance, as a compositor's depth pass is.
fn first_surface(
    scene: &Scene,
    mut ray: Ray,
    sampler: &mut crate::sampling::sampler::Sampler,
) -> FirstSurface {
    let mut found = FirstSurface::default();
    let mut crossings = 0;
    // The distance to the boundaries crossed before the first surface.
    let mut before = 0.0;
    for bounce in 0..=SPECULAR_BOUNCES {
        let Some(mut hit) = scene.intersect(&ray, T_MIN, f32::INFINITY) else {
            return found;
        };
        let wo = -ray.d;
        let mut textured = None;
        let mut material = scene.material_at(&mut hit, wo, ray.time, &mut textured);
        while material.is_null() && crossings < crate::ir::media::MAX_CROSSINGS {
            crossings += 1;
            if bounce == 0 {
                before += hit.t;
            }
            let from = crate::geometry::offset_origin(hit.p, hit.n_geo, ray.d);
            ray = Ray::new(from, ray.d, ray.time);
            let Some(next) = scene.intersect(&ray, T_MIN, f32::INFINITY) else {
                return found;
            };
            hit = next;
            material = scene.material_at(&mut hit, wo, ray.time, &mut textured);
        }
        if bounce == 0 {
            found.depth = before + hit.t;
            found.object = scene.prim_object.get(hit.prim as usize).copied();
        }
        (found.albedo, found.normal, found.position) = (material.albedo(), hit.n_shading, hit.p);
        if material.has_smooth_lobe() || !material.scatters() {
            return found;
        }
        sampler.start(bounce, Draws::Bsdf);
        let Some(bs) = material.sample(wo, hit.n_shading, sampler.next_f32(), sampler.next_2d())
        else {
            return found;
        };
        ray = Ray::new(
            crate::geometry::offset_origin(hit.p, hit.n_geo, bs.wi),
            bs.wi,
            ray.time,
        );
    }
    found
}

/// The values of `aovs` for every pixel of `film`'s render of `scene`,
/// each as its channels' planes one after the other (`None` when
/// cancelled).
pub fn render_aovs(
    scene: &Scene,
    aovs: &[Aov],
    film: &Film,
    cancel: &AtomicBool,
) -> Option<Vec<(Aov, Vec<Vec<f32>>)>> {
    let (w, h) = (film.width, film.height);
    let spp = AOV_SAMPLES.min(scene.settings.samples).max(1);
    let rows: Vec<Vec<FirstSurface>> = (0..h)
        .into_par_iter()
        .map(|y| {
            if cancel.load(Ordering::Relaxed) {
                return Vec::new();
            }
            (0..w).map(|x| pixel(scene, (x, y), spp)).collect()
        })
        .collect();
    if cancel.load(Ordering::Relaxed) {
        return None;
    }
    let surfaces: Vec<FirstSurface> = rows.into_iter().flatten().collect();
    let planes = |f: &dyn Fn(&FirstSurface) -> Vec3, n: usize| -> Vec<Vec<f32>> {
        (0..n)
            .map(|c| surfaces.iter().map(|s| f(s)[c]).collect())
            .collect()
    };
    let values = aovs
        .iter()
        .map(|&aov| {
            let v = match aov {
                Aov::Albedo => planes(&|s| s.albedo, 3),
                Aov::Normal => planes(&|s| s.normal, 3),
                Aov::Position => planes(&|s| s.position, 3),
                Aov::Depth => planes(&|s| Vec3::splat(s.depth), 1),
                Aov::Object => planes(&|s| Vec3::splat(s.object.map_or(-1.0, |o| o as f32)), 1),
                Aov::Samples => vec![film.count.iter().map(|&n| n as f32).collect()],
                Aov::Variance => variance_planes(film),
            };
            (aov, v)
        })
        .collect();
    Some(values)
}

/// The variance of each pixel's mean from its half images, as three
/// planes (0 where the film keeps no half images or a pixel has fewer than
/// two samples).
fn variance_planes(film: &Film) -> Vec<Vec<f32>> {
    let variance = |i: usize| -> Vec3 {
        let Some(halves) = &film.halves else {
            return Vec3::ZERO;
        };
        match super::adaptive::half_means(film.sum[i], halves.odd[i], film.count[i]) {
            Some((even, odd)) => {
                let half_difference = (even - odd) / 2.0;
                (half_difference * half_difference).as_vec3()
            }
            None => Vec3::ZERO,
        }
    };
    let pixels: Vec<Vec3> = (0..film.count.len()).map(variance).collect();
    (0..3)
        .map(|c| pixels.iter().map(|v| v[c]).collect())
        .collect()
}

/// The albedo and normal a denoiser is guided by, for an image `size`
/// whose pixels each cover `scale` × `scale` of the scene's (a live
/// render's preview), from `spp` camera rays per pixel; `None` when
/// cancelled.
pub fn denoiser_guides(
    scene: &Scene,
    size: (u32, u32),
    scale: u32,
    spp: u32,
    cancel: &AtomicBool,
) -> Option<(Vec<Vec3>, Vec<Vec3>)> {
    let rows: Vec<Vec<FirstSurface>> = (0..size.1)
        .into_par_iter()
        .map(|y| match cancel.load(Ordering::Relaxed) {
            true => Vec::new(),
            false => (0..size.0)
                .map(|x| pixel_of(scene, (x, y), scale, spp))
                .collect(),
        })
        .collect();
    if cancel.load(Ordering::Relaxed) {
        return None;
    }
    let surfaces = rows.into_iter().flatten();
    Some(surfaces.map(|s| (s.albedo, s.normal)).unzip())
}

/// One pixel's AOVs: the mean over `spp` camera rays (the normal
/// renormalised), the object of the first ray that hits.
fn pixel(scene: &Scene, (x, y): (u32, u32), spp: u32) -> FirstSurface {
    pixel_of(scene, (x, y), 1, spp)
}

/// [`pixel`] of an image whose pixels each cover `scale` × `scale` of the
/// scene's.
fn pixel_of(scene: &Scene, (x, y): (u32, u32), scale: u32, spp: u32) -> FirstSurface {
    let pixels = super::pixel_sampler(scene, x, y);
    let mut mean = FirstSurface::default();
    for i in 0..spp {
        let mut sampler = pixels.sample(i);
        let ray = super::camera_ray(scene, &mut sampler, (x, y), scale as f32);
        let f = first_surface(scene, ray, &mut sampler);
        mean.albedo += f.albedo;
        mean.normal += f.normal;
        mean.position += f.position;
        mean.depth += f.depth;
        mean.object = mean.object.or(f.object);
    }
    let n = spp as f32;
    FirstSurface {
        albedo: mean.albedo / n,
        normal: mean.normal.normalize_or_zero(),
        position: mean.position / n,
        depth: mean.depth / n,
        object: mean.object,
    }
}
