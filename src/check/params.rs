//! Per-block parameter schemas and the collector that checks a block's
//! entries against one: unknown, duplicate and ill-typed parameters.

use super::domain::Quantity;
use super::eval::{eval, Env, Value};
use crate::diag::codes;
use crate::diag::{did_you_mean, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::{Block, Entry, ExprKind};
use std::borrow::Cow;
use Quantity::{Direction, Magnitude, Radiance, Size};

/// The type a parameter expects.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Ty {
    /// Any finite number.
    Num,
    /// A whole number.
    Int,
    /// `<a, b>`
    Vec2,
    /// `<x, y, z>`
    Vec3,
    /// `rgb …`
    Color,
    /// `"…"`
    Str,
    /// `true` / `false`
    Bool,
    /// One of a fixed set of words.
    Word(&'static [&'static str]),
    /// A number (uniform) or a vector of 3.
    NumOrVec3,
    /// A number (the same for both) or a vector of 2.
    NumOrVec2,
    /// 12 or 16 numbers, row-major.
    Matrix,
    /// Only a texture (`kind { … }` or a texture's name).
    Texture,
}

impl Ty {
    /// The type's name in messages.
    pub fn describe(self) -> String {
        match self {
            Ty::Num => "a number".into(),
            Ty::Int => "a whole number".into(),
            Ty::Vec2 => "a vector of 2".into(),
            Ty::Vec3 => "a vector of 3".into(),
            Ty::Color => "a colour".into(),
            Ty::Str => "a string".into(),
            Ty::Bool => "a boolean".into(),
            Ty::Word(ws) => format!("one of {}", ws.join(", ")),
            Ty::NumOrVec3 => "a number or a vector of 3".into(),
            Ty::NumOrVec2 => "a number or a vector of 2".into(),
            Ty::Matrix => "a vector of 12 or 16 numbers".into(),
            Ty::Texture => "a texture such as `image { file \"normal.png\" }`".into(),
        }
    }
}

/// One parameter of a block.
#[derive(Debug, Clone, Copy)]
pub struct ParamSpec {
    /// Its name.
    pub name: &'static str,
    /// Its type.
    pub ty: Ty,
    /// An example value, used in help lines.
    pub example: &'static str,
    /// Whether it may appear several times (transforms; order matters).
    pub repeat: bool,
    /// What its numbers stand for, which fixes their range.
    pub quantity: Quantity,
    /// Whether it may be given a texture instead of a value.
    pub texture: bool,
    /// For a POV-Ray word this block refuses because ptsc means something
    /// else by it (or has it under another name): the ptsc parameter that
    /// does its job and a help line saying so. Not a parameter: refused
    /// with the line, left out of the lists of accepted names.
    pub povray: Option<(&'static str, &'static str)>,
}

impl ParamSpec {
    /// The same parameter, its numbers standing for `quantity`.
    const fn of(self, quantity: Quantity) -> ParamSpec {
        ParamSpec { quantity, ..self }
    }

    /// The same parameter, which may be given a texture.
    const fn textured(self) -> ParamSpec {
        ParamSpec {
            texture: true,
            ..self
        }
    }
}

const fn p(name: &'static str, ty: Ty, example: &'static str) -> ParamSpec {
    ParamSpec {
        name,
        ty,
        example,
        repeat: false,
        quantity: Quantity::Plain,
        texture: false,
        povray: None,
    }
}

const fn t(name: &'static str, ty: Ty, example: &'static str) -> ParamSpec {
    ParamSpec {
        name,
        ty,
        example,
        repeat: true,
        quantity: Quantity::Plain,
        texture: false,
        povray: None,
    }
}

/// The help for a light's `color`: POV-Ray's light colour.
const LIGHT_COLOR: &str = "POV-Ray's light `color` is `intensity rgb …` in ptsc: radiant intensity, falling off with the squared distance (POV-Ray's light does not fall off unless told: give about 1.9 × its colour × the squared distance to what it lights)";
/// [`LIGHT_COLOR`] spelt `colour`.
const LIGHT_COLOUR: &str = "POV-Ray's light `colour` is `intensity rgb …` in ptsc: radiant intensity, falling off with the squared distance (POV-Ray's light does not fall off unless told: give about 1.9 × its colour × the squared distance to what it lights)";

/// A POV-Ray word refused in one kind of block, with the ptsc parameter
/// that does its job and the help line (see [`ParamSpec::povray`]).
const fn povray(name: &'static str, instead: &'static str, help: &'static str) -> ParamSpec {
    ParamSpec {
        povray: Some((instead, help)),
        ..p(name, Ty::Num, "")
    }
}

/// The help line for POV-Ray's spot light angles, whose `falloff` is the
/// opposite of what the word suggests: it is the outer angle.
const SPOT_ANGLES: &str = "POV-Ray's `falloff` (the outer angle, where the light ends) is `angle` in ptsc; its `radius` (the hot spot, full light inside) is `hotspot`";

