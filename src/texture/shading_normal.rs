//! Normals that textures bend: tangent-space normal maps and bump maps.
//! Both perturb the shading normal only; the integrators keep the
//! geometric normal for deciding which side of a surface a direction is on
//! (see `ir::Scene::material_at`).

use glam::Vec3;

/// The tangent frame at a point with unit normal `n` whose position changes
/// along u by `dpdu`: the tangent is `dpdu` made orthogonal to `n` (Gram–
/// Schmidt), the bitangent `n × t` (pbrt-v4's `NormalMap` and Mitsuba 3's
/// `normalmap` build the same frame). Where `dpdu` vanishes or runs along
/// `n` (a sphere's poles) any tangent will do: one from `n` alone.
pub fn tangent_frame(n: Vec3, dpdu: Vec3) -> (Vec3, Vec3) {
    let t = (dpdu - n * n.dot(dpdu)).normalize_or_zero();
    let t = if t == Vec3::ZERO {
        crate::geometry::orthonormal_basis(n).0
    } else {
        t
    };
    (t, n.cross(t))
}

/// A normal map's texel as a direction in its tangent frame: components
/// in [0, 1] stand for [−1, 1], the tangent's and bitangent's times
/// `scale` (glTF's `normalTexture.scale`: 0 flattens the map, 1 is as
/// baked).
fn decoded(texel: Vec3, scale: f32) -> Vec3 {
    let m = texel * 2.0 - Vec3::ONE;
    Vec3::new(m.x * scale, m.y * scale, m.z)
}

/// The normal a tangent-space normal map gives: the texel's components in
/// [0, 1] stand for [−1, 1] along the tangent, the bitangent and the normal
/// (the OpenGL convention: green points along +v), the first two times
/// `scale`. A texel that decodes to no direction leaves the normal as it
/// is.
pub fn mapped_normal(texel: Vec3, scale: f32, n: Vec3, dpdu: Vec3) -> Vec3 {
    let m = decoded(texel, scale);
    let (t, b) = tangent_frame(n, dpdu);
    (m.x * t + m.y * b + m.z * n).normalize_or(n)
}

/// [`mapped_normal`] in the frame of a mesh's tangent `t` (made
/// perpendicular to `n`) and the bitangent n × t on its `side` (±1; −1
/// where the texture coordinates are mirrored), as glTF defines a normal
/// map's frame.
pub fn mapped_normal_along(texel: Vec3, scale: f32, n: Vec3, (t, side): (Vec3, f32)) -> Vec3 {
    let m = decoded(texel, scale);
    let (t, b) = tangent_frame(n, t);
    (m.x * t + side * m.y * b + m.z * n).normalize_or(n)
}

/// The normal of a surface displaced along its normal `n` by a height whose
/// derivatives along the surface's parameters are `dh_du` and `dh_dv`
/// (Blinn 1978, "Simulation of wrinkled surfaces"; pbrt-v4's `BumpMap`
/// without its small dn/du term): the cross product of the displaced
/// surface's tangents, on the side of `n`. The tangents are first made
/// perpendicular to `n` (which differs from the geometric normal on a
/// smooth-shaded mesh), as Mitsuba 3's `bumpmap` does:
/// ∂p/∂u' = ∂p/∂u − n (n · ∂p/∂u) + (∂h/∂u) n.
pub fn bumped_normal(n: Vec3, dpdu: Vec3, dpdv: Vec3, dh_du: f32, dh_dv: f32) -> Vec3 {
    let pu = dpdu + (dh_du - n.dot(dpdu)) * n;
    let pv = dpdv + (dh_dv - n.dot(dpdv)) * n;
    let ns = pu.cross(pv).normalize_or_zero();
    if ns == Vec3::ZERO {
        n
    } else if ns.dot(n) < 0.0 {
        -ns
    } else {
        ns
    }
}

