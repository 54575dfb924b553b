//! `tests/hostile/`: inputs that once crashed, hung or exhausted ptsc, one
//! file per problem, each run through the real binary under a memory limit
//! and a time limit. A case fails on a signal, a panic or stack-overflow text,
//! a wrong exit code, a missing or non-finite image, or a timeout.
//!
//! A case file opens with `//` directives (see `tests/hostile/README.md`):
//! `run:` the arguments (`{scene}`, `{out}` and `{dir}` are replaced),
//! `exit:` the expected exit code, `stderr:` / `stdout:` text that must appear,
//! `stderr-not:` text that must not, `finite:` an EXR output whose every
//! pixel must be finite and not all black, `interrupt:` seconds after which
//! SIGINT is sent and `within:` the seconds the process then has to exit,
//! `timeout:` the seconds the whole run may take (default 60), `memory:` the
//! address space it may use in MiB (default 4096).
//! Inputs too large to keep in the repository are generated below and run
//! through the same checks. `PTSC_HOSTILE_BIN=path/to/old/ptsc` runs the
//! cases against another build (each case must fail before its fix).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Address space a run may use unless its case says (`memory:`): a hostile
/// input must not take the machine.
const MEMORY_LIMIT_MIB: u64 = 4 * 1024;

/// What a case runs and expects.
#[derive(Debug, Default, Clone)]
pub struct Case {
    name: String,
    args: Vec<String>,
    exit: i32,
    stderr: Vec<String>,
    stderr_not: Vec<String>,
    stdout: Vec<String>,
    finite: Option<String>,
    interrupt: Option<f64>,
    within: Option<f64>,
    timeout: f64,
    /// The address space the run may use, in MiB.
    memory_mib: u64,
}

impl Case {
    /// Reads the directives at the top of a case file.
    fn parse(name: &str, text: &str) -> Case {
        let mut case = Case {
            name: name.to_string(),
            args: vec!["check".into(), "{scene}".into()],
            timeout: 60.0,
            memory_mib: MEMORY_LIMIT_MIB,
            ..Case::default()
        };
        for line in text.lines() {
            let Some(rest) = line.strip_prefix("//") else {
                break;
            };
            let Some((key, value)) = rest.trim().split_once(':') else {
                continue;
            };
            let value = value.trim().to_string();
            match key.trim() {
                "run" => case.args = value.split_whitespace().map(String::from).collect(),
                "exit" => case.exit = value.parse().expect("exit code"),
                "stderr" => case.stderr.push(value),
                "stderr-not" => case.stderr_not.push(value),
                "stdout" => case.stdout.push(value),
                "finite" => case.finite = Some(value),
                "interrupt" => case.interrupt = Some(value.parse().expect("seconds")),
                "within" => case.within = Some(value.parse().expect("seconds")),
                "timeout" => case.timeout = value.parse().expect("seconds"),
                "memory" => case.memory_mib = value.parse().expect("MiB"),
                _ => {}
            }
        }
        case
    }

