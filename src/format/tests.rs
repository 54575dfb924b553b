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
