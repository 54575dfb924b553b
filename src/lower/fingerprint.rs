//! A scene's fingerprint: a 64-bit hash of everything that shapes its image
//! except the render settings (which a render state lists one by one, so
//! that a refusal can name the setting). The checked scene is a function of
//! the text of its files, the frame being compiled and its data files, so
//! the fingerprint hashes those: every scene file's text with comments and
//! runs of white space read as one space and its `render { … }` blocks left
//! out (editing a comment, the layout or the samples keeps the
//! fingerprint), the frame's `frame` and `clock`, and the bytes of every
//! data file the scene names (meshes, image textures, environment maps),
//! read as their loaders read them: regular files within their format's
//! limit; a device, a FIFO or a file over the limit is never read (it
//! could be endless or wait forever) and hashes as unreadable, and
//! lowering refuses it.
//!
//! Hashing the checked scene instead would also see through `2 * 3` for
//! `6`, but formatting its numbers took 50 ms for 10,000 spheres, 4 % of
//! rendering them; the text takes a few milliseconds.
//!
//! The hash is FNV-1a (64-bit), over bytes for text and over 8-byte words
//! for data files: stable across machines and versions of Rust, which a
//! farm's nodes and a state file saved months ago need.

use crate::check::{self, Animation};
use crate::source::{Files, ReadError, SourceMap, MAX_MESH_BYTES};
use std::io::Read;

