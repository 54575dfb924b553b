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
    /// Names in quotes, each with a material (`{ "Leaf" green }`).
    Materials,
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
            Ty::Materials => "names in quotes, each with a material: `{ \"Leaf\" green }`".into(),
        }
    }
}

/// POV-Ray's order of a kind's positional values (`sphere { <0, 1, 0>, 1 }`):
/// the parameters they stand for, and a note on what ptsc means otherwise
/// (empty if none).
pub type Positional = (&'static [&'static str], &'static str);

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
    /// For a POV-Ray (or Mitsuba) word this block refuses because ptsc means
    /// something else by it (or has it under another name): the ptsc parameter that
    /// does its job and a help line saying so. Not a parameter: refused
    /// with the line, left out of the lists of accepted names.
    pub povray: Option<(&'static str, &'static str)>,
    /// What it means, its default and its range, in a line or two: the
    /// text of hover and of the docs' tables (empty where not written yet).
    pub doc: &'static str,
    /// The parameters of its block that do its job another way (`sun_direction`
    /// and `sun_elevation`): the checker refuses the two together, and
    /// completion leaves them out once one is given. Listed on one side
    /// of each pair; [`excludes`] reads both.
    pub excludes: &'static [&'static str],
}

impl ParamSpec {
    /// The same parameter, its numbers standing for `quantity`.
    pub(super) const fn of(self, quantity: Quantity) -> ParamSpec {
        ParamSpec { quantity, ..self }
    }

    /// The same parameter, documented by `doc` ([`ParamSpec::doc`]).
    pub(super) const fn doc(self, doc: &'static str) -> ParamSpec {
        ParamSpec { doc, ..self }
    }

    /// The same parameter, refused together with `names` ([`ParamSpec::excludes`]).
    const fn excludes(self, names: &'static [&'static str]) -> ParamSpec {
        ParamSpec {
            excludes: names,
            ..self
        }
    }

    /// The same parameter, which may be given a texture.
    const fn textured(self) -> ParamSpec {
        ParamSpec {
            texture: true,
            ..self
        }
    }
}

/// Whether `spec` and the parameter `other` of its block (whose rows are
/// `schemas`) may not be given together ([`ParamSpec::excludes`], read
/// from either side).
pub fn excludes(spec: &ParamSpec, other: &str, schemas: &[&[ParamSpec]]) -> bool {
    spec.excludes.contains(&other)
        || (schemas.iter().copied().flatten())
            .any(|o| o.name == other && o.excludes.contains(&spec.name))
}

/// A parameter given once.
pub(super) const fn p(name: &'static str, ty: Ty, example: &'static str) -> ParamSpec {
    ParamSpec {
        name,
        ty,
        example,
        repeat: false,
        quantity: Quantity::Plain,
        texture: false,
        povray: None,
        doc: "",
        excludes: &[],
    }
}

/// A parameter that may be given several times, in order (a transform).
pub(super) const fn t(name: &'static str, ty: Ty, example: &'static str) -> ParamSpec {
    ParamSpec {
        name,
        ty,
        example,
        repeat: true,
        quantity: Quantity::Plain,
        texture: false,
        povray: None,
        doc: "",
        excludes: &[],
    }
}

/// The help for a light's `color`: POV-Ray's light colour.
pub(super) const LIGHT_COLOR: &str = "POV-Ray's light `color` is `intensity rgb …` in ptsc: radiant intensity, falling off with the squared distance (POV-Ray's light does not fall off unless told: give about 1.9 × its colour × the squared distance to what it lights)";
/// [`LIGHT_COLOR`] spelt `colour`.
pub(super) const LIGHT_COLOUR: &str = "POV-Ray's light `colour` is `intensity rgb …` in ptsc: radiant intensity, falling off with the squared distance (POV-Ray's light does not fall off unless told: give about 1.9 × its colour × the squared distance to what it lights)";

/// A POV-Ray word refused in one kind of block, with the ptsc parameter
/// that does its job and the help line (see [`ParamSpec::povray`]).
pub(super) const fn povray(
    name: &'static str,
    instead: &'static str,
    help: &'static str,
) -> ParamSpec {
    ParamSpec {
        povray: Some((instead, help)),
        ..p(name, Ty::Num, "")
    }
}

