//! Why a session does not start, or did not finish its writes: values
//! the caller prints (their text is the command line's message).

use std::path::PathBuf;

/// Why a session does not start, or did not finish its writes.
#[derive(Debug)]
pub enum Error {
    /// The image cannot be written at `path` (a missing folder, an
    /// unknown format, a file of the scene).
    Output {
        /// The image.
        path: PathBuf,
        /// Why not.
        why: String,
    },
    /// The render is refused before it starts: a state the image would
    /// replace or that cannot be continued, memory, a pass's output.
    Refused(String),
    /// Writing the image or the state failed.
    Write {
        /// The file.
        path: PathBuf,
        /// What failed.
        error: std::io::Error,
    },
    /// Denoising failed after the render; the noisy image was written.
    Denoise {
        /// The image.
        path: PathBuf,
        /// Why.
        why: String,
    },
    /// A checkpoint could not save the state; the render stopped there.
    SaveState {
        /// The state file.
        path: PathBuf,
        /// What failed.
        error: std::io::Error,
    },
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            Error::Output { path, why } => {
                write!(f, "cannot write {}: {why}", crate::output::shown(path))
            }
            Error::Refused(why) => f.write_str(why),
            Error::Write { path, error } => write!(f, "cannot write {}: {error}", path.display()),
            Error::Denoise { path, why } => write!(
                f,
                "cannot denoise ({why}): {} holds the image without denoising",
                path.display()
            ),
            Error::SaveState { path, error } => {
                write!(f, "cannot save the state at {}: {error}", path.display())
            }
        }
    }
}

impl std::error::Error for Error {}
