//! The catalogue of diagnostic codes: every code ptsc reports, with a
//! title, a paragraph that explains it and an example that shows it.
//! `ptsc explain CODE` prints an entry; `docs/diagnostics.md` lists them all
//! (generated from this table, checked by a test, as is that every code used
//! in the source is here and every code here is used). Editors and CI
//! scripts match on the codes: never rename one.

/// One entry of the catalogue.
#[derive(Debug, Clone, Copy)]
pub struct Entry {
    /// The code, e.g. `pts::check::unknown_param`.
    pub code: &'static str,
    /// What the problem is, in a few words.
    pub title: &'static str,
    /// Why it is a problem and what to do.
    pub explanation: &'static str,
    /// A scene (or command) that shows it.
    pub example: &'static str,
}

/// A token the grammar does not allow here.
pub const UNEXPECTED_TOKEN: &str = "pts::syntax::unexpected_token";
/// A block without its closing `}`.
pub const UNCLOSED_BLOCK: &str = "pts::syntax::unclosed_block";
/// A string without its closing quote.
pub const UNTERMINATED_STRING: &str = "pts::syntax::unterminated_string";
/// A block comment without `*/`.
pub const UNTERMINATED_COMMENT: &str = "pts::syntax::unterminated_comment";
/// A keyword used as a name.
pub const RESERVED_WORD: &str = "pts::syntax::reserved_word";
/// Brackets nested too deeply.
pub const TOO_DEEP: &str = "pts::syntax::too_deep";
/// `rgb` applied to an `rgb` without brackets.
pub const RGB_OF_RGB: &str = "pts::syntax::rgb_of_rgb";
/// A POV-Ray `#` directive.
pub const DIRECTIVE: &str = "pts::syntax::directive";
/// An object used as a value.
pub const OBJECT_AS_VALUE: &str = "pts::syntax::object_as_value";
/// The parser disagreed with itself.
pub const INTERNAL: &str = "pts::syntax::internal";
/// A name that is not defined.
pub const UNKNOWN_NAME: &str = "pts::check::unknown_name";
/// A function that does not exist.
pub const UNKNOWN_FUNCTION: &str = "pts::check::unknown_function";
/// A call with the wrong number of arguments.
pub const WRONG_ARGUMENT_COUNT: &str = "pts::check::argument_count";
/// A vector's or colour's component that does not exist (`v.w`).
pub const UNKNOWN_COMPONENT: &str = "pts::check::unknown_component";
/// POV-Ray's `rgbf`/`rgbt` colour.
pub const FILTER_COLOR: &str = "pts::check::filter_color";
/// A block ptsc does not have inside a block (POV-Ray's `pigment { … }`).
pub const FOREIGN_BLOCK: &str = "pts::check::foreign_block";
/// A name alone at the end of a block, without its value.
pub const MISSING_VALUE: &str = "pts::check::missing_value";
/// Values without parameter names (POV-Ray's `sphere { <0, 1, 0>, 1 }`).
pub const POSITIONAL_VALUES: &str = "pts::check::positional_values";
/// An index outside a list.
pub const INDEX_OUT_OF_RANGE: &str = "pts::check::index_out_of_range";
/// A list or string too large.
pub const VALUE_TOO_LARGE: &str = "pts::check::value_too_large";
/// Function calls nested too deeply or made too often.
pub const RECURSION_LIMIT: &str = "pts::check::recursion_limit";
/// An instance of a group that is not declared.
pub const UNKNOWN_GROUP: &str = "pts::check::unknown_group";
/// A group that contains itself.
pub const GROUP_CYCLE: &str = "pts::check::group_cycle";
/// Warning: an instance of a group that holds nothing.
pub const EMPTY_GROUP: &str = "pts::check::empty_group";
/// A statement a group cannot hold.
pub const NOT_IN_GROUP: &str = "pts::check::not_in_group";
/// A value of the wrong type.
pub const TYPE_MISMATCH: &str = "pts::check::type_mismatch";
/// A word outside the accepted set.
pub const UNKNOWN_WORD: &str = "pts::check::unknown_word";
/// Division by zero.
pub const DIVISION_BY_ZERO: &str = "pts::check::division_by_zero";
/// A function argument outside its domain.
pub const DOMAIN: &str = "pts::check::domain";
/// An infinite or NaN value.
pub const NOT_FINITE: &str = "pts::check::not_finite";
/// A parameter the block does not have.
pub const UNKNOWN_PARAM: &str = "pts::check::unknown_param";
/// A parameter given twice.
pub const DUPLICATE_PARAM: &str = "pts::check::duplicate_param";
/// A required parameter not given.
pub const MISSING_PARAM: &str = "pts::check::missing_param";
/// A value outside its allowed range.
pub const OUT_OF_RANGE: &str = "pts::check::out_of_range";
/// Geometry without area or volume.
pub const DEGENERATE: &str = "pts::check::degenerate";
/// A name declared twice.
pub const DUPLICATE_NAME: &str = "pts::check::duplicate_name";
/// A second `render`, `camera` or `background`.
pub const DUPLICATE_BLOCK: &str = "pts::check::duplicate_block";
/// A texture kind that does not exist.
pub const UNKNOWN_TEXTURE: &str = "pts::check::unknown_texture";
/// A texture given to a parameter that takes a plain value.
pub const TEXTURE_NOT_ALLOWED: &str = "pts::check::texture_not_allowed";
/// Colour stops of a texture out of order.
pub const UNORDERED_STOPS: &str = "pts::check::unordered_stops";
/// An image file that is missing, unreadable or of an unknown format.
pub const IMAGE_FILE: &str = "pts::lower::image_file";
/// Warning: a texture that reads texture coordinates on a mesh that has none.
pub const NO_TEXCOORDS: &str = "pts::lower::no_texcoords";
/// Warning: an environment map that is not twice as wide as high.
pub const NOT_LATLONG: &str = "pts::lower::not_latlong";
/// A material that does not exist.
pub const UNKNOWN_MATERIAL: &str = "pts::check::unknown_material";
/// An included file that cannot be read.
pub const INCLUDE_NOT_FOUND: &str = "pts::check::include_not_found";
/// A file that includes itself.
pub const INCLUDE_CYCLE: &str = "pts::check::include_cycle";
/// A file that is not valid UTF-8.
pub const INVALID_UTF8: &str = "pts::check::invalid_utf8";
/// A file that is not a scene (an image, a model, a binary file).
pub const NOT_A_SCENE: &str = "pts::check::not_a_scene";
/// A scene without a camera.
pub const MISSING_CAMERA: &str = "pts::check::missing_camera";
/// Loops that run too many statements.
pub const LOOP_TOO_LONG: &str = "pts::check::loop_too_long";
/// Expressions that do too much work in all.
pub const EVALUATION_TOO_LONG: &str = "pts::check::evaluation_too_long";
/// A mesh file that is missing, unreadable or of an unknown format.
pub const MESH_FILE: &str = "pts::check::mesh_file";
/// An output image the render could not write.
pub const OUTPUT_FILE: &str = "pts::check::output_file";
/// A transform that cannot be inverted.
pub const SINGULAR_TRANSFORM: &str = "pts::check::singular_transform";
/// A scene making more primitives than the renderer holds.
pub const TOO_MANY_PRIMITIVES: &str = "pts::lower::too_many_primitives";
/// A sphere, disk, cylinder, cone or torus under a non-uniform scale.
pub const NON_UNIFORM_SCALE: &str = "pts::lower::non_uniform_scale";
/// Warning: a material never used.
pub const UNUSED_MATERIAL: &str = "pts::check::unused_material";
/// Warning: a constant never used.
pub const UNUSED_CONSTANT: &str = "pts::check::unused_constant";
/// Warning: nothing emits light.
pub const NO_LIGHT: &str = "pts::check::no_light";
/// A scene whose objects need more memory to load than is free.
pub const SCENE_MEMORY: &str = "pts::lower::scene_memory";
/// Warning: point lights too far or too weak to light what the camera sees.
pub const DIM_LIGHT: &str = "pts::check::dim_light";
/// Warning: a material that would reflect more than it receives.
pub const ENERGY_GAIN: &str = "pts::check::energy_gain";
/// Warning: `let n = n + 1;` in a loop, a new constant read as a counter.
pub const SHADOWED_IN_LOOP: &str = "pts::check::shadowed_in_loop";
/// Warning: a setting that biases the image or has no effect with this integrator.
pub const INTEGRATOR_SETTING: &str = "pts::check::integrator_setting";
/// Warning: a parameter that has no effect.
pub const NO_EFFECT: &str = "pts::check::no_effect";
/// Two parameters that say the same thing differently.
pub const CONFLICTING_PARAMS: &str = "pts::check::conflicting_params";
/// The scene file cannot be read.
pub const IO_READ: &str = "pts::io::read";

