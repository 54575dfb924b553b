//! Every shape through the whole front end and lowering, then intersected in
//! the IR: transformed (translate, rotate, scale, matrix) and moving (linear
//! motion over the shutter). The untransformed hit/miss/inside/grazing cases
//! live next to the intersection code in `src/geometry/shape.rs`.

use glam::Vec3;
use ptsc::compile::{compile_str, Options};
use ptsc::geometry::Ray;
use ptsc::ir::Scene;
use std::path::Path;

const HEADER: &str = "render { resolution <8, 8> samples 1 }
camera { position <0, 0, 10> look_at <0, 0, 0> shutter <0, 1> }
";

fn scene_in(dir: &Path, objects: &str) -> Scene {
    let path = dir.join("shape.pts");
    let c = compile_str(&path, &format!("{HEADER}{objects}\n"), Options::default());
    c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)))
}

fn scene(objects: &str) -> Scene {
    scene_in(Path::new("."), objects)
}

/// Distance and geometric normal of the closest hit of the ray `o + t·d` at `time`.
fn hit(s: &Scene, o: [f32; 3], d: [f32; 3], time: f32) -> Option<(f32, Vec3)> {
    let ray = Ray::new(Vec3::from(o), Vec3::from(d).normalize(), time);
    let h = s.intersect(&ray, 0.0, f32::INFINITY)?;
    // The shadow query must agree with the closest-hit query.
    assert!(s.occluded(&ray, 0.0, f32::INFINITY));
    Some((h.t, h.n_geo))
}

fn miss(s: &Scene, o: [f32; 3], d: [f32; 3], time: f32) -> bool {
    let ray = Ray::new(Vec3::from(o), Vec3::from(d).normalize(), time);
    let none = s.intersect(&ray, 0.0, f32::INFINITY).is_none();
    assert_eq!(none, !s.occluded(&ray, 0.0, f32::INFINITY));
    none
}

fn near(a: f32, b: f32) -> bool {
    (a - b).abs() < 1e-4 * b.abs().max(1.0)
}

fn near_v(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < 1e-4
}

#[test]
fn sphere_transformed_and_moving() {
    // Unit sphere scaled by 2 and moved to x = 3: surface at z = 2 facing +z.
    let s = scene("sphere { center <0, 0, 0> radius 1 scale 2 translate <3, 0, 0> }");
    let (t, n) = hit(&s, [3.0, 0.0, 10.0], [0.0, 0.0, -1.0], 0.0).unwrap();
    assert!(near(t, 8.0) && near_v(n, Vec3::Z), "{t} {n}");
    assert!(miss(&s, [0.0, 0.0, 10.0], [0.0, 0.0, -1.0], 0.0));
    // From inside: leaves through the far side, normal still outward.
    let (t, n) = hit(&s, [3.0, 0.0, 0.0], [1.0, 0.0, 0.0], 0.0).unwrap();
    assert!(near(t, 2.0) && near_v(n, Vec3::X), "{t} {n}");
    // Scaling about the origin moves the centre too (POV-Ray order).
    let s = scene("sphere { center <1, 0, 0> radius 0.5 translate <1, 0, 0> scale 2 }");
    let (t, _) = hit(&s, [4.0, 0.0, 10.0], [0.0, 0.0, -1.0], 0.0).unwrap();
    assert!(near(t, 9.0), "{t}");

    // Moving at 4 units per shutter time: at t = 0.5 it is at x = 2.
    let s = scene("sphere { center <0, 0, 0> radius 0.5 velocity <4, 0, 0> }");
    let (t, _) = hit(&s, [2.0, 0.0, 10.0], [0.0, 0.0, -1.0], 0.5).unwrap();
    assert!(near(t, 9.5), "{t}");
    assert!(miss(&s, [0.0, 0.0, 10.0], [0.0, 0.0, -1.0], 0.5));
    assert!(hit(&s, [0.0, 0.0, 10.0], [0.0, 0.0, -1.0], 0.0).is_some());
    assert!(hit(&s, [4.0, 0.0, 10.0], [0.0, 0.0, -1.0], 1.0).is_some());
}

