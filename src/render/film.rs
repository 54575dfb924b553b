//! The film: per pixel, the sum of its samples (in f64) and how many it
//! has. Each pixel's samples are a run of consecutive sample indices
//! starting at the film's `first`, added one by one in index order, so a
//! render stopped and continued from its film ([`crate::render::render_from`])
//! sums exactly what an uninterrupted one sums, and films of disjoint runs
//! add up to the film of their union (up to f64 rounding, far below what an
//! f32 pixel shows). [`crate::output`] encodes the mean. An adaptive render's
//! film also holds its [`Halves`].

use crate::output;
use glam::{DVec3, Vec3};
use std::path::Path;

/// Accumulated radiance.
#[derive(Debug, Clone, PartialEq)]
pub struct Film {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The sample index every pixel's run starts at (0, or the first
    /// sample of a pass of a split render).
    pub first: u32,
    /// Sum of samples per pixel, row-major.
    pub sum: Vec<DVec3>,
    /// Samples per pixel, row-major: pixel `i` holds samples
    /// `first .. first + count[i]`.
    pub count: Vec<u32>,
    /// Adaptive sampling's half films and stopped pixels (`None`: every
    /// pixel samples to the end).
    pub halves: Option<Halves>,
    /// The light that light paths joined to the camera brought (`None`:
    /// the integrator traces none).
    pub light: Option<LightFilm>,
}

/// The light of an integrator's splats ([`crate::integrator::Splat`]),
/// per pixel: what the light paths of all pixels' samples brought to it.
/// A pixel shows its samples' mean plus its splats' sum divided by the
/// light paths traced per pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct LightFilm {
    /// Sum of the splats per pixel, row-major.
    pub sum: Vec<DVec3>,
    /// Light paths traced, all pixels together (one per camera sample).
    pub paths: u64,
}

/// What adaptive sampling keeps beside the sums, per pixel: the sum of its
/// odd-indexed samples (the even ones' is the rest of the sum) and whether
/// it has stopped ([`crate::render::adaptive`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Halves {
    /// Sum of the samples of odd index, row-major.
    pub odd: Vec<DVec3>,
    /// Whether the pixel has stopped, row-major.
    pub stopped: Vec<bool>,
}

impl Film {
    /// A black film whose pixels' samples will start at index `first`.
    pub fn new(width: u32, height: u32, first: u32) -> Film {
        let n = width as usize * height as usize;
        Film {
            width,
            height,
            first,
            sum: vec![DVec3::ZERO; n],
            count: vec![0; n],
            halves: None,
            light: None,
        }
    }

    /// The film with an empty light film, for an integrator that splats
    /// (its samples so far, if any, count as light paths traced).
    pub fn with_light(self) -> Film {
        let n = self.sum.len();
        let paths = self.total_samples();
        Film {
            light: Some(LightFilm {
                sum: vec![DVec3::ZERO; n],
                paths,
            }),
            ..self
        }
    }

    /// A black film of the render `settings` describe, with half films if
    /// it samples adaptively, whose samples start at index `first`.
    pub fn for_settings(settings: &crate::ir::settings::Settings, first: u32) -> Film {
        let film = Film::new(settings.width, settings.height, first);
        match settings.adaptive {
            Some(_) => film.with_halves(),
            None => film,
        }
    }

    /// The film with (empty) half films, for adaptive sampling.
    pub fn with_halves(self) -> Film {
        let n = self.sum.len();
        Film {
            halves: Some(Halves {
                odd: vec![DVec3::ZERO; n],
                stopped: vec![false; n],
            }),
            ..self
        }
    }

    /// Whether pixel `i` has stopped (only adaptive sampling stops one).
    #[inline]
    pub fn stopped(&self, i: usize) -> bool {
        self.halves.as_ref().is_some_and(|h| h.stopped[i])
    }

    /// The fewest samples of a pixel that has not stopped; `None` when all
    /// have.
    pub fn least_active(&self) -> Option<u32> {
        (0..self.count.len())
            .filter(|&i| !self.stopped(i))
            .map(|i| self.count[i])
            .min()
    }

    /// Pixels that have not stopped.
    pub fn active_pixels(&self) -> u64 {
        match &self.halves {
            Some(h) => h.stopped.iter().filter(|&&s| !s).count() as u64,
            None => self.count.len() as u64,
        }
    }

