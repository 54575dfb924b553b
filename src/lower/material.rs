//! A checked material → the renderer's material, its textures added to the
//! scene's.

use crate::check;
use crate::check::scene::TextureInput;
use crate::diag::Diagnostics;
use crate::ir::cutout::Opacity;
use crate::lower::image::{Encoding, Images};
use crate::material::conductor::Conductor;
use crate::material::plastic::CoatFamily;
use crate::material::plastic::Plastic;
use crate::material::principled::Principled;
use crate::material::{self, microfacet, Input, Material, NormalInput, Textured};
use crate::source::Files;
use crate::texture::image::Channel;
use crate::texture::{ColorMap, Pattern, Space, Texture};
use glam::{Affine3A, DVec3, Vec3};
use std::collections::HashMap;
use std::sync::Arc;

/// The plastics' coats of one compile by (index, α) bits: a rough coat's
/// tables take about 4 ms to compute, and a loop of inline materials
/// repeats the same coat thousands of times.
#[derive(Default)]
pub struct Coats {
    coats: HashMap<(u32, u32), Plastic>,
    /// A check without a render: the coats' tables can find no problem, so
    /// none is computed (every coat is the smooth one).
    checking: bool,
}

impl Coats {
    /// Coats for a check that renders nothing.
    pub fn for_checking() -> Coats {
        Coats {
            checking: true,
            ..Coats::default()
        }
    }

    /// The coat of index `eta` and roughness `alpha`, computed once.
    fn get(&mut self, eta: f32, alpha: f32) -> Plastic {
        let alpha = if self.checking { 0.0 } else { alpha };
        *(self.coats)
            .entry((eta.to_bits(), alpha.to_bits()))
            .or_insert_with(|| Plastic::new(eta, alpha))
    }
}

/// A checked material in the renderer's f32; its textures are pushed onto
/// `textures` and named by index, their images read through `images`, its
/// coat (a plastic's) taken from `coats`; an image that cannot be read is
/// a diagnostic.
pub fn lower_material(
    m: &check::Material,
    textures: &mut Vec<Texture>,
    (images, files): (&mut Images, &dyn Files),
    coats: &mut Coats,
    diags: &mut Diagnostics,
) -> Material {
    let mut params = material::Params {
        diffuse: DVec3::from_array(m.diffuse).as_vec3(),
        reflection: DVec3::from_array(m.reflection).as_vec3(),
        gloss: m.gloss as f32,
        transmission: m.transmission as f32,
        // Every interface is between the inside and the medium outside:
        // its relative index is what refracts and reflects (as Mitsuba's
        // int_ior / ext_ior).
        ior: (m.ior / m.ior_outside) as f32,
        absorption: DVec3::from_array(m.absorption).as_vec3(),
        scattering: DVec3::from_array(m.scattering).as_vec3(),
        anisotropy: m.anisotropy as f32,
        emission: DVec3::from_array(m.emission).as_vec3(),
        two_sided: m.two_sided,
        kind: material::Kind::Lobes,
        multiscatter: m.multiscatter,
        roughness: m.roughness.map(|[u, v]| glam::DVec2::new(u, v).as_vec2()),
    };
    params.kind = kind(m, &mut params, coats);
    // A metal rough unevenly, or a principled material's stretched
    // highlight, lies along each hit's tangent.
    let uneven = params.roughness.is_some_and(|r| r.x != r.y)
        || matches!(params.kind, material::Kind::Principled(p) if p.anisotropic > 0.0);
    // An opacity texture is read by traversal (`lower_opacity`), not at
    // the hit.
    let shading_textures = (m.textures.iter()).any(|(i, _)| *i != TextureInput::Opacity);
    if !shading_textures && !uneven && !m.vertex_color {
        return Material::new(&params);
    }
    let textured_gloss = m.textures.iter().any(|(i, _)| *i == TextureInput::Gloss);
    let coats = match params.kind {
        material::Kind::Plastic(_) if textured_gloss => {
            Some(Arc::new(CoatFamily::new(params.ior, |eta, alpha| {
                coats.get(eta, alpha)
            })))
        }
        _ => None,
    };
    let mut textured = Textured {
        params: params.clone(),
        inputs: Vec::new(),
        normal: None,
        coats,
        tangent: uneven,
        vertex_color: m.vertex_color,
    };
    for (input, t) in m
        .textures
        .iter()
        .filter(|(i, _)| *i != TextureInput::Opacity)
    {
        let Some(texture) = lower_texture(t, input.is_data(), (images, files), diags) else {
            continue;
        };
        // What the parameter stands for in the lobes' weights and in a
        // light's power: the brightest colour the texture gives.
        let bright = texture.brightest();
        textures.push(texture);
        let index = textures.len() as u32 - 1;
        let input = match input {
            TextureInput::Diffuse => {
                params.diffuse = bright;
                Input::Diffuse
            }
            TextureInput::Reflection => {
                params.reflection = bright;
                Input::Reflection
            }
            TextureInput::Absorption => Input::Absorption,
            TextureInput::Emission => {
                params.emission = bright;
                Input::Emission
            }
            TextureInput::Gloss => Input::Gloss,
            TextureInput::Transmission => Input::Transmission,
            TextureInput::BaseColor => {
                params.diffuse = bright;
                Input::Diffuse
            }
            TextureInput::Metallic => Input::Metallic,
            TextureInput::Opacity => unreachable!("filtered out above"),
            TextureInput::NormalMap => {
                textured.normal = Some(NormalInput::Map {
                    texture: index,
                    scale: m.normal_scale as f32,
                });
                continue;
            }
            TextureInput::Bump => {
                textured.normal = Some(NormalInput::Bump {
                    texture: index,
                    height: m.bump_height as f32,
                });
                continue;
            }
        };
        textured.inputs.push((input, index));
    }
    let mut material = Material::new(&params);
    material.textured = Some(Box::new(textured));
    material
}

