//! The source map: every file read during a compile (the scene and its
//! includes), addressed by a small `FileId`, with a line index so that a
//! position costs a binary search, not a scan of the file; and the one way
//! every file of a scene is read, with a size limit.

pub mod files;

pub use files::{lexically_normal, Asked, Disk, Files, MemoryFiles};
use std::fmt;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

/// The largest scene file (and the most text of a scene and its includes
/// together). Spans hold 32-bit offsets; a scene this large is millions of
/// objects, which belong in a mesh file.
pub const MAX_SCENE_BYTES: u64 = 256 << 20;
/// The largest mesh file (a binary PLY of about 70 million triangles).
pub const MAX_MESH_BYTES: u64 = 2 << 30;

/// What a path is when it is not a regular file: the reason it is never
/// read, named in messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// A directory.
    Folder,
    /// A character device (`/dev/zero`, `/dev/urandom`, a terminal): endless
    /// or waiting for input.
    CharDevice,
    /// A block device (a disk).
    BlockDevice,
    /// A FIFO (named pipe): opening it waits for a writer, reading it for
    /// the writer's data.
    Fifo,
    /// A Unix socket.
    Socket,
    /// Anything else a platform has.
    Other,
}

impl fmt::Display for FileKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FileKind::Folder => "a folder",
            FileKind::CharDevice => "a character device",
            FileKind::BlockDevice => "a block device",
            FileKind::Fifo => "a FIFO (named pipe)",
            FileKind::Socket => "a socket",
            FileKind::Other => "not a file",
        })
    }
}

impl FileKind {
    /// What `meta` (of a path, links followed) describes, `None` for a
    /// regular file.
    pub fn of(meta: &std::fs::Metadata) -> Option<FileKind> {
        let t = meta.file_type();
        if t.is_file() {
            return None;
        }
        if t.is_dir() {
            return Some(FileKind::Folder);
        }
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileTypeExt;
            if t.is_char_device() {
                return Some(FileKind::CharDevice);
            }
            if t.is_block_device() {
                return Some(FileKind::BlockDevice);
            }
            if t.is_fifo() {
                return Some(FileKind::Fifo);
            }
            if t.is_socket() {
                return Some(FileKind::Socket);
            }
        }
        Some(FileKind::Other)
    }
}

/// Why a file of a scene could not be read.
#[derive(Debug)]
pub enum ReadError {
    /// Nothing at that path.
    NotFound,
    /// A folder, a device, a pipe or a socket: never read (it could be
    /// endless or wait forever).
    NotRegular(FileKind),
    /// Larger than the limit (the size found, at least).
    TooLarge {
        /// The limit in bytes.
        limit: u64,
        /// The size found (for a file that grows while read: what was read).
        size: u64,
    },
    /// Any other I/O error.
    Io(std::io::Error),
    /// Named relative to a document that has no folder (an editor's
    /// unsaved buffer, with no workspace to stand for its folder): there
    /// is no place to look, rather than a made-up one that holds nothing.
    Unsaved,
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReadError::NotFound => f.write_str("not found"),
            ReadError::NotRegular(kind) => write!(f, "not a regular file: it is {kind}"),
            ReadError::TooLarge { limit, size } => write!(
                f,
                "larger than {} (the file has {})",
                human_bytes(*limit),
                human_bytes(*size)
            ),
            ReadError::Io(e) => write!(f, "{e}"),
            ReadError::Unsaved => {
                f.write_str("the document is not saved, so it has no folder to read files from")
            }
        }
    }
}

/// `n` bytes in MiB or GiB, for messages.
pub fn human_bytes(n: u64) -> String {
    if n >= 1 << 30 {
        format!("{:.1} GiB", n as f64 / (1u64 << 30) as f64)
    } else {
        format!("{:.0} MiB", (n as f64 / (1u64 << 20) as f64).max(1.0))
    }
}

