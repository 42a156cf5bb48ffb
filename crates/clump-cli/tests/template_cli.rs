//! `clump template`: JSON output and exit codes.

use std::path::PathBuf;
use std::process::Command;

fn clump() -> Command {
    Command::new(env!("CARGO_BIN_EXE_clump"))
}

fn temp_file(name: &str, contents: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("clump-template-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, contents).unwrap();
    path
}

const KEYS: [&str; 9] = [
    "volume",
    "mass",
    "center_of_mass",
    "inertia",
    "principal_moments",
    "principal_axes",
    "naive_volume",
    "naive_principal_moments",
    "relative_error_bound",
];

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn json_output_has_exactly_the_keys() {
    // REFERENCE.md §2: two unit spheres, d = 1, ρ = 1 → V = 7.068583,
    // I_axis = 3.004148, I_trans = 5.213080 (in mm here, scaled to m).
    let path = temp_file(
        "pair.multisphere",
        b"# two spheres (mm)\n-0.5 0 0 1\n0.5 0 0 1 # second\n\n",
    );
    let out = clump()
        .args([
            "template",
            path.to_str().unwrap(),
            "--json",
            "--scale",
            "0.001",
            "--density",
            "2",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let obj = v.as_object().unwrap();
    let mut keys: Vec<&str> = obj.keys().map(|k| k.as_str()).collect();
    keys.sort_unstable();
    let mut want = KEYS.to_vec();
    want.sort_unstable();
    assert_eq!(keys, want);
    let f = |k: &str| obj[k].as_f64().unwrap();
    let arr = |k: &str| -> Vec<f64> {
        obj[k]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let mat = |k: &str| -> Vec<Vec<f64>> {
        obj[k]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| {
                r.as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap())
                    .collect()
            })
            .collect()
    };
    assert!(rel(f("volume"), 7.068583e-9) < 1e-6);
    assert!(rel(f("mass"), 2.0 * 7.068583e-9) < 1e-6);
    assert!(rel(f("naive_volume"), 8.377580e-9) < 1e-6);
    let pm = arr("principal_moments");
    assert!(rel(pm[0], 2.0 * 3.004148e-15) < 1e-6);
    assert!(rel(pm[1], 2.0 * 5.213080e-15) < 1e-6);
    assert!(rel(pm[2], 2.0 * 5.213080e-15) < 1e-6);
    let npm = arr("naive_principal_moments");
    assert!(rel(npm[2], 2.0 * 5.445427e-15) < 1e-6);
    assert_eq!(arr("center_of_mass").len(), 3);
    let inertia = mat("inertia");
    assert!(rel(inertia[0][0], 2.0 * 3.004148e-15) < 1e-6);
    let axes = mat("principal_axes");
    assert_eq!(axes.len(), 3);
    assert!((axes[0][0] - 1.0).abs() < 1e-9);
    // Rows are unit and right-handed.
    let cross = [
        axes[0][1] * axes[1][2] - axes[0][2] * axes[1][1],
        axes[0][2] * axes[1][0] - axes[0][0] * axes[1][2],
        axes[0][0] * axes[1][1] - axes[0][1] * axes[1][0],
    ];
    for k in 0..3 {
        assert!((cross[k] - axes[2][k]).abs() < 1e-9);
    }
    let b = f("relative_error_bound");
    assert!(b > 0.0 && b <= 1e-6);
}

#[test]
fn human_readable_table() {
    let path = temp_file(
        "tetra.multisphere",
        b"0.5 0.5 0.5 1\n0.5 -0.5 -0.5 1\n-0.5 0.5 -0.5 1\n-0.5 -0.5 0.5 1\n",
    );
    let out = clump()
        .args(["template", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    for word in [
        "volume",
        "mass",
        "naive",
        "%",
        "principal",
        "relative error bound",
    ] {
        assert!(text.contains(word), "missing {word:?} in\n{text}");
    }
}

#[test]
fn bad_file_exits_2_with_line_number() {
    let path = temp_file("bad.multisphere", b"# ok\n0 0 0 1\n1 2 3\n");
    let out = clump()
        .args(["template", path.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.multisphere:3"), "{err}");
    assert!(err.contains("expected 4 numbers x y z r, found 3"), "{err}");
    assert!(out.stdout.is_empty());

    let path = temp_file("negr.multisphere", b"0 0 0 1\n\n1 2 3 -1\n");
    let out = clump()
        .args(["template", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(":3:") && err.contains("radius must be > 0"),
        "{err}"
    );

    let path = temp_file("bin.multisphere", b"0 0 0 1\n\xff\xfe\x00\n");
    let out = clump()
        .args(["template", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));

    let out = clump()
        .args(["template", "/nonexistent/none.multisphere"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/none.multisphere"));
}

#[test]
fn bad_density_or_scale_exits_2() {
    let path = temp_file("one.multisphere", b"0 0 0 1\n");
    for args in [
        ["--density", "0"],
        ["--density", "-3"],
        ["--scale", "0"],
        ["--scale", "nan"],
    ] {
        let out = clump()
            .args(["template", path.to_str().unwrap()])
            .args(args)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
    }
}
