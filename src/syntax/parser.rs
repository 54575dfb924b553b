//! The pest parser and the translation of pest errors into ptsc diagnostics
//! with human words (never `Rule::expr`).

use crate::diag::{codes, Diagnostic};
use crate::source::FileId;
use crate::span::Span;
use pest::error::{ErrorVariant, InputLocation};

use super::error_context::*;
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
fn describe_found(text: &str, pos: usize) -> String {
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

/// Converts a pest error into a diagnostic pointing at the failing token;
/// pest parsed `text[base..]`.
pub fn convert_error(
    err: pest::error::Error<Rule>,
    file: FileId,
    (text, kinds): (&str, &[&str]),
    base: usize,
) -> Diagnostic {
    let pos = base
        + match err.location {
            InputLocation::Pos(p) => p,
            InputLocation::Span((s, _)) => s,
        };
    let d = diagnose(err, file, (text, kinds), base);
    super::nested_comment::explain(d, text, pos.min(text.len()), file)
}

/// The diagnostic for a pest error, from the token it failed at and the
/// text around it.
fn diagnose(
    err: pest::error::Error<Rule>,
    file: FileId,
    (text, kinds): (&str, &[&str]),
    base: usize,
) -> Diagnostic {
    let pos = base
        + match err.location {
            InputLocation::Pos(p) => p,
            InputLocation::Span((s, _)) => s,
        };
    let rest = &text[pos.min(text.len())..];
    let token_len = rest
        .chars()
        .next()
        .map(|c| {
            if c.is_alphanumeric() || c == '_' {
                rest.chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == '.')
                    .map(char::len_utf8)
                    .sum()
            } else {
                c.len_utf8()
            }
        })
        .unwrap_or(0);
    let span = Span::new(file, pos, pos + token_len);

    if rest.starts_with("/*") {
        return Diagnostic::error(
            codes::UNTERMINATED_COMMENT,
            "unterminated block comment",
            Span::new(file, pos, pos + 2),
        )
        .with_label("this comment is never closed")
        .with_help("close the comment with `*/`");
    }
    if rest.starts_with('"') {
        return Diagnostic::error(
            codes::UNTERMINATED_STRING,
            "unterminated string",
            Span::new(file, pos, pos + 1),
        )
        .with_label("this string has no closing quote on its line")
        .with_help("end the string with `\"` before the end of the line");
    }

    let found = describe_found(text, pos);
    if found == "`rgb`" && after_rgb(text.get(..pos).unwrap_or("")) {
        return Diagnostic::error(
            codes::RGB_OF_RGB,
            "`rgb` of `rgb`",
            span,
        )
        .with_label("a colour is already a colour")
        .with_help("write `rgb` once, e.g. `rgb 0.5`; to make a colour of an expression, put it in brackets: `rgb (a * 2)`");
    }
    if rest.trim().is_empty() {
        if let Some(&open) = open_braces(text).last() {
            let d = unclosed_block(file, open);
            return match kind_inside(text, open, kinds) {
                Some((at, kind)) => d.with_secondary(
                    Span::new(file, at, at + kind.len()),
                    format!("`{kind}` starts the next statement"),
                ),
                None => d,
            };
        }
    }
    // A statement keyword at the start of a line inside a block opened on
    // an earlier line: that block lacks its `}` (reported at its `{`, not
    // where the parser noticed).
    let word = found.trim_matches('`');
    if let Some((at, kw)) = statement_on_line(text, pos) {
        if let Some(&open) = open_braces(&text[..at]).last() {
            // Only where closing the block before the line gets the parse
            // further: a closed block is never blamed for an error on a
            // line that happens to start with a statement's word.
            // A file whose braces all pair up has no unclosed block.
            // The line may start before the piece being parsed (from
            // `base`) when that piece starts mid-line: then there is
            // nothing of the piece to close before it.
            if at >= base
                && block_brace(text, open)
                && !open_braces(text).is_empty()
                && closing_helps(text, base, at, pos)
            {
                return unclosed_block(file, open).with_secondary(
                    Span::new(file, at, at + kw.len()),
                    format!("`{kw}` starts the next statement"),
                );
            }
        }
    }
    if found == "`#`" {
        let directive: String = rest[1..]
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let help = super::povray::directive(&directive).map_or_else(
            || "ptsc has no `#` directives: write its statements without `#`: `let`, `include`, `for`, `if`, …".to_string(),
            str::to_string,
        );
        return Diagnostic::error(
            codes::DIRECTIVE,
            format!("`#{directive}` is a POV-Ray directive"),
            Span::new(file, pos, pos + 1 + directive.len()),
        )
        .with_label("not ptsc")
        .with_help(help);
    }
    let (expected, unexpected) = match &err.variant {
        ErrorVariant::ParsingError {
            positives,
            negatives,
        } => {
            let mut names: Vec<&str> = Vec::new();
            for r in positives {
                let n = rule_name(*r);
                if !names.contains(&n) {
                    names.push(n);
                }
            }
            let mut neg: Vec<&str> = Vec::new();
            for r in negatives {
                let n = rule_name(*r);
                if !neg.contains(&n) {
                    neg.push(n);
                }
            }
            // Noise unless nothing else fits: operators and indexes could
            // always continue an expression, a component `.x` follow any
            // operand, a colour stop is one more name where names are
            // expected; and where a parameter's value is expected, the `{`
            // of a foreign block and the `,` of positional values.
            let value_expected = positives
                .iter()
                .any(|r| rule_name(*r) == rule_name(Rule::expr));
            let noise = |r: &Rule| {
                matches!(
                    r,
                    Rule::bin_op
                        | Rule::component_op
                        | Rule::lbracket
                        | Rule::color_stop
                        | Rule::member
                ) || (value_expected && matches!(r, Rule::lbrace | Rule::comma))
            };
            let mut useful: Vec<&str> = Vec::new();
            for n in positives
                .iter()
                .filter(|r| !noise(r))
                .map(|r| rule_name(*r))
            {
                if !useful.contains(&n) {
                    useful.push(n);
                }
            }
            (if useful.is_empty() { names } else { useful }, neg)
        }
        ErrorVariant::CustomError { .. } => (Vec::new(), Vec::new()),
    };
    // At the start of a statement the full list of statement kinds is noise.
    let mut expected = expected;
    if expected.contains(&"`let`") && expected.contains(&"`include`") {
        expected = vec!["a statement"];
    }
    let message = if !expected.is_empty() {
        format!("expected {}, found {found}", join_or(&expected))
    } else if !unexpected.is_empty() {
        format!("unexpected {}", join_or(&unexpected))
    } else {
        format!("unexpected {found}")
    };
    let label = if !expected.is_empty() {
        format!("expected {} here", join_or(&expected))
    } else {
        "not allowed here".to_string()
    };
    let (previous, adjacent) = words_before(text, pos, 2);
    // `let ball = sphere { … }`: an object where a value goes.
    if found == "`{`" && expected.contains(&"`;`") {
        if let Some(kind) = previous.last().filter(|w| !KEYWORDS.contains(w)) {
            // `let ball = sphere {`: the constant's name, for the group's.
            let (three, _) = words_before(text, pos, 3);
            let name = match three.as_slice() {
                ["let" | "fn", name, _] => *name,
                _ => "name",
            };
            return Diagnostic::error(
                codes::OBJECT_AS_VALUE,
                format!("a `{kind}` is not a value"),
                span,
            )
            .with_label("an object's block")
            .with_help(format!("a constant holds a number, vector, colour or string; an object is named by a group and placed by instances: `group {name} {{ {kind} {{ … }} }}`, then `instance {name} {{ translate <1, 0, 0> }}` where it goes"));
        }
    }
    // `sphere { … hollow }`: a POV-Ray flag right before.
    if let Some((named, hint)) = previous
        .last()
        .filter(|_| adjacent)
        .and_then(|w| Some((*w, super::povray::flag(w)?)))
    {
        let end = text[..pos].trim_end().len();
        return Diagnostic::error(
            codes::UNEXPECTED_TOKEN,
            format!("`{named}` is a POV-Ray flag"),
            Span::new(file, end - named.len(), end),
        )
        .with_label("not ptsc")
        .with_help(hint);
    }
    // `material { … }`, `texture { … }` at the top level: a declaration
    // without its name.
    if found == "`{`" && expected.contains(&"a name") {
        let help = match previous.last().copied() {
            Some("material") => Some("a material declared here needs a name: `material NAME { diffuse rgb 0.8 }`, given to objects as `material NAME`; a material for one object goes inside it: `sphere { … material { … } }`".to_string()),
            Some("texture") => Some(format!(
                "a texture declared here needs a name and a kind: `texture NAME checker {{ … }}`, given to a material's parameter as `diffuse NAME`; {}",
                super::povray::block("texture").unwrap_or_default()
            )),
            _ => None,
        };
        if let Some(help) = help {
            return Diagnostic::error(codes::UNEXPECTED_TOKEN, message, span)
                .with_label(label)
                .with_help(help);
        }
    }
    // `let r = 1` and a statement on the next line: the `;` is missing at
    // the end of the line, not at the next statement (rustc's placement).
    let end = super::scan::code_end_before(text, pos);
    if expected == ["`;`"] && found.starts_with('`') && text[end..pos].contains('\n') {
        let at = Span::new(file, end, end);
        return Diagnostic::error(codes::UNEXPECTED_TOKEN, message, at)
            .with_label("add `;` here")
            .with_secondary(span, format!("{found} starts a new statement"))
            .with_help(help_for(&expected, &found))
            .with_fix(at, ";");
    }
    // `radius 1;` or `center <0, 0, 0>, radius 1` in a block: a separator
    // where entries just follow each other.
    if (found == "`;`" || found == "`,`") && expected.contains(&"`}`") {
        let sep = &found[1..2];
        return Diagnostic::error(codes::UNEXPECTED_TOKEN, message, span)
            .with_label(label)
            .with_help(format!(
                "a block's entries follow each other without `{sep}` between them: remove it"
            ))
            .with_fix(span, "");
    }
    let help = super::povray::hint(word)
        .map(str::to_string)
        .or_else(|| {
            // `sphere { … glass }`: a name without a value (not a number:
            // `radius 1;` is told above).
            let named = previous.last().filter(|_| adjacent)?;
            named.starts_with(|c: char| c.is_alphabetic() || c == '_').then_some(())?;
            expected.iter().any(|e| e.starts_with("a value")).then(|| match *named {
                "background" => "`background` takes a colour without braces: `background rgb <0.5, 0.7, 1>` (a daylight sky is `sky { … }`)".to_string(),
                _ => format!("`{named}` needs a value (e.g. `{named} 1`); a material is given as `material {named}`"),
            })
        })
        .or_else(|| {
            // `camera { orthographic location <…> }`: a POV-Ray word just
            // before (not a directive's: `#end` says its own).
            let directive = |w: &&str| {
                let before = &text[..pos];
                before.rfind(*w).is_some_and(|i| before[..i].ends_with('#'))
            };
            (previous.iter().filter(|w| !directive(w)))
                .find_map(|w| super::povray::hint(w))
                .map(str::to_string)
        })
        .or_else(|| range_habit(&text[..pos], &found))
        .or_else(|| missing_constant_value(&text[..pos], &expected, &found))
        .unwrap_or_else(|| help_for(&expected, &found));
    Diagnostic::error(codes::UNEXPECTED_TOKEN, message, span)
        .with_label(label)
        .with_help(help)
}