fn io_error(e: std::io::Error) -> ReadError {
    match e.kind() {
        std::io::ErrorKind::NotFound => ReadError::NotFound,
        _ => ReadError::Io(e),
    }
}

/// Opens the regular file at `path` (links followed) for reading, with its
/// length; anything else is refused without being opened (a device may
/// have effects when opened, a FIFO waits for a writer). The opened file is
/// checked again, so a path swapped for a FIFO in between is refused too:
/// it is opened without waiting (`O_NONBLOCK`, which regular files ignore).
pub fn open_regular(path: &Path) -> Result<(std::fs::File, u64), ReadError> {
    let meta = std::fs::metadata(path).map_err(io_error)?;
    if let Some(kind) = FileKind::of(&meta) {
        return Err(ReadError::NotRegular(kind));
    }
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(io_error)?;
    let meta = file.metadata().map_err(ReadError::Io)?;
    match FileKind::of(&meta) {
        Some(kind) => Err(ReadError::NotRegular(kind)),
        None => Ok((file, meta.len())),
    }
}

/// Reads a regular file of at most `limit` bytes (see [`open_regular`]).
/// The size is checked before reading and the read stops one byte past
/// the limit (a file that grows meanwhile is caught too).
pub fn read_file(path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
    let (file, len) = open_regular(path)?;
    read_stream(file, len, limit)
}

/// Reads at most `limit` bytes from `r`, expecting about `expected` (the
/// file's size, used to size the buffer).
pub fn read_stream(r: impl Read, expected: u64, limit: u64) -> Result<Vec<u8>, ReadError> {
    if expected > limit {
        return Err(ReadError::TooLarge {
            limit,
            size: expected,
        });
    }
    let mut bytes = Vec::with_capacity(expected as usize);
    r.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(ReadError::Io)?;
    if bytes.len() as u64 > limit {
        return Err(ReadError::TooLarge {
            limit,
            size: bytes.len() as u64,
        });
    }
    Ok(bytes)
}

/// Index of a file in a [`SourceMap`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct FileId(pub u32);

/// One source file: its path (as the user named it) and its text.
#[derive(Debug, Clone)]
pub struct SourceFile {
    /// Path used to read the file, for messages and relative includes.
    pub path: PathBuf,
    /// Full text (shared with miette diagnostics).
    pub text: Arc<String>,
    /// Byte offset of the start of every line, built on first use.
    line_starts: OnceLock<Arc<Vec<u32>>>,
}

impl SourceFile {
    /// A file with this path and text.
    pub fn new(path: impl Into<PathBuf>, text: String) -> SourceFile {
        SourceFile {
            path: path.into(),
            text: Arc::new(text),
            line_starts: OnceLock::new(),
        }
    }

    /// Byte offsets where lines start (the first is 0; a text ending in a
    /// line break has an empty last line).
    pub fn line_starts(&self) -> &[u32] {
        self.line_starts.get_or_init(|| {
            let mut starts = vec![0u32];
            starts.extend(
                self.text
                    .bytes()
                    .enumerate()
                    .filter(|&(_, b)| b == b'\n')
                    .map(|(i, _)| i as u32 + 1),
            );
            Arc::new(starts)
        })
    }

    /// The 0-based line holding byte `offset` (clamped to the text).
    pub fn line_of(&self, offset: usize) -> usize {
        let starts = self.line_starts();
        let offset = offset.min(self.text.len()) as u32;
        starts.partition_point(|&s| s <= offset) - 1
    }

    /// The byte range of 0-based line `line`, without its line break
    /// (`\n` or `\r\n`).
    pub fn line_range(&self, line: usize) -> std::ops::Range<usize> {
        let starts = self.line_starts();
        let start = starts[line] as usize;
        let mut end = starts
            .get(line + 1)
            .map_or(self.text.len(), |&s| s as usize - 1);
        if end > start && self.text.as_bytes()[end - 1] == b'\r' {
            end -= 1;
        }
        start..end
    }

