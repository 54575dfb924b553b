//! The command line: `ptsc check`, `ptsc render`, `ptsc merge`, `ptsc watch`,
//! `ptsc fmt`.

mod args;
mod check;
mod denoise;
mod farm;
mod fmt;
mod render;
mod signals;
mod watch;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Exit code: the scene is fine (warnings allowed).
pub const EXIT_OK: u8 = 0;
/// Exit code: the scene has errors.
pub const EXIT_SCENE_ERROR: u8 = 1;
/// Exit code: bad usage or an I/O error.
pub const EXIT_USAGE: u8 = 2;
pub use signals::{EXIT_SIGINT, EXIT_SIGTERM};

/// How much a command prints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verbosity {
    /// Errors only.
    Quiet,
    /// Errors, warnings, progress and a summary line.
    Normal,
    /// Also the time of each stage and pass.
    Verbose,
}

impl Verbosity {
    /// From `--quiet` and `--verbose` (which clap keeps apart).
    pub fn from_flags(quiet: bool, verbose: bool) -> Verbosity {
        match (quiet, verbose) {
            (true, _) => Verbosity::Quiet,
            (_, true) => Verbosity::Verbose,
            _ => Verbosity::Normal,
        }
    }
}

/// ptsc: compile and render `.pts` scenes.
#[derive(Debug, Parser)]
#[command(name = "ptsc", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// How diagnostics are printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// For people, with the source underlined.
    Human,
    /// One JSON object per diagnostic, for editors and scripts.
    Json,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Parse and check scenes; print every problem, then a summary.
    ///
    /// A folder stands for its *.pts files, sorted by name (not its
    /// subfolders; .ptsi include fragments are checked with the scenes that
    /// include them); `-` reads a scene from stdin. Exit status: 0 fine
    /// (warnings allowed), 1 a scene has errors, 2 a file or folder cannot
    /// be read.
    Check {
        /// The scene files and folders of scenes (`-`: stdin).
        #[arg(required = true, value_name = "FILE|FOLDER|-")]
        files: Vec<std::path::PathBuf>,
        /// Output format of the diagnostics.
        #[arg(long, value_enum, default_value = "human")]
        format: Format,
        /// Only errors (no warnings, no "ok" line).
        #[arg(short, long)]
        quiet: bool,
    },
    /// Render a scene to an image (or a pass of it, or frames).
    Render {
        /// What to render.
        #[command(flatten)]
        args: render::RenderArgs,
        /// Long renders and farms: state, resume, passes.
        #[command(flatten)]
        farm: farm::FarmArgs,
    },
    /// Add up the passes of a render made with `ptsc render --pass K/N`.
    Merge(farm::MergeArgs),
    /// Denoise a saved EXR render with Intel Open Image Denoise (its albedo
    /// and normal channels from `--aov albedo,normal` used when present; a
    /// build with the `denoise` feature).
    Denoise(denoise::DenoiseArgs),
    /// Re-render a scene every time it (or an included file or mesh) is saved.
    ///
    /// Each save first writes a 1-spp preview at a quarter of the resolution
    /// to NAME.preview.png beside the image NAME.png (same format, replaced
    /// atomically), then full-resolution passes of 1, 2, 4, … spp to the image
    /// itself: the image only ever holds full-resolution results.
    // The flags of a batch render's end are hidden (each is refused with
    // why), and those watch reads otherwise are described as it reads them.
    #[command(
        mut_arg("file", |a| a.help("The scene file to watch (not stdin, which is read once)")),
        mut_arg("frames", |a| a.help("An animation's frames A..B, for its `clock`: watch renders one of them, --frame's, else the first")),
        mut_arg("time", |a| a.hide(true)),
        mut_arg("denoise", |a| a.hide(true)),
        mut_arg("aov", |a| a.hide(true)),
        mut_arg("tev", |a| a.hide(true)),
    )]
    Watch(render::RenderArgs),
    /// Rewrite scenes in the canonical layout (docs/language.md, "Formatting").
    ///
    /// Each file is rewritten in place (atomically, and only if it changes);
    /// `-` or no file formats stdin to stdout. A folder stands for its .pts
    /// and .ptsi files (not its subfolders). A file with a syntax error is
    /// left as it is. Exit status: 0 fine, 1 a syntax error (or, with
    /// --check, a file that would change), 2 a file cannot be read or
    /// written, or the formatter failed its own check.
    Fmt {
        /// The files and folders to format; `-` or none: stdin.
        #[arg(value_name = "FILE|FOLDER|-")]
        files: Vec<std::path::PathBuf>,
        /// Change nothing: list the files that would change (exit status 1 if any).
        #[arg(long)]
        check: bool,
    },
    /// Serve the Language Server Protocol over stdin and stdout, for editors
    /// (diagnostics as you type, hover, completion, go to definition,
    /// rename, outline, colours, quick fixes, formatting; editors/README.md).
    Lsp,
    /// Explain a diagnostic code: what it means, an example (as `rustc --explain`).
    Explain {
        /// The code, in full (`pts::check::unknown_param`) or its last part (`unknown_param`).
        #[arg(required_unless_present = "all")]
        code: Option<String>,
        /// Every code, as the Markdown of docs/diagnostics.md.
        #[arg(long, conflicts_with = "code")]
        all: bool,
    },
}

