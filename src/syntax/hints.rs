//! The words of a syntax error: rules tried in order, as data. The first
//! rules read the failing token and the text around it (an unterminated
//! comment, a POV-Ray directive, a block left open); the next ones also
//! read what the parser expected there (a missing `;`, a separator in a
//! block); a rule that does not apply answers `None`, and the last word
//! is the general "expected …, found …" with the best help found.

use super::error_context::*;
use super::parser::{describe_found, join_or, rule_name, Rule, KEYWORDS};
use crate::diag::{codes, Diagnostic};
use crate::source::FileId;
use crate::span::Span;
use pest::error::{ErrorVariant, InputLocation};

/// Where the parse failed, and what stands there.
pub(super) struct Failure<'t> {
    file: FileId,
    text: &'t str,
    /// The block kinds' names (for "`sphere` starts the next statement").
    kinds: &'t [&'t str],
    /// Where the piece being parsed starts.
    base: usize,
    /// Where it failed.
    pos: usize,
    /// The text from there on.
    rest: &'t str,
    /// The failing token.
    span: Span,
    /// The failing token in words ("`}`", "end of file").
    found: String,
}

/// What the parser expected where it failed, in words.
pub(super) struct Expected<'t> {
    /// The useful names of what would have fitted.
    names: Vec<&'static str>,
    /// "expected …, found …".
    message: String,
    /// "expected … here".
    label: String,
    /// The two words before the failing token, and whether the last one
    /// ends right before it (blanks aside).
    previous: (Vec<&'t str>, bool),
}

/// A rule that reads the failing token and the text.
type TokenRule = fn(&Failure) -> Option<Diagnostic>;

/// A rule that also reads what was expected.
type ExpectedRule = fn(&Failure, &Expected) -> Option<Diagnostic>;

/// The rules on the token, in the order they are tried.
const BY_TOKEN: &[TokenRule] = &[
    unterminated_comment,
    unterminated_string,
    rgb_of_rgb,
    unclosed_at_end,
    unclosed_before_statement,
    directive,
];

/// The rules on what was expected, tried after [`BY_TOKEN`]'s.
const BY_EXPECTED: &[ExpectedRule] = &[
    object_as_value,
    povray_flag,
    nameless_declaration,
    missing_semicolon,
    separator,
];

/// Converts a pest error into a diagnostic pointing at the failing token;
/// pest parsed `text[base..]`.
pub(super) fn convert_error(
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
    let d = diagnose(&err, file, (text, kinds), base);
    super::nested_comment::explain(d, text, pos.min(text.len()), file)
}

/// The diagnostic for a pest error, from the token it failed at and the
/// text around it; pest parsed `text[base..]`.
fn diagnose(
    err: &pest::error::Error<Rule>,
    file: FileId,
    (text, kinds): (&str, &[&str]),
    base: usize,
) -> Diagnostic {
    let f = Failure::at(err, file, (text, kinds), base);
    if let Some(d) = BY_TOKEN.iter().find_map(|rule| rule(&f)) {
        return d;
    }
    let e = Expected::of(err, &f);
    if let Some(d) = BY_EXPECTED.iter().find_map(|rule| rule(&f, &e)) {
        return d;
    }
    general(&f, &e)
}

impl<'t> Failure<'t> {
    /// Where `err` failed in `text[base..]`.
    fn at(
        err: &pest::error::Error<Rule>,
        file: FileId,
        (text, kinds): (&'t str, &'t [&'t str]),
        base: usize,
    ) -> Failure<'t> {
        let pos = base
            + match err.location {
                InputLocation::Pos(p) => p,
                InputLocation::Span((s, _)) => s,
            };
        let rest = &text[pos.min(text.len())..];
        let token_len = (rest.chars().next())
            .map(|c| match c.is_alphanumeric() || c == '_' {
                true => (rest.chars())
                    .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == '.')
                    .map(char::len_utf8)
                    .sum(),
                false => c.len_utf8(),
            })
            .unwrap_or(0);
        Failure {
            file,
            text,
            kinds,
            base,
            pos,
            rest,
            span: Span::new(file, pos, pos + token_len),
            found: describe_found(text, pos),
        }
    }

