//! `material { }` → a checked material: the paper's mix of lobes or one of
//! the models a `type` names, each with its own defaults and the
//! parameters that mean nothing to it reported.

use super::eval::Env;
use super::medium::MEDIUM_WORDS;
use super::params::{CheckTexture, Params, Val};
use super::reader::{textures, Reader};
use super::scene::*;
use super::schema::MATERIAL;
use crate::diag::codes;
use crate::diag::{Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::Block;

/// `material { }` → material.
pub fn material(p: &Params, name: Option<String>, span: Span, diags: &mut Diagnostics) -> Material {
    let mut r = Reader { p, diags };
    let diffuse_given = p.given("diffuse");
    let kind = kind(&mut r);
    let mut m = Material {
        name,
        kind,
        multiscatter: r.boolean("multiscatter", true),
        diffuse: r.color("diffuse", if diffuse_given { [0.5; 3] } else { [0.0; 3] }),
        reflection: r.color("reflection", [0.0; 3]),
        textures: textures(p),
        bump_height: r.num_in("bump_height", -1e6, 1e6, false, 0.01),
        gloss: r.num_in("gloss", 0.0, 1.0, false, 0.0),
        transmission: r.num_in("transmission", 0.0, 1.0, false, 0.0),
        ior: r.num_in("ior", 1.0, 10.0, false, 1.5),
        ior_outside: r.num_in("ior_outside", 1.0, 10.0, false, 1.0),
        roughness: roughness(&mut r),
        absorption: r.color("absorption", [0.0; 3]),
        scattering: [0.0; 3],
        anisotropy: 0.0,
        emission: r.color("emission", [0.0; 3]),
        two_sided: r.boolean("two_sided", false),
        opacity: r.num_in("opacity", 0.0, 1.0, false, 1.0),
        opacity_cutoff: (p.given("opacity_cutoff"))
            .then(|| r.num_in("opacity_cutoff", 0.0, 1.0, false, 0.5)),
        vertex_color: r.boolean("vertex_color", false),
        normal_scale: r.num_in("normal_scale", -100.0, 100.0, false, 1.0),
        span,
    };
    // A textured parameter stands for its brightest value in the checks
    // below, in the lobes' weights and in a light's power (an image's
    // brightest texel is known only once it is read: 1 until then).
    for (input, t) in &m.textures {
        let bright = match t.kind {
            TextureKind::Image { factor, .. } => factor,
            _ => t.brightest(),
        };
        let number = bright.iter().cloned().fold(0.0, f64::max).min(1.0);
        match input {
            TextureInput::Diffuse => m.diffuse = bright,
            TextureInput::Reflection => m.reflection = bright,
            TextureInput::Absorption => m.absorption = bright,
            TextureInput::Emission => m.emission = bright,
            TextureInput::Gloss => m.gloss = number,
            TextureInput::Transmission => m.transmission = number,
            TextureInput::BaseColor => m.diffuse = bright,
            TextureInput::Metallic => {
                if let MaterialKind::Principled(pp) = &mut m.kind {
                    pp.metallic = number;
                }
            }
            TextureInput::Opacity => m.opacity = number,
            TextureInput::NormalMap | TextureInput::Bump => {}
        }
    }
    opacity_checks(p, &mut m, diags);
    medium_checks(p, &mut m, diags);
    if let Some((_, s)) = p.get("normal_scale") {
        if !p.given("normal_map") {
            let help = "give `normal_map` a texture, e.g. `normal_map image { file \"bricks_normal.png\" }`";
            diags.push(no_effect_without("normal_scale", "normal_map", *s, help));
        }
    }
    if let Some((_, s)) = p.get("bump_height") {
        if !p.given("bump") {
            let help = "give `bump` a texture, e.g. `bump noise { scale 0.05 }`";
            diags.push(no_effect_without("bump_height", "bump", *s, help));
        }
    }
    if m.kind == MaterialKind::Mix {
        mix_checks(p, &mut m, diags);
    } else {
        model_checks(p, &mut m, diags);
    }
    if matches!(m.kind, MaterialKind::Principled(_)) {
        principled_checks(&mut Reader { p, diags }, &mut m);
    } else {
        for name in PRINCIPLED_ONLY {
            if let Some((_, s)) = p.get(name) {
                let help = "it is a parameter of `type principled`";
                diags.push(no_effect(name, model_name(&m.kind), *s, help));
            }
        }
        m.textures.retain(|(input, _)| {
            !matches!(input, TextureInput::BaseColor | TextureInput::Metallic)
        });
    }
    m
}

/// Whether the model has no inside whatever its parameters (a metal, a
/// plastic, a thin pane): it ignores a medium as it ignores its other
/// unused words.
fn opaque_model(kind: &MaterialKind) -> bool {
    matches!(
        kind,
        MaterialKind::Conductor { .. } | MaterialKind::Plastic | MaterialKind::ThinDielectric
    )
}

/// The medium inside: read when the material has an inside (it refracts,
/// or is `type none`), reported as having no effect otherwise.
fn medium_checks(p: &Params, m: &mut Material, diags: &mut Diagnostics) {
    let inside =
        m.transmission > 0.0 || matches!(m.kind, MaterialKind::Dielectric | MaterialKind::None);
    if !inside && !opaque_model(&m.kind) {
        if !p.given_nonzero("transmission") {
            super::medium::warn_without_inside(p, diags);
        }
        return;
    }
    let medium = super::medium::read(p, m.absorption, diags);
    m.absorption = medium.absorption;
    m.scattering = medium.scattering;
    m.anisotropy = medium.anisotropy;
}

/// `opacity` and `opacity_cutoff`: a cutout cannot emit (light sampling
/// would choose points where the surface is not), and a cutoff needs an
/// opacity to cut.
fn opacity_checks(p: &Params, m: &mut Material, diags: &mut Diagnostics) {
    let textured = m.textures.iter().any(|(i, _)| *i == TextureInput::Opacity);
    if let Some((_, s)) = p.get("opacity_cutoff") {
        if !p.given("opacity") {
            let help = "give `opacity` a number or a texture, e.g. an image's alpha: `opacity image { file \"leaf.png\" channel a }`";
            diags.push(no_effect_without("opacity_cutoff", "opacity", *s, help));
            m.opacity_cutoff = None;
        }
    }
    let Some((_, s)) = p.get("opacity") else {
        return;
    };
    if m.emission.iter().any(|&c| c > 0.0) && (textured || m.opacity < 1.0) {
        diags.push(
            Diagnostic::error(
                codes::CONFLICTING_PARAMS,
                "an emitting surface cannot be cut out",
                *s,
            )
            .with_label("`opacity` on a material with `emission`")
            .with_help("lights are sampled over their whole surface; give the light its shape as geometry, or drop `opacity`"),
        );
        m.opacity = 1.0;
        m.textures.retain(|(i, _)| *i != TextureInput::Opacity);
    }
}

/// `type principled`: its base colour (held as `diffuse`), its roughness
/// (`gloss`, or `roughness` as one number, default 0.5 as Mitsuba's) and
/// its index (`specular` or `ior`, not both).
fn principled_checks(r: &mut Reader, m: &mut Material) {
    let p = r.p;
    let textured_base = m
        .textures
        .iter()
        .any(|(i, _)| *i == TextureInput::BaseColor);
    if !textured_base {
        m.diffuse = r.color("base_color", [0.5; 3]);
    }
    let textured_gloss = m.textures.iter().any(|(i, _)| *i == TextureInput::Gloss);
    match p.get("roughness") {
        Some((Val::Vector(v), s)) if v.len() == 2 => {
            if p.given("gloss") {
                r.diags.push(
                    Diagnostic::error(
                        codes::CONFLICTING_PARAMS,
                        "`roughness` and `gloss` both roughen the material",
                        *s,
                    )
                    .with_label("on `type principled` both are its roughness (α = roughness²)")
                    .with_help("keep one of them"),
                );
            } else if v[0] != v[1] {
                r.diags.push(
                    Diagnostic::error(
                        codes::OUT_OF_RANGE,
                        "`type principled` takes one roughness",
                        *s,
                    )
                    .with_label("two values along u and v")
                    .with_help(
                        "give one `roughness` and stretch the highlight with `anisotropic` (0..1)",
                    ),
                );
            } else if (0.0..=1.0).contains(&v[0]) {
                m.gloss = v[0];
            }
        }
        _ if !p.given("gloss") && !textured_gloss => m.gloss = 0.5,
        _ => {}
    }
    m.roughness = None;
    if let (Some((_, s)), true) = (p.get("specular"), p.given("ior")) {
        r.diags.push(
            Diagnostic::error(
                codes::CONFLICTING_PARAMS,
                "`specular` and `ior` both give the principled material's index",
                *s,
            )
            .with_label("specular s is an index of 2 / (1 − √(0.08 s)) − 1")
            .with_help("keep `specular` (0.5 is glass's 1.5) or `ior`"),
        );
    }
}

/// The help for a reflectance `name` of colour `c` above 1: whole numbers
/// up to 255 (one of 10 or more) are another program's 0–255 scale,
/// given divided.
fn above_one_help(name: &str, c: Rgb) -> String {
    // `rgb 2` is more likely meant as it is than as 2/255.
    let bytes = c
        .iter()
        .all(|x| x.fract() == 0.0 && (0.0..=255.0).contains(x))
        && c.iter().any(|&x| x >= 10.0);
    if !bytes {
        return format!("keep every component of `{name}` at most 1");
    }
    let scaled = c.map(|x| crate::check::eval::shown((x / 255.0 * 1000.0).round() / 1000.0));
    format!(
        "colours go from 0 to 1, not to 255: divided by 255 this is `{name} rgb <{}>`",
        scaled.join(", ")
    )
}

/// The checks of the paper's mix of lobes: its default, its energy, and
/// the parameters that need another lobe.
fn mix_checks(p: &Params, m: &mut Material, diags: &mut Diagnostics) {
    // A material with no lobe at all is the default grey diffuse (unless it only emits).
    let any_lobe = ["diffuse", "reflection", "transmission", "emission"]
        .iter()
        .any(|n| p.given(n));
    if !any_lobe {
        m.diffuse = [0.5; 3];
    }
    if let Some((_, s)) = p.get("diffuse") {
        if m.diffuse.iter().any(|c| *c > 1.0) {
            diags.push(
                Diagnostic::warning(codes::ENERGY_GAIN, "diffuse albedo above 1", *s)
                    .with_label("a surface cannot reflect more light than it receives")
                    .with_help(above_one_help("diffuse", m.diffuse)),
            );
        }
    }
    let max = |c: Rgb| c.iter().cloned().fold(0.0, f64::max);
    let total = max(m.diffuse) + max(m.reflection) + m.transmission;
    if total > 1.0 + 1e-9
        && p.given("diffuse") as u8 + p.given("reflection") as u8 + p.given("transmission") as u8
            > 1
    {
        diags.push(
            Diagnostic::warning(
                codes::ENERGY_GAIN,
                format!("the lobes of this material add up to {total:.3}, more than 1"),
                p.head,
            )
            .with_label("diffuse + reflection + transmission > 1")
            .with_help("ptsc scales the lobes down to sum to 1; lower them to silence this"),
        );
    }
    if let Some((_, s)) = p.get("gloss") {
        if max(m.reflection) == 0.0 && !p.given_nonzero("reflection") {
            diags.push(
                Diagnostic::warning(
                    codes::NO_EFFECT,
                    "`gloss` has no effect without `reflection`",
                    *s,
                )
                .with_label("ignored")
                .with_help("add `reflection rgb 1` to make the surface a glossy reflector"),
            );
        }
    }
    if let Some((_, s)) = p.get("absorption") {
        if m.transmission == 0.0 && !p.given("density") && !p.given_nonzero("transmission") {
            diags.push(
                Diagnostic::warning(
                    codes::NO_EFFECT,
                    "`absorption` has no effect without `transmission`",
                    *s,
                )
                .with_label("ignored")
                .with_help("absorption acts inside transparent objects: add `transmission 1`, or `type none` for a medium without a surface"),
            );
        }
    }
    if let Some((_, s)) = p.get("ior") {
        if m.transmission == 0.0 && !p.given_nonzero("transmission") {
            diags.push(no_effect_without(
                "ior",
                "transmission",
                *s,
                "the mix's `reflection` is a mirror without Fresnel: give glass `transmission 1`; for a coat that reflects by `ior`, `type plastic` (or `type dielectric` for clear glass)",
            ));
        }
    }
    if let Some((_, s)) = p.get("ior_outside") {
        if m.transmission == 0.0 && !p.given_nonzero("transmission") {
            diags.push(no_effect(
                "ior_outside",
                "a material without `transmission`",
                *s,
                "`ior_outside` is the index of the medium around glass: add `transmission 1`, or `type dielectric`",
            ));
        }
    }
    if let Some((_, s)) = p.get("roughness") {
        diags.push(no_effect(
            "roughness",
            model_name(&MaterialKind::Mix),
            *s,
            "`roughness <u, v>` roughens a metal (`type conductor`); here, roughen the reflection with `gloss`",
        ));
        m.roughness = None;
    }
    // (After an unknown `type`, the words of the type meant are no news.)
    for name in ["preset", "eta", "k"] {
        if let Some((_, s)) = p.get(name).filter(|_| !p.given("type")) {
            diags.push(no_effect(
                name,
                model_name(&MaterialKind::Mix),
                *s,
                "write `type conductor` to make a metal",
            ));
        }
    }
}

/// A metal's `roughness`: GGX α along ∂p/∂u and ∂p/∂v, each in [0, 1]
/// (0 for both: a mirror).
fn roughness(r: &mut Reader) -> Option<[f64; 2]> {
    let (Val::Vector(v), s) = r.p.get("roughness")? else {
        return None;
    };
    if v.len() != 2 || v.iter().any(|a| !(0.0..=1.0).contains(a)) {
        r.diags.push(
            Diagnostic::error(
                codes::OUT_OF_RANGE,
                "`roughness` must be between 0 and 1",
                *s,
            )
            .with_label("GGX α along u and v")
            .with_help("give one α (`roughness 0.2`) or one along u and one along v (`roughness <0.05, 0.4>`), each from 0 (smooth) to 1"),
        );
        return None;
    }
    Some([v[0], v[1]])
}

/// The scattering model a material's `type` names; a conductor's
/// constants from its `preset` or its `eta` and `k`.
fn kind(r: &mut Reader) -> MaterialKind {
    let p = r.p;
    // A word checked against `MaterialType::WORDS` by the row's `Ty::Word`.
    let model = match p.get("type") {
        Some((Val::Word(w), _)) => MaterialType::from_name(w).unwrap_or(MaterialType::Mix),
        _ => MaterialType::Mix,
    };
    match model {
        MaterialType::Conductor => {
            let preset = match p.get("preset") {
                Some((Val::Word(w), s)) => Some((w.as_str(), *s)),
                _ => None,
            };
            let (eta, k) = (p.given("eta"), p.given("k"));
            if let (Some((_, s)), true) = (preset, eta || k) {
                let other = if eta { "eta" } else { "k" };
                r.diags.push(
                    Diagnostic::error(
                        codes::CONFLICTING_PARAMS,
                        format!("`preset` and `{other}` both give the metal's constants"),
                        s,
                    )
                    .with_label("a preset sets `eta` and `k`")
                    .with_help("keep the preset, or remove it and give both `eta` and `k`"),
                );
            }
            if let Some((name, _)) = preset {
                // A word checked against `Metal::WORDS` (the row's `Ty::Word`).
                let name = crate::material::conductor::Metal::from_name(name);
                return MaterialKind::Conductor {
                    preset: name,
                    eta: [1.0; 3],
                    k: [0.0; 3],
                };
            }
            if !(p.meant("preset") || eta && k) {
                let missing = if eta { "k" } else { "eta" };
                r.diags.push(
                    Diagnostic::error(
                        codes::MISSING_PARAM,
                        format!("`{}` needs a `preset` or both `eta` and `k`", p.what),
                        p.head,
                    )
                    .with_label(format!("a conductor without `preset` or `{missing}`"))
                    .with_help("add `preset gold` (or silver, copper, aluminium, chromium)"),
                );
            }
            MaterialKind::Conductor {
                preset: None,
                eta: r.color("eta", [1.0; 3]),
                k: r.color("k", [0.0; 3]),
            }
        }
        MaterialType::Plastic => MaterialKind::Plastic,
        MaterialType::Dielectric => MaterialKind::Dielectric,
        MaterialType::ThinDielectric => MaterialKind::ThinDielectric,
        MaterialType::Principled => {
            let mut unit = |name: &str| r.num_in(name, 0.0, 1.0, false, 0.0);
            MaterialKind::Principled(PrincipledParams {
                metallic: unit("metallic"),
                specular: p.given("specular").then(|| unit("specular")),
                specular_tint: unit("specular_tint"),
                anisotropic: unit("anisotropic"),
                sheen: unit("sheen"),
                sheen_tint: unit("sheen_tint"),
                clearcoat: unit("clearcoat"),
                clearcoat_roughness: unit("clearcoat_roughness"),
            })
        }
        MaterialType::Mix => MaterialKind::Mix,
        MaterialType::None => MaterialKind::None,
    }
}

/// A warning for a parameter that a material's model ignores.
fn no_effect(name: &str, model: &str, span: Span, help: &str) -> Diagnostic {
    Diagnostic::warning(
        codes::NO_EFFECT,
        format!("`{name}` has no effect on {model}"),
        span,
    )
    .with_label("ignored")
    .with_help(help.to_string())
}

/// The warning for `name`, at `span`, given without `needs`.
fn no_effect_without(name: &str, needs: &str, span: Span, help: &str) -> Diagnostic {
    Diagnostic::warning(
        codes::NO_EFFECT,
        format!("`{name}` has no effect without `{needs}`"),
        span,
    )
    .with_label("ignored")
    .with_help(help.to_string())
}

/// What a material model is called in diagnostics.
fn model_name(kind: &MaterialKind) -> &'static str {
    match kind {
        MaterialKind::Mix => "the mix of lobes",
        MaterialKind::Conductor { .. } => "a conductor",
        MaterialKind::Plastic => "a plastic",
        MaterialKind::Dielectric => "a dielectric",
        MaterialKind::ThinDielectric => "a thin dielectric",
        MaterialKind::Principled(_) => "a principled material",
        MaterialKind::None => "a `type none` boundary",
    }
}

