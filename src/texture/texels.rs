//! An image's texels as its file holds them: grey or RGB (an alpha channel
//! is dropped when decoded), 8-bit, 16-bit or 32-bit float samples. They
//! become linear RGB when read, through a transfer curve (8-bit and 16-bit
//! values through a table), so one decoded image serves every encoding it
//! is read with (a colour texture and a bump map of one file) and costs
//! what its file holds: an 8-bit RGB texel takes 3 bytes, not the 12 of
//! linear f32 RGB.
//!
//! | layout | from | bytes a texel |
//! |---|---|---|
//! | `Gray8` | 1-, 2-, 4- and 8-bit grey PNG, grey JPEG | 1 |
//! | `Rgb8` | 8-bit (and palette) colour PNG, colour JPEG | 3 |
//! | `Gray16` | 16-bit grey PNG | 2 |
//! | `Rgb16` | 16-bit colour PNG | 6 |
//! | `RgbF32` | Radiance HDR, OpenEXR | 12 |

use super::image::srgb_to_linear;
use glam::Vec3;
use std::sync::LazyLock;

/// Texels above this are read as it: the largest radiance the checker
/// accepts, so that a texel times any accepted scale stays finite in f32.
pub const MAX_TEXEL: f32 = 1e12;

/// How texels are stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Layout {
    /// One 8-bit sample.
    Gray8,
    /// Three 8-bit samples.
    Rgb8,
    /// One 16-bit sample.
    Gray16,
    /// Three 16-bit samples.
    Rgb16,
    /// Three f32 samples (linear, finite, non-negative, at most [`MAX_TEXEL`]).
    RgbF32,
}

impl Layout {
    /// The bytes a texel takes.
    pub const fn bytes_per_texel(self) -> u64 {
        match self {
            Layout::Gray8 => 1,
            Layout::Rgb8 => 3,
            Layout::Gray16 => 2,
            Layout::Rgb16 => 6,
            Layout::RgbF32 => 12,
        }
    }

    /// Whether the samples are floating-point (linear radiance, not
    /// encoded values).
    pub const fn is_float(self) -> bool {
        matches!(self, Layout::RgbF32)
    }

    /// Its name in messages.
    pub const fn name(self) -> &'static str {
        match self {
            Layout::Gray8 => "8-bit grey",
            Layout::Rgb8 => "8-bit RGB",
            Layout::Gray16 => "16-bit grey",
            Layout::Rgb16 => "16-bit RGB",
            Layout::RgbF32 => "float RGB",
        }
    }
}

/// How stored values become linear ones.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Curve {
    /// As they are (integers scaled to [0, 1]).
    Linear,
    /// Through the sRGB curve (floats then capped at [`MAX_TEXEL`]).
    Srgb,
}

/// The samples, by layout.
#[derive(Debug, Clone, PartialEq)]
pub enum Samples {
    /// 8-bit grey, one sample a texel.
    Gray8(Vec<u8>),
    /// 8-bit RGB, three samples a texel.
    Rgb8(Vec<u8>),
    /// 16-bit grey.
    Gray16(Vec<u16>),
    /// 16-bit RGB.
    Rgb16(Vec<u16>),
    /// f32 RGB.
    RgbF32(Vec<f32>),
}

/// A decoded image's texels, rows from the top: its samples and the texel
/// a material's weights read (the brightest), found once.
#[derive(Debug, Clone, PartialEq)]
pub struct Texels {
    width: usize,
    height: usize,
    samples: Samples,
    brightest: usize,
}

/// 8-bit values → linear, as they are and through the sRGB curve.
static LINEAR8: LazyLock<[f32; 256]> = LazyLock::new(|| std::array::from_fn(|i| i as f32 / 255.0));
static SRGB8: LazyLock<[f32; 256]> =
    LazyLock::new(|| std::array::from_fn(|i| srgb_to_linear(i as f32 / 255.0)));
