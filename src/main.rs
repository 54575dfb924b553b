//! The `ptsc` binary: a thin shell over [`ptsc::cli::run`].

fn main() -> std::process::ExitCode {
    ptsc::cli::run()
}
