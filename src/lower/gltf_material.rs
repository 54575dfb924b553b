//! A glTF file's materials as ptsc's principled material, field by field
//! (the table is in docs/language.md, "Models from glTF files"), and its
//! images: a file beside the glTF is read by path like any texture; one
//! held inside the file (a GLB buffer view, a data URI) is kept under a
//! path of its own (`scene.glb#image3.png`) that lowering serves from
//! memory.
//!
//! - `baseColorFactor` → `base_color`, `baseColorTexture` → its texture
//!   times the factor; under `alphaMode` MASK or BLEND their alpha is
//!   `opacity` (`alphaCutoff` → `opacity_cutoff` for MASK);
//! - `metallicFactor`, `roughnessFactor` → `metallic` and the perceptual
//!   roughness; `metallicRoughnessTexture` → both, from its blue and green
//!   channels times the factors;
//! - `normalTexture` → `normal_map`, its `scale` → `normal_scale`;
//! - `emissiveFactor` × `KHR_materials_emissive_strength`, `emissiveTexture`
//!   → `emission`;
//! - `KHR_materials_ior` → `ior`; `KHR_materials_transmission` →
//!   `transmission`; `KHR_materials_specular` → `specular` (its factor times
//!   the F0 of the index, as Burley's 0.08·specular);
//!   `KHR_materials_clearcoat` → `clearcoat`, `clearcoat_roughness`;
//!   `KHR_materials_sheen` → `sheen` (the colour's largest component) with
//!   `sheen_tint` 1 when the colour is not grey;
//! - `occlusionTexture` is not read: a path tracer finds the occlusion;
//!   `doubleSided` neither: ptsc's surfaces have two sides;
//! - a sampler's `wrapS` → `wrap` (`wrapT` is read as the same); `KHR_texture_transform` → the texture's
//!   transform.

use super::gltf_accessor::Buffers;
use super::gltf_buffers::{data_uri, relative_path};
use super::mesh_data::FileScene;
use crate::check::domain::{MAX_MAGNITUDE, MAX_RADIANCE};
use crate::check::scene::{
    Material, MaterialKind, PrincipledParams, Rgb, Texture, TextureInput, TextureKind, TextureSpace,
};
use crate::diag::NamedIn;
use crate::span::Span;
use crate::texture::image::{Channel, Wrap};
use glam::{DMat4, DVec4};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Reads the images and materials of `doc` (the file at `path`) into
/// `scene`.
pub fn read(doc: &gltf::Document, path: &Path, buffers: &Buffers, scene: &mut FileScene) {
    let images: Vec<Option<PathBuf>> = doc
        .images()
        .map(|image| image_path(doc, &image, (path, buffers), scene))
        .collect();
    // Which image a texture reads, said when it cannot be read: its path
    // is the glTF's, not the scene's.
    let origins: std::collections::HashMap<&Path, Arc<NamedIn>> = (images.iter())
        .enumerate()
        .filter_map(|(k, p)| {
            let p = p.as_deref()?;
            Some((p, Arc::new(origin(doc, k, path))))
        })
        .collect();
    // A set: a hostile file's many materials and primitives would make a
    // list's search quadratic.
    let colored: std::collections::HashSet<u32> = scene.colored_materials.iter().copied().collect();
    for m in doc.materials() {
        let mut mapped = material(&m, &images, &mut scene.material_notes);
        // glTF multiplies the base colour by `COLOR_0` where a primitive has it.
        mapped.vertex_color = m.index().is_some_and(|k| colored.contains(&(k as u32)));
        for (_, t) in &mut mapped.textures {
            if let TextureKind::Image { path, origin, .. } = &mut t.kind {
                *origin = origins.get(path.as_path()).cloned();
            }
        }
        scene.materials.push(mapped);
        scene
            .material_names
            .push(m.name().unwrap_or_default().to_string());
    }
}

