//! Each block kind, checked: values in range, defaults filled in, the result
//! a piece of the checked [`Scene`](super::scene::Scene).

use super::params::{Params, Val};
use super::reader::{range_error, Reader, WholeSetting};
use super::scene::*;
use crate::diag::codes;
use crate::diag::{Diagnostic, Diagnostics};
use crate::span::Span;
use glam::DVec3;
use std::path::Path;

pub use crate::ir::settings::{MAX_PIXELS, MAX_SIDE, MAX_TIME};

/// Samples per pixel (`samples`, `--spp`).
pub const SAMPLES: WholeSetting = WholeSetting {
    name: "samples",
    min: 1,
    max: crate::ir::settings::MAX_SAMPLES as u64,
};
/// Samples before adaptive sampling may stop a pixel (`min_samples`,
/// `--min-samples`): at least two, to compare its two halves.
pub const MIN_SAMPLES: WholeSetting = WholeSetting {
    name: "min_samples",
    min: 2,
    max: 1_000_000,
};
/// The largest `noise_threshold` (`--noise`): past it every pixel stops
/// at its first chance.
pub const MAX_NOISE: f64 = 1.0;
/// The random seed (`seed`, `--seed`).
pub const SEED: WholeSetting = WholeSetting {
    name: "seed",
    min: 0,
    max: u32::MAX as u64,
};

/// `render { }` → settings.
pub fn render_settings(p: &Params, base_dir: &Path, diags: &mut Diagnostics) -> RenderSettings {
    let mut r = Reader { p, diags };
    let d = Settings::default();
    let (mut width, mut height) = (d.width, d.height);
    if let Some((Val::Vector(v), s)) = p.get("resolution") {
        let ok_side = |x: f64| x.fract() == 0.0 && (1.0..=MAX_SIDE).contains(&x);
        if !ok_side(v[0]) || !ok_side(v[1]) {
            r.diags.push(range_error(
                "render",
                "resolution",
                *s,
                "whole numbers from 1 to 16384",
                format!(
                    "the image is {} × {} here; try `resolution <512, 512>`",
                    v[0], v[1]
                ),
            ));
        } else if v[0] * v[1] > MAX_PIXELS {
            r.diags.push(range_error(
                "render",
                "resolution",
                *s,
                "at most 67,108,864 pixels (8192 × 8192)",
                format!(
                    "{} × {} pixels would not fit in memory; render a smaller image",
                    v[0], v[1]
                ),
            ));
        } else {
            width = v[0] as u32;
            height = v[1] as u32;
        }
    }
    let integrator = match p.get("integrator") {
        Some((Val::Word(w), _)) => IntegratorKind::from_name(w).unwrap_or(d.integrator),
        _ => d.integrator,
    };
    let light_selection = match p.get("light_selection") {
        Some((Val::Word(w), _)) => LightSelection::from_name(w).unwrap_or(d.light_selection),
        _ => d.light_selection,
    };
    let sampler = match p.get("sampler") {
        Some((Val::Word(w), _)) => SamplerKind::from_name(w).unwrap_or(d.sampler),
        _ => d.sampler,
    };
    // A time budget without a sample count renders until the time is spent.
    let time = r
        .num("time")
        .map(|_| r.num_in("time", 0.0, MAX_TIME, true, 60.0));
    let samples = match (time, p.get("samples")) {
        (Some(_), None) => SAMPLES.max,
        _ => r.whole(SAMPLES, d.samples as u64),
    };
    let adaptive = r.num("noise_threshold").map(|_| Adaptive {
        threshold: r.num_in("noise_threshold", 0.0, MAX_NOISE, true, 0.01) as f32,
        min_samples: r.whole(MIN_SAMPLES, DEFAULT_MIN_SAMPLES as u64) as u32,
    });
    if let (None, Some((_, span))) = (adaptive, r.num("min_samples")) {
        r.diags.push(
            Diagnostic::warning(
                codes::NO_EFFECT,
                "`min_samples` does nothing without `noise_threshold`".to_string(),
                span,
            )
            .with_help(
                "add `noise_threshold 0.01` to stop converged pixels early, or drop `min_samples`",
            ),
        );
    }
    let clamp = r
        .num("clamp")
        .map(|_| r.num_in("clamp", 0.0, f64::INFINITY, true, f64::INFINITY));
    // Each value within its range, rounded once to the renderer's f32.
    let settings = Settings {
        width,
        height,
        samples: samples as u32,
        max_depth: r.num_in("max_depth", 1.0, 1024.0, false, d.max_depth as f64) as u32,
        integrator,
        seed: r.whole(SEED, 0),
        sampler,
        ambient: glam::DVec3::from_array(r.color("ambient", [0.0; 3])).as_vec3(),
        rr_depth: r.num_in("rr_depth", 1.0, 1024.0, false, d.rr_depth as f64) as u32,
        hybrid_weight: r.num_in("hybrid_weight", 0.0, 1.0, false, d.hybrid_weight as f64) as f32,
        clamp: clamp.filter(|c| c.is_finite()).map(|c| c as f32),
        light_sampling: r.boolean("light_sampling", true),
        light_selection,
        light_samples: r.num_in("light_samples", 0.0, 1024.0, false, d.light_samples as f64) as u32,
        exposure: r.num_in("exposure", -32.0, 32.0, false, 0.0) as f32,
        time,
        adaptive,
    };
    let (output, output_span) = match p.get("output") {
        Some((Val::Str(s), span)) => (Some(base_dir.join(s)), Some(*span)),
        _ => (None, None),
    };
    RenderSettings {
        settings,
        output,
        output_span,
    }
}

