//! The principled material against Mitsuba 3's `principled`, value for
//! value: `tests/mitsuba/principled_eval.json` (by
//! `scripts/mitsuba_principled.py`) holds Mitsuba's f·|cos θ| and pdf at
//! random direction pairs and pairs near the specular lobes, for a grid of
//! metallic × roughness and for each other lobe.

use glam::Vec3;
use ptsc::material::principled::Principled;
use serde_json::Value;

/// The material of one configuration, in ptsc's parameters.
fn principled(params: &Value) -> Principled {
    let get = |name: &str, default: f64| {
        params.get(name).and_then(Value::as_f64).unwrap_or(default) as f32
    };
    Principled {
        metallic: get("metallic", 0.0),
        transmission: get("transmission", 0.0),
        eta: Principled::eta_of_specular(get("specular", 0.5)),
        roughness: get("roughness", 0.5),
        anisotropic: get("anisotropic", 0.0),
        specular_tint: get("specular_tint", 0.0),
        sheen: get("sheen", 0.0),
        sheen_tint: get("sheen_tint", 0.0),
        clearcoat: get("clearcoat", 0.0),
        clearcoat_alpha: Principled::clearcoat_alpha(get("clearcoat_roughness", 0.0)),
    }
}

fn vec3(v: &Value) -> Vec3 {
    let a: Vec<f32> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap() as f32)
        .collect();
    Vec3::new(a[0], a[1], a[2])
}

#[test]
fn principled_matches_mitsuba_value_for_value() {
    let text = std::fs::read_to_string(crate::root().join("tests/mitsuba/principled_eval.json"))
        .expect("tests/mitsuba/principled_eval.json");
    let data: Value = serde_json::from_str(&text).unwrap();
    let base = vec3(&data["base_color"]);
    let mut compared = 0;
    for config in data["configs"].as_array().unwrap() {
        let m = principled(&config["params"]);
        let mut nonzero = 0;
        for pair in config["pairs"].as_array().unwrap() {
            let (wo, wi) = (vec3(&pair["wo"]), vec3(&pair["wi"]));
            let (want, want_pdf) = (vec3(&pair["value"]), pair["pdf"].as_f64().unwrap() as f32);
            let (f, pdf) = m.eval(base, wo, wi);
            let got = f * wi.z.abs();
            let close = |a: f32, b: f32| (a - b).abs() <= 2e-3 * a.abs().max(b.abs()) + 1e-6;
            assert!(
                (0..3).all(|k| close(got[k], want[k])) && close(pdf, want_pdf),
                "{}: wo {wo} wi {wi}: f·cos {got} pdf {pdf}, Mitsuba {want} pdf {want_pdf}",
                config["params"]
            );
            nonzero += (want.max_element() > 0.0) as usize;
            compared += 1;
        }
        // Each configuration is compared where it reflects, not only where
        // both give zero.
        assert!(
            nonzero >= 12,
            "{}: {nonzero} pairs with light",
            config["params"]
        );
        // And the comparison can fail: a roughness 5 % off misses Mitsuba's
        // values on some pair.
        let off = Principled {
            roughness: m.roughness * 1.05,
            ..m
        };
        let misses = config["pairs"].as_array().unwrap().iter().any(|pair| {
            let (wo, wi) = (vec3(&pair["wo"]), vec3(&pair["wi"]));
            let got = off.eval(base, wo, wi).0 * wi.z.abs();
            (got - vec3(&pair["value"])).abs().max_element() > 1e-2 * got.max_element()
        });
        assert!(
            misses,
            "{}: a wrong roughness goes unnoticed",
            config["params"]
        );
    }
    assert!(compared >= 17 * 48, "{compared} pairs");
}

#[test]
fn the_language_gives_every_parameter_to_the_model() {
    use ptsc::compile::{compile_str, Options};
    use ptsc::material::Kind;
    let scene = "camera { position <0, 0, 5> look_at <0, 0, 0> }
        background rgb 1
        sphere { center <0, 0, 0> radius 1 material { type principled
            base_color rgb <0.8, 0.4, 0.2> metallic 0.3 roughness 0.6 specular 0.9
            specular_tint 0.25 anisotropic 0.5 sheen 0.75 sheen_tint 0.2
            clearcoat 0.4 clearcoat_roughness 0.3 transmission 0.1 } }
        sphere { center <3, 0, 0> radius 1 material { type principled } }";
    let c = compile_str(std::path::Path::new("p.pts"), scene, Options::default());
    assert!(!c.diagnostics.has_errors());
    let ir = c.ir.expect("compiles");
    let m = &ir.materials[0];
    let Kind::Principled(p) = m.kind else {
        panic!("{:?}", m.kind)
    };
    assert_eq!(m.diffuse, Vec3::new(0.8, 0.4, 0.2));
    let want = Principled {
        metallic: 0.3,
        transmission: 0.1,
        eta: Principled::eta_of_specular(0.9),
        roughness: 0.6,
        anisotropic: 0.5,
        specular_tint: 0.25,
        sheen: 0.75,
        sheen_tint: 0.2,
        clearcoat: 0.4,
        clearcoat_alpha: Principled::clearcoat_alpha(0.3),
    };
    assert_eq!(p, want);
    // The stretched highlight needs each hit's tangent.
    assert!(m.textured.as_ref().is_some_and(|t| t.tangent));
    // Mitsuba's defaults: grey, roughness 0.5, specular 0.5 (η 1.5).
    let d = &ir.materials[1];
    assert_eq!(d.diffuse, Vec3::splat(0.5));
    assert_eq!(d.kind, Kind::Principled(Principled::default()));
}
