//! `clump bench` refuses meaningless options with an error that names the
//! option, before it builds or runs anything.

use std::process::Command;

#[test]
fn bench_bad_options_are_named_errors() {
    for (args, needle) in [
        (&["--threads", "0"][..], "--threads"),
        (&["--scaling", "10000,0"][..], "--scaling"),
        (&["--scaling", "10000", "--steps", "0"][..], "--steps"),
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_clump"))
            .arg("bench")
            .args(args)
            .output()
            .unwrap();
        assert!(!o.status.success(), "{args:?} succeeded");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains(needle) && err.contains("got 0"),
            "{args:?}: {err}"
        );
    }
}
