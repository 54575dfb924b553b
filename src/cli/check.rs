//! `ptsc check FILE|FOLDER|-…`: parse and check each scene, print its
//! diagnostics, a summary, and set the exit code. `-` reads a scene from
//! stdin (its includes relative to the working folder).
//!
//! A folder stands for its `*.pts` files in name order; its subfolders are
//! not entered and its `.ptsi` include fragments are not checked alone (a
//! fragment is checked as part of each scene that includes it, where its
//! names mean something).

use super::{Format, Verbosity, EXIT_OK, EXIT_SCENE_ERROR, EXIT_USAGE};
use crate::compile::{compile_bytes, compile_file, Options};
use crate::diag::{Diagnostics, Severity};
use crate::source::SourceMap;
use std::path::{Path, PathBuf};

/// Prints the diagnostics of a compile on stderr (human) or stdout (JSON);
/// `Quiet` leaves the warnings out.
pub fn report(
    diagnostics: &Diagnostics,
    sources: &SourceMap,
    format: Format,
    verbosity: Verbosity,
) {
    let d = shown(diagnostics, verbosity);
    match format {
        Format::Human => {
            eprint!("{}", d.render_human(sources, super::stderr_is_terminal()));
            if !d.items.is_empty() {
                eprintln!("{}", counts(d.error_count(), d.warning_count()));
            }
        }
        Format::Json => println!("{}", d.render_json(sources)),
    }
}

/// The diagnostics a verbosity prints: `Quiet` only the errors.
fn shown(diagnostics: &Diagnostics, verbosity: Verbosity) -> Diagnostics {
    if verbosity == Verbosity::Quiet {
        (diagnostics.items.iter())
            .filter(|d| d.severity == Severity::Error)
            .cloned()
            .collect()
    } else {
        diagnostics.clone()
    }
}

/// "1 error, 2 warnings".
fn counts(errors: usize, warnings: usize) -> String {
    let s = |n: usize| if n == 1 { "" } else { "s" };
    format!(
        "{errors} error{}, {warnings} warning{}",
        s(errors),
        s(warnings)
    )
}

/// A scene to check, or what could not be read and why.
type Scene = Result<PathBuf, (PathBuf, String)>;

/// The scenes the arguments name: a file as it is, a folder as its `*.pts`
/// files sorted by name (or the reason it holds none).
fn scenes(args: &[PathBuf]) -> Vec<Scene> {
    let mut out = Vec::new();
    for arg in args {
        if !arg.is_dir() {
            out.push(Ok(arg.clone()));
            continue;
        }
        let entries = match std::fs::read_dir(arg) {
            Ok(e) => e,
            Err(e) => {
                let why = format!("cannot read the folder {}: {e}", arg.display());
                out.push(Err((arg.clone(), why)));
                continue;
            }
        };
        let mut found: Vec<PathBuf> = entries
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "pts") && !p.is_dir())
            .collect();
        if found.is_empty() {
            let why = format!(
                "{} holds no .pts scene (subfolders are not searched)",
                arg.display()
            );
            out.push(Err((arg.clone(), why)));
        }
        found.sort();
        out.extend(found.into_iter().map(Ok));
    }
    out
}

/// What one scene's check found.
struct Checked {
    errors: usize,
    warnings: usize,
    /// The scene could not be read (a usage problem, exit code 2).
    unreadable: bool,
}

