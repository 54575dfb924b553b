//! The lights that are not shapes: point, spot and directional lights, each
//! with its parameters and the function that checks them into a [`Light`].

use super::super::params::Params;
use super::super::reader::Reader;
use super::super::scene::{Light, Rgb};
use super::super::schema::{p, povray, ParamSpec, Ty, LIGHT_COLOR, LIGHT_COLOUR, SPOT_ANGLES};
use super::kind::{Kind, Role};
use crate::check::domain::Quantity::{Direction, Magnitude, Radiance};
use crate::diag::{codes, Diagnostic, Diagnostics};

/// The rows of this file, in the order the docs list them.
pub const ALL: &[&Kind] = &[&POINT_LIGHT, &SPOT_LIGHT, &DIRECTIONAL_LIGHT];

/// `point_light { }`
pub const POINT_LIGHT: Kind = Kind {
    name: "point_light",
    summary: "a light at a point, the same in every direction, falling off with the squared distance",
    params: &[
        p("position", Ty::Vec3, "<0, 5, 0>").of(Magnitude).doc("where the light is. Required"),
        p("intensity", Ty::Color, "rgb 100")
            .of(Radiance)
            .doc("radiant intensity in W/sr: a surface facing the light d away gets intensity / d². Required"),
        povray("color", "intensity", LIGHT_COLOR),
        povray("colour", "intensity", LIGHT_COLOUR),
    ],
    role: Role::Light(point_light),
    positional: Some((&["position", "intensity"], "ptsc's lights fall off with the squared distance (POV-Ray's do not unless told): an `intensity` of about 1.9 × POV-Ray's colour × the squared distance to what it lights looks alike there")),
    povray: &[("light_source", "POV-Ray's `light_source` is `point_light { position <x, y, z> intensity rgb … }` in ptsc (also `spot_light`, `directional_light`)")],
};

/// `spot_light { }`
pub const SPOT_LIGHT: Kind = Kind {
    name: "spot_light",
    summary: "a point light limited to a cone, with a smooth fall-off from `hotspot` to `angle`",
    params: &[
        p("position", Ty::Vec3, "<0, 5, 0>").of(Magnitude).doc("where the light is. Required"),
        p("look_at", Ty::Vec3, "<0, 0, 0>").of(Magnitude).doc("the point on the cone's axis. Required"),
        p("intensity", Ty::Color, "rgb 100")
            .of(Radiance)
            .doc("radiant intensity on the axis in W/sr. Required"),
        p("angle", Ty::Num, "30").doc("the cone's half-angle in degrees, where the light ends, 0..90. Default 30"),
        p("hotspot", Ty::Num, "25")
            .doc("the half-angle of full light in degrees, where the fall-off to `angle` starts, 0..`angle`. Default `angle` (a hard edge)"),
        povray("falloff", "angle", SPOT_ANGLES),
        povray("radius", "hotspot", SPOT_ANGLES),
        povray("tightness", "hotspot", "POV-Ray's `tightness` has no ptsc equivalent: the light falls off smoothly from `hotspot` to `angle`"),
        povray("point_at", "look_at", "POV-Ray's `point_at` is `look_at` in ptsc"),
        povray("color", "intensity", LIGHT_COLOR),
        povray("colour", "intensity", LIGHT_COLOUR),
    ],
    role: Role::Light(spot_light),
    positional: None,
    povray: &[("spotlight", "a spot light is its own block: `spot_light { position … look_at … intensity … angle … }`")],
};

/// `directional_light { }`
pub const DIRECTIONAL_LIGHT: Kind = Kind {
    name: "directional_light",
    summary: "light from one direction from infinitely far away, as the sun's",
    params: &[
        p("direction", Ty::Vec3, "<0, -1, 0>")
            .of(Direction)
            .doc("the way the light travels (from the light to the scene). Required"),
        p("irradiance", Ty::Color, "rgb 3")
            .of(Radiance)
            .doc("irradiance in W/m² on a surface facing the light. Required"),
    ],
    role: Role::Light(directional_light),
    positional: None,
    povray: &[],
};

/// A required colour of a light.
fn need_color(r: &mut Reader, name: &'static str, schema: &[ParamSpec]) -> Option<Rgb> {
    r.p.require(name, schema, r.diags)?;
    Some(r.color(name, [0.0; 3]))
}

/// `point_light { }` → a point light.
fn point_light(p: &Params, diags: &mut Diagnostics) -> Option<Light> {
    let schema = POINT_LIGHT.params;
    let mut r = Reader { p, diags };
    let pos = r.vec3_req("position", schema);
    let i = need_color(&mut r, "intensity", schema);
    Some(Light::Point {
        position: pos?.0,
        intensity: i?,
    })
}

/// `spot_light { }` → a spot light.
fn spot_light(p: &Params, diags: &mut Diagnostics) -> Option<Light> {
    let schema = SPOT_LIGHT.params;
    let mut r = Reader { p, diags };
    let pos = r.vec3_req("position", schema);
    let at = r.vec3_req("look_at", schema);
    let i = need_color(&mut r, "intensity", schema);
    let errors_before = r.diags.errors_pushed();
    let angle = r.num_in("angle", 0.0, 90.0, true, 30.0);
    let angle_refused = r.diags.errors_pushed() > errors_before;
    let hotspot = spot_hotspot(&mut r, angle, angle_refused);
    let (pos, s) = pos?;
    let dir = at?.0 - pos;
    if dir.length_squared() == 0.0 {
        r.diags.push(
            Diagnostic::error(
                codes::DEGENERATE,
                "the spot light points at its own position",
                s,
            )
            .with_label("`position` equals `look_at`")
            .with_help("aim `look_at` at the lit point"),
        );
        return None;
    }
    Some(Light::Spot {
        position: pos,
        direction: dir.normalize(),
        intensity: i?,
        angle,
        hotspot,
    })
}

/// A spot light's `hotspot`, within its `angle` (`angle_refused`: the
/// angle written had an error of its own, and the default stands in: the
/// hotspot is then not measured against it).
fn spot_hotspot(r: &mut Reader, angle: f64, angle_refused: bool) -> f64 {
    let hotspot = r.num_in("hotspot", 0.0, 90.0, false, angle);
    match r.num("hotspot") {
        // Within 0..90 (else its range error is said) but past the angle.
        Some((x, span)) if x == hotspot && x > angle && !angle_refused => {
            let angle_said = match r.p.get("angle") {
                Some(_) => format!("its `angle` is {angle}"),
                None => format!("its `angle` is {angle}, the default"),
            };
            r.diags.push(
                Diagnostic::error(
                    codes::OUT_OF_RANGE,
                    "`hotspot` of `spot_light` must be at most its `angle`",
                    span,
                )
                .with_label(format!("`hotspot` is {x} here; {angle_said}"))
                .with_help(format!(
                    "the full-light cone lies inside the light's cone: give `angle {x}` or more, or a smaller `hotspot`"
                )),
            );
            angle
        }
        _ => hotspot.min(angle),
    }
}

/// `directional_light { }` → a directional light.
fn directional_light(p: &Params, diags: &mut Diagnostics) -> Option<Light> {
    let schema = DIRECTIONAL_LIGHT.params;
    let mut r = Reader { p, diags };
    let d = r.direction("direction", schema);
    let e = need_color(&mut r, "irradiance", schema);
    Some(Light::Directional {
        direction: d?,
        irradiance: e?,
    })
}
