//! Wavefront MTL materials as ptsc's principled material (issue 41): what
//! a `.mtl` file beside an OBJ says, key by key, in the words of `type
//! principled` (the table is in docs/language.md, "Materials from OBJ
//! files"). Parsing is `tobj`'s; this file only maps.
//!
//! - `Kd` → `base_color`, `map_Kd` → its texture (the texture alone, as
//!   Blender reads it, not multiplied by `Kd`);
//! - `Ns` (Phong exponent) → roughness: the Beckmann α of the same lobe
//!   width, √(2 / (Ns + 2)) (Walter et al. 2007, §5.2), as GGX α, whose
//!   square root is the perceptual roughness; `Pr` overrides, `map_Pr` is
//!   its texture;
//! - `Ks` → `specular`, its mean (Blender's importer reads it so); `Ni` ≥ 1
//!   → `ior` instead when given (exporters write `Ni 1` for "none": then
//!   `Ks` decides);
//! - `Pm`/`map_Pm` → `metallic`, `Ps` → `sheen`, `Pc` → `clearcoat`, `Pcr`
//!   → `clearcoat_roughness`, `aniso` → `anisotropic`;
//! - `Ke`/`map_Ke` → `emission`;
//! - `map_Bump`/`bump` (`-bm` its height) → `bump`, `norm` → `normal_map`;
//! - `d` (or 1 − `Tr`) → `opacity`, `map_d` → its image's alpha channel
//!   (as Blender reads it) times `d`: cutouts, fractions passed at random;
//! - texture options: `-s` and `-o` scale and shift the texture
//!   coordinates, `-clamp on` clamps, `-bm` as above; the rest are named.

use crate::check::scene::{
    Material, MaterialKind, PrincipledParams, Texture, TextureInput, TextureKind, TextureSpace,
};
use crate::diag::NamedIn;
use crate::span::Span;
use crate::texture::image::{Channel, Wrap};
use glam::DMat4;
use std::path::Path;

/// An MTL material in ptsc's terms, and what of it was left out.
#[derive(Debug, Clone, PartialEq)]
pub struct Mapped {
    /// The principled material (named as in the file).
    pub material: Material,
    /// One line per key that has no counterpart (for a warning).
    pub left_out: Vec<String>,
}

/// A texture reference of an MTL key: its file (relative to the MTL's
/// folder) and the options ptsc reads.
#[derive(Debug, Clone, PartialEq)]
struct TextureRef {
    file: String,
    /// `-bm`: a bump map's multiplier.
    bump_multiplier: Option<f64>,
    /// `-clamp on`.
    clamp: bool,
    /// `-s`: the texture coordinates scaled (the image repeats as often).
    scale: Option<[f64; 3]>,
    /// `-o`: the texture coordinates shifted.
    offset: Option<[f64; 3]>,
    /// Options read but not followed (`-s`, `-o`, …).
    ignored: Vec<String>,
}

/// The options of a texture statement and how many values each takes
/// (`-o`, `-s`, `-t` take one to three numbers).
const OPTIONS: [(&str, usize); 11] = [
    ("-bm", 1),
    ("-blendu", 1),
    ("-blendv", 1),
    ("-boost", 1),
    ("-cc", 1),
    ("-clamp", 1),
    ("-imfchan", 1),
    ("-mm", 2),
    ("-texres", 1),
    ("-type", 1),
    ("-o", 3),
];

/// Parses `[options] file` of a texture statement; the file is the rest
/// after the options (names may hold spaces).
fn texture_ref(text: &str) -> Option<TextureRef> {
    let mut out = TextureRef {
        file: String::new(),
        bump_multiplier: None,
        clamp: false,
        scale: None,
        offset: None,
        ignored: Vec::new(),
    };
    let mut rest = text.trim();
    while rest.starts_with('-') {
        let (option, after) = rest.split_once(char::is_whitespace)?;
        let mut after = after.trim_start();
        let takes = match option {
            "-s" | "-t" => 3,
            _ => OPTIONS.iter().find(|(o, _)| *o == option)?.1,
        };
        let mut values = Vec::new();
        for k in 0..takes {
            let (word, next) = after.split_once(char::is_whitespace).unwrap_or((after, ""));
            // -o, -s and -t take one to three numbers; the others exactly theirs.
            let numeric = word.parse::<f64>().is_ok();
            if k > 0 && matches!(option, "-o" | "-s" | "-t") && !numeric {
                break;
            }
            values.push(word.to_string());
            after = next.trim_start();
        }
        match option {
            "-bm" => {
                out.bump_multiplier = (values.first())
                    .and_then(|v| v.parse::<f64>().ok())
                    .filter(|m| m.abs() <= 1e8)
            }
            "-clamp" => out.clamp = values.first().is_some_and(|v| v == "on"),
            "-s" | "-o" => {
                // Missing components are the identity's (1 to scale, 0 to shift).
                let fill = if option == "-s" { 1.0 } else { 0.0 };
                let mut v = [fill; 3];
                for (k, text) in values.iter().enumerate() {
                    v[k] = text.parse::<f64>().ok().filter(|x| x.abs() <= 1e6)?;
                }
                if option == "-s" {
                    // A zero scale squeezes the image to a point: not read.
                    if v.iter().any(|x| x.abs() < 1e-6) {
                        return None;
                    }
                    out.scale = Some(v);
                } else {
                    out.offset = Some(v);
                }
            }
            _ => out.ignored.push(option.to_string()),
        }
        rest = after;
    }
    (!rest.is_empty()).then(|| TextureRef {
        file: rest.to_string(),
        ..out
    })
}