    /// Runs the case with `scene` as `{scene}`; outputs go to `dir`.
    /// Returns a description of every way it failed.
    fn run(&self, scene: &Path, dir: &Path) -> Vec<String> {
        let fill = |a: &str| {
            a.replace("{scene}", &scene.display().to_string())
                .replace("{out}", &dir.join("out").display().to_string())
                .replace("{dir}", &dir.display().to_string())
        };
        let args: Vec<String> = self.args.iter().map(|a| fill(a)).collect();
        let mut child = Command::new("bash")
            .arg("-c")
            .arg(format!(
                "ulimit -v {}; exec \"$0\" \"$@\"",
                self.memory_mib * 1024
            ))
            .arg(binary())
            .args(&args)
            .current_dir(scene.parent().unwrap_or(Path::new(".")))
            .env("RAYON_NUM_THREADS", "2")
            .env("MALLOC_ARENA_MAX", "2")
            .env_remove("RUST_BACKTRACE")
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("bash runs");
        let (stdout, stderr) = (child.stdout.take().unwrap(), child.stderr.take().unwrap());
        let read = |mut r: Box<dyn std::io::Read + Send>| {
            std::thread::spawn(move || {
                let mut s = Vec::new();
                let _ = r.read_to_end(&mut s);
                String::from_utf8_lossy(&s).into_owned()
            })
        };
        let (out_thread, err_thread) = (read(Box::new(stdout)), read(Box::new(stderr)));
        let start = Instant::now();
        let mut failures = Vec::new();
        let mut interrupted_at = None;
        let status = loop {
            if let Some(status) = child.try_wait().expect("wait") {
                break Some(status);
            }
            let t = start.elapsed().as_secs_f64();
            if let (Some(after), None) = (self.interrupt, interrupted_at) {
                if t >= after {
                    let _ = Command::new("kill")
                        .args(["-INT", &child.id().to_string()])
                        .status();
                    interrupted_at = Some(Instant::now());
                }
            }
            if t > self.timeout {
                let _ = child.kill();
                let _ = child.wait();
                failures.push(format!("still running after {} s: killed", self.timeout));
                break None;
            }
            std::thread::sleep(Duration::from_millis(20));
        };
        if let (Some(at), Some(within)) = (interrupted_at, self.within) {
            let took = at.elapsed().as_secs_f64();
            if status.is_some() && took > within + 0.05 {
                failures.push(format!(
                    "exited {took:.2} s after SIGINT (at most {within} s)"
                ));
            }
        }
        let (stdout, stderr) = (out_thread.join().unwrap(), err_thread.join().unwrap());
        if let Some(status) = status {
            match status.code() {
                None => failures.push(format!("killed by a signal: {status:?}")),
                Some(c) if c != self.exit => {
                    failures.push(format!("exit code {c}, expected {}", self.exit))
                }
                Some(_) => {}
            }
        }
        for bad in [
            "panicked",
            "has overflowed its stack",
            "memory allocation",
            "RUST_BACKTRACE",
        ] {
            if stderr.contains(bad) {
                failures.push(format!("stderr contains `{bad}`"));
            }
        }
        for want in &self.stderr {
            if !stderr.contains(want.as_str()) {
                failures.push(format!("stderr lacks `{want}`"));
            }
        }
        for unwanted in &self.stderr_not {
            if stderr.contains(unwanted.as_str()) {
                failures.push(format!("stderr contains `{unwanted}`"));
            }
        }
        for want in &self.stdout {
            if !stdout.contains(want.as_str()) {
                failures.push(format!("stdout lacks `{want}`"));
            }
        }
        if let Some(image) = &self.finite {
            let path = PathBuf::from(fill(image));
            match ptsc::output::read_exr(&path) {
                Ok((_, _, px)) => {
                    if px.iter().any(|p| !p.is_finite()) {
                        failures.push(format!("{} has non-finite pixels", path.display()));
                    } else if px.iter().all(|p| *p == glam::Vec3::ZERO) {
                        failures.push(format!("{} is black", path.display()));
                    }
                }
                Err(e) => failures.push(format!("cannot read {}: {e}", path.display())),
            }
        }
        if !failures.is_empty() {
            let tail = |s: &str| {
                let start = s.len().saturating_sub(2000);
                let start = (start..s.len())
                    .find(|&i| s.is_char_boundary(i))
                    .unwrap_or(s.len());
                s[start..].to_string()
            };
            failures.push(format!(
                "--- {} {}\n--- stderr (end):\n{}\n--- stdout (end):\n{}",
                self.name,
                args.join(" "),
                tail(&stderr),
                tail(&stdout)
            ));
        }
        failures
    }
}

/// The binary under test: this build's, or `PTSC_HOSTILE_BIN` (to show
/// that a case fails on an older build).
fn binary() -> PathBuf {
    std::env::var_os("PTSC_HOSTILE_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_ptsc")))
}

fn hostile_dir() -> PathBuf {
    crate::root().join("tests/hostile")
}

