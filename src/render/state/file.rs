//! Reading and writing state files (the format is the parent module's),
//! in bounded memory: pixels go straight between the film and the file's
//! blocks, and a file is checked from its headers and its length before a
//! pixel is read.

use super::info::StateInfo;
use super::light;
use crate::ir::settings::{MAX_PIXELS, MAX_SIDE};
use crate::render::film::Film;
use glam::DVec3;
use std::io::{Read, Seek};
use std::path::Path;

/// The name of the state part and of its JSON attribute.
pub const STATE_PART: &str = "ptsc.state";
/// The state part's channels, in the order a file lists them (by name).
const CHANNELS: [&str; 7] = [
    "count", "sum.B.hi", "sum.B.lo", "sum.G.hi", "sum.G.lo", "sum.R.hi", "sum.R.lo",
];
/// The channels an adaptive render's state adds (its [`Halves`]): the sum
/// of the odd samples as f64 bits, and whether the pixel stopped (0 or 1).
const HALVES_CHANNELS: [&str; 7] = [
    "odd.B.hi", "odd.B.lo", "odd.G.hi", "odd.G.lo", "odd.R.hi", "odd.R.lo", "stopped",
];

/// The state part's channels of a state, by name: an adaptive render's
/// hold its halves too.
fn channels_of(info: &StateInfo) -> Vec<&'static str> {
    let mut names = CHANNELS.to_vec();
    if info.keeps_halves() {
        names.extend(HALVES_CHANNELS);
        names.sort_unstable();
    }
    names
}

/// Bytes a pixel takes in a state file: the image part's three float32,
/// the state part's uint32 channels.
fn bytes_per_pixel(info: &StateInfo) -> u64 {
    let light = if info.keeps_light() {
        light::LIGHT_BYTES_PER_PIXEL
    } else {
        0
    };
    12 + 4 * channels_of(info).len() as u64 + light
}

/// What takes the pixels a reader checked: (index, pixel).
type PixelVisitor<'a> = dyn FnMut(usize, &StatePixel) + 'a;

/// A pixel of the state part.
#[derive(Debug, Clone, Copy)]
struct StatePixel {
    sum: DVec3,
    count: u32,
    /// The odd samples' sum (adaptive renders; else 0).
    odd: DVec3,
    /// Whether adaptive sampling stopped it.
    stopped: bool,
}

/// Writes `film` and its description as a state file, atomically,
/// streaming the pixels block by block.
pub fn write_state(path: &Path, film: &Film, info: &StateInfo) -> std::io::Result<()> {
    write_state_encoded(path, film, info, exr::prelude::Encoding::UNCOMPRESSED)
}