/// The help line for POV-Ray's spot light angles, whose `falloff` is the
/// opposite of what the word suggests: it is the outer angle.
pub(super) const SPOT_ANGLES: &str = "POV-Ray's `falloff` (the outer angle, where the light ends) is `angle` in ptsc; its `radius` (the hot spot, full light inside) is `hotspot`";

/// Parameters every shape accepts besides `material`.
pub const SHAPE_COMMON: &[ParamSpec] = &[
    t("translate", Ty::Vec3, "<0, 1, 0>").of(Magnitude)
        .doc("moves the object (transforms apply in the order written)"),
    t("rotate", Ty::Vec3, "<0, 45, 0>")
        .doc("turns the object about x, then y, then z, in degrees"),
    t("scale", Ty::NumOrVec3, "2").of(Quantity::Scale)
        .doc("scales the object about the origin, by a number or per axis; no factor 0 (round shapes take uniform scales only)"),
    t("matrix", Ty::Matrix, "<1,0,0, 0,1,0, 0,0,1, 0,0,0>").of(Magnitude)
        .doc("an affine matrix, 12 numbers row by row (16 with a last row 0, 0, 0, 1)"),
    p("velocity", Ty::Vec3, "<1, 0, 0>").of(Magnitude)
        .doc("linear motion per unit of shutter time (motion blur). Default none"),
];

/// Integrator names accepted by `render { integrator … }`.
pub const INTEGRATORS: &[&str] = &crate::ir::settings::IntegratorKind::WORDS;

/// Light selection rules accepted by `render { light_selection … }`.
pub const LIGHT_SELECTIONS: &[&str] = &crate::ir::settings::LightSelection::WORDS;

/// Samplers accepted by `render { sampler … }`.
pub const SAMPLERS: &[&str] = &crate::ir::settings::SamplerKind::WORDS;

/// `render { }`
pub const RENDER: &[ParamSpec] = &[
    p("resolution", Ty::Vec2, "<512, 512>")
        .doc("image width and height in pixels; each side 1..16384, at most 8192 × 8192 pixels in all. Default `<512, 512>`"),
    p("samples", Ty::Int, "64")
        .doc("camera paths per pixel, 1..1000000. Default 16"),
    p("max_depth", Ty::Int, "8")
        .doc("path segments at most: 1 = emitters seen directly, 2 = direct light, … (Mitsuba's convention). Default 8"),
    p("integrator", Ty::Word(INTEGRATORS), "path")
        .doc("light transport: `path` (unbiased), `whitted`, `hybrid`, or a debug view (`normals`, `albedo`, `depth`, `uv`). Default `path`"),
    p("seed", Ty::Int, "1")
        .doc("seed of every random stream, 0..4294967295: same seed, same image. Default 0"),
    p("sampler", Ty::Word(SAMPLERS), "independent")
        .doc("the numbers samples draw: `sobol` (Owen-scrambled Sobol points, stratified in every decision of a pixel's samples) or `independent`. Default `sobol`"),
    p("ambient", Ty::Color, "rgb 0.1").of(Radiance)
        .doc("a constant ambient term added at diffuse hits (the paper's); biased. Default black"),
    p("rr_depth", Ty::Int, "5")
        .doc("path segments before Russian roulette may end a path (unbiased). Default 5"),
    p("output", Ty::Str, "\"out.png\"")
        .doc("the output file, relative to the scene: `.png`, `.exr` or `.pfm`. Default: the scene's name with `.png`"),
    p("hybrid_weight", Ty::Num, "0.5")
        .doc("weight of the Whitted estimate in `hybrid`, 0..1 (the rest is path traced). Default 0.5"),
    p("clamp", Ty::Num, "10")
        .doc("largest RGB component of an indirect contribution (biased; fights fireflies). Default off"),
    p("light_sampling", Ty::Bool, "true")
        .doc("next-event estimation with multiple importance sampling; `false` is naive path tracing. Default `true`"),
    p("light_selection", Ty::Word(LIGHT_SELECTIONS), "auto")
        .doc("how a shadow ray chooses its light: `auto`, `bvh`, `exhaustive`, `power` or `uniform`. Default `auto`"),
    p("light_samples", Ty::Int, "4")
        .doc("shadow rays per area light at each Whitted hit (soft shadows). Default 4"),
    p("time", Ty::Num, "90")
        .doc("a time budget in seconds: `ptsc render` stops when it is spent (or at `samples`, if given) and saves its state for `--resume`. Default none"),
    p("noise_threshold", Ty::Num, "0.01")
        .doc("adaptive sampling: a pixel stops once its noise (the difference of its even and odd samples' means over the square root of its brightness, Cycles's measure) is below this, 0 < t ≤ 1; typical 0.1 (draft) to 0.001 (final). Default off"),
    p("min_samples", Ty::Int, "16")
        .doc("with `noise_threshold`: samples every pixel takes before it may stop, 2..1000000. Default 16"),
    p("exposure", Ty::Num, "0")
        .doc("scales the image by 2^exposure before PNG encoding (stops). Default 0"),
    povray("spp", "samples", "Mitsuba's `spp` (of its sampler) is `samples` in ptsc (and `--spp` on the command line)"),
];

