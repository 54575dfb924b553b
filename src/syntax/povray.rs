//! POV-Ray's words and what ptsc says instead: a user who writes
//! `light_source` or `pigment` learns the ptsc word, not just that theirs
//! is wrong. Read by the parser's errors (a statement, directive or flag
//! that ptsc does not have) and by the checker's errors (an unknown
//! parameter, block, name or function). One table per kind of word; a
//! form whose answer needs the block's kind (POV-Ray's positional
//! `sphere { <0, 1, 0>, 1 }`) is answered from the kind's row in
//! `check/params.rs`.

/// POV-Ray words (and a few from other renderers and languages) with what
/// ptsc has instead, as a help line's text.
const WORDS: &[(&str, &str)] = &[
    ("union", "ptsc has no CSG; a `group name { … }` gathers objects to place together with `instance name { … }`"),
    ("merge", "ptsc has no CSG yet: write the objects one after the other"),
    ("difference", "ptsc has no CSG yet"),
    ("intersection", "ptsc has no CSG yet"),
    ("object", "POV-Ray's `#declare Thing = union { … }` and `object { Thing … }` are `group thing { … }` and `instance thing { translate … }` in ptsc"),
    ("function", "a user function is `fn name(a, b) = expression;` in ptsc"),
    ("array", "a list is written `[a, b, c]` in ptsc, indexed `xs[0]`, measured `len(xs)`, walked `for x in xs { … }`"),
    ("srgb", "colours are linear `rgb <r, g, b>` in ptsc"),
    ("radiosity", "the `path` integrator (the default) computes all indirect light: `render { integrator path }`"),
    ("location", "POV-Ray's `location` (of a camera or a light) is `position` in ptsc"),
    ("angle", "POV-Ray's camera `angle` is `fov` in ptsc, and ptsc's `fov` is the vertical field of view (POV-Ray's is horizontal)"),
    ("orthographic", "ptsc's camera is a perspective one (pinhole, or a thin lens with `aperture`); an orthographic camera is planned"),
    ("right", "ptsc's image proportions come from `render { resolution <w, h> }`"),
    ("focal_point", "POV-Ray's `focal_point` is `focus_distance` (a distance) in ptsc"),
    ("blur_samples", "ptsc takes depth of field samples from `render { samples … }`"),
    ("area_light", "an area light is an object with `material { emission rgb … }`, e.g. a `quad` or `disk`"),
    ("fade_distance", "ptsc's lights fall off with the square of the distance, as real ones do"),
    ("phong", "ptsc's highlight is a glossy lobe: `material { type plastic diffuse rgb … gloss 0.2 }` (smaller gloss, smaller highlight)"),
    ("specular", "ptsc's highlight is a glossy lobe: `material { type plastic diffuse rgb … gloss 0.2 }` (smaller gloss, smaller highlight)"),
    ("brilliance", "ptsc's diffuse reflection is Lambertian; a sheen or highlight is `type plastic` with `gloss`"),
    ("metallic", "a metal is `material { type conductor preset gold gloss 0.2 }` in ptsc"),
    ("phong_size", "ptsc's highlight size is `gloss` (0 a mirror, 1 very rough) with `type plastic`"),
    ("gradient", "in a material, `diffuse gradient { low rgb 0 high rgb 1 rotate <0, 0, 90> }` (a ramp along x)"),
    ("checker", "in a material, `diffuse checker { even rgb 1 odd rgb 0 }` (see \"Textures\" in docs/language.md)"),
    ("text", "POV-Ray's `text { ttf … }`: ptsc has no text objects; model the letters in a 3D program and load them with `mesh { file \"…\" }`"),
    ("blob", "ptsc has no blobs: spheres (`sphere { … }`), or a mesh of the shape from a 3D program (`mesh { file \"…\" }`)"),
    ("isosurface", "ptsc has no isosurfaces: a mesh of the surface (`mesh { file \"…\" }`), or its `sphere`, `capsule` and `torus` shapes"),
    ("bozo", "POV-Ray's `bozo` is ptsc's `noise { … }` texture: `diffuse noise { stop 0 rgb … stop 1 rgb … }`"),
    ("bumps", "POV-Ray's `normal { bumps … }` is a material's `bump noise { … }` with `bump_height`"),
    ("image_map", "POV-Ray's `image_map { png \"f.png\" }` is `diffuse image { file \"f.png\" }` in ptsc"),
    ("granite", "ptsc's `turbulence { … }` texture is a close match for POV-Ray's `granite`"),
];