/// The defaults of the models other than the mix, and the parameters they
/// ignore.
fn model_checks(p: &Params, m: &mut Material, diags: &mut Diagnostics) {
    let model = model_name(&m.kind);
    let (ignored, help): (&[&str], &str) = match m.kind {
        MaterialKind::Conductor { .. } => (
            &["diffuse", "transmission", "absorption", "ior"],
            "a metal is its `preset` (or `eta` and `k`), tinted by `reflection` and roughened by `gloss`",
        ),
        MaterialKind::Plastic => (
            &["transmission", "absorption", "preset", "eta", "k", "multiscatter", "roughness"],
            "a plastic is its `diffuse` base under a coat of index `ior`, roughened by `gloss`",
        ),
        MaterialKind::Dielectric => (
            &["diffuse", "reflection", "transmission", "preset", "eta", "k", "multiscatter", "roughness"],
            "glass is its `ior`, `gloss` (frosting) and `absorption` inside",
        ),
        MaterialKind::Mix => return,
        MaterialKind::Principled(_) => (
            &["diffuse", "reflection", "preset", "eta", "k", "multiscatter"],
            "a principled material is its `base_color`, `metallic`, `gloss` (or `roughness`), `specular` (or `ior`), `transmission`, `sheen` and `clearcoat`",
        ),
        MaterialKind::ThinDielectric => (
            &[
                "diffuse",
                "reflection",
                "transmission",
                "absorption",
                "gloss",
                "preset",
                "eta",
                "k",
                "multiscatter",
                "roughness",
            ],
            "a thin pane is its `ior` (and `ior_outside`) alone",
        ),
        MaterialKind::None => (
            &[
                "diffuse",
                "reflection",
                "transmission",
                "gloss",
                "ior",
                "ior_outside",
                "preset",
                "eta",
                "k",
                "multiscatter",
                "roughness",
                "emission",
                "two_sided",
                "normal_map",
                "bump",
                "opacity",
                "opacity_cutoff",
            ],
            "a `type none` boundary has no surface: it is the medium inside (`absorption`, `scattering` or `density`, `anisotropy`)",
        ),
    };
    // A model without an inside ignores the medium words too.
    let medium_words = opaque_model(&m.kind).then_some(MEDIUM_WORDS);
    let ignored: Vec<&str> = (ignored.iter().copied())
        .chain(medium_words.into_iter().flatten())
        .collect();
    let ignored = &ignored[..];
    for &name in ignored {
        if let Some((_, s)) = p.get(name) {
            diags.push(no_effect(name, model, *s, help));
        }
    }
    options_checks(p, m, ignored, diags);
    // A metal's or a coat's tint is white unless given; a plastic's base
    // is grey unless given.
    if !p.given("reflection") {
        m.reflection = [1.0; 3];
    }
    if m.kind == MaterialKind::Plastic && !p.given("diffuse") {
        m.diffuse = [0.5; 3];
    }
    for name in ["diffuse", "reflection"] {
        if let Some((_, s)) = p.get(name) {
            let c = if name == "diffuse" {
                m.diffuse
            } else {
                m.reflection
            };
            if c.iter().any(|x| *x > 1.0) && !matches!(m.kind, MaterialKind::Dielectric) {
                diags.push(
                    Diagnostic::warning(codes::ENERGY_GAIN, format!("`{name}` above 1"), *s)
                        .with_label("a surface cannot reflect more light than it receives")
                        .with_help(above_one_help(name, c)),
                );
            }
        }
    }
    // A parameter the model ignores plays no part: neither its value nor
    // its texture.
    for &name in ignored {
        match name {
            "diffuse" => m.diffuse = [0.0; 3],
            "reflection" => m.reflection = [0.0; 3],
            "transmission" => m.transmission = 0.0,
            "absorption" => m.absorption = [0.0; 3],
            "scattering" => m.scattering = [0.0; 3],
            "emission" => m.emission = [0.0; 3],
            "opacity" => m.opacity = 1.0,
            "opacity_cutoff" => m.opacity_cutoff = None,
            "gloss" => m.gloss = 0.0,
            _ => {}
        }
    }
    m.textures.retain(|(input, _)| {
        !(TextureInput::ALL.iter()).any(|(name, i)| i == input && ignored.contains(name))
    });
}