#[test]
fn plane_transformed_and_moving() {
    // The plane y = 0 rotated 90° about x becomes z = 0 facing +z, then moved to z = 1.
    let s = scene("plane { normal <0, 1, 0> rotate <90, 0, 0> translate <0, 0, 1> }");
    let (t, n) = hit(&s, [5.0, -3.0, 10.0], [0.0, 0.0, -1.0], 0.0).unwrap();
    assert!(near(t, 9.0) && near_v(n, Vec3::Z), "{t} {n}");
    assert!(miss(&s, [0.0, 0.0, 10.0], [0.0, 0.0, 1.0], 0.0));
    // Parallel ray: no hit.
    assert!(miss(&s, [0.0, 0.0, 2.0], [1.0, 0.0, 0.0], 0.0));

    let s = scene("plane { normal <0, 0, 1> velocity <0, 0, 2> }");
    let (t, _) = hit(&s, [0.0, 0.0, 10.0], [0.0, 0.0, -1.0], 0.5).unwrap();
    assert!(near(t, 9.0), "moving plane: {t}");
}

#[test]
fn quad_transformed_and_moving() {
    // Unit square in the xy plane, scaled to 2×4, rotated 90° about z: spans
    // x in [-4, 0], y in [0, 2].
    let s = scene(
        "quad { corner <0, 0, 0> edge1 <1, 0, 0> edge2 <0, 1, 0> scale <2, 4, 1> rotate <0, 0, 90> }",
    );
    let (t, n) = hit(&s, [-3.5, 1.5, 10.0], [0.0, 0.0, -1.0], 0.0).unwrap();
    assert!(near(t, 10.0) && near_v(n, Vec3::Z), "{t} {n}");
    assert!(miss(&s, [1.0, 1.0, 10.0], [0.0, 0.0, -1.0], 0.0));
    assert!(miss(&s, [-3.5, 2.5, 10.0], [0.0, 0.0, -1.0], 0.0));
    // From behind: hit, geometric normal unchanged (shading decides the side).
    let (_, n) = hit(&s, [-1.0, 1.0, -5.0], [0.0, 0.0, 1.0], 0.0).unwrap();
    assert!(near_v(n, Vec3::Z));

    let s = scene("quad { corner <0, 0, 0> edge1 <1, 0, 0> edge2 <0, 1, 0> velocity <-2, 0, 0> }");
    assert!(miss(&s, [0.5, 0.5, 10.0], [0.0, 0.0, -1.0], 1.0));
    assert!(hit(&s, [-1.5, 0.5, 10.0], [0.0, 0.0, -1.0], 1.0).is_some());
}

#[test]
fn disk_transformed_and_moving() {
    // A disk of radius 1 facing +y, rotated -90° about x to face +z, scaled by 3.
    let s = scene("disk { center <0, 0, 0> normal <0, 1, 0> radius 1 rotate <90, 0, 0> scale 3 }");
    let (t, n) = hit(&s, [2.0, 2.0, 10.0], [0.0, 0.0, -1.0], 0.0).unwrap();
    assert!(near(t, 10.0) && near_v(n, Vec3::Z), "{t} {n}");
    assert!(miss(&s, [2.2, 2.2, 10.0], [0.0, 0.0, -1.0], 0.0));

    let s = scene("disk { center <0, 0, 0> normal <0, 0, 1> radius 1 velocity <0, 3, 0> }");
    assert!(miss(&s, [0.0, 0.0, 10.0], [0.0, 0.0, -1.0], 1.0));
    assert!(hit(&s, [0.0, 3.0, 10.0], [0.0, 0.0, -1.0], 1.0).is_some());
}

#[test]
fn triangle_transformed_and_moving() {
    // A matrix that swaps x and y and moves by <1, 1, 1>: the vertices
    // (0,0,0), (1,0,0), (0,1,0) go to (1,1,1), (1,2,1), (2,1,1). Swapping two
    // axes mirrors the triangle; its normal moves as a normal (the inverse
    // transpose leaves +z alone), so the mirrored triangle keeps facing +z
    // although (v1 − v0) × (v2 − v0) of its new vertices points to −z.
    let s = scene(
        "triangle { v0 <0, 0, 0> v1 <1, 0, 0> v2 <0, 1, 0> matrix <0, 1, 0, 1, 1, 0, 0, 1, 0, 0, 1, 1> }",
    );
    let (t, n) = hit(&s, [1.2, 1.2, 10.0], [0.0, 0.0, -1.0], 0.0).unwrap();
    assert!(near(t, 9.0) && near_v(n, Vec3::Z), "{t} {n}");
    assert!(miss(&s, [1.8, 1.8, 10.0], [0.0, 0.0, -1.0], 0.0));
    // Grazing: a ray in the triangle's plane does not hit it.
    assert!(miss(&s, [0.0, 1.2, 1.0], [1.0, 0.0, 0.0], 0.0));

    let s = scene("triangle { v0 <0, 0, 0> v1 <1, 0, 0> v2 <0, 1, 0> velocity <0, 0, -5> }");
    let (t, _) = hit(&s, [0.2, 0.2, 10.0], [0.0, 0.0, -1.0], 0.4).unwrap();
    assert!(near(t, 12.0), "{t}");
}

