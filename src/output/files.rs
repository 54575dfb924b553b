//! Where outputs go: every path a run will write is checked before its
//! first sample ([`check_writable`]); files are written atomically through
//! a temporary file beside the target (a failed or interrupted run never
//! leaves a broken file), and temporary files that a killed run left
//! behind are removed by the next run of the same output.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// The longest file name (one path component) ptsc writes, in bytes: what
/// Linux, macOS and Windows file systems hold.
pub const MAX_FILE_NAME: usize = 255;

/// Names longer than this get a temporary file named by their hash, so
/// that the temporary name (name, host, process) still fits a file name.
const LONG_NAME: usize = 160;

/// A path as messages show it: whole, or its start and end around an
/// ellipsis when longer than a line (a 65,536-character `#` pattern).
pub fn shown(path: &Path) -> String {
    let text = path.display().to_string();
    let chars: Vec<char> = text.chars().collect();
    if chars.len() <= 120 {
        return text;
    }
    let (head, tail): (String, String) = (
        chars[..50].iter().collect(),
        chars[chars.len() - 50..].iter().collect(),
    );
    format!("{head}…{tail} ({} characters)", chars.len())
}

/// Why nothing can be written at `path`, found before a run starts rather
/// than after it: a path that names a folder (a trailing `/`) or something
/// other than a file, a file name longer than a file system holds, a
/// folder that is missing or takes no new file. Temporary files of dead
/// runs writing the same path are removed first.
pub fn check_writable(path: &Path) -> Result<(), String> {
    let text = path.as_os_str().to_string_lossy();
    if text.ends_with(std::path::is_separator) || text.ends_with("/.") || text.ends_with("/..") {
        return Err("it names a folder (it ends with a separator); name a file".into());
    }
    // A link is written through: what is checked is the file it names.
    let path = &link_target(path).map_err(|e| e.to_string())?;
    let name = path.file_name().ok_or("it names no file")?;
    if name.len() > MAX_FILE_NAME {
        return Err(format!(
            "its file name is {} bytes long; a file name holds at most {MAX_FILE_NAME}",
            name.len()
        ));
    }
    if let Ok(meta) = std::fs::metadata(path) {
        if meta.is_dir() {
            return Err("it is a folder; name a file in it".into());
        }
        if !meta.is_file() {
            return Err(format!("it is {}, not a file", kind_of(&meta)));
        }
        if meta.permissions().readonly() {
            return Err(READ_ONLY.into());
        }
    }
    let dir = folder_of(path);
    if !dir.is_dir() {
        return Err(format!("the folder {} does not exist", dir.display()));
    }
    remove_stale_temporaries(path);
    let probe = temporary_beside(path).map_err(|e| e.to_string())?;
    std::fs::File::create(&probe).map_err(|e| {
        let why = why_no_new_file(&e);
        format!(
            "the folder {} does not take new files: {why}",
            dir.display()
        )
    })?;
    // Where nothing is at the path yet, the probe takes its place as the
    // real write will (a rename), then goes.
    let renamed = match std::fs::symlink_metadata(path) {
        Err(_) => std::fs::rename(&probe, path).map(|()| std::fs::remove_file(path)),
        Ok(_) => Ok(Ok(())),
    };
    let _ = std::fs::remove_file(&probe);
    match renamed {
        Err(e) => Err(format!("a file cannot take its place: {e}")),
        Ok(_) => Ok(()),
    }
}

/// Why an existing folder refused a new file, in words: the system's own
/// message ("No such file or directory") contradicts a folder that is there.
fn why_no_new_file(e: &std::io::Error) -> String {
    use std::io::ErrorKind;
    match e.kind() {
        ErrorKind::PermissionDenied => "you may not write in it (permission denied)".into(),
        ErrorKind::ReadOnlyFilesystem => "it is on a read-only file system".into(),
        ErrorKind::StorageFull => "the disk is full".into(),
        ErrorKind::QuotaExceeded => "your disk quota is used up".into(),
        // Creating a file in /proc or /sys: the folder exists but is the
        // kernel's view, which holds no files of ours.
        ErrorKind::NotFound => {
            "it is a virtual folder of the system (as /proc and /sys are)".into()
        }
        _ => e.to_string(),
    }
}

/// What a non-file is, in words.
fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_socket() {
            return "a socket";
        }
        if t.is_block_device() || t.is_char_device() {
            return "a device";
        }
    }
    let _ = meta;
    "not a regular file"
}

/// The folder a file goes in (`.` for a bare name).
fn folder_of(path: &Path) -> &Path {
    path.parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// The start of every temporary file name of writes to `path`:
/// `.NAME.` (or `.ptsc-HASH.` for a long name).
fn temporary_prefix(path: &Path) -> std::io::Result<String> {
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidInput, "no file name"))?
        .to_string_lossy();
    if name.len() > LONG_NAME {
        // FNV-1a: stable from run to run, so the next run finds them.
        let hash = (name.bytes()).fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
            (h ^ b as u64).wrapping_mul(0x100_0000_01b3)
        });
        return Ok(format!(".ptsc-{hash:016x}."));
    }
    Ok(format!(".{name}."))
}

/// This machine's name as temporary file names carry it (letters, digits
/// and `-`): a folder shared by machines (a farm's network disk) holds
/// temporary files of processes this one cannot see.
fn host() -> String {
    let name = std::fs::read_to_string("/proc/sys/kernel/hostname")
        .or_else(|_| std::fs::read_to_string("/etc/hostname"))
        .unwrap_or_default();
    let clean: String = (name.trim().chars())
        .filter(|c| c.is_ascii_alphanumeric() || *c == '-')
        .take(64)
        .collect();
    if clean.is_empty() {
        "host".into()
    } else {
        clean
    }
}

