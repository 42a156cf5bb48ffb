//! `clump check` describes the setup in words (no Rust debug text): walls,
//! contact parameters per material pair with the stiffness at a typical
//! overlap, time-step margins, the overlap guard and the outputs.

use std::path::Path;
use std::process::Command;

#[test]
fn check_describes_the_setup_in_words() {
    let sc = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/liggghts_stone.toml");
    let o = Command::new(env!("CARGO_BIN_EXE_clump"))
        .arg("check")
        .arg(&sc)
        .output()
        .unwrap();
    assert!(o.status.success());
    let out = String::from_utf8_lossy(&o.stdout);
    for debug in ["DVec3", "Some(", "None", "Plane {", "{ "] {
        assert!(!out.contains(debug), "debug text {debug:?} in:\n{out}");
    }
    for want in [
        "floor            plane through (0.0000, 0.0000, 0.0000) m with normal (0.000, 0.000, 1.000), material 'stone'",
        "stone – stone: Hertz–Mindlin, e = 0.3, mu = 0.5, mu_r = 0, damping ratio ",
        "refused above 0.5 t_R, warned about above 0.3 t_R",
        "overlap guard: a run stops when an overlap exceeds ",
        "VTK frames   every 200 steps (2.0000e-3 s)",
        "checkpoints  off",
    ] {
        assert!(out.contains(want), "{want:?} missing from:\n{out}");
    }
    // Hertz tangent stiffness 2 E* √(R* δ) at δ = 0.01 R*: 0.2 E* R*, with
    // E* = E/(2(1 − ν²)) for two equal materials (E = 1e7 Pa, ν = 0.45)
    let line = out.lines().find(|l| l.contains("stone – stone")).unwrap();
    let field = |key: &str| -> f64 {
        line.split(key)
            .nth(1)
            .unwrap()
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    let e_star = 1e7 / (2.0 * (1.0 - 0.45 * 0.45));
    assert!((field("E* = ") / e_star - 1.0).abs() < 1e-3, "{line}");
    let r_star = field("(R* = ");
    let k = field("k_n = ");
    assert!((k / (0.2 * e_star * r_star) - 1.0).abs() < 1e-3, "{line}");
}
