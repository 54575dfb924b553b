//! Textures given to parameters (`diffuse checker { … }`): the kind is
//! looked up, the block checked against the kind's schema and the
//! texture's transforms.

use super::blocks::Reader;
use super::eval::Env;
use super::params::{Params, Val, CHECKER, TEXTURE_KINDS, TEXTURE_TRANSFORMS};
use super::scene::{Texture, TextureSpace};
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
    if kind.name != "checker" {
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
    let p = Params::collect(
        "checker",
        kind.span,
        block,
        &[CHECKER, TEXTURE_TRANSFORMS],
        env,
        diags,
    );
    let transform = super::objects::transform(&p, diags);
    let mut r = Reader { p: &p, diags };
    let even = r.color("even", [1.0; 3]);
    let odd = r.color("odd", [0.0; 3]);
    let space = match p.get("space") {
        Some((Val::Word(w), _)) if w == "object" => TextureSpace::Object,
        Some((Val::Word(w), _)) if w == "world" => TextureSpace::World,
        _ => TextureSpace::Uv,
    };
    Some(Texture {
        colors: [even, odd],
        space,
        transform,
        span,
    })
}
