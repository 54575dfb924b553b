//! Image textures: linear RGB texels looked up at (u, v) with bilinear
//! filtering and a wrap mode. (0, 0) is the image's bottom-left corner and
//! (1, 1) its top-right (rows are stored top to bottom, as files have them);
//! texel centres sit at half-integers, as in pbrt and Mitsuba.

use super::texels::{Curve, Samples, Texels};
use glam::{Vec2, Vec3};
use std::sync::Arc;

/// What (u, v) outside [0, 1] reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Wrap {
    /// The image tiles the plane.
    Repeat,
    /// The edge texels extend outwards.
    Clamp,
    /// The image tiles the plane, every other copy mirrored.
    Mirror,
}

named_values!(Wrap {
    "repeat" => Repeat,
    "clamp" => Clamp,
    "mirror" => Mirror,
});

impl Wrap {
    /// The texel a column or row index `i` (any integer) reads in a side of
    /// `n` texels.
    #[inline]
    pub fn texel(self, i: i64, n: usize) -> usize {
        let n = n as i64;
        // Inside the image every mode reads the texel itself: no division
        // (an i64 remainder is tens of cycles, four of them per lookup).
        if (0..n).contains(&i) {
            return i as usize;
        }
        let wrapped = match self {
            Wrap::Repeat => i.rem_euclid(n),
            Wrap::Clamp => i.clamp(0, n - 1),
            Wrap::Mirror => {
                let period = i.rem_euclid(2 * n);
                if period < n {
                    period
                } else {
                    2 * n - 1 - period
                }
            }
        };
        wrapped as usize
    }
}

/// One channel of an image read as a number (a glTF metallic-roughness
/// map keeps roughness in green and metallic in blue).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Channel {
    /// The first channel.
    Red,
    /// The second channel.
    Green,
    /// The third channel.
    Blue,
    /// The alpha channel (read from a plane of its own: see
    /// `lower::image::Images::get`; an image without one is opaque).
    Alpha,
}

named_values!(Channel {
    "r" => Red,
    "g" => Green,
    "b" => Blue,
    "a" => Alpha,
});

impl Channel {
    /// Its index in an RGB triple.
    pub fn index(self) -> usize {
        match self {
            Channel::Red => 0,
            Channel::Green => 1,
            Channel::Blue => 2,
            // The alpha plane is stored as a grey image.
            Channel::Alpha => 0,
        }
    }
}

/// An image read in linear RGB: its decoded texels (shared by every
/// texture that reads the file, whatever its encoding) and the curve that
/// turns their values into linear ones.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Width in texels.
    pub width: usize,
    /// Height in texels.
    pub height: usize,
    texels: Arc<Texels>,
    curve: Curve,
}

impl Image {
    /// `texels` read through `curve`.
    pub fn new(texels: Arc<Texels>, curve: Curve) -> Image {
        Image {
            width: texels.width(),
            height: texels.height(),
            texels,
            curve,
        }
    }

    /// An image of linear RGB texels, row by row from the top (finite,
    /// non-negative: tests and generated maps).
    pub fn from_rgb(width: usize, height: usize, rgb: &[Vec3]) -> Image {
        let samples = rgb.iter().flat_map(|c| c.to_array()).collect();
        let texels = Texels::new(width, height, Samples::RgbF32(samples));
        Image::new(Arc::new(texels), Curve::Linear)
    }

    /// Texel `i`, row by row from the top, in linear RGB.
    #[inline]
    pub fn texel(&self, i: usize) -> Vec3 {
        self.texels.get(i, self.curve)
    }

    /// Four texels at once (see [`Texels::get4`]).
    #[inline]
    pub fn texels4(&self, at: [usize; 4]) -> [Vec3; 4] {
        self.texels.get4(at, self.curve)
    }

    /// The decoded texels (shared between the encodings of a file).
    pub fn texels(&self) -> &Arc<Texels> {
        &self.texels
    }

    /// The bytes its texels take.
    pub fn bytes(&self) -> u64 {
        self.texels.bytes()
    }

    /// The brightest texel (by largest component).
    pub fn brightest(&self) -> Vec3 {
        self.texel(self.texels.brightest())
    }

