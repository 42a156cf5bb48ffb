//! A small settled bed in a laterally periodic box, run through the
//! scenario runner, shared by the post-processing tests; and the `vtk`
//! reader (`read_vtk.py`).
#![allow(dead_code)]

use clump_io::run::{RunOptions, Runner};
use clump_io::scenario;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The bed: dimers of 1.5 mm spheres packed into a 20 mm × 20 mm box,
/// periodic in x and y, settled on a floor at z = 0 under gravity; the
/// last stage damps nothing extra, it only lets the bed come to rest.
/// `output` is the `[output]` table's body.
pub fn bed_text(count: usize, seed: u64, output: &str) -> String {
    bed_text_steps(count, seed, 60000, output)
}

/// [`bed_text`] with `steps` steps.
pub fn bed_text_steps(count: usize, seed: u64, steps: u64, output: &str) -> String {
    format!(
        r#"
[simulation]
dt = 5e-6
gravity = [0.0, 0.0, -9.81]

[domain]
lo = [0.0, 0.0, -0.004]
hi = [0.02, 0.02, 0.05]
periodic = ["x", "y"]

[[material]]
name = "grain"
youngs_modulus = 5e7
poisson_ratio = 0.3
density = 2500

[[material]]
name = "steel"
youngs_modulus = inf
poisson_ratio = 0.3
density = 7800

[contact]
restitution = 0.1
friction = 0.5

[[template]]
name = "dimer"
material = "grain"
spheres = [[-0.0008, 0.0, 0.0, 0.0015], [0.0008, 0.0, 0.0, 0.0015]]

[[wall]]
name = "floor"
material = "steel"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[insert]]
kind = "pack"
template = "dimer"
count = {count}
region = {{ type = "box", lo = [0.0, 0.0, 0.0016], hi = [0.02, 0.02, 0.045] }}
seed = {seed}

[[stage]]
name = "settle"
steps = {steps}

[output]
{output}
"#
    )
}

/// A fresh folder under the system's temporary directory.
pub fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("clump_post_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs scenario `text` into `out`; the finished runner.
pub fn run(text: &str, out: &Path) -> Runner {
    let path = out.join("bed.toml");
    std::fs::write(&path, text).unwrap();
    let sc = scenario::load(&path).unwrap();
    let mut r = Runner::new(sc, &out.join("run")).unwrap();
    r.run(RunOptions::default()).unwrap();
    r
}

/// The files read by the `vtk` package (JSON), or `None` with a printed
/// note when no Python with `vtk` is found. Tried in order: `CLUMP_PYTHON`,
/// `python3` on the PATH (a virtual environment's), Debian's
/// `/usr/bin/python3` (where `.ci/run` installs `python3-vtk9`).
pub fn read_vtk(files: &[PathBuf]) -> Option<serde_json::Value> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/post/read_vtk.py");
    let candidates: Vec<String> = match std::env::var("CLUMP_PYTHON") {
        Ok(p) => vec![p],
        Err(_) => vec!["python3".into(), "/usr/bin/python3".into()],
    };
    for py in &candidates {
        match Command::new(py).arg(&script).args(files).output() {
            Ok(o) if o.status.success() => return Some(serde_json::from_slice(&o.stdout).unwrap()),
            // exit 3: this Python has no `vtk`; try the next
            Ok(o) if o.status.code() == Some(3) => {}
            Ok(o) => panic!("{py}: {}", String::from_utf8_lossy(&o.stderr)),
            Err(_) => {}
        }
    }
    eprintln!(
        "SKIPPED: the Python `vtk` package is not importable by {} (pip install vtk, or apt-get install python3-vtk9; CLUMP_PYTHON=<python>)",
        candidates.join(", ")
    );
    None
}

/// The value of column `name` in the last row of a CSV file.
pub fn last_column(path: &Path, name: &str) -> f64 {
    let text = std::fs::read_to_string(path).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let k = header
        .iter()
        .position(|c| *c == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    text.lines()
        .last()
        .unwrap()
        .split(',')
        .nth(k)
        .unwrap()
        .parse()
        .unwrap()
}