/// `camera { }`
pub const CAMERA: &[ParamSpec] = &[
    p("position", Ty::Vec3, "<0, 1, 5>")
        .of(Magnitude)
        .doc("the eye. Required"),
    p("look_at", Ty::Vec3, "<0, 0, 0>")
        .of(Magnitude)
        .doc("the point at the image centre. Required"),
    p("up", Ty::Vec3, "<0, 1, 0>")
        .of(Direction)
        .doc("the image's up direction; not parallel to the view. Default `<0, 1, 0>`"),
    p("fov", Ty::Num, "40").doc("full vertical field of view in degrees, 0..179. Default 40"),
    p("aperture", Ty::Num, "0.05")
        .of(Magnitude)
        .doc("lens radius; 0 is a pinhole. Default 0"),
    p("focus_distance", Ty::Num, "5")
        .of(Size)
        .doc("distance of the plane in focus (> 0). Default: the distance to `look_at`"),
    p("shutter", Ty::Vec2, "<0, 1>")
        .of(Magnitude)
        .doc("the time interval of the exposure, for motion blur. Default `<0, 0>`"),
    povray(
        "origin",
        "position",
        "Mitsuba's `origin` (of its camera's `look_at`) is `position` in ptsc",
    ),
    povray(
        "target",
        "look_at",
        "Mitsuba's `target` (of its camera's `look_at`) is `look_at` in ptsc",
    ),
];

/// `environment { }`
pub const ENVIRONMENT: &[ParamSpec] = &[
    p("file", Ty::Str, "\"studio.hdr\"")
        .doc("an equirectangular image (`.hdr`, `.exr`; `.png`, `.jpg` from sRGB), relative to the scene. Required"),
    p("intensity", Ty::Color, "rgb 1").of(Radiance)
        .doc("scales the image's radiance. Default `rgb 1`"),
    t("rotate", Ty::Vec3, "<0, 90, 0>")
        .doc("turns the map about x, then y, then z, in degrees (repeatable, in order)"),
];

/// `sky { }`
pub const SKY: &[ParamSpec] = &[
    p("sun_direction", Ty::Vec3, "<0.3, 0.6, -1>")
        .of(Direction)
        .excludes(&["sun_elevation", "sun_azimuth"])
        .doc("towards the sun, instead of the two angles (y ≥ 0)"),
    p("sun_elevation", Ty::Num, "35")
        .doc("the sun's height above the horizon in degrees, 0..90. Default 45"),
    p("sun_azimuth", Ty::Num, "20")
        .doc("where the sun stands in degrees: 0 towards −z, 90 towards +x. Default 0"),
    p("turbidity", Ty::Num, "3")
        .doc("haze, 1..10: 1–2 a clear mountain sky, 3 a clear day, 6–10 hazy. Default 3"),
    p("albedo", Ty::Color, "rgb 0.3").of(Magnitude).doc(
        "the ground's reflectance, 0..1, which brightens the sky near the horizon. Default 0.3",
    ),
    p("intensity", Ty::Color, "rgb 1")
        .of(Radiance)
        .doc("scales the sky. Default 1"),
    p("sun_intensity", Ty::Color, "rgb 1")
        .of(Radiance)
        .doc("scales the sun (0: the sky alone). Default 1"),
];