/// Runs a case on `scene` with outputs in `dir`; fails on any failure.
pub fn check_case(case: &Case, scene: &Path, dir: &Path) {
    let failures = case.run(scene, dir);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Runs a case on a scene file it writes into a fresh temporary folder.
pub fn run_generated(case: &Case, file_name: &str, text: &[u8]) {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join(file_name);
    std::fs::write(&scene, text).unwrap();
    check_case(case, &scene, dir.path());
}

/// Writes the include files `f0.ptsi` … given by `file(k)` for `k` in
/// `0..n` and a scene that includes `f0.ptsi`; returns the scene.
fn include_files(dir: &Path, n: usize, file: impl Fn(usize) -> String) -> PathBuf {
    for k in 0..n {
        std::fs::write(dir.join(format!("f{k}.ptsi")), file(k)).unwrap();
    }
    let scene = dir.join("scene.pts");
    std::fs::write(
        &scene,
        format!("{CAMERA}background rgb 1\ninclude \"f0.ptsi\"\n"),
    )
    .unwrap();
    scene
}

/// A case with directives written as in a file.
pub fn generated(name: &str, directives: &str) -> Case {
    Case::parse(name, directives)
}

#[test]
fn every_hostile_file_is_handled() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(hostile_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "pts"))
        .collect();
    files.sort();
    assert!(files.len() >= 20, "only {} hostile cases", files.len());
    let mut failures = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let name = file.file_stem().unwrap().to_string_lossy().to_string();
        let case = Case::parse(&name, &text);
        let dir = tempfile::tempdir().unwrap();
        let f = case.run(file, dir.path());
        if !f.is_empty() {
            failures.push(format!("{name}:\n  {}", f.join("\n  ")));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} hostile cases failed:\n{}",
        failures.len(),
        files.len(),
        failures.join("\n")
    );
}

pub const CAMERA: &str = "camera { position <0, 0, 5> look_at <0, 0, 0> }\n";

/// Item 1: a diagnostic past column 65,535 of a line panicked in miette.
#[test]
fn diagnostics_far_along_one_line() {
    let far = " ".repeat(70_000);
    let cases = [
        (
            "long_line_warning",
            format!("{} point_light {{ position <0, 5, 0> intensity rgb 10 }} {far}let x = 1; sphere {{ center <0, 0, 0> radius 1 }}", CAMERA.trim()),
            "// exit: 0\n// stderr: constant `x` is never used\n// stderr: 1:70",
        ),
        // An error whose secondary label is far from its primary one.
        (
            "long_line_error",
            format!("{} let r = 1; {}sphere {{ center <0, 0, 0> radius r radius 2 }}", CAMERA.trim(), "/* */ ".repeat(20_000)),
            "// exit: 1\n// stderr: given twice\n// stderr: first given here",
        ),
        (
            "long_line_render",
            format!("{} background rgb 1 {far}let x = 1; sphere {{ center <0, 0, 0> radius 1 }}", CAMERA.trim()),
            "// run: render {scene} -o {out}.exr --resolution 8x8 --spp 1\n// exit: 0\n// finite: {out}.exr",
        ),
    ];
    for (name, line, directives) in cases {
        run_generated(
            &generated(name, directives),
            "long_line.pts",
            line.as_bytes(),
        );
    }
}

/// Item 4: a flat chain of 30,000 operators, and `rgb` nested 3,000 times
/// without brackets, overflowed the stack.
#[test]
fn long_operator_chains_and_deep_rgb() {
    for op in ["*", "+", "-", "/"] {
        let chain = format!("100000{}", format!(" {op} 1").repeat(29_999));
        let text = format!(
            "{CAMERA}background rgb 1\nsphere {{ center <0, 0, 0> radius 2 + ({chain}) }}\n"
        );
        let case = generated(&format!("chain {op}"), "// exit: 0");
        run_generated(&case, "chain.pts", text.as_bytes());
    }
    let text = format!(
        "{CAMERA}background {}1\nsphere {{ center <0, 0, 0> radius 1 }}\n",
        "rgb ".repeat(3_000)
    );
    let case = generated("rgb nesting", "// exit: 1\n// stderr: rgb");
    run_generated(&case, "rgb.pts", text.as_bytes());
    // The deepest brackets allowed, each level a chain, rendered on the
    // render command's worker threads.
    let mut e = "1".to_string();
    for _ in 0..127 {
        e = format!("({e} + {} - 1)", vec!["1"; 50].join(" * "));
    }
    let text = format!(
        "{CAMERA}background rgb 1\nsphere {{ center <0, 0, 0> radius {e} }}\nrender {{ resolution <4, 4> samples 1 }}\n"
    );
    let case = generated(
        "deep and long",
        "// run: render {scene} -o {out}.exr\n// exit: 0\n// finite: {out}.exr",
    );
    run_generated(&case, "deep.pts", text.as_bytes());
}

