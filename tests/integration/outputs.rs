//! What a render writes, and that it loses nothing (issue 35): states of
//! large images in bounded memory, memory refused up front, outputs holding
//! samples never replaced without --force, every path checked before the
//! first sample, lying state files refused from their headers, temporary
//! files of killed runs cleaned.

use super::{ptsc_stderr, temp_dir_with};
use ptsc::render::state::{held_state, HeldState};
use std::path::Path;

/// A scene that renders fast at any size: a camera and a speck.
const SPECK: &str = "camera { position <0, 0, -5> look_at <0, 0, 0> }\n\
    sphere { center <0, 0, 0> radius 0.3 material { diffuse rgb 0.5 } }\n";

/// Runs the ptsc binary under an address-space limit (`ulimit -v`, KiB),
/// so that an allocation past it fails at once instead of swapping.
fn ptsc_limited(kib: u64, args: &[&str]) -> (i32, String) {
    let bin = env!("CARGO_BIN_EXE_ptsc");
    let out = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {kib} && exec \"$0\" \"$@\""))
        .arg(bin)
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn path_str(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn a_state_of_a_large_image_is_written_in_bounded_memory() {
    // 4096² (the largest CI holds quickly): the film is 470 MB; the state
    // file 671 MB. Writing it whole in memory (as before) took 1.8 GB.
    let dir = temp_dir_with(&[("s.pts", SPECK)]);
    let scene = dir.path().join("s.pts");
    let part = dir.path().join("part.exr");
    let limit_kib = 1_100_000;
    let (code, err) = ptsc_limited(
        limit_kib,
        &[
            "render",
            path_str(&scene),
            "--resolution",
            "4096x4096",
            "--spp",
            "1",
            "--threads",
            "2",
            "--pass",
            "1/1",
            "-q",
            "-o",
            path_str(&part),
        ],
    );
    assert_eq!(code, 0, "{err}");
    let len = std::fs::metadata(&part).unwrap().len();
    assert!(len > 40 * 4096 * 4096, "{len} bytes");
    // Merging it reads it into one film, in the same bound.
    let image = dir.path().join("image.exr");
    let (code, err) = ptsc_limited(
        limit_kib,
        &["merge", path_str(&part), "-o", path_str(&image), "-q"],
    );
    assert_eq!(code, 0, "{err}");
}

#[test]
fn memory_past_the_limit_is_refused_before_the_first_sample() {
    let dir = temp_dir_with(&[("s.pts", SPECK)]);
    let scene = dir.path().join("s.pts");
    let out = dir.path().join("big.png");
    let args = |extra: &'static [&'static str]| {
        let mut a = vec![
            "render",
            path_str(&scene),
            "--resolution",
            "8192x8192",
            "-o",
            path_str(&out),
        ];
        a.extend(extra);
        a
    };
    // The largest image under a 1 GB address space: its film alone is 1.9 GB.
    let (code, err) = ptsc_limited(1_000_000, &args(&[]));
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("needs 1.95 GB") && err.contains("ulimit -v"),
        "{err}"
    );
    let (code, err) = ptsc_stderr(&args(&["--memory-limit", "1G"]));
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--memory-limit"), "{err}");
    assert!(!out.exists());
    let (code, err) = ptsc_stderr(&["render", "s.pts", "--memory-limit", "lots"]);
    assert_eq!(code, 2, "{err}");
}

