//! The in-process fuzzer: mutates the checked-in corpus (`fuzz/corpus/TARGET`)
//! and feeds the fuzz targets of `ptsc::fuzz` for a bounded time, on stable
//! Rust, without coverage feedback (its feedback: a mutant that gets past the
//! parser is kept as a parent). CI runs it for a minute or two; the
//! coverage-guided targets in `fuzz/fuzz_targets/` (cargo-fuzz) are for long
//! runs.
//!
//! ```text
//! cargo run --release --example fuzz -- [--seconds N] [--seed S] scene|ply|obj|mtl|gltf|image|state|budget|all
//! cargo run --release --example fuzz -- --time-seeds scene   # the cost of each seed
//! ```
//!
//! Each input is written to `target/fuzz/current-TARGET` before it runs, so
//! that an abort (a stack overflow) leaves it behind; a panic saves the input
//! to `target/fuzz/crash-TARGET-N` and the run fails; an input that runs over
//! 30 s stops the run as a hang. Prints inputs, inputs/s and the pool size.

use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Longest an input may run before the run stops as a hang.
const HANG: Duration = Duration::from_secs(30);
/// Mutants kept as parents at most (the oldest go first).
const POOL: usize = 2000;
/// The largest input fed (mutants grow by insertion and duplication).
const MAX_INPUT: usize = 64 * 1024;

/// Numbers mutations insert or put in place of another: the values at the
/// edges of the numeric domain and of the settings' ranges.
const NUMBERS: &[&str] = &[
    "0",
    "1",
    "-1",
    "0.5",
    "2",
    "1e9",
    "1.0000001e9",
    "-1e9",
    "1e12",
    "1e13",
    "1e39",
    "-1e300",
    "1e300",
    "1e-9",
    "1e-10",
    "1e-320",
    "4294967295",
    "4294967296",
    "1000000",
    "1000001",
    "3.5",
    "99999999999999999999",
];

/// Words mutations insert: the language's tokens and some of its names.
const WORDS: &[&str] = &[
    "let ",
    "include ",
    "for ",
    " in ",
    "..",
    "background ",
    "material ",
    "rgb ",
    "true",
    "false",
    "render ",
    "camera ",
    "sphere ",
    "plane ",
    "quad ",
    "disk ",
    "triangle ",
    "box ",
    "mesh ",
    "point_light ",
    "spot_light ",
    "directional_light ",
    "{",
    "}",
    "<",
    ">",
    "(",
    ")",
    ",",
    ";",
    "=",
    "+",
    "-",
    "*",
    "/",
    "x",
    "_x",
    "i",
    "radius ",
    "center ",
    "scale ",
    "translate ",
    "rotate ",
    "matrix ",
    "velocity ",
    "emission ",
    "samples ",
    "resolution ",
    "max_depth ",
    "integrator ",
    "whitted",
    "hybrid",
    "path",
    "shutter ",
    "aperture ",
    "focus_distance ",
    "up ",
    "normal ",
    "intensity ",
    "transmission 1 ",
    "reflection rgb 1 ",
    "gloss ",
    "ior ",
    "absorption ",
    "two_sided true ",
    "light_samples ",
    "\"zero.ply\"",
    "\"/dev/zero\"",
    "\"fuzz.pts\"",
    "\"tests/golden/scenes/ball.obj\"",
    "sqrt(",
    "pow(",
    "normalize(",
    "cross(",
    "dot(",
    "length(",
    "<0, 0, 0>",
    "<1e9, 1e9, 1e9>",
    "rgb <1e12, 0, 1e12>",
    " // ",
    "/* ",
    " */",
    "\"",
    "\\",
    "\u{feff}",
    "\u{fffd}",
    "\r\n",
    "\u{0}",
    "é",
];

/// SplitMix64: a small deterministic generator (a seed repeats a run).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Sizes a binary mutation writes over a file's bytes: the edges of the
/// image limits (16,384² texels, 32,768 a side) and of 16 and 32 bits, so
/// that headers claim huge images often.
const SIZES: &[u32] = &[
    0,
    1,
    2,
    255,
    256,
    4096,
    16_383,
    16_384,
    16_385,
    32_767,
    32_768,
    65_535,
    65_536,
    1 << 20,
    1 << 28,
    i32::MAX as u32,
    u32::MAX,
];

