//! Command-line conventions: exit codes after signals with the image of
//! every sample done, JSON for a client even on I/O errors, `--quiet` and
//! `--verbose`, flags checked like the scene, `check` of several scenes.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::{ptsc, ptsc_stderr};

const SCENE: &str = "camera { position <0, 1, 4> look_at <0, 0.5, 0> }\n\
    background rgb 0.6\n\
    plane { normal <0, 1, 0> material { diffuse rgb 0.7 } }\n\
    sphere { center <0, 0.5, 0> radius 0.5 material { reflection rgb 0.8 gloss 0.2 } }\n";

/// Sends `signal` to a long render after `after`; returns its exit code and
/// stderr.
fn interrupt(scene: &Path, out: &Path, signal: &str, after: Duration) -> (i32, String) {
    let child = Command::new(env!("CARGO_BIN_EXE_ptsc"))
        .args([
            "render",
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ])
        .args([
            "--resolution",
            "48x48",
            "--spp",
            "1000000",
            "--threads",
            "2",
        ])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(after);
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let t0 = Instant::now();
    let out = child.wait_with_output().unwrap();
    assert!(t0.elapsed() < Duration::from_secs(5), "slow to stop");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn a_signal_writes_every_sample_done_and_sets_the_exit_code() {
    let dir = crate::temp_dir_with(&[("s.pts", SCENE)]);
    let scene = dir.path().join("s.pts");
    // "interrupted: N spp in every pixel, up to M, …": the pass in flight
    // was kept. A signal that lands just as a pass starts finds none of its
    // samples done (every = M): the run is tried again a little later.
    let mut tries = Vec::new();
    let (out, every) = loop {
        let k = tries.len();
        let out = dir.path().join(format!("interrupted{k}.exr"));
        let after = Duration::from_millis(2500 + 300 * k as u64);
        let (code, err) = interrupt(&scene, &out, "-INT", after);
        assert_eq!(code, 130, "{err}");
        let line = err
            .lines()
            .find(|l| l.contains("interrupted:"))
            .expect(&err)
            .to_string();
        let number_after = |word: &str| -> u32 {
            let rest = &line[line.find(word).unwrap() + word.len()..];
            rest.split(|c: char| !c.is_ascii_digit())
                .find(|w| !w.is_empty())
                .unwrap()
                .parse()
                .unwrap()
        };
        let (every, most) = (number_after("interrupted: "), number_after("up to "));
        assert!(every >= 1 && most >= every, "{line}");
        if most > every {
            break (out, every);
        }
        tries.push(line);
        assert!(tries.len() < 3, "no pass in flight was kept: {tries:?}");
    };
    // The image is not the image of the passes that finished: it holds more.
    let finished = dir.path().join("finished.exr");
    let (code, _, e) = ptsc(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        finished.to_str().unwrap(),
        "--resolution",
        "48x48",
        "--spp",
        &every.to_string(),
    ]);
    assert_eq!(code, 0, "{e}");
    let (_, _, a) = ptsc::output::read_exr(&out).unwrap();
    let (_, _, b) = ptsc::output::read_exr(&finished).unwrap();
    assert!(a.iter().all(|p| p.is_finite()));
    let differing = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    assert!(
        differing > 0,
        "the interrupted image holds only the finished passes"
    );

    // Another image: the first one's saved state would refuse a fresh
    // render there (without --resume or --restart).
    let out = dir.path().join("terminated.exr");
    let (code, err) = interrupt(&scene, &out, "-TERM", Duration::from_millis(1500));
    assert_eq!(code, 143, "{err}");
    assert!(err.contains("interrupted:"), "{err}");
}

#[test]
fn json_clients_get_json_for_io_errors_too() {
    let (code, out, err) = ptsc(&["check", "/no/such/scene.pts", "--format", "json"]);
    assert_eq!(code, 2);
    assert!(err.is_empty(), "{err}");
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(json[0]["code"], "pts::io::read");
    assert!(json[0]["message"]
        .as_str()
        .unwrap()
        .contains("/no/such/scene.pts"));
}

