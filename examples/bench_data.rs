//! Writes the data of the benchmark scenes into the repository's `target/`
//! (what `examples/bench/mesh.pts` reads), as tests and benches do on their
//! own: `cargo run --release --example bench_data`.

fn main() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    match ptsc::bench_data::ensure_mesh_blob(root) {
        Ok(path) => println!("{}", path.display()),
        Err(e) => {
            eprintln!("error: cannot write the mesh blob: {e}");
            std::process::exit(2);
        }
    }
}
