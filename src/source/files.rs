//! The file seam: every file a compile reads (the scene, its includes, its
//! meshes and images) is asked of a [`Files`], never of the disk directly.
//! The command line gives it the disk ([`Disk`]), tests a map of names to
//! bytes ([`MemoryFiles`]), an editor its open buffers over the disk
//! ([`MemoryFiles::over_disk`]); the compile driver wraps whichever it is
//! given in [`Asked`] and so learns every file the scene depends on.

use super::{open_regular, read_file, read_stream, FileKind, ReadError};
use std::collections::{HashMap, HashSet};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::SystemTime;

/// A file's length and modification time: when both are unchanged, a cache
/// may keep what it made of the file without reading it again.
pub type Stamp = (u64, SystemTime);

/// Where a compile reads its files: the one way the front end and lowering
/// reach a file (the scene, its includes, meshes, images).
pub trait Files: Sync {
    /// The bytes of the regular file at `path`, at most `limit` of them
    /// (larger is [`ReadError::TooLarge`], found before reading when it
    /// can be).
    fn read(&self, path: &Path, limit: u64) -> Result<Vec<u8>, ReadError>;
    /// The file at `path` as a stream of at most `limit` bytes, for those
    /// who hash a large file in pieces rather than hold it.
    fn open(&self, path: &Path, limit: u64) -> Result<Box<dyn Read + '_>, ReadError>;
    /// `Ok` when `path` names a regular file; what it is otherwise. Asks
    /// only what the path is (a `stat`, which never waits).
    fn exists(&self, path: &Path) -> Result<(), ReadError>;
    /// The name that identifies the file at `path` (links resolved): two
    /// paths with one canonical name are one file (include cycles, caches).
    /// The path itself when it cannot be resolved.
    fn canonical(&self, path: &Path) -> PathBuf;
    /// The file's [`Stamp`], when the files can tell one (in memory, they
    /// cannot: a cache then compares contents).
    fn stamp(&self, path: &Path) -> Option<Stamp>;
}

/// The file system, read with the limits and refusals of
/// [`crate::source::read_file`] (regular files only, bounded).
#[derive(Debug, Clone, Copy, Default)]
pub struct Disk;

impl Files for Disk {
    fn read(&self, path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
        read_file(path, limit)
    }

    fn open(&self, path: &Path, limit: u64) -> Result<Box<dyn Read + '_>, ReadError> {
        let (file, len) = open_regular(path)?;
        if len > limit {
            return Err(ReadError::TooLarge { limit, size: len });
        }
        Ok(Box::new(file.take(limit + 1)))
    }

    fn exists(&self, path: &Path) -> Result<(), ReadError> {
        match std::fs::metadata(path).map(|m| FileKind::of(&m)) {
            Ok(None) => Ok(()),
            Ok(Some(kind)) => Err(ReadError::NotRegular(kind)),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(ReadError::NotFound),
            Err(e) => Err(ReadError::Io(e)),
        }
    }

    fn canonical(&self, path: &Path) -> PathBuf {
        std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
    }

    fn stamp(&self, path: &Path) -> Option<Stamp> {
        let meta = std::fs::metadata(path).ok()?;
        Some((meta.len(), meta.modified().ok()?))
    }
}

/// Files held in memory by name, optionally over the disk: a name held
/// here wins (an editor's unsaved buffer), any other is read from the disk
/// when [`MemoryFiles::over_disk`] made it, and is not found otherwise.
#[derive(Debug, Default)]
pub struct MemoryFiles {
    files: HashMap<PathBuf, Arc<[u8]>>,
    disk: Option<Disk>,
    /// The made-up folder of documents that have none (see
    /// [`MemoryFiles::unsaved_folder`]).
    unsaved: Option<PathBuf>,
}

impl MemoryFiles {
    /// No files, and no disk below them.
    pub fn new() -> MemoryFiles {
        MemoryFiles::default()
    }

    /// No files yet, over the disk.
    pub fn over_disk() -> MemoryFiles {
        MemoryFiles {
            files: HashMap::new(),
            disk: Some(Disk),
            unsaved: None,
        }
    }

