//! `ptsc check FILE`: parse and check, print diagnostics, set the exit code.

use super::{Format, Verbosity, EXIT_OK, EXIT_SCENE_ERROR, EXIT_USAGE};
use crate::compile::{compile_file, Options};
use crate::diag::{Diagnostics, Severity};
use crate::source::SourceMap;
use std::path::Path;

/// Prints the diagnostics of a compile on stderr (human) or stdout (JSON);
/// `Quiet` leaves the warnings out.
pub fn report(
    diagnostics: &Diagnostics,
    sources: &SourceMap,
    format: Format,
    verbosity: Verbosity,
) {
    let quiet;
    let d = if verbosity == Verbosity::Quiet {
        quiet = (diagnostics.items.iter())
            .filter(|d| d.severity == Severity::Error)
            .cloned()
            .collect::<Diagnostics>();
        &quiet
    } else {
        diagnostics
    };
    match format {
        Format::Human => {
            eprint!("{}", d.render_human(sources, super::stderr_is_terminal()));
            if !d.items.is_empty() {
                eprintln!(
                    "{} error{}, {} warning{}",
                    d.error_count(),
                    if d.error_count() == 1 { "" } else { "s" },
                    d.warning_count(),
                    if d.warning_count() == 1 { "" } else { "s" },
                );
            }
        }
        Format::Json => println!("{}", d.render_json(sources)),
    }
}

/// Runs `check`; returns the exit code.
pub fn run(file: &Path, format: Format, verbosity: Verbosity) -> u8 {
    let options = Options {
        lower: false,
        ..Options::default()
    };
    let compiled = match compile_file(file, options) {
        Ok(c) => c,
        Err(e) => {
            let message = format!("cannot read {}: {e}", file.display());
            match format {
                Format::Human => eprintln!("error: {message}"),
                // A client reading JSON gets JSON: one diagnostic, no span.
                Format::Json => println!(
                    "{}",
                    serde_json::to_string_pretty(&serde_json::json!([{
                        "severity": "error",
                        "code": crate::diag::codes::IO_READ,
                        "message": message,
                        "label": "",
                        "help": "check the path and that the file is readable",
                        "file": file.display().to_string(),
                    }]))
                    .expect("JSON of plain values")
                ),
            }
            return EXIT_USAGE;
        }
    };
    report(&compiled.diagnostics, &compiled.sources, format, verbosity);
    if compiled.has_errors() {
        EXIT_SCENE_ERROR
    } else {
        if format == Format::Human && verbosity != Verbosity::Quiet {
            eprintln!("{}: ok", file.display());
        }
        EXIT_OK
    }
}
