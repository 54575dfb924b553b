//! Parse + check throughput on a generated 100,000-sphere scene (MB/s).
//! Run: `cargo bench --bench parse`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::path::Path;

/// A deterministic scene with `n` spheres, each with its own inline material.
fn scene(n: usize) -> String {
    let mut s = String::from(
        "render { resolution <512, 512> samples 64 }\n\
         camera { position <13, 2, 3> look_at <0, 0, 0> fov 30 }\n\
         background rgb <0.7, 0.8, 1.0>\n",
    );
    let mut state = 0x2545_f491_u32;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state as f64 / u32::MAX as f64
    };
    for i in 0..n {
        let (x, z) = (
            (i % 316) as f64 + 0.9 * next(),
            (i / 316) as f64 + 0.9 * next(),
        );
        s.push_str(&format!(
            "sphere {{ center <{x:.6}, 0.2, {z:.6}> radius 0.2 material {{ diffuse rgb <{:.6}, {:.6}, {:.6}> }} }}\n",
            next(),
            next(),
            next()
        ));
    }
    s
}

fn bench(c: &mut Criterion) {
    let text = scene(100_000);
    let mut g = c.benchmark_group("parse_check");
    g.throughput(Throughput::Bytes(text.len() as u64));
    g.sample_size(10);
    g.bench_function("spheres_100k", |b| {
        b.iter(|| {
            let checked = ptsc::check::check_str(Path::new("bench.pts"), &text);
            assert!(checked.scene.is_some());
            checked
        })
    });
    g.bench_function("spheres_100k_parse_only", |b| {
        b.iter(|| {
            ptsc::syntax::parse(ptsc::source::FileId(0), &text, &ptsc::check::kinds::NAMES).unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