    /// The largest character boundary at or before `offset` (clamped to the text).
    pub fn floor_char_boundary(&self, offset: usize) -> usize {
        let mut cut = offset.min(self.text.len());
        while !self.text.is_char_boundary(cut) {
            cut -= 1;
        }
        cut
    }
}

/// All files of a compile.
#[derive(Debug, Clone, Default)]
pub struct SourceMap {
    files: Vec<SourceFile>,
}

impl SourceMap {
    /// An empty map.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a file and returns its id.
    pub fn add(&mut self, path: impl Into<PathBuf>, text: String) -> FileId {
        self.files.push(SourceFile::new(path, text));
        FileId(self.files.len() as u32 - 1)
    }

    /// The file with this id.
    pub fn get(&self, id: FileId) -> &SourceFile {
        &self.files[id.0 as usize]
    }

    /// Every file, in the order they were added.
    pub fn files(&self) -> &[SourceFile] {
        &self.files
    }

    /// Id of an already loaded file with this path.
    pub fn find(&self, path: &Path) -> Option<FileId> {
        self.files
            .iter()
            .position(|f| f.path == path)
            .map(|i| FileId(i as u32))
    }

    /// Total size of the texts held, in bytes.
    pub fn total_bytes(&self) -> usize {
        self.files.iter().map(|f| f.text.len()).sum()
    }

    /// 1-based line and column (in characters) of a byte offset. Costs a
    /// binary search plus the characters of the line before the offset.
    pub fn line_col(&self, id: FileId, offset: u32) -> (usize, usize) {
        let file = self.get(id);
        let cut = file.floor_char_boundary(offset as usize);
        let line = file.line_of(cut);
        let start = file.line_starts()[line] as usize;
        let col = file.text[start..cut].chars().count() + 1;
        (line + 1, col)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_columns_from_the_index() {
        let mut map = SourceMap::new();
        let id = map.add("a.pts", "ab\r\nçd\n\nx".to_string());
        let f = map.get(id);
        assert_eq!(f.line_starts(), &[0, 4, 8, 9]);
        assert_eq!(f.line_range(0), 0..2);
        assert_eq!(f.line_range(1), 4..7);
        assert_eq!(f.line_range(2), 8..8);
        assert_eq!(f.line_range(3), 9..10);
        assert_eq!(map.line_col(id, 0), (1, 1));
        assert_eq!(map.line_col(id, 3), (1, 4));
        // `ç` is two bytes, one column; inside it the column is its own.
        assert_eq!(map.line_col(id, 6), (2, 2));
        assert_eq!(map.line_col(id, 5), (2, 1));
        assert_eq!(map.line_col(id, 9), (4, 1));
        // Past the end: clamped.
        assert_eq!(map.line_col(id, 1000), (4, 2));
    }

    #[test]
    fn reads_stop_at_the_limit() {
        assert_eq!(read_stream(&b"abc"[..], 3, 3).unwrap(), b"abc");
        // A stream longer than it said (a growing file, a device).
        let endless = std::io::repeat(0);
        assert!(matches!(
            read_stream(endless, 0, 1000),
            Err(ReadError::TooLarge {
                limit: 1000,
                size: 1001
            })
        ));
        assert!(matches!(
            read_stream(&b""[..], 5000, 1000),
            Err(ReadError::TooLarge { size: 5000, .. })
        ));
        let dir = std::env::temp_dir();
        assert!(matches!(
            read_file(&dir, 10),
            Err(ReadError::NotRegular(FileKind::Folder))
        ));
        assert!(matches!(
            read_file(&dir.join("no such file, surely"), 10),
            Err(ReadError::NotFound)
        ));
        if Path::new("/dev/zero").exists() {
            assert!(matches!(
                read_file(Path::new("/dev/zero"), 10),
                Err(ReadError::NotRegular(FileKind::CharDevice))
            ));
        }
        assert_eq!(human_bytes(MAX_SCENE_BYTES), "256 MiB");
        assert_eq!(human_bytes(MAX_MESH_BYTES), "2.0 GiB");
    }
}
