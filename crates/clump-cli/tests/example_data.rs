//! The mesh files of the examples (`examples/data/*.stl`) and the rock
//! template are generated procedurally here, and this test checks that the
//! shipped files are what the generators give.
//!
//! Regenerate them (from the repository root) with
//!
//! ```sh
//! CLUMP_WRITE_EXAMPLE_DATA=1 cargo test --release -p clump-cli --test example_data -- --test-threads=1
//! ```
//!
//! which writes `hopper.stl`, `hopper_gate.stl`, `drum.stl`, `rock.stl` and
//! then `rock.txt` (by running `clump template --from-mesh` with
//! [`ROCK_TEMPLATE_ARGS`]).

use clump_core::wall::mesh::primitives::{cylinder, plate, revolve, rock, MeshData};
use clump_io::mesh_file::{parse_stl, stl_binary};
use glam::DVec3;
use std::path::{Path, PathBuf};
use std::process::Command;

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/data")
}

fn writing() -> bool {
    std::env::var_os("CLUMP_WRITE_EXAMPLE_DATA").is_some_and(|v| v == "1")
}

/// examples/hopper_mesh.toml: a conical hopper in **mm** (the scenario reads
/// it with `scale = 0.001`): outlet radius 15 mm at z = 0, cone up to radius
/// 50 mm at z = 40 mm, then a cylindrical bin up to z = 120 mm; 64 facets
/// round, edges ≤ 10 mm along the profile.
fn hopper() -> MeshData {
    revolve(&[(15.0, 0.0), (50.0, 40.0), (50.0, 120.0)], 64, 10.0)
}

/// examples/hopper_mesh.toml: the gate, a 40 mm × 40 mm plate at z = 0 in m
/// (placed below the outlet with `offset`).
fn gate() -> MeshData {
    plate(0.04, 0.04, 4, 4)
}

/// examples/drum_mesh.toml: a closed drum of radius 50 mm and length 40 mm,
/// axis z, centred on the origin, in m (the scenario turns its axis to y);
/// 96 facets round, edges ≤ 5 mm.
fn drum() -> MeshData {
    cylinder(0.05, 0.04, 96, 0.005)
}

/// examples/rock_pour.toml: a rock-like stone, semi-axes 10 × 7.5 × 6 mm
/// with 25 % radial noise on a level-3 icosphere (1280 triangles), seed 7,
/// in m.
fn rock_mesh() -> MeshData {
    rock(3, 0.25, DVec3::new(0.010, 0.0075, 0.006), 7)
}

/// The options of `clump template --from-mesh` that made `rock.txt`.
const ROCK_TEMPLATE_ARGS: &[&str] = &["--spheres", "16", "--min-radius", "0.0018"];

