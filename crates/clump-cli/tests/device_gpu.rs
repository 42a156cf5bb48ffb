//! `--device gpu` (the `gpu` feature; on lavapipe in CI): `clump check`
//! names the adapter and refuses at the key what the GPU path does not
//! run yet; `clump bench` runs the box bed on the device and on the CPU
//! path, which agree to round-off; `clump run|resume --device gpu` write
//! the CPU path's outputs, which agree with a CPU run to round-off, and a
//! checkpoint of either device resumes on the other. Without the feature
//! the option is refused with how to build it.

use std::path::Path;
use std::process::Command;

fn clump(args: &[&str]) -> (bool, String, String) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let o = Command::new(env!("CARGO_BIN_EXE_clump"))
        .args(args)
        .current_dir(root)
        .output()
        .unwrap();
    let text = |b: &[u8]| String::from_utf8_lossy(b).into_owned();
    (o.status.success(), text(&o.stdout), text(&o.stderr))
}

#[cfg(feature = "gpu")]
#[test]
fn check_names_the_adapter_and_refuses_at_the_key() {
    let scenario = "crates/clump-cli/tests/fixtures/gpu_refused.toml";
    let (ok, out, err) = clump(&["check", "--device", "gpu", scenario]);
    assert!(
        !ok,
        "Zhao and van Wachem's rotation must be refused:\n{out}\n{err}"
    );
    assert!(out.contains("  adapter "), "no adapter named in:\n{out}");
    for want in [
        "error: 'integrator.rotation' is not on the GPU path yet",
        "crates/clump-cli/tests/fixtures/gpu_refused.toml:15:1",
        "allowed on the GPU path: \"no_squish\" (the default), \"richardson\" or \"richardson_liggghts\"",
    ] {
        assert!(err.contains(want), "{want:?} missing from:\n{err}");
    }
}

#[cfg(feature = "gpu")]
#[test]
fn bench_agrees_with_the_cpu_path() {
    let (ok, out, err) = clump(&["bench", "--device", "gpu", "--n", "27", "--nb", "300"]);
    assert!(ok, "{out}\n{err}");
    let line = out
        .lines()
        .find(|l| l.starts_with("largest |x_gpu - x_cpu| / domain size"))
        .expect("difference line");
    let dev: f64 = line.rsplit(' ').next().unwrap().parse().unwrap();
    assert!(dev < 1e-9, "{line}");
    assert!(out.contains(" M sphere-steps/s"), "{out}");
}

/// Body positions of a run folder's final_state.json by id.
#[cfg(feature = "gpu")]
fn positions(dir: &Path) -> std::collections::BTreeMap<u64, [f64; 3]> {
    let text = std::fs::read_to_string(dir.join("final_state.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["bodies"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| {
            let p = &b["position"];
            (
                b["id"].as_u64().unwrap(),
                [0, 1, 2].map(|k| p[k].as_f64().unwrap()),
            )
        })
        .collect()
}

/// thermo.csv: header and rows.
#[cfg(feature = "gpu")]
fn thermo(dir: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(dir.join("thermo.csv")).unwrap();
    let mut lines = text.lines();
    let head = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (head, rows)
}

