//! A render's state file: what a stopped render continues from, and what
//! `ptsc merge` adds up. An OpenEXR file of two parts (docs/farm.md):
//!
//! - `image`: R, G, B as float32, the mean so far, so any EXR viewer
//!   shows how far the render got;
//! - `ptsc.state`: per pixel the sum of its samples as the bits of three
//!   f64 (channels `sum.R.hi`, `sum.R.lo`, … as uint32, the high and low
//!   halves) and its sample count (`count`, uint32), uncompressed; its
//!   header's text attribute `ptsc.state` is a JSON object naming the
//!   scene's fingerprint, every setting that shapes a sample, the samples
//!   per pixel of the whole render and the pass (K of N) it holds.
//!
//! Sums are kept bit for bit, so a render continued from its state adds
//! the very samples, in the very order, of an uninterrupted one.

use super::film::Film;
use crate::ir::settings::{Settings, MAX_PIXELS, MAX_SIDE};
use glam::DVec3;
use std::path::Path;

/// The name of the state part and of its JSON attribute.
pub const STATE_PART: &str = "ptsc.state";
/// The `format` of the JSON attribute.
const FORMAT: &str = "ptsc-render-state";
/// The version of the layout; a reader refuses others.
const VERSION: u64 = 1;
/// The state part's channels, in the order of [`Film`]'s sums, then the count.
const CHANNELS: [&str; 7] = [
    "sum.R.hi", "sum.R.lo", "sum.G.hi", "sum.G.lo", "sum.B.hi", "sum.B.lo", "count",
];

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
        ambient,
        rr_depth,
        hybrid_weight,
        clamp,
        light_sampling,
        light_selection,
        light_samples,
        exposure: _,
    } = s;
    let pairs: [(&str, String); 12] = [
        ("width", width.to_string()),
        ("height", height.to_string()),
        ("seed", seed.to_string()),
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
    // In name order, as a state file's JSON object keeps them.
    named.sort();
    named
}

impl StateInfo {
    /// Why a state saved as `self` cannot hold samples of the render
    /// described by `now` (the first difference found), ignoring the pass
    /// and samples per pixel (the caller decides those).
    pub fn mismatch(&self, now: &StateInfo) -> Option<String> {
        if self.ptsc != now.ptsc {
            return Some(format!(
                "it was made by ptsc {}, this is ptsc {}",
                self.ptsc, now.ptsc
            ));
        }
        if self.fingerprint != now.fingerprint {
            return Some(format!(
                "its scene differs: {} (objects, materials, lights, camera or data files) changed since",
                self.scene
            ));
        }
        for (name, value) in &now.settings {
            let saved = self.settings.iter().find(|(n, _)| n == name);
            match saved {
                Some((_, v)) if v == value => {}
                Some((_, v)) => {
                    return Some(format!("its {name} is {v}, this render's is {value}"));
                }
                None => return Some(format!("it has no {name}")),
            }
        }
        None
    }

