//! The data of the benchmark scenes, made here so that a clone needs nothing
//! beside it: the 1,003,520-triangle blob of `examples/bench/mesh.pts`, byte
//! for byte the binary PLY that `../shared/bench/gen_mesh.py` writes (so the
//! Mitsuba references made from that file stay valid; a test compares the
//! two when `../shared` is there). Tests, benches and
//! `cargo run --release --example bench_data` write it once to
//! [`MESH_BLOB`] and reuse it.
//!
//! The construction (gen_mesh.py's): an icosahedron's 20 faces subdivided
//! into 224² triangles each, projected to the unit sphere, shared points
//! merged in order of first appearance; a radial displacement of 24 sines;
//! every triangle wound outward; placed on the ground; positions rounded to
//! 6 decimals, then to f32.

use glam::DVec3;
use std::collections::HashMap;
use std::io;
use std::path::{Path, PathBuf};

/// Where the blob is cached, relative to the repository root (the scene
/// `examples/bench/mesh.pts` names it there).
pub const MESH_BLOB: &str = "target/bench-data/mesh_blob.ply";
/// Subdivisions of each icosahedron edge.
const N: usize = 224;
/// The seed gen_mesh.py draws its displacement from (named in the header).
const SEED: u32 = 20240601;

/// The 24 displacement terms gen_mesh.py draws with
/// `numpy.random.default_rng(20240601)`: per term a unit direction (three
/// normal draws, normalised) and a phase (a uniform draw in [0, 2π)),
/// printed once from numpy 2.4 with `repr` (exact doubles).
const TERMS: [[f64; 4]; 24] = [
    [
        0.6312345388923883,
        0.4572444179806977,
        -0.6264746596110705,
        5.950406595263009,
    ],
    [
        -0.08028829571410227,
        0.6677956449671689,
        0.7400018690072395,
        3.3971993903901483,
    ],
    [
        0.16910387396255344,
        0.7807265798370701,
        0.601556221268443,
        0.9307920405185828,
    ],
    [
        -0.8858645723378915,
        -0.30411424512986185,
        -0.350369070246931,
        1.190142291951103,
    ],
    [
        -0.748574689842236,
        -0.07543181146738233,
        0.6587457594143201,
        2.230211344715052,
    ],
    [
        -0.4710514801133604,
        -0.05233096020679061,
        -0.8805520845962763,
        0.14273142667870387,
    ],
    [
        -0.01583261491026178,
        -0.004708631635786289,
        -0.9998635692399347,
        0.9637805192638305,
    ],
    [
        0.5877417869081055,
        -0.6423371671787244,
        0.49189689527672226,
        1.564485064859681,
    ],
    [
        -0.015014322144590562,
        -0.9110631531242253,
        -0.4119933265841605,
        1.4833779098572772,
    ],
    [
        0.7829831120826145,
        0.284598251021779,
        -0.5531195907837365,
        1.8687329241193307,
    ],
    [
        0.9493512988495527,
        -0.11214106294791204,
        0.29352426368799506,
        2.1477245829645035,
    ],
    [
        -0.1724693586432552,
        0.5635405036813955,
        -0.8078839155718496,
        1.695353599273777,
    ],
    [
        -0.571419059323388,
        -0.8039914166218584,
        0.16455412678007025,
        0.44714386250366506,
    ],
    [
        0.14597511907139116,
        -0.2517011842674348,
        -0.9567328668183527,
        3.8221930233901533,
    ],
    [
        0.19334050928639127,
        -0.5799631037866886,
        0.7913673266663145,
        5.856237879429518,
    ],
    [
        -0.8452634362909321,
        0.30581372437932514,
        0.43818682003329523,
        6.08865546679228,
    ],
    [
        0.8246094022201315,
        0.32195338470601476,
        -0.4651508914819987,
        5.468258391795772,
    ],
    [
        0.7139747024417529,
        -0.600826886879291,
        0.35950963307837824,
        3.8519794021691003,
    ],
    [
        0.7005871122938799,
        0.3140885382176536,
        -0.6407230979510729,
        0.7695099938851813,
    ],
    [
        -0.43838199345348267,
        0.022038871841057496,
        -0.8985185117423704,
        3.078318953737834,
    ],
    [
        -0.6566721395663058,
        -0.7009589155044809,
        0.2782773794116084,
        0.058234507465302954,
    ],
    [
        -0.037370407391889376,
        -0.5955077630109056,
        -0.8024798794020394,
        5.261603374140307,
    ],
    [
        0.9496815545318577,
        0.1464593475955381,
        0.27686567949791724,
        5.446175915965473,
    ],
    [
        0.6113484438756648,
        -0.07164228707646854,
        0.7881119608743772,
        2.2594096459864983,
    ],
];

