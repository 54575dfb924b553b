//! A glTF file's buffers: the GLB's binary chunk, `data:` URIs (base64)
//! and files beside the glTF, read through the caller's reader and
//! together at most [`MAX_MESH_BYTES`]; an image's URI is read the same way
//! (`gltf_material.rs`).

use super::mesh_data::{LibraryReader, MeshData};
use crate::source::MAX_MESH_BYTES;
use base64::Engine;
use std::borrow::Cow;
use std::path::{Path, PathBuf};

/// Every buffer's bytes: the GLB's binary chunk, a data URI's, or a file
/// beside the glTF's (read through `library`, listed in `out.libraries`);
/// together at most [`MAX_MESH_BYTES`].
pub(super) fn read_buffers<'a>(
    doc: &gltf::Document,
    blob: Option<&'a [u8]>,
    (folder, library): (&Path, &mut LibraryReader),
    out: &mut MeshData,
) -> Result<Vec<Cow<'a, [u8]>>, String> {
    let mut total = 0u64;
    let mut buffers = Vec::with_capacity(doc.buffers().len());
    for buffer in doc.buffers() {
        let left = MAX_MESH_BYTES.saturating_sub(total);
        let data: Cow<[u8]> = match buffer.source() {
            gltf::buffer::Source::Bin => Cow::Borrowed(blob.ok_or(format!(
                "buffer {} is the GLB's binary chunk, which the file does not have",
                buffer.index()
            ))?),
            gltf::buffer::Source::Uri(uri) => match data_uri(uri, left)? {
                Some(bytes) => Cow::Owned(bytes),
                None => {
                    let path = folder.join(relative_path(uri)?);
                    out.libraries.push(path.clone());
                    Cow::Owned(
                        library(&path, left)
                            .map_err(|e| format!("cannot read buffer `{}`: {e}", path.display()))?,
                    )
                }
            },
        };
        if data.len() < buffer.length() {
            return Err(format!(
                "buffer {} holds {} bytes but declares {}",
                buffer.index(),
                data.len(),
                buffer.length()
            ));
        }
        total += data.len() as u64;
        if total > MAX_MESH_BYTES {
            return Err(format!(
                "the buffers take more than {}",
                crate::source::human_bytes(MAX_MESH_BYTES)
            ));
        }
        buffers.push(data);
    }
    Ok(buffers)
}

/// The bytes of a `data:` URI (base64), at most `limit` of them; `None`
/// when `uri` is not one.
pub(super) fn data_uri(uri: &str, limit: u64) -> Result<Option<Vec<u8>>, String> {
    let Some(rest) = uri.strip_prefix("data:") else {
        return Ok(None);
    };
    let (header, payload) = rest.split_once(',').ok_or("a data URI without a comma")?;
    if !header.ends_with(";base64") {
        return Err("a data URI that is not base64".into());
    }
    // Decoded, four characters make three bytes: refused before decoding.
    if (payload.len() as u64 / 4) * 3 > limit {
        return Err(format!(
            "a data URI of {} characters, more than the {} a file may hold",
            payload.len(),
            crate::source::human_bytes(limit)
        ));
    }
    let bytes = (base64::engine::general_purpose::STANDARD)
        .decode(payload.trim_end())
        .map_err(|e| format!("a data URI that is not valid base64: {e}"))?;
    Ok(Some(bytes))
}

/// A URI naming a file beside the glTF as a relative path (percent-escapes
/// decoded); an absolute path or another scheme is refused.
pub(super) fn relative_path(uri: &str) -> Result<PathBuf, String> {
    if uri.contains("://") || uri.starts_with('/') || uri.starts_with('\\') {
        return Err(format!(
            "`{}` is not a relative path: ptsc reads the files beside the glTF only",
            uri.chars().take(80).collect::<String>()
        ));
    }
    let bytes = uri.as_bytes();
    let mut decoded = Vec::with_capacity(bytes.len());
    let mut k = 0;
    while k < bytes.len() {
        let hex = (bytes[k] == b'%')
            .then(|| bytes.get(k + 1..k + 3))
            .flatten()
            .and_then(|h| u8::from_str_radix(std::str::from_utf8(h).ok()?, 16).ok());
        match hex {
            Some(b) => {
                decoded.push(b);
                k += 3;
            }
            None => {
                decoded.push(bytes[k]);
                k += 1;
            }
        }
    }
    Ok(PathBuf::from(
        String::from_utf8_lossy(&decoded).into_owned(),
    ))
}