/// `scenario` run on the CPU path, on the GPU, and handed between them
/// through the checkpoint of step 500 in both directions, in a temporary
/// folder (`cpu`, `gpu`, `gpu_then_cpu`, `cpu_then_gpu`); every run ends
/// within 1e-12 of the box (`size`, m) of the CPU run and every thermo row
/// has the CPU's contact counts, step and body count, its other columns
/// within 1e-10 of each column's largest magnitude; the manifests name the
/// device (and adapter) of the run and of each segment (steps 0-500,
/// 500-1000).
#[cfg(feature = "gpu")]
fn four_runs(scenario: &str, size: f64) -> tempfile::TempDir {
    let tmp = tempfile::tempdir().unwrap();
    let dir = |n: &str| tmp.path().join(n);
    let s = |p: &Path| p.to_str().unwrap().to_string();
    let ok = |args: &[&str]| {
        let (ok, out, err) = clump(args);
        assert!(ok, "clump {args:?}:\n{out}\n{err}");
    };
    ok(&["run", scenario, "-o", &s(&dir("cpu"))]);
    ok(&["run", scenario, "-o", &s(&dir("gpu")), "--device", "gpu"]);
    for (name, first, then) in [
        ("gpu_then_cpu", "gpu", "cpu"),
        ("cpu_then_gpu", "cpu", "gpu"),
    ] {
        let d = dir(name);
        ok(&[
            "run",
            scenario,
            "-o",
            &s(&d),
            "--steps",
            "500",
            "--device",
            first,
        ]);
        let ckpt = d.join("checkpoint_000000500.ckpt");
        assert!(ckpt.exists(), "{name}: no checkpoint at step 500");
        ok(&["resume", &s(&ckpt), "--device", then]);
    }
    let cpu = positions(&dir("cpu"));
    let (head, cpu_rows) = thermo(&dir("cpu"));
    let pairs = head.iter().position(|h| h == "pair_contacts").unwrap();
    let most = cpu_rows.iter().map(|r| r[pairs]).fold(0.0, f64::max);
    assert!(
        most > 10.0,
        "the bed must have contacts for the comparison to mean anything"
    );
    for name in ["gpu", "gpu_then_cpu", "cpu_then_gpu"] {
        let other = positions(&dir(name));
        assert_eq!(other.len(), cpu.len(), "{name}: bodies");
        let worst = cpu
            .iter()
            .map(|(id, x)| {
                (0..3)
                    .map(|k| (x[k] - other[id][k]).abs())
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max)
            / size;
        eprintln!("{name}: largest |x - x_cpu| / L = {worst:.3e}");
        assert!(
            worst < 1e-12,
            "{name}: positions differ by {worst:e} of the box"
        );
        let (h, rows) = thermo(&dir(name));
        assert_eq!(h, head);
        assert_eq!(rows.len(), cpu_rows.len(), "{name}: thermo rows");
        for k in 0..head.len() {
            let scale = cpu_rows.iter().map(|r| r[k].abs()).fold(0.0, f64::max);
            for (a, b) in cpu_rows.iter().zip(&rows) {
                if head[k].contains("contacts") || head[k] == "step" || head[k] == "bodies" {
                    assert_eq!(a[k], b[k], "{name}: {} at step {}", head[k], a[1]);
                } else {
                    assert!(
                        (a[k] - b[k]).abs() <= 1e-10 * scale,
                        "{name}: {} at step {}: {} vs {}",
                        head[k],
                        a[1],
                        b[k],
                        a[k]
                    );
                }
            }
        }
    }
    // the manifest names the device of the run and of each resume segment
    let manifest = |n: &str| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(dir(n).join("manifest.json")).unwrap())
            .unwrap()
    };
    let adapter = manifest("gpu")["adapter"]
        .as_str()
        .unwrap_or("")
        .to_string();
    assert!(
        !adapter.is_empty(),
        "the GPU run's manifest names no adapter"
    );
    assert_eq!(manifest("cpu")["device"], "cpu");
    assert_eq!(manifest("cpu")["adapter"], serde_json::Value::Null);
    for (name, first, then) in [
        ("gpu_then_cpu", "gpu", "cpu"),
        ("cpu_then_gpu", "cpu", "gpu"),
    ] {
        let m = manifest(name);
        assert_eq!(m["device"], then, "{name}: {m}");
        let segs: Vec<(u64, u64, &str, &str)> = m["segments"]
            .as_array()
            .unwrap()
            .iter()
            .map(|g| {
                (
                    g["first_step"].as_u64().unwrap(),
                    g["final_step"].as_u64().unwrap(),
                    g["device"].as_str().unwrap(),
                    g["adapter"].as_str().unwrap_or(""),
                )
            })
            .collect();
        let named = |d: &str| if d == "gpu" { adapter.as_str() } else { "" };
        assert_eq!(
            segs,
            vec![
                (0, 500, first, named(first)),
                (500, 1000, then, named(then))
            ],
            "{name}"
        );
    }
    tmp
}

