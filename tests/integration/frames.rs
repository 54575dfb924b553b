//! The surface frame at a hit — point, geometric normal, texture
//! coordinates and the tangents ∂p/∂u, ∂p/∂v that normal and bump maps
//! are laid along — is the primitive's own, computed here from its
//! definition in f64, whatever the renderer made of it: a quad or triangle
//! kept as a record or packed into a 4-wide block of the BVH (alone, beside
//! one other primitive, in a crowd), placed through a group, under any
//! affine transform (mirrored, sheared, scaled unevenly).

use glam::{DMat3, DVec2, DVec3, Vec3};
use proptest::prelude::*;
use ptsc::compile::{compile_str, Options};
use ptsc::geometry::Ray;
use ptsc::ir::Scene;
use std::fmt::Write as _;
use std::path::Path;

/// What is defined: a quad, a triangle, or a one-triangle mesh with or
/// without texture coordinates and vertex normals.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Quad,
    Triangle,
    /// A mesh triangle without attributes (a plain triangle of a block).
    PlainMesh,
    /// A mesh triangle with `vt` texture coordinates.
    UvMesh,
    /// A mesh triangle with `vt` and `vn`, shaded smooth.
    SmoothMesh,
}

/// Where the primitive lives.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Context {
    /// The only object.
    Alone,
    /// Beside one small quad far away: both in one leaf, packed together.
    Pair,
    /// Among small quads and triangles just behind it.
    Crowd,
    /// In a group (with its crowd) placed twice, the transform the placement's.
    Placed,
}

/// One case: the primitive `corner + s·a + t·b` (a triangle: s, t its
/// barycentrics) under the affine map (`m`, `offset`), with its vertices'
/// texture coordinates and normals (meshes), hit at `(s, t)` from a
/// direction tilted by `tilt` from its normal.
#[derive(Debug, Clone)]
struct Case {
    kind: Kind,
    corner: DVec3,
    a: DVec3,
    b: DVec3,
    m: DMat3,
    offset: DVec3,
    uvs: [DVec2; 3],
    normals: [DVec3; 3],
    at: DVec2,
    tilt: DVec2,
}

/// A number on a grid of 1/1024 in `lo..hi`: written exactly in the scene.
fn exact(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    ((lo * 1024.0) as i64..(hi * 1024.0) as i64).prop_map(|k| k as f64 / 1024.0)
}

