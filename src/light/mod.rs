//! Lights: emissive shapes (area lights), point, spot and directional lights
//! and the constant background. Each can be sampled from a shading point;
//! which light a shadow ray goes to is [`selection`]'s choice.

pub mod bounds;
pub mod emission;
pub mod environment;
pub mod selection;
pub mod sky;
pub mod sphere;
mod sun_table;
pub mod tree;

use crate::geometry::shape::Shape;
use crate::geometry::Aabb;
use bounds::LightBounds;
use glam::{Vec2, Vec3};
use selection::Selectable;

/// One light.
#[derive(Debug, Clone)]
pub enum Light {
    /// An emissive primitive.
    Area {
        /// Index of the primitive.
        prim: u32,
        /// Its shape (a copy: a plain mesh triangle has no record to read).
        shape: Shape,
        /// Its linear motion per unit time.
        velocity: Vec3,
        /// The shape's area, kept: every light sample and pdf divides by
        /// it (a quad's cross product and square root each time were 1 %
        /// of the Cornell box's instructions).
        area: f32,
    },
    /// Isotropic point light.
    Point {
        /// Position.
        position: Vec3,
        /// Radiant intensity.
        intensity: Vec3,
    },
    /// Spot light with a smooth fall-off (pbrt-v4 §12.2.1).
    Spot {
        /// Position.
        position: Vec3,
        /// Unit axis.
        direction: Vec3,
        /// Intensity on the axis.
        intensity: Vec3,
        /// Cosine of the cone's half-angle.
        cos_total: f32,
        /// Cosine of the hot spot's half-angle: full light inside it, the
        /// fall-off from it to the cone's edge.
        cos_hotspot: f32,
    },
    /// Light from infinitely far away along `direction`.
    Directional {
        /// Unit direction the light travels.
        direction: Vec3,
        /// Irradiance.
        irradiance: Vec3,
    },
    /// Light from every direction: the background, a constant radiance or
    /// an environment map scaled by it.
    Environment {
        /// Radiance (the map's scale when there is one).
        radiance: Vec3,
        /// The map, if any (shared by clones of the scene).
        map: Option<std::sync::Arc<environment::EnvironmentMap>>,
    },
    /// A daylight sky and its sun, at infinity.
    Sky {
        /// The sky (shared by clones of the scene).
        sky: std::sync::Arc<sky::SunSky>,
    },
}

/// Light arriving at a point from a sampled light.
#[derive(Debug, Clone, Copy)]
pub struct LightSample {
    /// Unit direction towards the light.
    pub wi: Vec3,
    /// Distance to the light (infinite for distant lights).
    pub dist: f32,
    /// Radiance (or, for delta lights, irradiance-like value already divided by r²).
    pub li: Vec3,
    /// Pdf in solid angle (not including the choice of the light); 0 for delta lights.
    pub pdf: f32,
    /// The light's geometric normal at the point (an area light's; zero
    /// for the others).
    pub n: Vec3,
}

/// Luminance of linear sRGB.
pub fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// Smooth fall-off of a spot light (pbrt-v4 eq. 12.3: smoothstep).
pub fn spot_falloff(cos: f32, cos_total: f32, cos_hotspot: f32) -> f32 {
    if cos >= cos_hotspot {
        return 1.0;
    }
    if cos <= cos_total {
        return 0.0;
    }
    let t = (cos - cos_total) / (cos_hotspot - cos_total);
    t * t * (3.0 - 2.0 * t)
}

/// What an emissive primitive sends, as light selection weighs it: the
/// luminance of its radiance averaged over its surface (a textured
/// emitter's texture's mean there, not its brightest texel) and whether it
/// emits on both sides.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Emitter {
    /// Mean luminance of the emitted radiance over the surface.
    pub radiance: f64,
    /// Whether it emits on both sides.
    pub two_sided: bool,
}

/// The luminance of a colour, in f64.
fn luminance64(c: Vec3) -> f64 {
    luminance_of(c.as_dvec3())
}

/// The luminance of a colour given in f64 (a bright map times a large
/// intensity overflows f32).
fn luminance_of(c: glam::DVec3) -> f64 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

impl Light {
    /// The light of emissive primitive `prim` of `shape`, moving by
    /// `velocity` per unit time.
    pub fn area(prim: u32, shape: Shape, velocity: Vec3) -> Light {
        Light::Area {
            prim,
            shape,
            velocity,
            area: shape.area(),
        }
    }

