//! Embree as a yardstick, ptsc's half (issue 39, item 4): writes a bench
//! scene's geometry and three ray sets to binary files, traces the rays
//! through ptsc's own BVH (`Scene::intersect` and `Scene::occluded`, one
//! thread) and times it; the C half, `benches/embree/yardstick.c`, traces
//! the same files through Embree 3; `report` compares their answers and
//! prints the table. `scripts/embree-yardstick.sh` runs it all. Not part of
//! CI: it needs Embree (`apt-get install libembree-dev`).
//!
//! ```text
//! cargo run --release --example embree_yardstick -- dump OUT [SCENE...]
//! cargo run --release --example embree_yardstick -- report OUT...
//! cargo run --release --example embree_yardstick -- trace OUT SCENE SET QUERY
//! ```
//!
//! `trace` traces one set of a dump once more, untimed, through
//! `trace_closest` or `trace_any` (never inlined): what a profiler such as
//! `valgrind --tool=callgrind --toggle-collect='*trace_closest*'` counts.
//! Its Embree counterpart: `yardstick DIR QUALITY 1 SET` under
//! `--toggle-collect=rtcIntersect1`.
//!
//! `report` over several OUT folders (rounds of the same dump and runs)
//! gives each cell the median over the rounds.
//!
//! SCENE is a name of `examples/bench/` (default: `mesh spheres`). Ray sets,
//! each traced closest-hit and any-hit, over `(tnear, tfar)`:
//!
//! - `camera` (coherent): one ray through each pixel centre of the scene's
//!   camera at its resolution (512², pinhole), `(0, ∞)`.
//! - `diffuse` (incoherent): from the point each camera ray hits, a
//!   cosine-distributed direction about the normal on the side the camera
//!   sees (a diffuse bounce, whatever the material), the origin offset as
//!   the integrators do, `(T_MIN, ∞)`.
//! - `random` (incoherent): as `benches/bvh.rs`'s `incoherent`: origins
//!   uniform in the bounds of the scene's primitives other than quads (the
//!   blob's; the spheres'), directions uniform on the sphere, one per
//!   pixel, `(0, ∞)`.
//!
//! Files under `OUT/SCENE/` (little-endian):
//!
//! - `geometry.bin`: `PTSYGEO1`, u32 vertices, triangles, spheres; the
//!   vertices (3 × f32), triangles (3 × u32), each triangle's ptsc
//!   primitive (u32), spheres (centre, radius: 4 × f32), each sphere's
//!   primitive (u32). A quad is two triangles of one primitive.
//! - `SET.rays`: `PTSYRAY1`, u32 count, per ray 8 × f32: origin, tnear,
//!   direction, tfar.
//! - `SET.NAME.closest`: per ray f32 t and u32 primitive (∞ and
//!   `u32::MAX`: a miss); `SET.NAME.any`: per ray a byte, 1 when occluded.
//!   NAME: `ptsc`, `embree-QUALITY` (see the C half).
//! - `NAME.tsv`: the times and sizes, one row each (see `Rows`).
//!
//! Environment: `YARDSTICK_RUNS` timed passes over each set (default 5;
//! the median is reported), after one untimed pass. Times are CPU time
//! (`CLOCK_THREAD_CPUTIME_ID`; builds `CLOCK_PROCESS_CPUTIME_ID`), on both
//! sides: the machines here are shared, and wall time counted the waits
//! for a core (2× spreads between rounds under another's load).

mod report;

use glam::{Vec2, Vec3};
use ptsc::accel::bvh::Bvh;
use ptsc::accel::bvh4::Bvh4;
use ptsc::accel::tri4::{PackedTriangle, Tri4};
use ptsc::compile::{compile_file, Options};
use ptsc::geometry::shape::Shape;
use ptsc::geometry::{offset_origin, orthonormal_basis, Aabb, Ray};
use ptsc::integrator::T_MIN;
use ptsc::ir::{Prim, Scene};
use ptsc::sampling::warp::{cosine_hemisphere, uniform_sphere};
use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The ray sets, in table order.
const SETS: [&str; 3] = ["camera", "diffuse", "random"];
/// How far two answers' distances may differ and still agree, relative to
/// the distance (at least 1): the two triangle tests round differently.
const T_TOLERANCE: f32 = 1e-4;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("dump") if args.len() >= 2 => {
            let scenes: Vec<&str> = args[2..].iter().map(String::as_str).collect();
            let scenes = if scenes.is_empty() {
                vec!["mesh", "spheres"]
            } else {
                scenes
            };
            // One thread for the build as for the traversal, as Embree's
            // side is run (`threads=1`).
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(1)
                .build()
                .expect("a thread pool");
            pool.install(|| scenes.iter().try_for_each(|s| dump(Path::new(&args[1]), s)))
        }
        Some("report") if args.len() >= 2 => {
            report::report(&args[1..].iter().map(PathBuf::from).collect::<Vec<_>>())
        }
        Some("trace") if args.len() == 5 => trace(Path::new(&args[1]), &args[2], &args[3], &args[4]),
        _ => Err(
            "usage: embree_yardstick dump OUT [SCENE...] | report OUT... | trace OUT SCENE SET closest|any"
                .into(),
        ),
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}

