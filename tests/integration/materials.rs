//! Material types as the language gives them to the renderer.

use ptsc::compile::{compile_str, Options};
use std::path::Path;

#[test]
fn smooth_glass_is_the_same_by_type_or_by_lobe() {
    // `type dielectric` without gloss is the mix's transmission lobe,
    // even with a reflection or diffuse colour written (ignored, with
    // a warning), and its absorption kept.
    let scene = "camera { position <0, 0, 5> look_at <0, 0, 0> }
        background rgb 1
        sphere { center <0, 0, 0> radius 1
                 material { type dielectric ior 1.4 absorption rgb 0.5 reflection rgb 1 diffuse rgb 0.5 } }
        sphere { center <3, 0, 0> radius 1 material { transmission 1 ior 1.4 absorption rgb 0.5 } }";
    let c = compile_str(Path::new("glass.pts"), scene, Options::default());
    let ir = c.ir.expect("compiles");
    assert_eq!(ir.materials.len(), 2);
    assert_eq!(ir.materials[0], ir.materials[1]);
}