fn vector(lo: f64, hi: f64) -> impl Strategy<Value = DVec3> {
    (exact(lo, hi), exact(lo, hi), exact(lo, hi)).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn uv() -> impl Strategy<Value = DVec2> {
    (exact(0.0, 1.0), exact(0.0, 1.0)).prop_map(|(u, v)| DVec2::new(u, v))
}

/// A linear map that is neither close to singular nor too uneven (its
/// condition number in the Frobenius norm under 90, so its singular values
/// within a factor of 90), often mirroring. (A bound on the determinant
/// alone let through a map of condition 312, whose placed hits graze the
/// triangle in its own frame: texture coordinates 2.6e-3 off in f32.)
fn linear_map() -> impl Strategy<Value = DMat3> {
    (vector(-2.0, 2.0), vector(-2.0, 2.0), vector(-2.0, 2.0))
        .prop_map(|(x, y, z)| DMat3::from_cols(x, y, z))
        .prop_filter("well conditioned", |m| {
            m.determinant().abs() > 0.05 && condition(*m) < 90.0
        })
}

fn case() -> impl Strategy<Value = Case> {
    let kind = prop_oneof![
        Just(Kind::Quad),
        Just(Kind::Triangle),
        Just(Kind::PlainMesh),
        Just(Kind::UvMesh),
        Just(Kind::SmoothMesh),
    ];
    let uvs = (uv(), uv(), uv()).prop_filter("a UV triangle with area", |(a, b, c)| {
        (*b - *a).perp_dot(*c - *a).abs() > 0.05
    });
    let normals = (vector(-0.5, 0.5), vector(-0.5, 0.5), vector(-0.5, 0.5));
    (
        kind,
        vector(-3.0, 3.0),
        (vector(-2.0, 2.0), vector(-2.0, 2.0)).prop_filter("edges with area", |(a, b)| {
            a.cross(*b).length() > 0.2 * a.length() * b.length() && a.length() > 0.1
        }),
        (linear_map(), vector(-5.0, 5.0)),
        uvs,
        normals,
        (exact(0.15, 0.85), exact(0.15, 0.85)),
        (exact(-0.5, 0.5), exact(-0.5, 0.5)),
    )
        .prop_map(
            |(kind, corner, (a, b), (m, offset), (u0, u1, u2), (n0, n1, n2), (s, t), tilt)| {
                // A triangle is hit inside: barycentrics summing below 0.85.
                let at = if kind == Kind::Quad {
                    DVec2::new(s, t)
                } else {
                    DVec2::new(s, t) * (0.85 / (s + t).max(0.85))
                };
                let face = a.cross(b).normalize();
                Case {
                    kind,
                    corner,
                    a,
                    b,
                    m,
                    offset,
                    uvs: [u0, u1, u2],
                    // Vertex normals on the face's side, unnormalised.
                    normals: [n0 + face, n1 + face, n2 + face],
                    at: DVec2::new(at.x.max(0.05), at.y.max(0.05)),
                    tilt: DVec2::new(tilt.0, tilt.1),
                }
            },
        )
}

fn v(p: DVec3) -> String {
    format!("<{}, {}, {}>", p.x, p.y, p.z)
}

/// The scene language's `matrix` of the map (`m`, `offset`), row by row.
fn matrix(m: DMat3, offset: DVec3) -> String {
    let r = m.transpose();
    let row = |c: DVec3, o: f64| format!("{}, {}, {}, {}", c.x, c.y, c.z, o);
    format!(
        "matrix <{}, {}, {}>",
        row(r.x_axis, offset.x),
        row(r.y_axis, offset.y),
        row(r.z_axis, offset.z)
    )
}

impl Case {
    /// The point of the primitive at its own parameters `(s, t)`, before
    /// the transform.
    fn local(&self, st: DVec2) -> DVec3 {
        self.corner + st.x * self.a + st.y * self.b
    }

    fn world(&self, p: DVec3) -> DVec3 {
        self.m * p + self.offset
    }

    /// The outward normal in the world: the definition's, moved as a normal.
    fn normal(&self) -> DVec3 {
        (self.m.inverse().transpose() * self.a.cross(self.b)).normalize()
    }

    /// The OBJ file of a mesh case.
    fn obj(&self) -> String {
        let mut s = String::new();
        for p in [self.corner, self.corner + self.a, self.corner + self.b] {
            writeln!(s, "v {} {} {}", p.x, p.y, p.z).unwrap();
        }
        if matches!(self.kind, Kind::UvMesh | Kind::SmoothMesh) {
            for t in self.uvs {
                writeln!(s, "vt {} {}", t.x, t.y).unwrap();
            }
        }
        if self.kind == Kind::SmoothMesh {
            for n in self.normals {
                writeln!(s, "vn {} {} {}", n.x, n.y, n.z).unwrap();
            }
        }
        s + match self.kind {
            Kind::UvMesh => "f 1/1 2/2 3/3\n",
            Kind::SmoothMesh => "f 1/1/1 2/2/2 3/3/3\n",
            _ => "f 1 2 3\n",
        }
    }

    /// The object as written, with `transform` (possibly empty).
    fn object(&self, transform: &str) -> String {
        let (c, a, b) = (self.corner, self.a, self.b);
        match self.kind {
            Kind::Quad => format!(
                "quad {{ corner {} edge1 {} edge2 {} {transform} }}",
                v(c),
                v(a),
                v(b)
            ),
            Kind::Triangle => format!(
                "triangle {{ v0 {} v1 {} v2 {} {transform} }}",
                v(c),
                v(c + a),
                v(c + b)
            ),
            Kind::SmoothMesh => format!("mesh {{ file \"m.obj\" smooth true {transform} }}"),
            _ => format!("mesh {{ file \"m.obj\" {transform} }}"),
        }
    }

    /// Small quads and triangles just behind the primitive (on the side
    /// away from its normal, in its own frame), each with `transform`.
    fn crowd(&self, transform: &str) -> String {
        let n = self.a.cross(self.b).normalize();
        let mut s = String::new();
        for k in 0..12 {
            let st = DVec2::new((k % 4) as f64 / 4.0 + 0.05, (k / 4) as f64 / 3.0 + 0.05);
            let p = self.local(st) - n * (0.05 + 0.02 * k as f64);
            let (e1, e2) = (self.a * 0.1, self.b * 0.1);
            if k % 2 == 0 {
                let shape = format!("corner {} edge1 {} edge2 {}", v(p), v(e1), v(e2));
                writeln!(s, "quad {{ {shape} {transform} }}").unwrap();
            } else {
                let (p1, p2) = (p + e1, p + e2);
                let shape = format!("v0 {} v1 {} v2 {}", v(p), v(p1), v(p2));
                writeln!(s, "triangle {{ {shape} {transform} }}").unwrap();
            }
        }
        s
    }

    /// The scene of the case in `context`.
    fn scene(&self, context: Context) -> String {
        let t = matrix(self.m, self.offset);
        let head = "camera { position <0, 0, 50> look_at <0, 0, 0> }\n";
        let body = match context {
            Context::Alone => self.object(&t),
            Context::Pair => format!(
                "{}\nquad {{ corner <40, 40, 40> edge1 <0.1, 0, 0> edge2 <0, 0.1, 0> }}",
                self.object(&t)
            ),
            Context::Crowd => format!("{}\n{}", self.object(&t), self.crowd(&t)),
            Context::Placed => format!(
                "group g {{\n{}\n{}}}\ninstance g {{ {t} }}\ninstance g {{ translate <300, 0, 0> }}",
                self.object(""),
                self.crowd("")
            ),
        };
        format!("{head}{body}\n")
    }

    /// The texture coordinates the primitive's own definition gives at its
    /// parameters `at`.
    fn texcoords(&self) -> DVec2 {
        match self.kind {
            Kind::UvMesh | Kind::SmoothMesh => {
                let [u0, u1, u2] = self.uvs;
                (1.0 - self.at.x - self.at.y) * u0 + self.at.x * u1 + self.at.y * u2
            }
            _ => self.at,
        }
    }

    /// (∂p/∂u, ∂p/∂v) in the world from the definition: the transformed
    /// edges, or for texture coordinates the inverse of their map.
    fn tangents(&self) -> (DVec3, DVec3) {
        let (ma, mb) = (self.m * self.a, self.m * self.b);
        match self.kind {
            Kind::UvMesh | Kind::SmoothMesh => {
                let [u0, u1, u2] = self.uvs;
                let (d1, d2) = (u1 - u0, u2 - u0);
                let det = d1.perp_dot(d2);
                ((d2.y * ma - d1.y * mb) / det, (d1.x * mb - d2.x * ma) / det)
            }
            _ => (ma, mb),
        }
    }

    /// The shading normal of a smooth mesh: its unit vertex normals
    /// interpolated in the file's order, on the geometric normal's side.
    /// They are interpolated in the frame the mesh is stored in: the
    /// world's (each vertex normal moved, as Mitsuba 3 loads a mesh), or
    /// for a placed group the group's, moved after (as Mitsuba's
    /// `instance`); under an uneven scale the two differ slightly.
    fn shading_normal(&self, context: Context) -> DVec3 {
        let n = self.normal();
        if self.kind != Kind::SmoothMesh {
            return n;
        }
        let to_world = self.m.inverse().transpose();
        let moved = |n: DVec3| match context {
            Context::Placed => n.normalize(),
            _ => (to_world * n).normalize(),
        };
        let [n0, n1, n2] = self.normals.map(moved);
        let stored = (1.0 - self.at.x - self.at.y) * n0 + self.at.x * n1 + self.at.y * n2;
        let s = match context {
            Context::Placed => to_world * stored,
            _ => stored,
        }
        .normalize();
        if s.dot(n) < 0.0 {
            -s
        } else {
            s
        }
    }
}

/// The condition number of `m` in the Frobenius norm, ‖m‖·‖m⁻¹‖: how much
/// it can magnify a relative error.
fn condition(m: DMat3) -> f64 {
    let frobenius = |m: DMat3| {
        (m.x_axis.length_squared() + m.y_axis.length_squared() + m.z_axis.length_squared()).sqrt()
    };
    frobenius(m) * frobenius(m.inverse())
}

fn close(got: Vec3, want: DVec3, scale: f64) -> bool {
    (got.as_dvec3() - want).length() <= 2e-3 * scale.max(1.0)
}

/// Checks the frame of the case's hit in `scene`; returns whether the hit
/// was on a plain (packed, record-less) primitive.
fn check_frame(c: &Case, context: Context, ir: &Scene) -> Result<bool, TestCaseError> {
    let q = c.world(c.local(c.at));
    let n = c.normal();
    let scale = (c.m * c.a).length().max((c.m * c.b).length());
    // A ray towards q from the front, tilted.
    let (x, z) = {
        let helper = if n.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
        let x = n.cross(helper).normalize();
        (x, n.cross(x))
    };
    let d = -(n + c.tilt.x * x + c.tilt.y * z).normalize();
    let o = q - d * 2.0 * scale;
    let ray = Ray::new(o.as_vec3(), d.as_vec3(), 0.0);
    let hit = ir.intersect(&ray, 0.0, f32::INFINITY);
    let hit = hit.ok_or_else(|| TestCaseError::fail(format!("{context:?}: no hit")))?;
    prop_assert!(close(hit.p, q, scale), "{context:?}: p {} vs {q}", hit.p);
    prop_assert!(
        close(hit.n_geo, n, 1.0),
        "{context:?}: n {} vs {n}",
        hit.n_geo
    );
    let ns = c.shading_normal(context);
    // A placed group is intersected in its own frame, where an uneven
    // placement can make the ray graze the triangle: the barycentrics then
    // carry f32 errors growing with the placement's condition number, and
    // the inverse transpose moving the shading normal out magnifies them by
    // up to it again (a condition number of 124 turned one 3.6e-3 off).
    let placed = match context {
        Context::Placed => (condition(c.m) / 50.0).powi(2).max(1.0),
        _ => 1.0,
    };
    prop_assert!(
        close(hit.n_shading, ns, placed),
        "{context:?}: ns {} vs {ns}",
        hit.n_shading
    );
    let uv = ir.texcoords(&hit, 0.0);
    let want = c.texcoords();
    prop_assert!(
        (uv.as_dvec2() - want).length() < 2e-3,
        "{context:?}: uv {uv} vs {want}"
    );
    let (dpdu, dpdv) = ir.derivatives(&hit, 0.0);
    let (wu, wv) = c.tangents();
    let size = wu.length().max(wv.length());
    prop_assert!(close(dpdu, wu, size), "{context:?}: dp/du {dpdu} vs {wu}");
    prop_assert!(close(dpdv, wv, size), "{context:?}: dp/dv {dpdv} vs {wv}");
    let records = if hit.instance == u32::MAX {
        ir.prims.len()
    } else {
        let placement = &ir.instances.placements[hit.instance as usize];
        ir.instances.prototypes[placement.prototype as usize]
            .prims
            .len()
    };
    Ok(hit.prim as usize >= records)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(256),
        ..ProptestConfig::default()
    })]

    /// Every context of a random primitive gives its own frame; a quad or a
    /// plain triangle beside one other primitive is packed (so both forms
    /// are compared in every case).
    #[test]
    fn every_hit_has_the_primitives_own_frame(c in case()) {
        let dir = crate::temp_dir_with(&[("m.obj", &c.obj())]);
        let path = dir.path().join("frames.pts");
        for context in [Context::Alone, Context::Pair, Context::Crowd, Context::Placed] {
            let text = c.scene(context);
            let compiled = compile_str(&path, &text, Options::default());
            let ir = compiled.ir.unwrap_or_else(|| {
                panic!("{}\n{text}", compiled.diagnostics.render_human(&compiled.sources, false))
            });
            let plain = check_frame(&c, context, &ir)?;
            let packable = matches!(c.kind, Kind::Quad | Kind::Triangle | Kind::PlainMesh);
            if context == Context::Pair {
                prop_assert_eq!(plain, packable, "{:?} beside one other primitive", c.kind);
            }
            if context == Context::Alone && c.kind == Kind::Quad {
                prop_assert!(!plain, "a lone quad keeps its record");
            }
        }
    }
}

