//! Long renders and farms through the binary: passes merged equal one
//! render, a stopped render resumed equals an uninterrupted one, samples
//! added to a finished render equal a render of them all, foreign or
//! duplicate states are refused, frames number their images, and the
//! schedulers' files are well formed.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use crate::ptsc_stderr as ptsc;

/// Renders `scene` with `extra` arguments into `out`; panics on failure.
fn render(scene: &Path, out: &Path, extra: &[&str]) -> String {
    let mut args = vec![
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend(extra);
    let (code, err) = ptsc(&args);
    assert_eq!(code, 0, "{args:?}: {err}");
    err
}

/// A small scene with glossy reflection, a textured floor and an area
/// light: several paths per sample, random numbers drawn at many depths.
const SCENE: &str = "camera { position <0, 1, 4> look_at <0, 0.5, 0> }\n\
    background rgb 0.3\n\
    plane { normal <0, 1, 0> material { diffuse checker { even rgb 0.8 odd rgb 0.2 space world scale 0.5 } } }\n\
    sphere { center <0, 0.5, 0> radius 0.5 material { reflection rgb 0.8 gloss 0.2 } }\n\
    sphere { center <1, 2, 1> radius 0.3 material { emission rgb 8 } }\n\
    render { resolution <24, 20> }\n";

fn pixels(path: &Path) -> Vec<glam::Vec3> {
    ptsc::output::read_exr(path).unwrap().2
}

/// The largest relative difference of two images, pixel by pixel.
fn max_relative_difference(a: &[glam::Vec3], b: &[glam::Vec3]) -> f32 {
    assert_eq!(a.len(), b.len());
    (a.iter().zip(b))
        .map(|(x, y)| {
            ((*x - *y).abs() / x.abs().max(y.abs()).max(glam::Vec3::splat(1e-12))).max_element()
        })
        .fold(0.0, f32::max)
}

#[test]
fn passes_merged_in_any_order_equal_one_render() {
    let dir = crate::temp_dir_with(&[("s.pts", SCENE)]);
    let scene = dir.path().join("s.pts");
    let at = |name: &str| dir.path().join(name);
    render(&scene, &at("one.exr"), &["--spp", "14"]);
    render(&scene, &at("one.png"), &["--spp", "14"]);
    let one = pixels(&at("one.exr"));
    for n in [1u32, 3, 7] {
        let parts: Vec<PathBuf> = (1..=n).map(|k| at(&format!("part{n}_{k}.exr"))).collect();
        for (k, part) in (1..=n).zip(&parts) {
            let pass = format!("{k}/{n}");
            render(
                &scene,
                part,
                &["--spp", "14", "--pass", &pass, "--threads", "1"],
            );
        }
        // Given in reverse: merge adds passes in their order, not the arguments'.
        let mut args: Vec<String> = vec!["merge".into()];
        args.extend(parts.iter().rev().map(|p| p.display().to_string()));
        for out in ["merged.exr", "merged.png"] {
            let mut a = args.clone();
            a.extend(["-o".into(), at(out).display().to_string()]);
            let a: Vec<&str> = a.iter().map(String::as_str).collect();
            let (code, err) = ptsc(&a);
            assert_eq!(code, 0, "{err}");
            assert!(err.contains(&format!("merged {n} of {n} passes")), "{err}");
        }
        let d = max_relative_difference(&one, &pixels(&at("merged.exr")));
        assert!(d <= 1e-5, "N = {n}: max relative difference {d}");
        assert_eq!(
            std::fs::read(at("one.png")).unwrap(),
            std::fs::read(at("merged.png")).unwrap(),
            "N = {n}: the PNGs differ"
        );
    }
}

#[test]
fn merge_refuses_duplicate_foreign_and_missing_parts_by_name() {
    let dir = crate::temp_dir_with(&[("s.pts", SCENE)]);
    let scene = dir.path().join("s.pts");
    let at = |name: &str| dir.path().join(name).display().to_string();
    for k in 1..=3 {
        let pass = format!("{k}/3");
        render(
            &scene,
            Path::new(&at(&format!("p{k}.exr"))),
            &["--spp", "6", "--pass", &pass],
        );
    }
    // Another seed: a part of another image.
    render(
        &scene,
        Path::new(&at("seed.exr")),
        &["--spp", "6", "--pass", "2/3", "--seed", "9"],
    );
    // Another split of the same render.
    render(
        &scene,
        Path::new(&at("four.exr")),
        &["--spp", "6", "--pass", "2/4"],
    );
    // An edited scene.
    std::fs::write(
        dir.path().join("t.pts"),
        SCENE.replace("radius 0.5", "radius 0.45"),
    )
    .unwrap();
    let edited = dir.path().join("t.pts");
    render(
        &edited,
        Path::new(&at("edited.exr")),
        &["--spp", "6", "--pass", "2/3"],
    );
    let out = at("m.png");
    let merge = |parts: &[&str]| {
        let mut args = vec!["merge".to_string()];
        args.extend(parts.iter().map(|p| at(p)));
        args.extend(["-o".to_string(), out.clone()]);
        ptsc(&args.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let cases: [(&[&str], &str, &[&str]); 5] = [
        (
            &["p1.exr", "p2.exr", "p3.exr", "p2.exr"],
            "p2.exr",
            &["both hold pass 2/3"],
        ),
        (
            &["p1.exr", "seed.exr", "p3.exr"],
            "seed.exr",
            &["it was rendered with seed 9, "],
        ),
        (&["p1.exr", "four.exr", "p3.exr"], "four.exr", &["2/4"]),
        (
            &["p1.exr", "edited.exr", "p3.exr"],
            "edited.exr",
            &["it is a part of t.pts, "],
        ),
        (
            &["p1.exr", "p3.exr"],
            "",
            &["pass 2 of 3 is missing", "--partial"],
        ),
    ];
    for (parts, named, words) in cases {
        let (code, err) = merge(parts);
        assert_eq!(code, 2, "{parts:?}: {err}");
        assert!(err.contains(named), "{parts:?}: {err}");
        assert!(words.iter().any(|w| err.contains(w)), "{parts:?}: {err}");
        // Each value beside its own file, none in Rust's words.
        assert!(!err.contains("this render"), "{parts:?}: {err}");
        assert!(!Path::new(&out).exists(), "{parts:?}: nothing written");
    }
    // The image would replace a part.
    let mut args: Vec<String> = vec!["merge".into(), at("p1.exr"), at("p2.exr"), at("p3.exr")];
    args.extend(["-o".into(), at("p2.exr")]);
    let (code, err) = ptsc(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(code, 2);
    assert!(err.contains("one of the parts"), "{err}");
    // A plain image is no part.
    render(&scene, Path::new(&at("plain.exr")), &["--spp", "2"]);
    let (code, err) = merge(&["p1.exr", "plain.exr"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("plain.exr") && err.contains("no render state"),
        "{err}"
    );
    // A partial set, asked for: a warning, each pixel the mean of its samples.
    let mut args: Vec<String> = vec!["merge".into(), at("p1.exr"), at("p3.exr")];
    args.extend(["--partial".into(), "-o".into(), at("partial.exr")]);
    let (code, err) = ptsc(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("warning: pass 2 of 3 is missing"), "{err}");
    let partial = pixels(Path::new(&at("partial.exr")));
    let (p1, p3) = (
        pixels(Path::new(&at("p1.exr"))),
        pixels(Path::new(&at("p3.exr"))),
    );
    // Passes of 2 samples each: the mean of both parts' means.
    let mean: Vec<glam::Vec3> = p1.iter().zip(&p3).map(|(a, b)| (*a + *b) * 0.5).collect();
    assert!(max_relative_difference(&partial, &mean) < 1e-5);
}

/// Renders `scene` into `out` with `args` and SIGINT once its `-v` output
/// says the `after`-spp pass finished: the signal lands mid-render whatever
/// the machine's speed. Returns the exit code and stderr.
fn render_and_interrupt(
    scene: &Path,
    out: &Path,
    args: &[&str],
    after: u32,
) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_ptsc"))
        .args([
            "render",
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "-v",
        ])
        .args(args)
        .args(["--threads", "2"])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
    let mut seen = String::new();
    for line in lines.by_ref() {
        let line = line.unwrap();
        seen.push_str(&line);
        seen.push('\n');
        if line.contains(&format!("pass to {after} spp")) {
            break;
        }
    }
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status();
    assert!(kill.unwrap().success());
    let rest: Vec<String> = lines.map(Result::unwrap).collect();
    let status = child.wait().unwrap();
    (status.code(), seen + &rest.join("\n"))
}

#[test]
fn a_render_stopped_by_a_signal_resumes_to_the_uninterrupted_image() {
    let dir = crate::temp_dir_with(&[("s.pts", SCENE)]);
    let scene = dir.path().join("s.pts");
    let out = dir.path().join("stopped.exr");
    let args = ["--spp", "2048"];
    let (code, err) = render_and_interrupt(&scene, &out, &args, 16);
    assert_eq!(code, Some(130), "{err}");
    assert!(
        err.contains("interrupted:") && err.contains("--resume"),
        "{err}"
    );
    let state = dir.path().join("stopped.exr.state.exr");
    assert!(state.is_file(), "{err}");
    // Without --resume the saved state is not overwritten.
    let (code, err) = ptsc(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--resume") && err.contains("--restart"),
        "{err}"
    );
    let err = render(
        &scene,
        &out,
        &[&args[..], &["--resume", "--threads", "1"]].concat(),
    );
    assert!(err.contains("resuming "), "{err}");
    let whole = dir.path().join("whole.exr");
    render(&scene, &whole, &args);
    assert_eq!(
        pixels(&out),
        pixels(&whole),
        "the same samples, added in the same order"
    );
}

#[test]
fn an_interrupted_pass_is_refused_by_merge_until_resumed() {
    let dir = crate::temp_dir_with(&[("s.pts", SCENE)]);
    let scene = dir.path().join("s.pts");
    let at = |name: &str| dir.path().join(name);
    let spp = ["--spp", "1000"];
    render(
        &scene,
        &at("p1.exr"),
        &[&spp[..], &["--pass", "1/2"]].concat(),
    );
    // Pass 2 of 500 samples a pixel, stopped after its 16th.
    let pass2 = [&spp[..], &["--pass", "2/2"]].concat();
    let (code, err) = render_and_interrupt(&scene, &at("p2.exr"), &pass2, 16);
    assert_eq!(code, Some(130), "{err}");
    let merge = |extra: &[&str]| {
        let (p1, p2, out) = (at("p1.exr"), at("p2.exr"), at("m.exr"));
        let mut args = vec!["merge", p1.to_str().unwrap(), p2.to_str().unwrap()];
        args.extend(["-o", out.to_str().unwrap()]);
        args.extend(extra);
        ptsc(&args)
    };
    let (code, err) = merge(&[]);
    assert_eq!(code, 2);
    assert!(
        err.contains("p2.exr is unfinished") && err.contains("--resume"),
        "{err}"
    );
    let (code, err) = merge(&["--partial"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("warning: ") && err.contains("unfinished"),
        "{err}"
    );
    // The pass resumed from its part file, then merged: the single render.
    let resumed = render(&scene, &at("p2.exr"), &[&pass2[..], &["--resume"]].concat());
    assert!(resumed.contains("resuming pass 2/2"), "{resumed}");
    let (code, err) = merge(&[]);
    assert_eq!(code, 0, "{err}");
    render(&scene, &at("one.exr"), &spp);
    let d = max_relative_difference(&pixels(&at("one.exr")), &pixels(&at("m.exr")));
    assert!(d <= 1e-5, "max relative difference {d}");
}

#[test]
fn samples_added_to_a_finished_render_equal_a_render_of_them_all() {
    let dir = crate::temp_dir_with(&[("s.pts", SCENE)]);
    let scene = dir.path().join("s.pts");
    let out = dir.path().join("more.png");
    render(&scene, &out, &["--spp", "64", "--keep-state"]);
    let err = render(&scene, &out, &["--spp", "256", "--resume"]);
    assert!(err.contains("resuming a render of 64 spp"), "{err}");
    let whole = dir.path().join("whole.png");
    render(&scene, &whole, &["--spp", "256"]);
    assert_eq!(std::fs::read(&out).unwrap(), std::fs::read(&whole).unwrap());
    // Fewer samples than the state holds, another setting, another scene:
    // refused, naming what differs; a comment changes nothing.
    let text = |scene: &str| {
        std::fs::write(dir.path().join("s.pts"), scene).unwrap();
        let args = ["render", "s.pts", "-o", "more.png", "--resume"];
        let mut full: Vec<String> = args.iter().map(|a| a.to_string()).collect();
        full[1] = dir.path().join("s.pts").display().to_string();
        full[3] = out.display().to_string();
        full
    };
    let run = |args: Vec<String>, extra: &[&str]| {
        let mut a: Vec<&str> = args.iter().map(String::as_str).collect();
        a.extend(extra);
        ptsc(&a)
    };
    let (code, err) = run(text(SCENE), &["--spp", "100"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("it already has 256 samples in every pixel, more than the 100 asked"),
        "{err}"
    );
    let (code, err) = run(text(SCENE), &["--spp", "512", "--integrator", "whitted"]);
    assert_eq!(code, 2);
    assert!(
        err.contains(
            "it was rendered with the path integrator, this render with the whitted integrator"
        ),
        "{err}"
    );
    // Settings said as the flags spell them, never as Rust's values.
    for (flags, says) in [
        (
            &["--clamp", "1"][..],
            "it was rendered without --clamp, this render with --clamp 1",
        ),
        (
            &["--light-selection", "uniform"],
            "it was rendered with light selection auto, this render with light selection uniform",
        ),
        // A uniform render resumed with --noise: adaptive sampling is
        // named, not the --min-samples the user never gave.
        (
            &["--noise", "0.1"],
            "it was rendered without adaptive sampling (--noise), this render with adaptive sampling (--noise 0.1)",
        ),
    ] {
        let (code, err) = run(text(SCENE), &[&["--spp", "512"][..], flags].concat());
        assert_eq!(code, 2, "{flags:?}: {err}");
        assert!(err.contains(says), "{flags:?}: {err}");
        for debug in ["None", "Some(", "Auto", "Uniform", "min_samples"] {
            assert!(!err.contains(debug), "{flags:?}: {err}");
        }
    }
    let (code, err) = run(
        text(&SCENE.replace("rgb 0.3", "rgb 0.31")),
        &["--spp", "512"],
    );
    assert_eq!(code, 2);
    assert!(err.contains("scene differs"), "{err}");
    let commented =
        format!("// lit from the top left\n{SCENE}").replace("<24, 20>", "<24, 20> samples 512");
    let (code, err) = run(text(&commented), &[]);
    assert_eq!(
        code, 0,
        "a comment and the samples in the file keep the state: {err}"
    );
    assert!(err.contains("resuming a render of 256 spp"), "{err}");
}

#[test]
fn checkpoints_save_the_state_and_leave_the_image_unchanged() {
    let dir = crate::temp_dir_with(&[("s.pts", SCENE)]);
    let scene = dir.path().join("s.pts");
    let out = dir.path().join("long.exr");
    // A checkpoint every 0.2 s of a render of a second or so.
    let err = render(
        &scene,
        &out,
        &[
            "--spp",
            "3000",
            "--checkpoint",
            "0.2",
            "-v",
            "--threads",
            "1",
        ],
    );
    assert!(err.contains("checkpoint: state saved"), "{err}");
    assert!(dir.path().join("long.exr.state.exr").is_file());
    let whole = dir.path().join("whole.exr");
    render(&scene, &whole, &["--spp", "3000", "--checkpoint", "0"]);
    assert_eq!(pixels(&out), pixels(&whole));
    assert!(
        !dir.path().join("whole.exr.state.exr").exists(),
        "no state without a checkpoint"
    );
}

#[test]
fn frames_see_their_number_and_clock_and_number_their_images() {
    let moving = "let x = clock * 2 - 1;\n\
        camera { position <0, 1, 4> look_at <0, 0.5, 0> }\n\
        background rgb 0.5\n\
        sphere { center <x, 0.5, 0> radius 0.4 material { diffuse rgb 0.2 } }\n\
        render { resolution <16, 12> samples 2 output \"f_\" + str(frame, 3) + \".png\" }\n";
    let dir = crate::temp_dir_with(&[("m.pts", moving)]);
    let scene = dir.path().join("m.pts");
    let pattern = dir.path().join("frame_##.png");
    render(&scene, &pattern, &["--frames", "3..5"]);
    let frame = |n: u32| std::fs::read(dir.path().join(format!("frame_0{n}.png"))).unwrap();
    assert_ne!(frame(3), frame(4), "the clock moves the sphere");
    assert_ne!(frame(4), frame(5));
    // One frame of the animation, as a farm's task renders it.
    let one = dir.path().join("one_####.png");
    render(&scene, &one, &["--frames", "3..5", "--frame", "4"]);
    assert_eq!(
        std::fs::read(dir.path().join("one_0004.png")).unwrap(),
        frame(4)
    );
    // The scene names its images itself.
    let (code, err) = ptsc(&["render", scene.to_str().unwrap(), "--frame", "7"]);
    assert_eq!(code, 0, "{err}");
    assert!(dir.path().join("f_007.png").is_file(), "{err}");
    // The scene's own names, computed from the frame, for a range.
    let (code, err) = ptsc(&["render", scene.to_str().unwrap(), "--frames", "8..9"]);
    assert_eq!(code, 0, "{err}");
    assert!(dir.path().join("f_009.png").is_file(), "{err}");
    // Several frames into one file: refused before any frame renders,
    // whether the name is `-o`'s, the scene's or the scene file's.
    let same = dir.path().join("same.png");
    let (code, err) = ptsc(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        same.to_str().unwrap(),
        "--frames",
        "1..2",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("# pattern"), "{err}");
    assert!(!same.exists(), "nothing is rendered");
    let still = moving.replace("\"f_\" + str(frame, 3) + \".png\"", "\"still.png\"");
    let unnamed = moving.replace("output \"f_\" + str(frame, 3) + \".png\"", "");
    std::fs::write(dir.path().join("still.pts"), still).unwrap();
    std::fs::write(dir.path().join("unnamed.pts"), unnamed).unwrap();
    for (file, image) in [("still.pts", "still.png"), ("unnamed.pts", "unnamed.png")] {
        let scene = dir.path().join(file);
        let (code, err) = ptsc(&["render", scene.to_str().unwrap(), "--frames", "1..3"]);
        assert_eq!(code, 2, "{file}: {err}");
        assert!(err.contains("frames 1 and 3 would both write"), "{err}");
        assert!(
            !dir.path().join(image).exists(),
            "{file}: nothing is rendered"
        );
    }
    let (code, err) = ptsc(&[
        "render",
        scene.to_str().unwrap(),
        "--frames",
        "1..2",
        "--frame",
        "9",
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--frame 9 is not one of --frames 1..2"),
        "{err}"
    );
}

#[test]
fn a_pass_needs_an_exr_and_at_least_a_sample() {
    let dir = crate::temp_dir_with(&[("s.pts", SCENE)]);
    let scene = dir.path().join("s.pts").display().to_string();
    let png = dir.path().join("p.png").display().to_string();
    let (code, err) = ptsc(&["render", &scene, "--pass", "1/2", "-o", &png]);
    assert_eq!(code, 2);
    assert!(err.contains(".exr"), "{err}");
    let exr = dir.path().join("p.exr").display().to_string();
    let (code, err) = ptsc(&["render", &scene, "--pass", "1/5", "--spp", "4", "-o", &exr]);
    assert_eq!(code, 2);
    assert!(err.contains("at most 4"), "{err}");
    let (code, err) = ptsc(&["render", &scene, "--pass", "3/2", "-o", &exr]);
    assert_eq!(code, 2);
    assert!(err.contains("K must be at most N"), "{err}");
    // A part holds the colour alone: AOVs or a denoised image asked of a
    // part are refused before the render, not dropped after it.
    for asked in [&["--aov", "albedo,normal"][..], &["--denoise"]] {
        let args = [&["render", &scene, "--pass", "1/2", "-o", &exr][..], asked].concat();
        let (code, err) = ptsc(&args);
        assert_eq!(code, 2, "{err}");
        // (A build without the denoiser refuses `--denoise` before that.)
        let refused = err.contains(&format!("does not carry {}", asked[0]));
        assert!(refused || err.contains("built without denoising"), "{err}");
        assert!(!dir.path().join("p.exr").exists());
    }
}

/// The Kubernetes manifest: its Indexed Job's completions, the pass its
/// command renders and the merge's inputs agree, and every volume names
/// the claim it declares. (The schemas are checked by kubernetes-validate
/// where it is installed: docs/farm.md.)
#[test]
fn the_kubernetes_manifest_is_an_indexed_job_whose_pods_render_each_pass() {
    let text =
        std::fs::read_to_string(crate::root().join("deploy/kubernetes/render-job.yaml")).unwrap();
    let docs: Vec<serde_json::Value> = (text.split("\n---\n"))
        .map(|d| serde_yaml_ng::from_str(d).unwrap())
        .collect();
    assert_eq!(docs.len(), 3);
    let kind = |k: &str, name: &str| {
        docs.iter()
            .find(|d| d["kind"] == k && d["metadata"]["name"] == name)
            .unwrap_or_else(|| panic!("no {k} {name}"))
            .clone()
    };
    let claim = kind("PersistentVolumeClaim", "ptsc-work");
    assert!(
        claim["spec"]["accessModes"][0] == "ReadWriteMany",
        "shared by every pod"
    );
    let render_job = kind("Job", "ptsc-render");
    assert_eq!(render_job["apiVersion"], "batch/v1");
    let spec = &render_job["spec"];
    assert_eq!(spec["completionMode"], "Indexed");
    let n = spec["completions"].as_u64().unwrap();
    assert!(spec["parallelism"].as_u64().unwrap() <= n);
    let pod = &spec["template"]["spec"];
    assert_eq!(
        pod["restartPolicy"], "Never",
        "an indexed job's retries are its own"
    );
    let script = pod["containers"][0]["args"][0].as_str().unwrap();
    assert!(
        script.contains("ptsc render") && script.contains("--resume"),
        "{script}"
    );
    assert!(
        script.contains(&format!("--pass $((JOB_COMPLETION_INDEX + 1))/{n}")),
        "the pass counts from the 0-based index, out of `completions`: {script}"
    );
    let merge = kind("Job", "ptsc-merge");
    let merge_script = merge["spec"]["template"]["spec"]["containers"][0]["args"][0]
        .as_str()
        .unwrap();
    assert!(merge_script.contains("ptsc merge") && merge_script.contains("/work/out/part_*.exr"));
    assert!(script.contains("-o /work/out/part_$((JOB_COMPLETION_INDEX + 1)).exr"));
    for job in [&render_job, &merge] {
        let pod = &job["spec"]["template"]["spec"];
        assert_eq!(
            pod["volumes"][0]["persistentVolumeClaim"]["claimName"],
            "ptsc-work"
        );
        assert_eq!(
            pod["containers"][0]["volumeMounts"][0]["name"],
            pod["volumes"][0]["name"]
        );
    }
    // The pods' commands as written, with the volume at a folder here and
    // the binary on PATH as `ptsc`: each index renders its pass, then the
    // merge's loop ends at once with the single render's image.
    let dir = crate::temp_dir_with(&[]);
    let work = dir.path().join("work");
    std::fs::create_dir_all(work.join("scene")).unwrap();
    std::fs::write(work.join("scene/scene.pts"), SCENE).unwrap();
    let bin = dir.path().join("bin");
    std::fs::create_dir(&bin).unwrap();
    std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_ptsc"), bin.join("ptsc")).unwrap();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let here = |script: &str| script.replace("/work", work.to_str().unwrap());
    let sh = |script: &str, index: Option<u64>| {
        let mut command = Command::new("sh");
        command.args(["-c", &here(script)]).env("PATH", &path);
        if let Some(i) = index {
            command.env("JOB_COMPLETION_INDEX", i.to_string());
        }
        let out = command.output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    for index in 0..n {
        sh(script, Some(index));
        assert!(work.join(format!("out/part_{}.exr", index + 1)).is_file());
    }
    sh(merge_script, None);
    let spp = script
        .split("--spp ")
        .nth(1)
        .unwrap()
        .split_whitespace()
        .next()
        .unwrap();
    let single = dir.path().join("single.png");
    render(&work.join("scene/scene.pts"), &single, &["--spp", spp]);
    assert_eq!(
        std::fs::read(work.join("out/image.png")).unwrap(),
        std::fs::read(&single).unwrap()
    );
}

/// The Slurm script against a stand-in `sbatch` that records each job:
/// running every array task's command with its SLURM_ARRAY_TASK_ID and
/// then the merge's gives the single render's image.
#[test]
fn the_slurm_array_script_renders_passes_a_dependent_job_merges() {
    let dir = crate::temp_dir_with(&[("s.pts", SCENE)]);
    let bin = dir.path().join("bin");
    std::fs::create_dir(&bin).unwrap();
    let jobs = dir.path().join("jobs");
    std::fs::create_dir(&jobs).unwrap();
    // Each call saves its arguments and prints a job id.
    let fake = format!(
        "#!/usr/bin/env bash\nn=$(ls {jobs} | wc -l)\nprintf '%s\\n' \"$@\" > {jobs}/$n\necho $((100 + n))\n",
        jobs = jobs.display()
    );
    std::fs::write(bin.join("sbatch"), fake).unwrap();
    Command::new("chmod")
        .args(["+x", bin.join("sbatch").to_str().unwrap()])
        .status()
        .unwrap();
    let out = dir.path().join("out");
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let script = crate::root().join("deploy/slurm/render-array.sh");
    let status = Command::new("bash")
        .arg(&script)
        .args([
            "--ptsc",
            env!("CARGO_BIN_EXE_ptsc"),
            "--spp",
            "9",
            "--passes",
            "3",
        ])
        .arg(dir.path().join("s.pts"))
        .arg(&out)
        .env("PATH", &path)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&status.stdout);
    assert!(
        status.status.success(),
        "{said}{}",
        String::from_utf8_lossy(&status.stderr)
    );
    assert!(
        said.contains("render job 100 (array 1-3)") && said.contains("merge job 101"),
        "{said}"
    );
    let job = |n: usize| std::fs::read_to_string(jobs.join(n.to_string())).unwrap();
    let (array, merge) = (job(0), job(1));
    assert!(
        array.lines().any(|l| l == "--array=1-3") && array.lines().any(|l| l == "--requeue"),
        "{array}"
    );
    assert!(
        merge.lines().any(|l| l == "--dependency=afterok:100"),
        "{merge}"
    );
    let wrap = |job: &str| {
        job.lines()
            .find_map(|l| l.strip_prefix("--wrap="))
            .unwrap()
            .to_string()
    };
    // Each array task, then the merge, as Slurm would run them.
    let run = |job: &str, task: Option<u32>| {
        let mut command = Command::new("bash");
        command.args(["-c", &wrap(job)]);
        if let Some(id) = task {
            command.env("SLURM_ARRAY_TASK_ID", id.to_string());
        }
        let out = command.output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    for task in 1..=3 {
        run(&array, Some(task));
    }
    run(&merge, None);
    let single = dir.path().join("single.png");
    render(&dir.path().join("s.pts"), &single, &["--spp", "9"]);
    assert_eq!(
        std::fs::read(out.join("image.png")).unwrap(),
        std::fs::read(single).unwrap()
    );
}