#[test]
fn quiet_prints_errors_only_and_verbose_the_stages() {
    let dir = crate::temp_dir_with(&[(
        "s.pts",
        &format!("{SCENE}let unused = 1;\nrender {{ resolution <8, 8> samples 4 }}\n"),
    )]);
    let scene = dir.path().join("s.pts");
    let img = dir.path().join("o.png");
    let args = [
        "render",
        scene.to_str().unwrap(),
        "-o",
        img.to_str().unwrap(),
    ];
    let (code, _, err) = ptsc(&[&args[..], &["--quiet"]].concat());
    assert_eq!(code, 0);
    assert!(err.is_empty(), "quiet printed: {err}");
    assert!(img.is_file());
    let (code, _, err) = ptsc(&[&args[..], &["--verbose"]].concat());
    assert_eq!(code, 0);
    for want in ["never used", "loaded in", "pass to 4 spp", "4 spp in"] {
        assert!(err.contains(want), "no `{want}` in: {err}");
    }
    let (code, _, err) = ptsc(&["check", scene.to_str().unwrap(), "--quiet"]);
    assert_eq!((code, err.as_str()), (0, ""));
    // Flags follow the scene's rules, with its wording.
    let (code, _, err) = ptsc(&[&args[..], &["--spp", "0"]].concat());
    assert_eq!(code, 2);
    assert!(err.contains("a whole number from 1 to 1000000"), "{err}");
}

#[test]
fn materials_may_be_used_before_their_declaration() {
    let c = ptsc::check::check_str(
        Path::new("m.pts"),
        "camera { position <0, 0, 5> look_at <0, 0, 0> }\n\
         sphere { center <0, 0, 0> radius 1 material gold }\n\
         material gold { reflection rgb <1, 0.8, 0.3> emission rgb 1 }\n",
    );
    assert!(c.diagnostics.items.is_empty(), "{:?}", c.diagnostics.items);
    let scene = c.scene.unwrap();
    let m = &scene.materials[scene.objects[0].material];
    assert_eq!(m.name.as_deref(), Some("gold"));
    // Constants keep their order: a name is defined before it is used.
    let c = ptsc::check::check_str(
        Path::new("m.pts"),
        "camera { position <0, 0, 5> look_at <0, 0, 0> }\n\
         sphere { center <0, 0, 0> radius r }\nlet r = 1;\n",
    );
    assert!(c.diagnostics.has_errors());
}

/// A folder with a fine scene, one with a warning, one with an error, an
/// include fragment and a subfolder.
fn scenes_folder() -> tempfile::TempDir {
    let dir = crate::temp_dir_with(&[
        ("a_fine.pts", SCENE),
        ("b_warning.pts", &format!("{SCENE}let unused = 1;\n")),
        (
            "c_error.pts",
            &format!("{SCENE}sphere {{ center <0, 0, 0> radius -1 }}\n"),
        ),
        // Alone it would be missing its camera: it is not checked alone.
        ("part.ptsi", "sphere { center <0, 2, 0> radius 0.1 }\n"),
    ]);
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    std::fs::write(dir.path().join("sub/d_error.pts"), "sphere {").unwrap();
    dir
}