/// Parameters every shape accepts besides `material`.
pub const SHAPE_COMMON: &[ParamSpec] = &[
    t("translate", Ty::Vec3, "<0, 1, 0>").of(Magnitude),
    t("rotate", Ty::Vec3, "<0, 45, 0>"),
    t("scale", Ty::NumOrVec3, "2").of(Quantity::Scale),
    t("matrix", Ty::Matrix, "<1,0,0, 0,1,0, 0,0,1, 0,0,0>").of(Magnitude),
    p("velocity", Ty::Vec3, "<1, 0, 0>").of(Magnitude),
];

/// Integrator names accepted by `render { integrator … }`.
pub const INTEGRATORS: &[&str] = &crate::ir::settings::IntegratorKind::WORDS;

/// Light selection rules accepted by `render { light_selection … }`.
pub const LIGHT_SELECTIONS: &[&str] = &crate::ir::settings::LightSelection::WORDS;

/// `render { }`
pub const RENDER: &[ParamSpec] = &[
    p("resolution", Ty::Vec2, "<512, 512>"),
    p("samples", Ty::Int, "64"),
    p("max_depth", Ty::Int, "8"),
    p("integrator", Ty::Word(INTEGRATORS), "path"),
    p("seed", Ty::Int, "1"),
    p("ambient", Ty::Color, "rgb 0.1").of(Radiance),
    p("rr_depth", Ty::Int, "5"),
    p("output", Ty::Str, "\"out.png\""),
    p("hybrid_weight", Ty::Num, "0.5"),
    p("clamp", Ty::Num, "10"),
    p("light_sampling", Ty::Bool, "true"),
    p("light_selection", Ty::Word(LIGHT_SELECTIONS), "auto"),
    p("light_samples", Ty::Int, "4"),
    p("exposure", Ty::Num, "0"),
];

/// `camera { }`
pub const CAMERA: &[ParamSpec] = &[
    p("position", Ty::Vec3, "<0, 1, 5>").of(Magnitude),
    p("look_at", Ty::Vec3, "<0, 0, 0>").of(Magnitude),
    p("up", Ty::Vec3, "<0, 1, 0>").of(Direction),
    p("fov", Ty::Num, "40"),
    p("aperture", Ty::Num, "0.05").of(Magnitude),
    p("focus_distance", Ty::Num, "5").of(Size),
    p("shutter", Ty::Vec2, "<0, 1>").of(Magnitude),
];

/// `environment { }`
pub const ENVIRONMENT: &[ParamSpec] = &[
    p("file", Ty::Str, "\"studio.hdr\""),
    p("intensity", Ty::Color, "rgb 1").of(Radiance),
    t("rotate", Ty::Vec3, "<0, 90, 0>"),
];

/// `sky { }`
pub const SKY: &[ParamSpec] = &[
    p("sun_direction", Ty::Vec3, "<0.3, 0.6, -1>").of(Direction),
    p("sun_elevation", Ty::Num, "35"),
    p("sun_azimuth", Ty::Num, "20"),
    p("turbidity", Ty::Num, "3"),
    p("albedo", Ty::Color, "rgb 0.3").of(Magnitude),
    p("intensity", Ty::Color, "rgb 1").of(Radiance),
    p("sun_intensity", Ty::Color, "rgb 1").of(Radiance),
];

/// `material { }`
pub const MATERIAL: &[ParamSpec] = &[
    p("diffuse", Ty::Color, "rgb <0.8, 0.8, 0.8>")
        .of(Magnitude)
        .textured(),
    p("reflection", Ty::Color, "rgb 1").of(Magnitude).textured(),
    p("gloss", Ty::Num, "0.3").textured(),
    p("transmission", Ty::Num, "1").textured(),
    p("ior", Ty::Num, "1.5"),
    p("ior_outside", Ty::Num, "1.33"),
    p("roughness", Ty::NumOrVec2, "<0.05, 0.3>"),
    p("absorption", Ty::Color, "rgb <0.5, 0.1, 0.1>")
        .of(Magnitude)
        .textured(),
    p("emission", Ty::Color, "rgb 10").of(Radiance).textured(),
    p("two_sided", Ty::Bool, "true"),
    p(
        "normal_map",
        Ty::Texture,
        "image { file \"bricks_normal.png\" }",
    )
    .textured(),
    p("bump", Ty::Texture, "noise { scale 0.05 }").textured(),
    p("bump_height", Ty::Num, "0.01").of(Magnitude),
    p("type", Ty::Word(MATERIAL_TYPES), "plastic"),
    p("preset", Ty::Word(METAL_PRESETS), "gold"),
    p("eta", Ty::Color, "rgb <0.2, 0.92, 1.1>").of(Magnitude),
    p("k", Ty::Color, "rgb <3.9, 2.45, 2.14>").of(Magnitude),
    p("multiscatter", Ty::Bool, "false"),
];

/// The scattering models a material's `type` names (`mix`, the paper's
/// weighted lobes, when none is given).
pub const MATERIAL_TYPES: &[&str] = &[
    "mix",
    "conductor",
    "plastic",
    "dielectric",
    "thin_dielectric",
];

