//! The C example (examples/c/coupling.c) compiled with the system C
//! compiler against `include/clump.h` and the crate's shared library,
//! with every warning an error, and run: its coupling loop must finish
//! and report what it read.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The folder holding this build's `libclump_capi.so` (beside the test binary).
fn library_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    let deps = exe.parent().expect("deps folder").to_path_buf();
    for d in [
        deps.clone(),
        deps.parent().expect("profile folder").to_path_buf(),
    ] {
        if d.join("libclump_capi.so").exists() {
            return d;
        }
    }
    panic!("libclump_capi.so not found beside {}", exe.display());
}

#[test]
fn c_example_compiles_and_runs_its_coupling_loop() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = crate_dir.join("../..");
    let lib = library_dir();
    let tmp = tempfile::tempdir().expect("temp dir");
    let exe = tmp.path().join("coupling");
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let out = Command::new(&cc)
        .args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"])
        .arg(root.join("examples/c/coupling.c"))
        .arg("-I")
        .arg(crate_dir.join("include"))
        .arg("-L")
        .arg(&lib)
        .arg("-lclump_capi")
        .arg(format!("-Wl,-rpath,{}", lib.display()))
        .arg("-o")
        .arg(&exe)
        .output()
        .unwrap_or_else(|e| panic!("cannot run the C compiler `{cc}`: {e}"));
    assert!(
        out.status.success(),
        "the C example does not compile:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // the library of this build, not an older one that cargo's library
    // path (which comes before the rpath) may list first
    let run = Command::new(&exe)
        .env("LD_LIBRARY_PATH", &lib)
        .arg(root.join("examples/c/settling.toml"))
        .output()
        .expect("run the C example");
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "the C example failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(stdout.contains("NULL velocity: CLUMP_ERR_NULL"), "{stdout}");
    let rows: Vec<&str> = stdout.lines().filter(|l| l.starts_with("t = ")).collect();
    assert_eq!(rows.len(), 5, "{stdout}");
    for r in &rows {
        assert!(r.contains("bodies 40"), "{r}");
        // buoyancy and the upward drag push the grains up: the summed fluid force is > 0
        let fz: f64 = r
            .split("sum fluid Fz = ")
            .nth(1)
            .and_then(|s| s.split_whitespace().next())
            .and_then(|s| s.parse().ok())
            .expect("fluid force column");
        assert!(fz > 0.0, "{r}");
    }
    assert!(stdout.trim_end().ends_with("done"), "{stdout}");
}