/// Items 4 and 5: a chain of 32 includes, each nested as deeply as allowed.
#[test]
fn deepest_include_chain_with_deepest_expressions() {
    let dir = tempfile::tempdir().unwrap();
    let deep = format!("{}1{}", "(".repeat(127), ")".repeat(127));
    let scene = include_files(dir.path(), 40, |k| {
        let next = if k < 39 {
            format!("include \"f{}.ptsi\"\n", k + 1)
        } else {
            String::new()
        };
        format!("let a{k} = {deep};\n{next}")
    });
    let case = generated(
        "include chain",
        "// exit: 1\n// stderr: includes nested too deeply",
    );
    check_case(&case, &scene, dir.path());
}

/// A tree of includes, each file including the next twice: 2^30 runs of
/// the last without a single loop. Repeated includes count against the
/// statements loops may run, so the tree stops.
#[test]
fn exponential_include_tree() {
    let dir = tempfile::tempdir().unwrap();
    let scene = include_files(dir.path(), 31, |k| match k {
        30 => "let _x = 1;\n".to_string(),
        _ => format!("include \"f{}.ptsi\"\n", k + 1).repeat(2),
    });
    let case = generated(
        "include tree",
        "// exit: 1\n// stderr: in all\n// timeout: 60",
    );
    check_case(&case, &scene, dir.path());
}

/// Item 5: huge regular files are refused before they are read.
#[test]
fn files_over_the_size_limits() {
    let dir = tempfile::tempdir().unwrap();
    // Sparse: no disk space is used.
    let big = std::fs::File::create(dir.path().join("big.ptsi")).unwrap();
    big.set_len(300 << 20).unwrap();
    let mesh = std::fs::File::create(dir.path().join("big.ply")).unwrap();
    mesh.set_len(3 << 30).unwrap();
    let scene = dir.path().join("scene.pts");
    std::fs::write(&scene, format!("{CAMERA}include \"big.ptsi\"\n")).unwrap();
    let case = generated("big include", "// exit: 1\n// stderr: larger than");
    check_case(&case, &scene, dir.path());
    std::fs::write(
        &scene,
        format!("{CAMERA}background rgb 1\nmesh {{ file \"big.ply\" }}\n"),
    )
    .unwrap();
    let case = generated(
        "big mesh",
        "// run: render {scene} -o {out}.png\n// exit: 1\n// stderr: larger than",
    );
    check_case(&case, &scene, dir.path());
    let case = generated(
        "big scene",
        "// run: check {dir}/big.ptsi\n// exit: 2\n// stderr: larger than",
    );
    check_case(&case, &scene, dir.path());
}

/// Item 7: human diagnostics took quadratic time (20,000 took 25-55 s).
#[test]
fn fifty_thousand_diagnostics() {
    let mut text = String::from(CAMERA);
    text.push_str("background rgb 1\n");
    for i in 0..50_000 {
        text.push_str(&format!("let unused_{i} = {i};\n"));
    }
    let case = generated(
        "many warnings",
        "// exit: 0\n// stderr: 50000 warnings\n// stderr: more not shown\n// timeout: 60",
    );
    run_generated(&case, "many.pts", text.as_bytes());
    let case = generated(
        "many warnings, JSON",
        "// run: check {scene} --format json\n// exit: 0\n// stdout: unused_49999\n// timeout: 60",
    );
    run_generated(&case, "many.pts", text.as_bytes());
}

/// A scene named like an image was overwritten by its own default output.
#[test]
fn a_scene_is_never_its_own_output() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("scene.png");
    let text = format!("{CAMERA}background rgb 1\nrender {{ resolution <4, 4> samples 1 }}\n");
    std::fs::write(&scene, &text).unwrap();
    let case = generated(
        "scene.png",
        "// run: render {scene}\n// exit: 2\n// stderr: scene",
    );
    check_case(&case, &scene, dir.path());
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), text);
    // Nor is a file it includes.
    std::fs::write(dir.path().join("part.pts"), "background rgb 1\n").unwrap();
    let scene = dir.path().join("main.pts");
    std::fs::write(&scene, format!("{CAMERA}include \"part.pts\"\n")).unwrap();
    let case = generated(
        "include as output",
        "// run: render {scene} -o {dir}/part.pts\n// exit: 2",
    );
    check_case(&case, &scene, dir.path());
    assert_eq!(
        std::fs::read_to_string(dir.path().join("part.pts")).unwrap(),
        "background rgb 1\n"
    );
}