    /// The text before the failing token.
    fn before(&self) -> &'t str {
        self.text.get(..self.pos).unwrap_or("")
    }
}

impl<'t> Expected<'t> {
    /// What `err` expected at `f`.
    fn of(err: &pest::error::Error<Rule>, f: &Failure<'t>) -> Expected<'t> {
        let (mut names, unexpected) = match &err.variant {
            ErrorVariant::ParsingError {
                positives,
                negatives,
            } => (useful_names(positives), distinct_names(negatives)),
            ErrorVariant::CustomError { .. } => (Vec::new(), Vec::new()),
        };
        // At the start of a statement the full list of statement kinds is noise.
        if names.contains(&"`let`") && names.contains(&"`include`") {
            names = vec!["a statement"];
        }
        let found = &f.found;
        let message = match (names.is_empty(), unexpected.is_empty()) {
            (false, _) => format!("expected {}, found {found}", join_or(&names)),
            (true, false) => format!("unexpected {}", join_or(&unexpected)),
            (true, true) => format!("unexpected {found}"),
        };
        let label = match names.is_empty() {
            false => format!("expected {} here", join_or(&names)),
            true => "not allowed here".to_string(),
        };
        Expected {
            names,
            message,
            label,
            previous: words_before(f.text, f.pos, 2),
        }
    }
}

/// The names of `rules`, each once, in order.
fn distinct_names(rules: &[Rule]) -> Vec<&'static str> {
    let mut names: Vec<&str> = Vec::new();
    for n in rules.iter().map(|r| rule_name(*r)) {
        if !names.contains(&n) {
            names.push(n);
        }
    }
    names
}

/// The names of the rules that would have fitted (`positives`), without
/// those that are noise unless nothing else fits: operators and indexes
/// could always continue an expression, a component `.x` follow any
/// operand, a colour stop is one more name where names are expected; and
/// where a parameter's value is expected, the `{` of a foreign block and
/// the `,` of positional values.
fn useful_names(positives: &[Rule]) -> Vec<&'static str> {
    let value_expected = (positives.iter()).any(|r| rule_name(*r) == rule_name(Rule::expr));
    let noise = |r: &Rule| {
        matches!(
            r,
            Rule::bin_op | Rule::component_op | Rule::lbracket | Rule::color_stop | Rule::member
        ) || (value_expected && matches!(r, Rule::lbrace | Rule::comma))
    };
    let useful: Vec<Rule> = positives.iter().copied().filter(|r| !noise(r)).collect();
    match useful.is_empty() {
        true => distinct_names(positives),
        false => distinct_names(&useful),
    }
}

/// `/*` never closed.
fn unterminated_comment(f: &Failure) -> Option<Diagnostic> {
    f.rest.starts_with("/*").then(|| {
        let at = Span::new(f.file, f.pos, f.pos + 2);
        Diagnostic::error(
            codes::UNTERMINATED_COMMENT,
            "unterminated block comment",
            at,
        )
        .with_label("this comment is never closed")
        .with_help("close the comment with `*/`")
    })
}

/// A string without its closing quote on its line.
fn unterminated_string(f: &Failure) -> Option<Diagnostic> {
    f.rest.starts_with('"').then(|| {
        let at = Span::new(f.file, f.pos, f.pos + 1);
        Diagnostic::error(codes::UNTERMINATED_STRING, "unterminated string", at)
            .with_label("this string has no closing quote on its line")
            .with_help("end the string with `\"` before the end of the line")
    })
}

/// `rgb rgb 0.5`.
fn rgb_of_rgb(f: &Failure) -> Option<Diagnostic> {
    (f.found == "`rgb`" && after_rgb(f.before())).then(|| {
        Diagnostic::error(codes::RGB_OF_RGB, "`rgb` of `rgb`", f.span)
            .with_label("a colour is already a colour")
            .with_help("write `rgb` once, e.g. `rgb 0.5`; to make a colour of an expression, put it in brackets: `rgb (a * 2)`")
    })
}