/// The shading normal `ns` made safe to shade with at a surface whose
/// geometric normal is `ng`, seen from `wo`: on the side of `ng` (pbrt's
/// `FaceForward`), and when `wo` is below it while above the surface
/// itself (a steep bump at a grazing view) the geometric normal instead, so
/// that no lobe is sampled through the surface.
pub fn facing(ns: Vec3, ng: Vec3, wo: Vec3) -> Vec3 {
    let ns = if ns.dot(ng) < 0.0 { -ns } else { ns };
    if (wo.dot(ns) > 0.0) == (wo.dot(ng) > 0.0) {
        ns
    } else {
        ng
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn orthonormal(t: Vec3, b: Vec3, n: Vec3) -> bool {
        let close = |a: f32, b: f32| (a - b).abs() < 1e-5;
        close(t.length(), 1.0)
            && close(b.length(), 1.0)
            && close(t.dot(b), 0.0)
            && close(t.dot(n), 0.0)
            && close(b.dot(n), 0.0)
            && (t.cross(b) - n).length() < 1e-5
    }

    #[test]
    fn tangent_frames_are_orthonormal_and_right_handed() {
        let n = Vec3::new(0.3, 0.8, -0.52).normalize();
        for dpdu in [
            Vec3::X,
            Vec3::new(2.0, 5.0, -1.0),
            Vec3::new(-1e-3, 0.0, 3e-3),
            Vec3::ZERO,
            n * 4.0,
        ] {
            let (t, b) = tangent_frame(n, dpdu);
            assert!(orthonormal(t, b, n), "dpdu {dpdu}: {t} {b}");
        }
        // The tangent follows dpdu when it can.
        let (t, b) = tangent_frame(Vec3::Z, Vec3::new(3.0, 0.0, 1.0));
        assert!((t - Vec3::X).length() < 1e-6 && (b - Vec3::Y).length() < 1e-6);
    }

    #[test]
    fn a_flat_normal_map_keeps_the_normal_and_others_tilt_it() {
        let n = Vec3::Z;
        let flat = Vec3::new(0.5, 0.5, 1.0);
        assert!((mapped_normal(flat, 1.0, n, Vec3::X) - n).length() < 1e-6);
        // Red tilts towards +u, green towards +v (= n × u).
        let m = mapped_normal(Vec3::new(1.0, 0.5, 1.0), 1.0, n, Vec3::X);
        assert!((m - Vec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-6);
        let m = mapped_normal(Vec3::new(0.5, 1.0, 1.0), 1.0, n, Vec3::X);
        assert!((m - Vec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-6);
        // A texel that decodes to zero length leaves the normal.
        assert_eq!(mapped_normal(Vec3::splat(0.5), 1.0, n, Vec3::X), n);
        // A scale of 0 flattens the map; 2 steepens it as glTF's scale.
        let texel = Vec3::new(0.75, 0.5, 0.75);
        assert!((mapped_normal(texel, 0.0, n, Vec3::X) - n).length() < 1e-6);
        let steep = mapped_normal(texel, 2.0, n, Vec3::X);
        assert!(
            (steep - Vec3::new(1.0, 0.0, 0.5).normalize()).length() < 1e-6,
            "{steep}"
        );
    }

    #[test]
    fn bumps_tilt_against_the_slope() {
        let n = Vec3::Y;
        // Height rising along +x: the normal leans towards −x.
        let b = bumped_normal(n, Vec3::X, -Vec3::Z, 1.0, 0.0);
        assert!((b - Vec3::new(-1.0, 1.0, 0.0).normalize()).length() < 1e-6);
        // Whatever the parameters' handedness, the normal stays on n's side.
        let b2 = bumped_normal(n, Vec3::X, Vec3::Z, 1.0, 0.0);
        assert!((b2 - b).length() < 1e-6);
        assert_eq!(bumped_normal(n, Vec3::X, -Vec3::Z, 0.0, 0.0), n);
        // Degenerate parameters keep the normal.
        assert_eq!(bumped_normal(n, Vec3::ZERO, Vec3::ZERO, 1.0, 1.0), n);
    }

    #[test]
    fn facing_keeps_the_side_of_the_geometry() {
        let ng = Vec3::Y;
        let tilted = Vec3::new(0.6, 0.8, 0.0);
        assert_eq!(facing(tilted, ng, Vec3::Y), tilted);
        assert_eq!(facing(-tilted, ng, Vec3::Y), tilted);
        // Seen from where the tilted normal faces away: the geometric one.
        let grazing = Vec3::new(-0.99, 0.1, 0.0).normalize();
        assert_eq!(facing(tilted, ng, grazing), ng);
    }
}
