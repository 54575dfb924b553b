//! The yardstick's report: reads the times and answers both halves wrote,
//! compares the answers ray by ray and prints the table (see `main.rs`).

use super::*;

/// A renderer's rows of one scene, by kind.
#[derive(Default)]
struct Parsed {
    /// (set, query) → (rays, hits, checksum, median seconds).
    trace: BTreeMap<(String, String), (usize, usize, f64, f64)>,
    /// Other rows: kind and name → value.
    values: BTreeMap<String, String>,
}

fn parse(path: &Path) -> Option<Parsed> {
    let text = std::fs::read_to_string(path).ok()?;
    let mut p = Parsed::default();
    for line in text.lines() {
        let f: Vec<&str> = line.split('\t').collect();
        match f.as_slice() {
            ["trace", set, query, rays, hits, checksum, median, ..] => {
                p.trace.insert(
                    (set.to_string(), query.to_string()),
                    (
                        rays.parse().ok()?,
                        hits.parse().ok()?,
                        checksum.parse().ok()?,
                        median.parse().ok()?,
                    ),
                );
            }
            [kind, name, value] => {
                p.values.insert(format!("{kind} {name}"), value.to_string());
            }
            [kind, value] => {
                p.values.insert(kind.to_string(), value.to_string());
            }
            _ => {}
        }
    }
    Some(p)
}

fn read_closest(path: &Path) -> Option<Vec<(f32, u32)>> {
    let b = std::fs::read(path).ok()?;
    let word = |c: &[u8]| [c[0], c[1], c[2], c[3]];
    Some(
        b.chunks_exact(8)
            .map(|c| {
                (
                    f32::from_le_bytes(word(&c[..4])),
                    u32::from_le_bytes(word(&c[4..])),
                )
            })
            .collect(),
    )
}

/// How two renderers' closest hits compare, ray by ray.
#[derive(Default)]
struct Agreement {
    rays: usize,
    /// Both miss, or both hit the same primitive at distances within
    /// [`T_TOLERANCE`].
    same: usize,
    /// Both hit within the tolerance, different primitives (a shared
    /// edge, or the two triangles of a quad).
    other_prim: usize,
    /// Both hit, the distances further apart.
    t_differs: usize,
    /// One hits, the other misses.
    hit_miss: usize,
    /// The largest relative distance difference of the agreeing hits.
    max_rel: f32,
}

fn compare_closest(a: &[(f32, u32)], b: &[(f32, u32)]) -> Agreement {
    let mut g = Agreement {
        rays: a.len(),
        ..Agreement::default()
    };
    for (&(ta, pa), &(tb, pb)) in a.iter().zip(b) {
        match (pa != u32::MAX, pb != u32::MAX) {
            (false, false) => g.same += 1,
            (true, true) => {
                let rel = (ta - tb).abs() / ta.abs().max(1.0);
                if rel > T_TOLERANCE {
                    g.t_differs += 1;
                } else if pa == pb {
                    g.same += 1;
                    g.max_rel = g.max_rel.max(rel);
                } else {
                    g.other_prim += 1;
                }
            }
            _ => g.hit_miss += 1,
        }
    }
    g
}

/// The order of the Embree builds in the tables: by quality, then the
/// variants (`-user`).
fn embree_order(name: &str) -> (usize, String) {
    let quality = ["embree-high", "embree-medium", "embree-low"]
        .iter()
        .position(|q| name.starts_with(q))
        .unwrap_or(3);
    (quality, name.to_string())
}

/// The name a table gives an Embree build (`embree-high-user` → `high, user spheres`).
fn embree_label(name: &str) -> String {
    let q = name.trim_start_matches("embree-");
    match q.strip_suffix("-user") {
        Some(q) => format!("{q}, user spheres"),
        None => q.to_string(),
    }
}

