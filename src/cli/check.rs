//! `ptsc check FILE`: parse and check, print diagnostics, set the exit code.

use super::{Format, EXIT_OK, EXIT_SCENE_ERROR, EXIT_USAGE};
use crate::check::{check_file, Checked};
use std::path::Path;

/// Prints the diagnostics of a compile on stderr (human) or stdout (JSON).
pub fn report(checked: &Checked, format: Format) {
    match format {
        Format::Human => {
            let d = &checked.diagnostics;
            eprint!(
                "{}",
                d.render_human(&checked.sources, super::stderr_is_terminal())
            );
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
        Format::Json => println!("{}", checked.diagnostics.render_json(&checked.sources)),
    }
}

/// Runs `check`; returns the exit code.
pub fn run(file: &Path, format: Format) -> u8 {
    let checked = match check_file(file) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: cannot read {}: {e}", file.display());
            return EXIT_USAGE;
        }
    };
    report(&checked, format);
    if checked.diagnostics.has_errors() {
        EXIT_SCENE_ERROR
    } else {
        if format == Format::Human {
            eprintln!("{}: ok", file.display());
        }
        EXIT_OK
    }
}
