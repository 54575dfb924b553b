//! A scene's fingerprint: a 64-bit hash of everything in it that shapes its
//! image except the render settings (which a render state lists one by
//! one, so that a refusal can name the setting): the camera, background,
//! environment, sky, materials, objects, lights, groups and placements as
//! checked, and the bytes of every data file they name (meshes, image
//! textures, environment maps). Source locations are left out, so editing
//! a comment, the layout or the `render` block keeps the fingerprint; so
//! does writing the same value another way (`2 * 3` for `6`).
//!
//! The hash is FNV-1a (64-bit): stable across machines and versions of
//! Rust, which a farm's nodes and a state file saved months ago need.

use crate::check;
use std::io::Read;

/// FNV-1a's offset basis and prime (Fowler, Noll, Vo; IETF draft
/// draft-eastlake-fnv, 64-bit parameters).
const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
/// See [`FNV_OFFSET`].
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// The fingerprint of a checked scene (see the module's documentation).
pub fn fingerprint(scene: &check::Scene) -> u64 {
    use std::fmt::Write;
    // Destructured in full: a new part of a scene must be sorted in or out.
    let check::Scene {
        render: _,
        camera,
        background,
        environment,
        sky,
        materials,
        objects,
        lights,
        groups,
        instances,
    } = scene;
    let mut h = SpanlessHasher::default();
    let _ = write!(
        h,
        "{camera:?}{background:?}{environment:?}{sky:?}{materials:?}{objects:?}{lights:?}{groups:?}{instances:?}"
    );
    let mut hash = h.finish();
    for path in super::named_files(scene).0 {
        hash = fnv(hash, path.to_string_lossy().as_bytes());
        hash = hash_file(hash, &path);
    }
    hash
}

/// FNV-1a over `bytes`, continuing from `hash`.
fn fnv(mut hash: u64, bytes: &[u8]) -> u64 {
    for &b in bytes {
        hash = (hash ^ b as u64).wrapping_mul(FNV_PRIME);
    }
    hash
}

/// Hashes a file's bytes in pieces (a mesh may be hundreds of MB); an
/// unreadable file hashes as its error's kind (lowering reported it).
fn hash_file(hash: u64, path: &std::path::Path) -> u64 {
    let Ok(mut file) = std::fs::File::open(path) else {
        return fnv(hash, b"unreadable");
    };
    let (mut hash, mut buf) = (hash, vec![0u8; 1 << 16]);
    loop {
        match file.read(&mut buf) {
            Ok(0) => return hash,
            Ok(n) => hash = fnv(hash, &buf[..n]),
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(_) => return fnv(hash, b"unreadable"),
        }
    }
}

/// Hashes Debug text with every `Span { … }` left out.
struct SpanlessHasher {
    /// The hash so far.
    hash: u64,
    /// How many bytes of [`SPAN`] the text just matched.
    matched: usize,
    /// Brace depth inside a span being skipped (0: not in one).
    depth: u32,
}

impl Default for SpanlessHasher {
    fn default() -> Self {
        SpanlessHasher {
            hash: FNV_OFFSET,
            matched: 0,
            depth: 0,
        }
    }
}

/// How a source location starts in Debug text.
const SPAN: &[u8] = b"Span {";

impl SpanlessHasher {
    /// The hash, with a partly matched `Span {` counted as text.
    fn finish(self) -> u64 {
        fnv(self.hash, &SPAN[..self.matched])
    }
}

impl std::fmt::Write for SpanlessHasher {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        for &b in s.as_bytes() {
            if self.depth > 0 {
                match b {
                    b'{' => self.depth += 1,
                    b'}' => self.depth -= 1,
                    _ => {}
                }
                continue;
            }
            if b == SPAN[self.matched] {
                self.matched += 1;
                if self.matched == SPAN.len() {
                    (self.matched, self.depth) = (0, 1);
                }
                continue;
            }
            // Not a span after all: what matched was text.
            self.hash = fnv(self.hash, &SPAN[..self.matched]);
            self.matched = usize::from(b == SPAN[0]);
            if self.matched == 0 {
                self.hash = fnv(self.hash, &[b]);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fmt::Write;

    fn spanless(parts: &[&str]) -> u64 {
        let mut h = SpanlessHasher::default();
        for p in parts {
            h.write_str(p).unwrap();
        }
        h.finish()
    }

    #[test]
    fn spans_are_left_out_however_the_text_arrives() {
        let plain = fnv(FNV_OFFSET, b"Sphere { r: 1, at:  }");
        assert_eq!(
            spanless(&["Sphere { r: 1, at: Span { file: FileId(0), start: 3, end: 9 } }"]),
            plain
        );
        assert_eq!(
            spanless(&["Sphere { r: 1, at: Sp", "an", " { file: ", "FileId(1) } }"]),
            plain
        );
        // Text that only starts like a span is kept.
        assert_eq!(spanless(&["SpSpan"]), fnv(FNV_OFFSET, b"SpSpan"));
        assert_ne!(spanless(&["r: 1"]), spanless(&["r: 2"]));
    }

    #[test]
    fn fnv_matches_its_published_values() {
        // draft-eastlake-fnv test vectors for FNV-1a 64.
        assert_eq!(fnv(FNV_OFFSET, b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv(FNV_OFFSET, b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv(FNV_OFFSET, b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn layout_comments_and_settings_keep_it_values_change_it() {
        let fp = |text: &str| {
            let text = format!("camera {{ position <0, 1, 5> look_at <0, 0, 0> }}\n{text}");
            let c = check::check_str(std::path::Path::new("t.pts"), &text);
            fingerprint(&c.scene.expect("checks"))
        };
        let base = fp("render { samples 4 }\nsphere { center <0,0,0> radius 1 }");
        let same = fp("// a comment\nrender { samples 64 seed 3 }\n\nsphere { radius 1 center <0, 0, 2 - 2> }");
        assert_eq!(base, same);
        assert_ne!(
            base,
            fp("render { samples 4 }\nsphere { center <0,0,0> radius 1.001 }")
        );
    }
}
