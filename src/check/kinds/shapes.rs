//! The shapes: each kind's parameters and the function that checks them
//! into a [`Shape`] before transforms (the transforms and the material are
//! every shape's, read by `check/block_statement.rs`).

use super::super::params::Val;
use super::super::reader::range_error;
use super::super::scene::Shape;
use super::super::schema::{p, ParamSpec, Ty};
use super::kind::{Kind, Role, ShapeInput};
use crate::check::domain::Quantity::{Direction, Magnitude, Size};
use crate::diag::{codes, Diagnostic};
use crate::geometry::round::{capsule::CapsuleDesc, cone::ConeDesc, torus::TorusDesc, RoundDesc};
use crate::source::ReadError;
use glam::DVec3;

/// The rows of this file, in the order the docs list them.
pub const ALL: &[&Kind] = &[
    &SPHERE, &PLANE, &QUAD, &DISK, &TRIANGLE, &BOX, &CYLINDER, &CONE, &TORUS, &CAPSULE, &MESH,
];

/// `sphere { }`
pub const SPHERE: Kind = Kind {
    name: "sphere",
    summary: "a sphere: its centre and radius",
    params: &[
        p("center", Ty::Vec3, "<0, 1, 0>")
            .of(Magnitude)
            .doc("the centre. Required"),
        p("radius", Ty::Num, "1")
            .of(Size)
            .doc("the radius (> 0). Required"),
    ],
    role: Role::Shape(sphere),
    positional: Some((&["center", "radius"], "")),
    povray: &[],
};

fn sphere(s: &mut ShapeInput) -> Option<Shape> {
    let center = s.vec3("center");
    let radius = s.positive("radius");
    Some(Shape::Sphere {
        center: center?.0,
        radius: radius?,
    })
}

/// `plane { }`
pub const PLANE: Kind = Kind {
    name: "plane",
    summary: "an infinite plane through a point (it cannot emit light)",
    params: &[
        p("point", Ty::Vec3, "<0, 0, 0>")
            .of(Magnitude)
            .doc("a point on the plane. Default the origin"),
        p("normal", Ty::Vec3, "<0, 1, 0>")
            .of(Direction)
            .doc("the plane's normal, its front side. Required"),
    ],
    role: Role::Shape(plane),
    positional: Some((&["normal", "point"], "a plane is given by a point on it")),
    povray: &[],
};

fn plane(s: &mut ShapeInput) -> Option<Shape> {
    let point = s.vec3_or("point", DVec3::ZERO);
    let normal = s.direction("normal")?;
    Some(Shape::Plane { point, normal })
}

/// `quad { }`
pub const QUAD: Kind = Kind {
    name: "quad",
    summary: "a parallelogram: the points `corner + s·edge1 + t·edge2`, s and t in [0, 1]; normal `edge1 × edge2`",
    params: &[
        p("corner", Ty::Vec3, "<-1, 0, -1>").of(Magnitude).doc("one corner. Required"),
        p("edge1", Ty::Vec3, "<0, 0, 2>").of(Magnitude).doc("the first edge from `corner` (u runs along it). Required"),
        p("edge2", Ty::Vec3, "<2, 0, 0>").of(Magnitude).doc("the second edge from `corner` (v runs along it). Required"),
    ],
    role: Role::Shape(quad),
    positional: None,
    povray: &[
        ("polygon", "use `quad { corner … edge1 … edge2 … }` or `triangle { v0 … v1 … v2 … }`"),
        ("rectangle", "Mitsuba's `rectangle` (from -1 to 1 in x and y, placed by `to_world`) is `quad { corner <-1, -1, 0> edge1 <2, 0, 0> edge2 <0, 2, 0> }` in ptsc, placed by `translate`, `rotate` and `scale`"),
    ],
};

fn quad(s: &mut ShapeInput) -> Option<Shape> {
    let corner = s.vec3("corner");
    let e1 = s.vec3("edge1");
    let e2 = s.vec3("edge2");
    let ((edge1, s1), (edge2, s2)) = (e1?, e2?);
    if edge1.cross(edge2).length_squared() == 0.0 {
        return s.degenerate(
            "the quad has no area",
            s1.join(s2),
            "`edge1` and `edge2` are parallel or zero",
            "the two edges must span a parallelogram, e.g. `edge1 <1, 0, 0>` and `edge2 <0, 0, 1>`",
        );
    }
    Some(Shape::Quad {
        corner: corner?.0,
        edge1,
        edge2,
    })
}

/// `disk { }`
pub const DISK: Kind = Kind {
    name: "disk",
    summary: "a flat disk: its centre, normal and radius",
    params: &[
        p("center", Ty::Vec3, "<0, 0, 0>")
            .of(Magnitude)
            .doc("the centre. Required"),
        p("normal", Ty::Vec3, "<0, 1, 0>")
            .of(Direction)
            .doc("the normal, its front side. Required"),
        p("radius", Ty::Num, "1")
            .of(Size)
            .doc("the radius (> 0). Required"),
    ],
    role: Role::Shape(disk),
    positional: Some((&["center", "normal", "radius"], "")),
    povray: &[],
};