/// `camera { }` → camera.
pub fn camera(p: &Params, span: Span, diags: &mut Diagnostics) -> Option<Camera> {
    let schema = super::schema::CAMERA;
    let mut r = Reader { p, diags };
    let position = r.vec3_req("position", schema);
    let look_at = r.vec3_req("look_at", schema);
    let up = r.vec3("up").map(|v| v.0).unwrap_or(DVec3::Y);
    let fov = r.num_in("fov", 0.0, 179.0, true, 40.0);
    let aperture = r.num_in("aperture", 0.0, f64::INFINITY, false, 0.0);
    let focus = r
        .num("focus_distance")
        .map(|_| r.num_in("focus_distance", 0.0, f64::INFINITY, true, 1.0));
    let mut shutter = (0.0, 0.0);
    if let Some((Val::Vector(v), s)) = p.get("shutter") {
        if v[0] > v[1] {
            r.diags.push(range_error(
                "camera",
                "shutter",
                *s,
                "an interval <open, close> with open ≤ close",
                format!("swap them: `shutter <{}, {}>`", v[1], v[0]),
            ));
        } else {
            shutter = (v[0], v[1]);
        }
    }
    let (position, pspan) = position?;
    let (look_at, _) = look_at?;
    let dir = look_at - position;
    if dir.length_squared() == 0.0 {
        r.diags.push(
            Diagnostic::error(
                codes::DEGENERATE,
                "the camera looks at its own position",
                pspan,
            )
            .with_label("`position` equals `look_at`")
            .with_help("move `look_at` to the point the camera should face"),
        );
        return None;
    }
    let unit = |v| super::domain::unit(v).unwrap_or(DVec3::ZERO);
    if unit(dir).cross(unit(up)).length_squared() < 1e-12 {
        let s = p.get("up").map(|v| v.1).unwrap_or(p.head);
        r.diags.push(
            Diagnostic::error(
                codes::DEGENERATE,
                "the camera's `up` is parallel to its view direction",
                s,
            )
            .with_label("`up` points along the view")
            .with_help(
                "pick an `up` that is not parallel to `look_at - position`, e.g. `up <0, 0, 1>`",
            ),
        );
        return None;
    }
    Some(Camera {
        position,
        look_at,
        up,
        fov,
        aperture,
        focus_distance: focus.unwrap_or(dir.length()),
        shutter,
        span,
    })
}

