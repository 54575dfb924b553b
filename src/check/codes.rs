//! Stable diagnostic codes, one per kind of problem. Editors and CI scripts
//! match on these; never rename one.

/// Syntax errors come from `syntax::parser` (`pts::syntax::*`).
pub const UNKNOWN_NAME: &str = "pts::check::unknown_name";
/// A function that does not exist.
pub const UNKNOWN_FUNCTION: &str = "pts::check::unknown_function";
/// A call with the wrong number of arguments.
pub const WRONG_ARGUMENT_COUNT: &str = "pts::check::argument_count";
/// A value of the wrong type.
pub const TYPE_MISMATCH: &str = "pts::check::type_mismatch";
/// A word that is not in the accepted set (integrator names).
pub const UNKNOWN_WORD: &str = "pts::check::unknown_word";
/// Division by zero in an expression.
pub const DIVISION_BY_ZERO: &str = "pts::check::division_by_zero";
/// A function argument outside its domain.
pub const DOMAIN: &str = "pts::check::domain";
/// An infinite or NaN value.
pub const NOT_FINITE: &str = "pts::check::not_finite";
/// A parameter a block does not have.
pub const UNKNOWN_PARAM: &str = "pts::check::unknown_param";
/// A parameter given twice.
pub const DUPLICATE_PARAM: &str = "pts::check::duplicate_param";
/// A required parameter not given.
pub const MISSING_PARAM: &str = "pts::check::missing_param";
/// A value outside its allowed range.
pub const OUT_OF_RANGE: &str = "pts::check::out_of_range";
/// Geometry that has no area or volume.
pub const DEGENERATE: &str = "pts::check::degenerate";
/// A name declared twice.
pub const DUPLICATE_NAME: &str = "pts::check::duplicate_name";
/// A second `render`, `camera` or `background`.
pub const DUPLICATE_BLOCK: &str = "pts::check::duplicate_block";
/// A material that does not exist.
pub const UNKNOWN_MATERIAL: &str = "pts::check::unknown_material";
/// An included file that cannot be read.
pub const INCLUDE_NOT_FOUND: &str = "pts::check::include_not_found";
/// An include that includes itself.
pub const INCLUDE_CYCLE: &str = "pts::check::include_cycle";
/// A file that is not valid UTF-8.
pub const INVALID_UTF8: &str = "pts::check::invalid_utf8";
/// A scene without camera.
pub const MISSING_CAMERA: &str = "pts::check::missing_camera";
/// A loop that runs too often.
pub const LOOP_TOO_LONG: &str = "pts::check::loop_too_long";
/// A mesh file that is missing or of an unknown format.
pub const MESH_FILE: &str = "pts::check::mesh_file";
/// A transform that cannot be inverted.
pub const SINGULAR_TRANSFORM: &str = "pts::check::singular_transform";
/// Warning: a material never used.
pub const UNUSED_MATERIAL: &str = "pts::check::unused_material";
/// Warning: a constant never used.
pub const UNUSED_CONSTANT: &str = "pts::check::unused_constant";
/// Warning: nothing emits light.
pub const NO_LIGHT: &str = "pts::check::no_light";
/// Warning: a material reflects more than it receives.
pub const ENERGY_GAIN: &str = "pts::check::energy_gain";
/// Warning: a setting that biases the image or has no effect with this integrator.
pub const INTEGRATOR_SETTING: &str = "pts::check::integrator_setting";
/// Warning: a parameter that has no effect.
pub const NO_EFFECT: &str = "pts::check::no_effect";