/// After invalid UTF-8, spans counted the bytes of the replacement text.
#[test]
fn spans_after_invalid_utf8_are_file_offsets() {
    let mut text = b"// caf\xe9 \xff\xfe\n".to_vec();
    text.extend_from_slice(CAMERA.as_bytes());
    let at = text.len() + "sphere { center <0, 0, 0> ".len();
    text.extend_from_slice(b"sphere { center <0, 0, 0> radus 1 }\n");
    let case = generated(
        "utf8 offsets",
        &format!(
            "// run: check {{scene}} --format json\n// exit: 1\n// stdout: \"end\": {},\n// stdout: \"start\": {at}",
            at + "radus".len()
        ),
    );
    run_generated(&case, "utf8.pts", &text);
}

/// Files of the hostile suite a case names by a relative path must exist
/// (a typo would make a case pass for the wrong reason).
#[test]
fn hostile_cases_name_existing_files() {
    for entry in std::fs::read_dir(hostile_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "pts") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        for line in text.lines().filter(|l| !l.starts_with("//")) {
            if let Some(rest) = line.split("file \"").nth(1) {
                let name = rest.split('"').next().unwrap();
                assert!(
                    hostile_dir().join(name).symlink_metadata().is_ok(),
                    "{}: `{name}` does not exist",
                    path.display()
                );
            }
        }
    }
    let _ = std::io::stdout().flush();
}

/// Functions, conditionals, lists and groups: no construct of the language
/// can overflow the stack, hang or take unbounded memory; the limits are
/// diagnostics.
#[test]
fn deep_and_long_language_constructs() {
    let deep = |inner: &str| format!("{}{inner}{}", "-(".repeat(120), ")".repeat(120));
    // Functions each calling the one before under the deepest brackets
    // (each a negation: a level of evaluation): evaluation nests past its
    // limit (an error), within the stack.
    let mut text = format!("{CAMERA}background rgb 1\nfn f0(x) = x;\n");
    for k in 1..70 {
        text += &format!("fn f{k}(x) = {};\n", deep(&format!("f{}(x) + 1", k - 1)));
    }
    text += "sphere { center <0, 0, 0> radius f69(1) }\n";
    let case = generated("deep calls", "// exit: 1\n// stderr: nests deeper");
    run_generated(&case, "calls.pts", text.as_bytes());
    // A recursion without an end, and one that branches (2^60 calls).
    for (name, f) in [
        ("endless", "fn f(n) = f(n + 1);"),
        (
            "branching",
            "fn f(n) = if n <= 0 { 1 } else { f(n - 1) + f(n - 1) };",
        ),
    ] {
        let text =
            format!("{CAMERA}background rgb 1\n{f}\nsphere {{ center <0, 0, 0> radius f(60) }}\n");
        let case = generated(
            name,
            "// exit: 1\n// stderr: recursion_limit\n// timeout: 20",
        );
        run_generated(&case, "recursion.pts", text.as_bytes());
    }
    // 100,000 `else if` arms, statement and expression; alternating signs;
    // a long run of indexes; lists nested as deep as brackets go.
    let arms = " else if x == 1 { 2 }".repeat(100_000);
    let stmt_arms = " else if x == 1 { let _a = 2; }".repeat(100_000);
    let signs = "-!".repeat(50_000);
    let indexes = "[0]".repeat(50_000);
    let nested = format!("{}1{}", "[".repeat(126), "]".repeat(126));
    let text = format!(
        "{CAMERA}background rgb 1\nlet x = 0;\nlet y = if x == 0 {{ 1 }}{arms} else {{ 3 }};\n\
         if x == 0 {{ let _b = 1; }}{stmt_arms}\nlet _z = {signs}true;\nlet n = {nested};\n\
         let _w = n{indexes};\nsphere {{ center <0, 0, 0> radius y }}\n"
    );
    let case = generated(
        "long chains",
        "// exit: 1\n// stderr: `-`\n// stderr: cannot index\n// timeout: 30",
    );
    run_generated(&case, "chains.pts", text.as_bytes());
    // Groups each placing the one before twice: 2^3000 objects are refused;
    // a chain of 3,000 groups placing the one before once is expanded.
    for (name, twice, expect) in [
        ("doubling groups", true, "// exit: 1\n// stderr: place more than"),
        (
            "chain of groups",
            false,
            "// run: render {scene} -o {out}.exr --resolution 4x4 --spp 1\n// exit: 0\n// finite: {out}.exr",
        ),
    ] {
        let mut text = format!(
            "{CAMERA}background rgb 1\ngroup g0 {{ sphere {{ center <0, 0, 0> radius 1 }} }}\n"
        );
        for k in 1..3000 {
            let again = if twice {
                format!(" instance g{} {{ translate <0.001, 0, 0> }}", k - 1)
            } else {
                String::new()
            };
            text += &format!("group g{k} {{ instance g{} {{ }}{again} }}\n", k - 1);
        }
        text += "instance g2999 { }\n";
        run_generated(&generated(name, expect), "groups.pts", text.as_bytes());
    }
}

