//! Light leaving the lights: where a light path starts (bidirectional path
//! tracing). An area light emits from a point chosen uniformly on its
//! surface into a cosine-weighted direction, a point light uniformly over
//! the sphere, a spot light uniformly within its cone (pbrt-v4 §12.1–12.2,
//! `SampleLe`). Lights at infinity start no light paths: the paths that end
//! on them are left to the camera's side (see `integrator::bdpt`).

use super::Light;
use crate::sampling::distribution::Distribution1D;
use crate::sampling::warp::{cosine_hemisphere, uniform_sphere, UNIFORM_SPHERE_PDF};
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// The start of a light path.
#[derive(Debug, Clone, Copy)]
pub struct Emission {
    /// Where it leaves the light.
    pub p: Vec3,
    /// The light's normal there (zero for a point or spot light).
    pub n: Vec3,
    /// The direction it leaves in (unit).
    pub dir: Vec3,
    /// Radiance (an area light's) or intensity (a point or spot light's)
    /// along `dir`.
    pub le: Vec3,
    /// Density of `p` by area (1 for a light at a point: a delta).
    pub pdf_pos: f32,
    /// Density of `dir` by solid angle.
    pub pdf_dir: f32,
}

impl Light {
    /// Whether light paths start on it: area, point and spot lights
    /// (lights at infinity do not).
    pub fn starts_paths(&self) -> bool {
        matches!(
            self,
            Light::Area { .. } | Light::Point { .. } | Light::Spot { .. }
        )
    }

