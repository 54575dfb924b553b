//! Fuzz targets: what a fuzzer feeds arbitrary bytes, and the invariants it
//! checks. A target returns normally for every input; it panics only when
//! ptsc broke a promise (a non-finite pixel, a diagnostic outside its file).
//! Used by the coverage-guided targets in `fuzz/` (cargo-fuzz, libFuzzer)
//! and by the in-process fuzzer `fuzz/inprocess.rs` that CI runs for a
//! bounded time.

mod budget;

pub use budget::{budget, budget_scene};

use crate::compile::{compile_bytes, Options};
use crate::lower::decode::{decode, Format, Limits};
use crate::lower::mesh;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

/// The largest image a fuzzed scene renders: its resolution and samples are
/// cut to this (the pipeline is the same; the fuzzer stays fast).
const MAX_SIDE: u32 = 4;
/// The most samples per pixel a fuzzed scene renders.
const MAX_SAMPLES: u32 = 2;
/// The longest paths a fuzzed scene traces, and its most shadow rays per
/// Whitted hit: a scene may ask for slow renders; a fuzzer asks for many.
const MAX_DEPTH: u32 = 16;
/// See [`MAX_DEPTH`].
const MAX_LIGHT_SAMPLES: u32 = 4;
/// The statements a fuzzed scene's loops may run (the rule is the checker's;
/// only the budget is smaller, so that a mutated `0..4` into `0..1000000`
/// stays fast).
const LOOP_STATEMENTS: u64 = 20_000;
/// The steps of work a fuzzed scene's expressions may take (the rule is
/// the checker's; about 20 a loop statement, as the full budgets' ratio is
/// 10, so that the loops' budget still comes first in ordinary scenes).
const WORK: u64 = 400_000;

/// The whole pipeline on a scene given as bytes: parse, check, both
/// diagnostic formats, lowering and a tiny render, whose every pixel must be
/// finite. Relative paths (includes, meshes) start from the working folder.
/// Returns whether the input got past the parser (a fuzzer's hint that it
/// is worth mutating further).
pub fn scene(bytes: &[u8]) -> bool {
    let compiled = compile_bytes(
        Path::new("fuzz.pts"),
        bytes.to_vec(),
        Options {
            adjust: &|s| {
                s.width = s.width.min(MAX_SIDE);
                s.height = s.height.min(MAX_SIDE);
                s.samples = s.samples.min(MAX_SAMPLES);
                s.max_depth = s.max_depth.min(MAX_DEPTH);
                s.light_samples = s.light_samples.min(MAX_LIGHT_SAMPLES);
            },
            loop_statements: LOOP_STATEMENTS,
            work: WORK,
            // The fuzzer writes no image: a scene's `output` is not probed.
            output_elsewhere: true,
            ..Options::default()
        },
    );
    diagnostics_stay_in_their_files(&compiled.diagnostics, &compiled.sources);
    let _ = compiled.diagnostics.render_human(&compiled.sources, false);
    let _ = compiled.diagnostics.render_json(&compiled.sources);
    let parsed = !compiled
        .diagnostics
        .items
        .iter()
        .any(|d| d.code.starts_with("pts::syntax"));
    let Some(ir) = compiled.ir else {
        return parsed;
    };
    let integrator = crate::integrator::make(ir.settings.integrator, &ir);
    let cancel = AtomicBool::new(false);
    let film =
        crate::render::render(&ir, integrator.as_ref(), &cancel, &|_| {}, &mut |_, _| {}).film;
    if let Some(p) = film.pixels().iter().find(|p| !p.is_finite()) {
        panic!("a pixel is not finite: {p}");
    }
    true
}

/// A PLY file given as bytes: parsed, and when it parses, a mesh whose
/// every index names a vertex and every position is finite. Returns
/// whether it parsed.
pub fn ply(bytes: &[u8]) -> bool {
    mesh_invariants(mesh::parse(Path::new("fuzz.ply"), bytes))
}