/// The end of the file inside a block: the block is reported at its `{`,
/// with the kind that starts a statement inside it, if one does.
fn unclosed_at_end(f: &Failure) -> Option<Diagnostic> {
    if !f.rest.trim().is_empty() {
        return None;
    }
    let open = *open_braces(f.text).last()?;
    let d = unclosed_block(f.file, open);
    Some(match kind_inside(f.text, open, f.kinds) {
        Some((at, kind)) => d.with_secondary(
            Span::new(f.file, at, at + kind.len()),
            format!("`{kind}` starts the next statement"),
        ),
        None => d,
    })
}

/// A statement keyword at the start of a line inside a block opened on an
/// earlier line: that block lacks its `}` (reported at its `{`, not where
/// the parser noticed). Only where closing the block before the line gets
/// the parse further: a closed block is never blamed for an error on a
/// line that happens to start with a statement's word, and a file whose
/// braces all pair up has no unclosed block. The line may start before the
/// piece being parsed (from `base`) when that piece starts mid-line: then
/// there is nothing of the piece to close before it.
fn unclosed_before_statement(f: &Failure) -> Option<Diagnostic> {
    let (at, kw) = statement_on_line(f.text, f.pos)?;
    let open = *open_braces(&f.text[..at]).last()?;
    let blamed = at >= f.base
        && block_brace(f.text, open)
        && !open_braces(f.text).is_empty()
        && closing_helps(f.text, f.base, at, f.pos);
    blamed.then(|| {
        unclosed_block(f.file, open).with_secondary(
            Span::new(f.file, at, at + kw.len()),
            format!("`{kw}` starts the next statement"),
        )
    })
}

/// `#declare`, `#include`, …: POV-Ray's directives.
fn directive(f: &Failure) -> Option<Diagnostic> {
    if f.found != "`#`" {
        return None;
    }
    let directive: String = (f.rest[1..].chars())
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    let help = super::povray::directive(&directive).map_or_else(
        || "ptsc has no `#` directives: write its statements without `#`: `let`, `include`, `for`, `if`, …".to_string(),
        str::to_string,
    );
    let at = Span::new(f.file, f.pos, f.pos + 1 + directive.len());
    Some(
        Diagnostic::error(
            codes::DIRECTIVE,
            format!("`#{directive}` is a POV-Ray directive"),
            at,
        )
        .with_label("not ptsc")
        .with_help(help),
    )
}

/// `let ball = sphere { … }`: an object where a value goes.
fn object_as_value(f: &Failure, e: &Expected) -> Option<Diagnostic> {
    if f.found != "`{`" || !e.names.contains(&"`;`") {
        return None;
    }
    let kind = e.previous.0.last().filter(|w| !KEYWORDS.contains(w))?;
    // `let ball = sphere {`: the constant's name, for the group's.
    let (three, _) = words_before(f.text, f.pos, 3);
    let name = match three.as_slice() {
        ["let" | "fn", name, _] => *name,
        _ => "name",
    };
    Some(
        Diagnostic::error(codes::OBJECT_AS_VALUE, format!("a `{kind}` is not a value"), f.span)
            .with_label("an object's block")
            .with_help(format!("a constant holds a number, vector, colour or string; an object is named by a group and placed by instances: `group {name} {{ {kind} {{ … }} }}`, then `instance {name} {{ translate <1, 0, 0> }}` where it goes")),
    )
}

/// `sphere { … hollow }`: a POV-Ray flag right before.
fn povray_flag(f: &Failure, e: &Expected) -> Option<Diagnostic> {
    let (previous, adjacent) = &e.previous;
    let named = *previous.last().filter(|_| *adjacent)?;
    let hint = super::povray::flag(named)?;
    let end = f.before().trim_end().len();
    Some(
        Diagnostic::error(
            codes::UNEXPECTED_TOKEN,
            format!("`{named}` is a POV-Ray flag"),
            Span::new(f.file, end - named.len(), end),
        )
        .with_label("not ptsc")
        .with_help(hint),
    )
}