    /// Names `folder` as the made-up folder of documents that have none
    /// (an editor's unsaved buffers): the files held there are read, and
    /// any other path below it is [`ReadError::Unsaved`], never asked of
    /// the disk (whatever lies at that path is not beside the document).
    pub fn unsaved_folder(&mut self, folder: impl Into<PathBuf>) {
        self.unsaved = Some(lexically_normal(&folder.into()));
    }

    /// Holds `bytes` as the file `path` (replacing what it held).
    pub fn insert(&mut self, path: impl Into<PathBuf>, bytes: impl Into<Vec<u8>>) {
        let bytes: Vec<u8> = bytes.into();
        self.files
            .insert(lexically_normal(&path.into()), bytes.into());
    }

    /// Forgets the file `path` (the disk's, if any, shows again).
    pub fn remove(&mut self, path: &Path) {
        self.files.remove(&lexically_normal(path));
    }

    /// The bytes held as `path` (named with `.` and `..` parts or not:
    /// memory has no links, so they resolve by the name alone).
    fn held(&self, path: &Path) -> Option<&Arc<[u8]>> {
        self.files.get(&lexically_normal(path))
    }

    /// The disk below the held files, unless `path` lies in the unsaved
    /// documents' made-up folder (`Err`: nothing can be read there).
    fn disk_for(&self, path: &Path) -> Result<Option<&Disk>, ReadError> {
        match &self.unsaved {
            Some(folder) if lexically_normal(path).starts_with(folder) => Err(ReadError::Unsaved),
            _ => Ok(self.disk.as_ref()),
        }
    }
}

impl Files for MemoryFiles {
    fn read(&self, path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
        match self.held(path) {
            Some(bytes) => read_stream(&bytes[..], bytes.len() as u64, limit),
            None => match self.disk_for(path)? {
                Some(disk) => disk.read(path, limit),
                None => Err(self.missing(path)),
            },
        }
    }

    fn open(&self, path: &Path, limit: u64) -> Result<Box<dyn Read + '_>, ReadError> {
        match self.held(path) {
            Some(bytes) if bytes.len() as u64 > limit => Err(ReadError::TooLarge {
                limit,
                size: bytes.len() as u64,
            }),
            Some(bytes) => Ok(Box::new(&bytes[..])),
            None => match self.disk_for(path)? {
                Some(disk) => disk.open(path, limit),
                None => Err(self.missing(path)),
            },
        }
    }

    fn exists(&self, path: &Path) -> Result<(), ReadError> {
        match self.held(path) {
            Some(_) => Ok(()),
            None => match self.disk_for(path)? {
                Some(disk) => disk.exists(path),
                None => Err(self.missing(path)),
            },
        }
    }

    fn canonical(&self, path: &Path) -> PathBuf {
        match (self.held(path), self.disk_for(path)) {
            (None, Ok(Some(disk))) => disk.canonical(path),
            _ => lexically_normal(path),
        }
    }

    fn stamp(&self, path: &Path) -> Option<Stamp> {
        match (self.held(path), self.disk_for(path)) {
            (None, Ok(Some(disk))) => disk.stamp(path),
            _ => None,
        }
    }
}

impl MemoryFiles {
    /// Not held: nothing there, or a folder when held files lie below it.
    fn missing(&self, path: &Path) -> ReadError {
        let path = lexically_normal(path);
        if self.files.keys().any(|k| k.starts_with(&path)) {
            return ReadError::NotRegular(FileKind::Folder);
        }
        ReadError::NotFound
    }
}

/// `path` with its `.` parts dropped and each `..` taking the part before
/// it: the canonical name of a file held in memory, where no links exist.
pub fn lexically_normal(path: &Path) -> PathBuf {
    use std::path::Component;
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            Component::CurDir => {}
            Component::ParentDir if out.file_name().is_some() => {
                out.pop();
            }
            other => out.push(other.as_os_str()),
        }
    }
    out
}

/// Files that remember every path asked of them, in the order first
/// asked: the files a compile depends on (what `watch` watches), whether
/// they were found or not (a missing include appearing is a change too).
pub struct Asked<'a> {
    files: &'a dyn Files,
    asked: Mutex<(Vec<PathBuf>, HashSet<PathBuf>)>,
}