/// [`write_state`] with another encoding of the state part (the tests'
/// compressed states, which readers refuse).
fn write_state_encoded(
    path: &Path,
    film: &Film,
    info: &StateInfo,
    encoding: exr::prelude::Encoding,
) -> std::io::Result<()> {
    use exr::prelude::*;
    debug_assert_eq!(film.halves.is_some(), info.keeps_halves());
    debug_assert_eq!(film.light.is_some(), info.keeps_light());
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
    let mut attributes = LayerAttributes::named(STATE_PART);
    attributes.other.insert(
        Text::from(STATE_PART),
        AttributeValue::Text(Text::from(info.to_json().as_str())),
    );
    let attrs = ImageAttributes::new(IntegerBounds::from_dimensions(size));
    let bits = |v: f64| ((v.to_bits() >> 32) as u32, v.to_bits() as u32);
    let [c0, c1, c2, c3, c4, c5, c6] = CHANNELS;
    let sums = SpecificChannels::build()
        .with_channel(c0)
        .with_channel(c1)
        .with_channel(c2)
        .with_channel(c3)
        .with_channel(c4)
        .with_channel(c5)
        .with_channel(c6);
    // Uncompressed: 28 bytes a pixel written in a blink, where ZIP would
    // spend longer on f64 bits than the render saves. The image part
    // first: readers that take the first RGB part show it.
    let Some(halves) = &film.halves else {
        let channels = sums.with_pixel_fn(|p: Vec2<usize>| {
            let i = p.y() * w + p.x();
            let s = film.sum[i];
            let ((bh, bl), (gh, gl), (rh, rl)) = (bits(s.z), bits(s.y), bits(s.x));
            (film.count[i], bh, bl, gh, gl, rh, rl)
        });
        let state = Layer::new(size, attributes, encoding, channels);
        let parts = Image::empty(attrs).with_layer(image).with_layer(state);
        return match &film.light {
            None => write_parts(path, &parts),
            Some(l) => {
                let parts = parts.with_layer(light::light_layer!(l, (w, h), encoding));
                write_parts(path, &parts)
            }
        };
    };
    let [d0, d1, d2, d3, d4, d5, d6] = HALVES_CHANNELS;
    let channels = (sums.with_channel(d0).with_channel(d1).with_channel(d2))
        .with_channel(d3)
        .with_channel(d4)
        .with_channel(d5)
        .with_channel(d6)
        .with_pixel_fn(|p: Vec2<usize>| {
            let i = p.y() * w + p.x();
            let (s, o) = (film.sum[i], halves.odd[i]);
            let ((bh, bl), (gh, gl), (rh, rl)) = (bits(s.z), bits(s.y), bits(s.x));
            let ((obh, obl), (ogh, ogl), (orh, orl)) = (bits(o.z), bits(o.y), bits(o.x));
            let stopped = halves.stopped[i] as u32;
            let n = film.count[i];
            (
                n, bh, bl, gh, gl, rh, rl, obh, obl, ogh, ogl, orh, orl, stopped,
            )
        });
    let state = Layer::new(size, attributes, encoding, channels);
    let parts = Image::empty(attrs).with_layer(image).with_layer(state);
    match &film.light {
        None => write_parts(path, &parts),
        Some(l) => {
            let parts = parts.with_layer(light::light_layer!(l, (w, h), encoding));
            write_parts(path, &parts)
        }
    }
}

/// Writes the image and state parts of a state file, atomically, one
/// block at a time: nothing to compress, so nothing to gain from blocks in
/// flight.
fn write_parts<'i, L>(path: &Path, file: &'i exr::image::Image<L>) -> std::io::Result<()>
where
    L: exr::image::write::layers::WritableLayers<'i>,
{
    use exr::prelude::WritableImage;
    crate::output::write_atomically_with(path, |out| {
        (file.write().non_parallel().to_buffered(out)).map_err(std::io::Error::other)
    })
}

/// What a file says of render states, from its first bytes and headers
/// only.
#[derive(Debug, Clone, PartialEq)]
pub enum HeldState {
    /// No regular file there (a folder, a FIFO or a device is refused as
    /// an output by the checks of paths, not here).
    Absent,
    /// A file that holds no state: not OpenEXR, or an image without the
    /// state part; why, for messages.
    Other(String),
    /// A regular file that cannot be opened, or an OpenEXR file whose
    /// headers cannot be read: as far as anyone can tell, a state whose
    /// samples may still be recovered; why ("it cannot be read: …").
    Damaged(String),
    /// A render state (its headers name a state part).
    State,
}

/// The four bytes that open every OpenEXR file.
const EXR_MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];

/// What the file at `path` holds ([`HeldState`]).
pub fn held_state(path: &Path) -> HeldState {
    use std::io::{Read, Seek};
    let mut file = match open(path) {
        Ok((file, _)) => file,
        Err(why) if std::fs::metadata(path).is_ok_and(|m| m.is_file()) => {
            return HeldState::Damaged(format!("it cannot be read: {why}"));
        }
        Err(_) => return HeldState::Absent,
    };
    let mut magic = [0u8; 4];
    if file.read_exact(&mut magic).is_err() || magic != EXR_MAGIC {
        return HeldState::Other("it is not an OpenEXR file".into());
    }
    if let Err(why) = file.rewind() {
        return HeldState::Damaged(format!("it cannot be read: {why}"));
    }
    match exr::meta::MetaData::read_from_buffered(file, false) {
        Err(e) => HeldState::Damaged(format!(
            "it is an OpenEXR file whose headers cannot be read: {e}"
        )),
        Ok(m) if m.headers.iter().any(|h| is_state_part(&h.own_attributes)) => HeldState::State,
        Ok(_) => HeldState::Other("it is an image without the ptsc.state part".into()),
    }
}