/// Mitsuba 3's words (its plugins' parameters and names), for its users.
const MITSUBA: &[(&str, &str)] = &[
    ("reflectance", "Mitsuba's `reflectance` (of its `diffuse` BSDF) is `diffuse rgb …` in ptsc"),
    ("specular_reflectance", "Mitsuba's `specular_reflectance` is `reflection rgb …` in ptsc"),
    ("specular_transmittance", "Mitsuba's `specular_transmittance` is `transmission` in ptsc (a weight, 0..1)"),
    ("int_ior", "Mitsuba's `int_ior` is `ior` in ptsc"),
    ("ext_ior", "Mitsuba's `ext_ior` is `ior_outside` in ptsc"),
    ("alpha", "Mitsuba's `alpha` (GGX roughness) is `roughness` on a `type conductor` material in ptsc, or `gloss` (α = gloss²) on the others"),
    ("alpha_u", "Mitsuba's `alpha_u` and `alpha_v` are `roughness <α along u, α along v>` in ptsc"),
    ("alpha_v", "Mitsuba's `alpha_u` and `alpha_v` are `roughness <α along u, α along v>` in ptsc"),
    ("radiance", "Mitsuba's area emitter `radiance` is a material's `emission rgb …` in ptsc"),
    ("roughconductor", "Mitsuba's `roughconductor` is `material { type conductor preset gold roughness 0.1 }` in ptsc"),
    ("roughdielectric", "Mitsuba's `roughdielectric` is `material { type dielectric ior 1.5 gloss 0.3 }` in ptsc"),
    ("roughplastic", "Mitsuba's `roughplastic` is `material { type plastic diffuse rgb … gloss 0.3 }` in ptsc"),
    ("bsdf", "a Mitsuba `bsdf` is a `material name { … }` in ptsc, given to objects as `material name`"),
    ("to_world", "Mitsuba's `to_world` is an object's `translate`, `rotate`, `scale` or `matrix` in ptsc"),
    ("filename", "Mitsuba's `filename` is `file` in ptsc"),
];

/// POV-Ray's `#` directives, each with the ptsc statement that does its job.
const DIRECTIVES: &[(&str, &str)] = &[
    ("declare", "POV-Ray's `#declare NAME = …;` is `let NAME = …;` in ptsc (numbers, vectors, colours, strings, lists); an object to reuse is a `group`"),
    ("local", "POV-Ray's `#local NAME = …;` is `let NAME = …;` in ptsc"),
    ("include", "in ptsc, write `include \"file.pts\"` (no `#`); POV-Ray's own include files (colors.inc, textures.inc, …) have no ptsc version: write colours as `rgb <r, g, b>`"),
    ("if", "in ptsc, write `if a < b { … } else { … }` (no `#`, no `#end`; `else if` chains)"),
    ("else", "in ptsc, write `if a < b { … } else { … }` (no `#`, no `#end`)"),
    ("elseif", "in ptsc, write `if a { … } else if b { … } else { … }`"),
    ("end", "ptsc closes loops and branches with `}`: `for i in 0..10 { … }`, `if a { … }`"),
    ("while", "in ptsc, write `for i in 0..n { … }` (loops are always bounded; no `#end`)"),
    ("for", "in ptsc, write `for i in 0..n { … }` (the end is excluded; no `#`, no `#end`)"),
    ("switch", "ptsc has no `switch`: write `if a { … } else if b { … } else { … }`"),
    ("case", "ptsc has no `switch`: write `if a { … } else if b { … } else { … }`"),
    ("macro", "a POV-Ray macro that makes objects is a `group` placed with `instance`; one that computes a value is a function, `fn name(a, b) = …;`"),
    ("ifdef", "ptsc has no `#ifdef`: a name must be defined before it is used"),
    ("ifndef", "ptsc has no `#ifndef`: a name must be defined before it is used"),
    ("version", "ptsc needs no `#version`: a scene is read the same by every version"),
    ("default", "ptsc has no `#default`: an object without a material is grey diffuse; name a material and give it to each object with `material NAME`"),
    ("debug", "ptsc has no `#debug`: `ptsc check` reports every problem with its place"),
    ("warning", "ptsc has no `#warning`: `ptsc check` reports every problem with its place"),
    ("error", "ptsc has no `#error`: `ptsc check` reports every problem with its place"),
    ("undef", "ptsc has no `#undef`: a `let` inside a loop or an `if` is visible only there"),
];

