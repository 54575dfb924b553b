//! An OBJ file's lines read by ptsc's rules where `tobj`'s say too little.
//! `tobj` reads `f 1 2` as a line, which its triangulation makes a
//! triangle of zero area (nothing on screen, and no word of why), reads an
//! `l` polyline of three vertices as a face, and names no line in its
//! errors ("position parse error"). So faces are counted before `tobj`
//! reads the file (one pass that looks at the first word of each line),
//! and a vertex line that `tobj` refused, or whose numbers are not finite,
//! is looked for only after a refusal, as `obj_faces` finds a face.

use std::borrow::Cow;

/// The file's text for `tobj`: a face of fewer than three vertices is
/// refused with its line; `l` lines (polylines: edges, which Blender's
/// importer keeps as loose edges and renderers draw nothing of) become
/// comments, so that `tobj` makes no triangles of them (the text is then
/// a copy: `Cow::Owned`). The lines keep their numbers.
pub(super) fn faces_and_polylines(text: &str) -> Result<Cow<'_, str>, String> {
    let mut polylines = Vec::new();
    let mut start = 0;
    for (i, line) in text.split('\n').enumerate() {
        // Most lines are vertices: two byte tests each, no word split.
        let body = line.trim_start_matches(|c: char| c.is_ascii_whitespace());
        let word = match body.as_bytes() {
            [w @ (b'f' | b'l')] => *w,
            [w @ (b'f' | b'l'), blank, ..] if blank.is_ascii_whitespace() => *w,
            _ => 0,
        };
        match word {
            b'f' => {
                let n = body[1..].split_ascii_whitespace().take(3).count();
                if n < 3 {
                    let shown = shown(line);
                    let has = crate::diag::count(n as u32, "vertex", "vertices");
                    return Err(format!(
                        "the face at line {} (`{shown}`) has {has} (a face needs at least 3)",
                        i + 1
                    ));
                }
            }
            b'l' => polylines.push(start + line.len() - body.len()),
            _ => {}
        }
        start += line.len() + 1;
    }
    if polylines.is_empty() {
        return Ok(Cow::Borrowed(text));
    }
    // `l` is one ASCII byte: a `#` in its place keeps the text UTF-8.
    let mut bytes = text.as_bytes().to_vec();
    for at in polylines {
        bytes[at] = b'#';
    }
    Ok(Cow::Owned(
        String::from_utf8(bytes).map_err(|e| e.to_string())?,
    ))
}

/// The first vertex line (`v`, `vt`, `vn`) that `tobj` refused with
/// `error`, or (no error: `tobj` read the file) whose numbers are not
/// finite, written for the message: `line 2 (`v 1 x 0`): `x` is not a
/// number`; `None` when no line is found.
pub(super) fn locate_vertex(text: &str, error: Option<&tobj::LoadError>) -> Option<String> {
    use tobj::LoadError::*;
    let wanted: &[&str] = match error {
        Some(PositionParseError | ScalingByZeroError | ColorParseError) => &["v"],
        Some(TexcoordParseError) => &["vt"],
        Some(NormalParseError) => &["vn"],
        Some(_) => return None,
        None => &["v", "vt"],
    };
    for (i, line) in text.split('\n').enumerate() {
        let mut words = line.split_whitespace();
        let Some(kind) = words.next().filter(|k| wanted.contains(k)) else {
            continue;
        };
        let numbers: Vec<&str> = words.collect();
        if let Some(why) = broken(kind, &numbers, error.is_none()) {
            return Some(format!("line {} (`{}`): {why}", i + 1, shown(line)));
        }
    }
    None
}

/// What is wrong with a `kind` line's `numbers` by `tobj`'s reading (or,
/// where `finite`, by whether what it reads is finite); `None` if nothing.
fn broken(kind: &str, numbers: &[&str], finite: bool) -> Option<String> {
    let (needed, what) = match kind {
        "v" => (3, "a position needs x y z"),
        "vt" => (2, "a texture coordinate needs u v"),
        _ => (3, "a normal needs x y z"),
    };
    let first = &numbers[..numbers.len().min(needed)];
    for word in first {
        match word.parse::<f32>() {
            Err(_) => return Some(format!("`{word}` is not a number")),
            Ok(x) if finite && !x.is_finite() => {
                return Some(format!("`{word}` is not a finite number"))
            }
            Ok(_) => {}
        }
    }
    if numbers.len() < needed {
        let has = crate::diag::count(numbers.len() as u32, "number", "numbers");
        return Some(format!("it has {has} ({what})"));
    }
    if kind != "v" {
        return None;
    }
    // `v x y z w` divides by w; `v x y z r g b` adds a colour.
    match &numbers[needed..] {
        [] => None,
        [w] => match w.parse::<f32>() {
            Err(_) => Some(format!("`{w}` is not a number")),
            Ok(0.0) => Some("its w is 0 (x y z are divided by it)".into()),
            Ok(w) => {
                let divided = first.iter().filter_map(|c| c.parse::<f32>().ok());
                let bad = finite && divided.map(|c| c / w).any(|c| !c.is_finite());
                bad.then(|| format!("x y z divided by its w ({w}) are not finite numbers"))
            }
        },
        [_, _, _] => None,
        more => Some(format!(
            "it has {} (x y z, x y z w, or x y z r g b)",
            crate::diag::count(3 + more.len() as u32, "number", "numbers")
        )),
    }
}

