//! Textures evaluated at hits: a material's textured colours reach every
//! integrator through `Scene::material_at`. (The scene language's texture
//! blocks come later; these tests attach a texture to a lowered scene.)

use glam::{Affine3A, Vec2, Vec3};
use ptsc::compile::{compile_str, Options};
use ptsc::geometry::Ray;
use ptsc::integrator;
use ptsc::ir::Scene;
use ptsc::material::{Params, Textured};
use ptsc::texture::{Pattern, Space, Texture};
use std::path::Path;
use std::sync::atomic::AtomicBool;

const EVEN: f32 = 0.9;
const ODD: f32 = 0.1;

/// A unit quad facing the camera under a white sky, its diffuse colour a
/// checker in (u, v) scaled to 2 × 2 cells per unit (Mitsuba's default).
fn checkered_quad(integrator: &str) -> Scene {
    let text = format!(
        "render {{ resolution <16, 16> samples 64 integrator {integrator} max_depth 2 }}\n\
         camera {{ position <0.5, 0.5, 2> look_at <0.5, 0.5, 0> fov 28.07 }}\n\
         background rgb 1\n\
         quad {{ corner <0, 0, 0> edge1 <1, 0, 0> edge2 <0, 1, 0> material {{ diffuse rgb 0.5 }} }}\n"
    );
    let c = compile_str(Path::new("t.pts"), &text, Options::default());
    let mut ir =
        c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    ir.textures.push(Texture {
        pattern: Pattern::Checker,
        space: Space::Uv,
        to_pattern: Affine3A::IDENTITY,
        colors: [Vec3::splat(EVEN), Vec3::splat(ODD)],
    });
    let quad_material = ir.object_material[0] as usize;
    ir.materials[quad_material].textured = Some(Box::new(Textured {
        params: Params {
            diffuse: Vec3::splat(0.5),
            ..Params::default()
        },
        diffuse: Some(0),
        reflection: None,
    }));
    ir
}

#[test]
fn a_textured_colour_is_evaluated_at_each_hit() {
    let ir = checkered_quad("path");
    let at = |u: f32, v: f32| {
        let ray = Ray::new(Vec3::new(u, v, 1.0), -Vec3::Z, 0.0);
        let hit = ir.intersect(&ray, 0.0, f32::INFINITY).expect("the quad");
        assert!(
            (ir.texcoords(&hit, 0.0) - Vec2::new(u, v))
                .abs()
                .max_element()
                < 1e-5
        );
        ir.material_at(&hit, 0.0, &mut None).diffuse.x
    };
    assert!((at(0.25, 0.25) - EVEN).abs() < 1e-6);
    assert!((at(0.75, 0.25) - ODD).abs() < 1e-6);
    assert!((at(0.25, 0.75) - ODD).abs() < 1e-6);
    assert!((at(0.75, 0.75) - EVEN).abs() < 1e-6);
}

/// The mean of each quarter of a 16 × 16 image.
fn quarters(ir: &Scene) -> [f32; 4] {
    let integ = integrator::make(ir.settings.integrator);
    let film = ptsc::render::render(
        ir,
        integ.as_ref(),
        &AtomicBool::new(false),
        &|_| {},
        &mut |_, _| {},
    )
    .film;
    let px = film.pixels();
    let mut sums = [0.0f32; 4];
    for y in 0..16 {
        for x in 0..16 {
            // Image rows go down; v goes up.
            let q = (x / 8) + 2 * (1 - y / 8);
            sums[q as usize] += px[(y * 16 + x) as usize].x / 64.0;
        }
    }
    sums
}

#[test]
fn every_integrator_sees_the_texture() {
    // Albedo: exact. Path: a diffuse surface under a white sky of radiance 1
    // reflects its albedo (the quad sees the sky only), within noise (64
    // samples in each of 64 pixels per quarter: about 1 %).
    // Whitted: the sky is a light it samples with shadow rays, the same.
    for (integrator, tolerance) in [("albedo", 1e-6), ("path", 0.03), ("whitted", 0.03)] {
        let q = quarters(&checkered_quad(integrator));
        let expect = [EVEN, ODD, ODD, EVEN];
        for i in 0..4 {
            assert!(
                (q[i] - expect[i]).abs() <= tolerance * expect[i],
                "{integrator}: quarter {i} is {} (expected {})",
                q[i],
                expect[i]
            );
        }
    }
}
