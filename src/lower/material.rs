//! A checked material → the renderer's material.

use crate::check;
use crate::material::{self, Material};
use glam::DVec3;

/// A checked material in the renderer's f32.
pub fn lower_material(m: &check::Material) -> Material {
    Material::new(&material::Params {
        diffuse: DVec3::from_array(m.diffuse).as_vec3(),
        reflection: DVec3::from_array(m.reflection).as_vec3(),
        gloss: m.gloss as f32,
        transmission: m.transmission as f32,
        ior: m.ior as f32,
        absorption: DVec3::from_array(m.absorption).as_vec3(),
        emission: DVec3::from_array(m.emission).as_vec3(),
        two_sided: m.two_sided,
    })
}