/// Where the texture of `image` is read from (a path inside the file for
/// an embedded one, added to `scene.embedded`); `None`, with a note, when
/// ptsc cannot read it.
fn image_path(
    doc: &gltf::Document,
    image: &gltf::Image,
    (path, buffers): (&Path, &Buffers),
    scene: &mut FileScene,
) -> Option<PathBuf> {
    let k = image.index();
    // `Image::source` unwraps what the crate's checks do not ask for.
    let json = &doc.as_json().images[k];
    if json.uri.is_none() && json.buffer_view.is_none() {
        scene
            .notes
            .push(format!("image {k} has neither a `uri` nor a `bufferView`"));
        return None;
    }
    if json.buffer_view.is_some() && json.mime_type.is_none() {
        scene.material_notes.push(format!(
            "image {k} is in a buffer view without a `mimeType`"
        ));
        return None;
    }
    let (bytes, mime) = match image.source() {
        gltf::image::Source::Uri { uri, mime_type } => {
            match data_uri(uri, super::image::MAX_IMAGE_BYTES) {
                Ok(Some(bytes)) => (bytes, mime_type.or_else(|| mime_of_data(uri))),
                Ok(None) => {
                    let folder = path.parent().unwrap_or(Path::new(""));
                    return match relative_path(uri) {
                        Ok(p) => Some(folder.join(p)),
                        Err(e) => {
                            scene.material_notes.push(format!("image {k}: {e}"));
                            None
                        }
                    };
                }
                Err(e) => {
                    scene.material_notes.push(format!("image {k}: {e}"));
                    return None;
                }
            }
        }
        gltf::image::Source::View { view, mime_type } => {
            let bytes = (buffers.get(view.buffer().index()))
                .and_then(|b| b.get(view.offset()..view.offset().checked_add(view.length())?));
            match bytes {
                Some(b) => (b.to_vec(), Some(mime_type)),
                None => {
                    scene.material_notes.push(format!(
                        "image {k}: its buffer view reaches past its buffer"
                    ));
                    return None;
                }
            }
        }
    };
    let extension = match mime {
        Some("image/png") => "png",
        Some("image/jpeg") => "jpg",
        other => {
            scene.material_notes.push(format!(
                "image {k} is {}: ptsc reads PNG and JPEG",
                other.unwrap_or("of no stated type")
            ));
            return None;
        }
    };
    let mut name = path.as_os_str().to_owned();
    name.push(format!("#image{k}.{extension}"));
    let inside = PathBuf::from(name);
    scene.embedded.push((inside.clone(), Arc::new(bytes)));
    Some(inside)
}

/// Where image `k` of the glTF file `gltf` is, for an error about it: a
/// file its `uri` names relative to the glTF file, or bytes inside it.
fn origin(doc: &gltf::Document, k: usize, gltf: &Path) -> NamedIn {
    // The glTF by its file name, not its resolved path: that depends on
    // the folder the scene was opened from, and check and the editor say
    // the same.
    let file_name = gltf.file_name().unwrap_or_default().to_string_lossy();
    let uri = (doc.as_json().images[k].uri.as_deref()).filter(|u| !u.starts_with("data:"));
    match uri {
        Some(uri) => NamedIn {
            named: format!("`{uri}` of `images[{k}]` in `{file_name}`"),
            help: format!(
                "a glTF file's images are read relative to the glTF file: put `{uri}` beside `{file_name}`, or mend the image's `uri`"
            ),
        },
        None => NamedIn {
            named: format!("`images[{k}]` held inside `{file_name}`"),
            help: "the image is held inside the glTF file: export the model again, or mend the image in an image editor".into(),
        },
    }
}

/// The media type a data URI states (`data:image/png;base64,…`).
fn mime_of_data(uri: &str) -> Option<&str> {
    let header = uri.strip_prefix("data:")?.split([';', ',']).next()?;
    (!header.is_empty()).then_some(header)
}

/// A JSON number of an extension's object, if given.
fn number(ext: Option<&Value>, key: &str) -> Option<f64> {
    ext?.get(key)?.as_f64().filter(|x| x.is_finite())
}

/// A colour from glTF's f32 components, negative or non-finite ones 0,
/// within the scene language's magnitudes.
fn rgb(c: [f32; 3]) -> Rgb {
    c.map(|x| match x.is_finite() {
        true => (x as f64).clamp(0.0, MAX_MAGNITUDE),
        false => 0.0,
    })
}

/// An emission of `factor` times `KHR_materials_emissive_strength`'s
/// strength (a negative or non-finite one read as 1), within the language's
/// radiances.
fn emission(m: &gltf::Material) -> Rgb {
    let strength = (m.emissive_strength())
        .filter(|s| s.is_finite() && *s >= 0.0)
        .map_or(1.0, f64::from);
    rgb(m.emissive_factor()).map(|c| (c * strength).min(MAX_RADIANCE))
}