/// `atmosphere { }`
pub const ATMOSPHERE: &[ParamSpec] = &[
    p("absorption", Ty::Color, "rgb 0.01").of(Magnitude)
        .doc("light absorbed per scene unit travelled (σa, colour ≥ 0, up to 1e6). Default black"),
    p("scattering", Ty::Color, "rgb 0.05").of(Magnitude)
        .doc("light scattered per scene unit travelled (σs, colour ≥ 0, up to 1e6). Default black"),
    p("anisotropy", Ty::Num, "0.7")
        .doc("Henyey–Greenstein g, −0.999..0.999: 0 scatters evenly, > 0 forward (haze), < 0 back. Default 0"),
    p("density", Ty::Num, "0.05")
        .excludes(&["absorption", "scattering"])
        .doc("light stopped per scene unit (σt, 0..1e6), split by `medium_color`; instead of `absorption` and `scattering`"),
    p("medium_color", Ty::Color, "rgb 1")
        .doc("with `density`: the share of stopped light that scatters, per channel 0..1. Default white"),
    p("center", Ty::Vec3, "<0, 0, 0>").of(Magnitude)
        .doc("the centre of the ball the atmosphere fills. Default the centre of the scene's objects, camera and lights"),
    p("radius", Ty::Num, "100").of(Size)
        .doc("the radius of the ball the atmosphere fills (light from beyond it, a sky's or a sun's, crosses it). Default just around the objects, camera and lights"),
];