impl<'a> Asked<'a> {
    /// Asks `files`, remembering what.
    pub fn new(files: &'a dyn Files) -> Asked<'a> {
        Asked {
            files,
            asked: Mutex::new((Vec::new(), HashSet::new())),
        }
    }

    /// Every path asked so far, each once, in the order first asked.
    pub fn paths(&self) -> Vec<PathBuf> {
        self.asked.lock().map(|a| a.0.clone()).unwrap_or_default()
    }

    /// Remembers `path` as asked (a file given rather than read: the
    /// scene's own bytes).
    pub fn note(&self, path: &Path) {
        if let Ok(mut asked) = self.asked.lock() {
            if !asked.1.contains(path) {
                asked.1.insert(path.to_path_buf());
                asked.0.push(path.to_path_buf());
            }
        }
    }
}

impl Files for Asked<'_> {
    fn read(&self, path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
        self.note(path);
        self.files.read(path, limit)
    }

    fn open(&self, path: &Path, limit: u64) -> Result<Box<dyn Read + '_>, ReadError> {
        self.note(path);
        self.files.open(path, limit)
    }

    fn exists(&self, path: &Path) -> Result<(), ReadError> {
        self.note(path);
        self.files.exists(path)
    }

    fn canonical(&self, path: &Path) -> PathBuf {
        self.files.canonical(path)
    }

    fn stamp(&self, path: &Path) -> Option<Stamp> {
        self.note(path);
        self.files.stamp(path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn memory_files_read_what_they_hold_and_nothing_else() {
        let mut files = MemoryFiles::new();
        files.insert("/scenes/a.pts", "sphere { radius 1 }");
        let a = Path::new("/scenes/a.pts");
        assert_eq!(files.read(a, 100).unwrap(), b"sphere { radius 1 }");
        assert!(matches!(files.read(a, 5), Err(ReadError::TooLarge { .. })));
        assert!(matches!(files.open(a, 5), Err(ReadError::TooLarge { .. })));
        let mut streamed = Vec::new();
        files
            .open(a, 100)
            .unwrap()
            .read_to_end(&mut streamed)
            .unwrap();
        assert_eq!(streamed, b"sphere { radius 1 }");
        assert!(files.exists(a).is_ok());
        let folder = files.exists(Path::new("/scenes"));
        assert!(matches!(
            folder,
            Err(ReadError::NotRegular(FileKind::Folder))
        ));
        let missing = files.read(Path::new("/etc/hostname"), 100);
        assert!(matches!(missing, Err(ReadError::NotFound)));
        assert_eq!(files.stamp(a), None);
        assert_eq!(
            files.canonical(Path::new("/scenes/parts/../a.pts")),
            PathBuf::from("/scenes/a.pts")
        );
    }

    #[test]
    fn a_held_buffer_wins_over_the_disk() {
        let dir = tempfile::tempdir().unwrap();
        let (held, below) = (dir.path().join("held.pts"), dir.path().join("below.pts"));
        std::fs::write(&held, "on disk").unwrap();
        std::fs::write(&below, "only on disk").unwrap();
        let mut files = MemoryFiles::over_disk();
        files.insert(held.clone(), "unsaved");
        assert_eq!(files.read(&held, 100).unwrap(), b"unsaved");
        assert_eq!(files.read(&below, 100).unwrap(), b"only on disk");
        assert!(files.stamp(&below).is_some());
        files.remove(&held);
        assert_eq!(files.read(&held, 100).unwrap(), b"on disk");
    }

    #[test]
    fn asked_remembers_each_path_once_in_order() {
        let mut memory = MemoryFiles::new();
        memory.insert("/a", "x");
        let asked = Asked::new(&memory);
        let _ = asked.read(Path::new("/a"), 10);
        let _ = asked.exists(Path::new("/missing"));
        let _ = asked.read(Path::new("/a"), 10);
        let _ = asked.canonical(Path::new("/b"));
        assert_eq!(
            asked.paths(),
            [PathBuf::from("/a"), PathBuf::from("/missing")]
        );
    }
}