/// The material `m` in ptsc's terms, its textures' images from `images`;
/// what it asks that ptsc does not follow goes to `notes`.
pub fn material(
    m: &gltf::Material,
    images: &[Option<PathBuf>],
    notes: &mut Vec<String>,
) -> Material {
    let name = m
        .name()
        .map_or(format!("#{}", m.index().unwrap_or(0)), str::to_string);
    let unit = |x: f64| {
        if x.is_finite() {
            x.clamp(0.0, 1.0)
        } else {
            0.0
        }
    };
    let pbr = m.pbr_metallic_roughness();
    let mut out = Material::default_at(Span::default());
    out.name = Some(name.clone());
    let [r, g, b, alpha] = pbr.base_color_factor();
    out.diffuse = rgb([r, g, b]);
    out.gloss = unit(pbr.roughness_factor() as f64);
    let metallic = unit(pbr.metallic_factor() as f64);
    out.ior = m.ior().map_or(1.5, |n| (n as f64).clamp(1.0, 10.0));
    if m.ior().is_some_and(|n| n < 1.0) {
        notes.push(format!(
            "material `{name}`: an index of refraction below 1 is read as 1"
        ));
    }
    out.transmission = m
        .transmission()
        .map_or(0.0, |t| unit(t.transmission_factor() as f64));
    out.emission = emission(m);
    let clearcoat = m.extension_value("KHR_materials_clearcoat");
    let sheen = m.extension_value("KHR_materials_sheen");
    let sheen_color = (sheen.and_then(|s| s.get("sheenColorFactor")))
        .and_then(|c| serde_json::from_value::<[f32; 3]>(c.clone()).ok())
        .map_or([0.0; 3], rgb);
    let sheen_weight = unit(sheen_color.iter().cloned().fold(0.0, f64::max));
    let specular = m.specular().map(|s| {
        let f0 = ((out.ior - 1.0) / (out.ior + 1.0)).powi(2);
        if rgb(s.specular_color_factor()) != [1.0; 3] {
            notes.push(format!(
                "material `{name}`: its specular colour is not followed"
            ));
        }
        unit(s.specular_factor() as f64 * f0 / 0.08)
    });
    out.kind = MaterialKind::Principled(PrincipledParams {
        metallic,
        // A refracting surface keeps its index; its reflection follows it.
        specular: specular.filter(|_| out.transmission == 0.0),
        specular_tint: 0.0,
        anisotropic: 0.0,
        sheen: sheen_weight,
        sheen_tint: if sheen_color.iter().all(|&c| c == sheen_color[0]) {
            0.0
        } else {
            1.0
        },
        clearcoat: number(clearcoat, "clearcoatFactor").map_or(0.0, unit),
        clearcoat_roughness: number(clearcoat, "clearcoatRoughnessFactor").map_or(0.0, unit),
    });
    textures(m, images, &mut out, notes);
    out.normal_scale = m.normal_texture().map_or(1.0, |n| n.scale() as f64);
    match m.alpha_mode() {
        gltf::material::AlphaMode::Opaque if alpha < 1.0 => notes.push(format!(
            "material `{name}`: its alpha {alpha} has no effect under `alphaMode` OPAQUE"
        )),
        gltf::material::AlphaMode::Opaque => {}
        mode => cut_out(m, images, mode, &mut out, notes),
    }
    for (key, what) in [
        ("KHR_materials_unlit", "its unlit shading"),
        ("KHR_materials_volume", "its volume"),
        ("KHR_materials_iridescence", "its iridescence"),
        ("KHR_materials_anisotropy", "its anisotropy"),
    ] {
        if m.extension_value(key).is_some() {
            notes.push(format!(
                "material `{name}`: {what} (`{key}`) is not followed"
            ));
        }
    }
    out
}

