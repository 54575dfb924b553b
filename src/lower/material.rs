//! A checked material → the renderer's material, its textures added to the
//! scene's.

use crate::check;
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::lower::image::Images;
use crate::material::{self, Material, Textured};
use crate::texture::image::Wrap;
use crate::texture::noise::NoiseKind;
use crate::texture::{Pattern, Space, Texture};
use glam::{Affine3A, DVec3};

/// A checked material in the renderer's f32; its textures are pushed onto
/// `textures` and named by index, their images read through `images`; an
/// image that cannot be read is a diagnostic.
pub fn lower_material(
    m: &check::Material,
    textures: &mut Vec<Texture>,
    images: &mut Images,
    diags: &mut Diagnostics,
) -> Material {
    let params = material::Params {
        diffuse: DVec3::from_array(m.diffuse).as_vec3(),
        reflection: DVec3::from_array(m.reflection).as_vec3(),
        gloss: m.gloss as f32,
        transmission: m.transmission as f32,
        ior: m.ior as f32,
        absorption: DVec3::from_array(m.absorption).as_vec3(),
        emission: DVec3::from_array(m.emission).as_vec3(),
        two_sided: m.two_sided,
    };
    let mut material = Material::new(&params);
    if m.diffuse_texture.is_some() || m.reflection_texture.is_some() {
        let mut add = |t: &Option<check::Texture>| {
            let texture = lower_texture(t.as_ref()?, images, diags)?;
            textures.push(texture);
            Some(textures.len() as u32 - 1)
        };
        material.textured = Some(Box::new(Textured {
            params,
            diffuse: add(&m.diffuse_texture),
            reflection: add(&m.reflection_texture),
        }));
    }
    material
}

/// A checked texture in the renderer's f32: its transforms inverted, to
/// take the coordinates it reads into its pattern's.
fn lower_texture(
    t: &check::Texture,
    images: &mut Images,
    diags: &mut Diagnostics,
) -> Option<Texture> {
    let rgb = |c: [f64; 3]| DVec3::from_array(c).as_vec3();
    let pattern = match &t.kind {
        check::TextureKind::Checker => Pattern::Checker,
        check::TextureKind::Noise { pattern, octaves } => Pattern::Noise {
            kind: (NoiseKind::NAMES.iter())
                .find(|(n, _)| n == pattern)
                .map_or(NoiseKind::Noise, |&(_, k)| k),
            octaves: *octaves,
        },
        check::TextureKind::Image {
            path,
            path_span,
            wrap,
        } => match images.get(path) {
            Ok(image) => Pattern::Image {
                image,
                wrap: (Wrap::NAMES.iter())
                    .find(|(n, _)| n == wrap)
                    .map_or(Wrap::Repeat, |&(_, w)| w),
            },
            Err(e) => {
                diags.push(
                    Diagnostic::error(
                        codes::IMAGE_FILE,
                        format!("cannot load image `{}`", path.display()),
                        *path_span,
                    )
                    .with_label(e)
                    .with_help(
                        "textures read .png, .jpg, .hdr and .exr files, relative to the scene",
                    ),
                );
                return None;
            }
        },
    };
    Some(Texture {
        pattern,
        space: match t.space {
            check::TextureSpace::Uv => Space::Uv,
            check::TextureSpace::Object => Space::Object,
            check::TextureSpace::World => Space::World,
        },
        to_pattern: Affine3A::from_mat4(t.transform.inverse().as_mat4()),
        colors: [rgb(t.colors[0]), rgb(t.colors[1])],
    })
}