#[test]
fn check_takes_several_scenes_and_folders_and_sums_them_up() {
    let dir = scenes_folder();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    // Two fine scenes: a line each and the summary, exit 0.
    let (code, _, err) = ptsc(&["check", &p("a_fine.pts"), &p("b_warning.pts")]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("a_fine.pts: ok"), "{err}");
    assert!(err.contains("b_warning.pts: ok, 1 warning"), "{err}");
    assert!(
        err.ends_with("2 files checked: 0 errors, 1 warning\n"),
        "{err}"
    );
    // The folder: its three scenes in name order, not sub/ nor part.ptsi.
    let (code, _, err) = ptsc(&["check", dir.path().to_str().unwrap()]);
    assert_eq!(code, 1, "{err}");
    let (a, b, c) = (
        err.find("a_fine.pts: ok").unwrap(),
        err.find("b_warning.pts: ok, 1 warning").unwrap(),
        err.find("c_error.pts: 1 error, 0 warnings").unwrap(),
    );
    assert!(a < b && b < c, "{err}");
    assert!(
        !err.contains("d_error") && !err.contains("part.ptsi"),
        "{err}"
    );
    assert!(
        err.ends_with("3 files checked: 1 error, 1 warning\n"),
        "{err}"
    );
    // --quiet: the error and the summary only.
    let (code, _, err) = ptsc(&["check", dir.path().to_str().unwrap(), "--quiet"]);
    assert_eq!(code, 1);
    assert!(
        !err.contains(": ok") && !err.contains("never used"),
        "{err}"
    );
    assert!(
        err.contains("3 files checked: 1 error, 0 warnings"),
        "{err}"
    );
    // An unreadable file among them is a usage error (2); the others are
    // still checked. An empty folder says so.
    let empty = dir.path().join("sub/empty");
    std::fs::create_dir(&empty).unwrap();
    let (code, _, err) = ptsc(&[
        "check",
        &p("no_such.pts"),
        &p("c_error.pts"),
        empty.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("cannot read") && err.contains("no_such.pts"),
        "{err}"
    );
    assert!(err.contains("holds no .pts scene"), "{err}");
    assert!(err.contains("c_error.pts: 1 error"), "{err}");
    // The folder is not a file checked: two files, three errors.
    assert!(
        err.ends_with("2 files checked: 3 errors, 0 warnings\n"),
        "{err}"
    );
    // One scene with warnings only: its warnings and one line that says ok.
    let (code, _, err) = ptsc(&["check", &p("b_warning.pts")]);
    assert_eq!(code, 0, "{err}");
    assert!(err.ends_with("b_warning.pts: ok, 1 warning\n"), "{err}");
    assert!(!err.contains("0 errors"), "{err}");
}

#[test]
fn check_of_several_scenes_prints_one_json_array() {
    let dir = scenes_folder();
    let (code, out, err) = ptsc(&["check", dir.path().to_str().unwrap(), "--format", "json"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.is_empty(), "{err}");
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    let items = json.as_array().unwrap();
    let files: Vec<&str> = items.iter().map(|d| d["file"].as_str().unwrap()).collect();
    assert_eq!(items.len(), 2, "{out}");
    assert!(files[0].ends_with("b_warning.pts") && items[0]["severity"] == "warning");
    assert!(files[1].ends_with("c_error.pts") && items[1]["severity"] == "error");
    // Nothing to say is still JSON: an empty array.
    let fine = dir.path().join("a_fine.pts");
    let (code, out, _) = ptsc(&["check", fine.to_str().unwrap(), "--format", "json"]);
    assert_eq!(code, 0);
    assert_eq!(
        serde_json::from_str::<serde_json::Value>(&out).unwrap(),
        serde_json::json!([])
    );
}

/// A time budget (`--time`, `render { time … }`): the render stops when it
/// is spent, every pixel with the same count, and keeps its state for
/// `--resume --time` to add more; with `--spp` the samples bound it too.
#[test]
fn a_time_budget_stops_the_render_with_even_counts_and_resumes() {
    use ptsc::render::state::read_state;
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("budget.pts");
    std::fs::write(
        &scene,
        "render { resolution <32, 24> time 0.5 }\n\
         camera { position <0, 1, 4> look_at <0, 0, 0> }\n\
         point_light { position <2, 4, 3> intensity rgb 20 }\n\
         sphere { center <0, 0, 0> radius 1 }\n",
    )
    .unwrap();
    let out = dir.path().join("budget.exr");
    let run = |extra: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_ptsc"))
            .arg("render")
            .arg(&scene)
            .arg("-o")
            .arg(&out)
            .args(extra)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stderr).to_string()
    };
    let said = run(&[]);
    assert!(said.contains("time budget of 0.5 s spent"), "{said}");
    let state = dir.path().join("budget.exr.state.exr");
    let (film, _) = read_state(&state).unwrap();
    let (least, most, _) = film.sample_counts();
    assert_eq!(least, most, "a budget's passes end together");
    assert!(least > 1, "{least} spp in half a second of a tiny image");
    // Resumed with another budget: more samples, counts even again.
    run(&["--resume", "--time", "0.3s"]);
    let (again, _) = read_state(&state).unwrap();
    let (l2, m2, _) = again.sample_counts();
    assert!(l2 > least && l2 == m2, "{least} then {l2}..{m2}");
    // The samples asked bound a budget too: 4 spp end well within 60 s,
    // the budget not spent, and the state kept all the same (as --help
    // and the README say), for --resume to add samples.
    let bounded = dir.path().join("bounded.exr");
    let bounded_run = |extra: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_ptsc"))
            .args(["render", "-o"])
            .arg(&bounded)
            .arg(&scene)
            .args(extra)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr).to_string();
        assert!(o.status.success(), "{err}");
        err
    };
    let said = bounded_run(&["--time", "1m", "--spp", "4"]);
    let bounded_state = dir.path().join("bounded.exr.state.exr");
    assert!(bounded_state.exists(), "{said}");
    assert!(!said.contains("spent"), "{said}");
    assert!(said.contains("reached the 4 spp asked"), "{said}");
    // Resumed to more samples within a budget: the samples end it, and
    // nothing claims the budget was spent.
    let said = bounded_run(&["--time", "1m", "--spp", "8", "--resume"]);
    assert!(!said.contains("spent"), "{said}");
    assert!(said.contains("reached the 8 spp asked"), "{said}");
    let (film, _) = read_state(&bounded_state).unwrap();
    assert_eq!(film.sample_counts().0, 8);
}