/// Where a checked material's surface is there, if not everywhere: its
/// opacity texture (pushed onto `textures`) or number, and its cutoff.
pub fn lower_opacity(
    m: &check::Material,
    textures: &mut Vec<Texture>,
    (images, files): (&mut Images, &dyn Files),
    diags: &mut Diagnostics,
) -> Option<Opacity> {
    if !m.is_cut_out() {
        return None;
    }
    let cutoff = m.opacity_cutoff.map(|c| c as f32);
    let textured = m.textures.iter().find(|(i, _)| *i == TextureInput::Opacity);
    let texture = match textured {
        Some((_, t)) => {
            textures.push(lower_texture(t, true, (images, files), diags)?);
            Some(textures.len() as u32 - 1)
        }
        None => None,
    };
    Some(Opacity {
        // A textured opacity holds its brightest value in `m.opacity`.
        value: if texture.is_some() {
            1.0
        } else {
            m.opacity as f32
        },
        texture,
        cutoff,
    })
}

/// The renderer's scattering model for a checked material; smooth glass
/// (and glass of index 1, which bends nothing) is the mix's transmission
/// lobe.
fn kind(m: &check::Material, params: &mut material::Params, coats: &mut Coats) -> material::Kind {
    match m.kind {
        check::MaterialKind::Mix => material::Kind::Lobes,
        check::MaterialKind::Conductor { preset, eta, k } => {
            // A metal's complex index relative to the medium outside.
            let (eta, k) = match preset.map(|metal| metal.constants()) {
                Some((eta, k)) => (Vec3::from_array(eta), Vec3::from_array(k)),
                None => (
                    DVec3::from_array(eta).as_vec3(),
                    DVec3::from_array(k).as_vec3(),
                ),
            };
            let outside = m.ior_outside as f32;
            material::Kind::Conductor(Conductor::new(eta / outside, k / outside))
        }
        check::MaterialKind::Plastic => {
            let alpha = if m.gloss > 0.0 {
                microfacet::gloss_to_alpha(m.gloss as f32)
            } else {
                0.0
            };
            material::Kind::Plastic(coats.get(params.ior, alpha))
        }
        check::MaterialKind::Dielectric => {
            let textured_gloss = (m.textures.iter()).any(|(i, _)| *i == TextureInput::Gloss);
            if (m.gloss == 0.0 && !textured_gloss) || params.ior == 1.0 {
                params.transmission = 1.0;
                material::Kind::Lobes
            } else {
                material::Kind::RoughDielectric
            }
        }
        check::MaterialKind::ThinDielectric => material::Kind::ThinDielectric,
        check::MaterialKind::None => material::Kind::Null,
        check::MaterialKind::Principled(pp) => {
            // `specular` gives the index (relative to the outside, as `ior`).
            if let Some(s) = pp.specular {
                params.ior = Principled::eta_of_specular(s as f32);
            }
            material::Kind::Principled(Principled {
                metallic: pp.metallic as f32,
                specular_tint: pp.specular_tint as f32,
                anisotropic: pp.anisotropic as f32,
                sheen: pp.sheen as f32,
                sheen_tint: pp.sheen_tint as f32,
                clearcoat: pp.clearcoat as f32,
                clearcoat_alpha: Principled::clearcoat_alpha(pp.clearcoat_roughness as f32),
                // Taken from the parameters by `Material::new`.
                ..Principled::default()
            })
        }
    }
}