/// POV-Ray's blocks inside objects (`pigment { … }`), each with what ptsc
/// writes instead.
const BLOCKS: &[(&str, &str)] = &[
    ("pigment", "POV-Ray's `pigment { color rgb … }` is `material { diffuse rgb … }` in ptsc (a pattern: `diffuse checker { … }`; `rgbt`'s transmit t: `opacity 1 − t`)"),
    ("texture", "POV-Ray's `texture { pigment { … } finish { … } }` is one `material { … }` in ptsc: `diffuse rgb …`, `gloss …`, `reflection rgb …`"),
    ("finish", "POV-Ray's `finish` is part of ptsc's `material { … }`: `type plastic gloss 0.3` for a highlight, `reflection rgb …` for a mirror, `emission rgb …` for a glow"),
    ("normal", "POV-Ray's `normal { bumps … }` is a material's `bump` in ptsc: `material { bump noise { scale 0.1 } bump_height 0.02 }` (or `normal_map image { file … }`)"),
    ("interior", "POV-Ray's `interior { ior … media { … } }` is part of ptsc's `material { … }`: `transmission 1 ior 1.5` for glass, and the medium inside (`absorption rgb …`, `scattering rgb …`, `anisotropy …`) on the material itself; `type none` for fog or smoke without a surface"),
    ("color_map", "POV-Ray's `color_map { [0 rgb …] [1 rgb …] }` is a pattern's stops in ptsc: `marble { stop 0 rgb 1 stop 1 rgb 0.2 }`"),
    ("colour_map", "POV-Ray's `colour_map { [0 rgb …] [1 rgb …] }` is a pattern's stops in ptsc: `marble { stop 0 rgb 1 stop 1 rgb 0.2 }`"),
    ("pigment_map", "ptsc has no pigment maps: a pattern's `stop`s are colours (`marble { stop 0 rgb 1 stop 1 rgb 0.2 }`)"),
    ("image_map", "POV-Ray's `image_map { png \"file.png\" }` is `diffuse image { file \"file.png\" }` in a ptsc material; its alpha as holes (POV-Ray's `transmit all`) is `opacity image { file \"file.png\" channel a }`"),
    ("photons", "the `path` integrator (the default) renders caustics without photons"),
    ("media", "POV-Ray's `media { absorption … scattering { … } density { … } }` is the medium of a ptsc material, on the object that bounds it: `material { type none  scattering rgb 0.5  absorption rgb 0.05  anisotropy 0.3 }` (or `density 0.5  medium_color rgb 0.9`); media do not glow in ptsc (for `emission`, make an object emissive: `emission rgb …`)"),
    ("scattering", "POV-Ray's `scattering { 1, rgb … eccentricity g }` is a ptsc material's `scattering rgb …` (light scattered per unit) and `anisotropy g` (Henyey–Greenstein), with `transmission 1` or `type none`"),
    ("density", "POV-Ray's `density { pattern … }` has no ptsc counterpart yet: ptsc's media are homogeneous (`density 0.5` on the material is a number)"),
    ("bounded_by", "ptsc bounds every object itself (a BVH): leave `bounded_by` out"),
    ("clipped_by", "ptsc has no CSG or clipping yet"),
];

/// POV-Ray's object flags (a word without a value) with what ptsc does.
const FLAGS: &[(&str, &str)] = &[
    ("no_shadow", "ptsc's objects always cast shadows (a light bulb is an emissive object: it lights the scene whatever is around it); remove `no_shadow`"),
    ("hollow", "ptsc needs no `hollow`: nothing fills an object's inside unless its material gives it a medium (`absorption`, `scattering` or `density`); remove it"),
    ("no_image", "ptsc draws every object in the image; remove `no_image`"),
    ("no_reflection", "ptsc shows every object in reflections; remove `no_reflection`"),
    ("double_illuminate", "light reaches the back of a thin surface in ptsc through `transmission` (e.g. `type thin_dielectric`); remove `double_illuminate`"),
    ("inverse", "ptsc has no CSG yet, so nothing to invert; remove `inverse`"),
];