#[test]
fn render_help_names_every_integrator_sampler_and_light_selection() {
    // The help of these flags comes from the vocabularies' tables: `bdpt`
    // and `ptlt` were missing from a help written by hand.
    use ptsc::ir::settings::{IntegratorKind, LightSelection, SamplerKind};
    let (code, help, _) = ptsc(&["render", "--help"]);
    assert_eq!(code, 0);
    let line_after = |flag: &str| {
        let at = help
            .find(flag)
            .unwrap_or_else(|| panic!("no {flag} in\n{help}"));
        help[at..].lines().take(3).collect::<Vec<_>>().join(" ")
    };
    let words: [(&str, &[&str]); 3] = [
        ("--integrator", &IntegratorKind::WORDS),
        ("--sampler", &SamplerKind::WORDS),
        ("--light-selection", &LightSelection::WORDS),
    ];
    for (flag, words) in words {
        let text = line_after(flag);
        for word in words {
            assert!(text.contains(word), "{flag}'s help lacks {word}: {text}");
        }
    }
    // The defaults are the settings' own.
    let defaults = ptsc::ir::settings::Settings::default();
    for (flag, default) in [
        ("--integrator", defaults.integrator.name()),
        ("--sampler", defaults.sampler.name()),
        ("--light-selection", defaults.light_selection.name()),
    ] {
        let text = line_after(flag);
        assert!(text.contains(&format!("else {default})")), "{text}");
    }
}

#[test]
fn flags_that_bdpt_ignores_are_warned_of() {
    // The scene's check does not see the command line's flags: `render`
    // says itself what `check` would say of the same settings in the scene.
    let dir = crate::temp_dir_with(&[
        (
            "fog.pts",
            "camera { position <0, 1, 5> look_at <0, 0, 0> }\n\
            point_light { position <0, 5, 0> intensity rgb 10 }\n\
            atmosphere { density 0.1 }\n\
            render { resolution <8, 8> samples 1 }\n\
            sphere { center <0, 0, 0> radius 1 material { diffuse rgb 0.5 } }\n",
        ),
        (
            "clear.pts",
            "camera { position <0, 1, 5> look_at <0, 0, 0> }\n\
            point_light { position <0, 5, 0> intensity rgb 10 }\n\
            render { resolution <8, 8> samples 1 }\n\
            sphere { center <0, 0, 0> radius 1 material { diffuse rgb 0.5 } }\n",
        ),
    ]);
    let run = |scene: &str, flags: &[&str]| {
        let path = dir.path().join(scene);
        let out = dir.path().join("out.exr");
        let mut argv = vec![
            "render",
            path.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--force",
        ];
        argv.extend_from_slice(flags);
        let (code, _, stderr) = ptsc(&argv);
        assert_eq!(code, 0, "{stderr}");
        stderr
    };
    let media = "do not trace media";
    let clamp = "--clamp has no effect";
    assert!(run("fog.pts", &["--integrator", "bdpt"]).contains(media));
    assert!(!run("fog.pts", &["--integrator", "path"]).contains(media));
    assert!(!run("clear.pts", &["--integrator", "bdpt"]).contains(media));
    assert!(run("clear.pts", &["--integrator", "ptlt", "--clamp", "4"]).contains(clamp));
    assert!(!run("clear.pts", &["--clamp", "4"]).contains(clamp));
    // With media bdpt falls back to path, which clamps.
    assert!(!run("fog.pts", &["--integrator", "ptlt", "--clamp", "4"]).contains(clamp));
}

#[test]
fn negative_and_fractional_counts_are_told_what_they_must_be() {
    // clap's own tip ("to pass '-1' as a value, use '-- -1'") did not work:
    // numeric options take the number and say why it is refused.
    let (code, said) = ptsc_stderr(&["render", "s.pts", "--spp", "-1"]);
    assert_eq!(code, 2, "{said}");
    assert!(
        said.contains("-1 is out of range: a whole number from 1"),
        "{said}"
    );
    assert!(!said.contains("tip:"), "{said}");
    let (_, said) = ptsc_stderr(&["render", "s.pts", "--threads", "2.5"]);
    assert!(said.contains("2.5 is not a whole number"), "{said}");
}