/// How an image is read: as the scene says, else data maps linearly and
/// colours by their file (8-bit sRGB, floating-point linear).
fn encoding(color_space: Option<check::scene::ColorSpace>, data: bool) -> Encoding {
    match (color_space, data) {
        (Some(check::scene::ColorSpace::Srgb), _) => Encoding::Srgb,
        (Some(check::scene::ColorSpace::Linear), _) | (None, true) => Encoding::Linear,
        (None, false) => Encoding::ByFile,
    }
}

/// A checked texture in the renderer's f32: its transforms inverted, to
/// take the coordinates it reads into its pattern's; an image's 8-bit
/// values read linearly when it holds `data`.
fn lower_texture(
    t: &check::Texture,
    data: bool,
    (images, files): (&mut Images, &dyn Files),
    diags: &mut Diagnostics,
) -> Option<Texture> {
    let pattern = match &t.kind {
        check::TextureKind::Checker => Pattern::Checker,
        check::TextureKind::Gradient => Pattern::Gradient,
        check::TextureKind::Stripes => Pattern::Stripes,
        check::TextureKind::Noise { kind, params } => Pattern::Noise {
            kind: *kind,
            params: *params,
        },
        check::TextureKind::Image {
            path,
            named,
            path_span,
            wrap,
            color_space,
            factor,
            channel,
            origin,
            ..
        } => {
            let read = match channel {
                Some(Channel::Alpha) => images.get_alpha(files, path),
                _ => images.get(files, path, encoding(*color_space, data)),
            };
            match read {
                Ok(image) => Pattern::Image {
                    image,
                    wrap: *wrap,
                    factor: DVec3::from_array(*factor).as_vec3(),
                    channel: *channel,
                },
                Err(e) => {
                    diags.push(match origin {
                        Some(origin) => {
                            check::image_files::unreadable_in_model(origin, *path_span, e)
                        }
                        None => {
                            let help = check::image_files::TEXTURE_HELP;
                            check::image_files::unreadable(named, *path_span, e, help)
                        }
                    });
                    return None;
                }
            }
        }
    };
    let stops = (t.colors.iter())
        .map(|&(at, c)| (at as f32, DVec3::from_array(c).as_vec3()))
        .collect();
    Some(Texture {
        pattern,
        space: match t.space {
            check::TextureSpace::Uv => Space::Uv,
            check::TextureSpace::Object => Space::Object,
            check::TextureSpace::World => Space::World,
        },
        to_pattern: Affine3A::from_mat4(t.transform.inverse().as_mat4()),
        // The checker keeps stops in order; a lone colour is a flat map.
        colors: ColorMap::new(stops).unwrap_or_else(|| ColorMap::two(Vec3::ZERO, Vec3::ZERO)),
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_checker_knows_the_renderers_metals() {
        let names: Vec<&str> = (crate::material::conductor::PRESETS.iter())
            .map(|p| p.0)
            .collect();
        assert_eq!(names, crate::check::schema::METAL_PRESETS);
    }
}