/// The case: a constant normal map tilting 20° towards +u on a quad
/// whose `edge1` runs up, alone (its record) and with a small quad added
/// (packed into a block): the shading normal leans towards `edge1` in both.
#[test]
fn a_normal_map_turns_with_edge1_alone_and_packed() {
    let tilt = 20f32.to_radians();
    let texel = [tilt.sin(), 0.0, tilt.cos()].map(|c| ((c + 1.0) * 0.5 * 255.0).round() as u8);
    let dir = tempfile::tempdir().unwrap();
    let mut png = Vec::new();
    image::RgbImage::from_pixel(4, 4, image::Rgb(texel))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    std::fs::write(dir.path().join("tilt20.png"), png).unwrap();
    for turn in 0..4 {
        let a = turn as f32 * std::f32::consts::FRAC_PI_2;
        let e1 = Vec3::new(-a.sin(), a.cos(), 0.0);
        let e2 = Vec3::new(-a.cos(), -a.sin(), 0.0);
        let corner = -0.5 * (e1 + e2);
        let v = |p: Vec3| format!("<{}, {}, {}>", p.x, p.y, p.z);
        let quad = format!(
            "quad {{ corner {} edge1 {} edge2 {}\n\
             material {{ diffuse rgb 0.5 normal_map image {{ file \"tilt20.png\" }} }} }}\n",
            v(corner),
            v(e1),
            v(e2)
        );
        let expected = tilt.sin() * e1 + tilt.cos() * Vec3::Z;
        normal_leans(dir.path(), &quad, expected);
    }
}

