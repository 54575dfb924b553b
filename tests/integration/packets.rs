//! Camera-ray packets (`accel/packet.rs`, `ir/packet.rs`): each ray of a
//! packet gets the hit it gets alone, and packets are refused where they
//! cannot go.

use glam::Vec3;
use proptest::prelude::*;
use ptsc::compile::{compile_str, Options};
use ptsc::geometry::{Ray, T_MIN};
use ptsc::integrator::Integrator;
use ptsc::ir::Scene;
use ptsc::render::render;
use ptsc::sampling::sampler::Sampler;
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// A scene of `n` small random triangles in the unit cube (several per
/// leaf, so that blocks are full), spheres among them, a quad and an
/// unbounded plane below.
fn scene(seed: u64, n: usize) -> Scene {
    let mut state = seed | 1;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    };
    let mut text = String::from(
        "camera { position <0, 0, 4> look_at <0, 0, 0> }\npoint_light { position <3, 5, 4> intensity rgb 20 }\n",
    );
    for _ in 0..n {
        let c = Vec3::new(next(), next(), next());
        let v = |c: Vec3, k: &mut dyn FnMut() -> f32| c + 0.15 * Vec3::new(k(), k(), k());
        let (a, b, d) = (v(c, &mut next), v(c, &mut next), v(c, &mut next));
        text += &format!(
            "triangle {{ v0 <{}, {}, {}> v1 <{}, {}, {}> v2 <{}, {}, {}> }}\n",
            a.x, a.y, a.z, b.x, b.y, b.z, d.x, d.y, d.z
        );
    }
    for _ in 0..n / 20 {
        let c = Vec3::new(next(), next(), next());
        text += &format!(
            "sphere {{ center <{}, {}, {}> radius 0.08 }}\n",
            c.x, c.y, c.z
        );
    }
    text += "quad { corner <-1, -1, -1.2> edge1 <2, 0, 0> edge2 <0, 2, 0> }\n";
    text += "plane { normal <0, 1, 0> point <0, -1.5, 0> }\n";
    let c = compile_str(Path::new("packet.pts"), &text, Options::default());
    c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Every ray of a packet gets exactly the hit it gets alone: rays
    /// of one pixel from a pinhole (one origin) or a lens (origins
    /// spread), aimed anywhere at the scene, 2 to 16 of them.
    #[test]
    fn a_packet_finds_each_rays_own_hit(
        seed in 1u64..1000,
        eye in (-3f32..3.0, -3f32..3.0, 2.5f32..4.0),
        aim in (-1f32..1.0, -1f32..1.0, -1f32..1.0),
        spread in prop_oneof![Just(0.0f32), 0.0f32..0.05],
        footprint in 0.0001f32..0.05,
        jitter in prop::collection::vec((-1f32..1.0, -1f32..1.0, -1f32..1.0, -1f32..1.0), 2..=16),
    ) {
        let scene = scene(seed, 3000);
        prop_assert!(scene.traces_packets());
        let eye = Vec3::new(eye.0, eye.1, eye.2);
        let aim = Vec3::new(aim.0, aim.1, aim.2);
        let rays: Vec<Ray> = jitter
            .iter()
            .map(|&(a, b, c, d)| {
                let o = eye + spread * Vec3::new(a, b, 0.0);
                let target = aim + footprint * Vec3::new(c, d, c * d);
                Ray::new(o, (target - o).normalize(), 0.0)
            })
            .collect();
        let t_min = T_MIN;
        let Some(hits) = scene.intersect_packet(&rays, t_min) else {
            // Only rays without one direction sign per axis go alone.
            let signs = |a: usize| rays.iter().map(move |r| r.d[a].signum() as i32 * (r.d[a] != 0.0) as i32);
            let one_sign = (0..3).all(|a| {
                let s: Vec<i32> = signs(a).collect();
                s[0] != 0 && s.iter().all(|&x| x == s[0])
            });
            prop_assert!(!one_sign, "one pixel's rays go as a packet");
            return Ok(());
        };
        for (r, ray) in rays.iter().enumerate() {
            let alone = scene.intersect(ray, t_min, f32::INFINITY);
            let packed = hits.get(r);
            prop_assert_eq!(format!("{packed:?}"), format!("{alone:?}"), "ray {}", r);
        }
    }
}

#[test]
fn rays_of_mixed_directions_go_alone() {
    let scene = scene(7, 3000);
    let o = Vec3::new(0.0, 0.0, 4.0);
    let rays = [
        Ray::new(o, Vec3::new(0.1, 0.0, -1.0).normalize(), 0.0),
        Ray::new(o, Vec3::new(-0.1, 0.0, -1.0).normalize(), 0.0),
    ];
    assert!(scene.intersect_packet(&rays, 1e-4).is_none());
    let axis = [Ray::new(o, -Vec3::Z, 0.0), Ray::new(o, -Vec3::Z, 0.0)];
    assert!(
        scene.intersect_packet(&axis, 1e-4).is_none(),
        "a zero component"
    );
}

#[test]
fn a_small_tree_is_walked_ray_by_ray() {
    let scene = scene(3, 4);
    assert!(!scene.traces_packets());
    let o = Vec3::new(0.0, 0.0, 4.0);
    let rays = [Ray::new(o, Vec3::new(0.1, 0.1, -1.0).normalize(), 0.0); 2];
    assert!(scene.intersect_packet(&rays, 1e-4).is_none());
}

/// The path integrator with its camera rays traced one by one.
struct Alone(Box<dyn Integrator>);

impl Integrator for Alone {
    fn li(&self, scene: &Scene, ray: Ray, sampler: &mut Sampler) -> Vec3 {
        self.0.li(scene, ray, sampler)
    }
}

#[test]
fn packets_change_no_pixel_of_a_render() {
    // Big pixels (tests per packet past the gauge's limit turn packets
    // off in some tiles) and small ones (packets everywhere): the sums
    // equal the single rays' bit for bit.
    let mut ir = scene(11, 3000);
    ir.settings.samples = 40;
    let cancel = AtomicBool::new(false);
    for size in [24, 96] {
        (ir.settings.width, ir.settings.height) = (size, size);
        let path = ptsc::integrator::make(ir.settings.integrator, &ir);
        assert!(path.takes_first_hit(&ir) && ir.traces_packets());
        let alone = Alone(ptsc::integrator::make(ir.settings.integrator, &ir));
        let sums = |integ: &dyn Integrator| {
            render(&ir, integ, &cancel, &|_| {}, &mut |_, _| {})
                .film
                .sum
        };
        assert_eq!(sums(path.as_ref()), sums(&alone), "{size}²");
    }
}