fn check_stl(name: &str, (v, t): MeshData) {
    let path = data_dir().join(name);
    let bytes = stl_binary(&v, &t);
    if writing() {
        std::fs::write(&path, &bytes).unwrap();
    }
    let shipped = std::fs::read(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (regenerate, see the module docs)", path.display()));
    let (sv, st) = parse_stl(&shipped).unwrap();
    let (gv, gt) = parse_stl(&bytes).unwrap();
    assert_eq!(st.len(), t.len(), "{name}: triangle count");
    assert_eq!(sv.len(), gv.len(), "{name}: vertex count");
    let size = v.iter().fold(0.0f64, |m, p| m.max(p.abs().max_element()));
    for (k, (a, b)) in st.iter().zip(&gt).enumerate() {
        for (i, j) in a.iter().zip(b) {
            let d = (sv[*i as usize] - gv[*j as usize]).length();
            // f32 storage: a few ulps of the mesh size
            assert!(
                d <= 1e-6 * size,
                "{name}: triangle {k} differs from the generator by {d}"
            );
        }
    }
}

#[test]
fn shipped_meshes_match_their_generators() {
    check_stl("hopper.stl", hopper());
    check_stl("hopper_gate.stl", gate());
    check_stl("drum.stl", drum());
    check_stl("rock.stl", rock_mesh());
}

#[test]
fn generated_meshes_have_the_stated_geometry() {
    // the closed drum: every side vertex at the radius, caps at ±L/2
    let (v, t) = drum();
    let m = clump_core::wall::TriMesh::new(v.clone(), t).unwrap();
    m.check_closed().unwrap();
    for p in &v {
        let r = p.truncate().length();
        assert!(
            (p.z.abs() - 0.02).abs() < 1e-15 || (r - 0.05).abs() < 1e-15,
            "{p}"
        );
    }
    // the rock is closed and consistently wound
    let (v, t) = rock_mesh();
    let m = clump_core::wall::TriMesh::new(v, t).unwrap();
    let o = m.oriented_outward().unwrap();
    assert_eq!(o.triangles(), m.triangles(), "the rock is wound outward");
    // the hopper profile
    let (v, _) = hopper();
    let rmin = v
        .iter()
        .map(|p| p.truncate().length())
        .fold(f64::MAX, f64::min);
    assert!((rmin - 15.0).abs() < 1e-12);
}

#[test]
fn shipped_rock_template_is_what_from_mesh_gives() {
    let dir = data_dir();
    let out = std::env::temp_dir().join(format!("clump-rock-{}.txt", std::process::id()));
    let o = Command::new(env!("CARGO_BIN_EXE_clump"))
        .current_dir(&dir)
        .args(["template", "--from-mesh", "rock.stl"])
        .args(ROCK_TEMPLATE_ARGS)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let generated = std::fs::read_to_string(&out).unwrap();
    let _ = std::fs::remove_file(&out);
    let shipped_path = dir.join("rock.txt");
    if writing() {
        std::fs::write(&shipped_path, &generated).unwrap();
    }
    let shipped = std::fs::read_to_string(&shipped_path).unwrap();
    let rows = |s: &str| -> Vec<Vec<f64>> {
        s.lines()
            .filter(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty())
            .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
            .collect()
    };
    let (a, b) = (rows(&shipped), rows(&generated));
    assert_eq!(a.len(), b.len(), "sphere count");
    for (x, y) in a.iter().zip(&b) {
        for (p, q) in x.iter().zip(y) {
            // the file holds 10 significant digits
            assert!((p - q).abs() <= 1e-9 * 0.01, "{x:?} vs {y:?}");
        }
    }
}

/// The throughput comparison of the README: writes into `$CLUMP_BENCH_DIR`
/// (default `target/bench-drum`) `data/drum_1e5.stl` (the drum of
/// examples/drum_mesh.toml with 910 facets round and edges ≤ 2.5 mm:
/// 100 100 triangles), `drum_mesh_1e5.toml` (examples/drum_mesh.toml reading
/// it) and `drum_analytic.toml` (the same drum as an analytic cylinder and
/// two end planes, all turning with the drum). Run with
/// `cargo test --release -p clump-cli --test example_data -- --ignored`,
/// then `clump run` both scenarios and compare the `sphere_steps_per_s` of
/// their manifest.json.
#[test]
#[ignore]
fn write_drum_benchmark() {
    let dir = std::env::var_os("CLUMP_BENCH_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/bench-drum"));
    std::fs::create_dir_all(dir.join("data")).unwrap();
    let (v, t) = cylinder(0.05, 0.04, 910, 0.0025);
    assert!(t.len() >= 100_000, "{} triangles", t.len());
    std::fs::write(dir.join("data/drum_1e5.stl"), stl_binary(&v, &t)).unwrap();
    let example = std::fs::read_to_string(data_dir().join("../drum_mesh.toml")).unwrap();
    let mesh = example.replace("data/drum.stl", "data/drum_1e5.stl");
    assert_ne!(mesh, example);
    std::fs::write(dir.join("drum_mesh_1e5.toml"), mesh).unwrap();
    // the analytic drum: replace the [[wall]] and the stage's wall change
    let a = example.find("[[wall]]").unwrap();
    let b = example.find("[[stage]]").unwrap();
    let walls = r#"[[wall]]
name = "drum"
material = "steel"
type = "cylinder"
point = [0.0, 0.0, 0.0]
axis = [0.0, 1.0, 0.0]
radius = 0.05
inside = true

[[wall]]
name = "end_front"
material = "steel"
type = "plane"
point = [0.0, -0.02, 0.0]
normal = [0.0, 1.0, 0.0]

[[wall]]
name = "end_back"
material = "steel"
type = "plane"
point = [0.0, 0.02, 0.0]
normal = [0.0, -1.0, 0.0]

"#;
    let mut analytic = format!("{}{walls}{}", &example[..a], &example[b..]);
    let change = "[[stage.wall]]\nname = \"drum\"\nangular_velocity = [0.0, 3.0, 0.0]";
    let c = analytic.find(change).unwrap();
    let ends: String = ["end_front", "end_back"]
        .iter()
        .map(|n| {
            format!(
                "\n[[stage.wall]]\nname = \"{n}\"\nangular_velocity = [0.0, 3.0, 0.0]\ncenter = [0.0, 0.0, 0.0]"
            )
        })
        .collect();
    analytic.insert_str(c + change.len(), &ends);
    std::fs::write(dir.join("drum_analytic.toml"), analytic).unwrap();
}