/// Every code with its explanation, syntax first, then check, lowering, I/O.
pub const CATALOGUE: &[Entry] = &[
    Entry {
        code: UNEXPECTED_TOKEN,
        title: "A token the grammar does not allow here",
        explanation: "The parser met a word or symbol where the grammar expects something else: a missing `;` after a `let`, a missing comma in a vector, a value missing after a parameter name, a block ptsc does not have. The message lists what would have been accepted at that point; when a statement word is misspelled or comes from POV-Ray, the help names the ptsc word.",
        example: "let r = 1\nsphere { center <0, 0, 0> radius r }   // `;` missing after `let r = 1`",
    },
    Entry {
        code: UNCLOSED_BLOCK,
        title: "A block without its closing `}`",
        explanation: "A `{` was opened and the file (or the next statement) came before its `}`. The error points at the `{` that was never closed, not at the place where the parser gave up, which may be many lines later.",
        example: "sphere { center <0, 0, 0> radius 1\ncamera { position <0, 0, 5> look_at <0, 0, 0> }",
    },
    Entry {
        code: UNTERMINATED_STRING,
        title: "A string without its closing quote",
        explanation: "A `\"` opened a string (a file name) that no `\"` closes on the same line. Strings cannot span lines.",
        example: "mesh { file \"bunny.obj }",
    },
    Entry {
        code: UNTERMINATED_COMMENT,
        title: "A block comment without `*/`",
        explanation: "A `/*` comment runs to the end of the file. Block comments do not nest.",
        example: "/* a note\nsphere { center <0, 0, 0> radius 1 }",
    },
    Entry {
        code: RESERVED_WORD,
        title: "A keyword used as a name",
        explanation: "The language's own words (`let`, `for`, `in`, `if`, `material`, `group`, `rgb`, `true`, …) cannot name constants or materials. The kinds of blocks (`sphere`, `camera`) are not reserved.",
        example: "let material = 2;",
    },
    Entry {
        code: TOO_DEEP,
        title: "Brackets nested too deeply",
        explanation: "Brackets, braces and angle brackets nest at most 128 deep. The limit keeps parsing and evaluation bounded (no input can exhaust the stack); no hand-written scene comes close.",
        example: "let x = ((((((((((…1…))))))))));   // 129 levels",
    },
    Entry {
        code: RGB_OF_RGB,
        title: "`rgb` applied to an `rgb` without brackets",
        explanation: "`rgb` takes one value (a number or a 3-vector); `rgb rgb 1` is almost always a typing slip. Write the colour once, or bracket the inner expression.",
        example: "diffuse rgb rgb 0.5",
    },
    Entry {
        code: DIRECTIVE,
        title: "A POV-Ray `#` directive",
        explanation: "ptsc has no `#` directives. `#declare` and `#local` are `let`, `#include` is `include`, `#for`/`#while` are `for i in a..b { … }`; the help names the ptsc form when there is one.",
        example: "#declare R = 1;",
    },
    Entry {
        code: OBJECT_AS_VALUE,
        title: "An object used as a value",
        explanation: "Constants hold numbers, vectors, colours and booleans, not objects: `let ball = sphere { … };` is not a value. An object is named by a group, `group ball { sphere { … } }`, and placed (moved, turned, scaled) by each `instance ball { … }`; a `for` loop places many.",
        example: "let ball = sphere { center <0, 0, 0> radius 1 };",
    },
    Entry {
        code: INTERNAL,
        title: "The parser disagreed with itself",
        explanation: "Large files are parsed in pieces; a file that parses whole must parse in pieces too. This error means the two disagreed: it is a ptsc bug, and the file that shows it is worth reporting.",
        example: "(no scene should produce it)",
    },
    Entry {
        code: UNKNOWN_NAME,
        title: "A name that is not defined",
        explanation: "An expression uses a constant that no `let` (or `for` variable) defines before this point. Constants are defined in order: a `let` after its use does not count. The help suggests a similar name when there is one.",
        example: "sphere { center <0, 0, 0> radius raduis }\nlet radius = 1;",
    },
    Entry {
        code: UNKNOWN_FUNCTION,
        title: "A function that does not exist",
        explanation: "The name before `(` is neither a function declared before it with `fn name(x) = …;` nor one of the built-in functions: `sin`, `cos`, `tan`, `asin`, `acos`, `atan2`, `sqrt`, `pow`, `exp`, `log`, `abs`, `min`, `max`, `clamp`, `floor`, `ceil`, `round`, `int`, `mod`, `radians`, `degrees`, `normalize`, `length`, `dot`, `cross`, `len`, `str`, `rand` (see docs/language.md). The help suggests a similar name when there is one, or the ptsc name of a POV-Ray function (`vlength` is `length`).",
        example: "let x = sine(1);",
    },
    Entry {
        code: WRONG_ARGUMENT_COUNT,
        title: "A call with the wrong number of arguments",
        explanation: "A function (built-in or declared with `fn`) was called with more or fewer arguments than it takes.",
        example: "let m = max(1);",
    },
    Entry {
        code: UNKNOWN_COMPONENT,
        title: "A component a vector or colour does not have",
        explanation: "`v.x`, `v.y`, `v.z` (and `v.t`, `v.u`, `v.v`, as POV-Ray names them) read a vector's components; `c.red`, `c.green`, `c.blue` a colour's. ptsc colours have no filter or transmit channel; a list's items are read with `xs[i]`.",
        example: "let v = <1, 2, 3>;\nlet w = v.w;",
    },
    Entry {
        code: FILTER_COLOR,
        title: "A colour with filter or transmit channels",
        explanation: "POV-Ray's `rgbf`, `rgbt` and `rgbft` colours make a surface see-through. ptsc colours have three channels; a see-through material gives `transmission` (a smooth dielectric lobe: with `ior 1` light passes unbent, as through POV-Ray's filter without an `interior`). The help writes the colour and the transmission from the values given.",
        example: "material m { diffuse rgbf <1, 1, 1, 0.5> }",
    },
    Entry {
        code: FOREIGN_BLOCK,
        title: "A block ptsc does not have",
        explanation: "A statement or block ptsc does not have: POV-Ray's `light_source { … }`, `union { … }` or a misspelt `shpere { … }` where a statement goes, or a block inside an object. An object or material holds parameters (`name value`), textures (`diffuse checker { … }`) and a `material`, not other blocks. POV-Ray's `pigment { … }`, `finish { … }`, `texture { … }`, `normal { … }` and `interior { … }` are all parameters of one ptsc `material { … }`; the help says which. The rest of the scene is still checked.",
        example: "sphere { center <0, 0, 0> radius 1 pigment { color rgb 1 } }",
    },
    Entry {
        code: MISSING_VALUE,
        title: "A parameter without its value",
        explanation: "A block's last entry is a name alone: a parameter is a name and its value (`radius 1`), and an object names its material with `material NAME`. POV-Ray's flags (`no_shadow`, `hollow`) get their own answer.",
        example: "sphere { center <0, 0, 0> radius }",
    },
    Entry {
        code: POSITIONAL_VALUES,
        title: "Values without parameter names",
        explanation: "ptsc names every parameter: POV-Ray's `sphere { <0, 1, 0>, 1 }` is `sphere { center <0, 1, 0> radius 1 }`. The help writes the block with the names the values stand for, in POV-Ray's order, and says where ptsc's meaning differs (a plane is given by a point on it rather than a distance, a box by its smaller and larger corners). A checker's two colours are `even` and `odd`, a material's colour alone (POV-Ray's pigment) is its `diffuse`.",
        example: "sphere { <0, 1, 0>, 1 }",
    },
    Entry {
        code: INDEX_OUT_OF_RANGE,
        title: "An index outside a list",
        explanation: "Lists, vectors, colours and strings are indexed from 0: a list of 3 has the items 0, 1 and 2. The label gives the valid range; `len(xs)` is the number of items, one past the last index. `&&` evaluates its right side only when the left is true, so `i < len(xs) && xs[i] > 0` is safe.",
        example: "let xs = [1, 2, 3];\nlet x = xs[3];",
    },
    Entry {
        code: VALUE_TOO_LARGE,
        title: "A list or string too large",
        explanation: "A list holds at most 1,000,000 items and all the lists (and strings, 16 bytes counting as one item) a scene builds together 2,000,000; a string holds at most 4,096 bytes. The limits keep the memory of a compile bounded whatever the scene doubles or repeats. Large generated geometry belongs in a mesh file.",
        example: "let a = [0, 0, 0, 0, 0, 0, 0, 0];\nlet b = a + a + a + a + a + a + a + a;\nlet c = b + b + b + b + b + b + b + b;\nlet d = c + c + c + c + c + c + c + c;\nlet e = d + d + d + d + d + d + d + d;\nlet f = e + e + e + e + e + e + e + e;\nlet g = f + f + f + f + f + f + f + f;\nlet h = g + g;",
    },
    Entry {
        code: RECURSION_LIMIT,
        title: "Function calls nested too deeply or made too often",
        explanation: "A user function may call itself (or another function) but the calls nest at most 64 deep and a scene makes at most 1,000,000 calls; evaluation in all nests at most 1,024 levels. A recursion needs an `if` whose other arm stops calling; a function that calls itself twice doubles its calls at each level. Evaluation always ends: this error instead of a hang or a crash.",
        example: "fn forever(n) = forever(n + 1);\nlet x = forever(0);",
    },
    Entry {
        code: UNKNOWN_GROUP,
        title: "An instance of a group that is not declared",
        explanation: "`instance name { … }` places the group declared by `group name { … }` earlier in the scene (or an included file). Groups are declared before they are placed. The help suggests a similar name when there is one.",
        example: "group chair { box { min <0, 0, 0> max <1, 1, 1> } }\ninstance chiar { translate <2, 0, 0> }",
    },
    Entry {
        code: GROUP_CYCLE,
        title: "A group that contains itself",
        explanation: "A group places itself (directly, while it is being declared): it would hold infinitely many copies. Place another group, or build the repetition with a `for` loop.",
        example: "group tower {\n    box { min <0, 0, 0> max <1, 1, 1> }\n    instance tower { translate <0, 1, 0> }\n}",
    },
    Entry {
        code: EMPTY_GROUP,
        title: "An instance of a group that holds nothing",
        explanation: "A warning: the group placed holds no object (its loops ran no times, its `if` chose no branch, or it is empty), so the instance adds nothing to the image.",
        example: "group nothing { }\ninstance nothing { }",
    },
    Entry {
        code: NOT_IN_GROUP,
        title: "A statement a group cannot hold",
        explanation: "A group holds objects (shapes and meshes), lights (`point_light`, `spot_light`, `directional_light`: each placement places them), placements of other groups, and the `let`, `fn`, `for` and `if` statements that build them. Settings (`render`, `camera`), the background, environment and sky, declarations of materials, textures and groups belong at the top level of a scene.",
        example: "group lamp {\n    camera { position <0, 2, 5> look_at <0, 0, 0> }\n}",
    },
    Entry {
        code: TYPE_MISMATCH,
        title: "A value of the wrong type",
        explanation: "A number was given where a vector or colour is expected (or the reverse), two values of kinds an operator cannot combine were combined, or a parameter received the wrong kind of value. The labels show each operand's type; `rgb` applies to the one value after it, so `rgb 0.5 + 0.1` is a colour plus a number: write `rgb (0.5 + 0.1)`.",
        example: "sphere { center 1 radius 1 }",
    },
    Entry {
        code: UNKNOWN_WORD,
        title: "A word outside the accepted set",
        explanation: "A parameter that takes a word (such as `integrator path`) got one it does not know. The message lists the words it accepts.",
        example: "render { integrator pathtracer }",
    },
    Entry {
        code: DIVISION_BY_ZERO,
        title: "Division by zero",
        explanation: "An expression divides (or takes a remainder) by zero. Expressions are evaluated when the scene is checked, so the error points at the exact operation.",
        example: "let x = 1 / 0;",
    },
    Entry {
        code: DOMAIN,
        title: "A function argument outside its domain",
        explanation: "A built-in function got an argument it has no value for: the square root of a negative number, `normalize` of a zero vector.",
        example: "let x = sqrt(-1);",
    },
    Entry {
        code: NOT_FINITE,
        title: "An infinite or NaN value",
        explanation: "An expression overflowed to infinity or produced NaN. Every value of a scene must be a finite number.",
        example: "let x = 1e300 * 1e300;",
    },
    Entry {
        code: UNKNOWN_PARAM,
        title: "A parameter the block does not have",
        explanation: "The block has no parameter of that name. The help suggests the closest one, or the ptsc word for a POV-Ray word (`location` → `position`, `angle` → `fov`, `pigment` → `diffuse`).",
        example: "sphere { center <0, 0, 0> radus 1 }",
    },
    Entry {
        code: DUPLICATE_PARAM,
        title: "A parameter given twice",
        explanation: "The same parameter appears twice in one block; the second would silently win, so it is an error. The first one is marked too.",
        example: "sphere { center <0, 0, 0> radius 1 radius 2 }",
    },
    Entry {
        code: MISSING_PARAM,
        title: "A required parameter not given",
        explanation: "The block needs this parameter and has no default for it (a sphere's `radius`, a camera's `position`).",
        example: "sphere { center <0, 0, 0> }",
    },
    Entry {
        code: OUT_OF_RANGE,
        title: "A value outside its allowed range",
        explanation: "A number is outside what its parameter accepts: a negative radius, a gloss above 1, a resolution too large, an index of refraction below 1, or geometry that reaches beyond ±1e9 after its transforms and motion (the renderer computes in 32-bit floats). The label gives the range.",
        example: "sphere { center <0, 0, 0> radius -1 }",
    },
    Entry {
        code: DEGENERATE,
        title: "Geometry without area or volume",
        explanation: "Something has no extent or no direction: a quad with parallel edges, a triangle with three points on a line, a box whose `min` is not below its `max`, a mesh whose every triangle has zero area, an object too small for 32-bit floats after its transforms, a camera looking at its own position or with `up` along its view, a spot light pointing at its own position, an emissive infinite plane.",
        example: "triangle { v0 <0, 0, 0> v1 <1, 0, 0> v2 <2, 0, 0> }",
    },
    Entry {
        code: DUPLICATE_NAME,
        title: "A name declared twice",
        explanation: "Two `let`s or two named materials share a name. Names are declared once; the first declaration is marked.",
        example: "let r = 1;\nlet r = 2;",
    },
    Entry {
        code: DUPLICATE_BLOCK,
        title: "A second `render`, `camera` or `background`",
        explanation: "A scene has at most one of each of these blocks; the second would silently replace the first.",
        example: "camera { position <0, 0, 5> look_at <0, 0, 0> }\ncamera { position <0, 0, 9> look_at <0, 0, 0> }",
    },
    Entry {
        code: UNKNOWN_MATERIAL,
        title: "A material that does not exist",
        explanation: "`material NAME` names no declared material. Named materials may be declared anywhere in the scene (before or after their use); the help suggests a similar name.",
        example: "sphere { center <0, 0, 0> radius 1 material coper }\nmaterial copper { reflection rgb <0.95, 0.64, 0.54> }",
    },
    Entry {
        code: UNKNOWN_TEXTURE,
        title: "A texture kind that does not exist",
        explanation: "A parameter was given `NAME { … }` and NAME is not a kind of texture. The kinds are listed in docs/language.md (\"Textures\"); the help suggests the closest one.",
        example: "material { diffuse checkers { even rgb 1 odd rgb 0 } }",
    },
    Entry {
        code: TEXTURE_NOT_ALLOWED,
        title: "A texture given to a parameter that takes a plain value",
        explanation: "Only a material's parameters vary over a surface: its colours (`diffuse`, `reflection`, `absorption`, `emission`), its numbers `gloss` and `transmission`, and its `normal_map` and `bump`. The others (an index of refraction, a radius, a light's intensity) take one value.",
        example: "material { diffuse rgb 0.5 ior checker { } }",
    },
    Entry {
        code: UNORDERED_STOPS,
        title: "Colour stops out of order",
        explanation: "A texture's colour map lists its stops by position, from 0 to 1; a stop placed before the one written above it is refused (two stops at the same position make a sharp edge).",
        example: "material { diffuse marble { stop 0.6 rgb 1 stop 0.2 rgb 0 } }",
    },
    Entry {
        code: INCLUDE_NOT_FOUND,
        title: "An included file that cannot be read",
        explanation: "The file named by `include` does not exist or cannot be read. The path is relative to the file that includes it.",
        example: "include \"materials.ptsi\"",
    },
    Entry {
        code: INCLUDE_CYCLE,
        title: "A file that includes itself",
        explanation: "A chain of includes leads back to a file already being read; it would never end. The notes show the chain.",
        example: "// a.pts\ninclude \"a.pts\"",
    },
    Entry {
        code: INVALID_UTF8,
        title: "A file that is not valid UTF-8",
        explanation: "Scene files are UTF-8 text. Each invalid byte is read as `?` so that every other diagnostic still points at the right place; re-save the file as UTF-8.",
        example: "(a file saved as Latin-1 with an accented letter in a comment)",
    },
    Entry {
        code: NOT_A_SCENE,
        title: "A file that is not a scene",
        explanation: "An image, a model or another binary file was given where a scene goes (`ptsc render photo.png`) or included. It is told by its first bytes (the text formats of models by their extension) and not read as a scene, so that its bytes do not come back as a page of syntax errors. Scenes name images in textures (`diffuse image { file \"photo.png\" }`) and load models with `mesh { file \"model.obj\" }`.",
        example: "(`ptsc render photo.png`: an image where a scene goes)",
    },
    Entry {
        code: MISSING_CAMERA,
        title: "A scene without a camera",
        explanation: "A scene needs one `camera { position … look_at … }` block.",
        example: "sphere { center <0, 0, 0> radius 1 }",
    },
    Entry {
        code: LOOP_TOO_LONG,
        title: "Loops that run too many statements",
        explanation: "Loops and repeated includes run at most 4,000,000 statements in all, counted by their text, so that every scene checks in bounded time and memory. Use fewer iterations, or a mesh for very many triangles.",
        example: "for i in 0..100000000 { sphere { center <i, 0, 0> radius 0.5 } }",
    },
    Entry {
        code: EVALUATION_TOO_LONG,
        title: "Expressions that do too much work",
        explanation: "The expressions of a scene take at most 25,000,000 steps of work in all, so that every scene checks in seconds whatever its loops, functions and lists do. A step is an expression evaluated in a loop, in a file included again or in a function's body; a list item compared by `==` or `!=`; a byte of text written by `str`; and 16 bytes of a string or two components of a vector made or scanned (naming a value copies nothing). (An expression run once at the top level of a file costs nothing: its text bounds it.) Compare and print large lists outside loops, call long functions less often, and put large generated data in a mesh file.",
        example: "let a = [0, 0, 0, 0, 0, 0, 0, 0];\nlet b = a + a + a + a + a + a + a + a;\nlet c = b + b + b + b + b + b + b + b;\nlet d = c + c + c + c + c + c + c + c;\nlet e = d + d + d + d + d + d + d + d;\nlet f = d + d + d + d + d + d + d + d;\nfor i in 0..2000 { let _same = e == f; }",
    },
    Entry {
        code: OUTPUT_FILE,
        title: "An output image that cannot be written",
        explanation: "`render { output … }` names the image a render writes (unless `-o` names another): a `.png`, `.exr` or `.pfm` file in a folder that exists and takes new files, and not a file the scene reads (the scene itself, an include, a mesh), which the image would replace. A `#` in the name is the frame's number. `check` tests it as `render` does, before the first sample.",
        example: "render { output \"renders/final.jpg\" }",
    },
    Entry {
        code: MESH_FILE,
        title: "A mesh file that is missing, unreadable or of an unknown format",
        explanation: "`mesh { file … }` reads OBJ and PLY (ASCII, binary little and big endian) files with at least one triangle. The label says what went wrong: the file is missing, has another extension, or its contents are broken (the line or element is named).",
        example: "mesh { file \"bunny.stl\" }",
    },
    Entry {
        code: TOO_MANY_PRIMITIVES,
        title: "A scene making more primitives than the renderer holds",
        explanation: "A scene (and each group's shared copy) makes at most 50,000,000 primitives, a mesh triangle counting one and a box six: about 4 GB once built. Placements of a group are shared, not copied, so a group of a large mesh placed a thousand times costs one mesh; only its planes and the objects emissive under a placement are copied at each placement. The limit is checked before anything is built, so `check` reports it as `render` does.",
        example: "group lamp {\n  mesh { file \"million_triangles.ply\" material { emission rgb 5 } }\n}\nfor i in 0..1000 { instance lamp { translate <i, 0, 0> } }",
    },
    Entry {
        code: SINGULAR_TRANSFORM,
        title: "A transform that cannot be inverted",
        explanation: "A scale by zero or a matrix with a zero determinant flattens the object into nothing; the renderer needs the inverse of every transform.",
        example: "sphere { center <0, 0, 0> radius 1 scale <1, 0, 1> }",
    },
    Entry {
        code: NON_UNIFORM_SCALE,
        title: "A round shape under a non-uniform scale",
        explanation: "Spheres, disks, cylinders, cones and tori are stored exactly (centres, axes and radii), so they take translations, rotations and uniform scales only. A non-uniform scale or a shear would make an ellipsoid, an ellipse or an elliptic cylinder: use a mesh for those.",
        example: "sphere { center <0, 0, 0> radius 1 scale <2, 1, 1> }",
    },
    Entry {
        code: IMAGE_FILE,
        title: "An image file that is missing, unreadable or of an unknown format",
        explanation: "`image { file … }` and `environment { file … }` read PNG and JPEG (8- and 16-bit: colours decoded from sRGB, data such as normal maps as they are), Radiance HDR and OpenEXR (linear) files, relative to the scene file; an image a model names (an MTL library's map, a glTF's `images` entry) is read relative to that model file, and the message names the entry, the material and the file. The label says what went wrong: the file is missing, is not a regular file (a folder, a device, a FIFO), is of another format (read from its first bytes, else from its extension), cannot be decoded, is larger than ptsc reads (a file of 1 GiB, 32,768 texels a side, 16,384² texels), is shorter than the texels its header claims (truncated, or a hostile header), would take the scene's images past the 4 GiB they may hold together (the label gives the total), or holds texels that are not finite, non-negative numbers. Sizes are checked on the file's header, before its texels are decoded.",
        example: "material { diffuse image { file \"wood.gif\" } }",
    },
    Entry {
        code: NOT_LATLONG,
        title: "An environment map that is not equirectangular",
        explanation: "`environment { file … }` reads a latitude-longitude image: 360° across, 180° down, so twice as wide as high. Another shape still renders, stretched. A cube map or a mirror-ball photograph has to be converted first (e.g. with Blender or HDRShop).",
        example: "environment { file \"square.hdr\" }",
    },
    Entry {
        code: NO_TEXCOORDS,
        title: "A texture in (u, v) on a mesh without texture coordinates",
        explanation: "A texture that reads the surface's (u, v) (an image, a `checker`, or any texture with `space uv`) was given to a mesh whose file has no texture coordinates (OBJ `vt`, PLY `u v`). Each triangle then reads its own barycentrics, so the texture repeats once per triangle, which is rarely meant. Export the mesh with UVs, or use a solid texture (`space object`).",
        example: "mesh { file \"bunny.ply\" material { diffuse image { file \"fur.png\" } } }",
    },
    Entry {
        code: UNUSED_MATERIAL,
        title: "Warning: a material never used",
        explanation: "A named material is declared and no object uses it: often a typo in a `material NAME` elsewhere.",
        example: "material gold { reflection rgb <1, 0.8, 0.3> }",
    },
    Entry {
        code: UNUSED_CONSTANT,
        title: "Warning: a constant never used",
        explanation: "A `let` defines a constant that nothing reads. Prefix its name with `_` to keep it on purpose.",
        example: "let unused = 3;",
    },
    Entry {
        code: NO_LIGHT,
        title: "Warning: nothing emits light",
        explanation: "The scene has no light, no emissive object and a black background: every integrator but the debug ones renders black.",
        example: "camera { position <0, 0, 5> look_at <0, 0, 0> }\nsphere { center <0, 0, 0> radius 1 }",
    },
    Entry {
        code: SCENE_MEMORY,
        title: "A scene too large for the memory free",
        explanation: "Loading a scene takes about 500 bytes for every object it places (its primitive and its share of the BVH), besides the check's own. When the objects that loops and groups of groups place would need more than the memory free (the machine's available memory, its control group's limit, `ulimit -v`, or `--memory-limit`), the scene is refused before loading starts, instead of the process ending when an allocation fails. Place fewer objects (a mesh holds many triangles in far less memory), free memory, or give `--memory-limit` when the memory is there after all.",
        example: "// with --memory-limit 100M\ncamera { position <0, 0, 5> look_at <0, 0, 0> }\nfor i in 0..1000 { for j in 0..1000 { sphere { center <i, j, 0> radius 0.1 } } }",
    },
    Entry {
        code: DIM_LIGHT,
        title: "Warning: lights too far or too weak for what the camera looks at",
        explanation: "The scene is lit only by point and spot lights, and together they give the point the camera looks at an irradiance below 0.01 (intensity over distance squared): a diffuse surface there renders all but black. ptsc's lights fall off with the square of the distance, as physical lights do; POV-Ray's `light_source` does not (unless `fade_power 2`), so a POV-Ray light far away with `color rgb 1` is far too weak here. Raise the intensity to about the distance squared, move the light closer, or light the scene from far away with a `directional_light`.",
        example: "camera { position <0, 1, -5> look_at <0, 0, 0> }\npoint_light { position <500, 500, -500> intensity rgb 1 }\nsphere { center <0, 0, 0> radius 1 }",
    },
    Entry {
        code: SHADOWED_IN_LOOP,
        title: "Warning: a loop's constant that reads the one it hides",
        explanation: "Constants never change. `let n = n + 1;` in a loop's body declares a new `n` for that pass of the loop, computed from the outer `n`, which stays as it was: no pass sees the value of the pass before, and after the loop `n` is what it was before it. Compute the value from the loop variable instead (`let n = start + i;`), or give the new constant its own name.",
        example: "let n = 0;\nfor i in 0..3 {\n    let n = n + 1;\n    sphere { center <n, 0, 0> radius 0.3 }\n}",
    },
    Entry {
        code: ENERGY_GAIN,
        title: "Warning: a material that would reflect more than it receives",
        explanation: "A diffuse albedo above 1, or lobes (diffuse, reflection, transmission) that add up to more than 1. Physically impossible: the renderer scales the lobes down so that the material conserves energy, which is probably not what was meant.",
        example: "material { diffuse rgb 0.8 reflection rgb 0.5 }",
    },
    Entry {
        code: INTEGRATOR_SETTING,
        title: "Warning: a setting that biases the image or has no effect with this integrator",
        explanation: "Some settings do not suit the integrator chosen: `ambient` adds light that no source emits, which biases the `path` integrator (it is the paper's term for Whitted shading); `whitted` with `light_samples 0` sends no shadow ray to area lights, so a scene lit only by them renders without direct light; `bdpt` and `ptlt` apply neither `ambient` nor `clamp`, and leave a scene with media to the path integrator.",
        example: "render { integrator path ambient rgb 0.1 }",
    },
    Entry {
        code: NO_EFFECT,
        title: "Warning: a parameter that has no effect",
        explanation: "A parameter whose lobe is absent does nothing: `gloss` without `reflection`, `absorption` without `transmission`; so does one that a material's `type` does not use (`diffuse` on a conductor, `preset` on a plastic).",
        example: "material { diffuse rgb 0.5 gloss 0.3 }",
    },
    Entry {
        code: CONFLICTING_PARAMS,
        title: "Two parameters that say the same thing",
        explanation: "A conductor's optical constants come from a `preset` or from `eta` and `k`, not both: the preset would silently win.",
        example: "material { type conductor preset gold eta rgb 0.2 k rgb 3 }",
    },
    Entry {
        code: IO_READ,
        title: "The scene file cannot be read",
        explanation: "The file given on the command line does not exist, is a folder, or cannot be read. With `--format json` this is the one diagnostic printed; the exit code is 2 (a usage problem), not 1.",
        example: "ptsc check missing.pts",
    },
];