/// Issue 35, item 9: evaluation is bounded by its work, not by the
/// statements that ask for it. Each input ran for minutes, or crashed,
/// before the evaluation budget, shared values and nesting bound.
#[test]
fn work_that_statements_do_not_show() {
    let head = format!("{CAMERA}background rgb 1\nsphere {{ center <0, 0, 0> radius 1 }}\n");
    let doubling = |n: usize| {
        let mut s = String::from("let xs0 = [1];\n");
        for k in 1..=n {
            s += &format!("let xs{k} = xs{} + xs{};\n", k - 1, k - 1);
        }
        s
    };
    // A function of 2,000 terms called 500,000 times (5 minutes): every
    // expression of its body is a step.
    let terms: Vec<String> = (0..2000).map(|k| format!("x * {k}")).collect();
    let long_function = format!(
        "{head}fn f(x) = {};\nfor i in 0..500000 {{ let _v = f(i); }}\n",
        terms.join(" + ")
    );
    // `str` of a list of 524,288 items, 1,000 times (100 s): a text past
    // a string's 4,096 bytes is refused before it is written whole.
    let long_text = format!(
        "{head}{}for i in 0..1000 {{ let _s = str(xs19); }}\n",
        doubling(19)
    );
    // 20,000 unknown names among 40,000 constants: each error weighed
    // every name for a suggestion (8 minutes).
    let mut names = head.clone();
    for i in 0..20_000 {
        names += &format!("let a{i} = {i};\n");
    }
    for i in 0..20_000 {
        names += &format!("let b{i} = zz{i};\n");
    }
    // A list nested 300,000 deep by a chain of `let`s overflowed the
    // stack when it was dropped.
    let mut deep = format!("{head}let l0 = [];\n");
    for k in 1..300_000 {
        deep += &format!("let l{k} = [l{}];\n", k - 1);
    }
    // A vector of 100,000 components added to itself 100,000 times at the
    // top level: each sum made and checked the whole vector (and kept it).
    let mut long_vector = format!("{head}let v = <{}>;\n", vec!["1"; 100_000].join(", "));
    for i in 0..100_000 {
        long_vector += &format!("let _w{i} = v + v;\n");
    }
    for (name, text, expect) in [
        (
            "long function",
            long_function,
            "// stderr: evaluation_too_long",
        ),
        ("long text", long_text, "// stderr: value_too_large"),
        ("suggestions", names, "// stderr: 20000 errors"),
        (
            "deep list",
            deep,
            "// stderr: lists nest at most 256 levels deep",
        ),
        ("long vector", long_vector, "// stderr: evaluation_too_long"),
    ] {
        let case = generated(name, &format!("// exit: 1\n{expect}\n// timeout: 30"));
        run_generated(&case, "work.pts", text.as_bytes());
    }
}