/// Why an image must not be written at `output`: it holds a render's
/// state (a part file, a saved state) or may hold one ([`HeldState::Damaged`]),
/// whose samples the image would replace. `force`: the command's
/// `--force` (`None` for a command that has none, such as `watch`).
pub fn refuse_to_replace(output: &Path, force: Option<bool>) -> Result<(), String> {
    let damaged = match held_state(output) {
        _ if force == Some(true) => return Ok(()),
        HeldState::Absent | HeldState::Other(_) => return Ok(()),
        HeldState::Damaged(why) => Some(why),
        HeldState::State => None,
    };
    let advice = match force {
        Some(_) => "name another output, or add --force to replace it",
        None => "name another output",
    };
    if let Some(why) = damaged {
        return Err(format!(
            "{} may hold a render's samples, but {why}; {advice}",
            output.display()
        ));
    }
    let what = read_state_info(output).map_or_else(
        |_| "a render state".to_string(),
        |info| {
            format!(
                "the samples of a render of {} ({})",
                info.scene,
                info.describe()
            )
        },
    );
    Err(format!(
        "{} holds {what}; writing an image there would lose them: {advice}",
        output.display()
    ))
}

/// Whether a part of an EXR file is a render state's.
fn is_state_part(attributes: &exr::meta::header::LayerAttributes) -> bool {
    (attributes.layer_name.as_ref()).is_some_and(|n| n.eq(STATE_PART))
}

/// Reads a state file's description alone (its headers, not its pixels).
pub fn read_state_info(path: &Path) -> Result<StateInfo, String> {
    read_state_header(path).map(|(info, _)| info)
}

/// Reads a state file's description and image size (its headers, not its
/// pixels).
pub fn read_state_header(path: &Path) -> Result<(StateInfo, (u32, u32)), String> {
    let (file, len) = open(path)?;
    let (info, (w, h)) = read_header(file, len)?;
    Ok((info, (w as u32, h as u32)))
}

/// A state file opened for reading and its length, or why not: only a
/// regular file is opened (a FIFO would block, a device never end).
fn open(path: &Path) -> Result<(std::io::BufReader<std::fs::File>, u64), String> {
    let (file, len) = crate::source::open_regular(path).map_err(|e| e.to_string())?;
    Ok((std::io::BufReader::new(file), len))
}

/// A state given as bytes (the fuzzer's entry).
pub fn read_state_bytes(bytes: &[u8]) -> Result<(Film, StateInfo), String> {
    let source = || std::io::Cursor::new(bytes);
    let (info, size) = read_header(source(), bytes.len() as u64)?;
    read_film(source(), info, size)
}

/// A state file's description and size, from its headers and length: a
/// file that is no state (an image from elsewhere, a truncated, compressed
/// or hostile file) is refused before its pixels are read.
fn read_header(source: impl Read, len: u64) -> Result<(StateInfo, (usize, usize)), String> {
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
    // Two parts of the same size (the image and the state), and a
    // splatting render's light part, nothing else.
    let expected = channels_of(&info);
    let parts = 2 + info.keeps_light() as usize;
    let light_ok = !info.keeps_light()
        || (meta.headers.iter()).any(|h| {
            let named =
                (h.own_attributes.layer_name.as_ref()).is_some_and(|n| n.eq(light::LIGHT_PART));
            let names: Vec<String> = h.channels.list.iter().map(|c| c.name.to_string()).collect();
            named
                && names == light::LIGHT_CHANNELS
                && h.channels
                    .list
                    .iter()
                    .all(|c| c.sample_type == SampleType::U32)
        });
    if names != expected
        || !light_ok
        || meta.headers.len() != parts
        || (meta.headers.iter())
            .any(|h| h.layer_size != size || h.deep || h.channels.list.len() > expected.len())
        || (state_header.channels.list.iter()).any(|c| c.sample_type != SampleType::U32)
    {
        return Err("its ptsc.state part does not have the channels of a render state".into());
    }
    // ptsc writes states uncompressed: the declared size must then be in
    // the file, which a lying header's is not.
    if (meta.headers.iter()).any(|h| h.compression != Compression::Uncompressed) {
        return Err("it is compressed; ptsc writes states uncompressed".into());
    }
    let needed = bytes_per_pixel(&info) * w as u64 * h as u64;
    if len < needed {
        return Err(format!(
            "it is {len} bytes long, too short for the {w}×{h} pixels its header declares ({needed} bytes): a truncated file"
        ));
    }
    Ok((info, (w, h)))
}