/// The shading normal at the centre of `quad` (facing +z), alone and with a
/// small quad beside it, is `expected`; only the second is packed.
fn normal_leans(dir: &std::path::Path, quad: &str, expected: Vec3) {
    for extra in [
        "",
        "quad { corner <3, 3, -5> edge1 <0.1, 0, 0> edge2 <0, 0.1, 0> }\n",
    ] {
        let text = format!("camera {{ position <0, 0, 5> look_at <0, 0, 0> }}\n{quad}{extra}");
        let c = compile_str(&dir.join("s.pts"), &text, Options::default());
        let ir = c.ir.expect("compiles");
        let ray = Ray::new(Vec3::new(0.1, 0.1, 5.0), -Vec3::Z, 0.0);
        let mut hit = ir.intersect(&ray, 0.0, f32::INFINITY).unwrap();
        ir.material_at(&mut hit, Vec3::Z, 0.0, &mut None);
        let plain = hit.prim as usize >= ir.prims.len();
        assert_eq!(
            plain,
            !extra.is_empty(),
            "packed only beside the other quad"
        );
        assert!(
            (hit.n_shading - expected).length() < 0.01,
            "{extra}: {} vs {expected}",
            hit.n_shading
        );
    }
}

/// The round shapes (never packed into blocks), written with their
/// transform or placed through a group by it: the same hit frame.
const ROUND: &[&str] = &[
    "sphere { center <0.2, 0.1, -0.3> radius 0.8",
    "disk { center <0, 0, 0> normal <0.3, 1, 0.2> radius 1",
    "cylinder { base <0, -0.5, 0> top <0, 0.7, 0.2> radius 0.5 open true",
    "cone { base <0, -0.5, 0> top <0.1, 0.6, 0> base_radius 0.7 top_radius 0.2 open true",
    "torus { major_radius 1 minor_radius 0.3 axis <0.2, 1, 0.1>",
];