fn disk(s: &mut ShapeInput) -> Option<Shape> {
    let center = s.vec3("center");
    let normal = s.direction("normal");
    let radius = s.positive("radius");
    Some(Shape::Disk {
        center: center?.0,
        normal: normal?,
        radius: radius?,
    })
}

/// `triangle { }`
pub const TRIANGLE: Kind = Kind {
    name: "triangle",
    summary: "a triangle, counter-clockwise seen from the front: normal `(v1 − v0) × (v2 − v0)`",
    params: &[
        p("v0", Ty::Vec3, "<0, 0, 0>")
            .of(Magnitude)
            .doc("the first vertex. Required"),
        p("v1", Ty::Vec3, "<1, 0, 0>")
            .of(Magnitude)
            .doc("the second vertex. Required"),
        p("v2", Ty::Vec3, "<0, 1, 0>")
            .of(Magnitude)
            .doc("the third vertex. Required"),
    ],
    role: Role::Shape(triangle),
    positional: Some((&["v0", "v1", "v2"], "")),
    povray: &[],
};

fn triangle(s: &mut ShapeInput) -> Option<Shape> {
    let a = s.vec3("v0");
    let b = s.vec3("v1");
    let c = s.vec3("v2");
    let ((a, sa), (b, _), (c, sc)) = (a?, b?, c?);
    if (b - a).cross(c - a).length_squared() == 0.0 {
        return s.degenerate(
            "the triangle has no area",
            sa.join(sc),
            "these vertices are on one line",
            "move one vertex off the line through the other two",
        );
    }
    Some(Shape::Triangle { v: [a, b, c] })
}

/// `box { }`
pub const BOX: Kind = Kind {
    name: "box",
    summary: "an axis-aligned box between two corners (six quads)",
    params: &[
        p("min", Ty::Vec3, "<-1, -1, -1>")
            .of(Magnitude)
            .doc("the smaller corner. Required"),
        p("max", Ty::Vec3, "<1, 1, 1>")
            .of(Magnitude)
            .doc("the larger corner: every component above `min`'s. Required"),
    ],
    role: Role::Shape(cuboid),
    positional: Some((&["min", "max"], "`min` is the smaller corner")),
    povray: &[("cube", "ptsc's is `box { min <…> max <…> }`")],
};

fn cuboid(s: &mut ShapeInput) -> Option<Shape> {
    let lo = s.vec3("min");
    let hi = s.vec3("max");
    let ((min, s0), (max, s1)) = (lo?, hi?);
    if min.cmpge(max).any() {
        return s.degenerate(
            "the box's `min` is not below its `max`",
            s0.join(s1),
            "every component of `min` must be smaller than `max`",
            "swap the components that are in the wrong order",
        );
    }
    Some(Shape::Box { min, max })
}

/// `cylinder { }`
pub const CYLINDER: Kind = Kind {
    name: "cylinder",
    summary:
        "a cylinder from the centre of its base to the centre of its top, closed unless `open`",
    params: &[
        p("base", Ty::Vec3, "<0, 0, 0>")
            .of(Magnitude)
            .doc("the centre of the base. Required"),
        p("top", Ty::Vec3, "<0, 2, 0>")
            .of(Magnitude)
            .doc("the centre of the top. Required"),
        p("radius", Ty::Num, "0.5")
            .of(Size)
            .doc("the radius (> 0). Required"),
        p("open", Ty::Bool, "true").doc("without the end disks. Default `false`"),
    ],
    role: Role::Shape(cylinder),
    positional: Some((&["base", "top", "radius"], "")),
    povray: &[],
};

fn cylinder(s: &mut ShapeInput) -> Option<Shape> {
    axial(s, |s| s.positive("radius").map(|r| (r, r)))
}

/// `cone { }`
pub const CONE: Kind = Kind {
    name: "cone",
    summary: "a cone or truncated cone from the centre of its base to the centre of its top, closed unless `open`",
    params: &[
        p("base", Ty::Vec3, "<0, 0, 0>").of(Magnitude).doc("the centre of the base. Required"),
        p("top", Ty::Vec3, "<0, 2, 0>").of(Magnitude).doc("the centre of the top. Required"),
        p("base_radius", Ty::Num, "1").of(Size).doc("the radius at the base (≥ 0). Required"),
        p("top_radius", Ty::Num, "0").of(Size).doc("the radius at the top (≥ 0; 0 is a point, not both 0). Required"),
        p("open", Ty::Bool, "true").doc("without the end disks. Default `false`"),
    ],
    role: Role::Shape(cone),
    positional: Some((&["base", "base_radius", "top", "top_radius"], "")),
    povray: &[],
};