/// `material { }`
pub const MATERIAL: &[ParamSpec] = &[
    p("diffuse", Ty::Color, "rgb <0.8, 0.8, 0.8>")
        .of(Magnitude)
        .textured()
        .doc("Lambertian albedo, a colour or a texture. Default 0.5 grey when no lobe is given, else black"),
    p("reflection", Ty::Color, "rgb 1").of(Magnitude).textured()
        .doc("specular reflectance (a mirror; a metal's or a coat's tint), a colour or a texture. Default black"),
    p("gloss", Ty::Num, "0.3").textured()
        .doc("roughness of the reflection, 0..1 or a texture: 0 a mirror, 1 very rough (GGX α = gloss²). Default 0"),
    p("transmission", Ty::Num, "1").textured()
        .doc("weight of a smooth dielectric lobe (glass), 0..1 or a texture. Default 0"),
    p("ior", Ty::Num, "1.5")
        .doc("index of refraction inside (≥ 1). Default 1.5"),
    p("ior_outside", Ty::Num, "1.33")
        .doc("index of refraction of the medium outside (≥ 1; water 1.33). Default 1"),
    p("roughness", Ty::NumOrVec2, "<0.05, 0.3>")
        .excludes(&["gloss"])
        .doc("a metal's GGX α itself instead of `gloss`: one number, or `<α along u, α along v>`"),
    p("absorption", Ty::Color, "rgb <0.5, 0.1, 0.1>")
        .of(Magnitude)
        .textured()
        .doc("the medium inside a transparent object or a `type none` boundary: light absorbed per scene unit travelled (Beer's law; σa, colour ≥ 0 or texture). Default black"),
    p("scattering", Ty::Color, "rgb 0.5").of(Magnitude)
        .doc("the medium inside: light scattered per scene unit travelled (σs, colour ≥ 0, up to 1e6), with `transmission` or `type none`. Default black"),
    p("anisotropy", Ty::Num, "0.6")
        .doc("the medium's Henyey–Greenstein g, −0.999..0.999: 0 scatters evenly, > 0 forward (haze, water), < 0 back. Default 0"),
    p("density", Ty::Num, "0.5")
        .excludes(&["absorption", "scattering"])
        .doc("the medium inside: light stopped per scene unit (σt, 0..1e6), split by `medium_color` between scattering and absorption; instead of `absorption` and `scattering`"),
    p("medium_color", Ty::Color, "rgb <0.9, 0.95, 1>")
        .doc("with `density`: the share of stopped light that scatters, per channel 0..1 (the single-scattering albedo; 1 a white fog, lower absorbs). Default white"),
    p("emission", Ty::Color, "rgb 10").of(Radiance).textured()
        .doc("emitted radiance (colour ≥ 0 or texture): the object becomes an area light. Default black"),
    p("two_sided", Ty::Bool, "true")
        .doc("emission from both sides. Default `false`"),
    p("opacity", Ty::Num, "image { file \"leaf.png\" channel a }").textured()
        .doc("how much of the surface is there, 0..1 or a texture: rays pass where it is 0 (cutouts: leaves, fences), and through a fraction of it at random between. Default 1"),
    p("opacity_cutoff", Ty::Num, "0.5")
        .doc("with `opacity`: the surface is there where the opacity is at least this, and not at all elsewhere (a sharp cutout, glTF's `MASK`). Default none: fractions pass at random"),
    p("vertex_color", Ty::Bool, "true")
        .doc("multiplies the diffuse colour (a principled's `base_color`) by the mesh's vertex colours (a glTF's `COLOR_0`, an OBJ's `v x y z r g b`, a PLY's `red green blue`: whole numbers as sRGB, floats as linear), white where a surface has none. Default `false` (`true` for a glTF material whose primitives have colours)"),
    p(
        "normal_map",
        Ty::Texture,
        "image { file \"bricks_normal.png\" }",
    )
    .textured()
        .doc("a tangent-space normal map (texture) bending the shading normal. Default none"),
    p("normal_scale", Ty::Num, "0.5")
        .doc("with `normal_map`: scales the map's tangent and bitangent components before they are normalised (glTF's `normalTexture.scale`): 0 flattens it, more than 1 steepens it, −100..100. Default 1"),
    p("bump", Ty::Texture, "noise { scale 0.05 }").textured()
        .doc("a height field (texture) bending the shading normal, times `bump_height`. Default none"),
    p("bump_height", Ty::Num, "0.01").of(Magnitude)
        .doc("scene units of height per unit of the `bump` texture (negative: dents). Default 0.01"),
    p("type", Ty::Word(MATERIAL_TYPES), "plastic")
        .doc("the scattering model: `mix`, `conductor`, `plastic`, `dielectric`, `thin_dielectric`, `principled`, or `none` (no surface: the boundary of the medium inside). Default `mix`"),
    p("preset", Ty::Word(METAL_PRESETS), "gold")
        .excludes(&["eta", "k"])
        .doc("a named metal of `type conductor`: gold, silver, copper, aluminium, chromium"),
    p("eta", Ty::Color, "rgb <0.2, 0.92, 1.1>").of(Magnitude)
        .doc("a metal's index of refraction per channel (with `k`, instead of `preset`)"),
    p("k", Ty::Color, "rgb <3.9, 2.45, 2.14>").of(Magnitude)
        .doc("a metal's extinction coefficient per channel (with `eta`, instead of `preset`)"),
    p("multiscatter", Ty::Bool, "false")
        .doc("the multiple-scattering compensation of glossy reflection; `false` is plain GGX. Default `true`"),
    p("base_color", Ty::Color, "rgb <0.8, 0.2, 0.1>").of(Magnitude).textured()
        .doc("`type principled`: the base colour (diffuse albedo, a metal's reflectance), a colour or a texture. Default 0.5 grey"),
    p("metallic", Ty::Num, "1").textured()
        .doc("`type principled`: how much of it is metal, 0..1 or a texture. Default 0"),
    p("specular", Ty::Num, "0.5")
        .excludes(&["ior"])
        .doc("`type principled`: its dielectric reflectance head-on, 0..1 (0.5 is 4 %, η 1.5; instead of `ior`). Default 0.5"),
    p("specular_tint", Ty::Num, "0.5")
        .doc("`type principled`: how much of its dielectric reflection takes the base colour's hue, 0..1. Default 0"),
    p("anisotropic", Ty::Num, "0.6")
        .doc("`type principled`: how much the highlight stretches along the surface's ∂p/∂u, 0..1. Default 0"),
    p("sheen", Ty::Num, "1")
        .doc("`type principled`: a cloth-like rim at grazing angles, 0..1. Default 0"),
    p("sheen_tint", Ty::Num, "0.5")
        .doc("`type principled`: how much of the sheen takes the base colour's hue, 0..1. Default 0"),
    p("clearcoat", Ty::Num, "1")
        .doc("`type principled`: a clear varnish on top (a second, white highlight), 0..1. Default 0"),
    p("clearcoat_roughness", Ty::Num, "0.1")
        .doc("`type principled`: the varnish's roughness, 0..1 (Mitsuba's `clearcoat_gloss` is 1 minus it). Default 0"),
];

