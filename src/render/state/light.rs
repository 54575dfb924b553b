//! A state's third part, `ptsc.light`: the light film of an integrator
//! that splats (`bdpt`, `ptlt`), per pixel the sum of the splats it
//! received as the bits of three f64 (`light.R.hi`, `light.R.lo`, … as
//! uint32), uncompressed. Its light paths are the film's samples (one per
//! sample), so no count is kept.

use glam::DVec3;
use std::io::{Read, Seek};

/// The light part's name.
pub const LIGHT_PART: &str = "ptsc.light";

/// Its channels, in the order a file lists them (by name).
pub const LIGHT_CHANNELS: [&str; 6] = [
    "light.B.hi",
    "light.B.lo",
    "light.G.hi",
    "light.G.lo",
    "light.R.hi",
    "light.R.lo",
];

/// Bytes a pixel takes in the light part.
pub const LIGHT_BYTES_PER_PIXEL: u64 = 24;

/// The light part of a film: `light_layer!(light_film, (w, h), encoding)`
/// (a macro: the layer's type holds a closure, which no function can name
/// in a return type that every borrow of the image it joins accepts).
macro_rules! light_layer {
    ($light:expr, ($w:expr, $h:expr), $encoding:expr) => {{
        use exr::prelude::*;
        let (light, w): (&crate::render::film::LightFilm, usize) = ($light, $w);
        let bits = |v: f64| ((v.to_bits() >> 32) as u32, v.to_bits() as u32);
        let [c0, c1, c2, c3, c4, c5] = $crate::render::state::light::LIGHT_CHANNELS;
        let channels = SpecificChannels::build()
            .with_channel(c0)
            .with_channel(c1)
            .with_channel(c2)
            .with_channel(c3)
            .with_channel(c4)
            .with_channel(c5)
            .with_pixel_fn(move |p: Vec2<usize>| {
                let s = light.sum[p.y() * w + p.x()];
                let ((bh, bl), (gh, gl), (rh, rl)) = (bits(s.z), bits(s.y), bits(s.x));
                (bh, bl, gh, gl, rh, rl)
            });
        Layer::new(
            Vec2(w, $h),
            LayerAttributes::named($crate::render::state::light::LIGHT_PART),
            $encoding,
            channels,
        )
    }};
}
pub(crate) use light_layer;

/// The most a pixel's light sum may hold in a film of `samples` samples
/// over `pixels` pixels: what keeps the pixel's share of it (the sum over
/// the light paths per pixel) at most [`crate::render::MAX_SAMPLE`], so
/// every pixel of a film read back is a finite f32.
pub fn most(samples: u64, pixels: usize) -> f64 {
    crate::render::MAX_SAMPLE as f64 * samples as f64 / pixels.max(1) as f64
}

/// Reads the light part of a file whose headers were checked, handing
/// each pixel's sum to `visit(index, sum)` after checking it (finite, not
/// negative, at most `most`).
pub fn read(
    source: impl Read + Seek,
    (w, h): (usize, usize),
    most: f64,
    visit: &mut dyn FnMut(usize, DVec3),
) -> Result<(), String> {
    use exr::prelude::*;
    struct Sink<'a> {
        width: usize,
        visit: &'a mut dyn FnMut(usize, DVec3),
        rows: Vec<u32>,
        error: Option<String>,
    }
    let slot = std::cell::Cell::new(Some(visit));
    let [c0, c1, c2, c3, c4, c5] = LIGHT_CHANNELS;
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
        .collect_pixels(
            |_, _| Sink {
                width: w,
                visit: slot.take().expect("one layer is read"),
                rows: vec![0; h],
                error: None,
            },
            move |sink: &mut Sink, p: Vec2<usize>, (bh, bl, gh, gl, rh, rl)| {
                if sink.error.is_some() {
                    return;
                }
                let f64_of = |hi: u32, lo: u32| f64::from_bits((hi as u64) << 32 | lo as u64);
                let sum = DVec3::new(f64_of(rh, rl), f64_of(gh, gl), f64_of(bh, bl));
                sink.rows[p.y()] += 1;
                if sink.rows[p.y()] as usize > sink.width {
                    sink.error = Some("its light part holds a row of pixels twice".into());
                } else if !sum.is_finite() || sum.min_element() < 0.0 || sum.max_element() > most {
                    sink.error = Some("its light part has a sum no render makes".into());
                } else {
                    (sink.visit)(p.y() * sink.width + p.x(), sum);
                }
            },
        )
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_buffered(source)
        .map_err(|e| format!("its light part cannot be read ({e})"))?;
    let sink = image.layer_data.channel_data.pixels;
    match sink.error {
        Some(why) => Err(why),
        None if sink.rows.iter().any(|&n| n as usize != w) => {
            Err("its light part is missing pixels (a truncated or damaged file)".into())
        }
        None => Ok(()),
    }
}