/// The catalogue entry of `code`: its full name (`pts::check::unknown_param`)
/// or its last part (`unknown_param`).
pub fn lookup(code: &str) -> Option<&'static Entry> {
    CATALOGUE
        .iter()
        .find(|e| e.code == code || e.code.rsplit("::").next() == Some(code))
}

/// The catalogue as Markdown: the text of `docs/diagnostics.md`.
pub fn markdown() -> String {
    let mut out = String::from(
        "# Diagnostic codes\n\n\
         Every code ptsc reports, generated from `src/diag/codes.rs` (a test \
         keeps this file in step: `cargo run -- explain --all > docs/diagnostics.md`). \
         `ptsc explain CODE` prints one entry; the code may be given in full or by its \
         last part (`ptsc explain unknown_param`). Codes are stable: editors and \
         scripts may match on them.\n\n\
         | Code | Problem |\n| --- | --- |\n",
    );
    for e in CATALOGUE {
        out += &format!("| [`{}`](#{}) | {} |\n", e.code, anchor(e.code), e.title);
    }
    for e in CATALOGUE {
        out += &format!("\n## {}\n\n{}.\n\n{}\n\n", e.code, e.title, e.explanation);
        out += &format!("```pts\n{}\n```\n", e.example);
    }
    out
}

/// The Markdown anchor of a heading that is a code (GitHub's rule: lower
/// case, punctuation but `-` and `_` dropped).
fn anchor(code: &str) -> String {
    code.chars()
        .filter(|c| c.is_alphanumeric() || *c == '_' || *c == '-')
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_unique_and_found_by_either_name() {
        let mut seen = std::collections::BTreeSet::new();
        for e in CATALOGUE {
            assert!(seen.insert(e.code), "{} twice", e.code);
            assert!(e.code.starts_with("pts::"));
            assert!(!e.explanation.is_empty() && !e.example.is_empty());
        }
        assert_eq!(lookup("unknown_param").unwrap().code, UNKNOWN_PARAM);
        assert_eq!(lookup(UNKNOWN_PARAM).unwrap().code, UNKNOWN_PARAM);
        assert!(lookup("no_such_code").is_none());
        let mut last_parts = std::collections::BTreeSet::new();
        for e in CATALOGUE {
            let last = e.code.rsplit("::").next().unwrap();
            assert!(last_parts.insert(last), "`{last}` ends two codes");
        }
    }
}
