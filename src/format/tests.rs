//! Layout snapshots and small cases of the formatter.

use super::format_text;

/// The formatting of `text`, which must be idempotent.
fn fmt(text: &str) -> String {
    let once = format_text(text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let twice = format_text(&once).unwrap_or_else(|e| panic!("{e}\n{once}"));
    assert_eq!(once, twice, "not idempotent");
    once
}

#[test]
fn a_short_block_stays_on_its_line() {
    assert_eq!(
        fmt("sphere   {center <0,1,0>\n radius 1}"),
        "sphere { center <0, 1, 0> radius 1 }\n"
    );
}

/// Prints the raw formatting of the file `PTS_FMT_DEBUG` (no safety net):
/// `PTS_FMT_DEBUG=x.pts cargo test --lib format::tests::debug -- --ignored --nocapture`.
#[test]
#[ignore]
fn debug() {
    let path = std::env::var("PTS_FMT_DEBUG").expect("PTS_FMT_DEBUG");
    let text = std::fs::read_to_string(path).unwrap();
    let file = super::parse(&text).unwrap();
    let out = super::print(&text, &file);
    println!("{out}");
    println!("{:?}", super::verify::verify(&text, &file, &out));
    if let Ok(after) = super::parse(&out) {
        println!("{:?}", super::verify::comment_texts(&text, &file));
        println!("{:?}", super::verify::comment_texts(&out, &after));
    }
}