#[test]
fn check_reads_a_scene_from_stdin_with_its_includes_beside_the_working_folder() {
    let dir = crate::temp_dir_with(&[("parts.ptsi", "material clay { diffuse rgb 0.5 }\n")]);
    let scene = "include \"parts.ptsi\"\ncamera { position <0, 1, 5> look_at <0, 0, 0> }\n\
                 point_light { position <0, 5, 0> intensity rgb 10 }\n\
                 sphere { center <0, 0, 0> radius 1 material clay }\n";
    let (code, _, err) = crate::ptsc_fed(dir.path(), &["check", "-"], std::io::Cursor::new(scene));
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("<stdin>: ok"), "{err}");
    let broken = scene.replace("material clay }", "material caly }");
    let (code, _, err) = crate::ptsc_fed(dir.path(), &["check", "-"], std::io::Cursor::new(broken));
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("<stdin>:4:") && err.contains("did you mean `clay`?"),
        "{err}"
    );
    let (code, _, err) = ptsc(&["check", "-", "-"]);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn stdin_larger_than_a_scene_is_refused_before_it_is_held() {
    use std::io::Read;
    let dir = tempfile::tempdir().unwrap();
    let limited: [&[&str]; 4] = [
        &["check", "-"],
        &["fmt", "-"],
        &["fmt", "--check", "-"],
        &["render", "-", "-o", "never.png"],
    ];
    for args in limited {
        // One byte past the limit; the largest allowed size passes below.
        let past = std::io::repeat(b' ').take(ptsc::source::MAX_SCENE_BYTES + 1);
        let (code, out, err) = crate::ptsc_fed(dir.path(), args, past);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty(), "{args:?}");
        assert!(
            err.contains("stdin holds more than 256 MiB"),
            "{args:?}: {err}"
        );
    }
    assert!(!dir.path().join("never.png").exists());
    let at_limit = std::io::repeat(b' ').take(ptsc::source::MAX_SCENE_BYTES);
    let (code, _, err) = crate::ptsc_fed(dir.path(), &["fmt", "--check", "-"], at_limit);
    assert_eq!(code, 1, "{err}");
    assert!(!err.contains("256 MiB"), "{err}");
}

#[test]
fn render_reads_a_scene_from_stdin_and_asks_for_its_image_name() {
    let dir = crate::temp_dir_with(&[("parts.ptsi", "material clay { diffuse rgb 0.5 }\n")]);
    let scene = "include \"parts.ptsi\"\nrender { resolution <16, 12> samples 1 }\n\
                 camera { position <0, 1, 5> look_at <0, 0, 0> }\n\
                 point_light { position <0, 5, 0> intensity rgb 10 }\n\
                 sphere { center <0, 0, 0> radius 1 material clay }\n";
    let fed =
        |args: &[&str], text: String| crate::ptsc_fed(dir.path(), args, std::io::Cursor::new(text));
    // With -o: rendered, named `<stdin>` in the summary.
    let (code, _, err) = fed(&["render", "-", "-o", "piped.png"], scene.to_string());
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("<stdin>: 16×12"), "{err}");
    assert!(dir.path().join("piped.png").is_file());
    // Without: no `-.png`, a refusal that says what to add.
    let (code, _, err) = fed(&["render", "-"], scene.to_string());
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("add -o FILE"), "{err}");
    assert!(!dir.path().join("-.png").exists());
    // The scene's own `output` names it.
    let named = scene.replace("samples 1 }", "samples 1 output \"named.png\" }");
    let (code, _, err) = fed(&["render", "-"], named);
    assert_eq!(code, 0, "{err}");
    assert!(dir.path().join("named.png").is_file());
    // Errors point into `<stdin>`; watch refuses stdin outright.
    let (code, _, err) = fed(
        &["render", "-", "-o", "x.png"],
        scene.replace("clay }", "caly }"),
    );
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("<stdin>:5:"), "{err}");
    let (code, _, err) = fed(&["watch", "-"], scene.to_string());
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("stdin"), "{err}");
}

/// A negative duration is told as a negative `--checkpoint` is: clap's own
/// tip (`-- -5`) would not help.
#[test]
fn a_negative_time_is_told_in_ptscs_words() {
    let dir = crate::temp_dir_with(&[("s.pts", "sphere { center <0, 0, 0> radius 1 }\n")]);
    let scene = dir.path().join("s.pts");
    let (code, err) = crate::ptsc_stderr(&["render", scene.to_str().unwrap(), "--time", "-5s"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("note: `--time` takes no negative number (`-5s`)"),
        "{err}"
    );
}
