//! Explicit lights.

use crate::check;
use crate::light::Light;
use glam::{DVec3, Vec3};

fn v3(v: DVec3) -> Vec3 {
    v.as_vec3()
}

fn rgb(c: &[f64; 3]) -> Vec3 {
    Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32)
}

/// An explicit light (point, spot, directional) in the renderer's f32.
pub fn lower_light(l: &check::Light) -> Light {
    match l {
        check::Light::Point {
            position,
            intensity,
        } => Light::Point {
            position: v3(*position),
            intensity: rgb(intensity),
        },
        check::Light::Spot {
            position,
            direction,
            intensity,
            angle,
            hotspot,
        } => Light::Spot {
            position: v3(*position),
            direction: v3(*direction),
            intensity: rgb(intensity),
            cos_total: angle.to_radians().cos() as f32,
            cos_hotspot: hotspot.to_radians().cos() as f32,
        },
        check::Light::Directional {
            direction,
            irradiance,
        } => Light::Directional {
            direction: v3(*direction),
            irradiance: rgb(irradiance),
        },
    }
}
