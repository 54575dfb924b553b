//! POV-Ray's words and what ptsc says instead: a user who writes
//! `light_source` or `pigment` learns the ptsc word, not just that theirs
//! is wrong. Read by the parser's errors (a statement or parameter that
//! ptsc does not have) and by the checker's unknown-parameter errors.

/// POV-Ray words (and a few from other renderers and languages) with what
/// ptsc has instead, as a help line's text.
const WORDS: &[(&str, &str)] = &[
    ("light_source", "POV-Ray's `light_source` is `point_light { position <x, y, z> intensity rgb … }` in ptsc (also `spot_light`, `directional_light`)"),
    ("spotlight", "a spot light is its own block: `spot_light { position … look_at … intensity … angle … }`"),
    ("sky_sphere", "ptsc's `sky { … }` (a daylight sky and sun), `environment { … }` (an HDR image) or `background rgb …` is light from every direction, and lights the scene"),
    ("cube", "ptsc's is `box { min <…> max <…> }`"),
    ("polygon", "use `quad { corner … edge1 … edge2 … }` or `triangle { v0 … v1 … v2 … }`"),
    ("mesh2", "ptsc reads meshes from files: `mesh { file \"model.obj\" }` (OBJ or PLY)"),
    ("union", "ptsc has no CSG; a `group name { … }` gathers objects to place together with `instance name { … }`"),
    ("merge", "ptsc has no CSG yet: write the objects one after the other"),
    ("difference", "ptsc has no CSG yet"),
    ("intersection", "ptsc has no CSG yet"),
    ("object", "POV-Ray's `#declare Thing = union { … }` and `object { Thing … }` are `group thing { … }` and `instance thing { translate … }` in ptsc"),
    ("declare", "POV-Ray's `#declare NAME = …;` is `let NAME = …;` in ptsc (numbers, vectors, colours, strings, lists); an object to reuse is a `group`"),
    ("local", "POV-Ray's `#local NAME = …;` is `let NAME = …;` in ptsc"),
    ("macro", "a POV-Ray macro that makes objects is a `group` placed with `instance`; one that computes a value is a function, `fn name(a, b) = …;`"),
    ("function", "a user function is `fn name(a, b) = expression;` in ptsc"),
    ("array", "a list is written `[a, b, c]` in ptsc, indexed `xs[0]`, measured `len(xs)`, walked `for x in xs { … }`"),
    ("concat", "strings join with `+` in ptsc: `\"tree_\" + str(i) + \".obj\"`"),
    ("elseif", "ptsc writes `if a { … } else if b { … } else { … }`"),
    ("ifdef", "ptsc has no `#ifdef`: a name must be defined before it is used"),
    ("while", "ptsc loops are `for i in a..b { … }` (always bounded)"),
    ("switch", "ptsc has no `switch`: write `if a { … } else if b { … } else { … }`"),
    ("pigment", "POV-Ray's `pigment { color rgb … }` is `diffuse rgb …` inside ptsc's `material { … }`"),
    ("finish", "POV-Ray's `finish` settings are `material` parameters in ptsc: `reflection rgb …`, `gloss …`, `emission rgb …`"),
    ("normal", "POV-Ray's `normal { bumps … }` is a material's `bump` (any pattern, e.g. `bump noise { scale 0.1 }`) or `normal_map image { file … }`"),
    ("interior", "POV-Ray's `interior { ior … }` is `ior` and `absorption` inside ptsc's `material { transmission 1 … }`"),
    ("color", "colours are written `rgb <r, g, b>` (or `rgb 0.5` for grey)"),
    ("colour", "colours are written `rgb <r, g, b>` (or `rgb 0.5` for grey)"),
    ("srgb", "colours are linear `rgb <r, g, b>` in ptsc"),
    ("global_settings", "ptsc's settings are in `render { … }`: `resolution`, `samples`, `max_depth`, `integrator`, …"),
    ("radiosity", "the `path` integrator (the default) computes all indirect light: `render { integrator path }`"),
    ("photons", "the `path` integrator renders caustics without photons"),
    ("location", "POV-Ray's camera `location` is `position` in ptsc"),
    ("angle", "POV-Ray's camera `angle` is `fov` in ptsc, and ptsc's `fov` is the vertical field of view (POV-Ray's is horizontal)"),
    ("orthographic", "ptsc's camera is a perspective one (pinhole, or a thin lens with `aperture`); an orthographic camera is planned"),
    ("right", "ptsc's image proportions come from `render { resolution <w, h> }`"),
    ("focal_point", "POV-Ray's `focal_point` is `focus_distance` (a distance) in ptsc"),
    ("blur_samples", "ptsc takes depth of field samples from `render { samples … }`"),
    ("area_light", "an area light is an object with `material { emission rgb … }`, e.g. a `quad` or `disk`"),
    ("fade_distance", "ptsc's lights fall off with the square of the distance, as real ones do"),
    ("image_map", "an image map is `diffuse image { file \"wood.png\" }` in a ptsc material"),
    ("color_map", "a colour map is a texture's `stop` entries: `marble { stop 0 rgb 1 stop 0.7 rgb 0.2 }`"),
    ("gradient", "in a material, `diffuse gradient { low rgb 0 high rgb 1 rotate <0, 0, 90> }` (a ramp along x)"),
    ("checker", "in a material, `diffuse checker { even rgb 1 odd rgb 0 }` (see \"Textures\" in docs/language.md)"),
];

/// POV-Ray parameter names with the ptsc parameter that does their job.
const PARAMETERS: &[(&str, &str)] = &[
    ("location", "position"),
    ("angle", "fov"),
    ("sky", "up"),
    ("focal_point", "focus_distance"),
];

/// The ptsc parameter that does the job of POV-Ray's parameter `word`
/// (`location` → `position`): a block that lacks it should not also be
/// told so.
pub fn parameter(word: &str) -> Option<&'static str> {
    PARAMETERS.iter().find(|(w, _)| *w == word).map(|(_, p)| *p)
}

/// What ptsc has instead of `word`, if it is a POV-Ray (or similar) word
/// that ptsc does not have. `#declare` and `declare` are the same word.
pub fn hint(word: &str) -> Option<&'static str> {
    let word = word.trim_start_matches('#');
    WORDS
        .iter()
        .find(|(w, _)| *w == word)
        .map(|(_, hint)| *hint)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn povray_words_name_the_ptsc_word() {
        assert!(hint("light_source").unwrap().contains("point_light"));
        assert!(hint("#declare").unwrap().contains("let"));
        assert!(hint("pigment").unwrap().contains("diffuse"));
        assert!(hint("sphere").is_none());
        // No entry for a word ptsc has.
        for (w, _) in WORDS {
            assert!(
                !super::super::parser::KEYWORDS.contains(w),
                "{w} is a ptsc keyword"
            );
        }
    }
}