/// Writes one of [`SIZES`] over `v` at `at`: 2 or 4 bytes, little- or
/// big-endian (a PNG's or JPEG's header is big-endian, an EXR's little).
fn write_size(rng: &mut Rng, v: &mut [u8], at: usize) {
    let size = SIZES[rng.below(SIZES.len())];
    let bytes: Vec<u8> = match rng.below(4) {
        0 => size.to_le_bytes().to_vec(),
        1 => size.to_be_bytes().to_vec(),
        2 => (size as u16).to_le_bytes().to_vec(),
        _ => (size as u16).to_be_bytes().to_vec(),
    };
    let end = (at + bytes.len()).min(v.len());
    let n = end.saturating_sub(at);
    v[at.min(end)..end].copy_from_slice(&bytes[..n]);
}

/// One to four random edits of `input`, perhaps spliced with `other`; a
/// `binary` file also gets sizes written over its bytes (headers claiming
/// large images or films).
fn mutate(rng: &mut Rng, input: &[u8], other: &[u8], binary: bool) -> Vec<u8> {
    let mut v = input.to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(v.len() + 1);
        if binary && rng.below(3) == 0 {
            write_size(rng, &mut v, at);
            continue;
        }
        match rng.below(8) {
            0 if !v.is_empty() => {
                let i = rng.below(v.len());
                v[i] ^= 1 << rng.below(8);
            }
            1 if !v.is_empty() => {
                let end = (at + 1 + rng.below(16)).min(v.len());
                v.drain(at.min(end)..end);
            }
            2 if !v.is_empty() => {
                let start = rng.below(v.len());
                let end = (start + 1 + rng.below(64)).min(v.len());
                let chunk = v[start..end].to_vec();
                v.splice(at..at, chunk);
            }
            3 => {
                let cut = rng.below(other.len() + 1);
                v.truncate(at);
                v.extend_from_slice(&other[cut..]);
            }
            4 if !v.is_empty() => {
                // Replace a number with an edge value.
                let i = rng.below(v.len());
                if let Some(start) = (0..=i).rev().find(|&k| v[k].is_ascii_digit()) {
                    let mut end = start;
                    while end < v.len() && (v[end].is_ascii_alphanumeric() || v[end] == b'.') {
                        end += 1;
                    }
                    let mut start = start;
                    while start > 0 && (v[start - 1].is_ascii_digit() || v[start - 1] == b'.') {
                        start -= 1;
                    }
                    let word = NUMBERS[rng.below(NUMBERS.len())];
                    v.splice(start..end, word.bytes());
                }
            }
            5 => {
                let word = NUMBERS[rng.below(NUMBERS.len())];
                v.splice(at..at, word.bytes());
            }
            _ => {
                let word = WORDS[rng.below(WORDS.len())];
                v.splice(at..at, word.bytes());
            }
        }
    }
    v.truncate(MAX_INPUT);
    v
}

/// The files of a corpus folder.
fn corpus(dir: &Path) -> Vec<Vec<u8>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| {
            d.flatten()
                .map(|e| e.path())
                .filter(|p| p.is_file())
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files.iter().filter_map(|f| std::fs::read(f).ok()).collect()
}