/// `gpu_pour.toml` (60 rods packed in a box of five planes under strong
/// gravity, 8 more from a stream; 1000 steps with contacts from the
/// first steps) run on the CPU path, on the GPU, and handed between them
/// through the checkpoint of step 500 in both directions. Every run ends
/// within 1e-12 of the box of the CPU run (measured on lavapipe: 1.3e-15;
/// the device sums each body's contact loads in another order than the
/// CPU path, and the contacts amplify that round-off, cpu_reference.rs);
/// every thermo row has the CPU's contact counts and its other columns
/// within 1e-10 of each column's largest magnitude (measured: 1.3e-13,
/// in a floor's sideways force).
#[cfg(feature = "gpu")]
#[test]
fn run_and_resume_on_the_gpu_agree_with_the_cpu_path() {
    let tmp = four_runs("crates/clump-cli/tests/fixtures/gpu_pour.toml", 0.061);
    let dir = |n: &str| tmp.path().join(n);
    let frames = std::fs::read_dir(dir("gpu"))
        .unwrap()
        .filter(|e| {
            let n = e.as_ref().unwrap().file_name();
            let n = n.to_string_lossy();
            n.starts_with("spheres_") && n.ends_with(".vtp")
        })
        .count();
    assert_eq!(frames, 11, "VTK frames of the GPU run");
}

/// `gpu_mill.toml`: the device scope beyond the pour, end to end from the
/// scenario's keys: a turning drum (a cylinder wall) whose rate changes
/// at the second stage, a conveyor post (a box wall), a rising floor, a
/// driven paddle and two fixed rods, EPSD rolling resistance; the
/// checkpoint of step 500 is the stage change. The four runs agree as
/// the pour's do (measured on lavapipe: 2.5e-15 of the box, GPU run).
#[cfg(feature = "gpu")]
#[test]
fn the_mill_runs_on_the_gpu_as_on_the_cpu_path() {
    let tmp = four_runs("crates/clump-cli/tests/fixtures/gpu_mill.toml", 0.061);
    let (head, rows) = thermo(&tmp.path().join("cpu"));
    let col = |name: &str| head.iter().position(|h| h == name).unwrap();
    for wall in ["floor", "drum", "post"] {
        let fx = col(&format!("{wall}_fx[N]"));
        assert!(
            rows.iter().any(|r| (fx..fx + 3).any(|k| r[k] != 0.0)),
            "wall {wall} never touched: the comparison would not test it"
        );
    }
}

/// `gpu_mesh_drum.toml`: a mesh wall end to end from the scenario's keys,
/// the example's STL drum (5 184 triangles) at rest, then turning from
/// the stage change at step 500 (the checkpoint of the hand-overs, with
/// mesh contacts live); the four runs agree as the pour's do.
#[cfg(feature = "gpu")]
#[test]
fn a_mesh_drum_runs_on_the_gpu_as_on_the_cpu_path() {
    let tmp = four_runs("crates/clump-cli/tests/fixtures/gpu_mesh_drum.toml", 0.12);
    let (head, rows) = thermo(&tmp.path().join("cpu"));
    let col = |name: &str| head.iter().position(|h| h == name).unwrap();
    let (fx, step, walls) = (col("drum_fx[N]"), col("step"), col("wall_contacts"));
    let at_500 = rows.iter().find(|r| r[step] == 500.0).unwrap();
    assert!(
        at_500[walls] > 0.0,
        "no mesh contact at the hand-over step: it would not test the slots' trip"
    );
    assert!(
        rows.iter()
            .any(|r| r[step] > 500.0 && (fx..fx + 3).any(|k| r[k] != 0.0)),
        "the turning drum never touched: the comparison would not test it"
    );
}

/// A scenario the GPU path refuses: the refusal names the key, and
/// nothing is written (the output folder is not even made).
#[cfg(feature = "gpu")]
#[test]
fn run_refuses_before_any_write() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("never");
    let scenario = "crates/clump-cli/tests/fixtures/gpu_refused.toml";
    let (ok, _, err) = clump(&[
        "run",
        scenario,
        "-o",
        out.to_str().unwrap(),
        "--device",
        "gpu",
    ]);
    assert!(!ok);
    assert!(
        err.contains("error: 'integrator.rotation' is not on the GPU path yet"),
        "{err}"
    );
    assert!(!out.exists(), "a refused run wrote {}", out.display());
}

#[cfg(not(feature = "gpu"))]
#[test]
fn without_the_feature_the_device_is_refused_with_how_to_build_it() {
    let (ok, _, err) = clump(&["bench", "--device", "gpu"]);
    assert!(!ok);
    assert!(err.contains("--features gpu"), "{err}");
}