    /// The bilinearly filtered colour at (u, v).
    pub fn lookup(&self, uv: Vec2, wrap: Wrap) -> Vec3 {
        // Continuous texel coordinates, x right and y down, centres at +0.5.
        let x = uv.x * self.width as f32 - 0.5;
        let y = (1.0 - uv.y) * self.height as f32 - 0.5;
        if !(x.is_finite() && y.is_finite()) {
            return Vec3::ZERO;
        }
        // Far outside, f32 → i64 saturates; the wrap then keeps the index in range.
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        // The two columns and the two rows the four texels share.
        let (c0, c1) = (
            wrap.texel(x0, self.width),
            wrap.texel(x0.saturating_add(1), self.width),
        );
        let (r0, r1) = (
            wrap.texel(y0, self.height) * self.width,
            wrap.texel(y0.saturating_add(1), self.height) * self.width,
        );
        let [a, b, c, d] = self.texels4([r0 + c0, r0 + c1, r1 + c0, r1 + c1]);
        a.lerp(b, fx).lerp(c.lerp(d, fx), fy)
    }
}

/// sRGB-encoded value (0..1) → linear (the IEC 61966-2-1 curve).
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.040_45 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2 × 2: top row red, green; bottom row blue, white.
    fn image() -> Image {
        Image::from_rgb(2, 2, &[Vec3::X, Vec3::Y, Vec3::Z, Vec3::ONE])
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).abs().max_element() < 1e-5
    }

    #[test]
    fn texel_centres_are_exact_and_between_them_is_bilinear() {
        let im = image();
        // (0, 0) is the bottom-left corner: the bottom-left texel's centre
        // is at (0.25, 0.25).
        assert!(close(
            im.lookup(Vec2::new(0.25, 0.25), Wrap::Clamp),
            Vec3::Z
        ));
        assert!(close(
            im.lookup(Vec2::new(0.75, 0.25), Wrap::Clamp),
            Vec3::ONE
        ));
        assert!(close(
            im.lookup(Vec2::new(0.25, 0.75), Wrap::Clamp),
            Vec3::X
        ));
        assert!(close(
            im.lookup(Vec2::new(0.75, 0.75), Wrap::Clamp),
            Vec3::Y
        ));
        // The centre of the image is the mean of the four.
        let mean = (Vec3::X + Vec3::Y + Vec3::Z + Vec3::ONE) / 4.0;
        assert!(close(im.lookup(Vec2::splat(0.5), Wrap::Clamp), mean));
        // Halfway between two texels of the bottom row.
        assert!(close(
            im.lookup(Vec2::new(0.5, 0.25), Wrap::Clamp),
            (Vec3::Z + Vec3::ONE) / 2.0
        ));
    }

    #[test]
    fn wrap_modes() {
        assert_eq!(Wrap::Repeat.texel(-1, 4), 3);
        assert_eq!(Wrap::Repeat.texel(9, 4), 1);
        assert_eq!(Wrap::Clamp.texel(-5, 4), 0);
        assert_eq!(Wrap::Clamp.texel(9, 4), 3);
        assert_eq!(Wrap::Mirror.texel(-1, 4), 0);
        assert_eq!(Wrap::Mirror.texel(4, 4), 3);
        assert_eq!(Wrap::Mirror.texel(8, 4), 0);
        let im = image();
        // Repeat: a whole period away reads the same.
        let uv = Vec2::new(0.3, 0.6);
        assert!(close(
            im.lookup(uv, Wrap::Repeat),
            im.lookup(uv + Vec2::new(3.0, -2.0), Wrap::Repeat)
        ));
        // Clamp: far outside reads the edge.
        assert!(close(
            im.lookup(Vec2::new(-7.0, 0.25), Wrap::Clamp),
            Vec3::Z
        ));
        // Mirror: just past the right edge reads the right edge.
        assert!(close(
            im.lookup(Vec2::new(1.25, 0.25), Wrap::Mirror),
            Vec3::ONE
        ));
        // Extreme and non-finite coordinates stay in range.
        for w in [Wrap::Repeat, Wrap::Clamp, Wrap::Mirror] {
            assert!(im.lookup(Vec2::new(1e30, -1e30), w).is_finite());
            assert_eq!(im.lookup(Vec2::new(f32::NAN, 0.0), w), Vec3::ZERO);
        }
    }

    #[test]
    fn srgb_curve() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb_to_linear(0.5) - 0.214_04).abs() < 1e-4);
        // Continuous at the join.
        assert!((srgb_to_linear(0.040_45) - srgb_to_linear(0.040_451)).abs() < 1e-6);
    }
}