/// Reads a state file: its film (the samples of pass `info.pass`) and its
/// description. Errors say what is wrong with it.
pub fn read_state(path: &Path) -> Result<(Film, StateInfo), String> {
    let (file, len) = open(path)?;
    let (info, size) = read_header(file, len)?;
    read_film(open(path)?.0, info, size)
}

/// Adds the samples of the state file at `path` to `total` (a film of the
/// same size), pixel by pixel as they are read; returns its description
/// and the fewest samples a pixel of it has. On an error `total` holds
/// part of the file's samples.
pub fn add_state(path: &Path, total: &mut Film) -> Result<(StateInfo, u32), String> {
    let (file, len) = open(path)?;
    let (info, (w, h)) = read_header(file, len)?;
    if (w as u32, h as u32) != (total.width, total.height) {
        return Err("its image size differs".into());
    }
    if info.adaptive() {
        return Err("it is an adaptive render's state, which is not a part".into());
    }
    let (mut least, mut samples) = (u32::MAX, 0u64);
    read_pixels(open(path)?.0, &info, (w, h), &mut |i, p| {
        total.sum[i] += p.sum;
        total.count[i] = total.count[i].saturating_add(p.count);
        least = least.min(p.count);
        samples += p.count as u64;
    })?;
    if info.keeps_light() {
        if total.light.is_none() {
            *total = std::mem::replace(total, Film::new(0, 0, 0)).with_light();
        }
        let light = total.light.as_mut().expect("just made");
        let most = light::most(samples, w * h);
        light::read(open(path)?.0, (w, h), most, &mut |i, sum| {
            light.sum[i] += sum
        })?;
    }
    if let Some(light) = total.light.as_mut() {
        light.paths = total.count.iter().map(|&n| n as u64).sum();
    }
    Ok((info, least))
}

/// The film of a state whose header said `info` and `(w, h)`.
fn read_film(
    source: impl Read + Seek,
    info: StateInfo,
    (w, h): (usize, usize),
) -> Result<(Film, StateInfo), String> {
    let range = info.pass.range(info.samples);
    let mut film = Film::new(w as u32, h as u32, range.start);
    if info.keeps_halves() {
        film = film.with_halves();
    }
    let mut source = source;
    read_pixels(&mut source, &info, (w, h), &mut |i, p| {
        film.sum[i] = p.sum;
        film.count[i] = p.count;
        if let Some(halves) = film.halves.as_mut() {
            halves.odd[i] = p.odd;
            halves.stopped[i] = p.stopped;
        }
    })?;
    if info.keeps_light() {
        film = film.with_light();
        let most = light::most(film.total_samples(), w * h);
        let sums = &mut film.light.as_mut().expect("just made").sum;
        source.rewind().map_err(|e| e.to_string())?;
        light::read(source, (w, h), most, &mut |i, sum| sums[i] = sum)?;
    }
    Ok((film, info))
}

/// What the pixel reader keeps while it reads: where pixels go, how many
/// each row has had, and the first thing wrong.
struct PixelSink<'a> {
    width: usize,
    most: u32,
    visit: Option<&'a mut PixelVisitor<'a>>,
    row_pixels: Vec<u32>,
    error: Option<String>,
}

