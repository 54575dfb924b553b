//! The film: linear float accumulation per pixel, with the sample counts of
//! a pass that did not finish. [`crate::output`] encodes it.

use crate::output;
use glam::Vec3;
use std::path::Path;

/// Accumulated radiance.
#[derive(Debug, Clone)]
pub struct Film {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Sum of samples per pixel, row-major.
    pub sum: Vec<Vec3>,
    /// Samples per pixel in every pixel (the passes that finished).
    pub samples: u32,
    /// Samples of a cancelled pass, per pixel, beyond `samples` (absent
    /// while every pixel has `samples`).
    pub extra: Option<Vec<u32>>,
}

impl Film {
    /// A black film.
    pub fn new(width: u32, height: u32) -> Film {
        Film {
            width,
            height,
            sum: vec![Vec3::ZERO; (width * height) as usize],
            samples: 0,
            extra: None,
        }
    }

    /// A film holding finished pixels (one sample each), e.g. to write an image read elsewhere.
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<Vec3>) -> Film {
        assert_eq!(pixels.len(), (width * height) as usize);
        Film {
            width,
            height,
            sum: pixels,
            samples: 1,
            extra: None,
        }
    }

    /// Adds to a pixel's sum.
    pub fn add(&mut self, x: u32, y: u32, v: Vec3) {
        self.sum[(y * self.width + x) as usize] += v;
    }

    /// The mean radiance of each pixel.
    pub fn pixels(&self) -> Vec<Vec3> {
        (0..self.sum.len()).map(|i| self.pixel(i)).collect()
    }

    /// The mean radiance of pixel `i` (row-major); black without a sample.
    /// The encoders read pixels one by one: a copy of a 8192 × 8192 film is
    /// 805 MB.
    #[inline]
    pub fn pixel(&self, i: usize) -> Vec3 {
        let n = self.samples + self.extra.as_ref().map_or(0, |e| e[i]);
        self.sum[i] * (1.0 / n.max(1) as f32)
    }

    /// Adds `samples` samples of a pass that did not finish to a pixel.
    pub fn add_partial(&mut self, x: u32, y: u32, v: Vec3, samples: u32) {
        let i = (y * self.width + x) as usize;
        self.sum[i] += v;
        let n = self.sum.len();
        self.extra.get_or_insert_with(|| vec![0; n])[i] += samples;
    }

    /// Samples in every pixel, the most in any pixel, and the mean.
    pub fn sample_counts(&self) -> (u32, u32, f64) {
        match &self.extra {
            None => (self.samples, self.samples, self.samples as f64),
            Some(e) => {
                let min = e.iter().copied().min().unwrap_or(0);
                let max = e.iter().copied().max().unwrap_or(0);
                let mean = e.iter().map(|&n| n as f64).sum::<f64>() / e.len().max(1) as f64;
                (
                    self.samples + min,
                    self.samples + max,
                    self.samples as f64 + mean,
                )
            }
        }
    }

    /// Writes the image atomically; the format follows the extension
    /// (.png, .exr, .pfm), see [`output::write_image`].
    pub fn write(&self, path: &Path, exposure: f32) -> std::io::Result<()> {
        output::write_image(path, (self.width, self.height), |i| self.pixel(i), exposure)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pixel_is_the_mean_of_its_samples_cancelled_pass_included() {
        let mut f = Film::new(2, 1);
        f.samples = 2;
        f.add(0, 0, Vec3::splat(4.0));
        f.add_partial(1, 0, Vec3::splat(9.0), 1);
        assert_eq!(f.pixel(0), Vec3::splat(2.0));
        assert_eq!(f.pixel(1), Vec3::splat(3.0));
        assert_eq!(f.sample_counts(), (2, 3, 2.5));
    }
}