/// Runs the command line and returns the process exit code.
pub fn run() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            if e.use_stderr() {
                let args: Vec<String> = std::env::args().skip(1).collect();
                if let Some(hint) = usage_note(&args, e.kind()) {
                    eprintln!("note: {hint}");
                }
            }
            return ExitCode::from(if e.use_stderr() { EXIT_USAGE } else { EXIT_OK });
        }
    };
    let code = match cli.command {
        Command::Check {
            files,
            format,
            quiet,
        } => check::run(&files, format, Verbosity::from_flags(quiet, false)),
        Command::Render { args, farm } => render::run(&args, &farm),
        Command::Merge(args) => farm::merge(&args),
        Command::Denoise(args) => denoise::run(&args),
        Command::Watch(args) => watch::run(&args),
        Command::Fmt { files, check } => fmt::run(&files, check),
        Command::Explain { code, all } => explain(code.as_deref(), all),
        Command::Lsp => {
            if crate::lsp::run_stdio() {
                EXIT_OK
            } else {
                EXIT_SCENE_ERROR
            }
        }
    };
    ExitCode::from(code)
}

/// A note after a command line that did not parse, where clap's own tip
/// would mislead (`to pass '-1' as a value, use '-- -1'`): a POV-Ray
/// option, a width or height of their own, a negative number after an
/// option.
fn usage_note(args: &[String], kind: clap::error::ErrorKind) -> Option<String> {
    if let Some(hint) = args.iter().find_map(|a| povray_option(a)) {
        return Some(hint);
    }
    let size_word = ["-w", "--width", "--height", "--size"];
    if let Some(word) = args.iter().find(|a| size_word.contains(&a.as_str())) {
        return Some(format!(
            "ptsc has no `{word}`: the image's size is `--resolution WxH` (e.g. `--resolution 320x240`)"
        ));
    }
    let command = args.first().filter(|a| !a.starts_with('-'));
    let help = command.map_or("ptsc --help".to_string(), |c| format!("ptsc {c} --help"));
    // (A numeric option takes a negative number and says why not itself.)
    if kind != clap::error::ErrorKind::UnknownArgument {
        return None;
    }
    args.windows(2).find_map(|pair| {
        let (option, value) = (&pair[0], &pair[1]);
        // A number with or without a unit (`-1`, `-5s`, `-.5`, `-2G`):
        // clap reads `-5s` as short options, whatever the option takes.
        let negative = (value.strip_prefix('-'))
            .is_some_and(|rest| rest.starts_with(|c: char| c.is_ascii_digit() || c == '.'));
        // (Not `--` itself: `--spp -- -1` ends the options.)
        (option.starts_with("--") && option != "--" && negative).then(|| {
            format!("`{option}` takes no negative number (`{value}`): `{help}` says what it takes")
        })
    })
}

/// What ptsc writes for the POV-Ray command-line option `arg` (`+W320`,
/// `-H240`, `+A0.3`, `+Oout.png`), told after a command line that did not
/// parse.
fn povray_option(arg: &str) -> Option<String> {
    let rest = arg
        .strip_prefix(['+', '-'])
        .filter(|r| !r.starts_with('-'))?;
    let mut chars = rest.chars();
    let letter = chars.next()?;
    // ptsc's own short options are lower case (`-o`, `-v`, `-q`).
    if arg.starts_with('-') && !letter.is_ascii_uppercase() {
        return None;
    }
    let letter = letter.to_ascii_uppercase();
    let value = chars.as_str();
    let numeric = !value.is_empty() && value.parse::<f64>().is_ok();
    let instead = match letter {
        'W' | 'H' if numeric => "`--resolution WxH` (e.g. `--resolution 320x240`)",
        'O' if !value.is_empty() => "`-o FILE`",
        'I' if !value.is_empty() => "the scene's path after `render` (`ptsc render scene.pts`)",
        'A' => "`--spp N`: every pixel is sampled N times, there is no anti-aliasing switch",
        _ if arg.starts_with('+') => "ptsc's options, which start with `--` (`ptsc render --help`)",
        _ => return None,
    };
    Some(format!("POV-Ray's `{arg}` is {instead} in ptsc"))
}