/// The hit of `ray` in `ir`: point, normals, texture coordinates and tangents.
fn frame_of(ir: &Scene, ray: &Ray) -> Option<[Vec3; 5]> {
    let hit = ir.intersect(ray, 0.0, f32::INFINITY)?;
    let uv = ir.texcoords(&hit, 0.0);
    let (dpdu, dpdv) = ir.derivatives(&hit, 0.0);
    Some([hit.p, hit.n_geo, uv.extend(0.0), dpdu, dpdv])
}

/// How two hits of one ray differ beyond rounding (`None`: they agree), for
/// a shape of about `size`.
fn frames_differ(flat: Option<[Vec3; 5]>, placed: Option<[Vec3; 5]>, size: f32) -> Option<String> {
    let (fa, fb) = match (flat, placed) {
        (None, None) => return None,
        (Some(fa), Some(fb)) => (fa, fb),
        (fa, fb) => {
            return Some(format!(
                "hit {} flat, {} placed",
                fa.is_some(),
                fb.is_some()
            ))
        }
    };
    let names = ["p", "n", "uv", "dp/du", "dp/dv"];
    names.iter().enumerate().find_map(|(k, name)| {
        // Lengths scale with the shape; a seam of u (0 against 1) is the
        // same point.
        let tolerance = match k {
            0 | 3 | 4 => 2e-3 * size.max(1.0) * (1.0 + fa[k].length()),
            _ => 2e-3,
        };
        let same = (fa[k] - fb[k]).length() <= tolerance
            || (k == 2 && ((fa[k] - fb[k]).abs() - Vec3::X).abs().max_element() < 2e-3);
        (!same).then(|| format!("{name}: {} flat, {} placed", fa[k], fb[k]))
    })
}

