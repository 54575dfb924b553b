//! What a render's state says of itself: the scene, settings, samples
//! and pass its samples belong to ([`StateInfo`]), written as JSON in the
//! state file's header and checked before a pixel is read.

use super::mismatch::Mismatch;
use crate::ir::settings::Settings;

/// The `format` of the JSON attribute.
const FORMAT: &str = "ptsc-render-state";
/// The version of the layout; a reader refuses others.
const VERSION: u64 = 1;

/// What a state belongs to: everything that must match for two states to
/// hold samples of the same image.
#[derive(Debug, Clone, PartialEq)]
pub struct StateInfo {
    /// The version of ptsc that drew the samples.
    pub ptsc: String,
    /// The scene file's name, for messages.
    pub scene: String,
    /// The scene's fingerprint (its objects, materials, lights, camera and
    /// data files; not its render settings), see
    /// the lowering stage's `fingerprint`.
    pub fingerprint: u64,
    /// Every setting that shapes a sample, by name ([`sample_settings`]).
    pub settings: Vec<(String, String)>,
    /// Samples per pixel of the whole render.
    pub samples: u32,
    /// The pass this state holds: K of N (1 of 1: the whole render).
    pub pass: Pass,
    /// Exposure in stops, for a PNG made from the state.
    pub exposure: f32,
}

/// The setting a state of an adaptive render names (with `min_samples`).
const ADAPTIVE_KEY: &str = "noise_threshold";
/// The setting a state names whose uniform render keeps its half images
/// (for the variance AOV): a resume must keep them too.
const HALVES_KEY: &str = "half_images";
/// The setting that says a state keeps a light film (`bdpt`, `ptlt`).
const LIGHT_KEY: &str = "light_film";

/// The K-th of N disjoint parts of a render's samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pass {
    /// Which part, 1 ≤ K ≤ N.
    pub k: u32,
    /// How many parts.
    pub n: u32,
}

impl Pass {
    /// The whole render.
    pub const WHOLE: Pass = Pass { k: 1, n: 1 };

    /// The sample indices this pass renders of `samples` per pixel: the
    /// K-th of N runs as even as whole samples allow.
    pub fn range(self, samples: u32) -> std::ops::Range<u32> {
        let cut = |k: u32| (samples as u64 * k as u64 / self.n.max(1) as u64) as u32;
        cut(self.k - 1)..cut(self.k)
    }

    /// `K/N` with 1 ≤ K ≤ N ≤ 1,000,000.
    pub fn parse(s: &str) -> Result<Pass, String> {
        let (k, n) = s.split_once('/').ok_or("expected K/N, e.g. 3/8")?;
        let number = |t: &str| {
            (t.trim().parse::<u32>().ok())
                .filter(|v| (1..=1_000_000).contains(v))
                .ok_or_else(|| format!("`{t}` is not a whole number from 1 to 1000000"))
        };
        let (k, n) = (number(k)?, number(n)?);
        if k > n {
            return Err(format!("pass {k} of {n}: K must be at most N"));
        }
        Ok(Pass { k, n })
    }
}