    /// Samples where and in which direction light leaves it at `time`.
    /// `emitted(prim, q, uv, n, wo)` is an emissive primitive's radiance
    /// (see [`Light::sample`]); `two_sided` whether an area light's
    /// material emits on both sides (a side is then chosen evenly, as
    /// [`Light::emission_pdfs`] counts it). `None` where nothing leaves.
    pub fn sample_emission(
        &self,
        emitted: impl Fn(u32, Vec3, Vec2, Vec3, Vec3) -> Vec3,
        (time, two_sided): (f32, bool),
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> Option<Emission> {
        let e = match self {
            Light::Area {
                prim,
                shape,
                velocity,
                area,
            } => {
                let (q, n, uv) = shape.sample_area(u_pos);
                let q = q + *velocity * time;
                // A two-sided emitter picks a side with half of u_dir.x,
                // the rest rescaled. (From its material, not from the light
                // its back sends at this point: the densities the MIS
                // weights read must be the ones sampled.)
                let (n_side, u, sides) = match (two_sided, u_dir.x < 0.5) {
                    (false, _) => (n, u_dir, 1.0),
                    (true, true) => (n, Vec2::new(2.0 * u_dir.x, u_dir.y), 0.5),
                    (true, false) => (-n, Vec2::new(2.0 * u_dir.x - 1.0, u_dir.y), 0.5),
                };
                let l = cosine_hemisphere(u);
                let (t, b) = crate::geometry::orthonormal_basis(n_side);
                let dir = (l.x * t + l.y * b + l.z * n_side).normalize();
                let le = emitted(*prim, q, uv, n, dir);
                if le == Vec3::ZERO || l.z <= 0.0 {
                    return None;
                }
                Emission {
                    p: q,
                    n,
                    dir,
                    le,
                    pdf_pos: 1.0 / area,
                    pdf_dir: l.z * FRAC_1_PI * sides,
                }
            }
            Light::Point {
                position,
                intensity,
            } => Emission {
                p: *position,
                n: Vec3::ZERO,
                dir: uniform_sphere(u_dir),
                le: *intensity,
                pdf_pos: 1.0,
                pdf_dir: UNIFORM_SPHERE_PDF,
            },
            Light::Spot {
                position,
                direction,
                intensity,
                cos_total,
                cos_hotspot,
            } => {
                let l = uniform_cone(u_dir, *cos_total);
                let (t, b) = crate::geometry::orthonormal_basis(*direction);
                let dir = (l.x * t + l.y * b + l.z * *direction).normalize();
                let k = super::spot_falloff(dir.dot(*direction), *cos_total, *cos_hotspot);
                if k <= 0.0 {
                    return None;
                }
                Emission {
                    p: *position,
                    n: Vec3::ZERO,
                    dir,
                    le: *intensity * k,
                    pdf_pos: 1.0,
                    pdf_dir: uniform_cone_pdf(*cos_total),
                }
            }
            Light::Directional { .. } | Light::Environment { .. } | Light::Sky { .. } => {
                return None
            }
        };
        (e.pdf_dir > 0.0 && e.pdf_pos > 0.0 && e.le.is_finite()).then_some(e)
    }

    /// The densities with which [`Light::sample_emission`] starts a path at
    /// `p` (normal `n`, an area light's) in direction `dir`: by area and by
    /// solid angle. `two_sided` is whether the area light emits on both
    /// sides. Zero for lights that start no paths.
    pub fn emission_pdfs(&self, n: Vec3, dir: Vec3, two_sided: bool) -> (f32, f32) {
        match self {
            Light::Area { area, .. } => {
                let cos = n.dot(dir);
                let cos = if two_sided { cos.abs() * 0.5 } else { cos };
                (1.0 / area, cos.max(0.0) * FRAC_1_PI)
            }
            Light::Point { .. } => (1.0, UNIFORM_SPHERE_PDF),
            Light::Spot {
                direction,
                cos_total,
                ..
            } => {
                let inside = dir.dot(*direction) > *cos_total;
                (
                    1.0,
                    if inside {
                        uniform_cone_pdf(*cos_total)
                    } else {
                        0.0
                    },
                )
            }
            _ => (0.0, 0.0),
        }
    }
}

/// A direction uniform in the cone of half-angle cosine `cos_max` about +z.
fn uniform_cone(u: Vec2, cos_max: f32) -> Vec3 {
    let cos = 1.0 - u.x * (1.0 - cos_max);
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(sin * phi.cos(), sin * phi.sin(), cos)
}

/// Density of [`uniform_cone`].
fn uniform_cone_pdf(cos_max: f32) -> f32 {
    1.0 / (2.0 * PI * (1.0 - cos_max)).max(1e-12)
}

/// Which light a light path starts on: chosen by power among the lights
/// that start paths.
#[derive(Debug, Clone)]
pub struct EmissionSelection {
    /// The lights that start paths, by index into the scene's lights.
    lights: Vec<u32>,
    /// Their powers' distribution.
    dist: Distribution1D,
    /// Each light's probability of being chosen (0 for the others).
    pmf: Vec<f32>,
}

impl EmissionSelection {
    /// The selection over `lights` with powers `powers` (by index);
    /// `None` when no light starts paths.
    pub fn new(lights: &[Light], powers: &[f64]) -> Option<EmissionSelection> {
        let chosen: Vec<u32> = (0..lights.len() as u32)
            .filter(|&i| lights[i as usize].starts_paths() && powers[i as usize] > 0.0)
            .collect();
        if chosen.is_empty() {
            return None;
        }
        let most = chosen
            .iter()
            .map(|&i| powers[i as usize])
            .fold(0.0, f64::max);
        let weights: Vec<f32> = chosen
            .iter()
            .map(|&i| (powers[i as usize] / most) as f32)
            .collect();
        let dist = Distribution1D::new(&weights);
        let total: f64 = weights.iter().map(|&w| w as f64).sum();
        let mut pmf = vec![0.0; lights.len()];
        for (&i, &w) in chosen.iter().zip(&weights) {
            pmf[i as usize] = (w as f64 / total) as f32;
        }
        Some(EmissionSelection {
            lights: chosen,
            dist,
            pmf,
        })
    }

    /// Chooses a light: its index and probability.
    pub fn sample(&self, u: f32) -> (u32, f32) {
        let (_, _, bin) = self.dist.sample(u);
        let light = self.lights[bin.min(self.lights.len() - 1)];
        (light, self.pmf[light as usize])
    }