/// One ray of a set: what both sides trace.
#[derive(Debug, Clone, Copy)]
struct YRay {
    o: Vec3,
    tnear: f32,
    d: Vec3,
    tfar: f32,
}

/// The geometry Embree is given: triangles over shared vertices and
/// spheres, each with the ptsc primitive it is.
#[derive(Default)]
struct Geometry {
    vertices: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    triangle_prims: Vec<u32>,
    spheres: Vec<[f32; 4]>,
    sphere_prims: Vec<u32>,
    /// Every primitive's shape, for the timed rebuild.
    shapes: Vec<Shape>,
}

impl Geometry {
    /// The geometry of every primitive the scene traverses: its records
    /// and the blocks' plain lanes. Only static triangles, quads and
    /// spheres, no planes: what the two bench scenes hold.
    fn of(scene: &Scene) -> Result<Geometry, String> {
        if !scene.unbounded.is_empty() || !scene.instances.is_empty() {
            return Err("planes and placements are not dumped".into());
        }
        let mut g = Geometry::default();
        let mut index = HashMap::new();
        let records = scene.prims.iter().enumerate().map(|(i, p)| {
            let Prim { shape, velocity } = p;
            (i as u32, *shape, *velocity)
        });
        let plain = (scene.wide.plain_shapes()).map(|(i, shape)| (i, shape, Vec3::ZERO));
        for (prim, shape, velocity) in records.chain(plain) {
            if velocity != Vec3::ZERO {
                return Err(format!("primitive {prim} moves"));
            }
            g.shapes.push(shape);
            match shape {
                Shape::Triangle { p0, e1, e2, .. } => {
                    g.triangle(&mut index, prim, [p0, p0 + e1, p0 + e2]);
                }
                // The parallelogram p + s·e1 + t·e2 as two triangles.
                Shape::Quad { p, e1, e2, .. } => {
                    let far = p + e1 + e2;
                    g.triangle(&mut index, prim, [p, p + e1, far]);
                    g.triangle(&mut index, prim, [p, far, p + e2]);
                }
                Shape::Sphere { center, radius } => {
                    g.spheres.push([center.x, center.y, center.z, radius]);
                    g.sphere_prims.push(prim);
                }
                other => return Err(format!("primitive {prim}: {other:?} is not dumped")),
            }
        }
        Ok(g)
    }

    /// Adds a triangle, sharing vertices with equal bits (a mesh's
    /// triangles store their first vertex and two edges: the others come
    /// back exact wherever the edge was, as for neighbouring vertices).
    fn triangle(&mut self, index: &mut HashMap<[u32; 3], u32>, prim: u32, v: [Vec3; 3]) {
        let ids = v.map(|p| {
            *index
                .entry(p.to_array().map(f32::to_bits))
                .or_insert_with(|| {
                    self.vertices.push(p);
                    self.vertices.len() as u32 - 1
                })
        });
        self.triangles.push(ids);
        self.triangle_prims.push(prim);
    }

    fn write(&self, path: &Path) -> std::io::Result<()> {
        let mut b = b"PTSYGEO1".to_vec();
        for n in [
            self.vertices.len(),
            self.triangles.len(),
            self.spheres.len(),
        ] {
            b.extend((n as u32).to_le_bytes());
        }
        let floats = (self.vertices.iter()).flat_map(|v| v.to_array());
        b.extend(floats.flat_map(f32::to_le_bytes));
        b.extend(
            self.triangles
                .iter()
                .flatten()
                .flat_map(|i| i.to_le_bytes()),
        );
        b.extend(self.triangle_prims.iter().flat_map(|i| i.to_le_bytes()));
        b.extend(self.spheres.iter().flatten().flat_map(|f| f.to_le_bytes()));
        b.extend(self.sphere_prims.iter().flat_map(|i| i.to_le_bytes()));
        std::fs::write(path, b)
    }
}

