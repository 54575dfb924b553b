//! Textures given to parameters (`diffuse checker { … }`) or declared by
//! name (`texture oak wood { … }`): the kind is looked up, the block
//! checked against the kind's schema, its colour map and its transforms.

use super::eval::{eval, Env, Value};
use super::params::{Params, Val};
use super::reader::Reader;
use super::scene::{ColorSpace, Rgb, Texture, TextureKind, TextureSpace};
use super::schema::{
    ParamSpec, Positional, BANDS, CHECKER, COLOR_MAP, GRADIENT, IMAGE, NOISE, TEXTURE_KINDS,
    TEXTURE_TRANSFORMS, UNBANDED,
};
use crate::diag::{codes, did_you_mean, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::{Block, Entry, Ident};
use crate::texture::image::Wrap;
use crate::texture::noise::{NoiseKind, NoiseParams};

/// The parameter rows of the texture kind `name` (its own first, then its
/// bands or colour map and its transforms), `None` for a name that is not
/// a texture: what the checker reads a texture's block against, and what
/// an editor offers inside one.
pub fn texture_schemas(name: &str) -> Option<&'static [&'static [ParamSpec]]> {
    Some(match name {
        "checker" => &[CHECKER, COLOR_MAP, TEXTURE_TRANSFORMS],
        "image" => &[IMAGE, TEXTURE_TRANSFORMS],
        "marble" | "wood" => &[NOISE, BANDS, COLOR_MAP, TEXTURE_TRANSFORMS],
        "noise" | "turbulence" => &[NOISE, UNBANDED, COLOR_MAP, TEXTURE_TRANSFORMS],
        "gradient" | "stripes" => &[GRADIENT, COLOR_MAP, TEXTURE_TRANSFORMS],
        _ => return None,
    })
}

/// Where POV-Ray's checker and ptsc's differ: the cells' space.
const CHECKER_SPACE: &str = "POV-Ray's cells are unit cubes of the object's own space: add `space object`; ptsc's default reads the surface's texture coordinates";

/// POV-Ray's order of the texture `name`'s values written without names:
/// a checker's two colours (`checker rgb 1, rgb 0`; POV-Ray's first colour
/// fills the cell at the origin, as ptsc's `even`).
pub(super) fn povray_order(name: &str) -> Option<Positional> {
    match name {
        "checker" => Some((&["even", "odd"], CHECKER_SPACE)),
        _ => None,
    }
}

/// The error for the texture kind `kind` that is not one: POV-Ray's
/// word, a did-you-mean, or the textures there are.
pub(super) fn unknown_texture(kind: &Ident) -> Diagnostic {
    let povray = crate::syntax::povray::hint(&kind.name);
    let help = match (
        povray,
        did_you_mean(&kind.name, TEXTURE_KINDS.iter().copied()),
    ) {
        (Some(hint), _) => hint.to_string(),
        (None, Some(s)) => format!("did you mean `{s}`?"),
        (None, None) => format!("the textures are: {}", TEXTURE_KINDS.join(", ")),
    };
    Diagnostic::error(
        codes::UNKNOWN_TEXTURE,
        format!("unknown texture `{}`", kind.name),
        kind.span,
    )
    .with_label("not a texture")
    .with_help(help)
}

