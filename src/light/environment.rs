//! An environment map: radiance arriving from every direction, read from an
//! equirectangular (latitude-longitude) image, as Mitsuba 3's `envmap`
//! reads it. A direction d in the map's frame (y up) has
//! u = atan2(d.x, −d.z) / 2π (0 straight ahead along −z, growing towards
//! +x) and v = acos(d.y) / π from the image's top row (the zenith) to its
//! bottom row (the nadir); texels are samples at u = (i + ½) / width (as a
//! pixel's centre) and v = j / (height − 1) (the first and last rows at the
//! poles), interpolated bilinearly, the last column wrapping to the first
//! (measured against Mitsuba's `eval`: the same radiance in every
//! direction). Directions are importance-sampled in proportion to
//! luminance × sin θ over the cells between texels (pbrt-v4 §12.5.2; a
//! piecewise-constant version of Mitsuba's bilinear warp).

use crate::sampling::distribution::Distribution2D;
use crate::sampling::warp;
use crate::texture::image::Image;
use glam::{Mat3, Vec2, Vec3};
use std::f32::consts::{PI, TAU};

/// An environment map ready to evaluate and sample.
#[derive(Debug, Clone)]
pub struct EnvironmentMap {
    /// Linear RGB texels, rows from the zenith down (at least 2 × 2).
    image: Image,
    /// The map's frame → the world (a rotation).
    to_world: Mat3,
    /// The cells' sampling distribution over (u, v).
    distribution: Distribution2D,
    /// The mean radiance over the sphere (for the light's power).
    mean: Vec3,
    /// Whether directions are sampled uniformly over the sphere instead
    /// (to measure what importance sampling gains).
    uniform: bool,
}

fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
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
    pub fn new(image: Image, to_world: Mat3) -> EnvironmentMap {
        let (w, h) = (image.width, image.height);
        assert!(w >= 1 && h >= 2, "an environment map has two rows at least");
        let texel = |i: usize, j: usize| image.texel(j * w + i % w);
        // The mean radiance, each row weighted by the solid angle it stands
        // for; in f64, so that texels near f32's largest value do not add
        // up to infinity.
        let mut mean = glam::DVec3::ZERO;
        let mut weight = 0.0f64;
        for j in 0..h - 1 {
            let sin_theta = ((j as f64 + 0.5) / (h - 1) as f64 * std::f64::consts::PI).sin();
            for i in 0..w {
                let c = [
                    texel(i, j),
                    texel(i + 1, j),
                    texel(i, j + 1),
                    texel(i + 1, j + 1),
                ]
                .iter()
                .fold(glam::DVec3::ZERO, |a, t| a + t.as_dvec3())
                    * 0.25;
                mean += c * sin_theta;
                weight += sin_theta;
            }
        }
        let mean = (mean / weight.max(1e-30))
            .min(glam::DVec3::splat(1e30))
            .as_vec3();
        let mut map = EnvironmentMap {
            distribution: Distribution2D::new(&[1.0], 1, 1),
            mean,
            image,
            to_world,
            uniform: false,
        };
        map.build_distribution();
        map
    }

    /// The bytes a map of `width` × `height` texels takes besides its
    /// image: its sampling distribution over the cells between texels,
    /// about 8 bytes a texel.
    pub fn sampling_bytes(width: usize, height: usize) -> u64 {
        Distribution2D::bytes_for(width, height.saturating_sub(1))
    }

    /// The bytes its sampling distribution holds (its image's are
    /// [`Image::bytes`], perhaps shared with textures).
    pub fn distribution_bytes(&self) -> u64 {
        self.distribution.bytes()
    }

    /// The image the map reads.
    pub fn image(&self) -> &Image {
        &self.image
    }

    /// The same map, its directions sampled uniformly over the sphere (the
    /// cells by their solid angle alone): the baseline importance sampling
    /// is measured against.
    pub fn with_uniform_sampling(mut self) -> EnvironmentMap {
        self.uniform = true;
        self.build_distribution();
        self
    }

    fn build_distribution(&mut self) {
        let (w, h) = (self.image.width, self.image.height);
        // One cell between each two columns (the last wrapping) and rows,
        // chosen by the integral of its corners' bilinear weights (their
        // mean), then sampled bilinearly within (as Mitsuba's warp does
        // over the whole map).
        let cells: Vec<f32> = (0..(h - 1) * w)
            .map(|k| self.corner_weights((k % w, k / w)).iter().sum::<f32>() * 0.25)
            .collect();
        self.distribution = Distribution2D::new(&cells, w, h - 1);
    }

    /// The radiance arriving from the world direction `d` (unit), before
    /// the light's intensity.
    pub fn eval(&self, d: Vec3) -> Vec3 {
        self.lookup(direction_to_uv(self.to_world.transpose() * d))
    }

    /// The bilinear interpolation of the texels at (u, v).
    fn lookup(&self, uv: Vec2) -> Vec3 {
        let (w, h) = (self.image.width, self.image.height);
        let x = (uv.x * w as f32 - 0.5).rem_euclid(w as f32);
        let y = (uv.y * (h - 1) as f32).clamp(0.0, (h - 1) as f32);
        let (i, j) = ((x as usize).min(w - 1), (y as usize).min(h - 2));
        let (fx, fy) = (x - i as f32, y - j as f32);
        let [a, b, c, d] = self.corners((i, j));
        a.lerp(b, fx).lerp(c.lerp(d, fx), fy)
    }

    /// The texels at the corners of cell (i, j), the column after the last
    /// wrapping to the first, in the order [`warp::bilinear`] takes them.
    #[inline(always)]
    fn corners(&self, (i, j): (usize, usize)) -> [Vec3; 4] {
        let w = self.image.width;
        let (i0, i1) = (i % w, (i + 1) % w);
        let (r0, r1) = (j * w, (j + 1) * w);
        self.image.texels4([r0 + i0, r0 + i1, r1 + i0, r1 + i1])
    }

    /// A world direction for `u`, its radiance (before the intensity) and
    /// its density in solid angle; `None` at a pole.
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, Vec3, f32)> {
        let (cell_uv, pdf_cell) = self.distribution.sample(u);
        // Within its cell the point is uniform: a fresh sample for the
        // bilinear distribution of the cell's corners.
        let (cell, within) = self.cell_of(cell_uv);
        let weights = self.corner_weights(cell);
        let b = warp::bilinear(within, weights);
        let pdf_uv = pdf_cell * warp::bilinear_pdf(b, weights);
        let (w, h) = (self.image.width as f32, (self.image.height - 1) as f32);
        let cell_uv = Vec2::new((cell.0 as f32 + b.x) / w, (cell.1 as f32 + b.y) / h);
        let uv = Vec2::new(self.u_of_cells(cell_uv.x), cell_uv.y.min(1.0));
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
        let uv = direction_to_uv(local);
        let cell_uv = Vec2::new(self.cells_of_u(uv.x), uv.y);
        let (cell, within) = self.cell_of(cell_uv);
        let pdf_uv =
            self.distribution.pdf(cell_uv) * warp::bilinear_pdf(within, self.corner_weights(cell));
        pdf_uv / (2.0 * PI * PI * sin_theta)
    }

    /// The cell (column, row) holding a point of the cells' (u, v), and the
    /// point's place within it, in [0, 1)².
    fn cell_of(&self, cell_uv: Vec2) -> ((usize, usize), Vec2) {
        let (w, h) = (self.image.width, self.image.height - 1);
        let (x, y) = (cell_uv.x * w as f32, cell_uv.y * h as f32);
        let (i, j) = ((x as usize).min(w - 1), (y as usize).min(h - 1));
        let within = Vec2::new(x - i as f32, y - j as f32).clamp(Vec2::ZERO, Vec2::ONE);
        ((i, j), within)
    }

    /// The sampling weights (luminance × sin θ) at a cell's four corners,
    /// in the order [`warp::bilinear`] takes them.
    fn corner_weights(&self, (i, j): (usize, usize)) -> [f32; 4] {
        let h = self.image.height;
        let sin_theta = |j: usize| (j as f32 / (h - 1) as f32 * PI).sin().max(0.0);
        let (s0, s1) = (sin_theta(j), sin_theta(j + 1));
        let importance = match self.uniform {
            true => [1.0; 4],
            false => self.corners((i, j)).map(luminance),
        };
        // Capped: texels near f32's largest value must not overflow the
        // sums and squares of the bilinear warp (the density would turn to
        // NaN); 10^15 against the rest is importance enough.
        let [a, b, c, d] = importance;
        [a * s0, b * s0, c * s1, d * s1].map(|x| x.min(1e15))
    }

    /// u of a direction → u of the distribution's cells, whose cell i lies
    /// between the texel columns i and i + 1, half a texel further on.
    fn cells_of_u(&self, u: f32) -> f32 {
        let shifted = u - 0.5 / self.image.width as f32;
        if shifted < 0.0 {
            (shifted + 1.0).min(1.0 - f32::EPSILON / 2.0)
        } else {
            shifted
        }
    }

    /// The inverse of [`EnvironmentMap::cells_of_u`].
    fn u_of_cells(&self, u: f32) -> f32 {
        let shifted = u + 0.5 / self.image.width as f32;
        if shifted >= 1.0 {
            shifted - 1.0
        } else {
            shifted
        }
    }

    /// The mean radiance over the sphere of directions.
    pub fn mean(&self) -> Vec3 {
        self.mean
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::chi2::sphere_p_value;
    use crate::sampling::sampler::Sampler;

    fn image(w: usize, h: usize, f: impl Fn(usize, usize) -> Vec3) -> Image {
        let texels: Vec<Vec3> = (0..w * h).map(|k| f(k % w, k / w)).collect();
        Image::from_rgb(w, h, &texels)
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
        // On the horizon at column 1's centre, row 1.
        let d = uv_to_direction(Vec2::new(1.5 / 4.0, 0.5));
        assert!((map.eval(d) - Vec3::new(1.0, 1.0, 1.0)).length() < 1e-5);
        // Straight ahead (u = 0): half way between columns 3 and (wrapping) 0.
        assert!((map.eval(-Vec3::Z) - Vec3::new(1.5, 1.0, 1.0)).length() < 1e-4);
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
        let n = 300_000;
        let mut directions = Vec::with_capacity(n);
        let mut s = Sampler::new(9, 2, 0, 0);
        let mut bright = 0;
        for _ in 0..n {
            let Some((d, radiance, pdf)) = map.sample(s.next_2d()) else {
                continue;
            };
            directions.push(d);
            assert!(
                (pdf - map.pdf(d)).abs() <= 1e-2 * pdf,
                "{pdf} vs {} at {d} (uv {})",
                map.pdf(d),
                direction_to_uv(map.to_world.transpose() * d)
            );
            assert!((radiance - map.eval(d)).length() <= 1e-3 * radiance.length().max(1.0));
            bright += (radiance.x > 10.0) as usize;
        }
        // The spot's cells hold most of the luminance: most samples go there.
        assert!(bright > n / 2, "{bright} of {n} samples in the bright spot");
        let p = sphere_p_value(directions, n, |d| map.pdf(d), 16);
        assert!(p > 1e-3, "χ² p-value {p}");
    }

    #[test]
    fn uniform_sampling_is_uniform_over_the_sphere() {
        let im = image(16, 9, |i, _| Vec3::splat(if i == 3 { 100.0 } else { 0.1 }));
        let map = EnvironmentMap::new(im, Mat3::IDENTITY).with_uniform_sampling();
        let mut s = Sampler::new(1, 1, 0, 0);
        for _ in 0..1000 {
            let (d, _, pdf) = map.sample(s.next_2d()).unwrap();
            // Bilinear in sin θ within each cell: about 1 / 4π, exactly
            // what `pdf` says.
            assert!((pdf * 4.0 * PI - 1.0).abs() < 0.1, "{pdf}");
            assert!((pdf - map.pdf(d)).abs() < 1e-2 * pdf);
        }
    }

    #[test]
    fn texels_at_the_edge_of_f32_keep_everything_finite() {
        let im = image(8, 4, |i, j| {
            Vec3::splat(if (i, j) == (2, 1) { 3.4e38 } else { 1.0 })
        });
        let map = EnvironmentMap::new(im, Mat3::IDENTITY);
        assert!(map.mean().is_finite());
        let mut s = Sampler::new(2, 2, 0, 0);
        for _ in 0..1000 {
            let (d, li, pdf) = map.sample(s.next_2d()).unwrap();
            assert!(li.is_finite() && pdf.is_finite() && pdf > 0.0, "{li} {pdf}");
            assert!(map.pdf(d).is_finite());
        }
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