/// `material { … }`, `texture { … }` at the top level: a declaration
/// without its name.
fn nameless_declaration(f: &Failure, e: &Expected) -> Option<Diagnostic> {
    if f.found != "`{`" || !e.names.contains(&"a name") {
        return None;
    }
    let help = match e.previous.0.last().copied() {
        Some("material") => "a material declared here needs a name: `material NAME { diffuse rgb 0.8 }`, given to objects as `material NAME`; a material for one object goes inside it: `sphere { … material { … } }`".to_string(),
        Some("texture") => format!(
            "a texture declared here needs a name and a kind: `texture NAME checker {{ … }}`, given to a material's parameter as `diffuse NAME`; {}",
            super::povray::block("texture").unwrap_or_default()
        ),
        _ => return None,
    };
    Some(
        Diagnostic::error(codes::UNEXPECTED_TOKEN, e.message.clone(), f.span)
            .with_label(e.label.clone())
            .with_help(help),
    )
}

/// `let r = 1` and a statement on the next line: the `;` is missing at
/// the end of the line, not at the next statement (rustc's placement).
fn missing_semicolon(f: &Failure, e: &Expected) -> Option<Diagnostic> {
    let end = super::scan::code_end_before(f.text, f.pos);
    let found = &f.found;
    if e.names != ["`;`"] || !found.starts_with('`') || !f.text[end..f.pos].contains('\n') {
        return None;
    }
    let at = Span::new(f.file, end, end);
    Some(
        Diagnostic::error(codes::UNEXPECTED_TOKEN, e.message.clone(), at)
            .with_label("add `;` here")
            .with_secondary(f.span, format!("{found} starts a new statement"))
            .with_help(help_for(&e.names, found))
            .with_fix(at, ";"),
    )
}

/// `radius 1;` or `center <0, 0, 0>, radius 1` in a block: a separator
/// where entries just follow each other.
fn separator(f: &Failure, e: &Expected) -> Option<Diagnostic> {
    if !(f.found == "`;`" || f.found == "`,`") || !e.names.contains(&"`}`") {
        return None;
    }
    let sep = &f.found[1..2];
    Some(
        Diagnostic::error(codes::UNEXPECTED_TOKEN, e.message.clone(), f.span)
            .with_label(e.label.clone())
            .with_help(format!(
                "a block's entries follow each other without `{sep}` between them: remove it"
            ))
            .with_fix(f.span, ""),
    )
}

/// "expected …, found …", with the first help that applies: POV-Ray's
/// word, a name without its value, a POV-Ray word just before, a habit of
/// ranges, a constant without its value, or what was expected.
fn general(f: &Failure, e: &Expected) -> Diagnostic {
    let (found, before) = (&f.found, f.before());
    let (previous, adjacent) = &e.previous;
    let help = super::povray::hint(found.trim_matches('`'))
        .map(str::to_string)
        .or_else(|| {
            // `sphere { … glass }`: a name without a value (not a number:
            // `radius 1;` is told above).
            let named = previous.last().filter(|_| *adjacent)?;
            named.starts_with(|c: char| c.is_alphabetic() || c == '_').then_some(())?;
            e.names.iter().any(|n| n.starts_with("a value")).then(|| match *named {
                "background" => "`background` takes a colour without braces: `background rgb <0.5, 0.7, 1>` (a daylight sky is `sky { … }`)".to_string(),
                _ => format!("`{named}` needs a value (e.g. `{named} 1`); a material is given as `material {named}`"),
            })
        })
        .or_else(|| {
            // `camera { orthographic location <…> }`: a POV-Ray word just
            // before (not a directive's: `#end` says its own).
            let directive = |w: &&str| before.rfind(*w).is_some_and(|i| before[..i].ends_with('#'));
            (previous.iter().filter(|w| !directive(w)))
                .find_map(|w| super::povray::hint(w))
                .map(str::to_string)
        })
        .or_else(|| range_habit(before, found))
        .or_else(|| missing_constant_value(before, &e.names, found))
        .unwrap_or_else(|| help_for(&e.names, found));
    Diagnostic::error(codes::UNEXPECTED_TOKEN, e.message.clone(), f.span)
        .with_label(e.label.clone())
        .with_help(help)
}