#[test]
fn box_transformed_and_moving() {
    // The box [-1, 1]³ rotated 45° about y, then moved by <0, 0, -2>.
    let s = scene("box { min <-1, -1, -1> max <1, 1, 1> rotate <0, 45, 0> translate <0, 0, -2> }");
    // Along -z from above the box we meet the rotated edge at z = -2 + √2.
    let (t, _) = hit(&s, [0.0, 0.0, 10.0], [0.0, 0.0, -1.0], 0.0).unwrap();
    assert!(near(t, 12.0 - 2f32.sqrt()), "{t}");
    // From inside: out through a face, normal pointing outward.
    let (t, n) = hit(&s, [0.0, 0.0, -2.0], [0.0, 1.0, 0.0], 0.0).unwrap();
    assert!(near(t, 1.0) && near_v(n, Vec3::Y), "{t} {n}");
    assert!(miss(&s, [0.0, 1.5, 10.0], [0.0, 0.0, -1.0], 0.0));

    let s = scene("box { min <-1, -1, -1> max <1, 1, 1> velocity <10, 0, 0> }");
    assert!(miss(&s, [0.0, 0.0, 10.0], [0.0, 0.0, -1.0], 0.5));
    let (t, n) = hit(&s, [5.0, 0.0, 10.0], [0.0, 0.0, -1.0], 0.5).unwrap();
    assert!(near(t, 9.0) && near_v(n, Vec3::Z), "{t} {n}");
}