/// An OBJ file given as bytes, as [`ply`]; every material library it names
/// reads as the same bytes (so that its `usemtl` lines find materials), and
/// each triangle's material is one of them or none.
pub fn obj(bytes: &[u8]) -> bool {
    let parsed = mesh::parse_with(Path::new("fuzz.obj"), bytes, &mut |_, _| Ok(bytes.to_vec()));
    if let Ok(m) = &parsed {
        assert!(m.face_material.is_empty() || m.face_material.len() == m.triangles.len());
        let n = m.materials.len() as u32;
        assert!(m.face_material.iter().all(|&i| i < n || i == u32::MAX));
    }
    mesh_invariants(parsed)
}

/// A glTF file given as bytes (a GLB when it starts with `glTF`, else
/// JSON); an external buffer it names reads as the same bytes. When it
/// parses: a mesh as [`ply`]'s, whose parts' ranges lie in its lists and
/// do not overlap, each placement naming a mesh that has parts through a
/// finite transform, and materials whose numbers lie in their ranges.
/// Returns whether it parsed.
pub fn gltf(bytes: &[u8]) -> bool {
    let name = match bytes.starts_with(b"glTF") {
        true => "fuzz.glb",
        false => "fuzz.gltf",
    };
    let parsed = mesh::parse_with(Path::new(name), bytes, &mut |_, _| Ok(bytes.to_vec()));
    if let Ok(m) = &parsed {
        let scene = m.scene.as_ref().expect("a glTF file reads as a scene");
        let (mut vertices, mut triangles) = (0, 0);
        for (k, part) in scene.parts.iter().enumerate() {
            assert_eq!(part.vertices.start, vertices, "parts in order");
            assert_eq!(part.triangles.start, triangles, "parts in order");
            (vertices, triangles) = (part.vertices.end, part.triangles.end);
            let view = m.view(Some(k as u32));
            let n = view.positions.len() as u32;
            assert!(view.triangles.iter().flatten().all(|&i| i < n));
            let mine = &m.triangles[part.triangles.start as usize..part.triangles.end as usize];
            assert!(mine.iter().flatten().all(|i| part.vertices.contains(i)));
            assert!(part
                .material
                .is_none_or(|k| (k as usize) < scene.materials.len()));
        }
        assert_eq!(vertices as usize, m.positions.len());
        let (placed, _) = scene.placements(None).unwrap_or_default();
        for placed in &placed {
            assert!(placed.transform.is_finite());
            assert!(scene.parts.iter().any(|p| p.mesh == placed.mesh));
        }
        for material in &scene.materials {
            let unit = |x: f64| (0.0..=1.0).contains(&x);
            let colour = |c: [f64; 3]| c.iter().all(|x| x.is_finite() && *x >= 0.0);
            assert!(colour(material.diffuse) && colour(material.emission));
            assert!(unit(material.gloss) && unit(material.transmission));
            assert!((1.0..=10.0).contains(&material.ior));
            assert!(material
                .textures
                .iter()
                .all(|(_, t)| t.transform.is_finite()));
        }
    }
    mesh_invariants(parsed)
}

/// A material library (`.mtl`) given as bytes: when it parses, every
/// material maps to a principled material whose numbers lie in their
/// ranges and whose textures are images read at (u, v). Returns whether it
/// parsed.
pub fn mtl(bytes: &[u8]) -> bool {
    use crate::check::scene::{MaterialKind, TextureKind, TextureSpace};
    let (text, _) = crate::lower::mtl::readable(bytes);
    let Ok((materials, _)) = tobj::load_mtl_buf(&mut std::io::Cursor::new(text)) else {
        return false;
    };
    for m in &materials {
        let mapped = crate::lower::mtl::material(m, Path::new("models/m.mtl"), Default::default());
        let out = &mapped.material;
        let unit = |x: f64| (0.0..=1.0).contains(&x);
        let colour = |c: [f64; 3]| c.iter().all(|x| x.is_finite() && *x >= 0.0);
        assert!(colour(out.diffuse) && colour(out.emission), "{out:?}");
        assert!(
            unit(out.gloss) && out.ior >= 1.0 && out.ior <= 10.0,
            "{out:?}"
        );
        assert!(out.bump_height.is_finite(), "{out:?}");
        let MaterialKind::Principled(p) = out.kind else {
            panic!("not principled: {out:?}");
        };
        let shares = [
            p.metallic,
            p.specular_tint,
            p.anisotropic,
            p.sheen,
            p.sheen_tint,
        ];
        assert!(shares
            .into_iter()
            .chain([p.clearcoat, p.clearcoat_roughness])
            .all(unit));
        assert!(p.specular.is_none_or(unit), "{p:?}");
        for (_, t) in &out.textures {
            assert!(matches!(t.kind, TextureKind::Image { .. }) && t.space == TextureSpace::Uv);
        }
    }
    true
}