/// The temporary file an atomic write of `path` goes through:
/// `.NAME.HOST.PID-N.tmp` beside it, N counting this process's writes and
/// probes: two threads checking or writing one path at once (tests, an
/// editor's compile beside a render) each have their own, where one name
/// per process let one thread's rename take the other's file away.
fn temporary_beside(path: &Path) -> std::io::Result<PathBuf> {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let prefix = temporary_prefix(path)?;
    let file = format!("{prefix}{}.{}-{n}.tmp", host(), std::process::id());
    Ok(folder_of(path).join(file))
}

/// Removes the temporary files of writes to `path` whose process is gone
/// (killed before it could clean up): those of this machine (`.NAME.HOST.
/// PID-N.tmp`, `.NAME.HOST.PID.tmp` and `.NAME.PID.tmp` of earlier
/// versions) whose process no
/// longer runs. Where processes cannot be seen (no /proc), nothing goes.
fn remove_stale_temporaries(path: &Path) {
    let (Ok(prefix), true) = (temporary_prefix(path), Path::new("/proc/self").exists()) else {
        return;
    };
    let Ok(entries) = std::fs::read_dir(folder_of(path)) else {
        return;
    };
    let (host, me) = (host(), std::process::id());
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(middle) = (name.strip_prefix(&prefix)).and_then(|m| m.strip_suffix(".tmp")) else {
            continue;
        };
        let (writer_host, pid) = match middle.rsplit_once('.') {
            Some((h, pid)) => (h, pid),
            None => (host.as_str(), middle),
        };
        // `PID-N` (this version's) or `PID` (earlier ones').
        let pid = pid.split_once('-').map_or(pid, |(pid, _)| pid);
        let Ok(pid) = pid.parse::<u32>() else {
            continue;
        };
        let gone = !Path::new(&format!("/proc/{pid}")).exists();
        if writer_host == host && pid != me && gone && entry.path().is_file() {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Why a read-only file is not replaced: its mode says to keep it.
const READ_ONLY: &str = "it is read-only; make it writable (chmod u+w) or name another file";

/// The most links followed from one path (as Linux's `ELOOP`).
const MAX_LINKS: usize = 40;

/// The file that `path` names once every symbolic link on it is followed
/// (a link's relative target is relative to the link's folder); `path`
/// itself when it is no link. The target need not exist (a dangling
/// link's is where the file goes), but a cycle of links is an error.
pub fn link_target(path: &Path) -> std::io::Result<PathBuf> {
    let mut at = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&at) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let to = std::fs::read_link(&at)?;
                at = folder_of(&at).join(to);
            }
            _ => return Ok(at),
        }
    }
    Err(std::io::Error::other(format!(
        "{} is a link that leads through more than {MAX_LINKS} links (a cycle?)",
        path.display()
    )))
}

/// Writes a file atomically: `write` fills a temporary file beside `path`
/// (buffered, so it may stream any size in bounded memory), which is
/// synced and renamed over `path`; on failure the temporary file goes and
/// `path` is untouched. A link at `path` stays: the file it names is the
/// one replaced, keeping its mode; a read-only file is refused.
pub fn write_atomically_with(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<std::fs::File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let path = &link_target(path)?;
    let kept_mode = match std::fs::metadata(path) {
        Ok(meta) if meta.permissions().readonly() => {
            return Err(std::io::Error::new(
                std::io::ErrorKind::PermissionDenied,
                READ_ONLY,
            ))
        }
        Ok(meta) if meta.is_file() => Some(meta.permissions()),
        _ => None,
    };
    let tmp = temporary_beside(path)?;
    let result = (|| {
        let mut out = BufWriter::with_capacity(1 << 20, std::fs::File::create(&tmp)?);
        write(&mut out)?;
        let file = out.into_inner().map_err(|e| e.into_error())?;
        if let Some(mode) = kept_mode {
            file.set_permissions(mode)?;
        }
        file.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Writes `bytes` to `path` atomically ([`write_atomically_with`]).
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomically_with(path, |out| out.write_all(bytes))
}

/// Whether two paths name one existing file (through links and `..`).
pub fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// An output path with each run of `#` replaced by `frame`, zero-padded to
/// the run's length (`frame_####.png` → `frame_0012.png`). A run longer
/// than a file name is refused by [`check_writable`] afterwards, as the
/// name it makes.
pub fn frame_path(path: &Path, frame: u32) -> PathBuf {
    match path.to_str() {
        Some(text) if text.contains('#') => PathBuf::from(number_frame(text, frame)),
        _ => path.to_path_buf(),
    }
}

/// Replaces each run of `#` with `frame`, zero-padded to the run's length
/// (padded by hand: `format!`'s width stops at 65,535).
fn number_frame(pattern: &str, frame: u32) -> String {
    let digits = frame.to_string();
    let mut out = String::with_capacity(pattern.len() + digits.len());
    let mut run = 0;
    let flush = |out: &mut String, run: &mut usize| {
        if *run > 0 {
            out.extend(std::iter::repeat_n('0', run.saturating_sub(digits.len())));
            out.push_str(&digits);
            *run = 0;
        }
    };
    for c in pattern.chars() {
        if c == '#' {
            run += 1;
        } else {
            flush(&mut out, &mut run);
            out.push(c);
        }
    }
    flush(&mut out, &mut run);
    out
}

#[cfg(test)]
#[path = "files_tests.rs"]
mod tests;
