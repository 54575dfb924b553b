//! A daylight sky and its sun: the Hošek–Wilkie sky model (Hošek and
//! Wilkie 2012, "An Analytic Model for Full Spectral Sky-Dome Radiance",
//! its RGB dataset, evaluated by the `hw-skymodel` crate) for a sun
//! elevation, a turbidity and a ground albedo, and the sun as a disk of
//! uniform radiance (0.5358° across) from Hošek and Wilkie's 2013 solar
//! model as Mitsuba 3.9.1 reduces it to RGB (`sun_table`).
//!
//! Radiance is in Mitsuba 3's units for `sunsky` (the RGB dataset's values
//! divided by [`MITSUBA_SCALE`]), so that a scene lit here and there by the
//! same sky matches, and so that a white floor under a high sun is about 1.
//! The world is y-up; below the horizon the sky is black (the ground is the
//! scene's to model).
//!
//! Sampling: the sun's cone uniformly, or the sky by a piecewise-constant
//! distribution of its luminance × sin θ over a grid of the upper
//! hemisphere; the density of a direction is the mixture of both, so a
//! direction from either is weighed right.

use super::luminance;
use super::sun_table::SUN_RADIANCE;
use crate::geometry::orthonormal_basis;
use crate::sampling::distribution::Distribution2D;
use glam::{Vec2, Vec3};
use hw_skymodel::rgb::{Channel, SkyParams, SkyState};
use std::f32::consts::{FRAC_PI_2, PI, TAU};

/// Mitsuba 3's `sunsky` shows the Hošek–Wilkie RGB dataset divided by this
/// (measured: the ratio is 106.750 at every direction and channel).
pub const MITSUBA_SCALE: f32 = 106.75;

/// The sun's angular diameter in degrees (Mitsuba's `sun_aperture`).
pub const SUN_APERTURE_DEGREES: f32 = 0.5358;

/// Sampling grid over the upper hemisphere: cells in azimuth and in θ.
const GRID_PHI: usize = 128;
const GRID_THETA: usize = 32;

/// What a sky is made of.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkyParameters {
    /// Unit direction towards the sun (y up, y ≥ 0).
    pub sun_direction: Vec3,
    /// Atmospheric turbidity, 1 (clear) to 10 (hazy).
    pub turbidity: f32,
    /// Ground albedo per channel, 0 to 1.
    pub albedo: Vec3,
    /// Scale of the sky's radiance per channel.
    pub sky_scale: Vec3,
    /// Scale of the sun's radiance per channel.
    pub sun_scale: Vec3,
    /// Angular diameter of the sun's disk, degrees.
    pub sun_aperture: f32,
}

/// A sky and its sun, ready to be evaluated and sampled.
#[derive(Debug, Clone)]
pub struct SunSky {
    dome: Dome,
    sun_radiance: Vec3,
    /// cos of the sun's angular radius.
    cos_sun: f32,
    /// Probability of sampling the sun's cone rather than the sky.
    sun_probability: f32,
    distribution: Distribution2D,
    /// Mean radiance over the sphere (sky and sun), per channel.
    mean: Vec3,
}

/// The sun's radiance at `elevation` degrees (0 to 90) under `turbidity`
/// (1 to 10), bilinear in the table.
pub fn sun_radiance(elevation: f32, turbidity: f32) -> Vec3 {
    let e = elevation.clamp(0.0, 90.0);
    let t = turbidity.clamp(1.0, 10.0) - 1.0;
    let (e0, t0) = ((e as usize).min(89), (t as usize).min(8));
    let (we, wt) = (e - e0 as f32, t - t0 as f32);
    let at = |ti: usize, ei: usize| Vec3::from_array(SUN_RADIANCE[ti * 91 + ei]);
    let row = |ti: usize| at(ti, e0) * (1.0 - we) + at(ti, e0 + 1) * we;
    row(t0) * (1.0 - wt) + row(t0 + 1) * wt
}

