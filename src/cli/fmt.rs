//! `ptsc fmt [--check] [FILE|FOLDER…|-]`: rewrite scenes in the canonical
//! layout (`crate::format`), or, with `--check`, list those that would
//! change.
//!
//! A file is rewritten atomically (a temporary file beside it, renamed
//! over it) and only when its text changes. `-`, or no file, reads stdin
//! and writes stdout. A file with a syntax error is left as it is and its
//! diagnostic printed as `ptsc check` prints it. A folder stands for its
//! `*.pts` and `*.ptsi` files, sorted by name (not its subfolders).
//!
//! Exit status: 0 all formatted (or, with `--check`, nothing would
//! change); 1 a file has a syntax error, or would change under `--check`;
//! 2 a file cannot be read or written, or the formatter failed its own
//! check (a bug: the file is left as it is).

use super::{EXIT_OK, EXIT_SCENE_ERROR, EXIT_USAGE};
use crate::format::{format_text, FormatError};
use crate::source::SourceMap;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Runs `fmt`; returns the exit code.
pub fn run(files: &[PathBuf], check: bool) -> u8 {
    if files.is_empty() || (files.len() == 1 && files[0] == Path::new("-")) {
        return stdin(check);
    }
    if files.iter().any(|f| f == Path::new("-")) {
        eprintln!("error: `-` (stdin) cannot be formatted with other files");
        return EXIT_USAGE;
    }
    let mut code = EXIT_OK;
    for file in expand(files) {
        let one = match file {
            Ok(path) => one_file(&path, check),
            Err(why) => {
                eprintln!("error: {why}");
                EXIT_USAGE
            }
        };
        code = code.max(one);
    }
    code
}

/// The files the arguments name: a file as it is, a folder as its `.pts`
/// and `.ptsi` files sorted by name (or why it cannot be read).
fn expand(args: &[PathBuf]) -> Vec<Result<PathBuf, String>> {
    let mut out = Vec::new();
    for arg in args {
        if !arg.is_dir() {
            out.push(Ok(arg.clone()));
            continue;
        }
        match std::fs::read_dir(arg) {
            Ok(entries) => {
                let mut found: Vec<PathBuf> = entries
                    .filter_map(Result::ok)
                    .map(|e| e.path())
                    .filter(|p| {
                        !p.is_dir() && p.extension().is_some_and(|x| x == "pts" || x == "ptsi")
                    })
                    .collect();
                found.sort();
                out.extend(found.into_iter().map(Ok));
            }
            Err(e) => out.push(Err(format!(
                "cannot read the folder {}: {e}",
                arg.display()
            ))),
        }
    }
    out
}

/// Formats one file in place (or checks it); returns its exit code.
fn one_file(path: &Path, check: bool) -> u8 {
    // As `check` reads a scene: a regular file within the size limit.
    let bytes = match crate::check::read_scene_file(&crate::source::Disk, path) {
        Ok(bytes) => bytes,
        Err(e) => {
            eprintln!("error: cannot read {}: {e}", path.display());
            return EXIT_USAGE;
        }
    };
    // A model or an image is `check`'s one error, not a syntax error.
    if let Some(kind) = crate::check::not_a_scene(path, &bytes) {
        let mut sources = SourceMap::new();
        let file = sources.add(path, String::new());
        let d = crate::check::not_a_scene_error(path, kind, crate::span::Span::new(file, 0, 0));
        let d: crate::diag::Diagnostics = std::iter::once(d).collect();
        eprint!("{}", d.render_human(&sources, super::stderr_is_terminal()));
        eprintln!("{}: not formatted", path.display());
        return EXIT_SCENE_ERROR;
    }
    let text = match String::from_utf8(bytes) {
        Ok(text) => text,
        Err(e) => {
            let at = e.utf8_error().valid_up_to();
            let line = e.as_bytes()[..at].iter().filter(|&&b| b == b'\n').count() + 1;
            eprintln!(
                "error: {} is not UTF-8 text (byte {at}, line {line}): save it as UTF-8 to format it",
                path.display()
            );
            return EXIT_USAGE;
        }
    };
    let formatted = match format_text(&text) {
        Ok(f) => f,
        Err(e) => return refused(path, text, e),
    };
    if formatted == text {
        return EXIT_OK;
    }
    if check {
        println!("{}", path.display());
        return EXIT_SCENE_ERROR;
    }
    let permissions = std::fs::metadata(path).map(|m| m.permissions());
    let written = crate::output::write_atomically(path, formatted.as_bytes())
        .and_then(|()| permissions.and_then(|p| std::fs::set_permissions(path, p)));
    match written {
        Ok(()) => EXIT_OK,
        Err(e) => {
            eprintln!("error: cannot write {}: {e}", path.display());
            EXIT_USAGE
        }
    }
}

/// Reports a text the formatter refused (`name` is where it comes from);
/// returns the exit code: 1 for a syntax error, 2 for a formatter bug.
fn refused(name: &Path, text: String, error: FormatError) -> u8 {
    match error {
        FormatError::Syntax(diagnostics) => {
            let mut sources = SourceMap::new();
            sources.add(name, text);
            let d: crate::diag::Diagnostics = diagnostics.into_iter().collect();
            eprint!("{}", d.render_human(&sources, super::stderr_is_terminal()));
            eprintln!("{}: not formatted (syntax error)", name.display());
            EXIT_SCENE_ERROR
        }
        FormatError::Bug(why) => {
            eprintln!(
                "error: internal formatter bug, please report: {}: {why}; left as it is",
                name.display()
            );
            EXIT_USAGE
        }
    }
}

/// Formats stdin to stdout (with `--check`, writes nothing and says
/// whether it would change); returns the exit code. A refused text is
/// written back unchanged.
fn stdin(check: bool) -> u8 {
    let text = match super::read_stdin().map(String::from_utf8) {
        Ok(Ok(text)) => text,
        Ok(Err(_)) => {
            eprintln!("error: stdin is not UTF-8 text");
            return EXIT_USAGE;
        }
        Err(why) => {
            eprintln!("error: {why}");
            return EXIT_USAGE;
        }
    };
    let name = Path::new(super::STDIN_NAME);
    let (out, code) = match format_text(&text) {
        Ok(f) if check && f != text => {
            println!("{}", name.display());
            return EXIT_SCENE_ERROR;
        }
        Ok(f) => (f, EXIT_OK),
        Err(e) => (text.clone(), refused(name, text, e)),
    };
    if check {
        return code;
    }
    let mut stdout = std::io::stdout().lock();
    if let Err(e) = stdout
        .write_all(out.as_bytes())
        .and_then(|()| stdout.flush())
    {
        eprintln!("error: cannot write stdout: {e}");
        return EXIT_USAGE;
    }
    code
}
