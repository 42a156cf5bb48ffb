//! `--device gpu` (the `gpu` feature; on lavapipe in CI): `clump check`
//! names the adapter and refuses at the key what the GPU path does not
//! run yet; `clump bench` runs the box bed on the device and on the CPU
//! path, which agree to round-off. Without the feature the option is
//! refused with how to build it.

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
        "the exact Richardson rotation must be refused:\n{out}\n{err}"
    );
    assert!(out.contains("  adapter "), "no adapter named in:\n{out}");
    for want in [
        "error: 'integrator.rotation' is not on the GPU path yet",
        "crates/clump-cli/tests/fixtures/gpu_refused.toml:15:1",
        "allowed on the GPU path: \"no_squish\" (the default) or \"richardson_liggghts\"",
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

#[cfg(not(feature = "gpu"))]
#[test]
fn without_the_feature_the_device_is_refused_with_how_to_build_it() {
    let (ok, _, err) = clump(&["bench", "--device", "gpu"]);
    assert!(!ok);
    assert!(err.contains("--features gpu"), "{err}");
}