/// The sky without its sun: the model's state, its scale, where the sun
/// stands.
#[derive(Debug, Clone)]
struct Dome {
    state: SkyState,
    scale: Vec3,
    sun_direction: Vec3,
}

impl Dome {
    /// The sky's radiance towards `d`: black below the horizon.
    fn radiance(&self, d: Vec3) -> Vec3 {
        if d.y <= 0.0 {
            return Vec3::ZERO;
        }
        let theta = d.y.clamp(-1.0, 1.0).acos();
        let gamma = d.dot(self.sun_direction).clamp(-1.0, 1.0).acos();
        Vec3::new(
            self.state.radiance(theta, gamma, Channel::R),
            self.state.radiance(theta, gamma, Channel::G),
            self.state.radiance(theta, gamma, Channel::B),
        )
        .max(Vec3::ZERO)
            * self.scale
    }
}

impl SunSky {
    /// The sky of `p`; `None` when the model refuses its parameters (the
    /// checker keeps them in its ranges).
    pub fn new(p: &SkyParameters) -> Option<SunSky> {
        let sun_direction = p.sun_direction.normalize();
        let elevation = sun_direction.y.clamp(0.0, 1.0).asin();
        let dome = Dome {
            state: SkyState::new(&SkyParams {
                elevation: elevation.min(FRAC_PI_2),
                turbidity: p.turbidity,
                albedo: p.albedo.to_array(),
            })
            .ok()?,
            scale: p.sky_scale / MITSUBA_SCALE,
            sun_direction,
        };
        // The sky's luminance × sin θ at the cells' centres, and its
        // integral over the hemisphere.
        let mut func = Vec::with_capacity(GRID_PHI * GRID_THETA);
        let mut sky_integral = Vec3::ZERO;
        let cell = (TAU / GRID_PHI as f32) * (FRAC_PI_2 / GRID_THETA as f32);
        for j in 0..GRID_THETA {
            for i in 0..GRID_PHI {
                let d = grid_direction(Vec2::new(
                    (i as f32 + 0.5) / GRID_PHI as f32,
                    (j as f32 + 0.5) / GRID_THETA as f32,
                ));
                let l = dome.radiance(d);
                let sin_theta = (1.0 - d.y * d.y).max(0.0).sqrt();
                func.push((luminance(l) * sin_theta).max(0.0));
                sky_integral += l * sin_theta * cell;
            }
        }
        let sun_radiance = sun_radiance(elevation.to_degrees(), p.turbidity) * p.sun_scale;
        let cos_sun = (0.5 * p.sun_aperture).to_radians().cos();
        // The sun's light (radiance × solid angle), none below the horizon.
        let sun_light = if sun_direction.y > 0.0 {
            sun_radiance * TAU * (1.0 - cos_sun)
        } else {
            Vec3::ZERO
        };
        let (sun_power, sky_power) = (luminance(sun_light), luminance(sky_integral));
        // The sun's share of the samples, kept between 0.2 and 0.8 so that
        // neither part goes unsampled (the sun's reflection in glossy
        // surfaces, the sky's in rough ones).
        let sun_probability = if sun_power <= 0.0 {
            0.0
        } else if sky_power <= 0.0 {
            1.0
        } else {
            (sun_power / (sun_power + sky_power)).clamp(0.2, 0.8)
        };
        Some(SunSky {
            dome,
            sun_radiance,
            cos_sun,
            sun_probability,
            distribution: Distribution2D::new(&func, GRID_PHI, GRID_THETA),
            mean: (sky_integral + sun_light) / (4.0 * PI),
        })
    }

    /// The sky alone (no sun) towards `d`.
    pub fn sky(&self, d: Vec3) -> Vec3 {
        self.dome.radiance(d)
    }