/// POV-Ray's built-in functions that ptsc spells otherwise.
const FUNCTIONS: &[(&str, &str)] = &[
    ("vlength", "POV-Ray's `vlength(v)` is `length(v)` in ptsc"),
    ("vnormalize", "POV-Ray's `vnormalize(v)` is `normalize(v)` in ptsc"),
    ("vdot", "POV-Ray's `vdot(a, b)` is `dot(a, b)` in ptsc"),
    ("vcross", "POV-Ray's `vcross(a, b)` is `cross(a, b)` in ptsc"),
    ("sqr", "POV-Ray's `sqr(x)` is `x * x` (or `pow(x, 2)`) in ptsc"),
    ("ln", "POV-Ray's `ln(x)` is `log(x)` in ptsc (ptsc's `log` is the natural logarithm; POV-Ray's `log` is base 10: `log(x) / log(10)`)"),
    ("seed", "random numbers in ptsc need no stream: `rand(seed, i)` is the same number for the same `seed` and `i`"),
    ("div", "POV-Ray's `div(a, b)` is `int(a / b)` in ptsc"),
    ("select", "in ptsc, write `if a < 0 { b } else { c }` as a value"),
    ("vrotate", "ptsc has no `vrotate`: rotate the object with `rotate <x, y, z>` instead"),
    ("concat", "strings join with `+` in ptsc: `\"tree_\" + str(i) + \".obj\"`"),
];

/// Names of POV-Ray's `colors.inc` and `textures.inc` and what to write.
const NAMES: &[(&str, &str)] = &[
    ("White", "POV-Ray's colors.inc names are not predefined in ptsc: write `rgb 1` (or `let White = rgb 1;`)"),
    ("Black", "POV-Ray's colors.inc names are not predefined in ptsc: write `rgb 0`"),
    ("Red", "POV-Ray's colors.inc names are not predefined in ptsc: write `rgb <1, 0, 0>`"),
    ("Green", "POV-Ray's colors.inc names are not predefined in ptsc: write `rgb <0, 1, 0>`"),
    ("Blue", "POV-Ray's colors.inc names are not predefined in ptsc: write `rgb <0, 0, 1>`"),
    ("Yellow", "POV-Ray's colors.inc names are not predefined in ptsc: write `rgb <1, 1, 0>`"),
    ("Gray", "POV-Ray's colors.inc names are not predefined in ptsc: write `rgb 0.5`"),
    ("Grey", "POV-Ray's colors.inc names are not predefined in ptsc: write `rgb 0.5`"),
    ("Clear", "ptsc colours have no transmit channel: see-through is a material's `transmission 1` (with `ior 1` it bends nothing)"),
    ("Chrome_Metal", "in ptsc, write `material { type conductor preset chromium gloss 0.1 }`"),
    ("Glass", "in ptsc, write `material { type dielectric ior 1.5 }`"),
    ("color", "colours are written `rgb <r, g, b>` (or `rgb 0.5` for grey)"),
    ("colour", "colours are written `rgb <r, g, b>` (or `rgb 0.5` for grey)"),
];

/// The hint for POV-Ray's directive `#word`, if it has one.
pub fn directive(word: &str) -> Option<&'static str> {
    find(DIRECTIVES, word)
}

/// The hint for POV-Ray's object flag `word` (`no_shadow`, `hollow`).
pub fn flag(word: &str) -> Option<&'static str> {
    find(FLAGS, word)
}

/// The hint for POV-Ray's function `word` that ptsc spells otherwise.
pub fn function(word: &str) -> Option<&'static str> {
    find(FUNCTIONS, word)
}

/// The hint for a name POV-Ray's include files or syntax define
/// (`White`, `color`).
pub fn name(word: &str) -> Option<&'static str> {
    find(NAMES, word)
}