/// `alphaMode` MASK or BLEND → `opacity` (the base colour's alpha: its
/// factor times its texture's alpha channel), with `opacity_cutoff` from
/// `alphaCutoff` (default 0.5) for MASK. An emitting surface stays whole
/// (a light is not cut out), with a note.
fn cut_out(
    m: &gltf::Material,
    images: &[Option<PathBuf>],
    mode: gltf::material::AlphaMode,
    out: &mut Material,
    notes: &mut Vec<String>,
) {
    let name = out.name.clone().unwrap_or_default();
    let mode_name = match mode {
        gltf::material::AlphaMode::Mask => "MASK",
        _ => "BLEND",
    };
    if out.emission.iter().any(|&c| c > 0.0) {
        notes.push(format!(
            "material `{name}`: its `alphaMode` {mode_name} is not followed on an emitting surface, which stays whole"
        ));
        return;
    }
    let pbr = m.pbr_metallic_roughness();
    let alpha = pbr.base_color_factor()[3].clamp(0.0, 1.0) as f64;
    out.opacity = alpha;
    if mode == gltf::material::AlphaMode::Mask {
        out.opacity_cutoff = Some(m.alpha_cutoff().unwrap_or(0.5).clamp(0.0, 1.0) as f64);
    }
    if let Some(info) = pbr.base_color_texture() {
        let source = Source::of(&info, uv_set(m));
        match texture(&source, images, [alpha; 3], Some(Channel::Alpha)) {
            Ok(t) => out.textures.push((TextureInput::Opacity, t)),
            Err(e) => notes.push(format!("material `{name}`: {e}")),
        }
    }
}

/// The textures of `m` onto `out` (a textured parameter holds its factor,
/// the texture's brightest value before its image is read).
fn textures(
    m: &gltf::Material,
    images: &[Option<PathBuf>],
    out: &mut Material,
    notes: &mut Vec<String>,
) {
    let name = out.name.clone().unwrap_or_default();
    let pbr = m.pbr_metallic_roughness();
    let set = uv_set(m);
    let notes = std::cell::RefCell::new(notes);
    let add_note = |e: String| notes.borrow_mut().push(format!("material `{name}`: {e}"));
    let mut add =
        |input: TextureInput, info: Source, factor: Rgb, channel: Option<Channel>| match texture(
            &info, images, factor, channel,
        ) {
            Ok(t) => out.textures.push((input, t)),
            Err(e) => add_note(e),
        };
    let [r, g, b, _] = pbr.base_color_factor();
    if let Some(info) = pbr.base_color_texture() {
        add(
            TextureInput::BaseColor,
            Source::of(&info, set),
            rgb([r, g, b]),
            None,
        );
    }
    if let Some(info) = pbr.metallic_roughness_texture() {
        let roughness = [pbr.roughness_factor() as f64; 3];
        let metallic = [pbr.metallic_factor() as f64; 3];
        add(
            TextureInput::Gloss,
            Source::of(&info, set),
            roughness,
            Some(Channel::Green),
        );
        add(
            TextureInput::Metallic,
            Source::of(&info, set),
            metallic,
            Some(Channel::Blue),
        );
    }
    if let Some(info) = m.emissive_texture() {
        add(
            TextureInput::Emission,
            Source::of(&info, set),
            emission(m),
            None,
        );
    }
    if let Some(normal) = m.normal_texture() {
        let transform = normal
            .extension_value("KHR_texture_transform")
            .map(transform_of_json);
        let info = Source {
            texture: normal.texture(),
            tex_coord: normal.tex_coord(),
            transform,
            set,
        };
        add(TextureInput::NormalMap, info, [1.0; 3], None);
    }
}

/// A texture reference: the texture, its coordinate set, its transform
/// (offset, rotation, scale), and the set its material's surfaces read.
struct Source<'a> {
    texture: gltf::Texture<'a>,
    tex_coord: u32,
    transform: Option<([f64; 2], f64, [f64; 2])>,
    set: u32,
}

/// The texture coordinate set a material's surfaces read (`TEXCOORD_n`):
/// its base colour texture's, else its first texture's (metallic-roughness,
/// emissive, normal), 0 without textures. ptsc keeps one set per surface:
/// a texture of the material that reads another is left out with a note.
pub fn uv_set(m: &gltf::Material) -> u32 {
    let pbr = m.pbr_metallic_roughness();
    let sets = [
        pbr.base_color_texture()
            .map(|i| Source::of(&i, 0).tex_coord),
        pbr.metallic_roughness_texture()
            .map(|i| Source::of(&i, 0).tex_coord),
        m.emissive_texture().map(|i| Source::of(&i, 0).tex_coord),
        m.normal_texture().map(|n| n.tex_coord()),
    ];
    sets.into_iter().flatten().next().unwrap_or(0)
}