    /// The sun alone towards `d`: its radiance within its disk while it is
    /// above the horizon, else black.
    pub fn sun(&self, d: Vec3) -> Vec3 {
        if d.dot(self.dome.sun_direction) >= self.cos_sun && d.y > 0.0 {
            self.sun_radiance
        } else {
            Vec3::ZERO
        }
    }

    /// Radiance arriving from direction `d` (sky and sun).
    pub fn eval(&self, d: Vec3) -> Vec3 {
        self.sky(d) + self.sun(d)
    }

    /// Mean radiance over the sphere, per channel (for the light's power).
    pub fn mean(&self) -> Vec3 {
        self.mean
    }

    /// Samples a direction: (direction, radiance, density in solid angle).
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, Vec3, f32)> {
        let d = if u.x < self.sun_probability {
            let u = Vec2::new(u.x / self.sun_probability, u.y);
            let cos = 1.0 - u.x * (1.0 - self.cos_sun);
            let sin = (1.0 - cos * cos).max(0.0).sqrt();
            let phi = TAU * u.y;
            let (t, b) = orthonormal_basis(self.dome.sun_direction);
            (sin * phi.cos()) * t + (sin * phi.sin()) * b + cos * self.dome.sun_direction
        } else {
            let u = Vec2::new(
                ((u.x - self.sun_probability) / (1.0 - self.sun_probability)).min(1.0 - 1e-7),
                u.y,
            );
            let (p, _) = self.distribution.sample(u);
            grid_direction(p)
        };
        let pdf = self.pdf(d);
        (pdf > 0.0).then(|| (d, self.eval(d), pdf))
    }

    /// The density in solid angle with which [`SunSky::sample`] picks `d`.
    pub fn pdf(&self, d: Vec3) -> f32 {
        let sun = if d.dot(self.dome.sun_direction) >= self.cos_sun {
            1.0 / (TAU * (1.0 - self.cos_sun))
        } else {
            0.0
        };
        let sin_theta = (1.0 - d.y * d.y).max(0.0).sqrt();
        let sky = if d.y > 0.0 && sin_theta > 0.0 {
            let phi = d.z.atan2(d.x).rem_euclid(TAU);
            let theta = d.y.clamp(-1.0, 1.0).acos();
            let p = Vec2::new(phi / TAU, theta / FRAC_PI_2);
            self.distribution.pdf(p) / (TAU * FRAC_PI_2 * sin_theta)
        } else {
            0.0
        };
        self.sun_probability * sun + (1.0 - self.sun_probability) * sky
    }
}