/// Issue 37, item 5: parsing goes on past a syntax error. 99 mistakes
/// spread over a scene of 100,000 spheres are all reported, and the
/// statements after them checked (an unknown name at the end); a file of
/// 100,000 broken statements, on lines or all on one line far from any `;`
/// or `}`, stops at the hundred and first.
#[test]
fn many_broken_statements() {
    let sphere = "sphere { center <0, 0, 0> radius 0.5 }\n";
    let broken = "sphere { center <0, 0 0> radius 0.5 }\n";
    let head = format!("{CAMERA}background rgb 1\n");
    let spread = format!(
        "{head}{}sphere {{ center <0, 0, 0> radius zz }}\n",
        format!("{broken}{}", sphere.repeat(999)).repeat(99)
    );
    let case = generated(
        "99 syntax errors in a large scene",
        "// exit: 1\n// stderr: unknown name `zz`\n// stderr: 100 errors\n// stderr-not: more than 100\n// timeout: 30",
    );
    run_generated(&case, "spread.pts", spread.as_bytes());
    // The human report shows the first hundred diagnostics; JSON all.
    let too_many = "// run: check {scene} --format json\n// exit: 1\n// stdout: more than 100 syntax errors\n// timeout: 10";
    let lines = format!(
        "{head}{}",
        format!("{broken}let x = 1\n{sphere}").repeat(100_000)
    );
    run_generated(
        &generated("broken lines", too_many),
        "lines.pts",
        lines.as_bytes(),
    );
    // Each `let` is a broken statement (a keyword where a name goes).
    let line = format!("{head}{}", "let ".repeat(2_000_000));
    run_generated(
        &generated("one broken line", too_many),
        "line.pts",
        line.as_bytes(),
    );
}

#[test]
fn povray_blocks_and_directives_at_the_largest_sizes() {
    // POV-Ray's blocks are read whole, to their matching brace: nested as
    // deep as braces go (128 with the sphere's), one level more refused
    // as any nesting is; a directive line's braces likewise.
    let nested = |n: usize| {
        format!(
            "{CAMERA}background rgb 1\nsphere {{ center <0, 0, 0> radius 1 {}{} }}\n#declare T = {}{}\n",
            "pigment { ".repeat(n),
            "}".repeat(n),
            "{ ".repeat(n - 1),
            "}".repeat(n - 1)
        )
    };
    let case = generated(
        "deepest POV-Ray blocks",
        "// exit: 1\n// stderr: POV-Ray's `pigment { … }` is not ptsc\n// stderr: `#declare` is a POV-Ray directive",
    );
    run_generated(&case, "deep.pts", nested(127).as_bytes());
    let case = generated(
        "POV-Ray blocks too deep",
        "// exit: 1\n// stderr: nesting deeper than 128",
    );
    run_generated(&case, "deeper.pts", nested(128).as_bytes());
    // One block's content as long as a scene may be (256 MiB in all), with
    // braces in its comments and strings: read in one pass (17 s, 0.84 GB
    // peak on the 2-core machine).
    let line = "color rgb <1, 0.5, 0.2> // a } in a comment\n \"a { in a string\" [0 rgb 1]\n";
    let head =
        format!("{CAMERA}background rgb 1\nsphere {{ center <0, 0, 0> radius 1 pigment {{\n");
    let room = ptsc::source::MAX_SCENE_BYTES as usize - head.len() - 8;
    let mut text = head;
    text.push_str(&line.repeat(room / line.len()));
    text.push_str("} }\n");
    assert!(text.len() as u64 <= ptsc::source::MAX_SCENE_BYTES);
    let case = generated(
        "the longest POV-Ray block",
        "// exit: 1\n// stderr: POV-Ray's `pigment { … }` is not ptsc\n// timeout: 120",
    );
    run_generated(&case, "long.pts", text.as_bytes());
}

/// A name of a million letters, written in a message and its help: each
/// text keeps its start and end and says how long it was, so one warning
/// is not megabytes of output.
#[test]
fn a_huge_name_is_shortened_in_messages() {
    let name = "a".repeat(1_000_000);
    let scene = format!("{}\nbackground rgb 1\nlet {name} = 1;\n", CAMERA.trim());
    let dir = crate::temp_dir_with(&[("long_name.pts", &scene)]);
    let (code, err) =
        crate::ptsc_stderr(&["check", dir.path().join("long_name.pts").to_str().unwrap()]);
    assert_eq!(code, 0, "{}", &err[..err.len().min(2000)]);
    assert!(err.len() < 10_000, "{} bytes of output", err.len());
    assert!(err.contains("(1,000,025 characters)"), "{err}");
}
