//! The numeric domain: every number the checker accepts is safe in the
//! renderer's 32-bit float arithmetic, including the products it forms
//! (squared distances, areas, a light's power, a pixel's sum of samples).
//!
//! One rule, by what a number stands for ([`Quantity`]): coordinates,
//! lengths, times and factors stay within ±[`MAX_MAGNITUDE`], light within
//! [`MAX_RADIANCE`], sizes at least [`MIN_SIZE`]. With those bounds the
//! largest products stay far below f32's 3.4e38: a squared distance across
//! the scene is about 1.2e19, an area light's power 2π·1e12·(2e9)² ≈ 2.5e31
//! (summed in f64), a sample of a point light 1e12 at 1e-9 is 1e30 and a
//! pixel's sum of a million of them 1e36. What remains (a pdf at a grazing
//! angle) the renderer guards where it divides.
//! Lowering applies the same bounds after transforms and motion.

use crate::diag::Diagnostic;
use crate::span::Span;

/// The largest magnitude of a coordinate, length, time, scale factor,
/// matrix entry, velocity or coefficient (reflectance, absorption).
pub const MAX_MAGNITUDE: f64 = 1e9;
/// The largest radiance, intensity or irradiance (a component of an
/// emission, light or background colour): the sun's luminance in cd/m² is
/// about 1.6e9.
pub const MAX_RADIANCE: f64 = 1e12;
/// The smallest radius or distance that must be positive, and the smallest
/// magnitude of a non-zero scale factor.
pub const MIN_SIZE: f64 = 1e-9;

/// What a number stands for, which fixes its range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// A number with its own range, checked by its block (angles, weights,
    /// counts, indices of refraction).
    Plain,
    /// A coordinate, length, time, velocity, matrix entry or coefficient:
    /// within ±[`MAX_MAGNITUDE`].
    Magnitude,
    /// A radius or distance that must be positive: [`MIN_SIZE`] to
    /// [`MAX_MAGNITUDE`] (its block reports zero and negative values).
    Size,
    /// A direction: any vector with a length (normalised in f64 before it
    /// becomes f32, so its magnitude does not matter).
    Direction,
    /// A scale factor: zero (reported by the transform) or a magnitude from
    /// [`MIN_SIZE`] to [`MAX_MAGNITUDE`].
    Scale,
    /// Radiance, intensity or irradiance: 0 to [`MAX_RADIANCE`].
    Radiance,
}

impl Quantity {
    /// Whether one number is in range; else what it must be.
    fn check(self, x: f64) -> Result<(), String> {
        let ok = match self {
            Quantity::Plain | Quantity::Direction => true,
            Quantity::Magnitude => x.abs() <= MAX_MAGNITUDE,
            Quantity::Size => x <= 0.0 || (MIN_SIZE..=MAX_MAGNITUDE).contains(&x),
            Quantity::Scale => x == 0.0 || (MIN_SIZE..=MAX_MAGNITUDE).contains(&x.abs()),
            Quantity::Radiance => x <= MAX_RADIANCE,
        };
        if ok {
            return Ok(());
        }
        Err(match self {
            Quantity::Magnitude => format!("within ±{}", number(MAX_MAGNITUDE)),
            Quantity::Size => format!("between {} and {}", number(MIN_SIZE), number(MAX_MAGNITUDE)),
            Quantity::Scale => format!(
                "between {} and {} in magnitude",
                number(MIN_SIZE),
                number(MAX_MAGNITUDE)
            ),
            _ => format!("at most {}", number(MAX_RADIANCE)),
        })
    }

    /// Checks every number of a value (one number, a vector's components, a
    /// colour's channels) and reports the first out of range.
    pub fn check_all(
        self,
        values: &[f64],
        name: &str,
        what: &str,
        span: Span,
    ) -> Result<(), Diagnostic> {
        if self == Quantity::Direction {
            if values.iter().all(|x| *x == 0.0) {
                return Err(out_of_range(
                    name,
                    what,
                    span,
                    "a non-zero vector",
                    "a direction needs a length; e.g. `<0, 1, 0>`".into(),
                ));
            }
            return Ok(());
        }
        for &x in values {
            if let Err(needs) = self.check(x) {
                let shown = if values.len() == 1 {
                    number(x)
                } else {
                    format!(
                        "<{}>",
                        values
                            .iter()
                            .map(|v| number(*v))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                };
                return Err(out_of_range(
                    name,
                    what,
                    span,
                    &needs,
                    format!(
                        "`{name}` is {shown} here; {}",
                        match self {
                            Quantity::Radiance =>
                                "brighter light would overflow the renderer's 32-bit floats",
                            Quantity::Size =>
                                "smaller or larger sizes do not survive the renderer's 32-bit floats",
                            _ =>
                                "the renderer computes in 32-bit floats; keep the scene within this range (scale it down)",
                        }
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// `x` as a person writes it: `0.5`, `250`, `1e9`, `-3e39`, `1e-9`.
pub fn number(x: f64) -> String {
    if x != 0.0 && !(1e-4..1e6).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// The error for a value out of range: `` `name` of `what` must be … ``
/// (without `what` when it is empty).
pub fn out_of_range(name: &str, what: &str, span: Span, needs: &str, help: String) -> Diagnostic {
    let message = if what.is_empty() {
        format!("`{name}` must be {needs}")
    } else {
        format!("`{name}` of `{what}` must be {needs}")
    };
    Diagnostic::error(crate::diag::codes::OUT_OF_RANGE, message, span)
        .with_label(format!("must be {needs}"))
        .with_help(help)
}

// Directions are the geometry's (placing a round shape needs them too).
pub use crate::geometry::{unit, unit_f32};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_quantity_has_its_range() {
        let ok = |q: Quantity, x: f64| q.check_all(&[x], "n", "b", Span::default()).is_ok();
        assert!(ok(Quantity::Magnitude, 1e9) && ok(Quantity::Magnitude, -1e9));
        assert!(!ok(Quantity::Magnitude, 1.0000001e9) && !ok(Quantity::Magnitude, -1e39));
        assert!(ok(Quantity::Size, 1e-9) && !ok(Quantity::Size, 1e-10));
        // Zero and negative sizes are their block's to report.
        assert!(ok(Quantity::Size, 0.0) && ok(Quantity::Size, -1.0));
        assert!(ok(Quantity::Scale, 0.0) && ok(Quantity::Scale, -2.0));
        assert!(!ok(Quantity::Scale, 1e-12) && !ok(Quantity::Scale, -1e10));
        assert!(ok(Quantity::Radiance, 1e12) && !ok(Quantity::Radiance, 3e38));
        assert!(ok(Quantity::Plain, 1e300));
        let dir = |v: &[f64]| Quantity::Direction.check_all(v, "n", "b", Span::default());
        assert!(dir(&[3.4e38, 1.0, 0.0]).is_ok());
        assert!(dir(&[1e200, 1e200, 0.0]).is_ok());
        assert!(dir(&[0.0, 0.0, 0.0]).is_err());
    }

    #[test]
    fn the_message_names_the_value_and_the_range() {
        let d = Quantity::Magnitude
            .check_all(&[0.0, 0.0, 1e39], "position", "camera", Span::default())
            .unwrap_err();
        assert_eq!(d.message, "`position` of `camera` must be within ±1e9");
        assert!(d.help.unwrap().contains("<0, 0, 1e39>"));
        assert_eq!(number(0.5), "0.5");
        assert_eq!(number(-250.0), "-250");
        assert_eq!(number(2e9), "2e9");
        assert_eq!(number(1e-9), "1e-9");
        assert_eq!(number(0.0), "0");
    }
}
