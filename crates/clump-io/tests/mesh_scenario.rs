//! Mesh walls in scenario files: placement by scale, rotation and offset
//! (checked against the analytic rest state of a sphere on the floor), the
//! torque point and power columns, and checkpoint/resume with the mesh bytes
//! stored in the checkpoint.

use clump_core::wall::mesh::primitives::plate;
use clump_io::mesh_file::stl_ascii;
use clump_io::run::{RunOptions, Runner};
use clump_io::scenario;
use glam::DVec3;
use std::path::{Path, PathBuf};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("clump_mesh_scn_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const R: f64 = 0.005; // sphere radius, m
const RHO: f64 = 2500.0; // kg/m^3
const E: f64 = 1e7; // Pa
const NU: f64 = 0.3;
const G: f64 = 9.81;

/// A floor in the file's plane y = 20 (mm), 200 mm × 200 mm: the vertices
/// `(x, 20, z)`. Read with scale 0.001, a rotation of +90° about x (which
/// maps (x, y, z) to (x, −z, y)) and offset (0.01, −0.02, 0.05) m it is the
/// horizontal plane z = 0.02 + 0.05 = 0.07 m. (A rotation of −90° would put
/// it at z = 0.03 m, a scaled offset at 0.02 m.)
fn write_floor(d: &Path) {
    let (v, t) = plate(200.0, 200.0, 4, 4);
    let v: Vec<DVec3> = v.iter().map(|p| DVec3::new(p.x, 20.0, p.y)).collect();
    std::fs::write(d.join("floor.stl"), stl_ascii("floor", &v, &t)).unwrap();
}

fn scenario_text(extra_wall: &str, stage: &str) -> String {
    format!(
        r#"
[simulation]
dt = 2e-6
gravity = [0.0, 0.0, -{G}]

[domain]
lo = [-0.1, -0.1, 0.0]
hi = [0.1, 0.1, 0.2]

[[material]]
name = "grain"
youngs_modulus = {E}
poisson_ratio = {NU}
density = {RHO}

[[material]]
name = "rigid"
youngs_modulus = inf
poisson_ratio = 0.3
density = 7800

[contact]
restitution = 0.1
friction = 0.5

[[template]]
name = "ball"
material = "grain"
shape = "sphere"
radius = {R}

[[wall]]
name = "floor"
material = "rigid"
type = "mesh"
file = "floor.stl"
scale = 0.001
rotation = {{ axis = [1.0, 0.0, 0.0], angle = 90.0 }}
offset = [0.01, -0.02, 0.05]
torque_point = [0.03, 0.01, 0.0]
{extra_wall}
{stage}

[[insert]]
kind = "file"
file = "ball.csv"

[output]
thermo = {{ every_steps = 1000 }}
vtk = {{ every_steps = 100000 }}
"#
    )
}

/// Mass and Hertz rest overlap of the sphere on a rigid floor:
/// `m g = (4/3) E* √R δ^{3/2}`, `E* = E / (1 − ν²)`.
fn rest_overlap() -> (f64, f64) {
    let m = RHO * 4.0 / 3.0 * std::f64::consts::PI * R.powi(3);
    let e_star = E / (1.0 - NU * NU);
    let delta = (m * G / (4.0 / 3.0 * e_star * R.sqrt())).powf(2.0 / 3.0);
    (m, delta)
}

fn last_row(path: &Path) -> (Vec<String>, Vec<f64>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let row: Vec<f64> = lines
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    (header, row)
}

fn col(h: &[String], r: &[f64], name: &str) -> f64 {
    r[h.iter()
        .position(|c| c == name || c.strip_prefix(name).is_some_and(|u| u.starts_with('[')))
        .unwrap_or_else(|| panic!("no column {name}"))]
}

#[test]
fn sphere_rests_on_a_scaled_rotated_offset_stl_floor_at_the_hertz_height() {
    let d = dir("rest");
    write_floor(&d);
    let (m, delta) = rest_overlap();
    let floor_z = 0.07;
    // dropped from just touching, at rest
    let (x0, y0) = (0.004, -0.003);
    std::fs::write(
        d.join("ball.csv"),
        format!("template,x,y,z\nball,{x0},{y0},{}\n", floor_z + R),
    )
    .unwrap();
    let text = scenario_text("", "[[stage]]\nname = \"rest\"\nduration = 0.03\n");
    std::fs::write(d.join("s.toml"), &text).unwrap();
    let sc = scenario::load(&d.join("s.toml")).unwrap_or_else(|e| panic!("{e}"));
    // the mesh lies in the plane z = 0.07 after scale, rotation and offset
    assert_eq!(sc.meshes.len(), 1);
    let (lo, hi) = sc.meshes[0].bounds();
    assert!((lo.z - floor_z).abs() < 1e-15 && (hi.z - floor_z).abs() < 1e-15);
    // x ∈ 0.01 ± 0.1, y = −z_file·0.001 − 0.02 ∈ −0.02 ± 0.1
    assert!((lo.x - (-0.09)).abs() < 1e-15 && (hi.x - 0.11).abs() < 1e-15);
    assert!((lo.y - (-0.12)).abs() < 1e-15 && (hi.y - 0.08).abs() < 1e-15);
    // default centre of rotation: the offset
    assert_eq!(sc.walls[0].motion.center, DVec3::new(0.01, -0.02, 0.05));
    let mut run = Runner::new(sc, &d.join("out")).unwrap();
    run.run(RunOptions::default()).unwrap();
    let w = run.world();
    let z = w.bodies().position[0].z;
    let want = floor_z + R - delta;
    assert!(
        (z - want).abs() < 1e-3 * delta,
        "rest height {z}, Hertz {want} (overlap {} vs {delta})",
        floor_z + R - z
    );
    assert!(w.bodies().velocity[0].length() < 1e-5);
    // thermo: the floor carries the weight; its torque about the torque
    // point P is (c − P) × F with the contact point c under the sphere
    let (h, r) = last_row(&d.join("out/thermo.csv"));
    let f = DVec3::new(
        col(&h, &r, "floor_fx"),
        col(&h, &r, "floor_fy"),
        col(&h, &r, "floor_fz"),
    );
    let weight = DVec3::new(0.0, 0.0, -m * G);
    assert!((f - weight).length() < 1e-6 * m * G, "{f} vs {weight}");
    let c = DVec3::new(x0, y0, floor_z);
    let tq = (c - DVec3::new(0.03, 0.01, 0.0)).cross(weight);
    let t = DVec3::new(
        col(&h, &r, "floor_tx"),
        col(&h, &r, "floor_ty"),
        col(&h, &r, "floor_tz"),
    );
    assert!((t - tq).length() < 1e-5 * tq.length(), "{t} vs {tq}");
    // a wall that never moves has no power column
    assert!(!h.iter().any(|c| c.starts_with("floor_power")));
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn moving_mesh_resumes_bit_identically_without_its_file() {
    let d = dir("resume");
    write_floor(&d);
    std::fs::write(
        d.join("ball.csv"),
        "template,x,y,z,vx\nball,0.0,0.0,0.08,0.2\nball,0.02,0.01,0.09,-0.1\n",
    )
    .unwrap();
    // a second copy of the floor, higher, spinning about z and sliding: its
    // pose must be carried by the checkpoint
    let extra = r#"
[[wall]]
name = "paddle"
material = "rigid"
type = "mesh"
file = "floor.stl"
scale = 0.0002
rotation = { axis = [1.0, 0.0, 0.0], angle = 90.0 }
offset = [0.0, 0.0, 0.071]
"#;
    let stages = r#"
[[stage]]
name = "a"
steps = 3000
[[stage.wall]]
name = "paddle"
angular_velocity = [0.0, 0.0, 20.0]

[[stage]]
name = "b"
steps = 3000
[[stage.wall]]
name = "paddle"
angular_velocity = [0.0, 0.0, 0.0]
velocity = [0.0, 0.3, 0.0]
"#;
    std::fs::write(d.join("s.toml"), scenario_text(extra, stages)).unwrap();
    let load = || scenario::load(&d.join("s.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut full = Runner::new(load(), &d.join("full")).unwrap();
    full.run(RunOptions::default()).unwrap();
    let mut first = Runner::new(load(), &d.join("split")).unwrap();
    first
        .run(RunOptions {
            max_steps: Some(4000),
            ..Default::default()
        })
        .unwrap();
    let ck = first.write_checkpoint().unwrap();
    drop(first);
    // the mesh and the bodies file are needed no more
    std::fs::remove_file(d.join("floor.stl")).unwrap();
    std::fs::remove_file(d.join("ball.csv")).unwrap();
    let mut second = Runner::resume(&ck, None).unwrap_or_else(|e| panic!("{e}"));
    second.run(RunOptions::default()).unwrap();
    let (a, b) = (full.world(), second.world());
    assert_eq!(a.step, b.step);
    for i in 0..a.bodies().position.len() {
        assert_eq!(a.bodies().position[i], b.bodies().position[i]);
        assert_eq!(a.bodies().velocity[i], b.bodies().velocity[i]);
    }
    assert_eq!(a.walls[..], b.walls[..]);
    // the paddle rotated 20 rad/s for stage a, then slid 0.3 m/s for stage b
    let dt = 2e-6;
    let (_, pos, q) = b.walls[1].shape.mesh_pose().unwrap();
    let angle = 2.0 * q.w.acos();
    assert!((angle - 20.0 * 3000.0 * dt).abs() < 1e-9, "{angle}");
    assert!(
        (pos - DVec3::new(0.0, 0.3 * 3000.0 * dt, 0.0)).length() < 1e-12,
        "{pos}"
    );
    // both walls' thermo rows; the paddle has a power column
    let (h, _) = last_row(&d.join("split/thermo.csv"));
    assert!(h.iter().any(|c| c == "paddle_power[W]"));
    std::fs::remove_dir_all(&d).unwrap();
}