/// `environment { }` → the environment map (its file relative to `base`).
pub fn environment(
    p: &Params,
    base: &Path,
    span: Span,
    diags: &mut Diagnostics,
) -> Option<Environment> {
    let schema = super::schema::ENVIRONMENT;
    let (file, path_span) = match p.require("file", schema, diags)? {
        (Val::Str(f), s) => (f.clone(), *s),
        _ => return None,
    };
    let rotation = super::objects::transform(p, diags);
    let mut r = Reader { p, diags };
    let intensity = r.color("intensity", [1.0; 3]);
    Some(Environment {
        path: base.join(&file),
        name: file,
        path_span,
        intensity,
        rotation,
        span,
    })
}

/// `sky { }` → the daylight sky: the sun's direction from `sun_direction`
/// or from `sun_elevation` and `sun_azimuth` (degrees; azimuth 0 puts the
/// sun ahead, towards −z, 90 to the right, towards +x), above the horizon.
pub fn sky(p: &Params, span: Span, diags: &mut Diagnostics) -> Option<Sky> {
    let schema = super::schema::SKY;
    let mut r = Reader { p, diags };
    let angles = p.given("sun_elevation") || p.given("sun_azimuth");
    let direction = if p.given("sun_direction") {
        if let (true, Some((_, s))) = (angles, p.get("sun_direction")) {
            r.diags.push(
                Diagnostic::error(
                    codes::CONFLICTING_PARAMS,
                    "`sun_direction` and `sun_elevation`/`sun_azimuth` both place the sun",
                    *s,
                )
                .with_label("a direction")
                .with_help("give the sun a direction or an elevation and azimuth, not both"),
            );
        }
        r.direction("sun_direction", schema)?
    } else {
        let elevation = r
            .num_in("sun_elevation", 0.0, 90.0, false, 45.0)
            .to_radians();
        let azimuth = r
            .num_in("sun_azimuth", -360.0, 360.0, false, 0.0)
            .to_radians();
        DVec3::new(
            azimuth.sin() * elevation.cos(),
            elevation.sin(),
            -azimuth.cos() * elevation.cos(),
        )
    };
    let turbidity = r.num_in("turbidity", 1.0, 10.0, false, 3.0);
    let albedo = r.color("albedo", [0.3; 3]);
    if let Some((_, s)) = p.get("albedo").filter(|_| albedo.iter().any(|c| *c > 1.0)) {
        let what = p.what.clone();
        r.diags.push(range_error(
            &what,
            "albedo",
            *s,
            "between 0 and 1",
            "the ground's albedo is a reflectance".into(),
        ));
    }
    if direction.y < 0.0 {
        let s = p.get("sun_direction").map_or(span, |v| v.1);
        let what = p.what.clone();
        r.diags.push(range_error(
            &what,
            "sun_direction",
            s,
            "above the horizon (y ≥ 0)",
            "the sky model covers daylight: the sun between the horizon and the zenith".into(),
        ));
        return None;
    }
    Some(Sky {
        sun_direction: direction,
        turbidity,
        albedo: albedo.map(|c| c.min(1.0)),
        intensity: r.color("intensity", [1.0; 3]),
        sun_intensity: r.color("sun_intensity", [1.0; 3]),
        span,
    })
}

/// `atmosphere { }` → the medium around the objects.
pub fn atmosphere(p: &Params, span: Span, diags: &mut Diagnostics) -> Atmosphere {
    let mut r = Reader { p, diags };
    let absorption = r.color("absorption", [0.0; 3]);
    let medium = super::medium::read(p, absorption, diags);
    let mut r = Reader { p, diags };
    let center = match p.get("center") {
        Some((Val::Vector(v), _)) if v.len() == 3 => Some(DVec3::new(v[0], v[1], v[2])),
        _ => None,
    };
    let radius = p
        .given("radius")
        .then(|| r.num_in("radius", 0.0, 1e9, true, 1.0));
    Atmosphere {
        medium,
        center,
        radius,
        span,
    }
}
