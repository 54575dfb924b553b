//! A scene's image files (textures and the environment map): each read and
//! decoded once per compile however many textures read it and in whatever
//! encoding (`lower::decode`, header first), kept by `watch` while the file
//! is unchanged, and all of them together held within
//! [`MAX_TEXTURE_BYTES`].
//!
//! The limits, and why:
//! - a file is read up to [`MAX_IMAGE_BYTES`] (1 GiB);
//! - an image has at most [`MAX_IMAGE_SIDE`] texels a side and
//!   [`MAX_IMAGE_TEXELS`] in all (16,384², a 16k texture or a 32k × 8k
//!   panorama);
//! - its texels take 1 (8-bit grey) to 12 (float RGB) bytes each in their
//!   final layout (`texture::texels`), so the largest image takes 256 MiB
//!   to 3 GiB, and decoding it never more than 12 bytes a texel;
//! - a scene's images take at most [`MAX_TEXTURE_BYTES`] (4 GiB) together,
//!   each file counted once, an environment map with its sampling
//!   distribution (8 bytes a texel). The image that would cross the total
//!   is refused from its header, before it is decoded, with the total in
//!   the message. `watch`'s cache forgets the images the scene no longer
//!   reads before it decodes a new one, so that it never holds more either.

use super::decode::{self, Format, Header, Limits};
use crate::source::files::Stamp;
use crate::source::{human_bytes, Files};
use crate::texture::image::Image;
use crate::texture::texels::{Curve, Texels};
use std::collections::hash_map::DefaultHasher;
use std::collections::{HashMap, HashSet};
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The largest image file read, in bytes.
pub const MAX_IMAGE_BYTES: u64 = 1 << 30;
/// The longest side an image may have, in texels.
pub const MAX_IMAGE_SIDE: u32 = 32_768;
/// The most texels an image may have (16,384²).
pub const MAX_IMAGE_TEXELS: u64 = 1 << 28;
/// The most bytes a scene's images may take together: every texture's and
/// environment map's texels (each file once) and the environment map's
/// sampling distribution.
pub const MAX_TEXTURE_BYTES: u64 = 4 << 30;

/// How an image's values become linear ones.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Encoding {
    /// By the file: 8- and 16-bit values through the sRGB curve,
    /// floating-point ones (HDR, EXR) as they are (colours, by default).
    ByFile,
    /// Every value as it is (data maps by default; `color_space linear`).
    Linear,
    /// Every value through the sRGB curve (`color_space srgb`).
    Srgb,
}

impl Encoding {
    /// The curve that reads texels of `texels`' layout in this encoding.
    fn curve(self, texels: &Texels) -> Curve {
        match self {
            Encoding::ByFile if texels.layout().is_float() => Curve::Linear,
            Encoding::ByFile | Encoding::Srgb => Curve::Srgb,
            Encoding::Linear => Curve::Linear,
        }
    }
}

/// The images read so far, each file decoded once per compile; kept
/// between compiles (`watch`) while the file's length, modification time
/// and bytes are unchanged.
#[derive(Debug)]
pub struct Images {
    loaded: HashMap<PathBuf, CachedImage>,
    /// The files read since the last [`Images::keep_only_used`]: the
    /// scene's.
    used: HashSet<PathBuf>,
    /// Bytes the scene's images hold besides their texels (environment
    /// maps' distributions), since the last [`Images::keep_only_used`].
    extra: u64,
    /// The most bytes the scene's images may take together.
    limit: u64,
    /// Image files decoded so far (a cache hit does not count).
    pub decodes: usize,
}

impl Default for Images {
    fn default() -> Self {
        Images::with_limit(MAX_TEXTURE_BYTES)
    }
}

#[derive(Debug)]
struct CachedImage {
    stamp: Option<Stamp>,
    content: u64,
    texels: Arc<Texels>,
}

impl Images {
    /// No image yet; the scene's images may take `limit` bytes together.
    pub fn with_limit(limit: u64) -> Images {
        Images {
            loaded: HashMap::new(),
            used: HashSet::new(),
            extra: 0,
            limit,
            decodes: 0,
        }
    }

    /// The bytes the images read since the last
    /// [`Images::keep_only_used`] take together (each file once, with the
    /// environment map's distribution): what the limit bounds.
    pub fn scene_bytes(&self) -> u64 {
        let texels: u64 = (self.used.iter())
            .filter_map(|p| self.loaded.get(p))
            .map(|c| c.texels.bytes())
            .sum();
        texels + self.extra
    }

    /// The bytes of texels the cache holds (at most the limit).
    pub fn held_bytes(&self) -> u64 {
        self.loaded.values().map(|c| c.texels.bytes()).sum()
    }

    /// The image at `path` read with `encoding`, decoded on first use; the
    /// error is a sentence for a diagnostic. A file is known by its
    /// canonical path: named from two folders, or through a link, it is
    /// still read once.
    pub fn get(
        &mut self,
        files: &dyn Files,
        path: &Path,
        encoding: Encoding,
    ) -> Result<Image, String> {
        self.get_plane(files, path, encoding, false)
    }

