//! Imports only go down inside folders too: the modules of a folder (its
//! files and subfolders, and its `mod.rs`) form a DAG. A child naming
//! an item of `mod.rs` while `mod.rs` names the child is a circle, as is
//! any longer loop among siblings. Test modules and doc comments do not
//! count.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Folders whose modules must form a DAG: the front end's, the editor's,
/// and the renderer's pixel loop and its session.
const CHECKED: &[&str] = &[
    "src/syntax",
    "src/check",
    "src/check/eval",
    "src/check/kinds",
    "src/format",
    "src/ide",
    "src/lsp",
    "src/render",
    "src/render/session",
];

/// A file's module path from the crate root (`check::eval::env`; a
/// folder's `mod.rs` is the folder's own path).
fn module_path(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod" || p == "lib") {
        parts.pop();
    }
    parts
}

/// A file's code: no test module (they come last), no comments. Only a
/// test module ends it: an import under `#[cfg(test)]` is code (cutting
/// there hid every import after it).
fn code_of(text: &str) -> String {
    let text = text.split("#[cfg(test)]\nmod ").next().unwrap_or(text);
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The paths a file's code names, resolved to absolute module paths
/// (`super::`, `self::` and `crate::` paths, each name of a `{…}` group;
/// a folder's `mod.rs` also names its children by bare paths).
fn named_paths(
    code: &str,
    own: &[String],
    is_folder_root: bool,
    children: &[String],
) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let bytes = code.as_bytes();
    let word = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let mut i = 0;
    while i < bytes.len() {
        if !word(bytes[i]) || (i > 0 && (word(bytes[i - 1]) || bytes[i - 1] == b':')) {
            i += 1;
            continue;
        }
        let start = i;
        let mut end = i;
        while end < bytes.len() && (word(bytes[end]) || bytes[end] == b':') {
            end += 1;
        }
        let path = &code[start..end];
        i = end;
        let mut segments: Vec<&str> = path.split("::").collect();
        let base: Vec<String> = match segments[0] {
            "crate" => {
                segments.remove(0);
                Vec::new()
            }
            "self" | "super" => {
                // A file's path is its module's, so `super` is one step up
                // from a plain file and from a folder's `mod.rs` alike.
                let mut base = own.to_vec();
                while let Some(&s) = segments.first() {
                    match s {
                        "self" => {}
                        "super" => {
                            base.pop();
                        }
                        _ => break,
                    }
                    segments.remove(0);
                }
                if !is_folder_root && segments.is_empty() {
                    continue;
                }
                base
            }
            first
                if is_folder_root && children.iter().any(|c| c == first) && segments.len() > 1 =>
            {
                own.to_vec()
            }
            _ => continue,
        };
        // `super::{a, b::c}` and `super::*`: the group follows the path.
        let rest = &code[end..];
        let mut full = base.clone();
        full.extend(
            segments
                .iter()
                .filter(|s| !s.is_empty())
                .map(|s| s.to_string()),
        );
        if path.ends_with("::") && rest.starts_with('{') {
            let group = &rest[1..rest.find('}').unwrap_or(rest.len())];
            for item in group.split(',') {
                let item = item.trim();
                let mut p = full.clone();
                p.extend(
                    item.split("::")
                        .map(|s| s.trim().to_string())
                        .filter(|s| !s.is_empty()),
                );
                out.push(p);
            }
        } else if path.ends_with("::") && rest.starts_with('*') {
            full.push("*".to_string());
            out.push(full);
        } else {
            out.push(full);
        }
    }
    out
}

/// The circles among the modules of `folder` (empty: a DAG).
fn circles(folder: &str) -> Vec<String> {
    let root = crate::root();
    let src = root.join("src");
    let dir = root.join(folder);
    let folder_path = module_path(&src, &dir.join("mod.rs"));
    // The folder's children: files and subfolders.
    let mut children: Vec<String> = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        if path.is_dir() || (path.extension().is_some_and(|e| e == "rs") && name != "mod") {
            children.push(name);
        }
    }
    let node_of = |file: &Path| -> String {
        let path = module_path(&src, file);
        path.get(folder_path.len())
            .cloned()
            .unwrap_or_else(|| "mod".to_string())
    };
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for file in crate::files_below(&dir, "rs") {
        let name = file.file_stem().unwrap().to_string_lossy().into_owned();
        if name == "tests" || name.ends_with("_tests") {
            continue;
        }
        let own = module_path(&src, &file);
        let is_folder_root = name == "mod";
        let own_children: Vec<String> = if is_folder_root {
            std::fs::read_dir(file.parent().unwrap())
                .unwrap()
                .map(|e| {
                    e.unwrap()
                        .path()
                        .file_stem()
                        .unwrap()
                        .to_string_lossy()
                        .into_owned()
                })
                .collect()
        } else {
            Vec::new()
        };
        let from = node_of(&file);
        let code = code_of(&std::fs::read_to_string(&file).unwrap());
        for path in named_paths(&code, &own, is_folder_root, &own_children) {
            if path.len() <= folder_path.len() || path[..folder_path.len()] != folder_path[..] {
                continue;
            }
            let next = &path[folder_path.len()];
            let to = if children.contains(next) {
                next.clone()
            } else {
                "mod".to_string()
            };
            if to != from {
                edges.entry(from.clone()).or_default().insert(to);
            }
        }
    }
    find_circles(&edges)
}

/// Each circle of `edges`, written `a -> b -> a`.
fn find_circles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<String> {
    let mut found = BTreeSet::new();
    for start in edges.keys() {
        // Depth-first from `start`, back to `start`.
        let mut stack = vec![(start.clone(), vec![start.clone()])];
        let mut seen = BTreeSet::new();
        while let Some((node, trail)) = stack.pop() {
            for next in edges.get(&node).into_iter().flatten() {
                if next == start {
                    let mut circle = trail.clone();
                    // One spelling per circle: start at its least name.
                    let least = (0..circle.len())
                        .min_by_key(|&k| circle[k].clone())
                        .unwrap();
                    circle.rotate_left(least);
                    let first = circle[0].clone();
                    circle.push(first);
                    found.insert(circle.join(" -> "));
                } else if seen.insert(next.clone()) {
                    let mut t = trail.clone();
                    t.push(next.clone());
                    stack.push((next.clone(), t));
                }
            }
        }
    }
    found.into_iter().collect()
}

#[test]
fn the_front_end_folders_have_no_circles() {
    let mut all = Vec::new();
    for folder in CHECKED {
        for circle in circles(folder) {
            all.push(format!("{folder}: {circle}"));
        }
    }
    assert!(
        all.is_empty(),
        "imports go around in circles:\n{}",
        all.join("\n")
    );
}

#[test]
fn the_circle_finder_finds_circles_and_resolves_paths() {
    let edges: BTreeMap<String, BTreeSet<String>> = [
        ("a", &["b"][..]),
        ("b", &["c"][..]),
        ("c", &["a"][..]),
        ("d", &["a"][..]),
    ]
    .iter()
    .map(|(k, v)| (k.to_string(), v.iter().map(|s| s.to_string()).collect()))
    .collect();
    assert_eq!(find_circles(&edges), ["a -> b -> c -> a"]);
    let own: Vec<String> = ["check".to_string(), "params".to_string()].to_vec();
    let paths = named_paths(
        "use super::{eval::Env, scene};\nlet x = super::X;",
        &own,
        false,
        &[],
    );
    let text: Vec<String> = paths.iter().map(|p| p.join("::")).collect();
    assert_eq!(text, ["check::eval::Env", "check::scene", "check::X"]);
    let _ = PathBuf::new();
}