/// 16-bit values through the sRGB curve (256 KiB, built on first use).
static SRGB16: LazyLock<Vec<f32>> = LazyLock::new(|| {
    (0..=u16::MAX)
        .map(|v| srgb_to_linear(v as f32 / 65535.0))
        .collect()
});

/// The table that reads 8-bit values through `curve`.
#[inline(always)]
fn table8(curve: Curve) -> &'static [f32; 256] {
    match curve {
        Curve::Linear => &LINEAR8,
        Curve::Srgb => &SRGB8,
    }
}

impl Texels {
    /// `width` × `height` texels of `samples` (as many as that takes).
    pub fn new(width: usize, height: usize, samples: Samples) -> Texels {
        let mut t = Texels {
            width,
            height,
            samples,
            brightest: 0,
        };
        assert_eq!(
            t.sample_count(),
            width * height * t.channels(),
            "{width} × {height} texels"
        );
        t.brightest = t.find_brightest();
        t
    }

    /// Width in texels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// How they are stored.
    pub fn layout(&self) -> Layout {
        match &self.samples {
            Samples::Gray8(_) => Layout::Gray8,
            Samples::Rgb8(_) => Layout::Rgb8,
            Samples::Gray16(_) => Layout::Gray16,
            Samples::Rgb16(_) => Layout::Rgb16,
            Samples::RgbF32(_) => Layout::RgbF32,
        }
    }

    /// The bytes the texels take.
    pub fn bytes(&self) -> u64 {
        (self.width * self.height) as u64 * self.layout().bytes_per_texel()
    }

    fn channels(&self) -> usize {
        match self.layout() {
            Layout::Gray8 | Layout::Gray16 => 1,
            _ => 3,
        }
    }

    fn sample_count(&self) -> usize {
        match &self.samples {
            Samples::Gray8(v) | Samples::Rgb8(v) => v.len(),
            Samples::Gray16(v) | Samples::Rgb16(v) => v.len(),
            Samples::RgbF32(v) => v.len(),
        }
    }

    /// Texel `i` (row by row from the top) in linear RGB through `curve`.
    #[inline(always)]
    pub fn get(&self, i: usize, curve: Curve) -> Vec3 {
        self.get4([i; 4], curve)[0]
    }

    /// Four texels at once, as bilinear filtering reads them: one choice of
    /// layout for the four, inlined into the lookups (a float or 8-bit
    /// texel is then a load and a table read or two, as cheap as the
    /// `Vec<Vec3>` of before).
    #[inline(always)]
    pub fn get4(&self, at: [usize; 4], curve: Curve) -> [Vec3; 4] {
        // Written out: `array::map` leaves a loop of calls behind.
        #[inline(always)]
        fn each(at: [usize; 4], f: impl Fn(usize) -> Vec3) -> [Vec3; 4] {
            [f(at[0]), f(at[1]), f(at[2]), f(at[3])]
        }
        match (&self.samples, curve) {
            (Samples::RgbF32(v), Curve::Linear) => {
                let rgb = v.as_chunks::<3>().0;
                each(at, |i| Vec3::from_array(rgb[i]))
            }
            (Samples::Rgb8(v), _) => {
                let (t, rgb) = (table8(curve), v.as_chunks::<3>().0);
                each(at, |i| {
                    let [r, g, b] = rgb[i];
                    Vec3::new(t[r as usize], t[g as usize], t[b as usize])
                })
            }
            (Samples::Gray8(v), _) => {
                let t = table8(curve);
                each(at, |i| Vec3::splat(t[v[i] as usize]))
            }
            _ => each(at, |i| self.get_rare(i, curve)),
        }
    }