/// The blob's file at `root` (the repository root), made if it is missing
/// or not the size it must have. Safe to call from tests running at once:
/// each writes a file of its own and renames it over the target.
pub fn ensure_mesh_blob(root: &Path) -> io::Result<PathBuf> {
    let path = root.join(MESH_BLOB);
    let size = (header().len() + 12 * (10 * N * N + 2) + 13 * 20 * N * N) as u64;
    if std::fs::metadata(&path).is_ok_and(|m| m.len() == size) {
        return Ok(path);
    }
    std::fs::create_dir_all(path.parent().expect("a folder"))?;
    let bytes = mesh_blob_ply();
    let tmp = path.with_extension(format!(
        "ply.{}.{:?}.tmp",
        std::process::id(),
        std::thread::current().id()
    ));
    std::fs::write(&tmp, &bytes)?;
    std::fs::rename(&tmp, &path)?;
    Ok(path)
}

/// The PLY header gen_mesh.py writes.
fn header() -> String {
    format!(
        "ply\nformat binary_little_endian 1.0\n\
         comment gen_mesh.py displaced geodesic sphere N={N} seed={SEED}\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        10 * N * N + 2,
        20 * N * N
    )
}

/// The bytes of the blob's binary PLY.
pub fn mesh_blob_ply() -> Vec<u8> {
    let (mut v, mut f) = geodesic(N);
    displace(&mut v);
    // Wound outward: the blob is star-shaped about the origin.
    for t in &mut f {
        let (a, b, c) = (v[t[0]], v[t[1]], v[t[2]]);
        let n = cross(b - a, c - a);
        let s = (a + b) + c;
        if (n.x * s.x + n.y * s.y) + n.z * s.z < 0.0 {
            t.swap(1, 2);
        }
    }
    place_on_the_ground(&mut v);
    let mut out = header().into_bytes();
    out.reserve(12 * v.len() + 13 * f.len());
    for p in &v {
        for c in [p.x, p.y, p.z] {
            let c = (c * 1e6).round_ties_even() / 1e6;
            // No "-0": numpy's `v[v == 0] = 0.0`.
            let c = if c == 0.0 { 0.0 } else { c };
            out.extend_from_slice(&(c as f32).to_le_bytes());
        }
    }
    for t in &f {
        out.push(3);
        for &i in t {
            out.extend_from_slice(&(i as i32).to_le_bytes());
        }
    }
    out
}

/// numpy's `np.cross` of two 3-vectors, term by term.
fn cross(a: DVec3, b: DVec3) -> DVec3 {
    DVec3::new(
        a.y * b.z - a.z * b.y,
        a.z * b.x - a.x * b.z,
        a.x * b.y - a.y * b.x,
    )
}

/// `v` divided by its length, summed as numpy sums three squares.
fn normalised(v: DVec3) -> DVec3 {
    let norm = ((v.x * v.x + v.y * v.y) + v.z * v.z).sqrt();
    DVec3::new(v.x / norm, v.y / norm, v.z / norm)
}

