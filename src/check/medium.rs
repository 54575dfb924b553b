//! A medium's parameters, read alike inside a material (what fills a
//! transparent object or a `type none` boundary) and in `atmosphere { }`:
//! the coefficients per unit length (`absorption`, `scattering`, as pbrt's
//! and Mitsuba's σa and σs) or the artist's form (`density`, the extinction,
//! and `medium_color`, the share of it that scatters: Mitsuba's `albedo`),
//! and the Henyey–Greenstein `anisotropy`.

use super::params::Params;
use super::reader::{range_error, Reader};
use super::scene::{MediumParams, Rgb};
use crate::diag::{codes, Diagnostic, Diagnostics};

/// The largest coefficient or density, per scene unit: light crosses
/// 10⁻⁶ units of it before it scatters, far below anything a scene draws.
pub const MAX_DENSITY: f64 = 1e6;

/// The largest |anisotropy|: at ±1 the phase function is a delta.
pub const MAX_ANISOTROPY: f64 = 0.999;

/// The words that make a medium (the material's `absorption` is also
/// Beer's law in glass).
pub const MEDIUM_WORDS: [&str; 4] = ["scattering", "anisotropy", "density", "medium_color"];

/// Reads a block's medium; `absorption` is the one read already (a
/// material's may come from a texture).
pub fn read(p: &Params, absorption: Rgb, diags: &mut Diagnostics) -> MediumParams {
    let mut r = Reader { p, diags };
    let mut m = MediumParams {
        absorption,
        scattering: r.color("scattering", [0.0; 3]),
        anisotropy: r.num_in("anisotropy", -MAX_ANISOTROPY, MAX_ANISOTROPY, false, 0.0),
    };
    for name in ["absorption", "scattering"] {
        if let Some((_, s)) = p.get(name) {
            let c = if name == "absorption" {
                m.absorption
            } else {
                m.scattering
            };
            if c.iter().any(|x| *x > MAX_DENSITY) {
                let what = p.what.clone();
                diags.push(range_error(
                    &what,
                    name,
                    *s,
                    "at most 1000000 per unit",
                    "light meets it within a millionth of a unit".into(),
                ));
                if name == "absorption" {
                    m.absorption = [0.0; 3];
                } else {
                    m.scattering = [0.0; 3];
                }
            }
        }
    }
    let mut r = Reader { p, diags };
    let color = r.color("medium_color", [1.0; 3]);
    let density = r.num_in("density", 0.0, MAX_DENSITY, false, 0.0);
    if let Some((_, s)) = p.get("medium_color") {
        if color.iter().any(|x| *x > 1.0) {
            diags.push(
                Diagnostic::error(codes::OUT_OF_RANGE, "`medium_color` above 1", *s)
                    .with_label("the share of light that scatters")
                    .with_help("keep every component of `medium_color` between 0 and 1: a medium cannot scatter more light than it stops"),
            );
            return m;
        }
        if !p.given("density") {
            diags.push(
                Diagnostic::warning(
                    codes::NO_EFFECT,
                    "`medium_color` has no effect without `density`",
                    *s,
                )
                .with_label("ignored")
                .with_help(
                    "give the medium a `density` (how much it stops per unit), e.g. `density 0.5`",
                ),
            );
        }
    }
    if let Some((_, s)) = p.get("density") {
        for other in ["absorption", "scattering"] {
            if p.given(other) {
                diags.push(
                    Diagnostic::error(
                        codes::CONFLICTING_PARAMS,
                        format!("`density` and `{other}` both give the medium"),
                        *s,
                    )
                    .with_label("density and medium_color make absorption and scattering")
                    .with_help("give `density` (and `medium_color`), or `absorption` and `scattering`, not both"),
                );
                return m;
            }
        }
        m.scattering = color.map(|c| density * c);
        m.absorption = color.map(|c| density * (1.0 - c));
    }
    m
}

/// Warns about each medium word of a material that has no inside (it is
/// neither transparent nor `type none`).
pub fn warn_without_inside(p: &Params, diags: &mut Diagnostics) {
    for name in MEDIUM_WORDS {
        if let Some((_, s)) = p.get(name) {
            diags.push(
                Diagnostic::warning(
                    codes::NO_EFFECT,
                    format!("`{name}` has no effect without `transmission`"),
                    *s,
                )
                .with_label("ignored")
                .with_help("a medium fills transparent objects: add `transmission 1` (glass, water), or `type none` for fog or smoke without a surface"),
            );
        }
    }
}