#[test]
fn mesh_transformed_moving_and_smooth() {
    // A square of two triangles in the xy plane, with vertex normals tilted
    // outwards so smooth shading differs from flat shading.
    let dir = crate::temp_dir_with(&[(
        "square.obj",
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n\
         vn -1 -1 1\nvn 1 -1 1\nvn 1 1 1\nvn -1 1 1\n\
         f 1//1 2//2 3//3\nf 1//1 3//3 4//4\n",
    )]);
    let s = scene_in(
        dir.path(),
        r#"mesh { file "square.obj" scale 2 translate <0, 0, 1> }"#,
    );
    let (t, n) = hit(&s, [1.5, 1.5, 10.0], [0.0, 0.0, -1.0], 0.0).unwrap();
    assert!(near(t, 9.0) && near_v(n, Vec3::Z), "{t} {n}");
    assert!(miss(&s, [2.5, 0.0, 10.0], [0.0, 0.0, -1.0], 0.0));

    // Smooth: at a corner the shading normal is that vertex's normal; at the
    // centre, the average of the diagonal's two normals (+z).
    let s = scene_in(dir.path(), r#"mesh { file "square.obj" smooth true }"#);
    let shading = |x: f32, y: f32| {
        let ray = Ray::new(Vec3::new(x, y, 10.0), -Vec3::Z, 0.0);
        s.intersect(&ray, 0.0, f32::INFINITY).unwrap().n_shading
    };
    let corner = shading(0.999, 0.999);
    assert!((corner - Vec3::ONE.normalize()).length() < 2e-3, "{corner}");
    assert!((shading(0.0, 0.0) - Vec3::Z).length() < 1e-3);
    let mid = shading(0.5, 0.0);
    assert!(mid.x > 0.1 && mid.z > 0.5, "{mid}");

    let s = scene_in(
        dir.path(),
        r#"mesh { file "square.obj" velocity <0, -2, 0> }"#,
    );
    assert!(miss(&s, [0.0, 0.5, 10.0], [0.0, 0.0, -1.0], 1.0));
    assert!(hit(&s, [0.0, -2.5, 10.0], [0.0, 0.0, -1.0], 1.0).is_some());
}

#[test]
fn offsets_scale_with_the_hit_point() {
    // A sphere far from the origin: a secondary ray spawned at the hit point
    // must not hit the surface it leaves (acne), and one spawned just inside
    // a small sphere must still find the far side (no leaks).
    for (c, r) in [
        (1.0e4f32, 1.0f32),
        (1.0e5, 10.0),
        (0.0, 1.0e-3),
        (0.5, 1.0e-4),
    ] {
        let s = scene(&format!("sphere {{ center <{c}, 0, 0> radius {r} }}"));
        let ray = Ray::new(Vec3::new(c, 0.0, 10.0 * r + 10.0), -Vec3::Z, 0.0);
        let h = s.intersect(&ray, 0.0, f32::INFINITY).unwrap();
        let out = ptsc::geometry::offset_origin(h.p, h.n_geo, Vec3::Z);
        let leave = Ray::new(out, Vec3::new(0.3, 0.0, 1.0).normalize(), 0.0);
        assert!(
            s.intersect(&leave, 0.0, f32::INFINITY).is_none(),
            "acne at {c}"
        );
        let inside = ptsc::geometry::offset_origin(h.p, h.n_geo, -Vec3::Z);
        let through = Ray::new(inside, -Vec3::Z, 0.0);
        let far = s.intersect(&through, 0.0, f32::INFINITY);
        assert!(
            far.is_some_and(|f| near(f.t, 2.0 * r)),
            "leak at {c}: {far:?}"
        );
    }
}

#[test]
fn a_mesh_that_overflows_is_a_diagnostic() {
    // Flat (no vertex normals) and smooth meshes are lowered apart (a flat
    // one keeps no per-triangle record); both must report coordinates that
    // leave the numeric domain (±1e9) after the transform, or in the file.
    let dir = crate::temp_dir_with(&[
        (
            "t.obj",
            "v 0 0 0\nv 10 0 0\nv 0 10 0\nvn 0 0 1\nf 1//1 2//1 3//1\n",
        ),
        ("wide.obj", "v -3e38 0 0\nv 3e38 0 0\nv 0 1 0\nf 1 2 3\n"),
    ]);
    for mesh in [
        r#"mesh { file "t.obj" scale 1e9 }"#,
        r#"mesh { file "t.obj" scale 1e9 smooth true }"#,
        r#"mesh { file "t.obj" translate <1e6, 0, 0> velocity <1e9, 0, 0> }"#,
        r#"mesh { file "wide.obj" }"#,
    ] {
        let path = dir.path().join("shape.pts");
        let c = compile_str(&path, &format!("{HEADER}{mesh}\n"), Options::default());
        assert!(c.ir.is_none(), "{mesh} lowered");
        let codes: Vec<&str> = (c.diagnostics.items.iter())
            .filter(|d| d.is_error())
            .map(|d| d.code)
            .collect();
        assert_eq!(codes, ["pts::check::out_of_range"], "{mesh}");
    }
}

/// Texture coordinates of the closest hit of the ray `o + t·d` at `time`.
fn uv_at(s: &Scene, o: [f32; 3], d: [f32; 3], time: f32) -> glam::Vec2 {
    let ray = Ray::new(Vec3::from(o), Vec3::from(d).normalize(), time);
    let h = s.intersect(&ray, 0.0, f32::INFINITY).expect("a hit");
    s.texcoords(&h, time)
}

fn near_uv(a: glam::Vec2, b: [f32; 2]) -> bool {
    (a - glam::Vec2::from(b)).abs().max_element() < 1e-4
}

#[test]
fn texture_coordinates_follow_each_shape_and_its_transforms() {
    // A sphere: the point facing +z is the middle of the image.
    let s = scene("sphere { center <0, 0, 0> radius 1 }");
    let uv = uv_at(&s, [0.0, 0.0, 10.0], [0.0, 0.0, -1.0], 0.0);
    assert!(near_uv(uv, [0.5, 0.5]), "{uv}");
    let uv = uv_at(&s, [10.0, 0.0, 0.0], [-1.0, 0.0, 0.0], 0.0);
    assert!(near_uv(uv, [0.75, 0.5]), "{uv}");
    // Turned a quarter about y (+z goes to +x), scaled and moved: the
    // middle of the image now faces +x, and the coordinates ride along.
    let s = scene(
        "sphere { center <0, 0, 0> radius 1 rotate <0, 90, 0> scale 2 translate <1, 0, 0> \
         velocity <0, 3, 0> }",
    );
    let uv = uv_at(&s, [10.0, 0.0, 0.0], [-1.0, 0.0, 0.0], 0.0);
    assert!(near_uv(uv, [0.5, 0.5]), "{uv}");
    let uv = uv_at(&s, [10.0, 3.0, 0.0], [-1.0, 0.0, 0.0], 1.0);
    assert!(near_uv(uv, [0.5, 0.5]), "moving: {uv}");
    // North pole.
    let uv = uv_at(&s, [1.0, 10.0, 0.0], [0.0, -1.0, 0.0], 0.0);
    assert!((uv.y - 1.0).abs() < 1e-4, "{uv}");

    // A quad: (s, t) along its edges.
    let s = scene("quad { corner <-1, -1, 0> edge1 <2, 0, 0> edge2 <0, 2, 0> }");
    let uv = uv_at(&s, [-0.5, 0.5, 5.0], [0.0, 0.0, -1.0], 0.0);
    assert!(near_uv(uv, [0.25, 0.75]), "{uv}");

    // A box: every face upright from outside.
    let s = scene("box { min <-1, -1, -1> max <1, 1, 1> }");
    let face = |o: [f32; 3], d: [f32; 3], expect: [f32; 2]| {
        let uv = uv_at(&s, o, d, 0.0);
        assert!(near_uv(uv, expect), "{o:?}: {uv}");
    };
    // Front (+z): right is +x, up is +y.
    face([0.5, -0.5, 5.0], [0.0, 0.0, -1.0], [0.75, 0.25]);
    // Back (−z), seen from behind: right is −x.
    face([0.5, -0.5, -5.0], [0.0, 0.0, 1.0], [0.25, 0.25]);
    // Right (+x): right is −z.
    face([5.0, 0.5, 0.5], [-1.0, 0.0, 0.0], [0.25, 0.75]);
    // Left (−x): right is +z.
    face([-5.0, 0.5, 0.5], [1.0, 0.0, 0.0], [0.75, 0.75]);
    // Top (+y): right is +x, up is −z.
    face([0.5, 5.0, -0.5], [0.0, -1.0, 0.0], [0.75, 0.75]);
    // Bottom (−y): right is +x, up is +z.
    face([0.5, -5.0, -0.5], [0.0, 1.0, 0.0], [0.75, 0.25]);

    // A disk facing +y: planar, its centre at (0.5, 0.5), u along +x, v along −z.
    let s = scene("disk { center <0, 0, 0> normal <0, 1, 0> radius 2 }");
    let uv = uv_at(&s, [1.0, 5.0, -1.0], [0.0, -1.0, 0.0], 0.0);
    assert!(near_uv(uv, [0.75, 0.75]), "{uv}");
    // A plane: one unit of (u, v) per unit of length from its point.
    let s = scene("plane { point <1, 0, 0> normal <0, 1, 0> }");
    let uv = uv_at(&s, [4.0, 5.0, -2.0], [0.0, -1.0, 0.0], 0.0);
    assert!(near_uv(uv, [3.0, 2.0]), "{uv}");

    // A triangle: the barycentrics of v1 and v2.
    let s = scene("triangle { v0 <0, 0, 0> v1 <2, 0, 0> v2 <0, 2, 0> }");
    let uv = uv_at(&s, [0.5, 1.0, 5.0], [0.0, 0.0, -1.0], 0.0);
    assert!(near_uv(uv, [0.25, 0.5]), "{uv}");
}

#[test]
fn mesh_texture_coordinates_are_interpolated_from_the_file() {
    let dir = crate::temp_dir_with(&[
        (
            "uv.obj",
            "v -1 -1 0\nv 1 -1 0\nv -1 1 0\nvt 0.2 0.2\nvt 0.6 0.2\nvt 0.2 1.0\nf 1/1 2/2 3/3\n",
        ),
        ("plain.obj", "v -1 -1 0\nv 1 -1 0\nv -1 1 0\nf 1 2 3\n"),
    ]);
    for (file, expect) in [("uv.obj", [0.3, 0.6]), ("plain.obj", [0.25, 0.5])] {
        // Moving and mirrored (a winding flip) too: the UVs stay with their vertices.
        for extra in ["", "velocity <0, 0, 0.5>", "scale <-1, 1, 1>"] {
            let s = scene_in(dir.path(), &format!("mesh {{ file \"{file}\" {extra} }}"));
            let mirrored = extra.starts_with("scale");
            let x = if mirrored { 0.5 } else { -0.5 };
            let uv = uv_at(&s, [x, 0.0, 5.0], [0.0, 0.0, -1.0], 0.0);
            // Without UVs in the file, the barycentrics of the file's
            // vertices, also where a mirroring transform reversed the
            // winding the triangle is stored with.
            assert!(near_uv(uv, expect), "{file} {extra}: {uv}");
        }
    }
}