/// Fuzzes one target for `seconds`; returns the number of crashes.
fn run(target: &str, seconds: f64, seed: u64, out: &Path) -> usize {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let seeds = corpus(&root.join("fuzz/corpus").join(target));
    assert!(!seeds.is_empty(), "no corpus for {target}");
    let feed: fn(&[u8]) -> bool = match target {
        "scene" => |b| ptsc::fuzz::scene(b),
        "ply" => |b| ptsc::fuzz::ply(b),
        "obj" => |b| ptsc::fuzz::obj(b),
        "mtl" => |b| ptsc::fuzz::mtl(b),
        "gltf" => |b| ptsc::fuzz::gltf(b),
        "image" => |b| ptsc::fuzz::image(b),
        "state" => |b| ptsc::fuzz::state(b),
        "budget" => |b| ptsc::fuzz::budget(b),
        other => panic!("unknown target {other}"),
    };
    // Files whose sizes sit in binary headers.
    let binary = matches!(target, "image" | "state" | "gltf");
    let current = out.join(format!("current-{target}"));
    let started = Arc::new(AtomicU64::new(0));
    let t0 = Instant::now();
    {
        // The watchdog: an input running too long ends the run as a hang.
        let started = started.clone();
        let current = current.clone();
        std::thread::spawn(move || loop {
            std::thread::sleep(Duration::from_secs(1));
            let s = started.load(Ordering::Relaxed);
            if s > 0 && t0.elapsed().as_millis() as u64 - s > HANG.as_millis() as u64 {
                eprintln!(
                    "HANG: an input ran over {} s: {}",
                    HANG.as_secs(),
                    current.display()
                );
                std::process::exit(3);
            }
        });
    }
    let mut rng = Rng(seed ^ target.len() as u64);
    let mut pool: Vec<Vec<u8>> = Vec::new();
    let (mut inputs, mut crashes, mut kept) = (0u64, 0usize, 0u64);
    while t0.elapsed().as_secs_f64() < seconds {
        // Half the time a seed, else a kept mutant, as the parent.
        let parent = if pool.is_empty() || rng.below(2) == 0 {
            &seeds[rng.below(seeds.len())]
        } else {
            &pool[rng.below(pool.len())]
        };
        let other = &seeds[rng.below(seeds.len())];
        let input = mutate(&mut rng, parent, other, binary);
        let _ = std::fs::write(&current, &input);
        started.store(t0.elapsed().as_millis().max(1) as u64, Ordering::Relaxed);
        let result = std::panic::catch_unwind(AssertUnwindSafe(|| feed(&input)));
        started.store(0, Ordering::Relaxed);
        inputs += 1;
        match result {
            Ok(deep) => {
                if deep {
                    kept += 1;
                    if pool.len() >= POOL {
                        pool.remove(0);
                    }
                    pool.push(input);
                }
            }
            Err(_) => {
                let path = out.join(format!("crash-{target}-{crashes}"));
                let _ = std::fs::write(&path, &input);
                eprintln!("CRASH: {target}: input saved to {}", path.display());
                crashes += 1;
            }
        }
    }
    let secs = t0.elapsed().as_secs_f64();
    println!(
        "{target}: {inputs} inputs in {secs:.0} s ({:.0}/s), {kept} kept as parents, {} seeds, {crashes} crashes",
        inputs as f64 / secs,
        seeds.len()
    );
    crashes
}

/// Prints how long each seed of a target takes (slow seeds slow a fuzzer).
fn time_seeds(target: &str) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/corpus")
        .join(target);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("corpus folder")
        .flatten()
        .map(|e| e.path())
        .collect();
    files.sort();
    for f in files {
        let bytes = std::fs::read(&f).expect("seed");
        let t = Instant::now();
        match target {
            "scene" => ptsc::fuzz::scene(&bytes),
            "ply" => ptsc::fuzz::ply(&bytes),
            "mtl" => ptsc::fuzz::mtl(&bytes),
            "gltf" => ptsc::fuzz::gltf(&bytes),
            "image" => ptsc::fuzz::image(&bytes),
            "state" => ptsc::fuzz::state(&bytes),
            "budget" => ptsc::fuzz::budget(&bytes),
            _ => ptsc::fuzz::obj(&bytes),
        };
        println!(
            "{:9.3} ms  {}",
            t.elapsed().as_secs_f64() * 1e3,
            f.display()
        );
    }
}

fn main() {
    let mut args = std::env::args().skip(1);
    let (mut seconds, mut seed, mut targets) = (60.0, 1u64, Vec::new());
    let mut timing = false;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--time-seeds" => timing = true,
            "--seconds" => {
                seconds = args
                    .next()
                    .and_then(|s| s.parse().ok())
                    .expect("--seconds N")
            }
            "--seed" => seed = args.next().and_then(|s| s.parse().ok()).expect("--seed N"),
            "all" => targets.extend(
                [
                    "scene", "ply", "obj", "mtl", "gltf", "image", "state", "budget",
                ]
                .map(String::from),
            ),
            t => targets.push(t.to_string()),
        }
    }
    if targets.is_empty() {
        eprintln!(
            "usage: fuzz [--seconds N] [--seed S] scene|ply|obj|mtl|gltf|image|state|budget|all"
        );
        std::process::exit(2);
    }
    // Relative paths in the corpus (meshes, includes) start at the root.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::env::set_current_dir(root).expect("the repository root");
    if timing {
        targets.iter().for_each(|t| time_seeds(t));
        return;
    }
    let out = root.join("target/fuzz");
    std::fs::create_dir_all(&out).expect("target/fuzz");
    // A panic's message once, without the backtrace of every caught one.
    std::panic::set_hook(Box::new(|info| eprintln!("panic: {info}")));
    let per_target = seconds / targets.len() as f64;
    let crashes: usize = targets.iter().map(|t| run(t, per_target, seed, &out)).sum();
    if crashes > 0 {
        std::process::exit(1);
    }
}