    /// The probability of choosing light `light`.
    pub fn pmf(&self, light: u32) -> f32 {
        self.pmf.get(light as usize).copied().unwrap_or(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::shape::Shape;

    #[test]
    fn emission_carries_each_light_s_power_and_states_its_own_densities() {
        // A one-sided quad of radiance 2 and area 0.5 sends π · 2 · 0.5;
        // a point light of intensity 3 sends 4π · 3; a spot light of
        // intensity 1 with a hard cone of cosine 0.5 sends 2π (1 − 0.5).
        let quad = Shape::Quad {
            p: Vec3::ZERO,
            e1: Vec3::X,
            e2: Vec3::new(0.0, 0.0, 0.5),
            swapped: false,
        };
        let n_quad = quad.sample_area(Vec2::splat(0.5)).1;
        let lights = [
            (Light::area(0, quad, Vec3::ZERO), PI * 2.0 * 0.5),
            (
                Light::Point {
                    position: Vec3::ONE,
                    intensity: Vec3::splat(3.0),
                },
                4.0 * PI * 3.0,
            ),
            (
                Light::Spot {
                    position: Vec3::ZERO,
                    direction: Vec3::Y,
                    intensity: Vec3::ONE,
                    cos_total: 0.5,
                    cos_hotspot: 0.5,
                },
                2.0 * PI * 0.5,
            ),
        ];
        let emitted = |_, _, _, n: Vec3, w: Vec3| {
            if w.dot(n) > 0.0 {
                Vec3::splat(2.0)
            } else {
                Vec3::ZERO
            }
        };
        let mut rng = crate::light::test_rng(7);
        for (light, power) in lights {
            let k = 200_000;
            let mut sum = 0.0f64;
            for _ in 0..k {
                let u = [rng(), rng(), rng(), rng()];
                let u_pos = Vec2::new(u[0], u[1]);
                let u_dir = Vec2::new(u[2], u[3]);
                let Some(e) = light.sample_emission(emitted, (0.0, false), u_pos, u_dir) else {
                    continue;
                };
                let cos = if e.n == Vec3::ZERO {
                    1.0
                } else {
                    e.n.dot(e.dir).abs()
                };
                sum += (e.le.x * cos / (e.pdf_pos * e.pdf_dir)) as f64;
                let (pos, dir) = light.emission_pdfs(n_quad, e.dir, false);
                assert!((pos - e.pdf_pos).abs() < 1e-5 * pos.max(1.0));
                assert!(
                    (dir - e.pdf_dir).abs() < 1e-4 * dir.max(1.0),
                    "{dir} vs {}",
                    e.pdf_dir
                );
            }
            let estimate = sum / k as f64;
            assert!(
                (estimate / power as f64 - 1.0).abs() < 0.01,
                "{estimate} vs {power}"
            );
        }
    }
}

#[cfg(test)]
mod two_sided_tests {
    use super::*;
    use crate::geometry::shape::Shape;

    #[test]
    fn a_two_sided_emitter_sends_from_both_sides_with_the_densities_it_states() {
        // Radiance 2 on both sides of a quad of area 0.5: 2 · π · 2 · 0.5.
        let quad = Shape::Quad {
            p: Vec3::ZERO,
            e1: Vec3::X,
            e2: Vec3::new(0.0, 0.0, 0.5),
            swapped: false,
        };
        let light = Light::area(0, quad, Vec3::ZERO);
        let emitted = |_, _, _, _, _| Vec3::splat(2.0);
        let mut rng = crate::light::test_rng(11);
        let (k, mut sum, mut back) = (200_000, 0.0f64, 0);
        for _ in 0..k {
            let (u_pos, u_dir) = (Vec2::new(rng(), rng()), Vec2::new(rng(), rng()));
            let e = light
                .sample_emission(emitted, (0.0, true), u_pos, u_dir)
                .unwrap();
            let cos = e.n.dot(e.dir);
            back += (cos < 0.0) as u32;
            sum += (e.le.x * cos.abs() / (e.pdf_pos * e.pdf_dir)) as f64;
            let (_, dir) = light.emission_pdfs(e.n, e.dir, true);
            assert!((dir - e.pdf_dir).abs() < 1e-4 * dir.max(1.0));
        }
        let power = 2.0 * PI as f64 * 2.0 * 0.5;
        assert!((sum / k as f64 / power - 1.0).abs() < 0.01);
        assert!((back as f64 / k as f64 - 0.5).abs() < 0.01, "{back}");
    }
}