    /// Power used by the `power` rule to choose among lights, and to find
    /// the lights that emit at all (any positive value keeps the estimate
    /// unbiased). In f64: products of large accepted values (an
    /// emission of 1e12 over an area of 4e18) and their sum over many
    /// lights stay finite. `emitter` is what an area light emits (see
    /// [`Emitter`]); lights at infinity are measured over the sphere
    /// bounding `bounds`.
    pub fn power(&self, emitter: Emitter, bounds: Aabb) -> f64 {
        let radius = 0.5 * ((bounds.max - bounds.min).length() as f64).min(1e6);
        let lum = luminance64;
        let pi = std::f64::consts::PI;
        match self {
            Light::Area { shape, .. } => {
                let sides = if emitter.two_sided { 2.0 } else { 1.0 };
                emitter.radiance * shape.area() as f64 * pi * sides
            }
            Light::Point { intensity, .. } => 4.0 * pi * lum(*intensity),
            Light::Spot {
                intensity,
                cos_total,
                cos_hotspot,
                ..
            } => {
                2.0 * pi * lum(*intensity) * (1.0 - 0.5 * (*cos_total as f64 + *cos_hotspot as f64))
            }
            Light::Directional { irradiance, .. } => pi * radius * radius * lum(*irradiance),
            Light::Environment { .. } | Light::Sky { .. } => {
                4.0 * pi * pi * radius * radius * self.mean_radiance()
            }
        }
    }

    /// The luminance of a light at infinity's radiance averaged over the
    /// sphere of directions (0 for the others).
    fn mean_radiance(&self) -> f64 {
        match self {
            Light::Environment { radiance, map } => {
                let mean = map.as_ref().map_or(Vec3::ONE, |m| m.mean());
                luminance_of(radiance.as_dvec3() * mean.as_dvec3())
            }
            Light::Sky { sky } => luminance64(sky.mean()),
            _ => 0.0,
        }
    }

    /// What the light selection needs to know of the light: its
    /// [`LightBounds`] over the shutter interval `(t0, t1)`, or its weight
    /// at infinity. `emitter` is what an area light emits.
    pub fn selectable(&self, emitter: Emitter, (t0, t1): (f32, f32)) -> Selectable {
        let lum = luminance64;
        let four_pi = 4.0 * std::f64::consts::PI;
        let at = |p: Vec3| Aabb { min: p, max: p };
        let everywhere = |bounds, phi| LightBounds {
            bounds,
            w: Vec3::Z,
            phi,
            cos_o: -1.0,
            cos_e: 0.0,
            two_sided: false,
        };
        Selectable::Bounded(match self {
            Light::Area {
                shape, velocity, ..
            } => {
                let b = shape.bounds();
                let moved = |t: f32| Aabb {
                    min: b.min + *velocity * t,
                    max: b.max + *velocity * t,
                };
                let bounds = moved(t0).union(moved(t1));
                let phi = self.power(emitter, b);
                match shape {
                    // Round shapes face every way.
                    Shape::Sphere { .. } | Shape::Round(_) => everywhere(bounds, phi),
                    _ => LightBounds {
                        bounds,
                        // The emitting side, as `Material::emitted` sees it.
                        w: shape.sample_area(Vec2::splat(0.5)).1,
                        phi,
                        cos_o: 1.0,
                        cos_e: 0.0,
                        two_sided: emitter.two_sided,
                    },
                }
            }
            Light::Point {
                position,
                intensity,
            } => everywhere(at(*position), four_pi * lum(*intensity)),
            Light::Spot {
                position,
                direction,
                intensity,
                cos_total,
                cos_hotspot,
            } => {
                // The cone is in the bounds, so the power is a point
                // light's (as pbrt-v4's `SpotLight::Bounds`).
                // A milliradian of slack: the edge of a hard cone must not
                // round to outside it.
                let (total, falloff) = (cos_total.acos() + 1e-3, cos_hotspot.acos());
                LightBounds {
                    bounds: at(*position),
                    w: *direction,
                    phi: four_pi * lum(*intensity),
                    cos_o: *cos_hotspot,
                    cos_e: (total - falloff).max(0.0).cos(),
                    two_sided: false,
                }
            }
            // At infinity: an estimate of the irradiance it brings, in
            // the units of a bounded light's importance (power ÷ squared
            // distance, which for a diffuse area light is π × its
            // irradiance): π E for a directional light (on a surface
            // facing it), π · π L̄ for light from every direction of mean
            // radiance L̄ (a hemisphere's irradiance).
            Light::Directional {
                direction,
                irradiance,
            } => {
                return Selectable::Infinite {
                    weight: std::f64::consts::PI * lum(*irradiance),
                    axis: *direction,
                }
            }
            Light::Environment { .. } | Light::Sky { .. } => {
                return Selectable::Infinite {
                    weight: std::f64::consts::PI.powi(2) * self.mean_radiance(),
                    axis: Vec3::ZERO,
                }
            }
        })
    }