/// `d` (or 1 − `Tr`) → `opacity`, `map_d` → its texture's alpha channel
/// (as Blender reads it) times `d`; fractions pass at random (no cutoff).
/// An emitting surface stays whole (a light is not cut out).
fn opacity(
    m: &tobj::Material,
    library: &Path,
    span: Span,
    out: &mut Material,
    left_out: &mut Vec<String>,
) {
    let d = m
        .dissolve
        .map(f64::from)
        .or_else(|| number(m, "Tr").map(|t| 1.0 - t))
        .filter(|d| d.is_finite())
        .map_or(1.0, |d| d.clamp(0.0, 1.0));
    let map = m.dissolve_texture.as_ref();
    if d >= 1.0 && map.is_none() {
        return;
    }
    if out.emission.iter().any(|&c| c > 0.0) || m.unknown_param.contains_key("map_Ke") {
        left_out.push("its opacity (`d`, `Tr`, `map_d`): an emitting surface stays whole".into());
        return;
    }
    out.opacity = d;
    let Some(text) = map else {
        return;
    };
    match texture_ref(text) {
        Some(r) => {
            if !r.ignored.is_empty() {
                left_out.push(format!(
                    "`map_d`'s options {} (not followed)",
                    r.ignored.join(" ")
                ));
            }
            let mut t = image(&r, ("map_d", &m.name, library), span);
            if let TextureKind::Image {
                factor, channel, ..
            } = &mut t.kind
            {
                *factor = [d; 3];
                *channel = Some(Channel::Alpha);
            }
            out.textures.push((TextureInput::Opacity, t));
        }
        None => left_out.push(format!(
            "`map_d {text}` (its options or its file name cannot be read)"
        )),
    }
}

/// An image texture of `file`, which map `key` of material `name` of the
/// MTL file `library` names (relative to that file's folder, as Blender
/// reads it), read at the surface's (u, v) scaled by `-s` and shifted by
/// `-o`: the pattern reads s·uv + o, so the texture's transform (which
/// lowering inverts) is the inverse of that.
fn image(r: &TextureRef, (key, name, library): (&str, &str, &Path), span: Span) -> Texture {
    let folder = library.parent().unwrap_or(Path::new(""));
    // The library by its file name, not its resolved path: that depends
    // on the folder the scene was opened from, and check and the editor
    // say the same.
    let file_name = library.file_name().unwrap_or_default().to_string_lossy();
    let origin = NamedIn {
        named: format!("`{}` of `{key}` of material `{name}` in `{file_name}`", r.file),
        help: format!(
            "an MTL file's maps are read relative to the MTL file: put `{}` beside `{file_name}`, or mend the `{key}` line",
            r.file
        ),
    };
    let to_pattern = DMat4::from_translation(r.offset.unwrap_or([0.0; 3]).into())
        * DMat4::from_scale(r.scale.unwrap_or([1.0; 3]).into());
    Texture {
        kind: TextureKind::Image {
            path: folder.join(&r.file),
            named: r.file.clone(),
            path_span: span,
            wrap: if r.clamp { Wrap::Clamp } else { Wrap::Repeat },
            color_space: None,
            resolved: true,
            factor: [1.0; 3],
            channel: None,
            origin: Some(std::sync::Arc::new(origin)),
        },
        colors: vec![(0.0, [1.0; 3]), (1.0, [0.0; 3])],
        space: TextureSpace::Uv,
        transform: to_pattern.inverse(),
        span,
    }
}

/// The perceptual roughness of a Phong exponent `ns`: GGX α taken as the
/// Beckmann α of the same lobe, √(2 / (ns + 2)).
pub fn roughness_of_exponent(ns: f64) -> f64 {
    let alpha = (2.0 / (ns.max(0.0) + 2.0)).sqrt();
    alpha.sqrt().clamp(0.0, 1.0)
}

/// An MTL file's text as `tobj` can read it: a colour line (`Ka`, `Kd`,
/// `Ks`, `Ke`, `Tf`) with one value is that grey written out (`Kd 0.5`
/// means `Kd 0.5 0.5 0.5`), one with more than three keeps three, and one
/// that is not numbers (`Kd spectral …`, `Kd xyz …`) or has two is left out
/// (tobj 4 panics on fewer than three). Returns the text and the lines left
/// out.
pub fn readable(bytes: &[u8]) -> (String, Vec<String>) {
    let text = String::from_utf8_lossy(bytes);
    let mut out = String::with_capacity(text.len());
    let mut dropped = Vec::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        let key = words.next().unwrap_or("");
        if !matches!(key, "Ka" | "Kd" | "Ks" | "Ke" | "Tf") {
            out.push_str(line);
            out.push('\n');
            continue;
        }
        let values: Option<Vec<f32>> = words.map(|w| w.parse().ok()).collect();
        match values.as_deref() {
            Some([v]) => out.push_str(&format!("{key} {v} {v} {v}\n")),
            Some([a, b, c, ..]) => out.push_str(&format!("{key} {a} {b} {c}\n")),
            _ => dropped.push(line.trim().chars().take(80).collect()),
        }
    }
    (out, dropped)
}