    /// The alpha channel of the image at `path` as a grey image read
    /// linearly (an image without alpha: one opaque texel), decoded on
    /// first use and kept apart from the file's colours.
    pub fn get_alpha(&mut self, files: &dyn Files, path: &Path) -> Result<Image, String> {
        self.get_plane(files, path, Encoding::Linear, true)
    }

    /// [`Images::get`] of the file's colours or (`alpha`) of its alpha.
    fn get_plane(
        &mut self,
        files: &dyn Files,
        path: &Path,
        encoding: Encoding,
        alpha: bool,
    ) -> Result<Image, String> {
        let mut key = files.canonical(path);
        if alpha {
            let mut name = key.into_os_string();
            name.push("#alpha");
            key = PathBuf::from(name);
        }
        let now = files.stamp(path);
        if let Some(c) = self.loaded.get(&key) {
            if self.used.contains(&key) || (c.stamp == now && now.is_some()) {
                return self.share(&key, encoding);
            }
        }
        let bytes = files
            .read(path, MAX_IMAGE_BYTES)
            .map_err(|e| format!("cannot read the file: {e}"))?;
        let content = {
            let mut h = DefaultHasher::new();
            bytes.hash(&mut h);
            h.finish()
        };
        if let Some(c) = self.loaded.get_mut(&key) {
            if c.content == content {
                c.stamp = now;
                return self.share(&key, encoding);
            }
        }
        // A changed file: its old texels go before the new ones come.
        self.loaded.remove(&key);
        let texels = Arc::new(self.decode(path, &bytes, alpha)?);
        drop(bytes);
        self.decodes += 1;
        let cached = CachedImage {
            stamp: now,
            content,
            texels,
        };
        self.loaded.insert(key.clone(), cached);
        self.used.insert(key.clone());
        Ok(self.view(&key, encoding))
    }

    /// Decodes `bytes` of the file at `path`: admitted when the scene's
    /// images stay within the limit with it; the cache then forgets the
    /// images the scene has not read (yet) if it would hold more.
    fn decode(&mut self, path: &Path, bytes: &[u8], alpha: bool) -> Result<Texels, String> {
        let format = Format::sniff(path, bytes)?;
        let limits = Limits {
            side: MAX_IMAGE_SIDE,
            texels: MAX_IMAGE_TEXELS,
            bytes: self.limit,
        };
        let scene = self.scene_bytes();
        let (limit, used, loaded) = (self.limit, &self.used, &mut self.loaded);
        let admit = |header: &Header| {
            over_total(scene, header.bytes(), limit)
                .map(|total| format!("{} {total}", header.describe()))
                .map_or(Ok(()), Err)?;
            let held: u64 = loaded.values().map(|c| c.texels.bytes()).sum();
            if held + header.bytes() > limit {
                loaded.retain(|p, _| used.contains(p));
            }
            Ok(())
        };
        match alpha {
            false => decode::decode(bytes, format, &limits, admit),
            true => decode::decode_alpha(bytes, format, &limits, admit),
        }
    }

    /// A cached image (by its `key`) read again: the scene's once more, or
    /// for the first time this compile (then counted against the limit).
    fn share(&mut self, key: &Path, encoding: Encoding) -> Result<Image, String> {
        if !self.used.contains(key) {
            let bytes = self.loaded[key].texels.bytes();
            if let Some(total) = over_total(self.scene_bytes(), bytes, self.limit) {
                return Err(format!("its texels take {} {total}", human_bytes(bytes)));
            }
            self.used.insert(key.to_path_buf());
        }
        Ok(self.view(key, encoding))
    }

    fn view(&self, key: &Path, encoding: Encoding) -> Image {
        let texels = self.loaded[key].texels.clone();
        let curve = encoding.curve(&texels);
        Image::new(texels, curve)
    }

    /// Counts `bytes` more that an image of the scene holds besides its
    /// texels (an environment map's sampling distribution); an error
    /// (`what` says what they are) when the scene's images would take more
    /// than the limit.
    pub fn charge(&mut self, bytes: u64, what: &str) -> Result<(), String> {
        if let Some(total) = over_total(self.scene_bytes(), bytes, self.limit) {
            return Err(format!("{what} takes {} {total}", human_bytes(bytes)));
        }
        self.extra += bytes;
        Ok(())
    }

    /// Forgets the images not read since the last call: a texture removed
    /// from the scene releases its memory at the next compile.
    pub fn keep_only_used(&mut self) {
        let used = std::mem::take(&mut self.used);
        self.loaded.retain(|k, _| used.contains(k));
        self.extra = 0;
    }
}

/// When `more` bytes on top of the `scene`'s would cross `limit`: the end
/// of a message saying so.
fn over_total(scene: u64, more: u64, limit: u64) -> Option<String> {
    let total = scene + more;
    (total > limit).then(|| {
        format!(
            "and the scene's images would take {} together ({} before it), more than the {} ptsc gives them",
            human_bytes(total),
            human_bytes(scene),
            human_bytes(limit)
        )
    })
}

#[cfg(test)]
#[path = "image_tests.rs"]
mod tests;
