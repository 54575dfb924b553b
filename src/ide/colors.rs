//! Colour swatches: every `rgb` literal written with numbers (`rgb 0.5`,
//! `rgb <0.8, 0.2, 0.1>`), and what the editor's colour picker writes back.
//! The scene's colours are linear RGB and editors show sRGB: a swatch is
//! the colour put through the sRGB curve (values above 1, an emission's,
//! show as 1), and a picked colour is taken back through its inverse.

use super::tokens::{tokens, Token, TokenKind};
use std::ops::Range;

/// An `rgb` literal and its linear colour.
#[derive(Debug, Clone, PartialEq)]
pub struct ColorLiteral {
    /// From `rgb` to the end of its value.
    pub range: Range<usize>,
    /// The colour, linear, as written.
    pub linear: [f64; 3],
}

/// Every `rgb` literal of `text` whose value is written with numbers.
pub fn colors(text: &str) -> Vec<ColorLiteral> {
    let toks: Vec<Token> = tokens(text)
        .into_iter()
        .filter(|t| t.kind != TokenKind::Comment)
        .collect();
    let s = |t: &Token| &text[t.range.clone()];
    let mut out = Vec::new();
    for (i, t) in toks.iter().enumerate() {
        if t.kind != TokenKind::Word || s(t) != "rgb" {
            continue;
        }
        let rest = &toks[i + 1..];
        let num = |t: Option<&Token>| {
            t.filter(|t| t.kind == TokenKind::Number)
                .and_then(|t| s(t).parse::<f64>().ok())
        };
        // `rgb 0.5` (not `rgb 0.5 * x`).
        if let Some(v) = num(rest.first()) {
            let next = rest.get(1).map(s).unwrap_or("");
            if !matches!(next, "*" | "/" | "+" | "-" | "^" | "(" | "[" | ".") {
                out.push(ColorLiteral {
                    range: t.range.start..rest[0].range.end,
                    linear: [v; 3],
                });
            }
            continue;
        }
        // `rgb <a, b, c>`.
        if rest.len() >= 7
            && s(&rest[0]) == "<"
            && s(&rest[2]) == ","
            && s(&rest[4]) == ","
            && s(&rest[6]) == ">"
        {
            if let (Some(r), Some(g), Some(b)) =
                (num(rest.get(1)), num(rest.get(3)), num(rest.get(5)))
            {
                out.push(ColorLiteral {
                    range: t.range.start..rest[6].range.end,
                    linear: [r, g, b],
                });
            }
        }
    }
    out
}

/// A linear value as the sRGB curve encodes it, in [0, 1] (IEC 61966-2-1).
pub fn to_srgb(linear: f64) -> f64 {
    let x = linear.clamp(0.0, 1.0);
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// An sRGB-encoded value back to linear.
pub fn from_srgb(encoded: f64) -> f64 {
    let x = encoded.clamp(0.0, 1.0);
    if x <= 0.040_45 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

/// The `rgb` literal for a colour picked in sRGB.
pub fn presentation(srgb: [f64; 3]) -> String {
    let c = srgb.map(|v| {
        let s = format!("{:.3}", from_srgb(v));
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s.is_empty() {
            "0".to_string()
        } else {
            s.to_string()
        }
    });
    if c[0] == c[1] && c[1] == c[2] {
        format!("rgb {}", c[0])
    } else {
        format!("rgb <{}, {}, {}>", c[0], c[1], c[2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals_with_numbers_are_swatches() {
        let text = "diffuse rgb <0.8, 0.2, 0.1> // rgb 1\nemission rgb 4\ndiffuse rgb 0.5 * k\nx rgb <a, 0, 0>";
        let found = colors(text);
        assert_eq!(found.len(), 2);
        assert_eq!(&text[found[0].range.clone()], "rgb <0.8, 0.2, 0.1>");
        assert_eq!(found[1].linear, [4.0; 3]);
    }

    #[test]
    fn picked_colours_round_trip_through_the_srgb_curve() {
        for v in [0.0, 0.002, 0.2, 0.5, 1.0] {
            assert!((from_srgb(to_srgb(v)) - v).abs() < 1e-9);
        }
        assert_eq!(presentation([1.0, 1.0, 1.0]), "rgb 1");
        assert_eq!(presentation([0.0, 0.5, 1.0]), "rgb <0, 0.214, 1>");
    }
}
