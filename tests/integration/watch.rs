//! `ptsc watch` driven like an editor would drive it: saves, broken saves,
//! atomic saves, edits of included files and meshes, bursts of saves; the
//! preview beside the image, never in it.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

const TIMEOUT: Duration = Duration::from_secs(20);

struct Watch {
    child: Child,
    lines: Arc<Mutex<Vec<String>>>,
}

impl Watch {
    fn start(scene: &Path) -> Watch {
        Watch::start_with(scene, &["--threads", "2"])
    }

    /// `ptsc watch SCENE ARGS…`.
    fn start_with(scene: &Path, args: &[&str]) -> Watch {
        let mut child = Command::new(env!("CARGO_BIN_EXE_ptsc"))
            .args(["watch", scene.to_str().unwrap()])
            .args(args)
            .stderr(Stdio::piped())
            .stdout(Stdio::null())
            .spawn()
            .unwrap();
        let lines = Arc::new(Mutex::new(Vec::new()));
        let sink = lines.clone();
        let stderr = child.stderr.take().unwrap();
        std::thread::spawn(move || {
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                sink.lock().unwrap().push(line);
            }
        });
        Watch { child, lines }
    }

    fn count(&self, needle: &str) -> usize {
        self.lines
            .lock()
            .unwrap()
            .iter()
            .filter(|l| l.contains(needle))
            .count()
    }

    /// Waits until `needle` has appeared more than `before` times.
    fn wait_for(&self, needle: &str, before: usize) {
        let t0 = Instant::now();
        while self.count(needle) <= before {
            assert!(
                t0.elapsed() < TIMEOUT,
                "no new `{needle}` within {TIMEOUT:?}; output:\n{}",
                self.lines.lock().unwrap().join("\n")
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Saves `text` to `path` and waits for the finished render of it.
    fn save_and_wait(&self, path: &Path, text: &str) {
        let done = self.count("done:");
        std::fs::write(path, text).unwrap();
        self.wait_for("done:", done);
    }

    fn output(&self) -> String {
        self.lines.lock().unwrap().join("\n")
    }

    /// Waits until the last line says `done:` and `image` holds `expected`.
    fn wait_for_image(&self, image: &Path, expected: &[u8], timeout: Duration) {
        let t0 = Instant::now();
        loop {
            std::thread::sleep(Duration::from_millis(100));
            let quiet = self
                .lines
                .lock()
                .unwrap()
                .last()
                .is_some_and(|l| l.contains("done:"));
            if quiet && std::fs::read(image).unwrap() == expected {
                return;
            }
            assert!(t0.elapsed() < timeout, "{}", self.output());
        }
    }
}

impl Drop for Watch {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn scene(fov: u32, extra: &str) -> String {
    format!(
        "render {{ resolution <32, 32> samples 4 }}\n\
         camera {{ position <0, 1, 5> look_at <0, 0.5, 0> fov {fov} }}\n\
         background rgb 0.5\n\
         plane {{ normal <0, 1, 0> }}\n\
         sphere {{ center <0, 0.5, 0> radius 0.5 material {{ diffuse rgb <0.8, 0.2, 0.2> }} }}\n\
         {extra}\n"
    )
}

fn setup() -> (tempfile::TempDir, PathBuf, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let pts = dir.path().join("s.pts");
    let png = dir.path().join("s.png");
    (dir, pts, png)
}

/// `watch` started on the first scene (field of view 40), done rendering it.
fn watching_first_scene(pts: &Path) -> Watch {
    std::fs::write(pts, scene(40, "")).unwrap();
    let w = Watch::start(pts);
    w.wait_for("done:", 0);
    w
}

/// What `ptsc render` makes of the same scene (renders are deterministic).
fn reference_render(pts: &Path) -> Vec<u8> {
    let out = pts.with_file_name("reference.png");
    let status = Command::new(env!("CARGO_BIN_EXE_ptsc"))
        .args(["render", pts.to_str().unwrap(), "-o", out.to_str().unwrap()])
        .stderr(Stdio::null())
        .status()
        .unwrap();
    assert!(status.success());
    let bytes = std::fs::read(&out).unwrap();
    std::fs::remove_file(out).unwrap();
    bytes
}

#[test]
fn edits_render_broken_edits_keep_the_image_and_fixes_render_again() {
    let (_dir, pts, png) = setup();
    let w = watching_first_scene(&pts);
    let first = std::fs::read(&png).unwrap();
    // Nothing was saved yet: the first preview counts from the start, and
    // each render's lines carry its number.
    assert!(w.output().contains("ms after starting)"), "{}", w.output());
    assert!(w.output().contains("render 1: done:"), "{}", w.output());

    w.save_and_wait(&pts, &scene(30, ""));
    let second = std::fs::read(&png).unwrap();
    assert_ne!(first, second, "the edit changed the image");
    assert_eq!(second, reference_render(&pts));

    // A broken save: diagnostics, and the image stays byte for byte.
    let errors = w.count("keeping the last image");
    std::fs::write(&pts, scene(30, "sphere { radius -1 ")).unwrap();
    w.wait_for("keeping the last image", errors);
    assert!(w.output().contains("never closed"), "{}", w.output());
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(std::fs::read(&png).unwrap(), second);

    // The fix renders again.
    w.save_and_wait(&pts, &scene(35, ""));
    assert_eq!(std::fs::read(&png).unwrap(), reference_render(&pts));
}

#[test]
fn fifty_rapid_saves_end_with_the_last_scene() {
    let (dir, pts, png) = setup();
    let w = watching_first_scene(&pts);
    for i in 0..50 {
        std::fs::write(&pts, scene(20 + i, "")).unwrap();
        std::thread::sleep(Duration::from_millis(7 * (i % 5) as u64));
    }
    // Let the last batch render to the end.
    w.wait_for_image(&png, &reference_render(&pts), TIMEOUT);
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names.len(),
        3,
        "only the scene, its image and its preview remain: {names:?}"
    );
    assert!(!w.output().contains("panicked"));
}

#[test]
fn atomic_saves_includes_and_meshes_trigger_renders() {
    let (dir, pts, _png) = setup();
    let part = dir.path().join("part.ptsi");
    let obj = dir.path().join("tri.obj");
    std::fs::write(&part, "sphere { center <1, 0.3, 0> radius 0.3 }\n").unwrap();
    std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let text = |fov: u32| {
        scene(
            fov,
            "include \"part.ptsi\"\nmesh { file \"tri.obj\" translate <-1.5, 0, 0> }",
        )
    };
    std::fs::write(&pts, text(40)).unwrap();
    let w = Watch::start(&pts);
    w.wait_for("done:", 0);
    assert_eq!(w.count("1 mesh file(s) loaded"), 1);

    // Editor-style atomic save: write a temporary file, rename it over.
    let done = w.count("done:");
    let tmp = dir.path().join(".s.pts.swp");
    std::fs::write(&tmp, text(30)).unwrap();
    std::fs::rename(&tmp, &pts).unwrap();
    w.wait_for("done:", done);

    // A camera-only edit reuses the mesh and the BVH.
    assert_eq!(
        w.count("0 mesh file(s) loaded, geometry reused"),
        1,
        "{}",
        w.output()
    );

    // The included file.
    w.save_and_wait(&part, "sphere { center <1, 0.6, 0> radius 0.3 }\n");
    assert_eq!(w.count("geometry rebuilt"), 2, "{}", w.output());

    // The mesh file: reloaded.
    w.save_and_wait(&obj, "v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n");
    assert_eq!(w.count("1 mesh file(s) loaded"), 2, "{}", w.output());
}

#[test]
fn ctrl_c_stops_cleanly() {
    let (_dir, pts, _png) = setup();
    let mut w = watching_first_scene(&pts);
    let status = Command::new("kill")
        .args(["-INT", &w.child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let t0 = Instant::now();
    let code = loop {
        if let Some(s) = w.child.try_wait().unwrap() {
            break s.code();
        }
        assert!(t0.elapsed() < TIMEOUT);
        std::thread::sleep(Duration::from_millis(20));
    };
    assert_eq!(code, Some(0));
}

/// The kinds of save the soak test mixes: valid, broken, huge and hostile.
fn soak_save(k: usize) -> Vec<u8> {
    let valid = || scene(20 + (k % 40) as u32, "");
    match k % 12 {
        0 => valid().into_bytes(),
        1 => scene(30, "sphere { radius -1 ").into_bytes(),
        // A megabyte of constants: parsed and checked, then rendered.
        2 => {
            let mut s = valid();
            for i in 0..60_000 {
                s.push_str(&format!("let _a{i} = {i};\n"));
            }
            s.into_bytes()
        }
        3 => format!(
            "{}{}let x = 1;",
            valid().replace('\n', " "),
            " ".repeat(70_000)
        )
        .into_bytes(),
        4 => scene(30, &format!("let _c = {};", vec!["1"; 30_000].join(" * "))).into_bytes(),
        5 => scene(30, &format!("background {}1", "rgb ".repeat(3_000))).into_bytes(),
        6 => scene(30, "include \"/dev/zero\"").into_bytes(),
        7 => valid().replace("fov", "shutter <0, 1e39> fov").into_bytes(),
        8 => scene(30, "for i in 0..100000000 { }").into_bytes(),
        9 => {
            let mut b = valid().into_bytes();
            b.extend_from_slice(b"\xff\xfe sphere {");
            b
        }
        10 => Vec::new(),
        _ => scene(30, "point_light { position <0, 5, 0> intensity rgb 1e38 }").into_bytes(),
    }
}

#[test]
fn watch_survives_hundreds_of_hostile_saves() {
    let (_dir, pts, png) = setup();
    let mut w = watching_first_scene(&pts);
    let outcomes = |w: &Watch| w.count("keeping the last image") + w.count("compiled in");
    for k in 0..240 {
        // A third of the saves wait for their compile (each kind in turn);
        // the rest arrive in bursts, batched.
        let alone = (k + k / 12) % 3 == 0;
        let before = outcomes(&w);
        std::fs::write(&pts, soak_save(k)).unwrap();
        if alone {
            let t0 = Instant::now();
            while outcomes(&w) <= before {
                assert!(
                    t0.elapsed() < TIMEOUT,
                    "no compile after save {k}:\n{}",
                    w.output()
                );
                std::thread::sleep(Duration::from_millis(10));
            }
        } else {
            std::thread::sleep(Duration::from_millis(3 * (k % 7) as u64));
        }
        if k % 40 == 39 {
            assert!(
                w.child.try_wait().unwrap().is_none(),
                "watch died after save {k}:\n{}",
                w.output()
            );
        }
    }
    // The last save is a good scene: its image is the render of it.
    std::fs::write(&pts, scene(33, "")).unwrap();
    w.wait_for_image(&png, &reference_render(&pts), TIMEOUT * 3);
    assert!(w.child.try_wait().unwrap().is_none(), "watch ended");
    let out = w.output();
    for bad in ["panicked", "overflowed", "memory allocation"] {
        assert!(!out.contains(bad), "`{bad}` in:\n{out}");
    }
    // Each hostile kind was answered with its diagnostic at least once.
    for said in [
        "never closed",
        "`rgb` of `rgb`",
        "not a regular file",
        "shutter",
        "UTF-8",
    ] {
        assert!(out.contains(said), "no `{said}` in:\n{out}");
    }
}

#[test]
fn an_output_folder_that_disappears_is_reported_not_claimed() {
    let (dir, pts, _png) = setup();
    let out_dir = dir.path().join("out");
    std::fs::create_dir(&out_dir).unwrap();
    let img = out_dir.join("img.png");
    std::fs::write(&pts, scene(40, "")).unwrap();
    let w = Watch::start_with(&pts, &["-o", img.to_str().unwrap()]);
    w.wait_for("done:", 0);
    std::fs::remove_dir_all(&out_dir).unwrap();
    let before = w.count("keeping the last image");
    std::fs::write(&pts, scene(30, "")).unwrap();
    w.wait_for("keeping the last image", before);
    assert!(w.output().contains("does not exist"), "{}", w.output());
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(w.count("done:"), 1, "{}", w.output());
    // The folder back: the next save renders.
    std::fs::create_dir(&out_dir).unwrap();
    w.save_and_wait(&pts, &scene(35, ""));
    assert!(img.is_file());
}

#[test]
fn the_preview_goes_beside_the_image_never_into_it() {
    let (dir, pts, png) = setup();
    let preview = dir.path().join("s.preview.png");
    // Large enough that the full-resolution pass takes a while after the
    // preview: the old preview-in-the-image would stay for many polls.
    let text = scene(40, "").replace("<32, 32>", "<320, 240>");
    std::fs::write(&pts, &text).unwrap();
    // Every version of the image a viewer could have read.
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let (stop2, png2) = (stop.clone(), png.clone());
    let poll = std::thread::spawn(move || {
        let mut seen: Vec<Vec<u8>> = Vec::new();
        while !stop2.load(std::sync::atomic::Ordering::Relaxed) {
            if let Ok(b) = std::fs::read(&png2) {
                if seen.last() != Some(&b) {
                    seen.push(b);
                }
            }
            std::thread::sleep(Duration::from_millis(1));
        }
        seen
    });
    let w = Watch::start(&pts);
    w.wait_for("done:", 0);
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    let seen = poll.join().unwrap();
    let out = w.output();
    assert!(
        out.contains(&format!("→ {}", preview.display())),
        "the preview line names its file:\n{out}"
    );
    // The preview is a quarter of the image's width and height, in its format.
    let shot = std::fs::read(&preview).unwrap();
    let size = |b: &[u8]| image::load_from_memory(b).unwrap().to_rgb8().dimensions();
    assert_eq!(size(&shot), (80, 60));
    assert_eq!(std::fs::read(&png).unwrap(), reference_render(&pts));
    // Every version of the image is a full-resolution pass, none the
    // preview enlarged (whose 4×4 blocks would each be one colour).
    assert!(!seen.is_empty());
    for b in &seen {
        let img = image::load_from_memory(b).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), (320, 240));
        let blocky = (0..60).all(|by| {
            (0..80).all(|bx| {
                let corner = img.get_pixel(4 * bx, 4 * by);
                (0..16).all(|k| img.get_pixel(4 * bx + k % 4, 4 * by + k / 4) == corner)
            })
        });
        assert!(!blocky, "the image held the enlarged preview");
    }
}

#[test]
fn an_output_that_cannot_be_written_is_refused_before_watching() {
    // As `render` refuses it: exit 2 at once, naming the folder.
    let (dir, pts, _png) = setup();
    std::fs::write(&pts, scene(40, "")).unwrap();
    let img = dir.path().join("no_such_folder").join("img.png");
    let (code, _, err) =
        crate::ptsc(&["watch", pts.to_str().unwrap(), "-o", img.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("does not exist"), "{err}");
}

/// The flags of a batch render's end (`--denoise`, `--aov`, `--time`) are
/// refused by `watch` with a word, not silently ignored.
#[test]
fn watch_refuses_the_flags_of_a_batch_renders_end() {
    let (_dir, pts, _png) = setup();
    std::fs::write(&pts, scene(40, "")).unwrap();
    for flags in [&["--denoise"][..], &["--aov", "albedo"], &["--time", "10s"]] {
        let out = Command::new(env!("CARGO_BIN_EXE_ptsc"))
            .arg("watch")
            .arg(&pts)
            .args(flags)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            err.contains(flags[0]) && err.contains("ptsc render"),
            "{err}"
        );
    }
}

/// `watch --help` lists what watch takes: not the flags it refuses, nor
/// stdin, and --frames as watch reads it (one frame).
#[test]
fn watch_help_lists_only_what_watch_takes() {
    let (code, help, _) = crate::ptsc(&["watch", "--help"]);
    assert_eq!(code, 0);
    for refused in [
        "--time",
        "--denoise",
        "--aov",
        "--tev",
        "reads it from stdin",
    ] {
        assert!(!help.contains(refused), "{refused} in\n{help}");
    }
    for taken in ["--spp", "--frame ", "--output", "watch renders one of them"] {
        assert!(help.contains(taken), "no {taken} in\n{help}");
    }
    // `render --help` keeps them all.
    let (_, help, _) = crate::ptsc(&["render", "--help"]);
    for flag in ["--time", "--denoise", "--aov", "--tev", "stdin"] {
        assert!(help.contains(flag), "no {flag} in\n{help}");
    }
}

/// `watch --frames A..B` renders one frame, and says so.
#[test]
fn watch_of_several_frames_says_it_renders_one() {
    let (_dir, pts, png) = setup();
    std::fs::write(&pts, scene(40, "")).unwrap();
    let w = Watch::start_with(
        &pts,
        &[
            "--threads",
            "2",
            "--frames",
            "1..3",
            "-o",
            png.to_str().unwrap(),
        ],
    );
    w.wait_for(
        "warning: watch renders one frame: frame 1 of --frames 1..3",
        0,
    );
}

#[test]
fn light_paths_land_in_the_preview_as_in_the_render() {
    // bdpt and ptlt splat their light paths' joins to the camera into other
    // pixels; watch's passes (1, 2, 4 samples) must end on the image that
    // `render` makes in its own passes.
    for integrator in ["bdpt", "ptlt"] {
        let (_dir, pts, png) = setup();
        let lamp = "sphere { center <1, 2, 1> radius 0.2 material { emission rgb 20 } }\n\
             sphere { center <-1, 0.5, 0> radius 0.5 material { transmission 1 ior 1.5 } }";
        let text = scene(40, lamp).replace(
            "samples 4 }",
            &format!("samples 4 integrator {integrator} }}"),
        );
        assert!(text.contains(integrator));
        std::fs::write(&pts, &text).unwrap();
        let w = Watch::start(&pts);
        w.wait_for("done:", 0);
        assert_eq!(
            std::fs::read(&png).unwrap(),
            reference_render(&pts),
            "{integrator}: {}",
            w.output()
        );
    }
}