/// The named metals of `type conductor` (their constants live with the
/// conductor model, `material::conductor::PRESETS`, in this order).
pub const METAL_PRESETS: &[&str] = &crate::material::conductor::Metal::WORDS;

/// The kinds of texture a parameter may be given.
pub const TEXTURE_KINDS: &[&str] = &[
    "checker",
    "image",
    "noise",
    "turbulence",
    "marble",
    "wood",
    "gradient",
    "stripes",
];

/// A texture's colour map: its stops, in order, replacing its two colours
/// (`low`/`high`, `even`/`odd`).
pub const COLOR_MAP: &[ParamSpec] = &[t("stop", Ty::Num, "0.5 rgb <0.8, 0.2, 0.1>")];

/// `gradient { }` and `stripes { }`, besides [`COLOR_MAP`] and
/// [`TEXTURE_TRANSFORMS`].
pub const GRADIENT: &[ParamSpec] = &[
    p("low", Ty::Color, "rgb 0.2").of(Magnitude),
    p("high", Ty::Color, "rgb 0.9").of(Magnitude),
    p("space", Ty::Word(TEXTURE_SPACES), "world"),
];

/// `noise`, `turbulence`, `marble` and `wood { }`, besides
/// [`COLOR_MAP`] and [`TEXTURE_TRANSFORMS`] (and [`BANDS`] or
/// [`UNBANDED`]). `octaves` 1 to 16 (default 6), `omega` in (0, 1]
/// (default 0.5), `lambda` in (1, 10] (default 2), as POV-Ray's.
pub const NOISE: &[ParamSpec] = &[
    p("low", Ty::Color, "rgb 0.2").of(Magnitude),
    p("high", Ty::Color, "rgb 0.9").of(Magnitude),
    p("octaves", Ty::Int, "4"),
    p("omega", Ty::Num, "0.6"),
    p("lambda", Ty::Num, "2.5"),
    p("space", Ty::Word(TEXTURE_SPACES), "world"),
];

/// `marble` and `wood { }`'s bands, besides [`NOISE`]: `turbulence`, how
/// far noise displaces them, 0 to 100 (default 2 for marble, 0.25 for
/// wood); `frequency`, greater than 0 and at most 1000 (default 1);
/// `phase`, 0 to 1 (default 0).
pub const BANDS: &[ParamSpec] = &[
    p("turbulence", Ty::Num, "1.5"),
    p("frequency", Ty::Num, "2"),
    p("phase", Ty::Num, "0.25"),
];

/// `noise` and `turbulence { }`, which have no bands to disturb: POV-Ray's
/// `turbulence` (a warp any pattern takes) is refused with what to do.
pub const UNBANDED: &[ParamSpec] = &[povray(
    "turbulence",
    "scale",
    "ptsc's `turbulence` displaces the bands of `marble` and `wood`; `noise` and `turbulence` are the noise itself: `scale` them for larger features, `omega` for rougher ones",
)];

/// The wrap modes of an image texture.
pub const WRAPS: &[&str] = &crate::texture::image::Wrap::WORDS;

/// `image { }`, besides [`TEXTURE_TRANSFORMS`].
pub const IMAGE: &[ParamSpec] = &[
    p("file", Ty::Str, "\"wood.png\""),
    p("wrap", Ty::Word(WRAPS), "clamp"),
    p("space", Ty::Word(TEXTURE_SPACES), "object"),
    p("color_space", Ty::Word(COLOR_SPACES), "linear"),
];

/// How an image's values are encoded (`image { color_space … }`).
pub const COLOR_SPACES: &[&str] = &super::scene::ColorSpace::WORDS;

/// The spaces a texture's pattern can live in.
pub const TEXTURE_SPACES: &[&str] = &["uv", "object", "world"];

/// `checker { }`, besides the transforms of [`SHAPE_COMMON`] (velocity
/// excepted).
pub const CHECKER: &[ParamSpec] = &[
    p("even", Ty::Color, "rgb 0.9").of(Magnitude),
    p("odd", Ty::Color, "rgb 0.1").of(Magnitude),
    p("space", Ty::Word(TEXTURE_SPACES), "object"),
];

/// The transforms a texture takes (its pattern moves, turns and scales).
pub const TEXTURE_TRANSFORMS: &[ParamSpec] = &[
    t("translate", Ty::Vec3, "<0.5, 0, 0>").of(Magnitude),
    t("rotate", Ty::Vec3, "<0, 0, 45>"),
    t("scale", Ty::NumOrVec3, "0.25").of(Quantity::Scale),
];