fn cone(s: &mut ShapeInput) -> Option<Shape> {
    axial(s, cone_radii)
}

/// A cone's two radii, both 0 or more and not both 0.
fn cone_radii(s: &mut ShapeInput) -> Option<(f64, f64)> {
    let b = s.num("base_radius");
    let t = s.num("top_radius");
    let ((b, bs), (t, ts)) = (b?, t?);
    for (x, at, name) in [(b, bs, "base_radius"), (t, ts, "top_radius")] {
        if x < 0.0 {
            s.diags().push(range_error(
                "cone",
                name,
                at,
                "0 or more",
                format!("`{name}` is {x} here"),
            ));
            return None;
        }
    }
    if b == 0.0 && t == 0.0 {
        s.degenerate(
            "the cone has no width",
            bs.join(ts),
            "both radii are 0",
            "give the base or the top a radius above 0",
        );
        return None;
    }
    Some((b, t))
}

/// A cylinder or cone along its `base` and `top`, of the radii (base,
/// top) that `radii` reads after them.
fn axial(
    s: &mut ShapeInput,
    radii: impl FnOnce(&mut ShapeInput) -> Option<(f64, f64)>,
) -> Option<Shape> {
    let base = s.vec3("base");
    let top = s.vec3("top");
    let radii = radii(s);
    let ((base, bs), (top, ts)) = (base?, top?);
    let (base_radius, top_radius) = radii?;
    if base == top {
        let what = s.kind.name;
        return s.degenerate(
            format!("the {what} has no height"),
            bs.join(ts),
            "`base` and `top` are the same point",
            "move `top` away from `base` along the axis, e.g. `top <0, 1, 0>`",
        );
    }
    Some(Shape::Round(RoundDesc::Cone(ConeDesc {
        base,
        top,
        base_radius,
        top_radius,
        open: s.boolean("open", false),
    })))
}

/// `torus { }`
pub const TORUS: Kind = Kind {
    name: "torus",
    summary:
        "a torus: a circle of radius `minor_radius` swept around a circle of radius `major_radius`",
    params: &[
        p("center", Ty::Vec3, "<0, 0, 0>")
            .of(Magnitude)
            .doc("the centre. Default the origin"),
        p("axis", Ty::Vec3, "<0, 1, 0>")
            .of(Direction)
            .doc("the axis of symmetry. Default `<0, 1, 0>`"),
        p("major_radius", Ty::Num, "1")
            .of(Size)
            .doc("from the centre to the tube's centre line (> 0). Required"),
        p("minor_radius", Ty::Num, "0.25")
            .of(Size)
            .doc("the tube's radius, below `major_radius`. Required"),
    ],
    role: Role::Shape(torus),
    positional: Some((&["major_radius", "minor_radius"], "")),
    povray: &[],
};

fn torus(s: &mut ShapeInput) -> Option<Shape> {
    let center = s.vec3_or("center", DVec3::ZERO);
    let axis = match s.params().get("axis") {
        Some(_) => s.direction("axis")?,
        None => DVec3::Y,
    };
    let major = s.positive("major_radius");
    let minor = s.positive("minor_radius");
    let (major, minor) = (major?, minor?);
    if minor >= major {
        let at = (s.params().get("minor_radius").map(|v| v.1)).unwrap_or(s.params().head);
        s.diags().push(range_error(
            "torus",
            "minor_radius",
            at,
            "below `major_radius`",
            format!("the tube's radius {minor} is not below the ring's {major}: the torus would cross itself at its centre"),
        ));
        return None;
    }
    Some(Shape::Round(RoundDesc::Torus(TorusDesc {
        center,
        axis,
        major,
        minor,
    })))
}

/// `capsule { }`
pub const CAPSULE: Kind = Kind {
    name: "capsule",
    summary: "a capsule: the points within `radius` of the segment from `base` to `top`, a cylinder closed by two hemispheres",
    params: &[
        p("base", Ty::Vec3, "<0, 0, 0>").of(Magnitude).doc("one end of the axis: the centre of the base's hemisphere. Required"),
        p("top", Ty::Vec3, "<0, 2, 0>").of(Magnitude).doc("the other end: the centre of the top's hemisphere (equal to `base`: a sphere). Required"),
        p("radius", Ty::Num, "0.5").of(Size).doc("the distance of the surface from the axis (> 0). Required"),
    ],
    role: Role::Shape(capsule),
    positional: None,
    povray: &[("sphere_sweep", "a `sphere_sweep` of two points with one radius is ptsc's `capsule { base <…> top <…> radius … }`; a longer sweep is a row of capsules")],
};

