//! Files that are not scenes, given where a scene goes (`ptsc render
//! photo.png`, a tab completion's slip) or included: told apart by their
//! first bytes (or, for the text formats of models, by their extension) and
//! refused with one error, instead of a page of syntax errors quoting
//! binary bytes.

use crate::diag::{codes, Diagnostic};
use crate::span::Span;
use std::path::Path;

/// How many leading bytes are looked at for a NUL (text never holds one).
const SNIFFED: usize = 8192;

/// What the file `path` holding `bytes` is, when it is not a scene: its
/// kind in words and what to write instead.
pub fn not_a_scene(path: &Path, bytes: &[u8]) -> Option<(&'static str, &'static str)> {
    const IMAGE: &str = "a scene names an image in a texture (`diffuse image { file \"…\" }`) or as its `environment { file \"…\" }`";
    const MODEL: &str = "a scene loads a model with `mesh { file \"…\" }`";
    let magic: [(&[u8], &str, &str); 11] = [
        (b"\x89PNG\r\n\x1a\n", "a PNG image", IMAGE),
        (b"\xff\xd8\xff", "a JPEG image", IMAGE),
        (b"#?RADIANCE", "a Radiance HDR image", IMAGE),
        (b"#?RGBE", "a Radiance HDR image", IMAGE),
        (b"\x76\x2f\x31\x01", "an OpenEXR image", IMAGE),
        (b"GIF8", "a GIF image", IMAGE),
        (b"glTF", "a binary glTF model", MODEL),
        (b"ply\n", "a PLY model", MODEL),
        (b"ply\r\n", "a PLY model", MODEL),
        (b"\x7fELF", "a program", "give a `.pts` scene file"),
        (b"PK\x03\x04", "a ZIP archive", "give a `.pts` scene file"),
    ];
    if let Some((_, what, help)) = magic.iter().find(|(m, ..)| bytes.starts_with(m)) {
        return Some((what, help));
    }
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("obj") => return Some(("an OBJ model", MODEL)),
        Some("mtl") => return Some(("an OBJ material library", "an OBJ model names its materials library itself: load the model with `mesh { file \"…\" }`")),
        Some("gltf") => return Some(("a glTF model", MODEL)),
        _ => {}
    }
    let head = &bytes[..bytes.len().min(SNIFFED)];
    head.contains(&0)
        .then_some(("a binary file", "give a `.pts` scene file"))
}

/// The error for the file at `path`, which is `what` (written at `span`:
/// the root file's start, or the `include` naming it).
pub fn not_a_scene_error(path: &Path, (what, help): (&str, &str), span: Span) -> Diagnostic {
    Diagnostic::error(
        codes::NOT_A_SCENE,
        format!("`{}` is {what}, not a scene", path.display()),
        span,
    )
    .with_label("not read as a scene")
    .with_help(help)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn images_models_and_binaries_are_told_apart_from_scenes() {
        let kind = |name: &str, bytes: &[u8]| not_a_scene(Path::new(name), bytes).map(|k| k.0);
        assert_eq!(kind("a.png", b"\x89PNG\r\n\x1a\n\0\0"), Some("a PNG image"));
        // The content decides, whatever the name says.
        assert_eq!(kind("a.pts", b"\xff\xd8\xff\xe0"), Some("a JPEG image"));
        assert_eq!(
            kind("m.ply", b"ply\nformat ascii 1.0\n"),
            Some("a PLY model")
        );
        assert_eq!(kind("m.OBJ", b"v 0 0 0\n"), Some("an OBJ model"));
        assert_eq!(kind("x.bin", b"abc\0def"), Some("a binary file"));
        // Scenes, also in Latin-1 or named like POV-Ray's, are read.
        assert_eq!(kind("s.pts", b"sphere { center <0, 0, 0> radius 1 }"), None);
        assert_eq!(kind("s.pov", b"// caf\xe9\nsphere { <0, 0, 0>, 1 }"), None);
        assert_eq!(kind("empty.pts", b""), None);
    }
}
