//! An environment map: radiance arriving from every direction, read from an
//! equirectangular (latitude-longitude) image, as Mitsuba 3's `envmap`
//! reads it. A direction d in the map's frame (y up) has
//! u = atan2(d.x, −d.z) / 2π (0 straight ahead along −z, growing towards
//! +x) and v = acos(d.y) / π from the image's top row (the zenith) to its
//! bottom row (the nadir); texels are samples at u = i / width and
//! v = j / (height − 1), interpolated bilinearly, the last column wrapping
//! to the first. Directions are importance-sampled in proportion to
//! luminance × sin θ over the cells between texels (pbrt-v4 §12.5.2; a
//! piecewise-constant version of Mitsuba's bilinear warp).

use crate::sampling::distribution::Distribution2D;
use crate::texture::image::Image;
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::{PI, TAU};
use std::sync::Arc;

/// An environment map ready to evaluate and sample.
#[derive(Debug, Clone)]
pub struct EnvironmentMap {
    /// Linear RGB texels, rows from the zenith down (at least 2 × 2).
    image: Arc<Image>,
    /// The map's frame → the world (a rotation).
    to_world: Mat3,
    /// The cells' sampling distribution over (u, v).
    distribution: Distribution2D,
    /// The mean radiance over the sphere (for the light's power).
    mean: Vec3,
}

/// (u, v) of a unit direction in the map's frame.
pub fn direction_to_uv(d: Vec3) -> Vec2 {
    let u = d.x.atan2(-d.z) * (0.5 / PI);
    let u = if u < 0.0 { u + 1.0 } else { u };
    let v = d.y.clamp(-1.0, 1.0).acos() / PI;
    Vec2::new(u.min(1.0), v)
}

/// sin θ of a unit direction in the map's frame, from its horizontal
/// components (√(1 − y²) loses most of its digits next to the poles, where
/// the density divides by it), computed alike for sampling and for the
/// density so that the two agree.
fn sin_theta(d: Vec3) -> f32 {
    (d.x * d.x + d.z * d.z).sqrt()
}

/// The unit direction in the map's frame at (u, v).
pub fn uv_to_direction(uv: Vec2) -> Vec3 {
    let (sin_phi, cos_phi) = (uv.x * TAU).sin_cos();
    let (sin_theta, cos_theta) = (uv.y * PI).sin_cos();
    Vec3::new(sin_phi * sin_theta, cos_theta, -cos_phi * sin_theta)
}

impl EnvironmentMap {
    /// The map of `image` (at least 2 × 2 texels) turned by `to_world` (a
    /// rotation).
    pub fn new(image: Arc<Image>, to_world: Mat3) -> EnvironmentMap {
        let (w, h) = (image.width, image.height);
        assert!(w >= 1 && h >= 2, "an environment map has two rows at least");
        let lum = |t: Vec3| 0.2126 * t.x + 0.7152 * t.y + 0.0722 * t.z;
        let texel = |i: usize, j: usize| image.texels[j * w + i % w];
        // One cell between each two columns (the last wrapping) and rows.
        let mut cells = Vec::with_capacity(w * (h - 1));
        let mut mean = Vec3::ZERO;
        let mut weight = 0.0f64;
        for j in 0..h - 1 {
            let sin_theta = ((j as f32 + 0.5) / (h - 1) as f32 * PI).sin();
            for i in 0..w {
                let c =
                    (texel(i, j) + texel(i + 1, j) + texel(i, j + 1) + texel(i + 1, j + 1)) * 0.25;
                cells.push(lum(c) * sin_theta);
                mean += c * sin_theta;
                weight += sin_theta as f64;
            }
        }
        EnvironmentMap {
            distribution: Distribution2D::new(&cells, w, h - 1),
            mean: mean / weight.max(1e-30) as f32,
            image,
            to_world,
        }
    }

    /// The radiance arriving from the world direction `d` (unit), before
    /// the light's intensity.
    pub fn eval(&self, d: Vec3) -> Vec3 {
        self.lookup(direction_to_uv(self.to_world.transpose() * d))
    }

