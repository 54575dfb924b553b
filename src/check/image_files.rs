//! The image files a scene names and the errors for those that cannot be
//! read: lowering reads them (`lower/material.rs`, `lower/environment.rs`),
//! for a scene with errors too (`lower::validate_files`, through
//! `check::unbuilt`); the words are here, shared by both.

use super::scene::{Environment, Material, TextureKind};
use crate::diag::{codes, Diagnostic};
use crate::span::Span;
use std::path::Path;

/// The help for an image texture that cannot be read.
pub const TEXTURE_HELP: &str =
    "textures read .png, .jpg, .hdr and .exr files, relative to the scene";

/// The help for an environment map that cannot be read.
pub const ENVIRONMENT_HELP: &str =
    "an environment is an .hdr or .exr file (or .png, .jpg), relative to the scene";

/// The error for the image `named` (written at `span`) that cannot be
/// read or decoded (`why`): the checker's and lowering's, word for word.
/// It names the file as the scene writes it, not as resolved: the resolved
/// path depends on the folder the scene was opened from (`ptsc check s.pts`
/// or an editor's absolute path), and the verdict must not.
pub fn unreadable(named: &str, span: Span, why: String, help: &str) -> Diagnostic {
    Diagnostic::error(
        codes::IMAGE_FILE,
        format!("cannot load image `{named}`"),
        span,
    )
    .with_label(why)
    .with_help(help)
}

/// The error for an image that a model file names (`origin`: an MTL
/// library's map, a glTF's image) and that cannot be read: the message
/// says which entry of which file asked for it, and the help what its path
/// is relative to (the model file, not the scene). Its code and span
/// (where the scene places the model) are the other images'.
pub fn unreadable_in_model(origin: &crate::diag::NamedIn, span: Span, why: String) -> Diagnostic {
    Diagnostic::error(
        codes::IMAGE_FILE,
        format!("cannot load image {}", origin.named),
        span,
    )
    .with_label(why)
    .with_help(origin.help.clone())
}

/// An image file a scene names: its resolved path, the name as written,
/// where it is written and the help for it.
pub type NamedImage<'s> = (&'s Path, &'s str, Span, &'static str);

/// The image files a scene's materials and environment name, each once, in
/// source order.
pub fn named_images<'s>(
    materials: &'s [Material],
    environment: Option<&'s Environment>,
) -> Vec<NamedImage<'s>> {
    let textures = (materials.iter()).flat_map(|m| m.textures.iter().map(|(_, t)| t));
    let mut named: Vec<NamedImage> = textures
        .filter_map(|t| match &t.kind {
            TextureKind::Image {
                path,
                named,
                path_span,
                resolved: true,
                ..
            } => Some((path.as_path(), named.as_str(), *path_span, TEXTURE_HELP)),
            _ => None,
        })
        .collect();
    if let Some(e) = environment {
        named.push((e.path.as_path(), &e.name, e.path_span, ENVIRONMENT_HELP));
    }
    named.sort_by_key(|(_, _, span, _)| (span.file.0, span.start));
    named.dedup_by_key(|(_, _, span, _)| *span);
    named
}