/// A line as a message shows it: trimmed, at most 60 characters.
pub(super) fn shown(line: &str) -> String {
    line.trim().chars().take(60).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use tobj::LoadError::*;

    #[test]
    fn a_face_of_two_vertices_is_refused_with_its_line() {
        let e = faces_and_polylines("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n").unwrap_err();
        assert_eq!(
            e,
            "the face at line 4 (`f 1 2`) has 2 vertices (a face needs at least 3)"
        );
        let e = faces_and_polylines("v 0 0 0\r\n  f 1\r\n").unwrap_err();
        assert!(e.contains("line 2 (`f 1`) has 1 vertex ("), "{e}");
        assert!(faces_and_polylines("f 1 2 3\nf 1 2 3 4\n").is_ok());
    }

    #[test]
    fn polylines_become_comments_on_their_lines() {
        let text = "v 0 0 0\n  l 1 2 3\nf 1 2 3\nlo 1\n";
        let read = faces_and_polylines(text).unwrap();
        assert_eq!(read, "v 0 0 0\n  # 1 2 3\nf 1 2 3\nlo 1\n");
        assert!(matches!(read, Cow::Owned(_)));
        assert!(matches!(
            faces_and_polylines("f 1 2 3"),
            Ok(Cow::Borrowed(_))
        ));
    }

    #[test]
    fn a_whole_file_is_read_by_these_rules_wherever_its_lines_stand() {
        // The lines are counted only where a file may need it: an `l`
        // line anywhere (indented too) and a short face found after tobj.
        let parse =
            |t: &str| crate::lower::mesh::parse(std::path::Path::new("t.obj"), t.as_bytes());
        let quad = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\n";
        for polyline in ["l 1 2 4\n", "  l 1 2 4\n", "\tl 2 3 4\n"] {
            let m = parse(&format!("{quad}{polyline}")).unwrap();
            assert_eq!(m.triangles.len(), 1, "{polyline:?}");
        }
        let e = parse(&format!("{quad}f 2 3\n")).unwrap_err();
        assert!(e.contains("line 6 (`f 2 3`) has 2 vertices"), "{e}");
        assert_eq!(parse(&format!("l 1 2\n{quad}")).unwrap().triangles.len(), 1);
        assert!(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n").is_err());
    }

    #[test]
    fn a_refused_vertex_line_is_found() {
        let at = |text: &str, e| locate_vertex(text, e).unwrap();
        let v = "v 0 0 0\nv 1 x 0\n";
        assert_eq!(
            at(v, Some(&PositionParseError)),
            "line 2 (`v 1 x 0`): `x` is not a number"
        );
        let v = "v 0 0 0\nv 1 0\n";
        assert_eq!(
            at(v, Some(&PositionParseError)),
            "line 2 (`v 1 0`): it has 2 numbers (a position needs x y z)"
        );
        assert!(at("v 1 0 0 0\n", Some(&ScalingByZeroError)).contains("its w is 0"));
        assert!(at("v 1 0 0 1 1\n", Some(&ColorParseError)).contains("it has 5 numbers"));
        assert!(at("vt 0 x\n", Some(&TexcoordParseError)).starts_with("line 1 (`vt 0 x`)"));
        assert!(at("vn 0 0\n", Some(&NormalParseError)).contains("a normal needs x y z"));
        // Read by tobj, but not finite.
        assert!(at("v 0 0 0\nv 1 nan 0\n", None)
            .contains("line 2 (`v 1 nan 0`): `nan` is not a finite"));
        assert!(at("vt 0 inf\n", None).contains("`inf`"));
        assert!(at("v 1e38 0 0 1e-38\n", None).contains("divided by its w"));
        assert_eq!(locate_vertex("v 0 0 0\n", None), None);
    }

    #[test]
    fn the_located_errors_are_tobjs() {
        let opts = crate::lower::obj::tobj_options();
        for obj in [
            "v 0 0 0\nv 1 x 0\nf 1 1 1\n",
            "v 0 0\nf 1 1 1\n",
            "v 0 0 0 0\nf 1 1 1\n",
            "v 0 0 0 1 1\nf 1 1 1\n",
            "v 0 0 0\nvt 0\nf 1 1 1\n",
            "v 0 0 0\nvn 0 x 0\nf 1 1 1\n",
        ] {
            let loaded = tobj::load_obj_buf(&mut std::io::Cursor::new(obj), &opts, |_| {
                Err(tobj::LoadError::OpenFileFailed)
            });
            let Err(e) = loaded else {
                panic!("not refused: {obj}")
            };
            assert!(locate_vertex(obj, Some(&e)).is_some(), "{e}: {obj}");
        }
    }
}