/// xorshift32 in [0, 1): deterministic rays, as `benches/bvh.rs` draws them.
fn uniform(state: &mut u32) -> f32 {
    *state ^= *state << 13;
    *state ^= *state >> 17;
    *state ^= *state << 5;
    (*state >> 8) as f32 / (1u32 << 24) as f32
}

/// The three ray sets of `scene` (see the file's header).
fn ray_sets(scene: &Scene, geometry: &Geometry) -> [Vec<YRay>; 3] {
    let (w, h) = (scene.settings.width, scene.settings.height);
    let camera: Vec<YRay> = (0..w * h)
        .map(|i| {
            let film = Vec2::new((i % w) as f32 + 0.5, (i / w) as f32 + 0.5);
            let r = scene.camera.ray(film, Vec2::splat(0.5), 0.0);
            YRay {
                o: r.o,
                tnear: 0.0,
                d: r.d,
                tfar: f32::INFINITY,
            }
        })
        .collect();
    let mut s = 0x2545_f491;
    let diffuse = (camera.iter())
        .filter_map(|r| {
            let hit = scene.intersect(&Ray::new(r.o, r.d, 0.0), r.tnear, r.tfar)?;
            let n = if hit.n_geo.dot(r.d) < 0.0 {
                hit.n_geo
            } else {
                -hit.n_geo
            };
            let (t, b) = orthonormal_basis(n);
            let l = cosine_hemisphere(Vec2::new(uniform(&mut s), uniform(&mut s)));
            let d = (t * l.x + b * l.y + n * l.z).normalize();
            Some(YRay {
                o: offset_origin(hit.p, hit.n_geo, d),
                tnear: T_MIN,
                d,
                tfar: f32::INFINITY,
            })
        })
        .collect();
    // The box of everything but the quads (the bench scenes' ground and
    // light): the blob's, as `benches/bvh.rs` draws in the mesh's bounds,
    // and the spheres'; with the ground most origins would lie in empty
    // space.
    let bounds = (geometry.shapes.iter())
        .filter(|s| !matches!(s, Shape::Quad { .. }))
        .fold(Aabb::EMPTY, |b, s| b.union(s.bounds()));
    let mut s = 0x9e37_79b9;
    let random = (0..camera.len())
        .map(|_| {
            let u = Vec3::new(uniform(&mut s), uniform(&mut s), uniform(&mut s));
            YRay {
                o: bounds.min + (bounds.max - bounds.min) * u,
                tnear: 0.0,
                d: uniform_sphere(Vec2::new(uniform(&mut s), uniform(&mut s))),
                tfar: f32::INFINITY,
            }
        })
        .collect();
    [camera, diffuse, random]
}

fn write_rays(path: &Path, rays: &[YRay]) -> std::io::Result<()> {
    let mut b = b"PTSYRAY1".to_vec();
    b.extend((rays.len() as u32).to_le_bytes());
    for r in rays {
        let f = [r.o.x, r.o.y, r.o.z, r.tnear, r.d.x, r.d.y, r.d.z, r.tfar];
        b.extend(f.iter().flat_map(|x| x.to_le_bytes()));
    }
    std::fs::write(path, b)
}

/// Reads a set written by [`write_rays`].
fn read_rays(path: &Path) -> Result<Vec<YRay>, String> {
    let b = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let body = b
        .strip_prefix(b"PTSYRAY1".as_slice())
        .filter(|body| body.len() >= 4)
        .ok_or_else(|| format!("{}: not a ray set", path.display()))?;
    let f: Vec<f32> = body[4..]
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    Ok(f.chunks_exact(8)
        .map(|r| YRay {
            o: Vec3::new(r[0], r[1], r[2]),
            tnear: r[3],
            d: Vec3::new(r[4], r[5], r[6]),
            tfar: r[7],
        })
        .collect())
}

/// Traces one set of a dump of `scene` once (see the module's doc).
fn trace(out: &Path, name: &str, set: &str, query: &str) -> Result<(), String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = root.join("examples/bench").join(format!("{name}.pts"));
    let compiled =
        compile_file(&path, Options::default()).map_err(|e| format!("{}: {e}", path.display()))?;
    let scene = (compiled.ir).ok_or_else(|| format!("{}: does not compile", path.display()))?;
    let rays = read_rays(&out.join(name).join(format!("{set}.rays")))?;
    let hits = match query {
        "closest" => trace_closest(&scene, &rays),
        "any" => trace_any(&scene, &rays),
        _ => return Err(format!("`{query}`: the query is `closest` or `any`")),
    };
    eprintln!("{name} {set} {query}: {} rays, {hits} hits", rays.len());
    Ok(())
}