/// The class-I geodesic sphere of `n` subdivisions: vertices in order of
/// first appearance, triangles as vertex indices.
fn geodesic(n: usize) -> (Vec<DVec3>, Vec<[usize; 3]>) {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let ico: Vec<DVec3> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|&p| normalised(DVec3::from_array(p)))
    .collect();
    const FACES: [[usize; 3]; 20] = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    // The barycentric grid (i, j), i + j <= n, and one face's triangles on it.
    let grid: Vec<(usize, usize)> = (0..=n)
        .flat_map(|i| (0..=n - i).map(move |j| (i, j)))
        .collect();
    let local: HashMap<(usize, usize), usize> =
        grid.iter().enumerate().map(|(k, &ij)| (ij, k)).collect();
    let mut tris = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n - i {
            tris.push([local[&(i, j)], local[&(i + 1, j)], local[&(i, j + 1)]]);
            if j + 1 < n - i {
                tris.push([
                    local[&(i + 1, j)],
                    local[&(i + 1, j + 1)],
                    local[&(i, j + 1)],
                ]);
            }
        }
    }
    // Points merge where they round to the same 1e-7 grid point; a vertex
    // is numbered where it first appears.
    let mut index: HashMap<[i64; 3], usize> = HashMap::with_capacity(10 * n * n + 2);
    let mut verts = Vec::with_capacity(10 * n * n + 2);
    let mut faces = Vec::with_capacity(20 * n * n);
    let nf = n as f64;
    for [a, b, c] in FACES {
        let (pa, pb, pc) = (ico[a], ico[b], ico[c]);
        let (ab, ac) = (pb - pa, pc - pa);
        let ids: Vec<usize> = grid
            .iter()
            .map(|&(i, j)| {
                let (s, t) = (i as f64 / nf, j as f64 / nf);
                let p = normalised(DVec3::new(
                    (pa.x + s * ab.x) + t * ac.x,
                    (pa.y + s * ab.y) + t * ac.y,
                    (pa.z + s * ab.z) + t * ac.z,
                ));
                let key = [p.x, p.y, p.z].map(|c| (c * 1e7).round_ties_even() as i64);
                *index.entry(key).or_insert_with(|| {
                    verts.push(p);
                    verts.len() - 1
                })
            })
            .collect();
        faces.extend(tris.iter().map(|t| t.map(|k| ids[k])));
    }
    (verts, faces)
}

/// The radial displacement `r(p) = 1 + Σ a_k sin(f_k · (p·d_k) + φ_k)`.
fn displace(v: &mut [DVec3]) {
    let k_last = (TERMS.len() - 1) as f64;
    let terms: Vec<(DVec3, f64, f64, f64)> = TERMS
        .iter()
        .enumerate()
        .map(|(k, t)| {
            let x = k as f64 / k_last;
            let freq = 2.0 + 38.0 * (x * x);
            let amp = 0.09 / freq.powf(0.8);
            (DVec3::new(t[0], t[1], t[2]), freq, amp, t[3])
        })
        .collect();
    for p in v {
        let mut r = 1.0;
        for &(d, freq, amp, phase) in &terms {
            let dot = (p.x * d.x + p.y * d.y) + p.z * d.z;
            r += amp * (freq * dot + phase).sin();
        }
        *p = DVec3::new(p.x * r, p.y * r, p.z * r);
    }
}

/// Lowest point at y = 0, the box's centre at x = z = 0.
fn place_on_the_ground(v: &mut [DVec3]) {
    let min = v.iter().fold(DVec3::INFINITY, |m, p| m.min(*p));
    let max = v.iter().fold(DVec3::NEG_INFINITY, |m, p| m.max(*p));
    let (cx, cz) = (0.5 * (min.x + max.x), 0.5 * (min.z + max.z));
    for p in v {
        p.y -= min.y;
        p.x -= cx;
        p.z -= cz;
    }
}
