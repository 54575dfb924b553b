//! Object blocks, checked: the shape of each kind (before transforms), the
//! object-to-world transform and the linear motion.

use super::params::{Params, Val};
use super::reader::{range_error, Reader};
use super::scene::*;
use super::schema::SHAPE_COMMON;
use crate::diag::codes;
use crate::diag::{Diagnostic, Diagnostics};
use crate::geometry::round::{cone::ConeDesc, torus::TorusDesc};
use crate::source::{Files, ReadError};
use crate::syntax::ast::BlockKind;
use glam::{DMat4, DVec3};
use std::path::Path;

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

/// A shape block → its shape (before transforms).
pub fn shape(
    kind: BlockKind,
    p: &Params,
    (base_dir, files): (&Path, &dyn Files),
    diags: &mut Diagnostics,
) -> Option<Shape> {
    let schema = super::schema::shape_schema(kind);
    let mut r = Reader { p, diags };
    let what = kind.keyword();
    let positive = |r: &mut Reader, name: &'static str| -> Option<f64> {
        let (x, s) = r.num_req(name, schema)?;
        if x > 0.0 {
            Some(x)
        } else {
            r.diags.push(range_error(
                what,
                name,
                s,
                "greater than 0",
                format!("`{name}` is {x} here; give a positive size"),
            ));
            None
        }
    };
    let shape = match kind {
        BlockKind::Sphere => {
            let c = r.vec3_req("center", schema);
            let rad = positive(&mut r, "radius");
            Shape::Sphere {
                center: c?.0,
                radius: rad?,
            }
        }
        BlockKind::Plane => {
            let point = r.vec3("point").map(|v| v.0).unwrap_or(DVec3::ZERO);
            let n = r.direction("normal", schema)?;
            Shape::Plane { point, normal: n }
        }
        BlockKind::Quad => {
            let c = r.vec3_req("corner", schema);
            let e1 = r.vec3_req("edge1", schema);
            let e2 = r.vec3_req("edge2", schema);
            let (e1, s1) = e1?;
            let (e2, s2) = e2?;
            if e1.cross(e2).length_squared() == 0.0 {
                r.diags.push(
                    Diagnostic::error(codes::DEGENERATE, "the quad has no area", s1.join(s2))
                        .with_label("`edge1` and `edge2` are parallel or zero")
                        .with_help("the two edges must span a parallelogram, e.g. `edge1 <1, 0, 0>` and `edge2 <0, 0, 1>`"),
                );
                return None;
            }
            Shape::Quad {
                corner: c?.0,
                edge1: e1,
                edge2: e2,
            }
        }
        BlockKind::Disk => {
            let c = r.vec3_req("center", schema);
            let n = r.direction("normal", schema);
            let rad = positive(&mut r, "radius");
            Shape::Disk {
                center: c?.0,
                normal: n?,
                radius: rad?,
            }
        }
        BlockKind::Triangle => {
            let a = r.vec3_req("v0", schema);
            let b = r.vec3_req("v1", schema);
            let c = r.vec3_req("v2", schema);
            let (a, sa) = a?;
            let (b, _) = b?;
            let (c, sc) = c?;
            if (b - a).cross(c - a).length_squared() == 0.0 {
                r.diags.push(
                    Diagnostic::error(codes::DEGENERATE, "the triangle has no area", sa.join(sc))
                        .with_label("these vertices are on one line")
                        .with_help("move one vertex off the line through the other two"),
                );
                return None;
            }
            Shape::Triangle { v: [a, b, c] }
        }
        BlockKind::Box => {
            let lo = r.vec3_req("min", schema);
            let hi = r.vec3_req("max", schema);
            let (lo, s0) = lo?;
            let (hi, s1) = hi?;
            if lo.cmpge(hi).any() {
                r.diags.push(
                    Diagnostic::error(
                        codes::DEGENERATE,
                        "the box's `min` is not below its `max`",
                        s0.join(s1),
                    )
                    .with_label("every component of `min` must be smaller than `max`")
                    .with_help("swap the components that are in the wrong order"),
                );
                return None;
            }
            Shape::Box { min: lo, max: hi }
        }
        BlockKind::Mesh => {
            p.require("file", schema, r.diags)?;
            let Some((Val::Str(f), s)) = p.get("file") else {
                return None;
            };
            let path = base_dir.join(f);
            let ext = path
                .extension()
                .and_then(|e| e.to_str())
                .map(|e| e.to_ascii_lowercase());
            if !matches!(ext.as_deref(), Some("obj") | Some("ply")) {
                r.diags.push(
                    Diagnostic::error(codes::MESH_FILE, format!("unknown mesh format `{f}`"), *s)
                        .with_label("not an .obj or .ply file")
                        .with_help("meshes are read from Wavefront OBJ (.obj) or PLY (.ply) files"),
                );
                return None;
            }
            // Only the path's kind (a `stat`, which never waits): lowering
            // reads the file, bounded, and reports what else is wrong.
            match files.exists(&path) {
                Ok(()) => {}
                Err(ReadError::NotRegular(kind)) => {
                    r.diags.push(
                        Diagnostic::error(
                            codes::MESH_FILE,
                            format!("mesh file `{f}` is not a regular file"),
                            *s,
                        )
                        .with_label(format!("{} is {kind}", path.display()))
                        .with_help("a mesh is read from an OBJ or PLY file"),
                    );
                    return None;
                }
                Err(_) => {
                    r.diags.push(
                        Diagnostic::error(
                            codes::MESH_FILE,
                            format!("mesh file `{f}` not found"),
                            *s,
                        )
                        .with_label(format!("looked for {}", path.display()))
                        .with_help("mesh paths are relative to the scene file that names them"),
                    );
                    return None;
                }
            }
            Shape::Mesh {
                path,
                path_span: *s,
                smooth: r.boolean("smooth", false),
            }
        }
        BlockKind::Cylinder | BlockKind::Cone => {
            let base = r.vec3_req("base", schema);
            let top = r.vec3_req("top", schema);
            let radii = if kind == BlockKind::Cylinder {
                positive(&mut r, "radius").map(|x| (x, x))
            } else {
                let b = r.num_req("base_radius", schema);
                let t = r.num_req("top_radius", schema);
                let ((b, bs), (t, ts)) = (b?, t?);
                for (x, s, name) in [(b, bs, "base_radius"), (t, ts, "top_radius")] {
                    if x < 0.0 {
                        r.diags.push(range_error(
                            what,
                            name,
                            s,
                            "0 or more",
                            format!("`{name}` is {x} here"),
                        ));
                        return None;
                    }
                }
                if b == 0.0 && t == 0.0 {
                    r.diags.push(
                        Diagnostic::error(codes::DEGENERATE, "the cone has no width", bs.join(ts))
                            .with_label("both radii are 0")
                            .with_help("give the base or the top a radius above 0"),
                    );
                    return None;
                }
                Some((b, t))
            };
            let ((base, bs), (top, ts)) = (base?, top?);
            let (base_radius, top_radius) = radii?;
            if base == top {
                r.diags.push(
                    Diagnostic::error(
                        codes::DEGENERATE,
                        format!("the {what} has no height"),
                        bs.join(ts),
                    )
                    .with_label("`base` and `top` are the same point")
                    .with_help("move `top` away from `base` along the axis, e.g. `top <0, 1, 0>`"),
                );
                return None;
            }
            Shape::Round(RoundDesc::Cone(ConeDesc {
                base,
                top,
                base_radius,
                top_radius,
                open: r.boolean("open", false),
            }))
        }
        BlockKind::Torus => {
            let center = r.vec3("center").map(|v| v.0).unwrap_or(DVec3::ZERO);
            let axis = match p.get("axis") {
                Some(_) => r.direction("axis", schema)?,
                None => DVec3::Y,
            };
            let major = positive(&mut r, "major_radius");
            let minor = positive(&mut r, "minor_radius");
            let (major, minor) = (major?, minor?);
            if minor >= major {
                let at = p.get("minor_radius").map(|v| v.1).unwrap_or(p.head);
                r.diags.push(range_error(
                    what,
                    "minor_radius",
                    at,
                    "below `major_radius`",
                    format!("the tube's radius {minor} is not below the ring's {major}: the torus would cross itself at its centre"),
                ));
                return None;
            }
            Shape::Round(RoundDesc::Torus(TorusDesc {
                center,
                axis,
                major,
                minor,
            }))
        }
        _ => unreachable!("not a shape: {kind:?}"),
    };
    Some(shape)
}

/// The velocity of an object (linear motion per unit shutter time).
pub fn velocity(p: &Params) -> DVec3 {
    match p.get("velocity") {
        Some((Val::Vector(v), _)) => DVec3::new(v[0], v[1], v[2]),
        _ => DVec3::ZERO,
    }
}

/// The schemas a shape block is checked against.
pub fn shape_schemas(kind: BlockKind) -> [&'static [super::schema::ParamSpec]; 2] {
    let common: &[_] = if kind.is_shape() { SHAPE_COMMON } else { &[] };
    [super::schema::shape_schema(kind), common]
}
