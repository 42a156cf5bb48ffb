//! A body file never makes scenario parsing, validation or the world build
//! panic. The first byte picks the format (CSV with a header, or `xyzq`);
//! the rest is the file's bytes, read by a fixed scenario with two templates
//! so that the template column, names and indices are exercised.
#![no_main]
use clump_io::scenario::{self, Files};
use libfuzzer_sys::fuzz_target;
use std::collections::BTreeMap;
use std::path::Path;

const SCENARIO: &str = r#"
[simulation]
dt = 1e-5
steps = 10
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [-0.1, -0.1, -0.1]
hi = [0.1, 0.1, 0.1]
[[material]]
name = "rock"
youngs_modulus = 5e6
poisson_ratio = 0.3
density = 2500
[contact]
restitution = 0.5
friction = 0.5
[[template]]
name = "ball"
material = "rock"
shape = "sphere"
radius = 0.002
[[template]]
name = "pair"
material = "rock"
spheres = [[0.0, 0.0, 0.0, 0.002], [0.002, 0.0, 0.0, 0.002]]
[[insert]]
kind = "file"
file = "b.txt"
template = "ball"
format = "FORMAT"
"#;

fuzz_target!(|data: &[u8]| {
    let (format, body) = match data.split_first() {
        Some((b, rest)) if b % 2 == 1 => ("xyzq", rest),
        Some((_, rest)) => ("csv", rest),
        None => ("csv", data),
    };
    let mut files = BTreeMap::new();
    files.insert("b.txt".to_string(), body.to_vec());
    let text = SCENARIO.replace("FORMAT", format);
    if let Ok(sc) = scenario::parse(Path::new("fuzz.toml"), text, Files::embedded(files)) {
        let _ = sc.build_world();
    }
});