    /// The JSON text of the state part's attribute.
    fn to_json(&self) -> String {
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
    fn from_json(text: &str) -> Result<StateInfo, String> {
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

/// Writes `film` and its description as a state file, atomically.
pub fn write_state(path: &Path, film: &Film, info: &StateInfo) -> std::io::Result<()> {
    use exr::prelude::*;
    let (w, h) = (film.width as usize, film.height as usize);
    let size = Vec2(w, h);
    // Uncompressed, as the state: a state is written at checkpoints and
    // interruptions, when time counts more than its size.
    let image = Layer::new(
        size,
        LayerAttributes::named("image"),
        Encoding::UNCOMPRESSED,
        SpecificChannels::rgb(|p: Vec2<usize>| {
            let v = film.pixel(p.y() * w + p.x());
            (v.x, v.y, v.z)
        }),
    );
    let mut halves: Vec<Vec<u32>> = (0..7).map(|_| Vec::with_capacity(w * h)).collect();
    for (sum, &count) in film.sum.iter().zip(&film.count) {
        for (c, v) in [sum.x, sum.y, sum.z].into_iter().enumerate() {
            let bits = v.to_bits();
            halves[2 * c].push((bits >> 32) as u32);
            halves[2 * c + 1].push(bits as u32);
        }
        halves[6].push(count);
    }
    let channels = (CHANNELS.iter().zip(halves))
        .map(|(name, data)| AnyChannel::new(*name, FlatSamples::U32(data)))
        .collect();
    let mut attributes = LayerAttributes::named(STATE_PART);
    attributes.other.insert(
        Text::from(STATE_PART),
        AttributeValue::Text(Text::from(info.to_json().as_str())),
    );
    // Uncompressed: 28 bytes a pixel written in a blink, where ZIP would
    // spend longer on f64 bits than the render saves.
    let state = Layer::new(
        size,
        attributes,
        Encoding::UNCOMPRESSED,
        AnyChannels::sort(channels),
    );
    let attrs = ImageAttributes::new(IntegerBounds::from_dimensions(size));
    let mut cur = std::io::Cursor::new(Vec::new());
    // The image part first: readers that take the first RGB part show it.
    Image::empty(attrs)
        .with_layer(image)
        .with_layer(state)
        .write()
        .to_buffered(&mut cur)
        .map_err(std::io::Error::other)?;
    crate::output::write_atomically(path, &cur.into_inner())
}

/// Whether a part of an EXR file is a render state's.
fn is_state_part(attributes: &exr::meta::header::LayerAttributes) -> bool {
    (attributes.layer_name.as_ref()).is_some_and(|n| n.eq(STATE_PART))
}

/// Reads a state file's description alone (its headers, not its pixels).
pub fn read_state_info(path: &Path) -> std::result::Result<StateInfo, String> {
    read_header(open(path)?).map(|(info, _)| info)
}

/// A state file opened for reading, or why not (a regular file only: a
/// FIFO would wait for a writer, a device could be endless).
fn open(path: &Path) -> std::result::Result<std::io::BufReader<std::fs::File>, String> {
    let (file, _) = crate::source::open_regular(path).map_err(|e| e.to_string())?;
    Ok(std::io::BufReader::new(file))
}

/// A state given as bytes (the fuzzer's entry).
pub fn read_state_bytes(bytes: &[u8]) -> std::result::Result<(Film, StateInfo), String> {
    read_state_from(|| Ok(std::io::Cursor::new(bytes)))
}

/// A state file's description and size, from its headers: a file that is
/// no state (an image from elsewhere, a truncated or hostile file) is
/// refused before its pixels are read.
fn read_header(
    source: impl std::io::Read,
) -> std::result::Result<(StateInfo, (usize, usize)), String> {
    use exr::prelude::*;
    let meta = exr::meta::MetaData::read_from_buffered(source, false).map_err(|e| match e {
        exr::error::Error::Io(e) => e.to_string(),
        e => format!("it is not an OpenEXR file ({e})"),
    })?;
    let state_header = (meta.headers.iter())
        .find(|h| is_state_part(&h.own_attributes))
        .ok_or("it holds no render state (an image without the ptsc.state part)")?;
    let json = match state_header
        .own_attributes
        .other
        .get(&Text::from(STATE_PART))
    {
        Some(AttributeValue::Text(t)) => t.to_string(),
        _ => return Err("its ptsc.state part has no description".into()),
    };
    let info = StateInfo::from_json(&json)?;
    let size = state_header.layer_size;
    let (w, h) = (size.width(), size.height());
    let pixels = w as f64 * h as f64;
    if w == 0 || h == 0 || pixels > MAX_PIXELS || w.max(h) as f64 > MAX_SIDE {
        return Err(format!("its size {w}×{h} is not an image ptsc renders"));
    }
    let names: Vec<String> = (state_header.channels.list.iter())
        .map(|c| c.name.to_string())
        .collect();
    let mut expected: Vec<&str> = CHANNELS.to_vec();
    expected.sort();
    // Two parts of the same size (the image and the state), nothing else:
    // what the pixels' reader allocates is bounded by the size checked.
    if names != expected
        || meta.headers.len() != 2
        || (meta.headers.iter())
            .any(|h| h.layer_size != size || h.deep || h.channels.list.len() > CHANNELS.len())
        || (state_header.channels.list.iter()).any(|c| c.sample_type != SampleType::U32)
    {
        return Err("its ptsc.state part does not have the channels of a render state".into());
    }
    Ok((info, (w, h)))
}

/// Reads a state file: its film (the samples of pass `info.pass`) and its
/// description. Errors say what is wrong with it.
pub fn read_state(path: &Path) -> std::result::Result<(Film, StateInfo), String> {
    read_state_from(|| open(path))
}

/// [`read_state`] from a source opened twice: once for the headers, once
/// for the pixels.
fn read_state_from<R: std::io::Read + std::io::Seek>(
    open: impl Fn() -> std::result::Result<R, String>,
) -> std::result::Result<(Film, StateInfo), String> {
    use exr::prelude::*;
    let (info, (w, h)) = read_header(open()?)?;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .from_buffered(open()?)
        .map_err(|e| format!("its pixels cannot be read ({e})"))?;
    let layer = (image.layer_data.iter())
        .find(|l| is_state_part(&l.attributes))
        .ok_or("it holds no render state")?;
    let channel = |name: &str| -> std::result::Result<&[u32], String> {
        let c = (layer.channel_data.list.iter())
            .find(|c| c.name.eq(name))
            .ok_or(format!("its state has no channel {name}"))?;
        match &c.sample_data {
            FlatSamples::U32(v) if v.len() == w * h => Ok(v),
            _ => Err(format!("its state channel {name} is not {w}×{h} uint32")),
        }
    };
    let range = info.pass.range(info.samples);
    let mut film = Film::new(w as u32, h as u32, range.start);
    let f64_channel = |c: &str| -> std::result::Result<Vec<f64>, String> {
        let (hi, lo) = (
            channel(&format!("sum.{c}.hi"))?,
            channel(&format!("sum.{c}.lo"))?,
        );
        let v: Vec<f64> = (hi.iter().zip(lo))
            .map(|(&a, &b)| f64::from_bits((a as u64) << 32 | b as u64))
            .collect();
        match v.iter().all(|x| x.is_finite()) {
            true => Ok(v),
            false => Err(format!("its state has a sum that is not finite in {c}")),
        }
    };
    let (r, g, b) = (f64_channel("R")?, f64_channel("G")?, f64_channel("B")?);
    for (i, s) in film.sum.iter_mut().enumerate() {
        *s = DVec3::new(r[i], g[i], b[i]);
    }
    film.count.copy_from_slice(channel("count")?);
    // Sums a render can make: at most its largest sample per sample
    // (so every pixel's mean is a finite f32), nothing without samples.
    let possible =
        |(s, &n): (&DVec3, &u32)| s.abs().max_element() <= super::MAX_SAMPLE as f64 * n as f64;
    if !film.sum.iter().zip(&film.count).all(possible) {
        return Err(
            "its state has a sum no render makes (beyond its samples' largest value)".into(),
        );
    }
    let most = range.end - range.start;
    if let Some(n) = film.count.iter().find(|&&n| n > most) {
        return Err(format!(
            "a pixel of its state has {n} samples, more than its pass {} of {} samples per pixel holds ({most})",
            info.pass, info.samples
        ));
    }
    Ok((film, info))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn info() -> StateInfo {
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
    fn a_state_round_trips_bit_for_bit() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.exr");
        let mut film = Film::new(3, 2, 3);
        for (i, (s, n)) in film.sum.iter_mut().zip(&mut film.count).enumerate() {
            *n = i as u32 % 4;
            *s = DVec3::new(0.1 * i as f64, 1.0 / 3.0, 1e25) * *n as f64;
        }
        write_state(&path, &film, &info()).unwrap();
        let (back, back_info) = read_state(&path).unwrap();
        assert_eq!(back, film);
        assert_eq!(back_info, info());
        // The image part is what an EXR reader sees first.
        let (w, h, px) = crate::output::read_exr(&path).unwrap();
        assert_eq!((w, h, px[1]), (3, 2, film.pixel(1)));
    }

    #[test]
    fn sums_no_render_makes_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.exr");
        let mut film = Film::new(1, 1, 0);
        film.sum[0] = DVec3::splat(1.0);
        write_state(&path, &film, &info()).unwrap();
        assert!(
            read_state(&path).unwrap_err().contains("no render makes"),
            "a sum without samples"
        );
        film.count[0] = 1;
        film.sum[0] = DVec3::splat(1e31);
        write_state(&path, &film, &info()).unwrap();
        assert!(read_state(&path).is_err(), "a sum past the largest sample");
        film.sum[0] = DVec3::new(f64::NAN, 0.0, 0.0);
        write_state(&path, &film, &info()).unwrap();
        assert!(read_state(&path).unwrap_err().contains("not finite"));
    }

    #[test]
    fn a_plain_image_or_garbage_is_no_state() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("plain.exr");
        crate::output::write_image(&path, (2, 2), |_| Vec3::ONE, 0.0).unwrap();
        assert!(read_state(&path).unwrap_err().contains("no render state"));
        std::fs::write(&path, b"not an exr").unwrap();
        assert!(read_state(&path).unwrap_err().contains("not an OpenEXR"));
    }

    #[test]
    fn mismatches_name_what_differs() {
        let a = info();
        let mut b = info();
        assert_eq!(a.mismatch(&b), None);
        b.settings.iter_mut().find(|(k, _)| k == "seed").unwrap().1 = "7".into();
        assert_eq!(a.mismatch(&b).unwrap(), "its seed is 0, this render's is 7");
        let mut c = info();
        c.fingerprint += 1;
        assert!(a.mismatch(&c).unwrap().contains("scene differs"));
    }
}
