//! Lights in groups: each placement places the group's lights with its
//! transforms, so a scene with a lamp group placed by instances renders
//! the image of the same scene with the lights written at the places the
//! transforms take them to.
//!
//! Placements whose arithmetic is exact (translations and scales by
//! numbers binary floats hold exactly) give byte-identical images: the
//! placed light is the very light written flat. Rotations are not exact
//! (cos 90° is 6e-17 in f64, not 0), so those compare within float noise:
//! the placed light may be a few ulps from the flat one. (These cases
//! measured byte-identical too, the f32 light absorbing the difference,
//! but nothing guarantees it.)

use ptsc::compile::{compile_str, Options};
use ptsc::diag::codes;
use std::path::Path;

/// The room the lamps light: a floor, a wall and two shapes to cast
/// shadows, no other light.
const ROOM: &str = "render { resolution <40, 30> samples 8 max_depth 3 }\n\
    camera { position <0, 3, 8> look_at <0, 0.5, 0> }\n\
    plane { point <0, 0, 0> normal <0, 1, 0> material { diffuse rgb 0.6 } }\n\
    plane { point <0, 0, -3> normal <0, 0, 1> material { diffuse rgb 0.4 } }\n\
    sphere { center <-1, 0.5, 0> radius 0.5 material { diffuse rgb <0.8, 0.3, 0.2> } }\n\
    box { min <0.5, 0, -0.5> max <1.5, 1, 0.5> rotate <0, 30, 0> }\n";

/// The pixels of `ROOM` + `text` rendered on one thread.
fn pixels(text: &str) -> Vec<[f32; 3]> {
    let text = format!("{ROOM}{text}");
    let c = compile_str(Path::new("group_lights.pts"), &text, Options::default());
    assert!(
        c.diagnostics.items.is_empty(),
        "{}",
        c.diagnostics.render_human(&c.sources, false)
    );
    crate::render_pixels(&c.ir.expect("a scene without diagnostics lowers"))
}

/// The image's mean brightness (so that a test comparing images also
/// knows the lights lit something).
fn mean(image: &[[f32; 3]]) -> f64 {
    image.iter().flatten().map(|&c| c as f64).sum::<f64>() / (image.len() * 3) as f64
}

/// Asserts two images equal within float noise: no pixel's channel
/// differs by more than 1e-3 of the image's mean, and both are lit.
fn assert_close(placed: &[[f32; 3]], flat: &[[f32; 3]], what: &str) {
    let m = mean(flat);
    assert!(m > 0.01, "{what}: the flat scene is dark ({m})");
    let worst = (placed.iter().flatten().zip(flat.iter().flatten()))
        .map(|(a, b)| (a - b).abs() as f64)
        .fold(0.0, f64::max);
    assert!(worst <= 1e-3 * m, "{what}: differs by {worst} (mean {m})");
}

#[test]
fn translated_and_scaled_lamps_render_byte_identically_to_lights_written_there() {
    let cases = [
        (
            "point_light { position <0, 2, 0> intensity rgb 8 }",
            "translate <1, 0.5, 1>",
            "point_light { position <1, 2.5, 1> intensity rgb 8 }",
        ),
        (
            // A scale moves the light; its intensity stays.
            "spot_light { position <0, 1.5, 0> look_at <0, 0, 0.5> intensity rgb 30 angle 40 hotspot 25 }",
            "scale 2 translate <-0.5, 0, 0>",
            "spot_light { position <-0.5, 3, 0> look_at <-0.5, 0, 1> intensity rgb 30 angle 40 hotspot 25 }",
        ),
        (
            "directional_light { direction <0, -1, -1> irradiance rgb 2 }",
            "translate <5, 5, 5> scale <1, 1, 3>",
            "directional_light { direction <0, -1, -3> irradiance rgb 2 }",
        ),
    ];
    for (light, placement, flat) in cases {
        let placed = pixels(&format!(
            "group lamp {{\n    {light}\n}}\ninstance lamp {{ {placement} }}\n"
        ));
        let written = pixels(&format!("{flat}\n"));
        assert!(mean(&written) > 0.01, "{flat} lights nothing");
        assert_eq!(placed, written, "{light} placed by {placement}");
    }
}

#[test]
fn rotated_and_nested_lamps_render_as_lights_written_there() {
    // `lamp` turned a quarter about y (x → -z, z → x) and moved; `post`
    // places it 1 up, and is itself turned a quarter about z (y → -x) and
    // moved by <0.5, 2, 0>: the lamp's <0, 0.5, 0> is at <-1, 2, 0>.
    let lamp = |light: &str| format!("group lamp {{\n    {light}\n}}\n");
    let post = "group post {\n    instance lamp { translate <0, 1, 0> }\n}\n";
    let cases = [
        (
            lamp("point_light { position <1, 1.5, 0> intensity rgb 8 }")
                + "instance lamp { rotate <0, 90, 0> translate <0, 0, 1> }\n",
            "point_light { position <0, 1.5, 0> intensity rgb 8 }",
        ),
        (
            lamp("spot_light { position <0, 2, 0> look_at <1, 0, 0> intensity rgb 30 angle 35 hotspot 20 }")
                + "instance lamp { rotate <0, 90, 0> }\n",
            "spot_light { position <0, 2, 0> look_at <0, 0, -1> intensity rgb 30 angle 35 hotspot 20 }",
        ),
        (
            lamp("directional_light { direction <1, -1, 0> irradiance rgb 2 }")
                + "instance lamp { rotate <0, 90, 0> translate <3, 0, 0> }\n",
            "directional_light { direction <0, -1, -1> irradiance rgb 2 }",
        ),
        (
            lamp("point_light { position <0, 0.5, 0> intensity rgb 8 }")
                + post
                + "instance post { rotate <0, 0, 90> translate <0.5, 2, 0> }\n",
            "point_light { position <-1, 2, 0> intensity rgb 8 }",
        ),
        (
            lamp("spot_light { position <0, 0, 0> look_at <-1, 0, 0> intensity rgb 30 angle 35 hotspot 20 }")
                + post
                + "instance post { rotate <0, 0, 90> translate <1, 2, 0> }\n",
            // The lamp at <0, 1, 0> in the post, aimed along -x: turned
            // to <-1, 0, 0> aimed along -y, then moved.
            "spot_light { position <0, 2, 0> look_at <0, 1, 0> intensity rgb 30 angle 35 hotspot 20 }",
        ),
    ];
    for (grouped, flat) in cases {
        assert_close(&pixels(&grouped), &pixels(flat), &grouped);
    }
}

#[test]
fn a_scene_lit_only_by_a_placed_lamp_is_lit() {
    let check = |text: &str| {
        let c = compile_str(Path::new("lamp.pts"), text, Options::default());
        (c.diagnostics.items.iter()).any(|d| d.code == codes::NO_LIGHT)
    };
    let lamp = "camera { position <0, 1, 5> look_at <0, 0, 0> }\n\
        sphere { center <0, 0, 0> radius 1 }\n\
        group lamp { point_light { position <0, 3, 0> intensity rgb 10 } }\n";
    assert!(!check(&format!("{lamp}instance lamp {{ }}\n")));
    // Declared but never placed: no light in the scene.
    assert!(check(lamp));
    // Placed twice, through a group: two lights.
    let twice = format!("{lamp}group pair {{ instance lamp {{ }} instance lamp {{ translate <1, 0, 0> }} }}\ninstance pair {{ }}\n");
    let c = compile_str(Path::new("lamp.pts"), &twice, Options::default());
    assert_eq!(c.ir.expect("renders").lights.len(), 2);
}
