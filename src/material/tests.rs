//! Tests of [`super`]: the mix of lobes and its energy.
use super::*;
use crate::sampling::sampler::Sampler;

/// A material from the four lobe parameters (grey, default IOR).
pub(crate) fn mat(diffuse: f32, reflection: f32, gloss: f32, transmission: f32) -> Material {
    Material::new(&Params {
        diffuse: Vec3::splat(diffuse),
        reflection: Vec3::splat(reflection),
        gloss,
        transmission,
        ..Params::default()
    })
}

/// Directional albedo by sampling: the mean weight of sampled directions.
fn albedo(m: &Material, wo: Vec3, n: usize) -> f32 {
    let mut s = Sampler::new(3, 1, 2, 0);
    let mut sum = 0.0f64;
    for _ in 0..n {
        if let Some(b) = m.sample(wo, Vec3::Z, s.next_f32(), s.next_2d()) {
            sum += b.weight.x as f64;
        }
    }
    (sum / n as f64) as f32
}

#[test]
fn white_diffuse_and_mirror_and_glass_conserve_energy_exactly() {
    let wo = Vec3::new(0.3, 0.0, 0.954).normalize();
    assert!((albedo(&mat(1.0, 0.0, 0.0, 0.0), wo, 10_000) - 1.0).abs() < 1e-4);
    assert!((albedo(&mat(0.0, 1.0, 0.0, 0.0), wo, 1000) - 1.0).abs() < 1e-6);
    assert!((albedo(&mat(0.0, 0.0, 0.0, 1.0), wo, 1000) - 1.0).abs() < 1e-6);
    assert!((albedo(&mat(0.0, 0.0, 0.0, 1.0), -wo, 1000) - 1.0).abs() < 1e-6);
}

#[test]
fn white_glossy_reflects_all_it_receives() {
    for gloss in [0.1, 0.3, 0.7, 1.0] {
        for cos in [0.2f32, 0.6, 1.0] {
            let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
            let a = albedo(&mat(0.0, 1.0, gloss, 0.0), wo, 50_000);
            // With the multiple-scattering compensation a white glossy
            // surface reflects everything, within sampling noise.
            assert!((a - 1.0).abs() < 0.01, "gloss {gloss} cos {cos}: {a}");
        }
    }
}

#[test]
fn mixed_lobes_are_scaled_to_conserve_energy() {
    let m = mat(0.8, 0.8, 0.0, 0.0);
    assert!((m.diffuse.x - 0.5).abs() < 1e-6 && (m.reflection.x - 0.5).abs() < 1e-6);
    let wo = Vec3::new(0.0, 0.0, 1.0);
    assert!((albedo(&m, wo, 20_000) - 1.0).abs() < 0.02);
}

#[test]
fn eval_is_reciprocal() {
    let m = mat(0.5, 0.5, 0.4, 0.0);
    let a = Vec3::new(0.3, 0.2, 0.9).normalize();
    let b = Vec3::new(-0.5, 0.1, 0.7).normalize();
    let (fab, _) = m.eval(a, b, Vec3::Z);
    let (fba, _) = m.eval(b, a, Vec3::Z);
    assert!((fab - fba).abs().max_element() < 1e-5);
}

#[test]
fn refraction_obeys_snell() {
    let wo = Vec3::new(0.5, 0.0, 0.866).normalize();
    let wi = refract(wo, Vec3::Z, 1.5).unwrap();
    let sin_o = (1.0 - wo.z * wo.z).sqrt();
    let sin_i = (1.0 - wi.z * wi.z).sqrt();
    assert!((sin_o - 1.5 * sin_i).abs() < 1e-5 && wi.z < 0.0);
}
