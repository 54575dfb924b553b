//! What every object block has besides its shape (each kind's is in
//! `kinds/shapes.rs`): the object-to-world transform and the linear motion.

use super::params::{Params, Val};
use crate::diag::codes;
use crate::diag::{Diagnostic, Diagnostics};
use crate::geometry::round::similarity_scale;
use crate::span::Span;
use glam::{DMat4, DVec3};

/// The object-to-world transform from `translate`, `rotate`, `scale` and `matrix` in order.
pub fn transform(p: &Params, diags: &mut Diagnostics) -> DMat4 {
    let mut m = DMat4::IDENTITY;
    for (name, val, span) in &p.ordered {
        let Val::Vector(v) = val else { continue };
        let step = match *name {
            "translate" => DMat4::from_translation(DVec3::new(v[0], v[1], v[2])),
            // POV-Ray order: about x, then y, then z, in degrees.
            "rotate" => {
                DMat4::from_rotation_z(v[2].to_radians())
                    * DMat4::from_rotation_y(v[1].to_radians())
                    * DMat4::from_rotation_x(v[0].to_radians())
            }
            "scale" => {
                if v.contains(&0.0) {
                    diags.push(
                        Diagnostic::error(codes::SINGULAR_TRANSFORM, "scale by zero", *span)
                            .with_label("flattens the object to nothing")
                            .with_help("every scale factor must be non-zero"),
                    );
                    continue;
                }
                DMat4::from_scale(DVec3::new(v[0], v[1], v[2]))
            }
            "matrix" => {
                if v.len() == 16 && (v[12] != 0.0 || v[13] != 0.0 || v[14] != 0.0 || v[15] != 1.0) {
                    diags.push(
                        Diagnostic::error(
                            codes::SINGULAR_TRANSFORM,
                            "projective matrices are not supported",
                            *span,
                        )
                        .with_label("the last row must be 0, 0, 0, 1")
                        .with_help("give the 12 numbers of the 3 × 4 affine part, row by row"),
                    );
                    continue;
                }
                let mm = DMat4::from_cols_array(&[
                    v[0], v[4], v[8], 0.0, v[1], v[5], v[9], 0.0, v[2], v[6], v[10], 0.0, v[3],
                    v[7], v[11], 1.0,
                ]);
                if mm.determinant().abs() < 1e-12 {
                    diags.push(
                        Diagnostic::error(
                            codes::SINGULAR_TRANSFORM,
                            "the matrix cannot be inverted",
                            *span,
                        )
                        .with_label("determinant is zero")
                        .with_help("a transform must keep the object three-dimensional"),
                    );
                    continue;
                }
                mm
            }
            _ => continue,
        };
        m = step * m;
    }
    m
}

/// The velocity of an object (linear motion per unit shutter time).
pub fn velocity(p: &Params) -> DVec3 {
    match p.get("velocity") {
        Some((Val::Vector(v), _)) => DVec3::new(v[0], v[1], v[2]),
        _ => DVec3::ZERO,
    }
}

/// The error of a round shape (`what`) at `span` under an uneven scale or
/// a shear; lowering gives it too, for a group's placement.
pub fn non_uniform(span: Span, what: &str) -> Diagnostic {
    Diagnostic::error(
        codes::NON_UNIFORM_SCALE,
        format!("a {what} takes only uniform scaling"),
        span,
    )
    .with_label("this object is scaled unevenly or sheared")
    .with_help(format!(
        "scale the {what} by a single number, or use a mesh for ellipsoids"
    ))
}

/// The error when `transform`, an object's own, scales the round shape
/// `what` unevenly or shears it: at the first `scale` of unequal factors
/// or `matrix` of the block, else at the object (`span`).
pub fn uneven_round(p: &Params, transform: &DMat4, what: &str, span: Span) -> Option<Diagnostic> {
    if similarity_scale(transform).is_some() {
        return None;
    }
    let culprit = p.ordered.iter().find(|(name, val, _)| match (*name, val) {
        ("scale", Val::Vector(v)) => v.iter().any(|x| x.abs() != v[0].abs()),
        ("matrix", _) => true,
        _ => false,
    });
    Some(match culprit {
        Some((name, _, at)) => non_uniform(*at, what).with_label(match *name {
            "scale" => format!("scales the {what} unevenly"),
            _ => format!("this matrix shears or scales the {what} unevenly"),
        }),
        None => non_uniform(span, what),
    })
}