/// A number of an unknown key (`Pm`, `Pr`, …), if given and finite.
fn number(m: &tobj::Material, key: &str) -> Option<f64> {
    let v: f64 = m
        .unknown_param
        .get(key)?
        .split_whitespace()
        .next()?
        .parse()
        .ok()?;
    v.is_finite().then_some(v)
}

/// A colour as three f64 in [0, ∞) (negative values clamped).
fn rgb(c: [f32; 3]) -> [f64; 3] {
    c.map(|x| {
        if x.is_finite() {
            (x as f64).max(0.0)
        } else {
            0.0
        }
    })
}

/// The material `m` of the MTL file `library`, its diagnostics' span the
/// mesh statement's `span`.
pub fn material(m: &tobj::Material, library: &Path, span: Span) -> Mapped {
    let mut left_out = Vec::new();
    let unit = |x: f64| x.clamp(0.0, 1.0);
    let mut out = Material::default_at(span);
    out.name = Some(m.name.clone());
    out.diffuse = m.diffuse.map_or([0.5; 3], rgb);
    out.gloss = match (number(m, "Pr"), m.shininess) {
        (Some(pr), _) => unit(pr),
        (None, Some(ns)) if ns.is_finite() => roughness_of_exponent(ns as f64),
        _ => 0.5,
    };
    let specular = m.specular.map(|ks| unit(rgb(ks).iter().sum::<f64>() / 3.0));
    let ior = m
        .optical_density
        .filter(|n| n.is_finite() && *n > 1.0 && *n <= 10.0)
        .map(f64::from);
    if let Some(ior) = ior {
        out.ior = ior;
    }
    out.kind = MaterialKind::Principled(PrincipledParams {
        metallic: number(m, "Pm").map_or(0.0, unit),
        specular: if ior.is_some() { None } else { specular },
        specular_tint: 0.0,
        anisotropic: number(m, "aniso").map_or(0.0, unit),
        sheen: number(m, "Ps").map_or(0.0, unit),
        sheen_tint: 0.0,
        clearcoat: number(m, "Pc").map_or(0.0, unit),
        clearcoat_roughness: number(m, "Pcr").map_or(0.0, unit),
    });
    out.emission = m.emissive.map_or([0.0; 3], rgb);
    let mut texture = |input: TextureInput, key: &str, text: Option<&String>| {
        let text = text?;
        match texture_ref(text) {
            Some(r) => {
                if !r.ignored.is_empty() {
                    left_out.push(format!(
                        "`{key}`'s options {} (not followed)",
                        r.ignored.join(" ")
                    ));
                }
                out.textures
                    .push((input, image(&r, (key, &m.name, library), span)));
                Some(r)
            }
            None => {
                left_out.push(format!(
                    "`{key} {text}` (its options or its file name cannot be read)"
                ));
                None
            }
        }
    };
    texture(
        TextureInput::BaseColor,
        "map_Kd",
        m.diffuse_texture.as_ref(),
    );
    texture(TextureInput::Gloss, "map_Pr", m.unknown_param.get("map_Pr"));
    texture(
        TextureInput::Metallic,
        "map_Pm",
        m.unknown_param.get("map_Pm"),
    );
    texture(
        TextureInput::Emission,
        "map_Ke",
        m.unknown_param.get("map_Ke"),
    );
    texture(TextureInput::NormalMap, "norm", m.unknown_param.get("norm"));
    if let Some(bump) = texture(TextureInput::Bump, "map_Bump", m.normal_texture.as_ref()) {
        // MTL's bump is in the texture's units; -bm scales it (ptsc's
        // default height is 0.01 scene units per unit).
        out.bump_height = 0.01 * bump.bump_multiplier.unwrap_or(1.0);
    }
    if m.diffuse_texture.is_some() {
        // The texture stands for its brightest value where a value is
        // needed (`check::material`): an image's is not known yet.
        out.diffuse = [1.0; 3];
    }
    if m.unknown_param.contains_key("map_Ke") {
        out.emission = [1.0; 3];
    }
    if m.unknown_param.contains_key("map_Pr") {
        out.gloss = 1.0;
    }
    if let (MaterialKind::Principled(p), true) =
        (&mut out.kind, m.unknown_param.contains_key("map_Pm"))
    {
        p.metallic = 1.0;
    }
    opacity(m, library, span, &mut out, &mut left_out);
    Mapped {
        material: out,
        left_out,
    }
}

#[cfg(test)]
#[path = "mtl_tests.rs"]
mod tests;