/// Closest hits of `rays`; how many hit.
#[inline(never)]
fn trace_closest(scene: &Scene, rays: &[YRay]) -> usize {
    (rays.iter())
        .filter(|r| (scene.intersect(&Ray::new(r.o, r.d, 0.0), r.tnear, r.tfar)).is_some())
        .count()
}

/// Any hits of `rays`; how many are blocked.
#[inline(never)]
fn trace_any(scene: &Scene, rays: &[YRay]) -> usize {
    (rays.iter())
        .filter(|r| scene.occluded(&Ray::new(r.o, r.d, 0.0), r.tnear, r.tfar))
        .count()
}

/// Rows of a `NAME.tsv` (tab-separated, the first field the kind):
/// `trace SET QUERY RAYS HITS CHECKSUM MEDIAN MIN MAX WALL` (CHECKSUM: the
/// sum of the hit distances, in ray order, as f64; 0 for any-hit; the
/// thread's CPU seconds of a pass over the set: median, minimum, maximum;
/// the median of wall seconds), `build SECONDS` (median of 3, the process's
/// CPU time), `bytes WHAT BYTES`, `count WHAT N`, `note TEXT`.
#[derive(Default)]
struct Rows(String);

impl Rows {
    fn row(&mut self, fields: &[&dyn std::fmt::Display]) {
        let line: Vec<String> = fields.iter().map(|f| f.to_string()).collect();
        writeln!(self.0, "{}", line.join("\t")).expect("a string");
    }
}

/// A clock in seconds: the CPU time of the calling thread or of the
/// whole process (where there are none, wall time from the first call).
/// On a machine shared with other work, CPU time is the time the code ran;
/// wall time also counts the time it waited for a core.
fn cpu_seconds(thread: bool) -> f64 {
    #[cfg(unix)]
    {
        use rustix::time::{clock_gettime, ClockId};
        let clock = if thread {
            ClockId::ThreadCPUTime
        } else {
            ClockId::ProcessCPUTime
        };
        let t = clock_gettime(clock);
        t.tv_sec as f64 + 1e-9 * t.tv_nsec as f64
    }
    #[cfg(not(unix))]
    {
        let _ = thread;
        static START: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();
        START.get_or_init(Instant::now).elapsed().as_secs_f64()
    }
}

/// The seconds `pass` takes over `runs` timed calls after one untimed
/// call: the median, minimum and maximum of `clock`'s, and the median of
/// wall time.
fn time(runs: usize, clock: impl Fn() -> f64, mut pass: impl FnMut()) -> [f64; 4] {
    pass();
    let (mut t, mut wall): (Vec<f64>, Vec<f64>) = (0..runs)
        .map(|_| {
            let (start, wall) = (clock(), Instant::now());
            pass();
            (clock() - start, wall.elapsed().as_secs_f64())
        })
        .unzip();
    t.sort_by(f64::total_cmp);
    wall.sort_by(f64::total_cmp);
    [t[t.len() / 2], t[0], t[t.len() - 1], wall[wall.len() / 2]]
}

fn runs() -> usize {
    std::env::var("YARDSTICK_RUNS")
        .ok()
        .and_then(|s| s.parse().ok())
        .filter(|&n| n > 0)
        .unwrap_or(5)
}

