//! Textures given to parameters (`diffuse checker { … }`): the kind is
//! looked up, the block checked against the kind's schema and the
//! texture's transforms.

use super::blocks::Reader;
use super::eval::Env;
use super::params::{Params, Val, CHECKER, IMAGE, NOISE, TEXTURE_KINDS, TEXTURE_TRANSFORMS};
use super::scene::{Texture, TextureKind, TextureSpace};
use crate::diag::{codes, did_you_mean, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::{Block, Ident};

/// The texture `kind { block }` written at `span`; `None` after reporting
/// why not.
pub fn check_texture(
    kind: &Ident,
    block: &Block,
    span: Span,
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<Texture> {
    let schema: &'static [super::params::ParamSpec] = match kind.name.as_str() {
        "checker" => CHECKER,
        "image" => IMAGE,
        "noise" | "turbulence" | "marble" | "wood" => NOISE,
        _ => {
            let help = match did_you_mean(&kind.name, TEXTURE_KINDS.iter().copied()) {
                Some(s) => format!("did you mean `{s}`?"),
                None => format!("the textures are: {}", TEXTURE_KINDS.join(", ")),
            };
            diags.push(
                Diagnostic::error(
                    codes::UNKNOWN_TEXTURE,
                    format!("unknown texture `{}`", kind.name),
                    kind.span,
                )
                .with_label("not a texture")
                .with_help(help),
            );
            return None;
        }
    };
    let p = Params::collect(
        kind.name.clone(),
        kind.span,
        block,
        &[schema, TEXTURE_TRANSFORMS],
        env,
        diags,
    );
    let transform = super::objects::transform(&p, diags);
    let word = |name: &str| match p.get(name) {
        Some((Val::Word(w), _)) => Some(w.clone()),
        _ => None,
    };
    let solid = schema.as_ptr() == NOISE.as_ptr();
    let space = match word("space").as_deref() {
        Some("object") => TextureSpace::Object,
        Some("world") => TextureSpace::World,
        Some(_) => TextureSpace::Uv,
        // Solid patterns live in the object by default, the others on the surface.
        None if solid => TextureSpace::Object,
        None => TextureSpace::Uv,
    };
    let texture_kind = if kind.name == "image" {
        let (file, path_span) = match p.require("file", IMAGE, diags)? {
            (Val::Str(f), s) => (f.clone(), *s),
            _ => return None,
        };
        TextureKind::Image {
            path: file.into(),
            path_span,
            wrap: word("wrap").unwrap_or_else(|| "repeat".into()),
        }
    } else if solid {
        let mut r = Reader { p: &p, diags };
        let octaves = r.num_in("octaves", 1.0, 16.0, false, 6.0) as u32;
        TextureKind::Noise {
            pattern: kind.name.clone(),
            octaves,
        }
    } else {
        TextureKind::Checker
    };
    let mut r = Reader { p: &p, diags };
    let (even, odd) = if solid {
        (r.color("low", [0.0; 3]), r.color("high", [1.0; 3]))
    } else {
        (r.color("even", [1.0; 3]), r.color("odd", [0.0; 3]))
    };
    Some(Texture {
        kind: texture_kind,
        colors: [even, odd],
        space,
        transform,
        span,
    })
}