/// The `report` command: the Mrays/s table (per cell the median over the
/// rounds `outs` of the medians each round timed), the agreement of each
/// Embree build with ptsc (from the first round), build times and
/// memory, as Markdown.
pub fn report(outs: &[PathBuf]) -> Result<(), String> {
    let first = outs.first().ok_or("no folder to report on")?;
    let mut scenes: Vec<String> = std::fs::read_dir(first)
        .map_err(|e| format!("{}: {e}", first.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.join("ptsc.tsv").is_file())
        .filter_map(|p| Some(p.file_name()?.to_string_lossy().into_owned()))
        .collect();
    scenes.sort();
    // Every renderer of every scene and round: ptsc, then Embree's builds.
    let mut embrees: Vec<String> = Vec::new();
    for out in outs {
        for scene in &scenes {
            for e in std::fs::read_dir(out.join(scene))
                .into_iter()
                .flatten()
                .flatten()
            {
                let file = e.file_name().to_string_lossy().into_owned();
                if let Some(name) = file
                    .strip_suffix(".tsv")
                    .filter(|n| n.starts_with("embree-"))
                {
                    if !embrees.iter().any(|e| e == name) {
                        embrees.push(name.to_string());
                    }
                }
            }
        }
    }
    embrees.sort_by_key(|n| embree_order(n));
    let renderers: Vec<&str> = std::iter::once("ptsc")
        .chain(embrees.iter().map(String::as_str))
        .collect();
    // parsed[round][scene][renderer]
    let parsed: Vec<Vec<Vec<Option<Parsed>>>> = (outs.iter())
        .map(|out| {
            (scenes.iter())
                .map(|scene| {
                    (renderers.iter())
                        .map(|r| parse(&out.join(scene).join(format!("{r}.tsv"))))
                        .collect()
                })
                .collect()
        })
        .collect();
    let labels: Vec<String> = embrees.iter().map(|e| embree_label(e)).collect();

    let mut speed = format!(
        "| scene | rays | query | ptsc |{}{}\n| --- | --- | --- | ---: |{}{}\n",
        labels
            .iter()
            .map(|l| format!(" Embree {l} |"))
            .collect::<String>(),
        labels
            .iter()
            .map(|l| format!(" ptsc / {l} |"))
            .collect::<String>(),
        " ---: |".repeat(labels.len()),
        " ---: |".repeat(labels.len()),
    );
    let mut agree = String::from(
        "| scene | rays | query | Embree | rays | same | other primitive, same t | t differs | hit/miss differ | hits ptsc / Embree | checksum rel. diff. |\n\
         | --- | --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n",
    );
    let mut builds = String::from(
        "| scene | renderer | build (s) | bytes | per primitive | build peak |\n\
         | --- | --- | ---: | ---: | ---: | ---: |\n",
    );
    for (si, scene) in scenes.iter().enumerate() {
        let dir = first.join(scene);
        let ptsc = parsed[0][si][0].as_ref().ok_or("ptsc.tsv does not parse")?;
        for set in SETS {
            for query in ["closest", "any"] {
                let key = (set.to_string(), query.to_string());
                // Per renderer, the median over the rounds.
                let mrays: Vec<Option<f64>> = (0..renderers.len())
                    .map(|r| {
                        let mut m: Vec<f64> = (parsed.iter())
                            .filter_map(|round| {
                                let &(n, _, _, s) = round[si][r].as_ref()?.trace.get(&key)?;
                                Some(n as f64 / s / 1e6)
                            })
                            .collect();
                        m.sort_by(f64::total_cmp);
                        m.get(m.len().saturating_sub(1) / 2).copied()
                    })
                    .collect();
                let cell = |m: Option<f64>| m.map_or("–".into(), |m| format!("{m:.2}"));
                let ratio = |e: Option<f64>| match (mrays[0], e) {
                    (Some(p), Some(e)) => format!("{:.2}", p / e),
                    _ => "–".into(),
                };
                writeln!(
                    speed,
                    "| {scene} | {set} | {query} | {} |{}{}",
                    cell(mrays[0]),
                    mrays[1..]
                        .iter()
                        .map(|&m| format!(" {} |", cell(m)))
                        .collect::<String>(),
                    mrays[1..]
                        .iter()
                        .map(|&m| format!(" {} |", ratio(m)))
                        .collect::<String>(),
                )
                .expect("a string");
                for (r, embree) in embrees.iter().zip(&parsed[0][si][1..]) {
                    let Some(embree) = embree else { continue };
                    let (Some(a), Some(b)) = (ptsc.trace.get(&key), embree.trace.get(&key)) else {
                        continue;
                    };
                    let file = |who: &str| dir.join(format!("{set}.{who}.{query}"));
                    let (rays, same, other, t_differs, hit_miss, max_rel) = if query == "closest" {
                        let (Some(pa), Some(pb)) =
                            (read_closest(&file("ptsc")), read_closest(&file(r)))
                        else {
                            continue;
                        };
                        let g = compare_closest(&pa, &pb);
                        let other = g.other_prim.to_string();
                        let t = g.t_differs.to_string();
                        (g.rays, g.same, other, t, g.hit_miss, Some(g.max_rel))
                    } else {
                        let (Ok(pa), Ok(pb)) =
                            (std::fs::read(file("ptsc")), std::fs::read(file(r)))
                        else {
                            continue;
                        };
                        let differ = pa.iter().zip(&pb).filter(|(x, y)| x != y).count();
                        (
                            pa.len(),
                            pa.len() - differ,
                            "–".into(),
                            "–".into(),
                            differ,
                            None,
                        )
                    };
                    let checksum = if query == "closest" {
                        format!("{:.1e}", (a.2 - b.2).abs() / a.2.abs().max(1.0))
                    } else {
                        "–".into()
                    };
                    let max_rel =
                        max_rel.map_or(String::new(), |m| format!(" (max rel. Δt {m:.0e})"));
                    writeln!(
                        agree,
                        "| {scene} | {set} | {query} | {} | {rays} | {same}{max_rel} | {other} | {t_differs} | {hit_miss} | {} / {} | {checksum} |",
                        embree_label(r),
                        a.1,
                        b.1,
                    )
                    .expect("a string");
                }
            }
        }
        // Memory: the first round's (the same every round); build times:
        // the median over the rounds.
        let value = |p: &Option<Parsed>, k: &str| p.as_ref().and_then(|p| p.values.get(k).cloned());
        let number = |p: &Option<Parsed>, k: &str| value(p, k).and_then(|v| v.parse::<f64>().ok());
        let count = |k: &str| number(&parsed[0][si][0], &format!("count {k}")).unwrap_or(0.0);
        let primitives = count("triangles") + count("spheres");
        let bytes = |b: Option<f64>| b.map_or("–".into(), |b| format!("{b:.0}"));
        let per = |b: Option<f64>| b.map_or("–".into(), |b| format!("{:.1}", b / primitives));
        for (ri, (r, p)) in renderers.iter().zip(&parsed[0][si]).enumerate() {
            if p.is_none() {
                continue;
            }
            let mut build: Vec<f64> = (parsed.iter())
                .filter_map(|round| number(&round[si][ri], "build"))
                .collect();
            build.sort_by(f64::total_cmp);
            let build = build.get(build.len().saturating_sub(1) / 2);
            // ptsc: wide nodes, blocks and records; Embree: its own
            // allocations after the build (memory monitor) and the vertex
            // and index buffers it shares with the harness.
            let parts: &[&str] = if *r == "ptsc" {
                &["nodes", "blocks", "records"]
            } else {
                &["bvh", "buffers"]
            };
            let total: Option<f64> = (parts.iter())
                .map(|k| number(p, &format!("bytes {k}")))
                .sum();
            let peak = number(p, "bytes peak");
            let name = if *r == "ptsc" {
                "ptsc".to_string()
            } else {
                format!("Embree {}", embree_label(r))
            };
            writeln!(
                builds,
                "| {scene} | {name} | {} | {} | {} | {} |",
                build.map_or("–".into(), |s| format!("{s:.3}")),
                bytes(total),
                per(total),
                bytes(peak),
            )
            .expect("a string");
        }
    }
    let rounds = outs.len();
    println!(
        "Mrays/s, one thread (each cell the median of {rounds} round(s) of medians):\n\n{speed}"
    );
    println!("Agreement with ptsc's answers (t within {T_TOLERANCE:e} relative):\n\n{agree}");
    println!(
        "Builds (one thread, CPU seconds, the median over the rounds of medians of 3) and memory (ptsc: wide nodes, blocks with their \
         4-byte plain-lane counts, records; Embree: its allocations after the build by its \
         memory monitor, plus the vertex and index buffers it shares; per primitive: per \
         triangle or sphere):\n\n{builds}"
    );
    Ok(())
}
