//! Save-to-first-preview latency of `ptsc watch` on the cornell example
//! (examples/bench/cornell.pts, 512×512): the time from writing the scene to
//! the preview image being on disk, as an editor user sees it. Includes the
//! 100 ms batching window. Run: `cargo bench --bench watch_latency`.

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

const SAVES: usize = 15;

fn main() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("cornell.pts");
    let text = std::fs::read_to_string(root.join("examples/bench/cornell.pts")).unwrap();
    std::fs::write(&scene, &text).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_ptsc"))
        .args(["watch", scene.to_str().unwrap(), "--threads", "2"])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let (tx, rx) = mpsc::channel();
    let stderr = child.stderr.take().unwrap();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            let _ = tx.send((Instant::now(), line));
        }
    });
    let wait_for = |needle: &str| -> Instant {
        loop {
            let (t, line) = rx
                .recv_timeout(Duration::from_secs(60))
                .expect("watch stopped");
            if line.contains(needle) {
                return t;
            }
        }
    };
    wait_for("done:");
    let mut latencies = Vec::new();
    for i in 0..SAVES {
        // A camera edit, as when framing a shot.
        let edited = text.replace("fov 39.3077", &format!("fov {}", 38 + i % 3));
        let t0 = Instant::now();
        std::fs::write(&scene, edited).unwrap();
        let t = wait_for("preview");
        latencies.push(t.duration_since(t0).as_secs_f64() * 1e3);
        wait_for("pass 2:");
    }
    let _ = child.kill();
    let _ = child.wait();
    latencies.sort_by(f64::total_cmp);
    println!(
        "watch save-to-preview latency on examples/bench/cornell.pts ({SAVES} saves): median {:.0} ms, min {:.0} ms, max {:.0} ms",
        latencies[SAVES / 2],
        latencies[0],
        latencies[SAVES - 1]
    );
}
