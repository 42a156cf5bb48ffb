//! `clump bench` refuses meaningless options with an error that names the
//! option, before it builds or runs anything.

use std::process::Command;

/// Runs `clump bench ARGS`, checks that it fails, and returns its stderr.
fn refused(args: &[&str]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_clump"))
        .arg("bench")
        .args(args)
        .output()
        .unwrap();
    assert!(!o.status.success(), "{args:?} succeeded");
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn bench_bad_options_are_named_errors() {
    for (args, needle) in [
        (&["--threads", "0"][..], "--threads"),
        (&["--scaling", "10000,0"][..], "--scaling"),
        (&["--scaling", "10000", "--steps", "0"][..], "--steps"),
    ] {
        let err = refused(args);
        assert!(
            err.contains(needle) && err.contains("got 0"),
            "{args:?}: {err}"
        );
    }
}

/// The bench's internal one-round mode (which it runs as a child process
/// per round) names what it lacks instead of running a default case.
#[test]
fn a_child_round_without_its_inputs_is_refused() {
    let err = refused(&["--child-round", "--na", "10", "--nb", "10"]);
    assert!(
        err.contains("--child-round") && err.contains("--scenario"),
        "{err}"
    );
    let err = refused(&[
        "--child-round",
        "--scenario",
        "/nonexistent/bed.toml",
        "--na",
        "10",
        "--nb",
        "10",
    ]);
    assert!(err.contains("/nonexistent/bed.toml"), "{err}");
    assert!(!err.contains("error: error:"), "{err}");
}

/// The stone cases refuse a missing stone template, or no stones, with a
/// named error (no panic), and run a tiny procedural pile end to end.
#[test]
fn stone_bench_errors_and_a_tiny_procedural_pile() {
    for (args, needle) in [
        (
            &[
                "--case",
                "stone-pile",
                "--stone",
                "/nonexistent/stone1.multisphere",
            ][..],
            "no stone template file at /nonexistent/stone1.multisphere",
        ),
        (
            &[
                "--case",
                "stone-bed",
                "--stone",
                "procedural",
                "--stones",
                "0",
            ][..],
            "--stones",
        ),
    ] {
        let err = refused(args);
        assert!(
            err.contains(needle) && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
    let work = std::env::temp_dir().join(format!("clump-bench-stone-cli-{}", std::process::id()));
    let out = tiny_stone_bench("stone-pile", 10, &work);
    assert!(out.contains("stone-pile: 10 stones, 500 spheres"), "{out}");
    assert!(out.contains("physics clump"), "{out}");
    for f in [
        "scenario.toml",
        "ic.csv",
        "stone.xyzr",
        "liggghts/in.stone",
        "liggghts/ins.in",
    ] {
        assert!(work.join(f).is_file(), "{f} missing");
    }
    // `--pose-seed` pours another pile: another initial condition
    let ic = std::fs::read_to_string(work.join("ic.csv")).unwrap();
    let seeded = work.with_extension("seed7");
    tiny_stone_bench_with("stone-pile", 10, &seeded, &["--pose-seed", "7"]);
    let ic7 = std::fs::read_to_string(seeded.join("ic.csv")).unwrap();
    assert_eq!(ic.lines().count(), ic7.lines().count());
    assert_ne!(ic, ic7);
    let _ = std::fs::remove_dir_all(&seeded);
    let _ = std::fs::remove_dir_all(&work);
    // the mixed case: six templates, each with its file for both codes
    let out = tiny_stone_bench("stone-mix", 12, &work);
    assert!(out.contains("stone-mix: 12 stones, 600 spheres"), "{out}");
    for k in 0..6 {
        assert!(
            out.contains(&format!("stone-mix: stone {k}: 2 of 12")),
            "{out}"
        );
        assert!(work.join(format!("liggghts/stone{k}.xyzr")).is_file());
    }
    let _ = std::fs::remove_dir_all(&work);
}

/// `clump bench --case <case>` with the procedural stone, `stones` stones
/// and 20 + 10 steps, into `work`; its stdout (it must succeed).
fn tiny_stone_bench(case: &str, stones: usize, work: &std::path::Path) -> String {
    tiny_stone_bench_with(case, stones, work, &[])
}

/// [`tiny_stone_bench`] with the further arguments `extra`.
fn tiny_stone_bench_with(
    case: &str,
    stones: usize,
    work: &std::path::Path,
    extra: &[&str],
) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_clump"))
        .args(["bench", "--case", case, "--stone", "procedural", "--stones"])
        .arg(stones.to_string())
        .args(["--na", "20", "--nb", "10", "--work"])
        .arg(work)
        .args(extra)
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        o.status.success(),
        "{out}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    out
}