/// Runs `check` on every scene the arguments name; returns the exit code:
/// 2 if one cannot be read, else 1 if one has errors, else 0. One scene
/// prints as it always did; several add a line per scene and a summary.
pub fn run(args: &[PathBuf], format: Format, verbosity: Verbosity) -> u8 {
    if args.iter().filter(|a| *a == Path::new("-")).count() > 1 {
        eprintln!("error: `-` (stdin) can be checked once");
        return EXIT_USAGE;
    }
    let scenes = scenes(args);
    let several = scenes.len() > 1 || args.iter().any(|a| a.is_dir());
    let mut json = Vec::new();
    let mut all = Vec::new();
    for scene in &scenes {
        let checked = match scene {
            Ok(path) => check_one(path, format, verbosity, several, &mut json),
            Err((path, why)) => unreadable(path, why, format, &mut json),
        };
        all.push(checked);
    }
    let errors: usize = all.iter().map(|c| c.errors).sum();
    let warnings: usize = all.iter().map(|c| c.warnings).sum();
    match format {
        Format::Json => println!(
            "{}",
            serde_json::to_string_pretty(&json).expect("JSON of plain values")
        ),
        Format::Human if several && (verbosity != Verbosity::Quiet || errors > 0) => {
            // (A folder without scenes is an error, not a file checked.)
            let is_folder = |s: &&Scene| matches!(s, Err((path, _)) if path.is_dir());
            let n = scenes.iter().filter(|s| !is_folder(s)).count();
            let files = if n == 1 { "file" } else { "files" };
            eprintln!("{n} {files} checked: {}", counts(errors, warnings));
        }
        Format::Human => {}
    }
    if all.iter().any(|c| c.unreadable) {
        EXIT_USAGE
    } else if errors > 0 {
        EXIT_SCENE_ERROR
    } else {
        EXIT_OK
    }
}

/// Checks one scene through the compile driver (checking only, no
/// lowering) and prints what it found (JSON objects go to `json`).
fn check_one(
    file: &Path,
    format: Format,
    verbosity: Verbosity,
    several: bool,
    json: &mut Vec<serde_json::Value>,
) -> Checked {
    let options = Options {
        lower: false,
        ..Options::default()
    };
    let compiled = if file == Path::new("-") {
        match super::read_stdin() {
            Ok(bytes) => compile_bytes(Path::new(super::STDIN_NAME), bytes, options),
            Err(why) => return unreadable(file, &why, format, json),
        }
    } else {
        match compile_file(file, options) {
            Ok(c) => c,
            Err(e) => {
                let why = format!("cannot read {}: {e}", file.display());
                return unreadable(file, &why, format, json);
            }
        }
    };
    let file = match file == Path::new("-") {
        true => Path::new(super::STDIN_NAME),
        false => file,
    };
    let d = shown(&compiled.diagnostics, verbosity);
    let (errors, warnings) = (d.error_count(), d.warning_count());
    match format {
        Format::Json => {
            let name = file.display().to_string();
            json.extend(d.json_items(&compiled.sources).into_iter().map(|mut o| {
                // Every object says which scene it belongs to.
                if o.get("file").is_none() {
                    o["file"] = name.clone().into();
                }
                o
            }));
        }
        Format::Human => {
            eprint!(
                "{}",
                d.render_human(&compiled.sources, super::stderr_is_terminal())
            );
            let quiet = verbosity == Verbosity::Quiet;
            let name = file.display();
            match (errors, warnings) {
                (0, 0) if !quiet => eprintln!("{name}: ok"),
                (0, 0) => {}
                (0, 1) => eprintln!("{name}: ok, 1 warning"),
                (0, n) => eprintln!("{name}: ok, {n} warnings"),
                _ if several => eprintln!("{name}: {}", counts(errors, warnings)),
                _ => eprintln!("{}", counts(errors, warnings)),
            }
        }
    }
    Checked {
        errors,
        warnings,
        unreadable: false,
    }
}

/// Reports a scene (or folder) that cannot be read (`message` says why);
/// JSON clients get JSON: one diagnostic without a span.
fn unreadable(
    path: &Path,
    message: &str,
    format: Format,
    json: &mut Vec<serde_json::Value>,
) -> Checked {
    match format {
        Format::Human => eprintln!("error: {message}"),
        Format::Json => json.push(serde_json::json!({
            "severity": "error",
            "code": crate::diag::codes::IO_READ,
            "message": message,
            "label": "",
            "help": "check the path and that the file is readable",
            "file": path.display().to_string(),
        })),
    }
    Checked {
        errors: 1,
        warnings: 0,
        unreadable: true,
    }
}
