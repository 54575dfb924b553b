//! Textures: colours that vary over a surface. A texture is a pattern (a
//! function of a point) read in one of three spaces (the surface's (u, v),
//! the object's frame or the world) through its own transform, and a
//! colour for each value of the pattern. Materials name textures for their
//! colours; the scene evaluates them at a hit (`ir::Scene::material_at`),
//! so an untextured material costs nothing.

pub mod checker;
pub mod color_map;
pub mod gradient;
pub mod image;
pub mod noise;
pub mod shading_normal;
pub mod texels;

pub use color_map::ColorMap;

use glam::{Affine3A, Vec2, Vec3};

/// Where a texture is evaluated: the three spaces a pattern can live in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadingPoint {
    /// The surface's texture coordinates (see `geometry::texcoord`).
    pub uv: Vec2,
    /// The point in its object's frame (as written in the scene, before the
    /// object's transforms), at time 0 for a moving object.
    pub object: Vec3,
    /// The point in the world.
    pub world: Vec3,
}

/// The coordinates a pattern reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Space {
    /// (u, v, 0) from the surface's texture coordinates.
    Uv,
    /// The object's own frame: the pattern moves with the object.
    Object,
    /// World coordinates: objects move through the pattern.
    World,
}

/// What a texture computes from its coordinates.
#[derive(Debug, Clone, PartialEq)]
pub enum Pattern {
    /// Two colours in alternating cells (see [`checker`]).
    Checker,
    /// A ramp along x repeating every unit (see [`gradient`]).
    Gradient,
    /// Stripes across x, one unit wide (see [`gradient`]).
    Stripes,
    /// A solid noise pattern blending the two colours (see [`noise`]).
    Noise {
        /// Which pattern.
        kind: noise::NoiseKind,
        /// Its octaves and bands.
        params: noise::NoiseParams,
    },
    /// An image, read at (x, y) of the coordinates (in (u, v): the image
    /// over the unit square; in object or world space: projected along z).
    Image {
        /// The texels (shared by every texture that reads the same file).
        image: image::Image,
        /// What coordinates outside [0, 1] read.
        wrap: image::Wrap,
        /// Multiplies every texel (a glTF material's factor; 1 otherwise).
        factor: Vec3,
        /// The channel read where one number is wanted (`None`: the
        /// luminance).
        channel: Option<image::Channel>,
    },
}

/// A texture ready to evaluate.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// The function of the coordinates.
    pub pattern: Pattern,
    /// The coordinates it reads.
    pub space: Space,
    /// Applied to the coordinates before the pattern (the inverse of the
    /// transforms written on the texture: scaling a texture by 2 makes its
    /// cells twice as large).
    pub to_pattern: Affine3A,
    /// The pattern's value → colour (a checker's and stripes' even cells
    /// read it at 0, odd ones at 1; unused by an image).
    pub colors: ColorMap,
}

impl Texture {
    /// The texture's colour at `at`.
    pub fn eval(&self, at: &ShadingPoint) -> Vec3 {
        let p = self.to_pattern.transform_point3(self.coordinates(at));
        match &self.pattern {
            Pattern::Checker => {
                let odd = match self.space {
                    Space::Uv => checker::odd_uv(Vec2::new(p.x, p.y)),
                    Space::Object | Space::World => checker::odd_solid(p),
                };
                self.colors.end(odd)
            }
            Pattern::Gradient => self.colors.at(gradient::ramp(p)),
            Pattern::Stripes => self.colors.end(gradient::stripe(p) > 0.5),
            Pattern::Image {
                image,
                wrap,
                factor,
                ..
            } => image.lookup(Vec2::new(p.x, p.y), *wrap) * *factor,
            Pattern::Noise { kind, params } => self.colors.at(kind.value(p, params)),
        }
    }

    /// The texture's value at `at` as one number (for a roughness, a
    /// weight or a height): the luminance of its colour, which is the
    /// colour itself for a grey one, or an image's chosen channel.
    pub fn eval_scalar(&self, at: &ShadingPoint) -> f32 {
        let c = self.eval(at);
        match &self.pattern {
            Pattern::Image {
                channel: Some(channel),
                ..
            } => c[channel.index()],
            _ => 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z,
        }
    }

    /// The coordinates the texture reads at `at`.
    fn coordinates(&self, at: &ShadingPoint) -> Vec3 {
        match self.space {
            Space::Uv => at.uv.extend(0.0),
            Space::Object => at.object,
            Space::World => at.world,
        }
    }

    /// The brightest colour the texture gives (by largest component).
    pub fn brightest(&self) -> Vec3 {
        match &self.pattern {
            Pattern::Image { image, factor, .. } => image.brightest() * *factor,
            _ => self.colors.brightest(),
        }
    }

    /// Whether the texture reads texture coordinates (a mesh without them
    /// gets its triangles' barycentrics).
    pub fn reads_uv(&self) -> bool {
        self.space == Space::Uv
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(uv: [f32; 2], object: [f32; 3], world: [f32; 3]) -> ShadingPoint {
        ShadingPoint {
            uv: Vec2::from(uv),
            object: Vec3::from(object),
            world: Vec3::from(world),
        }
    }

    #[test]
    fn each_space_reads_its_own_coordinates_through_the_transform() {
        let (even, odd) = (Vec3::ONE, Vec3::ZERO);
        let mut t = Texture {
            pattern: Pattern::Checker,
            space: Space::Uv,
            to_pattern: Affine3A::IDENTITY,
            colors: ColorMap::two(even, odd),
        };
        // Mitsuba's checkerboard: four cells in the unit square.
        assert_eq!(t.eval(&at([0.25, 0.25], [0.0; 3], [0.0; 3])), even);
        assert_eq!(t.eval(&at([0.75, 0.25], [0.0; 3], [0.0; 3])), odd);
        t.space = Space::Object;
        assert_eq!(
            t.eval(&at([0.75, 0.25], [0.5, 0.5, 0.5], [1.5, 0.5, 0.5])),
            even
        );
        t.space = Space::World;
        assert_eq!(
            t.eval(&at([0.75, 0.25], [0.5, 0.5, 0.5], [1.5, 0.5, 0.5])),
            odd
        );
        // Scaled by 2 (the pattern reads half the coordinates): the cell
        // at 1.5 is now the even one.
        t.to_pattern = Affine3A::from_scale(Vec3::splat(0.5));
        assert_eq!(t.eval(&at([0.0; 2], [0.0; 3], [1.5, 0.5, 0.5])), even);
        assert!(!t.reads_uv());
    }
}