/// A render state given as bytes (what `--resume` and `ptsc merge` read):
/// when it reads, a film of a size ptsc renders whose every sum is finite,
/// whose counts stay within its pass's share, and whose pixels are finite.
/// Returns whether it read.
pub fn state(bytes: &[u8]) -> bool {
    let Ok((film, info)) = crate::render::state::read_state_bytes(bytes) else {
        return false;
    };
    let share = info.pass.range(info.samples);
    assert_eq!(film.first, share.start);
    assert!(film.width > 0 && film.height > 0);
    assert_eq!(film.sum.len(), (film.width * film.height) as usize);
    assert!(film.count.iter().all(|&n| n <= share.end - share.start));
    assert!(film.sum.iter().all(|s| s.is_finite()));
    assert!(film.pixels().iter().all(|p| p.is_finite()));
    assert_eq!(film.halves.is_some(), info.keeps_halves());
    assert_eq!(film.light.is_some(), info.keeps_light());
    if let Some(light) = &film.light {
        assert!(light
            .sum
            .iter()
            .all(|s| s.is_finite() && s.min_element() >= 0.0));
        assert_eq!(light.paths, film.total_samples());
    }
    let mut film = film;
    if let Some(halves) = &film.halves {
        assert!(halves.odd.iter().all(|o| o.is_finite()));
        // An adaptive decision on it, as a resumed render takes.
        let most = film.count.iter().copied().max().unwrap_or(0);
        crate::render::adaptive::decide(&mut film, most, 0.01);
        assert!(film
            .stopped_share()
            .is_some_and(|s| (0.0..=1.0).contains(&s)));
    }
    true
}

/// The limits a fuzzed image is read under: small, so that a mutated
/// header claiming a large image is refused from its header, and an image
/// within them decodes in milliseconds.
pub const IMAGE_LIMITS: Limits = Limits {
    side: 4096,
    texels: 1 << 20,
    bytes: 12 << 20,
};

/// An image file given as bytes, decoded as PNG, JPEG, Radiance HDR and
/// OpenEXR in turn (the texture reader, header first, under
/// [`IMAGE_LIMITS`]). Header first: refused admission, no format decodes,
/// and it says so within a second (nothing but headers was read). When one
/// decodes: the size its header claimed and was admitted, within the
/// limits; as many texels as its size says, every one finite and
/// non-negative through both curves, and a lookup anywhere finite.
/// Returns whether any decoded.
pub fn image(bytes: &[u8]) -> bool {
    use crate::texture::image::{Image, Wrap};
    use crate::texture::texels::Curve;
    let mut any = false;
    for format in Format::ALL {
        let t0 = std::time::Instant::now();
        let refused = decode(bytes, format, &IMAGE_LIMITS, |_| Err("refused".into()));
        assert!(
            refused.is_err(),
            "{format:?} decoded an image it did not admit"
        );
        let took = t0.elapsed().as_secs_f64();
        assert!(took < 1.0, "{format:?} took {took:.2} s to refuse an image");
        let mut admitted = None;
        let decoded = decode(bytes, format, &IMAGE_LIMITS, |h| {
            admitted = Some(*h);
            Ok(())
        });
        let Ok(texels) = decoded else {
            continue;
        };
        any = true;
        let claim = admitted.expect("a decoded image was admitted");
        assert!(claim.bytes() <= IMAGE_LIMITS.bytes && claim.texels() <= IMAGE_LIMITS.texels);
        assert!(
            texels.bytes() <= claim.bytes(),
            "{format:?}: more than it claimed"
        );
        assert_eq!(texels.layout(), claim.layout);
        let texels = Arc::new(texels);
        for curve in [Curve::Linear, Curve::Srgb] {
            let im = Image::new(texels.clone(), curve);
            assert!(im.width > 0 && im.height > 0);
            assert!((0..im.width * im.height)
                .map(|i| im.texel(i))
                .all(|t| t.is_finite() && t.min_element() >= 0.0));
            for wrap in [Wrap::Repeat, Wrap::Clamp, Wrap::Mirror] {
                assert!(im.lookup(glam::Vec2::new(-3.7, 1.2), wrap).is_finite());
            }
        }
    }
    any | alpha_plane(bytes) | exr_channels(bytes)
}