/// The checks of `roughness` and `ior_outside` beside a model's
/// parameters (`ignored`: those it does not use).
fn options_checks(p: &Params, m: &mut Material, ignored: &[&str], diags: &mut Diagnostics) {
    if ignored.contains(&"roughness") {
        m.roughness = None;
    }
    let principled = matches!(m.kind, MaterialKind::Principled(_));
    if let (Some((_, s)), true) = (p.get("roughness"), p.given("gloss")) {
        if m.roughness.is_some() && !principled {
            diags.push(
                Diagnostic::error(
                    codes::CONFLICTING_PARAMS,
                    "`roughness` and `gloss` both roughen the metal",
                    *s,
                )
                .with_label("GGX α, as Mitsuba's `alpha_u` and `alpha_v`")
                .with_help("keep `gloss` (α = gloss²) or `roughness` (α itself, or `<α along u, α along v>`)"),
            );
        }
    }
    if m.kind == MaterialKind::Plastic && m.ior < m.ior_outside {
        if let Some((_, s)) = p.get("ior_outside") {
            diags.push(
                Diagnostic::error(
                    codes::OUT_OF_RANGE,
                    "a plastic's coat is less dense than the medium outside it",
                    *s,
                )
                .with_label(format!(
                    "`ior` {} is below `ior_outside` {}",
                    m.ior, m.ior_outside
                ))
                .with_help("give the coat an `ior` at least `ior_outside`"),
            );
        }
    }
}

/// A material's values written without names: a colour alone is
/// POV-Ray's `pigment { rgb … }`, ptsc's `diffuse`.
pub(super) const POSITIONAL: Option<super::schema::Positional> = Some((&["diffuse"], ""));

/// A material block's parameters (inline or named), textures and all.
pub fn collect(
    what: impl Into<std::borrow::Cow<'static, str>>,
    head: Span,
    block: &Block,
    checking: (&mut Env, &mut Diagnostics),
) -> Params {
    let texture: CheckTexture = super::texture::check_texture;
    let order = (&[MATERIAL][..], POSITIONAL);
    Params::collect_ordered(what, head, block, order, checking, Some(texture))
}