impl PixelSink<'_> {
    /// Takes the pixel at `(x, y)` if it is one a render makes (`stopped`
    /// as read: 0 or 1).
    fn take(&mut self, (x, y): (usize, usize), pixel: &StatePixel, stopped: u32) {
        if self.error.is_some() {
            return;
        }
        let (sum, count) = (pixel.sum, pixel.count);
        let most = crate::render::MAX_SAMPLE as f64 * count as f64;
        let row = &mut self.row_pixels[y];
        *row += 1;
        self.error = if *row as usize > self.width {
            Some("it holds a row of pixels twice".into())
        } else if !sum.is_finite() || !pixel.odd.is_finite() {
            Some("its state has a sum that is not finite".into())
        } else if stopped > 1 {
            Some("its state has a pixel neither stopped nor going on".into())
        } else if sum.abs().max_element() > most || pixel.odd.abs().max_element() > most {
            // At most its largest sample per sample (so every pixel's mean
            // is a finite f32), nothing without samples.
            Some("its state has a sum no render makes (beyond its samples' largest value)".into())
        } else if count > self.most {
            Some(format!("a pixel of its state has {count} samples"))
        } else {
            None
        };
        if let (None, Some(visit)) = (&self.error, &mut self.visit) {
            visit(y * self.width + x, pixel);
        }
    }
}

/// Reads the state part's pixels of a file whose headers were checked,
/// handing each to `visit` (index, sum, count) after checking it.
fn read_pixels<'v>(
    source: impl Read + Seek,
    info: &StateInfo,
    (w, h): (usize, usize),
    visit: &'v mut PixelVisitor<'v>,
) -> Result<(), String> {
    use exr::prelude::*;
    let most = info.pass.range(info.samples).len() as u32;
    let slot = std::cell::Cell::new(Some(visit));
    let [c0, c1, c2, c3, c4, c5, c6] = CHANNELS;
    let [d0, d1, d2, d3, d4, d5, d6] = HALVES_CHANNELS;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .specific_channels()
        .required::<u32>(c0)
        .required::<u32>(c1)
        .required::<u32>(c2)
        .required::<u32>(c3)
        .required::<u32>(c4)
        .required::<u32>(c5)
        .required::<u32>(c6)
        .optional::<u32>(d0, 0)
        .optional::<u32>(d1, 0)
        .optional::<u32>(d2, 0)
        .optional::<u32>(d3, 0)
        .optional::<u32>(d4, 0)
        .optional::<u32>(d5, 0)
        .optional::<u32>(d6, 0)
        .collect_pixels(
            |_, _| PixelSink {
                width: w,
                most,
                visit: slot.take(),
                row_pixels: vec![0; h],
                error: None,
            },
            |sink: &mut PixelSink, p: Vec2<usize>, channels| {
                let (n, bh, bl, gh, gl, rh, rl, obh, obl, ogh, ogl, orh, orl, stopped) = channels;
                let f64_of = |hi: u32, lo: u32| f64::from_bits((hi as u64) << 32 | lo as u64);
                let pixel = StatePixel {
                    sum: DVec3::new(f64_of(rh, rl), f64_of(gh, gl), f64_of(bh, bl)),
                    count: n,
                    odd: DVec3::new(f64_of(orh, orl), f64_of(ogh, ogl), f64_of(obh, obl)),
                    stopped: stopped == 1,
                };
                sink.take((p.x(), p.y()), &pixel, stopped)
            },
        )
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_buffered(source)
        .map_err(|e| format!("its pixels cannot be read ({e})"))?;
    let sink = image.layer_data.channel_data.pixels;
    match sink.error {
        Some(why) if why.starts_with("a pixel") => Err(format!(
            "{why}, more than its pass {} of {} samples per pixel holds ({most})",
            info.pass, info.samples
        )),
        Some(why) => Err(why),
        None if sink.row_pixels.iter().any(|&n| n as usize != w) => {
            Err("it is missing pixels (a truncated or damaged file)".into())
        }
        None => Ok(()),
    }
}

#[cfg(test)]
#[path = "file_tests.rs"]
mod tests;
