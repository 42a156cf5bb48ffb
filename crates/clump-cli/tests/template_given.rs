//! A template's given mass, inertia and centre of mass (LIGGGHTS templates
//! state them): `clump template --mass --inertia --center-of-mass` and
//! `clump check` show the values in use.

use std::process::Command;

fn clump() -> Command {
    Command::new(env!("CARGO_BIN_EXE_clump"))
}

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("clump_given_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn template_shows_the_given_centre_and_inertia() {
    let d = tmp("template");
    let f = d.join("dimer.txt");
    std::fs::write(&f, "0 0 0 0.01\n0.02 0 0 0.01\n").unwrap();
    let out = clump()
        .args([
            "template",
            f.to_str().unwrap(),
            "--density",
            "2500",
            "--json",
        ])
        .args(["--mass", "0.02", "--inertia", "3e-6,0,0,1e-6,0,2e-6"])
        .args(["--center-of-mass", "0.005,0,0"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["mass"], 0.02);
    assert_eq!(v["center_of_mass"], serde_json::json!([0.005, 0.0, 0.0]));
    let pm: Vec<f64> = v["principal_moments"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(pm, vec![1e-6, 2e-6, 3e-6]);
    let table = clump()
        .args(["template", f.to_str().unwrap(), "--density", "2500"])
        .args([
            "--mass",
            "0.02",
            "--inertia",
            "3e-6,0,0,1e-6,0,2e-6",
            "--center-of-mass",
            "0.005,0,0",
        ])
        .output()
        .unwrap();
    let s = String::from_utf8_lossy(&table.stdout);
    assert!(
        s.contains("(given)") && s.contains("+5.000000000e-3"),
        "{s}"
    );
    let bad = clump()
        .args(["template", f.to_str().unwrap(), "--center-of-mass", "0,0,0"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--center-of-mass needs --mass"));
}

#[test]
fn check_shows_the_given_centre() {
    let d = tmp("check");
    std::fs::write(
        d.join("s.toml"),
        r#"
[simulation]
dt = 1e-5
[domain]
lo = [-1.0, -1.0, -1.0]
hi = [1.0, 1.0, 1.0]
[[material]]
name = "m"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2500
[[template]]
name = "dimer"
material = "m"
spheres = [[0.0, 0.0, 0.0, 0.01], [0.02, 0.0, 0.0, 0.01]]
mass = 0.02
inertia = [[3e-6, 0, 0], [0, 1e-6, 0], [0, 0, 2e-6]]
center_of_mass = [0.005, 0.0, 0.0]
[[insert]]
kind = "pack"
template = "dimer"
count = 1
region = { type = "box", lo = [-0.5, -0.5, -0.5], hi = [0.5, 0.5, 0.5] }
[[stage]]
steps = 1
"#,
    )
    .unwrap();
    let out = clump().arg("check").arg(d.join("s.toml")).output().unwrap();
    let s = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{s}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        s.contains("centre of mass (input frame) (5.000000e-3, 0.000000e0, 0.000000e0) m  (mass, inertia and centre as given)"),
        "{s}"
    );
    assert!(s.contains("I = (1.0000e-6, 2.0000e-6, 3.0000e-6)"), "{s}");
}
