//! What a lowered scene holds in memory, for estimates made before a render
//! (film, state and textures): the bytes of its images.

use super::Scene;
use crate::light::Light;
use crate::texture::Pattern;
use std::collections::HashSet;

impl Scene {
    /// The bytes the scene's images hold: every image texture's and the
    /// environment map's texels (a file read by several textures, or in
    /// several encodings, once) and the environment map's sampling
    /// distribution. At most `lower::image::MAX_TEXTURE_BYTES`, which
    /// lowering enforces; a texel takes 1 to 12 bytes
    /// (`texture::texels::Layout::bytes_per_texel`).
    pub fn texture_bytes(&self) -> u64 {
        let mut seen = HashSet::new();
        let mut image_bytes = |image: &crate::texture::image::Image| {
            let first = seen.insert(std::sync::Arc::as_ptr(image.texels()));
            if first {
                image.bytes()
            } else {
                0
            }
        };
        let textures: u64 = (self.textures.iter())
            .filter_map(|t| match &t.pattern {
                Pattern::Image { image, .. } => Some(image_bytes(image)),
                _ => None,
            })
            .sum();
        let environment: u64 = (self.lights.iter())
            .filter_map(|l| match l {
                Light::Environment { map: Some(map), .. } => {
                    Some(image_bytes(map.image()) + map.distribution_bytes())
                }
                _ => None,
            })
            .sum();
        textures + environment
    }
}