/// The alpha plane of the same bytes (`image { channel a }`): refused
/// when not admitted, within what it claims, values in [0, 1].
fn alpha_plane(bytes: &[u8]) -> bool {
    use crate::lower::decode::decode_alpha;
    use crate::texture::texels::Curve;
    let mut any = false;
    for format in Format::ALL {
        let refused = decode_alpha(bytes, format, &IMAGE_LIMITS, |_| Err("refused".into()));
        assert!(
            refused.is_err(),
            "{format:?}: an alpha plane it did not admit"
        );
        let mut admitted = None;
        let Ok(texels) = decode_alpha(bytes, format, &IMAGE_LIMITS, |h| {
            admitted = Some(*h);
            Ok(())
        }) else {
            continue;
        };
        any = true;
        let claim = admitted.expect("a decoded alpha plane was admitted");
        assert!(texels.bytes() <= claim.bytes() && claim.bytes() <= IMAGE_LIMITS.bytes);
        assert!((0..texels.width() * texels.height())
            .map(|i| texels.get(i, Curve::Linear).x)
            .all(|a| (0.0..=1.0).contains(&a)));
    }
    any
}

/// The named-channel reading of `ptsc denoise` on the same bytes: within
/// the limits, one finite sample per pixel in every channel found.
fn exr_channels(bytes: &[u8]) -> bool {
    use crate::lower::decode::decode_exr_channels;
    let names = crate::render::denoise::CHANNELS;
    let Ok((w, h, planes)) = decode_exr_channels(bytes, &IMAGE_LIMITS, &names) else {
        return false;
    };
    assert!(w > 0 && h > 0 && (w as u64 * h as u64) <= IMAGE_LIMITS.texels);
    for plane in planes.iter().flatten() {
        assert_eq!(plane.len(), (w * h) as usize, "a channel of another size");
        assert!(plane.iter().all(|s| s.is_finite()));
    }
    true
}

fn mesh_invariants(parsed: Result<mesh::MeshData, String>) -> bool {
    let Ok(m) = parsed else { return false };
    let n = m.positions.len();
    assert!(!m.triangles.is_empty(), "a mesh without triangles parsed");
    assert!(m.triangles.iter().flatten().all(|&i| (i as usize) < n));
    assert!(m.positions.iter().all(|p| p.is_finite()));
    assert!(m.normals.is_empty() || m.normals.len() == n);
    assert!(m.uvs.is_empty() || m.uvs.len() == n);
    assert!(m.uvs.iter().all(|uv| uv.is_finite()));
    true
}

fn diagnostics_stay_in_their_files(
    diags: &crate::diag::Diagnostics,
    sources: &crate::source::SourceMap,
) {
    for d in &diags.items {
        for span in d.span.iter().chain(d.secondary.iter().map(|(s, _)| s)) {
            let len = sources.get(span.file).text.len() as u32;
            assert!(
                span.start <= span.end && span.end <= len,
                "{}: span {span:?} outside its file of {len} bytes",
                d.code
            );
        }
    }
}