impl<'a> Source<'a> {
    /// The reference of a `textureInfo` on a surface that reads `set`.
    fn of(info: &gltf::texture::Info<'a>, set: u32) -> Source<'a> {
        let transform = info.texture_transform().map(|t| {
            let [ox, oy] = t.offset().map(f64::from);
            let [sx, sy] = t.scale().map(f64::from);
            ([ox, oy], t.rotation() as f64, [sx, sy])
        });
        Source {
            texture: info.texture(),
            tex_coord: info
                .texture_transform()
                .and_then(|t| t.tex_coord())
                .unwrap_or(info.tex_coord()),
            transform,
            set,
        }
    }
}

/// A `KHR_texture_transform` object read from its JSON.
fn transform_of_json(v: &Value) -> ([f64; 2], f64, [f64; 2]) {
    let pair = |key: &str, default: [f64; 2]| {
        (v.get(key)
            .and_then(|p| serde_json::from_value::<[f64; 2]>(p.clone()).ok()))
        .unwrap_or(default)
    };
    let rotation = v.get("rotation").and_then(Value::as_f64).unwrap_or(0.0);
    (pair("offset", [0.0; 2]), rotation, pair("scale", [1.0; 2]))
}

/// The texture of `info`, its texels times `factor`, one number read from
/// `channel`.
fn texture(
    info: &Source,
    images: &[Option<PathBuf>],
    factor: Rgb,
    channel: Option<Channel>,
) -> Result<Texture, String> {
    let image = info.texture.source().index();
    let path = (images.get(image).cloned().flatten()).ok_or(format!(
        "texture {} reads image {image}, which is not read",
        info.texture.index()
    ))?;
    if info.tex_coord != info.set {
        return Err(format!(
            "texture {} reads texture coordinates {} while the material's others read set {}: ptsc reads one set per material, and leaves it out",
            info.texture.index(),
            info.tex_coord,
            info.set
        ));
    }
    let sampler = info.texture.sampler();
    let wrap = |mode: gltf::texture::WrappingMode| match mode {
        gltf::texture::WrappingMode::ClampToEdge => Wrap::Clamp,
        gltf::texture::WrappingMode::MirroredRepeat => Wrap::Mirror,
        gltf::texture::WrappingMode::Repeat => Wrap::Repeat,
    };
    let transform = match info.transform {
        Some(t) => uv_transform(t).ok_or("its texture transform is not finite")?,
        None => DMat4::IDENTITY,
    };
    Ok(Texture {
        kind: TextureKind::Image {
            // The image's own name: the folder it was read from depends
            // on where the scene was opened, which messages leave out.
            named: (path.file_name()).map_or(String::new(), |n| n.to_string_lossy().into_owned()),
            path,
            path_span: Span::default(),
            wrap: wrap(sampler.wrap_s()),
            color_space: None,
            resolved: true,
            factor,
            channel,
            // Set by `read`, which knows the image's index.
            origin: None,
        },
        colors: vec![(0.0, [1.0; 3]), (1.0, [0.0; 3])],
        space: TextureSpace::Uv,
        transform,
        span: Span::default(),
    })
}

/// The texture transform (what ptsc's texture `transform` holds: the
/// inverse of the map from the surface's (u, v) to the image's) of a
/// `KHR_texture_transform`: glTF reads its image at T·R·S·uv in its own
/// coordinates (v down), ptsc's have v up, so the map is F·T·R·S·F with
/// F(u, v) = (u, 1 − v).
pub fn uv_transform((offset, rotation, scale): ([f64; 2], f64, [f64; 2])) -> Option<DMat4> {
    let flip = DMat4::from_cols(
        DVec4::new(1.0, 0.0, 0.0, 0.0),
        DVec4::new(0.0, -1.0, 0.0, 0.0),
        DVec4::new(0.0, 0.0, 1.0, 0.0),
        DVec4::new(0.0, 1.0, 0.0, 1.0),
    );
    let (s, c) = rotation.sin_cos();
    let rotate = DMat4::from_cols(
        DVec4::new(c, s, 0.0, 0.0),
        DVec4::new(-s, c, 0.0, 0.0),
        DVec4::Z,
        DVec4::W,
    );
    let map = flip
        * DMat4::from_translation([offset[0], offset[1], 0.0].into())
        * rotate
        * DMat4::from_scale([scale[0], scale[1], 1.0].into())
        * flip;
    let inverse = map.inverse();
    (inverse.is_finite() && map.determinant().abs() > 1e-12).then_some(inverse)
}