    /// Samples light arriving at `p`. `time` is the ray's: a moving emitter
    /// is sampled where it is then. `emitted(prim, q, uv, n, wo)` is the
    /// radiance an emissive primitive sends towards `wo` from its point `q`
    /// with surface parameters `uv` and normal `n` (its texture read there).
    #[inline(always)]
    pub fn sample(
        &self,
        emitted: impl Fn(u32, Vec3, Vec2, Vec3, Vec3) -> Vec3,
        p: Vec3,
        time: f32,
        u: Vec2,
    ) -> Option<LightSample> {
        match self {
            Light::Area {
                prim,
                shape: Shape::Sphere { center, radius },
                velocity,
                ..
            } if sphere::cone_pdf(*center + *velocity * time, *radius, p).is_some() => {
                // From outside: by the cone the sphere subtends.
                let (q, n, pdf) = sphere::sample_cone(*center + *velocity * time, *radius, p, u)?;
                let to = q - p;
                let dist = to.length();
                if dist == 0.0 {
                    return None;
                }
                let wi = to / dist;
                let li = emitted(*prim, q, Vec2::ZERO, n, -wi);
                (li != Vec3::ZERO).then_some(LightSample {
                    wi,
                    dist,
                    li,
                    pdf,
                    n,
                })
            }
            Light::Area {
                prim,
                shape,
                velocity,
                area,
            } => {
                let (q, n, uv) = shape.sample_area(u);
                let q = q + *velocity * time;
                let to = q - p;
                let d2 = to.length_squared();
                if d2 == 0.0 {
                    return None;
                }
                let dist = d2.sqrt();
                let wi = to / dist;
                let cos_l = n.dot(-wi);
                let li = emitted(*prim, q, uv, n, -wi);
                if li == Vec3::ZERO || cos_l.abs() < 1e-7 {
                    return None;
                }
                let pdf = d2 / (cos_l.abs() * area);
                Some(LightSample {
                    wi,
                    dist,
                    li,
                    pdf,
                    n,
                })
            }
            Light::Point {
                position,
                intensity,
            } => {
                let to = *position - p;
                let d2 = to.length_squared();
                let dist = d2.sqrt();
                Some(LightSample {
                    wi: to / dist,
                    dist,
                    li: *intensity / d2,
                    pdf: 0.0,
                    n: Vec3::ZERO,
                })
            }
            Light::Spot {
                position,
                direction,
                intensity,
                cos_total,
                cos_hotspot,
            } => {
                let to = *position - p;
                let d2 = to.length_squared();
                let dist = d2.sqrt();
                let wi = to / dist;
                let k = spot_falloff((-wi).dot(*direction), *cos_total, *cos_hotspot);
                (k > 0.0).then(|| LightSample {
                    wi,
                    dist,
                    li: *intensity * k / d2,
                    pdf: 0.0,
                    n: Vec3::ZERO,
                })
            }
            Light::Directional {
                direction,
                irradiance,
            } => Some(LightSample {
                wi: -*direction,
                dist: f32::INFINITY,
                li: *irradiance,
                pdf: 0.0,
                n: Vec3::ZERO,
            }),
            Light::Environment {
                radiance,
                map: None,
            } => {
                let wi = crate::sampling::warp::uniform_sphere(u);
                Some(LightSample {
                    wi,
                    dist: f32::INFINITY,
                    li: *radiance,
                    pdf: crate::sampling::warp::UNIFORM_SPHERE_PDF,
                    n: Vec3::ZERO,
                })
            }
            Light::Environment {
                radiance,
                map: Some(map),
            } => {
                let (wi, li, pdf) = map.sample(u)?;
                Some(LightSample {
                    wi,
                    dist: f32::INFINITY,
                    li: *radiance * li,
                    pdf,
                    n: Vec3::ZERO,
                })
            }
            Light::Sky { sky } => {
                let (wi, li, pdf) = sky.sample(u)?;
                Some(LightSample {
                    wi,
                    dist: f32::INFINITY,
                    li,
                    pdf,
                    n: Vec3::ZERO,
                })
            }
        }
    }

