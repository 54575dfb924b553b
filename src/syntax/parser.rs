//! The pest parser, and the human names of its rules and tokens that
//! syntax errors use (never `Rule::expr`; the errors' words: `hints.rs`).

pub use super::grammar::{PtsParser, Rule};
pub use super::words::KEYWORDS;

/// How a rule is called in an error message ("expected …").
/// Exhaustive on purpose: a new rule must get a human name.
pub fn rule_name(rule: Rule) -> &'static str {
    match rule {
        Rule::EOI => "end of file",
        Rule::WHITESPACE | Rule::COMMENT => "a blank or comment",
        Rule::file | Rule::statement | Rule::next_statement | Rule::only_blanks => "a statement",
        Rule::let_stmt | Rule::let_head | Rule::kw_let => "`let`",
        Rule::unended => "a statement",
        Rule::include_stmt | Rule::kw_include => "`include`",
        Rule::for_stmt | Rule::kw_for => "`for`",
        Rule::body => "statements in braces `{ … }`",
        Rule::if_stmt | Rule::if_expr | Rule::kw_if => "`if`",
        Rule::kw_else => "`else`",
        Rule::fn_stmt | Rule::fn_head | Rule::kw_fn => "`fn`",
        Rule::group_stmt | Rule::kw_group => "`group`",
        Rule::instance_stmt | Rule::kw_instance => "`instance`",
        Rule::list => "a list `[a, b, c]`",
        Rule::lbracket => "`[`",
        Rule::index => "an index `[i]`",
        Rule::rbracket => "`]`",
        Rule::not => "`!`",
        Rule::component_op => "an operator (`+`, `-`, `*`, `/`, `%`, `==`, `&&`, …)",
        Rule::kw_in => "`in`",
        Rule::background_stmt | Rule::kw_background => "`background`",
        Rule::material_decl | Rule::material_entry | Rule::kw_material => "`material`",
        Rule::block_stmt => "a block such as `sphere { … }`",
        Rule::block => "a block `{ … }`",
        Rule::entry | Rule::param => "a parameter name",
        Rule::foreign_block | Rule::opaque_block | Rule::opaque_text => "a block `{ … }`",
        Rule::positional | Rule::axis_word => "a value",
        Rule::foreign_stmt | Rule::directive_stmt | Rule::directive_rest => "a statement",
        Rule::declare_stmt | Rule::declare_word => "`let`",
        Rule::flag => "a parameter name",
        Rule::member => "a component `.x`",
        Rule::filter_color | Rule::filter_word => "a colour `rgb …`",
        Rule::texture_param => "a parameter given a texture",
        Rule::texture_decl | Rule::kw_texture => "`texture`",
        Rule::color_stop | Rule::stop_word => "a colour stop `stop 0.5 rgb …`",
        Rule::materials_entry | Rule::materials_word => "`materials { … }`",
        Rule::material_swap => "a material's name in quotes and a material (`\"Leaf\" green`)",
        Rule::expr | Rule::component | Rule::operand | Rule::primary => {
            "a value (number, vector, colour, string or name)"
        }
        Rule::paren | Rule::lparen => "`(`",
        Rule::rparen => "`)`",
        Rule::call => "a function call",
        Rule::vector | Rule::langle => "a vector `<x, y, z>`",
        Rule::rangle => "`>`",
        Rule::color | Rule::kw_rgb => "a colour `rgb …`",
        Rule::color_value => "a grey level or an `<r, g, b>` triple",
        Rule::boolean | Rule::kw_true | Rule::kw_false => "`true` or `false`",
        Rule::number => "a number",
        Rule::string | Rule::string_body => "a string",
        Rule::ident => "a name",
        Rule::keyword | Rule::entry_word => "a keyword",
        Rule::boundary => "the end of a word",
        Rule::bin_op => "an operator (`+`, `-`, `*`, `/`, `%`, `==`, `<`, `&&`, …)",
        Rule::neg => "`-`",
        Rule::equals => "`=`",
        Rule::semicolon => "`;`",
        Rule::range_dots => "`..`",
        Rule::lbrace => "`{`",
        Rule::rbrace => "`}`",
        Rule::comma => "`,`",
    }
}

/// Joins names as "a, b or c".
pub fn join_or(names: &[&str]) -> String {
    match names {
        [] => String::new(),
        [one] => one.to_string(),
        [init @ .., last] => format!("{} or {}", init.join(", "), last),
    }
}

/// Describes what stands at byte `pos` of `text`, for "found …".
pub(super) fn describe_found(text: &str, pos: usize) -> String {
    let rest = &text[pos.min(text.len())..];
    let Some(c) = rest.chars().next() else {
        return "end of file".into();
    };
    if c.is_alphabetic() || c == '_' {
        let word: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        return format!("`{word}`");
    }
    if c.is_ascii_digit() {
        let num: String = rest
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '.')
            .collect();
        return format!("`{num}`");
    }
    // Invisible characters (controls, format marks such as a byte order mark
    // out of place, non-breaking blanks) are named by their code point.
    let invisible =
        matches!(c, '\u{AD}' | '\u{200B}'..='\u{200F}' | '\u{2060}'..='\u{2064}' | '\u{FEFF}');
    if c.is_control() || c == '\u{FFFD}' || c.is_whitespace() || invisible {
        return format!("the character U+{:04X}", c as u32);
    }
    format!("`{c}`")
}
