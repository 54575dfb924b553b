//! The schema of each block: its parameters, their types, examples and
//! ranges, and the POV-Ray words a row refuses with the ptsc word that does
//! their job; the word lists of the enumerated parameters, each defined once
//! by the type it names. The checker, the docs' tables and the editors'
//! keyword lists read these rows.

use super::domain::Quantity;
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

/// The help for a metal `name` that is not one of the presets: the
/// preset it is another name for, or how to give a metal's constants.
pub fn other_metal(name: &str) -> Option<String> {
    let preset = match name {
        "chrome" | "chromium_metal" => "chromium",
        "aluminum" | "aluminum_metal" | "alu" => "aluminium",
        "au" => "gold",
        "ag" => "silver",
        "cu" => "copper",
        "cr" => "chromium",
        "al" => "aluminium",
        _ => {
            let look = match name {
                "brass" | "bronze" => " (`preset gold` or `preset copper` looks close)",
                "steel" | "iron" | "stainless" | "nickel" | "titanium" | "platinum" | "tin"
                | "zinc" => " (`preset chromium` or `preset aluminium` looks close)",
                _ => return None,
            };
            return Some(format!(
                "`{name}` is not a preset{look}; for any metal, remove `preset` and give its complex index of refraction per channel: `eta rgb <…> k rgb <…>` (tables of n and k: refractiveindex.info, or Mitsuba 3's data/ior)"
            ));
        }
    };
    Some(format!("did you mean `{preset}`?"))
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