    /// The radiance an environment light sends along `-d` (arriving from
    /// the direction `d`); zero for the other lights.
    pub fn arriving_from(&self, d: Vec3) -> Vec3 {
        match self {
            Light::Environment { radiance, map } => match map {
                Some(m) => *radiance * m.eval(d),
                None => *radiance,
            },
            Light::Sky { sky } => sky.eval(d),
            _ => Vec3::ZERO,
        }
    }

    /// The density in solid angle with which [`Light::sample`] picks the
    /// direction `d` of an environment light (0 for the other lights).
    pub fn direction_pdf(&self, d: Vec3) -> f32 {
        match self {
            Light::Environment { map: Some(m), .. } => m.pdf(d),
            Light::Environment { map: None, .. } => crate::sampling::warp::UNIFORM_SPHERE_PDF,
            Light::Sky { sky } => sky.pdf(d),
            _ => 0.0,
        }
    }

    /// The density in solid angle with which [`Light::sample`] from the
    /// point `from` picks the direction `dir` that reaches this light at
    /// the point `p` with geometric normal `n` (a surface hit on an area
    /// light; ignored for lights at infinity); 0 for delta lights.
    #[inline]
    pub fn pdf_towards(&self, from: Vec3, dir: Vec3, p: Vec3, n: Vec3) -> f32 {
        match self {
            Light::Area { shape, area, .. } => {
                if let Shape::Sphere { radius, .. } = shape {
                    // Sampled by its cone from outside; the centre where the
                    // sphere was hit (it may be moving).
                    if let Some(pdf) = sphere::cone_pdf(p - *radius * n, *radius, from) {
                        return pdf;
                    }
                }
                let cos = n.dot(-dir).abs();
                if cos <= 0.0 {
                    0.0
                } else {
                    (p - from).length_squared() / (cos * area)
                }
            }
            Light::Environment { .. } | Light::Sky { .. } => self.direction_pdf(dir),
            Light::Point { .. } | Light::Spot { .. } | Light::Directional { .. } => 0.0,
        }
    }

    /// Whether the light is a delta distribution (cannot be hit by rays).
    pub fn is_delta(&self) -> bool {
        matches!(
            self,
            Light::Point { .. } | Light::Spot { .. } | Light::Directional { .. }
        )
    }
}

/// A small deterministic stream of numbers in [0, 1) for the light tests.
#[cfg(test)]
pub(crate) fn test_rng(seed: u64) -> impl FnMut() -> f32 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 40) as f32 / (1u64 << 24) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spot_falloff_is_smooth_and_bounded() {
        let (ct, cf) = (0.8f32, 0.9f32);
        assert_eq!(spot_falloff(1.0, ct, cf), 1.0);
        assert_eq!(spot_falloff(0.5, ct, cf), 0.0);
        let mid = spot_falloff(0.85, ct, cf);
        assert!((mid - 0.5).abs() < 1e-5);
    }

    #[test]
    fn a_sphere_lamp_gives_the_analytic_irradiance() {
        // A sphere of radiance 1 wholly above a point's horizon: E = π (r/D)²
        // cos θ (the sphere subtends a cone of sin² = (r/D)²), close to the
        // point and far from it.
        let material = crate::material::Material::new(&crate::material::Params {
            emission: Vec3::ONE,
            ..Default::default()
        });
        for (center, radius) in [
            (Vec3::new(0.0, 0.25, 0.0), 0.2f32),
            (Vec3::new(0.3, 2.0, 0.1), 0.5),
        ] {
            let light = Light::area(0, Shape::Sphere { center, radius }, Vec3::ZERO);
            let n = Vec3::Y;
            let k = 1024;
            let mut sum = 0.0f64;
            for i in 0..k {
                for j in 0..k {
                    let u = Vec2::new((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32);
                    let emitted = |_, _, _, nq: Vec3, w: Vec3| material.emitted(w, nq);
                    if let Some(ls) = light.sample(emitted, Vec3::ZERO, 0.0, u) {
                        sum += (luminance(ls.li) * ls.wi.dot(n).max(0.0) / ls.pdf) as f64;
                    }
                }
            }
            let e = sum / (k * k) as f64;
            let d = center.length() as f64;
            let expected =
                std::f64::consts::PI * (radius as f64 / d).powi(2) * (center.y as f64 / d);
            assert!((e / expected - 1.0).abs() < 1e-3, "{e} vs {expected}");
        }
    }
}