    /// The share of pixels adaptive sampling has stopped (`None` for a
    /// film without halves).
    pub fn stopped_share(&self) -> Option<f64> {
        let h = self.halves.as_ref()?;
        let stopped = h.stopped.iter().filter(|&&s| s).count();
        Some(stopped as f64 / h.stopped.len().max(1) as f64)
    }

    /// A film holding finished pixels (one sample each), e.g. to write an
    /// image made elsewhere.
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<Vec3>) -> Film {
        assert_eq!(pixels.len(), width as usize * height as usize);
        Film {
            width,
            height,
            first: 0,
            count: vec![1; pixels.len()],
            sum: pixels.iter().map(Vec3::as_dvec3).collect(),
            halves: None,
            light: None,
        }
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
        let own = self.sum[i] / self.count[i].max(1) as f64;
        match &self.light {
            Some(l) if l.paths > 0 => {
                let per_pixel = l.paths as f64 / self.sum.len() as f64;
                (own + l.sum[i] / per_pixel).as_vec3()
            }
            _ => own.as_vec3(),
        }
    }

    /// Samples in every pixel, the most in any pixel, and the mean.
    pub fn sample_counts(&self) -> (u32, u32, f64) {
        let min = self.count.iter().copied().min().unwrap_or(0);
        let max = self.count.iter().copied().max().unwrap_or(0);
        (
            min,
            max,
            self.total_samples() as f64 / self.count.len().max(1) as f64,
        )
    }

    /// Pixel samples the film holds, all pixels together.
    pub fn total_samples(&self) -> u64 {
        self.count.iter().map(|&n| n as u64).sum()
    }

    /// Adds another film's samples, pixel by pixel (the parts of a split
    /// render, never adaptive; the caller checks that their sample runs
    /// are disjoint).
    pub fn add(&mut self, other: &Film) {
        debug_assert_eq!((self.width, self.height), (other.width, other.height));
        for (s, o) in self.sum.iter_mut().zip(&other.sum) {
            *s += *o;
        }
        for (n, o) in self.count.iter_mut().zip(&other.count) {
            *n = n.saturating_add(*o);
        }
        if let Some(o) = &other.light {
            let l = self.light.get_or_insert_with(|| LightFilm {
                sum: vec![DVec3::ZERO; o.sum.len()],
                paths: 0,
            });
            for (s, o) in l.sum.iter_mut().zip(&o.sum) {
                *s += *o;
            }
            l.paths += o.paths;
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
    fn a_pixel_is_the_mean_of_its_samples() {
        let mut f = Film::new(2, 1, 0);
        f.sum[0] = DVec3::splat(4.0);
        f.count[0] = 2;
        f.sum[1] = DVec3::splat(9.0);
        f.count[1] = 3;
        assert_eq!(f.pixel(0), Vec3::splat(2.0));
        assert_eq!(f.pixel(1), Vec3::splat(3.0));
        assert_eq!(f.sample_counts(), (2, 3, 2.5));
        assert_eq!(Film::new(1, 1, 0).pixel(0), Vec3::ZERO, "no sample: black");
    }

    #[test]
    fn films_of_disjoint_runs_add_up() {
        let mut a = Film::from_pixels(1, 1, vec![Vec3::ONE]);
        let b = Film::from_pixels(1, 1, vec![Vec3::splat(3.0)]);
        a.add(&b);
        assert_eq!((a.pixel(0), a.count[0]), (Vec3::splat(2.0), 2));
    }

    #[test]
    fn a_film_with_splats_adds_them_and_shows_them_per_light_path() {
        let mut a = Film::new(2, 1, 0);
        let mut b = Film::from_pixels(2, 1, vec![Vec3::ONE, Vec3::ONE]).with_light();
        b.light.as_mut().unwrap().sum[1] = DVec3::splat(4.0);
        assert_eq!(
            b.light.as_ref().unwrap().paths,
            2,
            "its samples were light paths"
        );
        // One light path per pixel: pixel 1 shows 1 + 4.
        assert_eq!(b.pixel(1), Vec3::splat(5.0));
        a.add(&b);
        a.add(&b);
        // Two samples a pixel, two light paths a pixel: 1 + 8 / 2.
        assert_eq!((a.pixel(0), a.pixel(1)), (Vec3::ONE, Vec3::splat(5.0)));
    }
}