/// The error of a transform given to what lies at infinity (an
/// environment or a sky): only turning means anything there.
fn at_infinity(what: &str, name: &str, span: Span) -> Option<Diagnostic> {
    if !matches!(what, "environment" | "sky") || !matches!(name, "translate" | "scale" | "matrix") {
        return None;
    }
    let why = match name {
        "translate" => "it is infinitely far: moving it changes nothing",
        "scale" => "it has no size: every direction keeps its light",
        _ => "a matrix could move, scale or shear it",
    };
    let help = match what {
        "environment" => "turn it with `rotate <x, y, z>` (degrees); to move the scene against it, move the camera and the objects",
        _ => "turn the sun with `sun_direction` or `sun_azimuth`; to move the scene against it, move the camera and the objects",
    };
    Some(
        Diagnostic::error(
            codes::UNKNOWN_PARAM,
            format!("`{name}` has no meaning for the {what}"),
            span,
        )
        .with_label(why)
        .with_help(help),
    )
}

/// Every parameter name of every block and of materials, sorted (editors
/// highlight them; their grammars are tested against this list).
pub fn all_parameter_names() -> Vec<&'static str> {
    let mut names: Vec<&'static str> = crate::syntax::ast::BlockKind::ALL
        .iter()
        .flat_map(|&k| shape_schema(k).iter())
        .chain(SHAPE_COMMON)
        .chain(MATERIAL)
        .chain(CHECKER)
        .chain(IMAGE)
        .chain(NOISE)
        .chain(BANDS)
        .chain(GRADIENT)
        .chain(COLOR_MAP)
        .filter(|p| p.povray.is_none())
        .map(|p| p.name)
        .collect();
    names.sort_unstable();
    names.dedup();
    names
}

/// The parameters of each shape, without [`SHAPE_COMMON`].
pub fn shape_schema(kind: crate::syntax::ast::BlockKind) -> &'static [ParamSpec] {
    use crate::syntax::ast::BlockKind::*;
    match kind {
        Sphere => {
            const S: &[ParamSpec] = &[
                p("center", Ty::Vec3, "<0, 1, 0>").of(Magnitude),
                p("radius", Ty::Num, "1").of(Size),
            ];
            S
        }
        Plane => {
            const S: &[ParamSpec] = &[
                p("point", Ty::Vec3, "<0, 0, 0>").of(Magnitude),
                p("normal", Ty::Vec3, "<0, 1, 0>").of(Direction),
            ];
            S
        }
        Quad => {
            const S: &[ParamSpec] = &[
                p("corner", Ty::Vec3, "<-1, 0, -1>").of(Magnitude),
                p("edge1", Ty::Vec3, "<0, 0, 2>").of(Magnitude),
                p("edge2", Ty::Vec3, "<2, 0, 0>").of(Magnitude),
            ];
            S
        }
        Disk => {
            const S: &[ParamSpec] = &[
                p("center", Ty::Vec3, "<0, 0, 0>").of(Magnitude),
                p("normal", Ty::Vec3, "<0, 1, 0>").of(Direction),
                p("radius", Ty::Num, "1").of(Size),
            ];
            S
        }
        Triangle => {
            const S: &[ParamSpec] = &[
                p("v0", Ty::Vec3, "<0, 0, 0>").of(Magnitude),
                p("v1", Ty::Vec3, "<1, 0, 0>").of(Magnitude),
                p("v2", Ty::Vec3, "<0, 1, 0>").of(Magnitude),
            ];
            S
        }
        Box => {
            const S: &[ParamSpec] = &[
                p("min", Ty::Vec3, "<-1, -1, -1>").of(Magnitude),
                p("max", Ty::Vec3, "<1, 1, 1>").of(Magnitude),
            ];
            S
        }
        Cylinder => {
            const S: &[ParamSpec] = &[
                p("base", Ty::Vec3, "<0, 0, 0>").of(Magnitude),
                p("top", Ty::Vec3, "<0, 2, 0>").of(Magnitude),
                p("radius", Ty::Num, "0.5").of(Size),
                p("open", Ty::Bool, "true"),
            ];
            S
        }
        Cone => {
            const S: &[ParamSpec] = &[
                p("base", Ty::Vec3, "<0, 0, 0>").of(Magnitude),
                p("top", Ty::Vec3, "<0, 2, 0>").of(Magnitude),
                p("base_radius", Ty::Num, "1").of(Size),
                p("top_radius", Ty::Num, "0").of(Size),
                p("open", Ty::Bool, "true"),
            ];
            S
        }
        Torus => {
            const S: &[ParamSpec] = &[
                p("center", Ty::Vec3, "<0, 0, 0>").of(Magnitude),
                p("axis", Ty::Vec3, "<0, 1, 0>").of(Direction),
                p("major_radius", Ty::Num, "1").of(Size),
                p("minor_radius", Ty::Num, "0.25").of(Size),
            ];
            S
        }
        Mesh => {
            const S: &[ParamSpec] = &[
                p("file", Ty::Str, "\"bunny.ply\""),
                p("smooth", Ty::Bool, "true"),
            ];
            S
        }
        PointLight => {
            const S: &[ParamSpec] = &[
                p("position", Ty::Vec3, "<0, 5, 0>").of(Magnitude),
                p("intensity", Ty::Color, "rgb 100").of(Radiance),
                povray("color", "intensity", LIGHT_COLOR),
                povray("colour", "intensity", LIGHT_COLOUR),
            ];
            S
        }
        SpotLight => {
            const S: &[ParamSpec] = &[
                p("position", Ty::Vec3, "<0, 5, 0>").of(Magnitude),
                p("look_at", Ty::Vec3, "<0, 0, 0>").of(Magnitude),
                p("intensity", Ty::Color, "rgb 100").of(Radiance),
                p("angle", Ty::Num, "30"),
                p("hotspot", Ty::Num, "25"),
                povray("falloff", "angle", SPOT_ANGLES),
                povray("radius", "hotspot", SPOT_ANGLES),
                povray("tightness", "hotspot", "POV-Ray's `tightness` has no ptsc equivalent: the light falls off smoothly from `hotspot` to `angle`"),
                povray("point_at", "look_at", "POV-Ray's `point_at` is `look_at` in ptsc"),
                povray("color", "intensity", LIGHT_COLOR),
                povray("colour", "intensity", LIGHT_COLOUR),
            ];
            S
        }
        DirectionalLight => {
            const S: &[ParamSpec] = &[
                p("direction", Ty::Vec3, "<0, -1, 0>").of(Direction),
                p("irradiance", Ty::Color, "rgb 3").of(Radiance),
            ];
            S
        }
        Render => RENDER,
        Camera => CAMERA,
        Environment => ENVIRONMENT,
        Sky => SKY,
    }
}