/// The direction of a point of the grid's [0, 1)²: u turns the azimuth
/// from +x towards +z, v the zenith angle from the zenith to the horizon.
fn grid_direction(p: Vec2) -> Vec3 {
    let (phi, theta) = (TAU * p.x, FRAC_PI_2 * p.y);
    let s = theta.sin();
    Vec3::new(s * phi.cos(), theta.cos(), s * phi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::chi2::sphere_p_value;
    use crate::sampling::sampler::Sampler;

    fn sky(elevation_deg: f32, aperture: f32) -> SunSky {
        let e = elevation_deg.to_radians();
        SunSky::new(&SkyParameters {
            // The sun towards −z; Mitsuba's scene below had it at −y, z up.
            sun_direction: Vec3::new(0.0, e.sin(), -e.cos()),
            turbidity: 3.0,
            albedo: Vec3::splat(0.3),
            sky_scale: Vec3::ONE,
            sun_scale: Vec3::ONE,
            sun_aperture: aperture,
        })
        .unwrap()
    }

    #[test]
    fn sky_radiance_matches_mitsuba() {
        // Mitsuba 3.9.1 `sunsky` (scalar_rgb), sun at 30°, turbidity 3,
        // albedo 0.3, sun_scale 0; its (x, y, z) with z up is ptsc's
        // (x, z, y) with the sun at −z.
        let s = sky(30.0, SUN_APERTURE_DEGREES);
        for (d, expect) in [
            ((0.0, 0.0, 1.0), [0.0164659, 0.0313386, 0.0625406]),
            ((0.0, -0.866, 0.5), [0.238539, 0.256706, 0.255219]),
            ((0.7, 0.648, 0.3), [0.0551073, 0.0937736, 0.147005]),
            ((0.0, 0.995, 0.1), [0.131273, 0.192357, 0.234757]),
            ((0.3, -0.9, 0.3), [0.185514, 0.225008, 0.257241]),
        ] {
            let ours = s.sky(Vec3::new(d.0, d.2, d.1).normalize());
            let expect = Vec3::from_array(expect);
            let err = ((ours - expect) / expect).abs().max_element();
            assert!(err < 0.01, "{d:?}: {ours} vs {expect}");
        }
        assert_eq!(s.sky(-Vec3::Y), Vec3::ZERO);
    }

    #[test]
    fn sun_radiance_matches_mitsuba() {
        // Mitsuba 3.9.1 `sunsky` with sky_scale 0, at the sun's centre;
        // 3.5° and turbidity 2.5 fall between the table's rows.
        for (elevation, turbidity, expect) in [
            (30.0f32, 3.0f32, [20274.44, 15949.582, 10618.099]),
            (25.0, 3.0, [19618.904, 15020.011, 9396.18]),
            (12.0, 3.0, [15767.141, 10166.622, 4222.6387]),
            (3.5, 3.0, [6590.162, 2603.2417, 252.84512]),
            (30.0, 2.5, [20592.383, 16224.64, 10793.093]),
            (30.0, 10.0, [9218.179, 6688.703, 4656.209]),
        ] {
            let ours = sun_radiance(elevation, turbidity);
            let expect = Vec3::from_array(expect);
            let err = ((ours - expect) / expect).abs().max_element();
            assert!(err < 0.01, "{elevation}° T {turbidity}: {ours} vs {expect}");
        }
        // The disk: uniform inside its 0.2679° radius, nothing outside.
        let s = sky(30.0, SUN_APERTURE_DEGREES);
        let at = |off: f32| {
            let e = (30.0 + off).to_radians();
            s.sun(Vec3::new(0.0, e.sin(), -e.cos()))
        };
        assert_eq!(at(0.0), at(0.26));
        assert_eq!(at(0.28), Vec3::ZERO);
    }

    #[test]
    fn sampling_follows_the_pdf() {
        // A sun 20° across (so that the bins resolve it) over the sky; a
        // fine grid integrates the pdf over the bins the disk's edge cuts.
        let s = sky(35.0, 20.0);
        let n = 300_000;
        let mut directions = Vec::with_capacity(n);
        let mut sampler = Sampler::new(4, 2, 0, 0);
        for _ in 0..n {
            let Some((d, radiance, pdf)) = s.sample(sampler.next_2d()) else {
                continue;
            };
            directions.push(d);
            assert!((pdf - s.pdf(d)).abs() <= 1e-3 * pdf);
            assert!((radiance - s.eval(d)).abs().max_element() <= 1e-3 * radiance.max_element());
        }
        let p = sphere_p_value(directions, n, |d| s.pdf(d), 64);
        assert!(p > 1e-3, "χ² p-value {p}");
    }

    #[test]
    fn a_sun_below_the_horizon_leaves_the_sky_alone() {
        let s = SunSky::new(&SkyParameters {
            sun_direction: Vec3::new(0.0, -0.1, -1.0),
            turbidity: 2.0,
            albedo: Vec3::ZERO,
            sky_scale: Vec3::ONE,
            sun_scale: Vec3::ONE,
            sun_aperture: SUN_APERTURE_DEGREES,
        })
        .unwrap();
        assert_eq!(s.sun_probability, 0.0);
        let d = Vec3::new(0.0, -0.1, -1.0).normalize();
        assert_eq!(s.sun(d), Vec3::ZERO);
        assert!(s.mean().is_finite());
    }
}
