//! End-to-end tests of the instability check of `clump run`: a deliberately
//! unstable scenario stops with exit status 1 and a message naming the step,
//! the bodies, the likely cause and the last good checkpoint; nothing of the
//! good part of the run is lost or overwritten, the last good checkpoint
//! resumes, and the detection is the same for any thread count.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn clump() -> Command {
    Command::new(env!("CARGO_BIN_EXE_clump"))
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("clump-cli-unstable-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Twenty tetrahedral clumps fall onto a floor with linear springs far too
/// stiff for the time step. The scenario is valid (dt is 0.16 × the
/// Rayleigh time of the material, which the validator checks), but dt is
/// about 30 × the linear contact time `π√(m*/k_n)`: the first hard contacts
/// blow up.
const STIFF: &str = r#"
[simulation]
dt = 4e-5
steps = 3000

[domain]
lo = [-0.03, -0.03, -0.01]
hi = [0.03, 0.03, 0.1]

[[material]]
name = "rock"
youngs_modulus = 5e6
poisson_ratio = 0.3
density = 2500

[contact]
restitution = 0.3
friction = 0.5
law = "linear"
kn = 1e9

[[template]]
name = "tetra"
material = "rock"
shape = "tetrahedron"
radius = 0.002
edge = 0.0025

[[wall]]
name = "floor"
material = "rock"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[insert]]
kind = "pack"
template = "tetra"
count = 20
region = { type = "box", lo = [-0.01, -0.01, 0.002], hi = [0.01, 0.01, 0.03] }
seed = 3

[output]
vtk = { every_steps = 100 }
thermo = { every_steps = 20 }
checkpoint = { every_steps = 100 }
"#;

fn run(dir: &Path, name: &str, text: &str, out: &str, threads: &str) -> Output {
    let sc = dir.join(name);
    std::fs::write(&sc, text).unwrap();
    clump()
        .arg("run")
        .arg(&sc)
        .arg("-o")
        .arg(dir.join(out))
        .args(["--threads", threads])
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The step named in "became unstable at step N".
fn unstable_step(err: &str) -> u64 {
    let rest = err
        .split("became unstable at step ")
        .nth(1)
        .unwrap_or_else(|| panic!("no instability message:\n{err}"));
    rest.split(' ').next().unwrap().parse().unwrap()
}

#[test]
fn unstable_run_stops_with_diagnosis_and_keeps_last_good_checkpoint() {
    let d = tmp("stiff");
    let o = run(&d, "stiff.toml", STIFF, "out", "1");
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    let step = unstable_step(&err);
    assert!(step > 100 && step < 3000, "{err}");
    assert!(err.contains("bodies involved: "), "{err}");
    // the cause names dt against the linear contact time, with a remedy
    assert!(
        err.contains("likely cause: dt = 4.000e-5 s is") && err.contains("contact duration"),
        "{err}"
    );
    assert!(err.contains("use dt ≤"), "{err}");
    assert!(err.contains("stiff.toml:3 ([simulation] dt)"), "{err}");
    // the last good checkpoint is the last periodic one before the instability
    let good = (step - 1) / 100 * 100;
    let ck = d.join("out").join(format!("checkpoint_{good:09}.ckpt"));
    assert!(ck.is_file(), "{err}");
    assert!(
        err.contains(&format!("last good checkpoint: {}", ck.display())),
        "{err}"
    );
    // nothing at or after the unstable step was written
    for e in std::fs::read_dir(d.join("out")).unwrap() {
        let name = e.unwrap().file_name().to_string_lossy().into_owned();
        if let Some(n) = name
            .strip_prefix("checkpoint_")
            .and_then(|s| s.strip_suffix(".ckpt"))
        {
            assert!(n.parse::<u64>().unwrap() < step, "{name} written");
        }
    }
    let thermo = std::fs::read_to_string(d.join("out/thermo.csv")).unwrap();
    let last: Vec<&str> = thermo.lines().last().unwrap().split(',').collect();
    assert!(last[1].parse::<u64>().unwrap() < step);
    assert!(
        !thermo.contains("NaN") && !thermo.contains("inf"),
        "{thermo}"
    );
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("out/manifest.json")).unwrap())
            .unwrap();
    assert_eq!(m["status"], format!("unstable at step {step}"));
    // the last good checkpoint loads and runs on
    let target = (good + 10).to_string();
    let r = clump()
        .arg("resume")
        .arg(&ck)
        .args(["--threads", "1", "--steps", &target])
        .output()
        .unwrap();
    assert!(r.status.success(), "{}", stderr(&r));
    // the detection does not depend on the thread count
    let o2 = run(&d, "stiff.toml", STIFF, "out2", "2");
    assert_eq!(o2.status.code(), Some(1));
    assert_eq!(unstable_step(&stderr(&o2)), step);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn overlapping_bodies_from_a_file_are_reported_at_once() {
    let d = tmp("overlap");
    std::fs::write(
        d.join("bodies.csv"),
        "template,x,y,z\ntetra,0.0,0.0,0.01\ntetra,0.0005,0.0,0.0105\ntetra,0.01,0.01,0.01\n",
    )
    .unwrap();
    let text = STIFF
        .replace("law = \"linear\"\nkn = 1e9\n", "")
        .replace("dt = 4e-5", "dt = 2e-5")
        .replace(
            "kind = \"pack\"\ntemplate = \"tetra\"\ncount = 20\nregion = { type = \"box\", lo = [-0.01, -0.01, 0.002], hi = [0.01, 0.01, 0.03] }\nseed = 3\n",
            "kind = \"file\"\nfile = \"bodies.csv\"\n",
        )
        .replace("[simulation]\n", "[simulation]\nmax_overlap_ratio = 0.2\n");
    let o = run(&d, "overlap.toml", &text, "out", "1");
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(unstable_step(&err), 1, "{err}");
    assert!(err.contains("bodies 1 and 2 overlap by"), "{err}");
    assert!(err.contains("limit max_overlap_ratio = 0.2"), "{err}");
    assert!(err.contains("bodies involved: 1, 2"), "{err}");
    assert!(
        err.contains("likely cause: overlapping initial placement"),
        "{err}"
    );
    assert!(err.contains("none was written"), "{err}");
    // a bad threshold is a scenario error with its line
    let bad = text.replace("max_overlap_ratio = 0.2", "max_overlap_ratio = 2.0");
    let o = run(&d, "bad.toml", &bad, "out3", "1");
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("max_overlap_ratio must lie in (0, 1]") && err.contains("bad.toml:3:"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&d);
}