/// The text of `word`'s row in `table`.
fn find(table: &[(&str, &'static str)], word: &str) -> Option<&'static str> {
    table
        .iter()
        .find(|(w, _)| *w == word)
        .map(|(_, hint)| *hint)
}

/// POV-Ray's (and Mitsuba's) parameter names with the ptsc parameter that
/// does their job.
const PARAMETERS: &[(&str, &str)] = &[
    ("location", "position"),
    ("angle", "fov"),
    ("sky", "up"),
    ("focal_point", "focus_distance"),
    ("reflectance", "diffuse"),
    ("specular_reflectance", "reflection"),
    ("specular_transmittance", "transmission"),
    ("int_ior", "ior"),
    ("ext_ior", "ior_outside"),
    ("alpha", "roughness"),
    ("alpha_u", "roughness"),
    ("radiance", "emission"),
    ("filename", "file"),
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
    // ptsc's own words (`if`, `for`, `texture`) are not taken for POV-Ray's.
    if super::words::KEYWORDS.contains(&word) {
        return None;
    }
    [WORDS, BLOCKS, FLAGS, DIRECTIVES, FUNCTIONS, NAMES, MITSUBA]
        .iter()
        .find_map(|table| find(table, word))
}

/// The renderer whose word `word` is, for messages: "Mitsuba" for
/// Mitsuba's, else "POV-Ray".
pub fn renderer(word: &str) -> &'static str {
    match find(MITSUBA, word) {
        Some(_) => "Mitsuba",
        None => "POV-Ray",
    }
}

/// The hint for POV-Ray's block `word { … }` inside an object
/// (`pigment`, and `texture`, a ptsc word with another meaning).
pub fn block(word: &str) -> Option<&'static str> {
    find(BLOCKS, word).or_else(|| hint(word))
}

/// The name a POV-Ray directive's line binds, as its offset in `rest` (the
/// line after the word) and its text: `#declare NAME =` and `#local NAME =`
/// whose value did not read as one (no `;`), `#for (NAME, …)`.
pub(super) fn bound_name<'t>(word: &str, rest: &'t str) -> Option<(usize, &'t str)> {
    let after = |text: &'t str, at: usize| {
        let skipped = text[at..].len() - text[at..].trim_start().len();
        at + skipped
    };
    let mut at = after(rest, 0);
    let closing = match word {
        "declare" | "local" => '=',
        "for" => {
            rest[at..].strip_prefix('(')?;
            at = after(rest, at + 1);
            ','
        }
        _ => return None,
    };
    let len = rest[at..]
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(rest.len() - at);
    let name = &rest[at..at + len];
    let first = name.chars().next()?;
    let next = after(rest, at + len);
    let is_name =
        (first.is_ascii_alphabetic() || first == '_') && !super::words::KEYWORDS.contains(&name);
    (is_name && rest[next..].starts_with(closing)).then_some((at, name))
}

/// The parameters of a `#macro NAME(A, B)` line, each as its offset in
/// `rest` (the line after the word) and its text; none where the line is
/// not of that form.
pub(super) fn macro_parameters(rest: &str) -> Vec<(usize, &str)> {
    let (Some(open), Some(close)) = (rest.find('('), rest.find(')')) else {
        return Vec::new();
    };
    if close < open {
        return Vec::new();
    }
    let is_name = |w: &str| {
        let first = w.chars().next();
        first.is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && w.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            && !super::words::KEYWORDS.contains(&w)
    };
    let mut at = open + 1;
    let mut names = Vec::new();
    for part in rest[open + 1..close].split(',') {
        let name = part.trim();
        if is_name(name) {
            names.push((at + (part.len() - part.trim_start().len()), name));
        }
        at += part.len() + 1;
    }
    names
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn povray_words_name_the_ptsc_word() {
        // POV-Ray's statements that a ptsc kind stands for are in the
        // kind's row (check/kinds).
        assert!(hint("light_source").is_none());
        assert!(hint("#declare").unwrap().contains("let"));
        assert!(hint("pigment").unwrap().contains("diffuse"));
        assert!(hint("sphere").is_none());
        assert!(hint("if").is_none(), "ptsc's `if` is not POV-Ray's");
        assert!(directive("if").unwrap().contains("if a < b {"));
        assert!(block("texture").unwrap().contains("material"));
        assert!(flag("no_shadow").is_some() && hint("hollow").is_some());
        assert!(function("vlength").unwrap().contains("length(v)"));
        // No entry for a word ptsc has.
        for (w, _) in [WORDS, FLAGS, FUNCTIONS, NAMES].concat() {
            assert!(
                !super::super::words::KEYWORDS.contains(&w),
                "{w} is a ptsc keyword"
            );
        }
    }

    #[test]
    fn a_directive_line_gives_the_name_it_binds() {
        let bound = |word, rest| bound_name(word, rest).map(|(_, n)| n);
        assert_eq!(bound("declare", " V = <1, 2, 3>"), Some("V"));
        assert_eq!(bound("local", "  Radius_2=1"), Some("Radius_2"));
        assert_eq!(bound("for", " (I, 0, 4)"), Some("I"));
        assert_eq!(bound("for", "(J,0,9)"), Some("J"));
        assert_eq!(bound("declare", " V <1, 2, 3>"), None, "no `=`");
        assert_eq!(bound("declare", " 2V = 1"), None);
        assert_eq!(bound("while", " (I < 3)"), None);
        assert_eq!(bound("for", " I, 0, 4"), None, "no bracket");
        assert_eq!(bound("declare", ""), None);
        // The offset is where the name starts in the line.
        assert_eq!(bound_name("for", " ( K ,1,2)"), Some((3, "K")));
    }
}
