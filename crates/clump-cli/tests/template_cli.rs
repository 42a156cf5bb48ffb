//! `clump template`: JSON output and exit codes.

use std::path::PathBuf;
use std::process::Command;

fn clump() -> Command {
    Command::new(env!("CARGO_BIN_EXE_clump"))
}

/// `contents` written as `name` in a fresh directory, which is removed when
/// the returned guard is dropped.
fn temp_file(name: &str, contents: &[u8]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::Builder::new()
        .prefix("clump-template-cli-")
        .tempdir()
        .unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, contents).unwrap();
    (dir, path)
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
    let (_dir, path) = temp_file(
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
    let (_dir, path) = temp_file(
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
    let (_dir, path) = temp_file("bad.multisphere", b"# ok\n0 0 0 1\n1 2 3\n");
    let out = clump()
        .args(["template", path.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.multisphere:3"), "{err}");
    assert!(err.contains("expected 4 numbers x y z r, found 3"), "{err}");
    assert!(out.stdout.is_empty());

    let (_dir, path) = temp_file("negr.multisphere", b"0 0 0 1\n\n1 2 3 -1\n");
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

    let (_dir, path) = temp_file("bin.multisphere", b"0 0 0 1\n\xff\xfe\x00\n");
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
    let (_dir, path) = temp_file("one.multisphere", b"0 0 0 1\n");
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

/// Where Debian's `liggghts-doc` puts LIGGGHTS' own 50-sphere stone template
/// (GPL data, so it is not shipped; `CLUMP_STONE_FILE` may point elsewhere).
const STONE: &str = "/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public/multisphere_stone_restitution/data/stone1.multisphere";

/// `clump template` on LIGGGHTS' `stone1.multisphere` (density 2500, scale
/// 0.001, as in LIGGGHTS' `in.multisphere`): it runs in under a second, its
/// volume agrees with a test-local Monte-Carlo estimate (2·10⁶ points in the
/// bounding box, standard error printed), and twice its mass agrees with LIGGGHTS' own
/// Monte-Carlo value for 2 stones, 9.201859e-02 kg (10⁶ tries, about 0.1 %
/// standard error). Skipped (with a note) when the file is not installed.
#[test]
fn liggghts_stone_template() {
    let path = std::env::var("CLUMP_STONE_FILE").unwrap_or_else(|_| STONE.to_string());
    let Ok(text) = std::fs::read_to_string(&path) else {
        eprintln!("SKIPPED: {path} not found (apt-get install liggghts-doc)");
        return;
    };
    let t0 = std::time::Instant::now();
    let out = clump()
        .args([
            "template",
            &path,
            "--density",
            "2500",
            "--scale",
            "0.001",
            "--json",
        ])
        .output()
        .unwrap();
    let secs = t0.elapsed().as_secs_f64();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let volume = v["volume"].as_f64().unwrap();
    let mass = v["mass"].as_f64().unwrap();
    // test-local Monte-Carlo volume of the union (deterministic LCG)
    let spheres: Vec<[f64; 4]> = text
        .lines()
        .map(|l| l.split('#').next().unwrap().trim())
        .filter(|l| !l.is_empty())
        .map(|l| {
            let x: Vec<f64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            [x[0] * 1e-3, x[1] * 1e-3, x[2] * 1e-3, x[3] * 1e-3]
        })
        .collect();
    assert_eq!(spheres.len(), 50);
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for s in &spheres {
        for a in 0..3 {
            lo[a] = lo[a].min(s[a] - s[3]);
            hi[a] = hi[a].max(s[a] + s[3]);
        }
    }
    let mut seed = 2024u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let n = 2_000_000;
    let mut hits = 0u64;
    for _ in 0..n {
        let p: Vec<f64> = (0..3).map(|a| lo[a] + (hi[a] - lo[a]) * rnd()).collect();
        if spheres.iter().any(|s| {
            (p[0] - s[0]).powi(2) + (p[1] - s[1]).powi(2) + (p[2] - s[2]).powi(2) < s[3] * s[3]
        }) {
            hits += 1;
        }
    }
    let box_volume: f64 = (0..3).map(|a| hi[a] - lo[a]).product();
    let frac = hits as f64 / n as f64;
    let mc_volume = box_volume * frac;
    let mc_sigma = ((1.0 - frac) / (frac * n as f64)).sqrt();
    let liggghts_two = 9.201859e-2;
    eprintln!(
        "stone1: {secs:.3} s; volume {volume:.6e} m^3 (test MC {mc_volume:.6e} ± {:.3} %, {:+.3} %); 2 x mass {:.6e} kg vs LIGGGHTS MC {liggghts_two:e} ({:+.3} %); naive volume {:.6e}; error bound {:e}",
        100.0 * mc_sigma,
        100.0 * (volume / mc_volume - 1.0),
        2.0 * mass,
        100.0 * (2.0 * mass / liggghts_two - 1.0),
        v["naive_volume"].as_f64().unwrap(),
        v["relative_error_bound"].as_f64().unwrap()
    );
    assert!(
        rel(volume, mc_volume) < 4.0 * mc_sigma,
        "{volume} vs MC {mc_volume}"
    );
    assert!(rel(2.0 * mass, liggghts_two) < 0.004);
    assert!(rel(mass, 2500.0 * volume) < 1e-12);
    assert!(v["relative_error_bound"].as_f64().unwrap() <= 1e-6);
}

/// `--from-mesh --resolution 2000` (the documented maximum) on the rock
/// mesh needs about 10¹⁰ voxels: refused with the memory it needs and a
/// resolution that fits, instead of aborting on allocation.
#[test]
fn from_mesh_resolution_beyond_memory_is_refused() {
    let mesh =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/data/rock.stl");
    let avail_gb = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find_map(|l| l.strip_prefix("MemAvailable:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        })
        .map(|kb| kb * 1024.0 / 1e9);
    match avail_gb {
        Some(gb) if gb < 400.0 => {}
        _ => {
            eprintln!("SKIPPED: needs Linux with less than 400 GB of free memory");
            return;
        }
    }
    let out = clump()
        .args(["template", "--from-mesh"])
        .arg(&mesh)
        .args(["--resolution", "2000"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--resolution 2000 needs about") && err.contains("use --resolution"),
        "{err}"
    );
}