/// Runs `explain`; returns the exit code.
fn explain(code: Option<&str>, all: bool) -> u8 {
    use crate::diag::codes::{lookup, markdown, CATALOGUE};
    if all {
        print!("{}", markdown());
        return EXIT_OK;
    }
    let code = code.unwrap_or_default();
    match lookup(code) {
        Some(e) => {
            println!("{}: {}\n\n{}\n\nExample:\n", e.code, e.title, e.explanation);
            for line in e.example.lines() {
                println!("    {line}");
            }
            EXIT_OK
        }
        None => {
            let names = CATALOGUE
                .iter()
                .flat_map(|e| [e.code, e.code.rsplit("::").next().unwrap_or(e.code)]);
            let hint = crate::diag::did_you_mean(code, names)
                .map(|n| format!(" (did you mean `{n}`?)"))
                .unwrap_or_default();
            eprintln!("error: no diagnostic code `{code}`{hint}; `ptsc explain --all` lists them");
            EXIT_USAGE
        }
    }
}

/// The name a scene read from stdin (`-`) goes by in messages; includes
/// are found relative to the working folder.
pub const STDIN_NAME: &str = "<stdin>";

/// Reads a scene from stdin, refusing one larger than a scene file may
/// be ([`crate::source::MAX_SCENE_BYTES`]) before holding more of it.
pub fn read_stdin() -> Result<Vec<u8>, String> {
    use std::io::Read;
    let limit = crate::source::MAX_SCENE_BYTES;
    let mut bytes = Vec::new();
    (std::io::stdin().lock().take(limit + 1))
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read stdin: {e}"))?;
    if bytes.len() as u64 > limit {
        return Err(format!(
            "stdin holds more than {}, the most a scene may be",
            crate::source::human_bytes(limit)
        ));
    }
    Ok(bytes)
}

/// Whether stderr is a terminal (colours, progress bars).
pub fn stderr_is_terminal() -> bool {
    use std::io::IsTerminal;
    std::io::stderr().is_terminal()
}

#[cfg(test)]
mod tests {
    use super::{povray_option, usage_note};

    #[test]
    fn a_width_of_its_own_and_a_negative_value_are_told() {
        let note = |args: &[&str]| {
            let args: Vec<String> = args.iter().map(|a| a.to_string()).collect();
            usage_note(&args, clap::error::ErrorKind::UnknownArgument)
        };
        let said = note(&["render", "s.pts", "-w", "320"]).unwrap();
        assert!(said.contains("--resolution"), "{said}");
        let said = note(&["render", "s.pts", "--seed", "-1"]).unwrap();
        assert!(said.contains("`--seed` takes no negative number"), "{said}");
        // A duration or a size: a number with its unit.
        for (flag, value) in [
            ("--time", "-5s"),
            ("--memory-limit", "-2G"),
            ("--time", "-.5h"),
        ] {
            let said = note(&["render", "s.pts", flag, value]).unwrap();
            assert!(
                said.contains(&format!("`{flag}` takes no negative number (`{value}`)")),
                "{said}"
            );
        }
        assert_eq!(note(&["render", "s.pts", "--spp", "4", "-o"]), None);
        assert!(note(&["render", "+W320"]).unwrap().contains("--resolution"));
        // `--` ends the options: it takes no value to be told about.
        assert_eq!(note(&["render", "s.pts", "--spp", "--", "-1"]), None);
        // A numeric option's own error says why a negative number is refused.
        let args: Vec<String> = ["render", "s.pts", "--spp", "-1"]
            .map(String::from)
            .to_vec();
        assert_eq!(
            usage_note(&args, clap::error::ErrorKind::ValueValidation),
            None
        );
    }

    #[test]
    fn povray_options_are_told_and_ptsc_options_are_not() {
        for (arg, says) in [
            ("+W320", "--resolution"),
            ("-H240", "--resolution"),
            ("+w640", "--resolution"),
            ("+Oout.png", "-o FILE"),
            ("+Iscene.pov", "after `render`"),
            ("+A0.3", "--spp"),
            ("+Q9", "start with `--`"),
        ] {
            let hint = povray_option(arg).unwrap_or_else(|| panic!("{arg}: no hint"));
            assert!(hint.contains(says), "{arg}: {hint}");
        }
        for arg in [
            "-o",
            "-oout.png",
            "-v",
            "-q",
            "--spp",
            "-1",
            "-w",
            "scene.pts",
            "+",
            "-",
        ] {
            assert_eq!(povray_option(arg), None, "{arg}");
        }
    }
}
