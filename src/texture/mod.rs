//! Textures: colours that vary over a surface. A texture is a pattern (a
//! function of a point) read in one of three spaces (the surface's (u, v),
//! the object's frame or the world) through its own transform, and a
//! colour for each value of the pattern. Materials name textures for their
//! colours; the scene evaluates them at a hit (`ir::Scene::material_at`),
//! so an untextured material costs nothing.

pub mod checker;
pub mod image;
pub mod noise;

use glam::{Affine3A, Vec2, Vec3};
use std::sync::Arc;

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
    /// A solid noise pattern blending the two colours (see [`noise`]).
    Noise {
        /// Which pattern.
        kind: noise::NoiseKind,
        /// Octaves of its fractal sum.
        octaves: u32,
    },
    /// An image, read at (x, y) of the coordinates (in (u, v): the image
    /// over the unit square; in object or world space: projected along z).
    Image {
        /// The texels (shared by every texture that reads the same file).
        image: Arc<image::Image>,
        /// What coordinates outside [0, 1] read.
        wrap: image::Wrap,
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
    /// The pattern's colours (for a checker: the even and the odd cells;
    /// for noise: the colours at 0 and 1; unused by an image).
    pub colors: [Vec3; 2],
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
                self.colors[odd as usize]
            }
            Pattern::Image { image, wrap } => image.lookup(Vec2::new(p.x, p.y), *wrap),
            Pattern::Noise { kind, octaves } => {
                self.colors[0].lerp(self.colors[1], kind.value(p, *octaves))
            }
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
            colors: [even, odd],
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