#[test]
fn an_output_holding_samples_is_not_replaced_without_force() {
    let dir = temp_dir_with(&[("s.pts", SPECK)]);
    let scene = dir.path().join("s.pts");
    let at = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let render = |extra: &[&str]| {
        let mut a = vec![
            "render",
            path_str(&scene),
            "--resolution",
            "16x16",
            "--spp",
            "2",
            "-q",
        ];
        a.extend(extra);
        ptsc_stderr(&a)
    };
    let (p1, p2) = (at("p1.exr"), at("p2.exr"));
    assert_eq!(render(&["--pass", "1/2", "-o", &p1]).0, 0);
    assert_eq!(render(&["--pass", "2/2", "-o", &p2]).0, 0);
    let part = std::fs::read(&p1).unwrap();
    // A farm script that lost its --pass.
    let (code, err) = render(&["-o", &p1]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("p1.exr") && err.contains("--force"), "{err}");
    // A merge written over another part.
    let (code, err) = ptsc_stderr(&["merge", &p1, "-o", &p2, "--partial", "-q"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("p2.exr") && err.contains("--force"), "{err}");
    assert_eq!(std::fs::read(&p1).unwrap(), part, "the samples are kept");
    let (code, err) = render(&["-o", &p1, "--force"]);
    assert_eq!(code, 0, "{err}");
    assert_ne!(held_state(Path::new(&p1)), HeldState::State);
}

#[test]
fn every_path_a_render_writes_is_checked_before_the_first_sample() {
    let dir = temp_dir_with(&[("s.pts", SPECK)]);
    let scene = dir.path().join("s.pts");
    // Many samples: a render that started would take minutes.
    let render = |out: &str, extra: &[&str]| {
        let mut a = vec!["render", path_str(&scene), "--spp", "100000", "-o", out];
        a.extend(extra);
        ptsc_stderr(&a)
    };
    let slash = format!("{}/", dir.path().join("out.png").display());
    let (code, err) = render(&slash, &[]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("names a folder"), "{err}");
    let out = dir.path().join("o.png");
    std::fs::create_dir(dir.path().join("o.png.state.exr")).unwrap();
    let (code, err) = render(path_str(&out), &["--keep-state"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("o.png.state.exr") && err.contains("folder"),
        "{err}"
    );
    // A frame pattern wider than a file name: refused, not a panic.
    let wide = dir.path().join(format!("{}.png", "#".repeat(65_536)));
    let (code, err) = render(path_str(&wide), &[]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("at most 255") && err.len() < 1000, "{err}");
}

/// `ptsc render SCENE --resolution SIZE --spp 2 -q EXTRA…`: exit code and
/// stderr.
fn render_quietly(scene: &Path, size: &str, extra: &[&str]) -> (i32, String) {
    render_at(scene, size, &[&["--spp", "2", "-q"], extra].concat())
}

/// `ptsc render SCENE --resolution SIZE EXTRA…`: its exit code and stderr.
fn render_at(scene: &Path, size: &str, extra: &[&str]) -> (i32, String) {
    let mut args = vec!["render", path_str(scene), "--resolution", size];
    args.extend(extra);
    ptsc_stderr(&args)
}

#[test]
fn compressed_or_truncated_states_are_refused_by_resume_and_merge() {
    let dir = temp_dir_with(&[("s.pts", SPECK)]);
    let scene = dir.path().join("s.pts");
    let part = dir.path().join("p.exr");
    let render = |extra: &[&str]| render_quietly(&scene, "64x48", extra);
    assert_eq!(render(&["--pass", "1/1", "-o", path_str(&part)]).0, 0);
    // The same state, its parts rewritten ZIP-compressed (as a tool that
    // recompresses EXR files would).
    let zipped = dir.path().join("z.exr");
    recompress(&part, &zipped);
    let image = dir.path().join("i.png");
    let (code, err) = ptsc_stderr(&["merge", path_str(&zipped), "-o", path_str(&image)]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("compressed"), "{err}");
    std::fs::copy(&zipped, &part).unwrap();
    let (code, err) = render(&["--pass", "1/1", "--resume", "-o", path_str(&part)]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("compressed"), "{err}");
    // Truncated: its header declares more than the file holds.
    assert_eq!(
        render(&["--pass", "1/1", "--restart", "-o", path_str(&part)]).0,
        0
    );
    let bytes = std::fs::read(&part).unwrap();
    std::fs::write(&part, &bytes[..bytes.len() * 2 / 3]).unwrap();
    let (code, err) = ptsc_stderr(&["merge", path_str(&part), "-o", path_str(&image)]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("too short"), "{err}");
}

#[test]
fn a_state_whose_headers_are_damaged_is_kept_until_restart_or_force() {
    let dir = temp_dir_with(&[("s.pts", SPECK)]);
    let scene = dir.path().join("s.pts");
    let render = |extra: &[&str]| render_quietly(&scene, "8x8", extra);
    let part = dir.path().join("p.exr");
    assert_eq!(render(&["--pass", "1/2", "-o", path_str(&part)]).0, 0);
    // One attribute's text edited so that its declared size no longer
    // matches: the headers cannot be read, the samples are all there.
    let bytes = std::fs::read(&part).unwrap();
    let at = (bytes.windows(12).position(|w| w == b"\"pass\":[1,2]"))
        .expect("the description names the pass");
    let mut damaged = bytes[..at].to_vec();
    damaged.extend_from_slice(b"\"pass\":[1e9,]");
    damaged.extend_from_slice(&bytes[at + 12..]);
    std::fs::write(&part, &damaged).unwrap();
    for extra in [&[][..], &["--resume"][..]] {
        let (code, err) = render(&[&["--pass", "1/2", "-o", path_str(&part)], extra].concat());
        assert_eq!(code, 2, "{err}");
        assert!(err.contains("headers cannot be read"), "{err}");
        assert_eq!(std::fs::read(&part).unwrap(), damaged, "{extra:?}: kept");
    }
    // As the image of a whole render: --force, not --restart, replaces it.
    let (code, err) = render(&["-o", path_str(&part)]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("may hold a render's samples") && err.contains("--force"),
        "{err}"
    );
    assert_eq!(std::fs::read(&part).unwrap(), damaged);
    assert_eq!(
        render(&["--pass", "1/2", "--restart", "-o", path_str(&part)]).0,
        0
    );
    std::fs::write(&part, &damaged).unwrap();
    assert_eq!(render(&["-o", path_str(&part), "--force"]).0, 0);
    // A file at a whole render's state path that is no OpenEXR file holds
    // no samples: --resume starts over and says why.
    let image = dir.path().join("i.png");
    std::fs::write(dir.path().join("i.png.state.exr"), b"garbage").unwrap();
    let (code, err) = ptsc_stderr(&[
        "render",
        path_str(&scene),
        "--resolution",
        "8x8",
        "--spp",
        "2",
        "--resume",
        "-o",
        path_str(&image),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("no saved state") && err.contains("not an OpenEXR file"),
        "{err}"
    );
}

/// Rewrites an EXR file with every part ZIP-compressed.
fn recompress(from: &Path, to: &Path) {
    use exr::prelude::*;
    let mut image = read_all_data_from_file(from).unwrap();
    for layer in &mut image.layer_data {
        layer.encoding = Encoding::SMALL_LOSSLESS;
    }
    image.write().to_file(to).unwrap();
}

#[test]
fn temporary_files_of_killed_runs_are_removed_by_the_next_run() {
    let dir = temp_dir_with(&[("s.pts", SPECK)]);
    let scene = dir.path().join("s.pts");
    let out = dir.path().join("out.png");
    let mut child = std::process::Command::new("true").spawn().unwrap();
    let dead = child.id();
    child.wait().unwrap();
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap_or_default();
    let host: String = (host.trim().chars())
        .filter(|c| c.is_ascii_alphanumeric() || *c == '-')
        .collect();
    let stale = [
        format!(".out.png.{host}.{dead}.tmp"),
        format!(".out.png.{dead}.tmp"),
        format!(".out.png.state.exr.{host}.{dead}.tmp"),
    ];
    for name in &stale {
        std::fs::write(dir.path().join(name), vec![0u8; 4096]).unwrap();
    }
    let (code, err) = ptsc_stderr(&[
        "render",
        path_str(&scene),
        "--resolution",
        "8x8",
        "-q",
        "-o",
        path_str(&out),
    ]);
    assert_eq!(code, 0, "{err}");
    let left: Vec<String> = (std::fs::read_dir(dir.path()).unwrap().flatten())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

/// `--aov`: the output variables as channels of the EXR's one part,
/// readable by the `exr` crate (Mitsuba's `Bitmap` reads the same file:
/// checked by hand, docs/performance.md "AOVs"), with the values they
/// promise; an output that cannot hold them is refused before the render.
#[test]
fn aovs_are_channels_of_the_exr_with_the_values_they_promise() {
    use exr::prelude::*;
    let dir = temp_dir_with(&[(
        "s.pts",
        "render { resolution <24, 16> samples 4 }\n\
         camera { position <0, 0, -5> look_at <0, 0, 0> }\n\
         point_light { position <0, 3, -3> intensity rgb 10 }\n\
         sphere { center <0, 0, 0> radius 1 material { diffuse rgb <0.2, 0.4, 0.8> } }\n",
    )]);
    let scene = dir.path().join("s.pts");
    let out = dir.path().join("s.exr");
    let (code, err) = ptsc_stderr(&[
        "render",
        path_str(&scene),
        "--aov",
        "all",
        "-o",
        path_str(&out),
    ]);
    assert_eq!(code, 0, "{err}");
    let image = read_all_flat_layers_from_file(&out).unwrap();
    assert_eq!(image.layer_data.len(), 1, "one part");
    let layer = &image.layer_data[0];
    let names: Vec<String> = layer
        .channel_data
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    for want in [
        "R",
        "albedo.R",
        "albedo.B",
        "normal.X",
        "normal.Z",
        "depth.Z",
        "position.Y",
        "object.id",
        "samples.count",
        "variance.G",
    ] {
        assert!(
            names.iter().any(|n| n == want),
            "{want} missing from {names:?}"
        );
    }
    let channel = |name: &str| -> Vec<f32> {
        let c = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .unwrap();
        c.sample_data.values_as_f32().collect()
    };
    // The centre pixel sees the ball head on: its albedo, a normal towards
    // the camera, 4 units away, object 0; a corner sees nothing.
    let centre = 8 * 24 + 12;
    let (ar, ab) = (channel("albedo.R")[centre], channel("albedo.B")[centre]);
    assert!(
        (ar - 0.2).abs() < 1e-4 && (ab - 0.8).abs() < 1e-4,
        "{ar} {ab}"
    );
    assert!(channel("normal.Z")[centre] < -0.9, "raw normal in [-1, 1]");
    assert!((channel("depth.Z")[centre] - 4.0).abs() < 0.05);
    assert_eq!(channel("object.id")[centre], 0.0);
    assert_eq!(
        (channel("object.id")[0], channel("depth.Z")[0]),
        (-1.0, 0.0)
    );
    assert!(channel("samples.count").iter().all(|&n| n == 4.0));
    // A PNG cannot hold them: refused before the first sample.
    let png = dir.path().join("s.png");
    let (code, err) = ptsc_stderr(&[
        "render",
        path_str(&scene),
        "--aov",
        "albedo",
        "-o",
        path_str(&png),
    ]);
    assert_ne!(code, 0);
    assert!(err.contains("--aov") && err.contains(".exr"), "{err}");
    assert!(!png.exists());
}

/// `--aov variance`: the variance of each pixel's mean from its half
/// images. Two renders with other seeds differ by twice that variance on
/// average: over the image the estimate must agree (independent samples,
/// so that the variance is the textbook one; a sky for light, whose
/// samples have no fireflies to make either side's mean wander).
#[test]
fn the_variance_aov_is_the_variance_of_each_pixels_mean() {
    use exr::prelude::*;
    let dir = temp_dir_with(&[(
        "s.pts",
        "render { resolution <48, 40> samples 16 sampler independent }\n\
         camera { position <0, 1, 4> look_at <0, 0.5, 0> }\n\
         background rgb 1\n\
         plane { normal <0, 1, 0> material { diffuse rgb 0.5 } }\n\
         sphere { center <0, 0.5, 0> radius 0.5 material { diffuse rgb 0.8 } }\n",
    )]);
    let scene = dir.path().join("s.pts");
    let read = |path: &Path, name: &str| -> Vec<f32> {
        let image = read_all_flat_layers_from_file(path).unwrap();
        let list = &image.layer_data[0].channel_data.list;
        let c = list.iter().find(|c| c.name.to_string() == name).unwrap();
        c.sample_data.values_as_f32().collect()
    };
    let mut images = Vec::new();
    for (seed, aov) in [("1", "variance"), ("2", "samples")] {
        let out = dir.path().join(format!("s{seed}.exr"));
        let args = ["render", path_str(&scene), "--seed", seed, "--aov", aov];
        let (code, err) = ptsc_stderr(&[&args[..], &["-o", path_str(&out)]].concat());
        assert_eq!(code, 0, "{err}");
        // The half images kept for the variance make no adaptive render.
        assert!(
            err.contains(" 16 spp in ") && !err.contains("converged"),
            "{err}"
        );
        images.push(out);
    }
    let (mut difference, mut estimate) = (0.0, 0.0);
    for (colour, variance) in [
        ("R", "variance.R"),
        ("G", "variance.G"),
        ("B", "variance.B"),
    ] {
        let (a, b) = (read(&images[0], colour), read(&images[1], colour));
        difference += a
            .iter()
            .zip(&b)
            .map(|(x, y)| ((x - y) as f64).powi(2))
            .sum::<f64>()
            / 2.0;
        estimate += read(&images[0], variance)
            .iter()
            .map(|&v| v as f64)
            .sum::<f64>();
    }
    let ratio = estimate / difference;
    assert!((0.8..1.25).contains(&ratio), "estimate / measured {ratio}");
}

/// One packet of tev's protocol as tev's own Python client writes it: a
/// little-endian u32 length (itself included), a type byte, the fields.
fn tev_packets(bytes: &[u8]) -> Vec<(u8, Vec<u8>)> {
    let mut packets = Vec::new();
    let mut at = 0;
    while at + 5 <= bytes.len() {
        let n = u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
        assert!(n >= 5 && at + n <= bytes.len(), "a whole packet");
        packets.push((bytes[at + 4], bytes[at + 5..at + n].to_vec()));
        at += n;
    }
    assert_eq!(at, bytes.len(), "nothing after the last packet");
    packets
}

/// Reads tev's fields from the front of a packet.
struct Fields<'a>(&'a [u8]);
impl Fields<'_> {
    fn byte(&mut self) -> u8 {
        let b = self.0[0];
        self.0 = &self.0[1..];
        b
    }
    fn text(&mut self) -> String {
        let end = self.0.iter().position(|&b| b == 0).unwrap();
        let s = String::from_utf8(self.0[..end].to_vec()).unwrap();
        self.0 = &self.0[end + 1..];
        s
    }
    fn take<const N: usize>(&mut self) -> [u8; N] {
        let v = self.0[..N].try_into().unwrap();
        self.0 = &self.0[N..];
        v
    }
    fn int(&mut self) -> i32 {
        i32::from_le_bytes(self.take())
    }
    fn long(&mut self) -> i64 {
        i64::from_le_bytes(self.take())
    }
    fn float(&mut self) -> f32 {
        f32::from_le_bytes(self.take())
    }
}

/// `--tev`: the image created in a stand-in for tev, then every pass sent
/// tile by tile; the last pass is the image written. Nothing listening:
/// refused before the render.
#[test]
fn tev_is_sent_every_pass_and_refused_when_absent() {
    use std::io::Read;
    let dir = temp_dir_with(&[(
        "s.pts",
        "render { resolution <150, 20> samples 4 }\n\
         camera { position <0, 1, 4> look_at <0, 0.5, 0> }\n\
         background rgb <0.2, 0.4, 0.8>\n\
         sphere { center <0, 0.5, 0> radius 0.5 material { diffuse rgb 0.8 } }\n",
    )]);
    let scene = dir.path().join("s.pts");
    let out = dir.path().join("s.pfm");
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let address = listener.local_addr().unwrap().to_string();
    let server = std::thread::spawn(move || {
        let (mut stream, _) = listener.accept().unwrap();
        let mut bytes = Vec::new();
        stream.read_to_end(&mut bytes).unwrap();
        bytes
    });
    let (code, err) = ptsc_stderr(&[
        "render",
        path_str(&scene),
        "--tev",
        &address,
        "-o",
        path_str(&out),
    ]);
    assert_eq!(code, 0, "{err}");
    let packets = tev_packets(&server.join().unwrap());
    let (kind, create) = &packets[0];
    let mut f = Fields(create);
    assert_eq!((*kind, f.byte(), f.text()), (4, 1, "s.pfm".to_string()));
    assert_eq!((f.int(), f.int(), f.int()), (150, 20, 3));
    assert_eq!([f.text(), f.text(), f.text()], ["R", "G", "B"]);
    // Passes to 1 and 4 spp (a batch render's: whole runs after the first
    // sample), each in two tiles (128 and 22 wide); the first and the last
    // are always shown.
    let updates = &packets[1..];
    assert_eq!(updates.len(), 4);
    let mut shown = vec![[0f32; 3]; 150 * 20];
    for (kind, update) in &updates[updates.len() - 2..] {
        let mut f = Fields(update);
        assert_eq!(
            (*kind, f.byte(), f.text(), f.int()),
            (6, 0, "s.pfm".to_string(), 3)
        );
        assert_eq!([f.text(), f.text(), f.text()], ["R", "G", "B"]);
        let (x0, y0, w, h) = (f.int(), f.int(), f.int(), f.int());
        assert_eq!([f.long(), f.long(), f.long()], [0, 1, 2], "offsets");
        assert_eq!([f.long(), f.long(), f.long()], [3, 3, 3], "strides");
        for y in y0..y0 + h {
            for x in x0..x0 + w {
                shown[(y * 150 + x) as usize] = [f.float(), f.float(), f.float()];
            }
        }
        assert!(f.0.is_empty());
    }
    let (_, _, written) = ptsc::output::read_pfm(&std::fs::read(&out).unwrap()).unwrap();
    for (s, v) in shown.iter().zip(&written) {
        assert_eq!(*s, v.to_array(), "the last pass is the image");
    }
    // Nothing listening: refused before a sample, nothing written.
    let closed = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let gone = closed.local_addr().unwrap().to_string();
    drop(closed);
    let other = dir.path().join("t.pfm");
    let (code, err) = ptsc_stderr(&[
        "render",
        path_str(&scene),
        "--tev",
        &gone,
        "-o",
        path_str(&other),
    ]);
    assert_ne!(code, 0);
    assert!(err.contains("cannot reach tev"), "{err}");
    assert!(!other.exists());
}

#[test]
fn a_default_image_over_a_texture_is_refused_by_check_and_render_alike() {
    // `poster.pts` reads `poster.png`: a render without `-o` would write
    // its image there. Check, render and watch say so before any work;
    // `-o` elsewhere renders.
    let scene = "camera { position <0, 0, 5> look_at <0, 0, 0> }\n\
        point_light { position <0, 5, 5> intensity rgb 10 }\n\
        sphere { center <0, 0, 0> radius 1 material { diffuse image { file \"poster.png\" } } }\n";
    let dir = temp_dir_with(&[("poster.pts", scene)]);
    let texture = dir.path().join("poster.png");
    let source = super::root().join("examples/images/cornell_128.png");
    std::fs::copy(&source, &texture).unwrap();
    let before = std::fs::read(&texture).unwrap();
    let path = dir.path().join("poster.pts");
    let path = path.to_str().unwrap();
    let (code, said) = ptsc_stderr(&["check", path]);
    assert_eq!(code, 1, "{said}");
    assert!(
        said.contains("would replace a file this scene reads"),
        "{said}"
    );
    assert!(said.contains("poster.pts:3:"), "the texture's line: {said}");
    let (code, said) = ptsc_stderr(&["render", path, "--resolution", "8x8", "--spp", "1"]);
    assert_eq!(code, 1, "{said}");
    assert!(
        said.contains("would replace a file this scene reads"),
        "{said}"
    );
    assert_eq!(std::fs::read(&texture).unwrap(), before);
    let elsewhere = dir.path().join("out.png");
    let elsewhere = elsewhere.to_str().unwrap();
    let args = [
        "render",
        path,
        "--resolution",
        "8x8",
        "--spp",
        "1",
        "-o",
        elsewhere,
    ];
    let (code, said) = ptsc_stderr(&args);
    assert_eq!(code, 0, "{said}");
}

#[test]
fn a_scene_whose_objects_outgrow_the_memory_is_refused_before_it_loads() {
    // A million spheres placed by twenty levels of groups placing groups:
    // a few lines, checked in kilobytes, about half a gigabyte to load.
    let mut scene = String::from(
        "camera { position <0, 0, 5> look_at <0, 0, 0> }\nbackground rgb 1\n\
         group g0 { sphere { center <0, 0, 0> radius 0.1 } }\n",
    );
    for k in 1..=20 {
        scene += &format!(
            "group g{k} {{ instance g{0} {{ }} instance g{0} {{ translate <0.001, 0, 0> }} }}\n",
            k - 1
        );
    }
    scene += "instance g20 { }\n";
    let dir = temp_dir_with(&[("many.pts", &scene)]);
    let scene = dir.path().join("many.pts");
    let out = dir.path().join("many.png");
    let render = |limit: &str| {
        render_quietly(
            &scene,
            "16x16",
            &["--memory-limit", limit, "-o", path_str(&out)],
        )
    };
    let (code, err) = render("200M");
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("pts::lower::scene_memory")
            && err.contains("needs about 0.52 GB")
            && err.contains("1,048,576 objects"),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn samples_on_the_command_line_is_spp_as_in_the_scene() {
    let dir = temp_dir_with(&[("s.pts", SPECK)]);
    let scene = dir.path().join("s.pts");
    let out = dir.path().join("s.pfm");
    let (code, err) = render_at(&scene, "8x8", &["--samples", "3", "-o", path_str(&out)]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("3 spp"), "{err}");
}

#[test]
fn noise_at_no_more_samples_than_the_minimum_is_said_to_do_nothing() {
    let dir = temp_dir_with(&[("s.pts", SPECK)]);
    let scene = dir.path().join("s.pts");
    let out = dir.path().join("s.pfm");
    let render = |spp: &str| {
        render_at(
            &scene,
            "8x8",
            &["--noise", "0.05", "--spp", spp, "-o", path_str(&out)],
        )
    };
    let (code, err) = render("8");
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("--noise has no effect at 8 spp: a pixel may stop only after 16 samples"),
        "{err}"
    );
    assert!(err.contains("or a lower --min-samples"), "{err}");
    let (code, err) = render("64");
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("no effect"), "{err}");
    // At the least --min-samples there is, only more samples help.
    let (code, err) = render_at(
        &scene,
        "8x8",
        &[
            "--noise",
            "0.05",
            "--spp",
            "2",
            "--min-samples",
            "2",
            "-o",
            path_str(&out),
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("--noise has no effect at 2 spp: a pixel may stop only after 2 samples (--min-samples); ask for more samples\n"),
        "{err}"
    );
    assert!(!err.contains("lower"), "{err}");
}