impl std::fmt::Display for Pass {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

/// Every setting that changes what a sample is, as (name, value) text: a
/// state is refused by a render whose values differ. The samples per pixel
/// and the exposure are not among them (more samples continue a render;
/// exposure only scales a PNG).
pub fn sample_settings(s: &Settings) -> Vec<(String, String)> {
    // Destructured in full: a new setting must be sorted in or out here.
    let Settings {
        width,
        height,
        samples: _,
        max_depth,
        integrator,
        seed,
        sampler,
        ambient,
        rr_depth,
        hybrid_weight,
        clamp,
        light_sampling,
        light_selection,
        light_samples,
        exposure: _,
        time: _,
        adaptive,
    } = s;
    let pairs: [(&str, String); 13] = [
        ("width", width.to_string()),
        ("height", height.to_string()),
        ("seed", seed.to_string()),
        ("sampler", sampler.name().to_string()),
        ("integrator", integrator.name().to_string()),
        ("max_depth", max_depth.to_string()),
        ("rr_depth", rr_depth.to_string()),
        ("ambient", format!("{ambient:?}")),
        ("hybrid_weight", format!("{hybrid_weight:?}")),
        ("clamp", format!("{clamp:?}")),
        ("light_sampling", light_sampling.to_string()),
        ("light_selection", format!("{light_selection:?}")),
        ("light_samples", light_samples.to_string()),
    ];
    let mut named: Vec<(String, String)> =
        pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect();
    // Only an adaptive render names them: a uniform render's state reads
    // as it did before adaptive sampling came.
    if let Some(a) = adaptive {
        named.push((ADAPTIVE_KEY.into(), format!("{:?}", a.threshold)));
        named.push(("min_samples".into(), a.min_samples.to_string()));
    }
    // In name order, as a state file's JSON object keeps them.
    named.sort();
    named
}

impl StateInfo {
    /// Why a state saved as `self` cannot hold samples of the render
    /// described by `now` (the first difference found), ignoring the pass
    /// and samples per pixel (the caller decides those).
    pub fn mismatch(&self, now: &StateInfo) -> Option<Mismatch> {
        if self.ptsc != now.ptsc {
            return Some(Mismatch::Ptsc {
                saved: self.ptsc.clone(),
                now: now.ptsc.clone(),
            });
        }
        if self.fingerprint != now.fingerprint {
            return Some(Mismatch::Scene {
                saved: self.scene.clone(),
                now: now.scene.clone(),
            });
        }
        let setting = |name: &str, saved: Option<String>, now: Option<String>| {
            Some(Mismatch::Setting {
                name: name.into(),
                saved,
                now,
            })
        };
        // The image's size in one phrase: "its height is 128" alone hid
        // that the widths differ too.
        let size = |info: &StateInfo| match (info.get("width"), info.get("height")) {
            (Some(w), Some(h)) => Some(format!("{w}×{h}")),
            _ => None,
        };
        if let (Some(saved), Some(then)) = (size(self), size(now)) {
            if saved != then {
                return setting("size", Some(saved), Some(then));
            }
        }
        // Adaptive sampling on one side only: said as such, before its
        // `min_samples` (which sorts first) is found missing.
        if self.adaptive() != now.adaptive() {
            return setting(ADAPTIVE_KEY, self.get(ADAPTIVE_KEY), now.get(ADAPTIVE_KEY));
        }
        for (name, value) in &now.settings {
            let saved = self.get(name);
            if saved.as_ref() != Some(value) {
                return setting(name, saved, Some(value.clone()));
            }
        }
        // A setting only some renders name (the half images, a light film).
        let only_saved =
            (self.settings.iter()).find(|(n, _)| now.settings.iter().all(|m| m.0 != *n));
        only_saved.and_then(|(name, v)| setting(name, Some(v.clone()), None))
    }

    /// A setting's stored value.
    fn get(&self, name: &str) -> Option<String> {
        (self.settings.iter())
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.clone())
    }

    /// Whether its render samples adaptively: its film then holds the
    /// half films and the stopped pixels.
    pub fn adaptive(&self) -> bool {
        self.settings.iter().any(|(k, _)| k == ADAPTIVE_KEY)
    }

    /// Whether its film keeps the half images (an adaptive render's, or one
    /// that writes the variance AOV).
    pub fn keeps_halves(&self) -> bool {
        self.adaptive() || self.settings.iter().any(|(k, _)| k == HALVES_KEY)
    }

    /// The description of the same render keeping its half images.
    pub fn with_halves(mut self) -> StateInfo {
        if !self.keeps_halves() {
            self.settings.push((HALVES_KEY.into(), "kept".into()));
            self.settings.sort();
        }
        self
    }

    /// Whether its film keeps a light film (the splats of `bdpt` and
    /// `ptlt`), in a part of its own.
    pub fn keeps_light(&self) -> bool {
        self.settings.iter().any(|(k, _)| k == LIGHT_KEY)
    }

    /// The description of the same render keeping its light film.
    pub fn with_light(mut self) -> StateInfo {
        if !self.keeps_light() {
            self.settings.push((LIGHT_KEY.into(), "kept".into()));
            self.settings.sort();
        }
        self
    }

    /// What the state holds, for messages: "64 spp", "pass 2/4 of 64 spp"
    /// (from the description alone).
    pub fn describe(&self) -> String {
        match self.pass {
            Pass::WHOLE => format!("{} spp", self.samples),
            p => format!("pass {p} of {} spp", self.samples),
        }
    }

    /// The JSON text of the state part's attribute.
    pub(super) fn to_json(&self) -> String {
        let settings: serde_json::Map<String, serde_json::Value> = (self.settings.iter())
            .map(|(k, v)| (k.clone(), serde_json::Value::String(v.clone())))
            .collect();
        serde_json::json!({
            "format": FORMAT,
            "version": VERSION,
            "ptsc": self.ptsc,
            "scene": self.scene,
            "fingerprint": format!("{:016x}", self.fingerprint),
            "settings": settings,
            "samples": self.samples,
            "pass": [self.pass.k, self.pass.n],
            "exposure": self.exposure,
        })
        .to_string()
    }