/// FNV-1a's offset basis and prime (Fowler, Noll, Vo; IETF draft
/// draft-eastlake-fnv, 64-bit parameters).
const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
/// See [`FNV_OFFSET`].
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// The fingerprint of a scene: its files' significant text, the frame, and
/// its data files' bytes (see the module's documentation).
pub fn fingerprint(
    files: &dyn Files,
    (sources, asked): (&SourceMap, &[std::path::PathBuf]),
    scene: &check::Scene,
    animation: Animation,
) -> u64 {
    let mut hash = FNV_OFFSET;
    for file in sources.files() {
        hash = fnv(hash, &significant_text(&file.text));
        hash = fnv(hash, &[0]);
    }
    hash = fnv(hash, &animation.frame.to_le_bytes());
    hash = fnv(hash, &animation.clock.to_bits().to_le_bytes());
    let data = super::data_files(scene);
    for (path, limit) in &data {
        hash = hash_file(hash, files.open(path, *limit), *limit);
    }
    // The files the data files name, that lowering read: an OBJ's material
    // libraries, a glTF's buffers. (Hashed after the rest: a scene without
    // any keeps the fingerprint it had before they were.)
    let mut named: Vec<&std::path::PathBuf> = (asked.iter())
        .filter(|p| sources.files().iter().all(|f| &f.path != *p))
        .filter(|p| data.iter().all(|(d, _)| d != *p) && files.exists(p).is_ok())
        .collect();
    named.sort();
    named.dedup();
    for path in named {
        hash = hash_file(hash, files.open(path, MAX_MESH_BYTES), MAX_MESH_BYTES);
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

/// FNV-1a's step over 8-byte little-endian words, the tail bytewise: a
/// data file of hundreds of MB hashes 8 times faster.
fn fnv_words(mut hash: u64, bytes: &[u8]) -> u64 {
    let mut words = bytes.chunks_exact(8);
    for w in &mut words {
        let word = u64::from_le_bytes(w.try_into().expect("8 bytes"));
        hash = (hash ^ word).wrapping_mul(FNV_PRIME);
    }
    fnv(hash, words.remainder())
}

/// Hashes a file's bytes in pieces (a mesh may be hundreds of MB), as its
/// loader reads it: a regular file of at most `limit` bytes, opened without
/// waiting and read no further than the limit however the file grows. Any
/// other file (a device, a FIFO, one too large) hashes as unreadable
/// without being read: lowering reports it.
fn hash_file(hash: u64, file: Result<Box<dyn Read + '_>, ReadError>, limit: u64) -> u64 {
    let unreadable = |hash| fnv(hash, b"unreadable");
    let Ok(file) = file else {
        return unreadable(hash);
    };
    let mut file = file.take(limit + 1);
    // Pieces of a multiple of 8 bytes: the words fall the same way however
    // the reads split the file.
    let (mut hash, mut buf, mut filled, mut total) = (hash, vec![0u8; 1 << 16], 0, 0u64);
    loop {
        match file.read(&mut buf[filled..]) {
            Ok(0) if total > limit => return unreadable(hash),
            Ok(0) => return fnv_words(hash, &buf[..filled]),
            Ok(n) => {
                (filled, total) = (filled + n, total + n as u64);
                if filled == buf.len() {
                    hash = fnv_words(hash, &buf);
                    filled = 0;
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(_) => return unreadable(hash),
        }
    }
}

/// A scene file's text as far as its checked scene goes: comments and runs
/// of white space become one space, strings are kept as written, and each
/// `render { … }` block is left out.
fn significant_text(text: &str) -> Vec<u8> {
    let b = text.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut space = false;
    // Inside a `render` block: its brace depth (0 once the block ends).
    let (mut in_render, mut depth) = (false, 0u32);
    let word_byte = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let start = i;
        if c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
            space = true;
            continue;
        }
        if c == b'/' && b.get(i + 1) == Some(&b'*') {
            i += 2;
            while i < b.len() && !(b[i] == b'*' && b.get(i + 1) == Some(&b'/')) {
                i += 1;
            }
            i = (i + 2).min(b.len());
            space = true;
            continue;
        }
        if c.is_ascii_whitespace() {
            i += 1;
            space = true;
            continue;
        }
        if c == b'"' {
            // A string, escapes and all, to its closing quote or line end.
            i += 1;
            while i < b.len() && b[i] != b'"' && b[i] != b'\n' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i = (i + 1).min(b.len());
        } else if word_byte(c) {
            while i < b.len() && word_byte(b[i]) {
                i += 1;
            }
            if &b[start..i] == b"render" && !in_render {
                (in_render, depth) = (true, 0);
            }
        } else {
            i += 1;
        }
        if in_render {
            match c {
                b'{' => depth += 1,
                b'}' => {
                    depth = depth.saturating_sub(1);
                    in_render = depth > 0;
                }
                _ => {}
            }
            space = false;
            continue;
        }
        if space && !out.is_empty() {
            out.push(b' ');
        }
        space = false;
        out.extend_from_slice(&b[start..i.min(b.len())]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::Disk;

    #[test]
    fn fnv_matches_its_published_values() {
        // draft-eastlake-fnv test vectors for FNV-1a 64.
        assert_eq!(fnv(FNV_OFFSET, b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv(FNV_OFFSET, b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv(FNV_OFFSET, b"foobar"), 0x8594_4171_f739_67e8);
        // Words: the tail bytewise.
        assert_eq!(fnv_words(FNV_OFFSET, b"abc"), fnv(FNV_OFFSET, b"abc"));
        assert_ne!(
            fnv_words(FNV_OFFSET, b"abcdefgh"),
            fnv_words(FNV_OFFSET, b"abcdefgi")
        );
    }

    #[test]
    fn data_files_hash_as_their_loaders_read_them() {
        let dir = tempfile::tempdir().unwrap();
        let unreadable = fnv(FNV_OFFSET, b"unreadable");
        // A regular file: its bytes, in 8-byte words, across pieces.
        let path = dir.path().join("m.ply");
        let bytes: Vec<u8> = (0..200_003u32).map(|i| (i * 7) as u8).collect();
        std::fs::write(&path, &bytes).unwrap();
        let h = hash_file(FNV_OFFSET, Disk.open(&path, 1 << 20), 1 << 20);
        assert_eq!(h, fnv_words(FNV_OFFSET, &bytes));
        // Over the limit (a sparse terabyte, or a small limit): not read.
        assert_eq!(
            hash_file(FNV_OFFSET, Disk.open(&path, 1000), 1000),
            unreadable
        );
        let sparse = dir.path().join("big.png");
        let f = std::fs::File::create(&sparse).unwrap();
        if f.set_len(1 << 40).is_ok() {
            let t = std::time::Instant::now();
            assert_eq!(
                hash_file(FNV_OFFSET, Disk.open(&sparse, 1 << 30), 1 << 30),
                unreadable
            );
            assert!(t.elapsed().as_secs_f64() < 1.0);
        }
        // A device, a folder: never opened for reading.
        if std::path::Path::new("/dev/zero").exists() {
            assert_eq!(
                hash_file(
                    FNV_OFFSET,
                    Disk.open(std::path::Path::new("/dev/zero"), 1 << 30),
                    1 << 30
                ),
                unreadable
            );
        }
        assert_eq!(
            hash_file(FNV_OFFSET, Disk.open(dir.path(), 1 << 30), 1 << 30),
            unreadable
        );
        // A FIFO without a writer: refused at once, not waited on.
        let fifo = dir.path().join("f.obj");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            assert_eq!(
                hash_file(FNV_OFFSET, Disk.open(&fifo, 1 << 30), 1 << 30),
                unreadable
            );
        }
    }

    #[test]
    fn comments_layout_and_render_blocks_are_not_significant() {
        let s = |t: &str| String::from_utf8(significant_text(t)).unwrap();
        assert_eq!(
            s("sphere {\n  radius 1 // big\n}\n/* a\n b */ box { }"),
            "sphere { radius 1 } box { }"
        );
        assert_eq!(
            s("let a = 1;\nrender { samples 64 output \"x}.png\" }\nsphere { }"),
            "let a = 1; sphere { }"
        );
        // Strings keep their spaces and what looks like a comment.
        assert_eq!(s("output \"a  // b\""), "output \"a  // b\"");
        // A name that only contains `render` is text.
        assert_eq!(s("let renderer = 1;"), "let renderer = 1;");
        // Separated tokens stay separated.
        assert_ne!(s("radius 1 2"), s("radius 12"));
    }

    #[test]
    fn layout_comments_and_settings_keep_it_values_change_it() {
        let fp = |text: &str, frame: u32| {
            let text = format!("camera {{ position <0, 1, 5> look_at <0, 0, 0> }}\n{text}");
            let c = check::check_str(std::path::Path::new("t.pts"), &text);
            let animation = Animation {
                frame,
                ..Animation::default()
            };
            fingerprint(
                &Disk,
                (&c.sources, &[]),
                &c.scene.expect("checks"),
                animation,
            )
        };
        let base = fp(
            "render { samples 4 }\nsphere { center <0,0,0> radius 1 }",
            0,
        );
        let same = fp(
            "// a comment\nrender { samples 64 seed 3 }\n\nsphere { center <0,0,0>   radius 1 }",
            0,
        );
        assert_eq!(base, same);
        let other = fp(
            "render { samples 4 }\nsphere { center <0,0,0> radius 1.001 }",
            0,
        );
        assert_ne!(base, other);
        assert_ne!(
            base,
            fp(
                "render { samples 4 }\nsphere { center <0,0,0> radius 1 }",
                1
            )
        );
    }
}