    /// [`Texels::get`] for 16-bit samples and floats through the sRGB curve.
    #[inline(never)]
    fn get_rare(&self, i: usize, curve: Curve) -> Vec3 {
        let to16 = |v: u16| match curve {
            Curve::Linear => v as f32 / 65535.0,
            Curve::Srgb => SRGB16[v as usize],
        };
        match &self.samples {
            Samples::Gray16(v) => Vec3::splat(to16(v[i])),
            Samples::Rgb16(v) => {
                let s = &v[3 * i..3 * i + 3];
                Vec3::new(to16(s[0]), to16(s[1]), to16(s[2]))
            }
            Samples::RgbF32(v) => {
                let c = Vec3::from_slice(&v[3 * i..3 * i + 3]);
                match curve {
                    Curve::Linear => c,
                    Curve::Srgb => Vec3::new(
                        srgb_to_linear(c.x),
                        srgb_to_linear(c.y),
                        srgb_to_linear(c.z),
                    )
                    .min(Vec3::splat(MAX_TEXEL)),
                }
            }
            Samples::Gray8(_) | Samples::Rgb8(_) => unreachable!("read by get4"),
        }
    }

    /// The brightest texel's index (by largest component; both curves
    /// keep the order of values, so it is the brightest through either).
    pub fn brightest(&self) -> usize {
        self.brightest
    }

    /// The first texel whose largest sample is the largest of all: the
    /// first holding the largest sample (two passes that vectorise: this
    /// runs over every texel of every image decoded).
    fn find_brightest(&self) -> usize {
        fn first_max<T: PartialOrd + Copy>(samples: &[T], channels: usize) -> usize {
            let Some(&first) = samples.first() else {
                return 0;
            };
            let max = (samples.iter()).fold(first, |a, &b| if b > a { b } else { a });
            samples.iter().position(|&s| s == max).unwrap_or(0) / channels
        }
        let c = self.channels();
        match &self.samples {
            Samples::Gray8(v) | Samples::Rgb8(v) => first_max(v, c),
            Samples::Gray16(v) | Samples::Rgb16(v) => first_max(v, c),
            Samples::RgbF32(v) => first_max(v, c),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_layout_reads_through_both_curves() {
        let gray = Texels::new(2, 1, Samples::Gray8(vec![0, 128]));
        assert_eq!(gray.get(1, Curve::Linear), Vec3::splat(128.0 / 255.0));
        assert!((gray.get(1, Curve::Srgb).x - 0.2158).abs() < 1e-3);
        assert_eq!((gray.bytes(), gray.brightest()), (2, 1));
        let rgb = Texels::new(1, 2, Samples::Rgb8(vec![255, 0, 128, 1, 2, 3]));
        assert_eq!(rgb.get(0, Curve::Linear).x, 1.0);
        assert_eq!(rgb.get(0, Curve::Srgb).z, srgb_to_linear(128.0 / 255.0));
        assert_eq!((rgb.bytes(), rgb.brightest()), (6, 0));
        let deep = Texels::new(1, 1, Samples::Rgb16(vec![65535, 0, 32768]));
        assert_eq!(deep.get(0, Curve::Linear).x, 1.0);
        assert!((deep.get(0, Curve::Srgb).z - srgb_to_linear(0.5)).abs() < 1e-4);
        assert_eq!(deep.bytes(), 6);
        let g16 = Texels::new(1, 1, Samples::Gray16(vec![65535]));
        assert_eq!(g16.get(0, Curve::Srgb), Vec3::ONE);
        let float = Texels::new(2, 1, Samples::RgbF32(vec![0.5, 2.0, 0.0, 3.0, 1.0, 1.0]));
        assert_eq!(float.get(0, Curve::Linear), Vec3::new(0.5, 2.0, 0.0));
        assert_eq!(float.get(0, Curve::Srgb).x, srgb_to_linear(0.5));
        assert_eq!((float.bytes(), float.brightest()), (24, 1));
        // sRGB of a texel at the cap stays at the cap.
        let huge = Texels::new(1, 1, Samples::RgbF32(vec![MAX_TEXEL; 3]));
        assert_eq!(huge.get(0, Curve::Srgb), Vec3::splat(MAX_TEXEL));
    }
}
