//! `check` reports every independent error of a scenario in one pass: one
//! in each of two `[[material]]`s, `[domain]` and two `[[stage]]`s,
//! each at its own line.

use clump_io::scenario::{self, Files};
use std::collections::BTreeMap;
use std::path::Path;

const TEXT: &str = r#"[simulation]
dt = 1e-5
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [-0.1, -0.1, -0.1]
hi = [0.1, -0.2, 0.1]
[[material]]
name = "rock"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2000
[[material]]
name = "soft"
youngs_modulus = 1e7
poisson_ratio = 0.7
density = 2000
[[material]]
name = "light"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = -5
[contact]
restitution = 0.5
friction = 0.5
[[template]]
name = "ball"
material = "rock"
shape = "sphere"
radius = 0.002
[[stage]]
name = "one"
duration = -1.0
[[stage]]
name = "two"
duration = 0.1
steps = 100
"#;

#[test]
fn errors_of_independent_sections_are_reported_together() {
    let err = scenario::parse(
        Path::new("s.toml"),
        TEXT.to_string(),
        Files::embedded(BTreeMap::new()),
    )
    .expect_err("the scenario has errors");
    let lines: Vec<(usize, String)> = err
        .diagnostics
        .iter()
        .map(|d| (d.location.as_ref().map_or(0, |l| l.line), d.message.clone()))
        .collect();
    eprintln!("{}", err);
    for (line, msg) in &lines {
        eprintln!("line {line}: {msg}");
    }
    // materials, domain and stages are independent of each other (the
    // stages use the dt given in [simulation]); [output] needs the stages
    let want = [
        (15, "poisson_ratio"),
        (21, "density"),
        (6, "hi"),
        (32, "duration"),
        (35, "not both"),
    ];
    for (line, word) in want {
        assert!(
            lines.iter().any(|(l, m)| *l == line && m.contains(word)),
            "no error at line {line} about '{word}': {lines:?}"
        );
    }
}