/// POV-Ray's positional values of a shape (`sphere { <0, 1, 0>, 1 }`):
/// the ptsc parameters they stand for in POV-Ray's order, and what ptsc
/// means otherwise. A plane's second value is POV-Ray's distance along the
/// normal, written as a `point` (see `check::povray`).
pub fn povray_positional(
    kind: crate::syntax::ast::BlockKind,
) -> Option<(&'static [&'static str], &'static str)> {
    use crate::syntax::ast::BlockKind::*;
    Some(match kind {
        Sphere => (&["center", "radius"], ""),
        Plane => (&["normal", "point"], "a plane is given by a point on it"),
        Box => (&["min", "max"], "`min` is the smaller corner"),
        Cylinder => (&["base", "top", "radius"], ""),
        Cone => (&["base", "base_radius", "top", "top_radius"], ""),
        Torus => (&["major_radius", "minor_radius"], ""),
        Disk => (&["center", "normal", "radius"], ""),
        Triangle => (&["v0", "v1", "v2"], ""),
        PointLight => (&["position", "intensity"], "ptsc's lights fall off with the squared distance (POV-Ray's do not unless told): an `intensity` of about 1.9 × POV-Ray's colour × the squared distance to what it lights looks alike there"),
        _ => return None,
    })
}

/// A checked parameter value.
#[derive(Debug, Clone, PartialEq)]
pub enum Val {
    /// A number (or whole number).
    Num(f64),
    /// A vector.
    Vector(Vec<f64>),
    /// A colour.
    Color([f64; 3]),
    /// A string.
    Str(String),
    /// A boolean.
    Bool(bool),
    /// A word from a fixed set.
    Word(String),
    /// A texture (for the parameters that take one).
    Texture(Box<super::scene::Texture>),
}

/// What an entry gives a parameter: a value, a texture (its kind, its
/// block, the whole entry's span) or a colour stop (read by the texture's
/// own check).
enum Source<'a> {
    Value(&'a crate::syntax::ast::Expr),
    Texture(&'a crate::syntax::ast::Ident, &'a Block, Span),
    Stop(Span),
}

impl Source<'_> {
    /// Where the value is written.
    fn span(&self) -> Span {
        match self {
            Source::Value(e) => e.span,
            Source::Texture(_, _, span) | Source::Stop(span) => *span,
        }
    }
}

/// The error for a texture (`what`, at `span`) given to a parameter that
/// takes a plain value.
fn texture_not_allowed(spec: &ParamSpec, what: &str, span: Span) -> Diagnostic {
    Diagnostic::error(
        codes::TEXTURE_NOT_ALLOWED,
        format!("`{}` cannot be given a texture", spec.name),
        span,
    )
    .with_label(what.to_string())
    .with_help(format!(
        "`{}` takes {}; textures go on a material's colours and numbers (`diffuse`, `gloss`, `emission`, …) and its `normal_map` and `bump`",
        spec.name,
        spec.ty.describe()
    ))
}

/// The error for a POV-Ray word that a block's row refuses (`falloff` in
/// a `spot_light`), with its row's help line and the names it accepts.
fn refused_povray_word(
    name: &crate::syntax::ast::Ident,
    what: &str,
    help: &str,
    accepted: &[&str],
) -> Diagnostic {
    Diagnostic::error(
        codes::UNKNOWN_PARAM,
        format!("unknown parameter `{}` in `{what}`", name.name),
        name.span,
    )
    .with_label("a POV-Ray parameter this block does not take")
    .with_help(format!("{help}; `{what}` accepts {}", accepted.join(", ")))
}

