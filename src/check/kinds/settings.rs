//! The settings blocks: `render`, `camera`, `environment`, `sky` and
//! `atmosphere`, each
//! given at most once at the top level of a scene (the checker keeps them;
//! see `check/block_statement.rs`).

use super::super::schema;
use super::kind::{Kind, Role, Setting};

/// The rows of this file, in the order the docs list them.
pub const ALL: &[&Kind] = &[&RENDER, &CAMERA, &ENVIRONMENT, &SKY, &ATMOSPHERE];

/// `render { }`
pub const RENDER: Kind = Kind {
    name: "render",
    summary: "the render's settings: resolution, samples, integrator, output",
    params: schema::RENDER,
    role: Role::Setting(Setting::Render),
    positional: None,
    povray: &[("global_settings", "POV-Ray's `global_settings` are in ptsc's `render { … }`: `resolution`, `samples`, `max_depth`, `integrator`, …")],
};

/// `camera { }`
pub const CAMERA: Kind = Kind {
    name: "camera",
    summary: "the camera: a pinhole, or a thin lens with `aperture`",
    params: schema::CAMERA,
    role: Role::Setting(Setting::Camera),
    positional: None,
    povray: &[],
};

/// `environment { }`
pub const ENVIRONMENT: Kind = Kind {
    name: "environment",
    summary: "light from every direction from an equirectangular image (`.hdr`, `.exr`)",
    params: schema::ENVIRONMENT,
    role: Role::Setting(Setting::Environment),
    positional: None,
    povray: &[("envmap", "Mitsuba's `envmap` emitter is `environment { file \"sky.exr\" }` in ptsc (its `scale` is `intensity`)")],
};

/// `sky { }`
pub const SKY: Kind = Kind {
    name: "sky",
    summary: "a daylight sky and its sun (Hošek–Wilkie), lighting the scene",
    params: schema::SKY,
    role: Role::Setting(Setting::Sky),
    positional: None,
    povray: &[("sky_sphere", "ptsc's `sky { … }` (a daylight sky and sun), `environment { … }` (an HDR image) or `background rgb …` is light from every direction, and lights the scene")],
};

/// `atmosphere { }`
pub const ATMOSPHERE: Kind = Kind {
    name: "atmosphere",
    summary: "a medium filling the air around the objects: fog, haze, light shafts",
    params: schema::ATMOSPHERE,
    role: Role::Setting(Setting::Atmosphere),
    positional: None,
    povray: &[("fog", "POV-Ray's `fog { … }` is ptsc's `atmosphere { density 0.05  medium_color rgb 1 }`: a medium that scatters light (light shafts come with it) rather than a blend towards a colour")],
};
