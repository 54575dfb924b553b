//! Where in an OBJ file the face is that `tobj` refused: its errors name
//! no line ("face vertex index out of bounds"), and a file of a million
//! faces needs one. Read again only after a refusal, by `tobj`'s rules:
//! indices from 1, negative ones counted back from the elements read so
//! far, positive ones up to the elements read when the object ends (the
//! next `o` or `g`, or the end of the file); texture coordinates and
//! normals are looked up only in a file that has some.

/// The line of the first face that breaks `tobj`'s `error`, written for the
/// message (`line 5 (f 1 2 9): vertex 9 of 3`); `None` for other errors.
pub(super) fn locate(bytes: &[u8], error: &tobj::LoadError) -> Option<String> {
    let kind = match error {
        tobj::LoadError::FaceVertexOutOfBounds => Some(0),
        tobj::LoadError::FaceTexCoordOutOfBounds => Some(1),
        tobj::LoadError::FaceNormalOutOfBounds => Some(2),
        tobj::LoadError::FaceParseError => None,
        _ => return None,
    };
    // Line by line without a copy of the file or a table per line: at
    // each object's start a second look ahead finds what it will have read
    // at its end (each line is read twice in all).
    let lines = bytes
        .split(|&b| b == b'\n')
        .map(|l| std::str::from_utf8(l).unwrap_or(""));
    let total = counts_until(lines.clone(), [0; 3], false);
    let mut so_far = [0usize; 3];
    let mut at_end = counts_until(lines.clone(), so_far, true);
    let mut rest = lines.clone();
    let mut number = 0;
    while let Some(line) = rest.next() {
        number += 1;
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => so_far[0] += 1,
            Some("vt") => so_far[1] += 1,
            Some("vn") => so_far[2] += 1,
            Some("o" | "g") => at_end = counts_until(rest.clone(), so_far, true),
            Some("f" | "l") => {
                let why = words.find_map(|w| broken(w, kind, (so_far, at_end, total)));
                if let Some(why) = why {
                    let shown: String = line.trim().chars().take(60).collect();
                    return Some(format!("line {number} (`{shown}`): {why}"));
                }
            }
            _ => {}
        }
    }
    None
}

/// The positions, texture coordinates and normals read after `lines`,
/// starting from `read`: to the next `o` or `g` where `object`, else to the
/// end of the file.
fn counts_until<'l>(
    lines: impl Iterator<Item = &'l str>,
    mut read: [usize; 3],
    object: bool,
) -> [usize; 3] {
    for line in lines {
        match line.split_whitespace().next() {
            Some("v") => read[0] += 1,
            Some("vt") => read[1] += 1,
            Some("vn") => read[2] += 1,
            Some("o" | "g") if object => break,
            _ => {}
        }
    }
    read
}

/// What is wrong with the face's vertex `word` (`9/2/1`): an index of
/// `kind` (0 positions, 1 texture coordinates, 2 normals) out of bounds,
/// or (no `kind`) a part that is not a number; `None` if nothing.
fn broken(
    word: &str,
    kind: Option<usize>,
    (so_far, at_end, total): ([usize; 3], [usize; 3], [usize; 3]),
) -> Option<String> {
    const WHAT: [&str; 3] = ["vertex", "texture coordinate", "normal"];
    let parts: Vec<&str> = word.split('/').collect();
    let Some(k) = kind else {
        let bad = parts.len() > 3
            || parts
                .iter()
                .any(|p| !p.is_empty() && p.parse::<isize>().is_err());
        return bad
            .then(|| format!("`{word}` is not a vertex's indices (v, v/vt, v//vn or v/vt/vn)"));
    };
    let part = parts.get(k).filter(|p| !p.is_empty())?;
    if k > 0 && total[k] == 0 {
        return None;
    }
    let index: isize = part.parse().ok()?;
    let ok = match index {
        0 => false,
        i if i < 0 => i.unsigned_abs() <= so_far[k],
        i => i.unsigned_abs() <= at_end[k],
    };
    let what = WHAT[k];
    (!ok).then(|| match index {
        0 => format!("{what} 0 (indices start at 1)"),
        i if i < 0 => format!("{what} {i}, {} back of {} read so far", -i, so_far[k]),
        i => format!("{what} {i} of {}", at_end[k]),
    })
}

#[cfg(test)]
mod tests {
    use super::locate;
    use tobj::LoadError::*;

    #[test]
    fn the_refused_face_is_found_by_its_line() {
        let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n";
        assert_eq!(
            locate(obj, &FaceVertexOutOfBounds).as_deref(),
            Some("line 5 (`f 1 2 9`): vertex 9 of 3")
        );
        let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n";
        let at = locate(obj, &FaceVertexOutOfBounds).unwrap();
        assert!(at.contains("vertex -4, 4 back of 3"), "{at}");
        let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n";
        let at = locate(obj, &FaceNormalOutOfBounds).unwrap();
        assert!(
            at.starts_with("line 5") && at.ends_with("normal 2 of 1"),
            "{at}"
        );
        let obj = b"v 0 0 0\nf 1 0 1\n";
        assert!(locate(obj, &FaceVertexOutOfBounds)
            .unwrap()
            .contains("vertex 0"));
        let obj = b"v 0 0 0\nf 1 x 1\n";
        assert!(locate(obj, &FaceParseError).unwrap().contains("`x`"));
        // A face may name a vertex written after it in its object.
        let obj = b"o a\nv 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\no b\nf 1 2 4\n";
        assert!(locate(obj, &FaceVertexOutOfBounds)
            .unwrap()
            .starts_with("line 7"));
    }

    #[test]
    fn the_located_errors_are_tobjs() {
        // Each case above is refused by tobj with the error located.
        let opts = crate::lower::obj::tobj_options();
        for (obj, expected) in [
            (
                &b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"[..],
                "face vertex index out of bounds",
            ),
            (
                &b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n"[..],
                "face vertex index out of bounds",
            ),
            (&b"v 0 0 0\nf 1 x 1\n"[..], "face parse error"),
        ] {
            let loaded = tobj::load_obj_buf(&mut std::io::Cursor::new(obj), &opts, |_| {
                Err(tobj::LoadError::OpenFileFailed)
            });
            let Err(e) = loaded else {
                panic!("not refused")
            };
            assert!(e.to_string().contains(expected), "{e}");
            assert!(locate(obj, &e).is_some(), "{e}");
        }
    }
}
