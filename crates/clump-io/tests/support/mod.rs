//! Helpers shared by the scenario-level tests.
#![allow(dead_code)]

use std::path::Path;

/// The last row of a CSV output (trajectory, thermo): value of column `name`.
pub fn last_value(path: &Path, name: &str) -> f64 {
    let text = std::fs::read_to_string(path).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let last: Vec<f64> = text
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    last[header
        .iter()
        .position(|c| *c == name)
        .unwrap_or_else(|| panic!("no column {name}"))]
}

/// Parses `text` (as `case.toml`, files from `tests/bad_scenarios`) and
/// checks that it is refused at the line of `marker` with an error that
/// contains every string of `want`.
pub fn refused(text: &str, marker: &str, want: &[&str]) {
    let line = text[..text.find(marker).expect("marker")]
        .matches('\n')
        .count()
        + 1;
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_scenarios");
    let e = clump_io::scenario::parse(
        Path::new("case.toml"),
        text.to_string(),
        clump_io::scenario::Files::disk(&base),
    )
    .map(|_| ())
    .expect_err("the scenario must be refused");
    let msg = e.to_string();
    assert!(
        msg.contains(&format!("case.toml:{line}:")),
        "line {line}:\n{msg}"
    );
    for w in want {
        assert!(msg.contains(w), "lacks {w:?}:\n{msg}");
    }
}