/// The texture `kind { block }` written at `span`; `None` after reporting
/// why not.
pub fn check_texture(
    kind: &Ident,
    block: &Block,
    span: Span,
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<Texture> {
    let Some(schemas) = texture_schemas(&kind.name) else {
        diags.push(unknown_texture(kind));
        return None;
    };
    let (schema, is_image) = (schemas[0], kind.name == "image");
    let noise = NoiseKind::from_name(&kind.name);
    let order = (schemas, povray_order(&kind.name));
    let p = Params::collect_ordered(
        kind.name.clone(),
        kind.span,
        block,
        order,
        (env, diags),
        None,
    );
    let transform = super::objects::transform(&p, diags);
    let word = |name: &str| match p.get(name) {
        Some((Val::Word(w), _)) => Some(w.clone()),
        _ => None,
    };
    let solid = schema.as_ptr() != CHECKER.as_ptr() && !is_image;
    // A word checked against `TextureSpace::WORDS` by the row's `Ty::Word`.
    let space = match word("space").as_deref().and_then(TextureSpace::from_name) {
        Some(space) => space,
        // Solid patterns live in the object by default, the others on the surface.
        None if solid => TextureSpace::Object,
        None => TextureSpace::Uv,
    };
    let texture_kind = match kind.name.as_str() {
        "image" => {
            let (file, path_span) = match p.require("file", IMAGE, diags)? {
                (Val::Str(f), s) => (f.clone(), *s),
                _ => return None,
            };
            TextureKind::Image {
                path: (&file).into(),
                named: file,
                path_span,
                // A word checked against `Wrap::WORDS` (the row's `Ty::Word`).
                wrap: word("wrap")
                    .and_then(|w| Wrap::from_name(&w))
                    .unwrap_or(Wrap::Repeat),
                color_space: word("color_space").and_then(|w| ColorSpace::from_name(&w)),
                resolved: false,
                factor: [1.0; 3],
                // A word checked against `Channel::WORDS` (the row's `Ty::Word`).
                channel: word("channel")
                    .and_then(|w| crate::texture::image::Channel::from_name(&w)),
                origin: None,
            }
        }
        "checker" => TextureKind::Checker,
        "gradient" => TextureKind::Gradient,
        "stripes" => TextureKind::Stripes,
        _ => {
            let kind = noise?;
            TextureKind::Noise {
                kind,
                params: noise_params(kind, &mut Reader { p: &p, diags }),
            }
        }
    };
    let (low, high) = if schema.as_ptr() == CHECKER.as_ptr() {
        ("even", "odd")
    } else {
        ("low", "high")
    };
    let stops = color_stops(block, env, diags);
    let colors = match stops {
        Some((stops, first)) => {
            for name in [low, high] {
                if let Some((_, s)) = p.get(name) {
                    diags.push(
                        Diagnostic::error(
                            codes::DUPLICATE_PARAM,
                            format!("`{name}` and `stop` together in `{}`", kind.name),
                            *s,
                        )
                        .with_label("the colour stops give the colours")
                        .with_secondary(first, "first stop here")
                        .with_help(format!(
                            "remove `{name}`, or the stops; `{low}` and `{high}` are the stops at 0 and 1"
                        )),
                    );
                }
            }
            stops
        }
        None => {
            let mut r = Reader { p: &p, diags };
            let (d0, d1) = if is_image || low == "even" {
                ([1.0; 3], [0.0; 3])
            } else {
                ([0.0; 3], [1.0; 3])
            };
            vec![(0.0, r.color(low, d0)), (1.0, r.color(high, d1))]
        }
    };
    Some(Texture {
        kind: texture_kind,
        colors,
        space,
        transform,
        span,
    })
}

/// The octaves and bands of a noise texture, each in its range (ranges
/// and POV-Ray's differences in docs/language.md). The defaults are
/// POV-Ray's but for marble's and wood's `turbulence`, which keep the
/// amounts they always had.
fn noise_params(kind: NoiseKind, r: &mut Reader) -> NoiseParams {
    let d = NoiseParams::defaults(kind);
    let mut num = |name, lo, hi, open_lo, default: f32| {
        r.num_in(name, lo, hi, open_lo, default as f64) as f32
    };
    NoiseParams {
        octaves: num("octaves", 1.0, 16.0, false, d.octaves as f32) as u32,
        omega: num("omega", 0.0, 1.0, true, d.omega),
        lambda: num("lambda", 1.0, 10.0, true, d.lambda),
        turbulence: num("turbulence", 0.0, 100.0, false, d.turbulence),
        frequency: num("frequency", 0.0, 1000.0, true, d.frequency),
        phase: num("phase", 0.0, 1.0, false, d.phase),
    }
}

/// The colour stops of a texture's block, with the first one's span;
/// `None` when it has none. Each position must lie in [0, 1] and follow
/// the one before; each colour be a colour ≥ 0.
fn color_stops(
    block: &Block,
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<(Vec<(f64, Rgb)>, Span)> {
    let mut stops = Vec::new();
    let mut first = None;
    let mut previous: Option<(f64, Span)> = None;
    for entry in &block.entries {
        let Entry::Stop {
            position,
            color,
            span,
            ..
        } = entry
        else {
            continue;
        };
        first.get_or_insert(*span);
        let at = eval(position, env, diags);
        let c = eval(color, env, diags);
        let at = match at {
            Some(Value::Num(x)) if (0.0..=1.0).contains(&x) => x,
            Some(Value::Num(x)) => {
                diags.push(
                    Diagnostic::error(
                        codes::OUT_OF_RANGE,
                        format!("a colour stop at {x}, outside [0, 1]"),
                        position.span,
                    )
                    .with_label("must be from 0 to 1")
                    .with_help("stops place colours along the pattern's values, 0 to 1"),
                );
                continue;
            }
            Some(other) => {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!("a stop's position is a number, found {}", other.type_name()),
                        position.span,
                    )
                    .with_label("not a number")
                    .with_help("write `stop 0.5 rgb <1, 0, 0>`"),
                );
                continue;
            }
            None => continue,
        };
        let c = match c {
            Some(Value::Color(c)) if c.iter().all(|&x| (0.0..=1e9).contains(&x)) => c,
            Some(Value::Color(_)) => {
                diags.push(
                    Diagnostic::error(
                        codes::OUT_OF_RANGE,
                        "a colour stop's colour must have components from 0 to 1e9",
                        color.span,
                    )
                    .with_label("out of range")
                    .with_help("colour components are ≥ 0"),
                );
                continue;
            }
            Some(other) => {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!("a stop's colour is a colour, found {}", other.type_name()),
                        color.span,
                    )
                    .with_label("not a colour")
                    .with_help("write `stop 0.5 rgb <1, 0, 0>`"),
                );
                continue;
            }
            None => continue,
        };
        if let Some((before, before_span)) = previous {
            if at < before {
                diags.push(
                    Diagnostic::error(
                        codes::UNORDERED_STOPS,
                        format!("a colour stop at {at} after one at {before}"),
                        position.span,
                    )
                    .with_label("comes before the previous stop")
                    .with_secondary(before_span, "the previous stop")
                    .with_help("write the stops in order of position, from 0 to 1"),
                );
                continue;
            }
        }
        previous = Some((at, position.span));
        stops.push((at, c));
    }
    let first = first?;
    if stops.is_empty() {
        // Every stop had an error (reported): the texture keeps one colour.
        stops.push((0.0, [0.0; 3]));
    }
    Some((stops, first))
}