    /// The bilinear interpolation of the texels at (u, v).
    fn lookup(&self, uv: Vec2) -> Vec3 {
        let (w, h) = (self.image.width, self.image.height);
        let x = (uv.x * w as f32).clamp(0.0, w as f32);
        let y = (uv.y * (h - 1) as f32).clamp(0.0, (h - 1) as f32);
        let (i, j) = ((x as usize).min(w - 1), (y as usize).min(h - 2));
        let (fx, fy) = (x - i as f32, y - j as f32);
        let t = |i: usize, j: usize| self.image.texels[j * w + i % w];
        let top = t(i, j).lerp(t(i + 1, j), fx);
        let bottom = t(i, j + 1).lerp(t(i + 1, j + 1), fx);
        top.lerp(bottom, fy)
    }

    /// A world direction for `u`, its radiance (before the intensity) and
    /// its density in solid angle; `None` at a pole.
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, Vec3, f32)> {
        let (uv, pdf_uv) = self.distribution.sample(u);
        let local = uv_to_direction(uv);
        let sin_theta = sin_theta(local);
        if pdf_uv <= 0.0 || sin_theta <= 0.0 {
            return None;
        }
        let d = self.to_world * local;
        Some((d, self.lookup(uv), pdf_uv / (2.0 * PI * PI * sin_theta)))
    }

    /// The density in solid angle with which [`EnvironmentMap::sample`]
    /// picks the world direction `d`.
    pub fn pdf(&self, d: Vec3) -> f32 {
        let local = self.to_world.transpose() * d;
        let sin_theta = sin_theta(local);
        if sin_theta <= 0.0 {
            return 0.0;
        }
        self.distribution.pdf(direction_to_uv(local)) / (2.0 * PI * PI * sin_theta)
    }

    /// The mean radiance over the sphere of directions.
    pub fn mean(&self) -> Vec3 {
        self.mean
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::chi2::pearson_p_value;
    use crate::sampling::sampler::Sampler;

    fn image(w: usize, h: usize, f: impl Fn(usize, usize) -> Vec3) -> Arc<Image> {
        Arc::new(Image {
            width: w,
            height: h,
            texels: (0..w * h).map(|k| f(k % w, k / w)).collect(),
        })
    }

    #[test]
    fn directions_and_coordinates_invert_each_other() {
        // Ahead (−z) is u = 0, +x a quarter turn on, the zenith v = 0.
        assert!((direction_to_uv(-Vec3::Z) - Vec2::new(0.0, 0.5)).length() < 1e-6);
        assert!((direction_to_uv(Vec3::X) - Vec2::new(0.25, 0.5)).length() < 1e-6);
        assert!((direction_to_uv(Vec3::Z) - Vec2::new(0.5, 0.5)).length() < 1e-6);
        assert!(direction_to_uv(Vec3::Y).y.abs() < 1e-6);
        for k in 0..200 {
            let uv = Vec2::new(
                (k as f32 * 0.618).fract(),
                0.02 + 0.96 * (k as f32 * 0.377).fract(),
            );
            let back = direction_to_uv(uv_to_direction(uv));
            assert!((back - uv).length() < 1e-4, "{uv} → {back}");
        }
    }

    #[test]
    fn texels_are_samples_at_the_grid_points() {
        // 4 × 3: the top row is the zenith, the bottom the nadir.
        let im = image(4, 3, |i, j| Vec3::new(i as f32, j as f32, 1.0));
        let map = EnvironmentMap::new(im, Mat3::IDENTITY);
        assert_eq!(map.eval(Vec3::Y).y, 0.0);
        assert_eq!(map.eval(-Vec3::Y).y, 2.0);
        // On the horizon straight ahead: column 0, row 1.
        assert_eq!(map.eval(-Vec3::Z), Vec3::new(0.0, 1.0, 1.0));
        // Half way between columns 3 and (wrapping) 0.
        let d = uv_to_direction(Vec2::new(0.875, 0.5));
        assert!((map.eval(d) - Vec3::new(1.5, 1.0, 1.0)).length() < 1e-4);
        // A turned map: what was ahead is now to the right (+x).
        let turned = EnvironmentMap::new(
            image(4, 3, |i, j| Vec3::new(i as f32, j as f32, 1.0)),
            Mat3::from_rotation_y(-std::f32::consts::FRAC_PI_2),
        );
        assert!((turned.eval(Vec3::X) - map.eval(-Vec3::Z)).length() < 1e-4);
    }

    #[test]
    fn sampling_follows_the_pdf_and_favours_the_bright_spot() {
        // A dim sky with a bright spot, turned: χ² over directions.
        let im = image(16, 9, |i, j| {
            if (i, j) == (5, 3) {
                Vec3::splat(200.0)
            } else {
                Vec3::new(0.2, 0.3, 0.5 + 0.05 * j as f32)
            }
        });
        let map = EnvironmentMap::new(im, Mat3::from_rotation_x(0.3));
        let (n_cos, n_phi) = (16usize, 32usize);
        let bin = |d: Vec3| {
            let c = (((d.z + 1.0) * 0.5 * n_cos as f32) as usize).min(n_cos - 1);
            let phi = d.y.atan2(d.x).rem_euclid(TAU);
            c * n_phi + ((phi / TAU * n_phi as f32) as usize).min(n_phi - 1)
        };
        let n = 300_000;
        let mut observed = vec![0.0; n_cos * n_phi];
        let mut s = Sampler::new(9, 2, 0, 0);
        let mut bright = 0;
        for _ in 0..n {
            let Some((d, radiance, pdf)) = map.sample(s.next_2d()) else {
                continue;
            };
            observed[bin(d)] += 1.0;
            assert!(
                (pdf - map.pdf(d)).abs() <= 2e-3 * pdf,
                "{pdf} vs {} at {d} (uv {})",
                map.pdf(d),
                direction_to_uv(map.to_world.transpose() * d)
            );
            assert!((radiance - map.eval(d)).length() <= 1e-3 * radiance.length().max(1.0));
            bright += (radiance.x > 10.0) as usize;
        }
        // The spot's cells hold most of the luminance: most samples go there.
        assert!(bright > n / 2, "{bright} of {n} samples in the bright spot");
        let sub = 16;
        let expected: Vec<f64> = (0..n_cos * n_phi)
            .map(|b| {
                let (c, p) = (b / n_phi, b % n_phi);
                let mut sum = 0.0;
                for a in 0..sub {
                    for q in 0..sub {
                        let cos =
                            -1.0 + 2.0 * (c as f64 + (a as f64 + 0.5) / sub as f64) / n_cos as f64;
                        let phi =
                            TAU as f64 * (p as f64 + (q as f64 + 0.5) / sub as f64) / n_phi as f64;
                        let sin = (1.0 - cos * cos).sqrt();
                        let d = Vec3::new(
                            (sin * phi.cos()) as f32,
                            (sin * phi.sin()) as f32,
                            cos as f32,
                        );
                        sum += map.pdf(d) as f64;
                    }
                }
                sum / (sub * sub) as f64
                    * (2.0 / n_cos as f64)
                    * (TAU as f64 / n_phi as f64)
                    * n as f64
            })
            .collect();
        let p = pearson_p_value(&observed, &expected);
        assert!(p > 1e-3, "χ² p-value {p}");
    }

    #[test]
    fn a_constant_map_is_its_colour_everywhere() {
        let map = EnvironmentMap::new(image(8, 4, |_, _| Vec3::new(0.5, 1.0, 2.0)), Mat3::IDENTITY);
        for d in [Vec3::X, -Vec3::Y, Vec3::new(0.3, 0.4, -0.5).normalize()] {
            assert!((map.eval(d) - Vec3::new(0.5, 1.0, 2.0)).length() < 1e-6);
        }
        assert!((map.mean() - Vec3::new(0.5, 1.0, 2.0)).length() < 1e-5);
    }
}
