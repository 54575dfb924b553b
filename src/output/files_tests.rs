use super::*;

#[test]
fn runs_of_hashes_become_the_frame_number_padded_to_their_length() {
    assert_eq!(number_frame("frame_####.png", 12), "frame_0012.png");
    assert_eq!(number_frame("a#/b_##.exr", 7), "a7/b_07.exr");
    // A number longer than its run is written whole.
    assert_eq!(number_frame("f_##.png", 12345), "f_12345.png");
    assert_eq!(number_frame("plain.png", 3), "plain.png");
}

#[test]
fn a_run_wider_than_any_format_width_makes_a_name_that_is_refused() {
    // `format!` panics on widths past 65,535.
    let pattern = format!("{}.png", "#".repeat(70_000));
    let name = number_frame(&pattern, 7);
    assert_eq!(name.len(), 70_004);
    assert!(name.ends_with("0007.png"));
    let why = check_writable(Path::new(&name)).unwrap_err();
    assert!(why.contains("70004 bytes long"), "{why}");
}

#[test]
fn paths_that_name_folders_or_other_things_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let at = |name: &str| dir.path().join(name);
    let slash = format!("{}/", at("out.png").display());
    assert!(check_writable(Path::new(&slash))
        .unwrap_err()
        .contains("names a folder"));
    std::fs::create_dir(at("sub")).unwrap();
    assert!(check_writable(&at("sub"))
        .unwrap_err()
        .contains("is a folder"));
    assert!(check_writable(&at("missing/out.png"))
        .unwrap_err()
        .contains("does not exist"));
    let fifo = at("pipe.png");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        assert!(check_writable(&fifo).unwrap_err().contains("FIFO"));
    }
    let long = at(&format!("{}.png", "a".repeat(300)));
    assert!(check_writable(&long).unwrap_err().contains("at most 255"));
    // A fine path is left as it was: nothing created, nothing left over.
    assert_eq!(check_writable(&at("out.png")), Ok(()));
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().flatten().collect();
    assert_eq!(left.len(), 2, "only the folder and the FIFO: {left:?}");
}

#[test]
fn threads_checking_one_path_at_once_do_not_take_each_others_probe() {
    // One temporary name per process let one thread's probe rename take
    // the other's file away ("a file cannot take its place: No such file").
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    std::thread::scope(|s| {
        let runs: Vec<_> = (0..8)
            .map(|_| s.spawn(|| (0..50).map(|_| check_writable(&out)).collect::<Vec<_>>()))
            .collect();
        for run in runs {
            for result in run.join().unwrap() {
                assert_eq!(result, Ok(()));
            }
        }
    });
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().flatten().collect();
    assert!(left.is_empty(), "{left:?}");
}

#[test]
fn a_folder_refusing_new_files_says_why_in_words() {
    use std::io::{Error, ErrorKind};
    let said = |kind: ErrorKind| why_no_new_file(&Error::from(kind));
    assert!(said(ErrorKind::NotFound).contains("virtual folder"));
    assert!(said(ErrorKind::PermissionDenied).contains("permission denied"));
    assert!(said(ErrorKind::ReadOnlyFilesystem).contains("read-only"));
    // The kernel's /proc takes no files (where this machine has one).
    if Path::new("/proc/self").is_dir() {
        let why = check_writable(Path::new("/proc/out.png")).unwrap_err();
        assert!(why.contains("/proc does not take new files"), "{why}");
        assert!(!why.contains("No such file"), "{why}");
    }
}

#[test]
fn long_names_write_through_a_temporary_file_that_fits() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir
        .path()
        .join(format!("{}.png", "b".repeat(MAX_FILE_NAME - 4)));
    assert_eq!(check_writable(&path), Ok(()));
    write_atomically(&path, b"x").unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"x");
}

#[test]
fn temporary_files_of_dead_runs_are_removed_by_the_next_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    // A process that has ended: its PID names no running process (PIDs are
    // not reused this quickly).
    let mut child = std::process::Command::new("true").spawn().unwrap();
    let dead = child.id();
    child.wait().unwrap();
    let host = host();
    let stale = [
        format!(".out.png.{host}.{dead}-3.tmp"),
        format!(".out.png.{host}.{dead}.tmp"),
        format!(".out.png.{dead}.tmp"),
    ];
    let kept = [
        // Another machine's, another output's.
        format!(".out.png.elsewhere.{dead}.tmp"),
        format!(".other.png.{host}.{dead}.tmp"),
    ];
    for name in stale.iter().chain(&kept) {
        std::fs::write(dir.path().join(name), b"samples").unwrap();
    }
    check_writable(&out).unwrap();
    for name in &stale {
        assert!(!dir.path().join(name).exists(), "{name} stays");
    }
    for name in &kept {
        assert!(dir.path().join(name).exists(), "{name} went");
    }
}

#[cfg(unix)]
#[test]
fn a_link_is_written_through_and_stays_a_link() {
    use std::os::unix::fs::symlink;
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("real.png");
    std::fs::write(&target, b"old").unwrap();
    let link = dir.path().join("link.png");
    symlink("real.png", &link).unwrap();
    assert_eq!(check_writable(&link), Ok(()));
    write_atomically(&link, b"new").unwrap();
    assert!(is_link(&link));
    assert_eq!(std::fs::read(&target).unwrap(), b"new");
    // A dangling link's target is made where it points, in its own folder.
    std::fs::create_dir(dir.path().join("elsewhere")).unwrap();
    let dangling = dir.path().join("dangling.png");
    symlink("elsewhere/made.png", &dangling).unwrap();
    assert_eq!(check_writable(&dangling), Ok(()));
    write_atomically(&dangling, b"made").unwrap();
    assert!(is_link(&dangling));
    assert_eq!(
        std::fs::read(dir.path().join("elsewhere/made.png")).unwrap(),
        b"made"
    );
    // A link into a missing folder is refused before any work, a cycle too.
    let nowhere = dir.path().join("nowhere.png");
    symlink("missing/x.png", &nowhere).unwrap();
    assert!(check_writable(&nowhere)
        .unwrap_err()
        .contains("does not exist"));
    symlink("loop_b.png", dir.path().join("loop_a.png")).unwrap();
    symlink("loop_a.png", dir.path().join("loop_b.png")).unwrap();
    let why = check_writable(&dir.path().join("loop_a.png")).unwrap_err();
    assert!(why.contains("more than 40 links"), "{why}");
    assert!(write_atomically(&dir.path().join("loop_a.png"), b"x").is_err());
}

#[cfg(unix)]
#[test]
fn a_replaced_file_keeps_its_mode_and_a_read_only_one_is_refused() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let shared = dir.path().join("shared.png");
    std::fs::write(&shared, b"old").unwrap();
    std::fs::set_permissions(&shared, std::fs::Permissions::from_mode(0o640)).unwrap();
    write_atomically(&shared, b"new").unwrap();
    let mode = std::fs::metadata(&shared).unwrap().permissions().mode();
    assert_eq!(mode & 0o777, 0o640);
    let kept = dir.path().join("kept.png");
    std::fs::write(&kept, b"keep me").unwrap();
    std::fs::set_permissions(&kept, std::fs::Permissions::from_mode(0o444)).unwrap();
    let why = check_writable(&kept).unwrap_err();
    assert!(why.contains("read-only"), "{why}");
    assert!(write_atomically(&kept, b"x").is_err());
    assert_eq!(std::fs::read(&kept).unwrap(), b"keep me");
}

#[cfg(unix)]
fn is_link(path: &Path) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink())
}