    /// Reads the JSON attribute, checking every field.
    pub(super) fn from_json(text: &str) -> Result<StateInfo, String> {
        let v: serde_json::Value =
            serde_json::from_str(text).map_err(|e| format!("its description is not JSON: {e}"))?;
        let field = |name: &str| {
            v.get(name)
                .ok_or(format!("its description has no `{name}`"))
        };
        let text = |name: &str| {
            field(name)?
                .as_str()
                .map(str::to_string)
                .ok_or(format!("its `{name}` is not text"))
        };
        let whole = |x: &serde_json::Value, name: &str| {
            (x.as_u64().filter(|&n| (1..=1_000_000).contains(&n)))
                .map(|n| n as u32)
                .ok_or(format!(
                    "its `{name}` is not a whole number from 1 to 1000000"
                ))
        };
        if text("format")? != FORMAT || field("version")?.as_u64() != Some(VERSION) {
            return Err(format!(
                "it is not a ptsc render state of version {VERSION}"
            ));
        }
        let fingerprint = u64::from_str_radix(&text("fingerprint")?, 16)
            .map_err(|_| "its `fingerprint` is not hexadecimal".to_string())?;
        let settings = (field("settings")?.as_object())
            .ok_or("its `settings` is not an object")?
            .iter()
            .map(|(k, v)| {
                let value = v.as_str().ok_or(format!("its setting `{k}` is not text"))?;
                Ok((k.clone(), value.to_string()))
            })
            .collect::<Result<Vec<_>, String>>()?;
        let pass = field("pass")?
            .as_array()
            .filter(|a| a.len() == 2)
            .ok_or("its `pass` is not [K, N]")?;
        let pass = Pass {
            k: whole(&pass[0], "pass")?,
            n: whole(&pass[1], "pass")?,
        };
        let samples = whole(field("samples")?, "samples")?;
        if pass.k > pass.n || pass.n > samples {
            return Err(format!(
                "its pass {pass} of {samples} samples per pixel is impossible"
            ));
        }
        let exposure = (field("exposure")?.as_f64())
            .filter(|e| e.abs() <= 64.0)
            .ok_or("its `exposure` is not a number of stops")? as f32;
        Ok(StateInfo {
            ptsc: text("ptsc")?,
            scene: text("scene")?,
            fingerprint,
            settings,
            samples,
            pass,
            exposure,
        })
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A description for tests.
    pub(crate) fn info() -> StateInfo {
        StateInfo {
            ptsc: "0.1.0".into(),
            scene: "a.pts".into(),
            fingerprint: 0xdead_beef_0123_4567,
            settings: sample_settings(&Settings::default()),
            samples: 10,
            pass: Pass { k: 2, n: 3 },
            exposure: 0.5,
        }
    }

    #[test]
    fn passes_split_the_samples_into_disjoint_runs() {
        let runs: Vec<_> = (1..=3).map(|k| Pass { k, n: 3 }.range(10)).collect();
        assert_eq!(runs, vec![0..3, 3..6, 6..10]);
        assert_eq!(Pass::WHOLE.range(7), 0..7);
        // Large counts do not overflow.
        let last = Pass {
            k: 999_999,
            n: 1_000_000,
        }
        .range(1_000_000);
        assert_eq!(last, 999_998..999_999);
        assert_eq!(Pass::parse("3/8"), Ok(Pass { k: 3, n: 8 }));
        for bad in ["0/3", "4/3", "3", "a/b", "1/0", "1/1000001"] {
            assert!(Pass::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn mismatches_name_what_differs() {
        let a = info();
        let mut b = info();
        assert_eq!(a.mismatch(&b), None);
        b.settings.iter_mut().find(|(k, _)| k == "seed").unwrap().1 = "7".into();
        assert_eq!(
            a.mismatch(&b).unwrap().for_resume(),
            "it was rendered with seed 0, this render with seed 7"
        );
        let mut c = info();
        c.fingerprint += 1;
        assert!(a
            .mismatch(&c)
            .unwrap()
            .for_resume()
            .contains("scene differs"));
        // A render without adaptive sampling against one with it: named
        // by its threshold, not by the `min_samples` it also lacks.
        let adaptive = Settings {
            adaptive: Some(crate::ir::settings::Adaptive {
                threshold: 0.1,
                min_samples: 16,
            }),
            ..Settings::default()
        };
        let d = StateInfo {
            settings: sample_settings(&adaptive),
            ..info()
        };
        let why = a.mismatch(&d).unwrap().for_resume();
        assert!(why.contains("without adaptive sampling (--noise)"), "{why}");
        assert!(!why.contains("min_samples"), "{why}");
    }

    #[test]
    fn the_clamp_is_a_setting_of_the_samples() {
        let clamped = Settings {
            clamp: Some(4.0),
            ..Settings::default()
        };
        let settings = sample_settings(&clamped);
        let clamp = settings.iter().find(|(k, _)| k == "clamp").unwrap();
        assert_ne!(
            clamp,
            sample_settings(&Settings::default())
                .iter()
                .find(|(k, _)| k == "clamp")
                .unwrap()
        );
    }
}