/// The texture `value` names, if it is a bare name that is not a constant
/// but a declared texture (`texture oak wood { … }`).
fn named_texture(value: &crate::syntax::ast::Expr, env: &mut Env) -> Option<super::scene::Texture> {
    let ExprKind::Name(name) = &value.kind else {
        return None;
    };
    if env.is_bound(name) {
        return None;
    }
    let (texture, decl) = env.textures.get(name)?.clone();
    env.used.insert(decl);
    Some(texture)
}

/// The checked parameters of one block.
pub struct Params {
    /// What the block is called in messages (`sphere`, `material glass`).
    pub what: Cow<'static, str>,
    /// Where the block's keyword or name is (missing-parameter errors point there).
    pub head: Span,
    /// Well-typed single parameters. A block has a handful: a vector searched
    /// in order beats hashing (SipHash was 5 % of checking 100,000 spheres).
    values: Vec<(&'static str, (Val, Span))>,
    /// Repeatable parameters (transforms) in source order.
    pub ordered: Vec<(&'static str, Val, Span)>,
    /// Names that were given (well-typed or not), so a later "missing" is not reported twice.
    given: Vec<&'static str>,
    /// Names an unknown parameter was probably meant to be: not reported missing again.
    suggested: Vec<&'static str>,
}

impl Params {
    /// Checks `block` against `schema` (plus `extra`), evaluating values.
    /// Entries that are `material` references are left to the caller.
    pub fn collect(
        what: impl Into<Cow<'static, str>>,
        head: Span,
        block: &Block,
        schemas: &[&'static [ParamSpec]],
        env: &mut Env,
        diags: &mut Diagnostics,
    ) -> Params {
        let what = what.into();
        let mut params = Params {
            what: what.clone(),
            head,
            values: Vec::new(),
            ordered: Vec::new(),
            given: Vec::new(),
            suggested: Vec::new(),
        };
        let mut first_seen: Vec<(&'static str, Span)> = Vec::new();
        for (i, entry) in block.entries.iter().enumerate() {
            let (name, value) = match entry {
                Entry::Foreign { name, span } => {
                    diags.push(super::povray::foreign_block(&what, name, *span, schemas));
                    continue;
                }
                Entry::Flag { name } => {
                    diags.push(super::povray::flag(&what, name));
                    // A parameter written without its value is not missing too.
                    let all = schemas.iter().flat_map(|s| s.iter());
                    params
                        .suggested
                        .extend(all.map(|p| p.name).find(|n| *n == name.name));
                    continue;
                }
                Entry::Positional { values, span } => {
                    match took_next_word(&block.entries, i, env) {
                        // `no_shadow radius 1`, `diffuse color rgb 1`: the
                        // word before took the next one as its value; its
                        // error says why, and the parameter taken is given.
                        Some(taken) => {
                            // POV-Ray's `location` is `position`.
                            let taken = crate::syntax::povray::parameter(taken).unwrap_or(taken);
                            let all = schemas.iter().flat_map(|s| s.iter());
                            params
                                .suggested
                                .extend(all.map(|p| p.name).find(|n| *n == taken))
                        }
                        None => {
                            let (d, names) = super::povray::positional(&what, values, *span, env);
                            diags.push(d);
                            // Not reported missing too: the help names them.
                            params.suggested.extend_from_slice(names);
                        }
                    }
                    continue;
                }
                // `diffuse color rgb 1`: `rgb 1` after a word taken as a value.
                Entry::Param { name, .. }
                    if name.name == "rgb" && took_next_word(&block.entries, i, env).is_some() =>
                {
                    continue
                }
                Entry::Param { name, value, .. } => (name, Source::Value(value)),
                Entry::Texture {
                    name,
                    kind,
                    block,
                    span,
                } => (name, Source::Texture(kind, block, *span)),
                Entry::Stop { word, span, .. } => (word, Source::Stop(*span)),
                Entry::Material { .. } => continue,
            };
            if name.name == "material" {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        "`material` takes a material name or an inline material block",
                        value.span(),
                    )
                    .with_label("not a material")
                    .with_help("write `material white` (a declared name) or `material { diffuse rgb 0.8 }`"),
                );
                continue;
            }
            let found = schemas
                .iter()
                .flat_map(|s| s.iter())
                .find(|s| s.name == name.name);
            let all = || -> Vec<&'static str> {
                (schemas.iter().flat_map(|s| s.iter()))
                    .filter(|p| p.povray.is_none())
                    .map(|p| p.name)
                    .collect()
            };
            if let Some(&ParamSpec {
                povray: Some((instead, help)),
                ..
            }) = found
            {
                params.suggested.push(instead);
                diags.push(refused_povray_word(name, &what, help, &all()));
                continue;
            }
            let Some(spec) = found else {
                if let Some(d) = at_infinity(&what, &name.name, name.span) {
                    diags.push(d);
                    continue;
                }
                let all = all();
                let help = match did_you_mean(&name.name, all.iter().copied()) {
                    Some(s) => {
                        params.suggested.push(s);
                        format!("did you mean `{s}`?")
                    }
                    None => {
                        let hint = crate::syntax::povray::hint(&name.name);
                        match crate::syntax::povray::parameter(&name.name) {
                            Some(instead) => {
                                if let Some(&known) = all.iter().find(|&&n| n == instead) {
                                    params.suggested.push(known);
                                }
                                let hint = hint.map(String::from).unwrap_or_else(|| {
                                    format!("POV-Ray's `{}` is `{instead}` in ptsc", name.name)
                                });
                                format!("{hint}; `{what}` accepts {}", all.join(", "))
                            }
                            None => match hint {
                                Some(hint) => {
                                    format!("{hint}; `{what}` accepts {}", all.join(", "))
                                }
                                None => format!("`{what}` accepts {}", all.join(", ")),
                            },
                        }
                    }
                };
                diags.push(
                    Diagnostic::error(
                        codes::UNKNOWN_PARAM,
                        format!("unknown parameter `{}` in `{what}`", name.name),
                        name.span,
                    )
                    .with_label("not a parameter of this block")
                    .with_help(help),
                );
                continue;
            };
            if !spec.repeat {
                if let Some((_, first)) = first_seen.iter().find(|(n, _)| *n == spec.name) {
                    diags.push(
                        Diagnostic::error(
                            codes::DUPLICATE_PARAM,
                            format!("parameter `{}` given twice in `{what}`", spec.name),
                            name.span,
                        )
                        .with_label("given again here")
                        .with_secondary(*first, "first given here")
                        .with_help("remove one of them"),
                    );
                    continue;
                }
                first_seen.push((spec.name, name.span));
            }
            params.given.push(spec.name);
            let val = match value {
                // Stops are read with their texture (`check::texture`).
                Source::Stop(_) => continue,
                Source::Value(value) if spec.texture => match named_texture(value, env) {
                    Some(t) => Some(Val::Texture(Box::new(t))),
                    None => typed_value(spec, value, env, diags),
                },
                Source::Texture(kind, block, span) if spec.texture => {
                    super::texture::check_texture(kind, block, span, env, diags)
                        .map(|t| Val::Texture(Box::new(t)))
                }
                Source::Value(value) => match named_texture(value, env) {
                    Some(_) => {
                        diags.push(texture_not_allowed(spec, "a texture's name", value.span));
                        None
                    }
                    None => typed_value(spec, value, env, diags),
                },
                Source::Texture(kind, _, span) => {
                    let what = format!("a `{}` texture", kind.name);
                    diags.push(texture_not_allowed(spec, &what, span));
                    None
                }
            };
            let Some(val) = val else {
                continue;
            };
            let value_span = value.span();
            let numbers: &[f64] = match &val {
                Val::Num(x) => std::slice::from_ref(x),
                Val::Vector(v) => v,
                Val::Color(c) => c,
                _ => &[],
            };
            if let Err(d) = spec
                .quantity
                .check_all(numbers, spec.name, &what, value_span)
            {
                diags.push(d);
                continue;
            }
            if spec.repeat {
                params.ordered.push((spec.name, val, value_span));
            } else {
                params.values.push((spec.name, (val, value_span)));
            }
        }
        params
    }

    /// The value of an optional parameter.
    pub fn get(&self, name: &str) -> Option<&(Val, Span)> {
        self.values.iter().find(|(n, _)| *n == name).map(|(_, v)| v)
    }

    /// Whether the parameter was written (even if its value had an error).
    pub fn given(&self, name: &str) -> bool {
        self.given.contains(&name)
    }

    /// A required parameter; reports it missing (once) if absent.
    pub fn require(
        &self,
        spec_name: &'static str,
        schema: &[ParamSpec],
        diags: &mut Diagnostics,
    ) -> Option<&(Val, Span)> {
        if let Some(v) = self.get(spec_name) {
            return Some(v);
        }
        if !self.given(spec_name) && !self.suggested.contains(&spec_name) {
            let example = schema
                .iter()
                .find(|s| s.name == spec_name)
                .map(|s| s.example)
                .unwrap_or("…");
            diags.push(
                Diagnostic::error(
                    codes::MISSING_PARAM,
                    format!("`{}` needs {} `{spec_name}`", self.what, article(spec_name)),
                    self.head,
                )
                .with_label(format!("`{spec_name}` is missing"))
                .with_help(format!("add `{spec_name} {example}` inside the braces")),
            );
        }
        None
    }
}

/// The word the entry before `entries[i]` took as its value, when it is
/// a bare name that means nothing (`no_shadow radius`, `diffuse color`):
/// then `entries[i]` is the rest of a POV-Ray form already reported.
fn took_next_word<'a>(entries: &'a [Entry], i: usize, env: &mut Env) -> Option<&'a str> {
    let previous = entries.get(i.checked_sub(1)?)?;
    let Entry::Param { value, .. } = previous else {
        return None;
    };
    match &value.kind {
        ExprKind::Name(n) if env.lookup(n).is_none() => Some(n),
        _ => None,
    }
}