/// Whether `ray` passes within `by` of where the surface it meets in `ir`
/// ends: a parallel ray moved `by` across it misses, or meets a point that
/// is not the nearby one (a far wall past an open rim).
fn at_an_edge(ir: &Scene, ray: &Ray, by: f32) -> bool {
    let here = frame_of(ir, ray).map(|f| f[0]);
    let (e1, e2) = ray.d.any_orthonormal_pair();
    [e1, -e1, e2, -e2].iter().any(|side| {
        let beside = frame_of(ir, &Ray::new(ray.o + *side * by, ray.d, 0.0)).map(|f| f[0]);
        match (here, beside) {
            (Some(p), Some(q)) => (q - p).length() > 50.0 * by,
            (here, beside) => here.is_some() != beside.is_some(),
        }
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(256),
        ..ProptestConfig::default()
    })]

    /// A sphere, disk, cylinder, cone or torus under a random similarity
    /// (turned, scaled, moved, sometimes mirrored) has at every hit the
    /// frame of the same shape placed through a group by that transform.
    #[test]
    fn round_shapes_placed_or_not_share_their_frame(
        shape in 0..ROUND.len(),
        turn in vector(-180.0, 180.0),
        scale in exact(0.3, 3.0),
        mirror in any::<bool>(),
        offset in vector(-3.0, 3.0),
        towards in prop::collection::vec((vector(-1.0, 1.0), vector(-0.4, 0.4)), 12),
    ) {
        let s = if mirror { -scale } else { scale };
        let transform = format!("rotate {} scale {s} translate {}", v(turn), v(offset));
        let head = "camera { position <0, 0, 50> look_at <0, 0, 0> }\n";
        let flat = format!("{head}{} {transform} }}\n", ROUND[shape]);
        let placed = format!(
            "{head}group g {{ {} }} }}\ninstance g {{ {transform} }}\ninstance g {{ translate <500, 0, 0> }}\n",
            ROUND[shape]
        );
        let compile = |text: &str| {
            let c = compile_str(Path::new("round.pts"), text, Options::default());
            c.ir.unwrap_or_else(|| panic!("{}\n{text}", c.diagnostics.render_human(&c.sources, false)))
        };
        let (a, b) = (compile(&flat), compile(&placed));
        prop_assert!(!b.instances.is_empty(), "the group is shared");
        for (dir, aim) in towards {
            if dir.length() < 0.1 {
                continue;
            }
            let d = dir.normalize();
            let target = offset + aim * scale;
            let ray = Ray::new((target - d * 20.0 * scale).as_vec3(), d.as_vec3(), 0.0);
            let Some(differ) = frames_differ(frame_of(&a, &ray), frame_of(&b, &ray), scale as f32) else {
                continue;
            };
            // A shape moved and a ray moved round differently: where the
            // surface ends (an edge, a silhouette, an open rim) one may hit
            // and the other miss or hit beyond, but only there.
            let by = 1e-3 * scale as f32;
            prop_assert!(
                at_an_edge(&a, &ray, by) || at_an_edge(&b, &ray, by),
                "{} away from any edge\n{}",
                differ,
                flat
            );
        }
    }
}