/// The scattering models a material's `type` names (`mix`, the paper's
/// weighted lobes, when none is given).
pub const MATERIAL_TYPES: &[&str] = &super::scene::MaterialType::WORDS;

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
    p("channel", Ty::Word(CHANNELS), "a").doc(
        "the channel a number is read from: `r`, `g`, `b` or `a` (alpha; an image without one is opaque). Default: the luminance",
    ),
];

/// The channels an image can be read from (`image { channel … }`).
pub const CHANNELS: &[&str] = &crate::texture::image::Channel::WORDS;

/// How an image's values are encoded (`image { color_space … }`).
pub const COLOR_SPACES: &[&str] = &super::scene::ColorSpace::WORDS;

/// The spaces a texture's pattern can live in.
pub const TEXTURE_SPACES: &[&str] = &super::scene::TextureSpace::WORDS;

/// `checker { }`, besides the transforms of [`SHAPE_COMMON`] (velocity
/// excepted).
pub const CHECKER: &[ParamSpec] = &[
    p("even", Ty::Color, "rgb 0.9").of(Magnitude),
    p("odd", Ty::Color, "rgb 0.1").of(Magnitude),
    p("space", Ty::Word(TEXTURE_SPACES), "object"),
    povray(
        "color0",
        "even",
        "Mitsuba's `color0` (the cell at the origin) is `even` in ptsc",
    ),
    povray("color1", "odd", "Mitsuba's `color1` is `odd` in ptsc"),
];

/// The transforms a texture takes (its pattern moves, turns and scales).
pub const TEXTURE_TRANSFORMS: &[ParamSpec] = &[
    t("translate", Ty::Vec3, "<0.5, 0, 0>").of(Magnitude),
    t("rotate", Ty::Vec3, "<0, 0, 45>"),
    t("scale", Ty::NumOrVec3, "0.25").of(Quantity::Scale),
];

/// The parameters a block of `schemas` accepts, as its errors and hover
/// list them: the rows but POV-Ray's refused words, then `material` where
/// the block takes one.
pub fn accepted_names(schemas: &[&'static [ParamSpec]], takes_material: bool) -> Vec<&'static str> {
    (schemas.iter().flat_map(|s| s.iter()))
        .filter(|p| p.povray.is_none())
        .map(|p| p.name)
        .chain(takes_material.then_some("material"))
        .collect()
}

/// The preset that a metal's other name stands for: the preset in any
/// case (`Gold`), Mitsuba's element symbols (`Au`, as its conductor's
/// `material "Au"` writes them), the American spelling.
pub fn metal_preset(name: &str) -> Option<&'static str> {
    let lower = name.to_ascii_lowercase();
    if let Some(preset) = METAL_PRESETS.iter().find(|p| **p == lower) {
        return Some(preset);
    }
    Some(match lower.as_str() {
        "chrome" | "chromium_metal" | "cr" => "chromium",
        "aluminum" | "aluminum_metal" | "alu" | "al" => "aluminium",
        "au" => "gold",
        "ag" => "silver",
        "cu" => "copper",
        _ => return None,
    })
}

/// The help for a metal `name` that is not one of the presets: the
/// preset it is another name for, or how to give a metal's constants.
pub fn other_metal(name: &str) -> Option<String> {
    if let Some(preset) = metal_preset(name) {
        return Some(format!("did you mean `{preset}`?"));
    }
    let look = match name.to_ascii_lowercase().as_str() {
        "brass" | "bronze" => " (`preset gold` or `preset copper` looks close)",
        "steel" | "iron" | "stainless" | "nickel" | "titanium" | "platinum" | "tin" | "zinc" => {
            " (`preset chromium` or `preset aluminium` looks close)"
        }
        _ => return None,
    };
    Some(format!(
        "`{name}` is not a preset{look}; for any metal, remove `preset` and give its complex index of refraction per channel: `eta rgb <…> k rgb <…>` (tables of n and k: refractiveindex.info, or Mitsuba 3's data/ior)"
    ))
}