/// "a" or "an" before `word`, by its first letter.
fn article(word: &str) -> &'static str {
    match word.chars().next() {
        Some('a' | 'e' | 'i' | 'o' | 'u') => "an",
        _ => "a",
    }
}

/// Evaluates one parameter value and checks its type against the spec.
fn typed_value(
    spec: &ParamSpec,
    value: &crate::syntax::ast::Expr,
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<Val> {
    if let Ty::Word(words) = spec.ty {
        let ExprKind::Name(w) = &value.kind else {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("`{}` expects {}", spec.name, spec.ty.describe()),
                    value.span,
                )
                .with_label("not one of the accepted words")
                .with_help(format!("write e.g. `{} {}`", spec.name, spec.example)),
            );
            return None;
        };
        if words.contains(&w.as_str()) {
            return Some(Val::Word(w.clone()));
        }
        let metal = (words == METAL_PRESETS).then(|| super::material::other_metal(w));
        let help = match (metal.flatten(), did_you_mean(w, words.iter().copied())) {
            (Some(help), _) => help,
            (None, Some(s)) => format!("did you mean `{s}`?"),
            (None, None) => format!("use one of {}", words.join(", ")),
        };
        diags.push(
            Diagnostic::error(
                codes::UNKNOWN_WORD,
                format!("unknown {} `{w}`", spec.name),
                value.span,
            )
            .with_label(format!("not a known {}", spec.name))
            .with_help(help),
        );
        return None;
    }
    let v = eval(value, env, diags)?;
    let ok = match (&spec.ty, v) {
        (Ty::Num, Value::Num(x)) => Some(Val::Num(x)),
        (Ty::Int, Value::Num(x)) if x.fract() == 0.0 => Some(Val::Num(x)),
        (Ty::Int, Value::Num(x)) => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("`{}` must be a whole number, found {x}", spec.name),
                    value.span,
                )
                .with_label("has a fractional part")
                .with_help(format!("write e.g. `{} {}`", spec.name, spec.example)),
            );
            return None;
        }
        (Ty::Vec2, Value::Vector(v)) if v.len() == 2 => Some(Val::Vector(v.to_vec())),
        (Ty::Vec3, Value::Vector(v)) if v.len() == 3 => Some(Val::Vector(v.to_vec())),
        (Ty::NumOrVec3, Value::Num(x)) => Some(Val::Vector(vec![x; 3])),
        (Ty::NumOrVec3, Value::Vector(v)) if v.len() == 3 => Some(Val::Vector(v.to_vec())),
        (Ty::NumOrVec2, Value::Num(x)) => Some(Val::Vector(vec![x; 2])),
        (Ty::NumOrVec2, Value::Vector(v)) if v.len() == 2 => Some(Val::Vector(v.to_vec())),
        (Ty::Matrix, Value::Vector(v)) if v.len() == 12 || v.len() == 16 => {
            Some(Val::Vector(v.to_vec()))
        }
        (Ty::Color, Value::Color(c)) => Some(Val::Color(c)),
        (Ty::Str, Value::Str(s)) => Some(Val::Str(s.to_string())),
        (Ty::Bool, Value::Bool(b)) => Some(Val::Bool(b)),
        (ty, other) => {
            let help = match (ty, &other) {
                (Ty::Color, Value::Vector(v)) if v.len() == 3 => format!(
                    "colours are written with `rgb`: `{} rgb <{}, {}, {}>`",
                    spec.name, v[0], v[1], v[2]
                ),
                (Ty::Color, Value::Num(x)) => {
                    format!("colours are written with `rgb`: `{} rgb {x}`", spec.name)
                }
                _ => format!("write e.g. `{} {}`", spec.name, spec.example),
            };
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!(
                        "`{}` expects {}, found {}",
                        spec.name,
                        ty.describe(),
                        other.type_name()
                    ),
                    value.span,
                )
                .with_label(format!("this is {}", other.type_name()))
                .with_help(help),
            );
            return None;
        }
    };
    ok
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::ast::BlockKind;

    #[test]
    fn a_refused_povray_word_names_a_parameter_its_block_has() {
        let rows = (BlockKind::ALL.iter().map(|&k| shape_schema(k)))
            .chain([NOISE, BANDS, UNBANDED, GRADIENT, CHECKER, IMAGE, MATERIAL]);
        let mut refused = 0;
        for row in rows {
            for spec in row.iter().filter(|s| s.povray.is_some()) {
                let (instead, help) = spec.povray.unwrap();
                refused += 1;
                assert!(help.contains(&format!("`{}`", spec.name)), "{help}");
                // `scale` is every texture's (TEXTURE_TRANSFORMS).
                let has = row.iter().any(|s| s.name == instead && s.povray.is_none());
                assert!(has || instead == "scale", "{}: {instead}", spec.name);
            }
        }
        assert_eq!(refused, 9);
        // Editors highlight parameters only: no word that is only refused.
        let names = all_parameter_names();
        for word in ["falloff", "tightness", "point_at"] {
            assert!(!names.contains(&word), "{word}");
        }
    }
}