fn capsule(s: &mut ShapeInput) -> Option<Shape> {
    let base = s.vec3("base");
    let top = s.vec3("top");
    let radius = s.positive("radius");
    Some(Shape::Round(RoundDesc::Capsule(CapsuleDesc {
        base: base?.0,
        top: top?.0,
        radius: radius?,
    })))
}

/// `mesh { }`
pub const MESH: Kind = Kind {
    name: "mesh",
    summary: "a triangle mesh read from a Wavefront OBJ, PLY or glTF 2.0 file",
    params: &[
        p("file", Ty::Str, "\"bunny.ply\"").doc("the `.obj`, `.ply`, `.gltf` or `.glb` file, relative to the scene file; vertex normals and texture coordinates are read when present, an OBJ's or glTF's materials when the mesh names none, a glTF's whole scene (its nodes' transforms on top of the mesh's). Required"),
        p("smooth", Ty::Bool, "true").doc("interpolate the file's vertex normals. Default `false` (flat shading) for OBJ and PLY, `true` for glTF (its normals are part of the model)"),
        p("materials", Ty::Materials, "{ \"Leaf\" green }").doc("replaces the file's materials by name (an OBJ's `newmtl`, a glTF material's `name`): each name in quotes, then a material's name or `material { … }`; the others stay the file's. A name the file does not have is a warning. Without effect when the mesh has a `material`, which replaces them all"),
        p("node", Ty::Str, "\"Chair\"").doc("a glTF file's node, by name: only it and its children are placed, at the mesh's transforms (the node's own place in the file is left out). Default: the file's whole scene"),
    ],
    role: Role::Shape(mesh),
    positional: None,
    povray: &[("mesh2", "ptsc reads meshes from files: `mesh { file \"model.obj\" }` (OBJ, PLY or glTF)")],
};

fn mesh(s: &mut ShapeInput) -> Option<Shape> {
    let schema: &[ParamSpec] = s.kind.params;
    s.r.p.require("file", schema, s.r.diags)?;
    let Some((Val::Str(f), at)) = s.params().get("file") else {
        return None;
    };
    let (f, at) = (f.clone(), *at);
    let path = s.base_dir.join(&f);
    let ext = (path.extension().and_then(|e| e.to_str())).map(|e| e.to_ascii_lowercase());
    // Only the path's kind (a `stat`, which never waits): lowering reads
    // the file, bounded, and reports what else is wrong. A folder is said
    // to be one, whatever its name.
    let kind = s.files.exists(&path);
    let known = matches!(ext.as_deref(), Some("obj" | "ply" | "gltf" | "glb"));
    if !known && !matches!(kind, Err(ReadError::NotRegular(_))) {
        s.diags().push(
            Diagnostic::error(codes::MESH_FILE, format!("unknown mesh format `{f}`"), at)
                .with_label("not an .obj, .ply, .gltf or .glb file")
                .with_help("meshes are read from Wavefront OBJ (.obj), PLY (.ply) and glTF 2.0 (.gltf, .glb) files"),
        );
        return None;
    }
    let missing = match kind {
        Ok(()) => None,
        Err(ReadError::NotRegular(kind)) => Some(
            Diagnostic::error(
                codes::MESH_FILE,
                format!("mesh file `{f}` is not a regular file"),
                at,
            )
            .with_label(format!("{} is {kind}", path.display()))
            .with_help("a mesh is read from an OBJ, PLY or glTF file"),
        ),
        Err(ReadError::Unsaved) => Some(
            Diagnostic::error(codes::MESH_FILE, format!("mesh file `{f}` not found"), at)
                .with_label(ReadError::Unsaved.to_string())
                .with_help("save the document, or open the folder it belongs to as the workspace"),
        ),
        Err(_) => Some(
            Diagnostic::error(codes::MESH_FILE, format!("mesh file `{f}` not found"), at)
                .with_label(format!("looked for {}", path.display()))
                .with_help("mesh paths are relative to the scene file that names them"),
        ),
    };
    if let Some(d) = missing {
        s.diags().push(d);
        return None;
    }
    let gltf = matches!(ext.as_deref(), Some("gltf" | "glb"));
    let node = match s.params().get("node") {
        Some((Val::Str(name), span)) => Some((name.clone(), *span)),
        _ => None,
    };
    if let (Some((_, span)), false) = (&node, gltf) {
        s.diags().push(
            Diagnostic::error(
                codes::MESH_FILE,
                "`node` picks a node of a glTF file",
                *span,
            )
            .with_label(format!("`{f}` is not a .gltf or .glb file"))
            .with_help("remove `node`, or place a glTF file"),
        );
        return None;
    }
    Some(Shape::Mesh {
        path,
        named: f,
        path_span: at,
        smooth: s.boolean("smooth", gltf),
        node,
        group: None,
        swaps: Vec::new(),
    })
}
