//! Why two render states cannot hold samples of one image, said in the
//! user's terms: the flags and scene settings that differ with the values
//! as they are typed (`--clamp 1`, `uniform`), for a `--resume` refused
//! and for `ptsc merge` of parts that do not belong together.

/// The first difference found between a saved state's description and
/// another's (this render's, or another part's).
#[derive(Debug, Clone, PartialEq)]
pub enum Mismatch {
    /// Drawn by other versions of ptsc.
    Ptsc {
        /// The saved state's version.
        saved: String,
        /// The other's.
        now: String,
    },
    /// Of scenes whose fingerprints differ, by their file names.
    Scene {
        /// The saved state's scene file.
        saved: String,
        /// The other's.
        now: String,
    },
    /// A setting that shapes the samples, by its state name, with each
    /// side's stored value (`None`: that side does not name it).
    Setting {
        /// The setting's name in a state (`seed`, `clamp`, `size`…).
        name: String,
        /// The saved state's value.
        saved: Option<String>,
        /// The other's.
        now: Option<String>,
    },
}

/// The words a fingerprint covers, for a scene that changed.
const SCENE_PARTS: &str = "objects, materials, lights, camera or data files";

impl Mismatch {
    /// Why a `--resume` from the saved state is refused: "it was rendered
    /// without --clamp, this render with --clamp 1".
    pub fn for_resume(&self) -> String {
        match self {
            Mismatch::Ptsc { saved, now } => {
                format!("it was made by ptsc {saved}, this is ptsc {now}")
            }
            Mismatch::Scene { saved, now } if saved == now => {
                format!("its scene differs: {saved} ({SCENE_PARTS}) changed since")
            }
            Mismatch::Scene { saved, now } => {
                format!("it holds a render of {saved}, not of {now}")
            }
            Mismatch::Setting { name, saved, now } => format!(
                "it was rendered {}, this render {}",
                rendered(name, saved.as_deref()),
                rendered(name, now.as_deref())
            ),
        }
    }

    /// Why `part` is no part of the render `first` belongs to, the saved
    /// side being `first`'s: "it was rendered with seed 5, part_1.exr with
    /// seed 0".
    pub fn between_parts(&self, first: &str) -> String {
        match self {
            Mismatch::Ptsc { saved, now } => {
                format!("it was made by ptsc {now}, {first} by ptsc {saved}")
            }
            Mismatch::Scene { saved, now } if saved == now => format!(
                "it is a part of another version of {now} (its {SCENE_PARTS} differ from {first}'s)"
            ),
            Mismatch::Scene { saved, now } => {
                format!("it is a part of {now}, {first} of {saved}")
            }
            Mismatch::Setting { name, saved, now } => format!(
                "it was rendered {}, {first} {}",
                rendered(name, now.as_deref()),
                rendered(name, saved.as_deref())
            ),
        }
    }
}

/// What follows "rendered" for a setting of a state at its stored value:
/// "with seed 5", "without --clamp", "with the path integrator".
fn rendered(name: &str, stored: Option<&str>) -> String {
    let value = stored.and_then(shown);
    match (name, value) {
        ("size", Some(v)) => format!("at {v}"),
        ("seed", Some(v)) => format!("with seed {v}"),
        ("integrator" | "sampler", Some(v)) => format!("with the {v} {name}"),
        ("clamp", Some(v)) => format!("with --clamp {v}"),
        ("clamp", None) => "without --clamp".into(),
        ("light_selection", Some(v)) => format!("with light selection {v}"),
        ("noise_threshold", Some(v)) => format!("with adaptive sampling (--noise {v})"),
        ("noise_threshold", None) => "without adaptive sampling (--noise)".into(),
        ("min_samples", Some(v)) => format!("with --min-samples {v}"),
        ("half_images", Some(_)) => "keeping the half images of --aov variance".into(),
        ("half_images", None) => "without the half images of --aov variance".into(),
        ("light_film", Some(_)) => "with a light film (bdpt, ptlt)".into(),
        ("light_film", None) => "without a light film (bdpt, ptlt)".into(),
        // The scene's own parameter names (`max_depth 8`).
        (_, Some(v)) => format!("with {name} {v}"),
        (_, None) => format!("without {name}"),
    }
}

/// A stored value as a user types it, `None` for a setting that is off.
/// States keep some values in the form they were first written in
/// (`None`, `Some(1.0)`, `Auto`, `Vec3(0.1, 0.1, 0.1)`), and states on
/// disk must still resume, so the text is translated here rather than
/// changed in the file.
fn shown(stored: &str) -> Option<String> {
    let v = stored.trim();
    if v == "None" {
        return None;
    }
    if let Some(inner) = v.strip_prefix("Some(").and_then(|r| r.strip_suffix(')')) {
        return shown(inner);
    }
    if let Some(inner) = v.strip_prefix("Vec3(").and_then(|r| r.strip_suffix(')')) {
        let parts: Vec<String> = inner.split(',').map(|p| number(p.trim())).collect();
        return Some(format!("<{}>", parts.join(", ")));
    }
    // An enumeration's name (`Auto`): the scene's and the flag's word.
    if v.chars().all(|c| c.is_ascii_alphabetic()) && v.starts_with(|c: char| c.is_uppercase()) {
        return Some(v.to_ascii_lowercase());
    }
    Some(number(v))
}

/// A number as a user writes it: `1` rather than `1.0`.
fn number(v: &str) -> String {
    match v.strip_suffix(".0") {
        Some(whole) if v.parse::<f64>().is_ok() => whole.to_string(),
        _ => v.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setting(name: &str, saved: Option<&str>, now: Option<&str>) -> Mismatch {
        Mismatch::Setting {
            name: name.into(),
            saved: saved.map(Into::into),
            now: now.map(Into::into),
        }
    }

    #[test]
    fn settings_are_said_as_the_user_types_them() {
        let clamp = setting("clamp", Some("None"), Some("Some(1.0)"));
        assert_eq!(
            clamp.for_resume(),
            "it was rendered without --clamp, this render with --clamp 1"
        );
        let rule = setting("light_selection", Some("Auto"), Some("Uniform"));
        assert_eq!(
            rule.for_resume(),
            "it was rendered with light selection auto, this render with light selection uniform"
        );
        let noise = setting("noise_threshold", None, Some("0.1"));
        assert_eq!(
            noise.for_resume(),
            "it was rendered without adaptive sampling (--noise), this render with adaptive sampling (--noise 0.1)"
        );
        let ambient = setting(
            "ambient",
            Some("Vec3(0.0, 0.0, 0.0)"),
            Some("Vec3(0.5, 0.0, 0.0)"),
        );
        assert_eq!(
            ambient.for_resume(),
            "it was rendered with ambient <0, 0, 0>, this render with ambient <0.5, 0, 0>"
        );
        for text in [clamp, rule, noise, ambient].map(|m| m.for_resume()) {
            for debug in ["None", "Some(", "Auto", "Uniform", "Vec3"] {
                assert!(!text.contains(debug), "{text}");
            }
        }
    }

    #[test]
    fn parts_are_said_each_with_its_own_value() {
        let seed = setting("seed", Some("0"), Some("5"));
        assert_eq!(
            seed.between_parts("part_1.exr"),
            "it was rendered with seed 5, part_1.exr with seed 0"
        );
        let scene = Mismatch::Scene {
            saved: "mitsuba.pts".into(),
            now: "other.pts".into(),
        };
        assert_eq!(
            scene.between_parts("part_1.exr"),
            "it is a part of other.pts, part_1.exr of mitsuba.pts"
        );
        assert!(!scene.between_parts("part_1.exr").contains("changed since"));
    }
}