fn dump(out: &Path, name: &str) -> Result<(), String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    if name == "mesh" {
        ptsc::bench_data::ensure_mesh_blob(root).map_err(|e| format!("the mesh blob: {e}"))?;
    }
    let path = root.join("examples/bench").join(format!("{name}.pts"));
    let compiled =
        compile_file(&path, Options::default()).map_err(|e| format!("{}: {e}", path.display()))?;
    let lower_seconds = compiled.lower_seconds;
    let scene = compiled
        .ir
        .ok_or_else(|| format!("{}: does not compile", path.display()))?;
    let dir = out.join(name);
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let io = |e: std::io::Error| e.to_string();

    let geometry = Geometry::of(&scene)?;
    geometry.write(&dir.join("geometry.bin")).map_err(io)?;
    let mut rows = Rows::default();
    rows.row(&[&"count", &"triangles", &geometry.triangles.len()]);
    rows.row(&[&"count", &"vertices", &geometry.vertices.len()]);
    rows.row(&[&"count", &"spheres", &geometry.spheres.len()]);
    rows.row(&[&"count", &"primitives", &geometry.shapes.len()]);
    eprintln!(
        "{name}: {} triangles over {} vertices, {} spheres",
        geometry.triangles.len(),
        geometry.vertices.len(),
        geometry.spheres.len()
    );
    let runs = runs();
    rows.row(&[
        &"note",
        &format!("one thread; medians of {runs}; the thread's CPU time"),
    ]);

    // The tree as the renderer holds it (blocks of four triangles and the
    // count of plain lanes before each block, 4 bytes; records of the
    // primitives not in blocks, the spheres'), and apart the 4-byte object
    // of every primitive, which has no counterpart in Embree's scene.
    let wide = &scene.wide;
    rows.row(&[
        &"bytes",
        &"nodes",
        &(wide.nodes.len() * size_of::<ptsc::accel::bvh4::Node4>()),
    ]);
    rows.row(&[
        &"bytes",
        &"blocks",
        &(wide.tris.len() * (size_of::<Tri4>() + 4)),
    ]);
    rows.row(&[
        &"bytes",
        &"records",
        &(scene.prims.len() * size_of::<Prim>()),
    ]);
    rows.row(&[&"bytes", &"objects", &(scene.prim_object.len() * 4)]);
    rows.row(&[&"count", &"nodes", &wide.nodes.len()]);
    rows.row(&[&"count", &"blocks", &wide.tris.len()]);
    rows.row(&[&"lower", &lower_seconds]);

    // The build alone, as lowering makes it (binned SAH, collapse to 4
    // wide, packing), over the primitives' shapes on one thread.
    // The whole process's CPU time: the build runs on the pool's thread.
    let [build, _, _, _] = time(
        3,
        || cpu_seconds(false),
        || {
            black_box(build_tree(&geometry.shapes));
        },
    );
    rows.row(&[&"build", &build]);
    eprintln!("{name}: ptsc build {build:.3} s (lowering {lower_seconds:.3} s)");

    for (set, rays) in SETS.iter().zip(ray_sets(&scene, &geometry)) {
        write_rays(&dir.join(format!("{set}.rays")), &rays).map_err(io)?;
        let n = rays.len();
        let mut closest = vec![(f32::INFINITY, u32::MAX); n];
        let [closest_median, min, max, wall] = time(
            runs,
            || cpu_seconds(true),
            || {
                for (r, out) in rays.iter().zip(closest.iter_mut()) {
                    let ray = Ray::new(r.o, r.d, 0.0);
                    *out = scene
                        .intersect(&ray, r.tnear, r.tfar)
                        .map_or((f32::INFINITY, u32::MAX), |h| (h.t, h.prim));
                }
            },
        );
        let hits = closest.iter().filter(|c| c.1 != u32::MAX).count();
        let checksum: f64 = (closest.iter())
            .filter(|c| c.1 != u32::MAX)
            .map(|c| c.0 as f64)
            .sum();
        rows.row(&[
            &"trace",
            set,
            &"closest",
            &n,
            &hits,
            &checksum,
            &closest_median,
            &min,
            &max,
            &wall,
        ]);
        let bytes: Vec<u8> = (closest.iter())
            .flat_map(|&(t, p)| t.to_le_bytes().into_iter().chain(p.to_le_bytes()))
            .collect();
        std::fs::write(dir.join(format!("{set}.ptsc.closest")), bytes).map_err(io)?;

        let mut any = vec![0u8; n];
        let [median, min, max, any_wall] = time(
            runs,
            || cpu_seconds(true),
            || {
                for (r, out) in rays.iter().zip(any.iter_mut()) {
                    let ray = Ray::new(r.o, r.d, 0.0);
                    *out = scene.occluded(&ray, r.tnear, r.tfar) as u8;
                }
            },
        );
        let hits = any.iter().filter(|&&a| a != 0).count();
        rows.row(&[
            &"trace", set, &"any", &n, &hits, &0, &median, &min, &max, &any_wall,
        ]);
        std::fs::write(dir.join(format!("{set}.ptsc.any")), &any).map_err(io)?;
        eprintln!(
            "{name} {set}: {n} rays, ptsc {:.2} Mrays/s closest, {:.2} any",
            n as f64 / closest_median / 1e6,
            n as f64 / median / 1e6
        );
    }
    std::fs::write(dir.join("ptsc.tsv"), rows.0).map_err(io)
}

/// The wide tree over `shapes` built as lowering builds it.
fn build_tree(shapes: &[Shape]) -> Bvh4 {
    let boxes: Vec<Aabb> = shapes.iter().map(Shape::bounds).collect();
    let bvh = Bvh::build(&boxes, &|i| {
        PackedTriangle::of(&shapes[i as usize]).is_some()
    });
    drop(boxes);
    let mut wide = Bvh4::from_binary(&bvh);
    let order = bvh.order;
    wide.pack_triangles(|place| PackedTriangle::of(&shapes[order[place as usize] as usize]));
    wide
}
