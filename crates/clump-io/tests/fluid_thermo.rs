//! thermo.csv with `[fluid]`: the total fluid force columns, checked
//! against Stokes' drag and Archimedes' buoyancy on two held spheres in a
//! uniform upward flow, and in a sheared flow read from a grid file; and
//! the columns survive a resume.

mod support;

use clump_io::run::{RunOptions, Runner};
use clump_io::scenario;
use std::path::PathBuf;

const R: f64 = 0.0005; // m
const MU: f64 = 1e-3; // Pa s
const RHO_F: f64 = 1000.0; // kg/m^3
const U: f64 = 0.01; // m/s, upward

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("clump_fluid_thermo_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn scenario_file(d: &std::path::Path) -> PathBuf {
    scenario_with_velocity(d, &format!("[0.0, 0.0, {U}]"))
}

/// The scenario with `[fluid] velocity = <velocity>`.
fn scenario_with_velocity(d: &std::path::Path, velocity: &str) -> PathBuf {
    std::fs::write(
        d.join("bodies.csv"),
        "template,x,y,z,driven\nball,0.0,0.0,0.01,1\nball,0.004,0.0,0.01,1\n",
    )
    .unwrap();
    let text = format!(
        r#"
[simulation]
dt = 1e-5
gravity = [0.0, 0.0, -9.81]

[domain]
lo = [-0.01, -0.01, 0.0]
hi = [0.01, 0.01, 0.02]

[[material]]
name = "glass"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2500

[contact]
restitution = 0.5
friction = 0.4

[[template]]
name = "ball"
material = "glass"
spheres = [[0.0, 0.0, 0.0, {R}]]

[[insert]]
kind = "file"
file = "bodies.csv"

[[stage]]
name = "flow"
steps = 20

[output]
thermo = {{ every_steps = 10 }}
checkpoint = {{ every_steps = 10 }}

[fluid]
density = {RHO_F}
viscosity = {MU}
drag = "stokes"
velocity = {velocity}
"#
    );
    let p = d.join("scenario.toml");
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn thermo_has_the_total_fluid_force() {
    let d = dir("total");
    let sc = scenario::load(&scenario_file(&d)).unwrap_or_else(|e| panic!("{e}"));
    let out = d.join("out");
    let mut run = Runner::new(sc, &out).unwrap();
    run.run(RunOptions::default()).unwrap();
    let text = std::fs::read_to_string(out.join("thermo.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        &header[header.len() - 3..],
        ["fluid_fx[N]", "fluid_fy[N]", "fluid_fz[N]"]
    );
    let last: Vec<f64> = lines
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(last.len(), header.len());
    // two spheres held at rest: Stokes drag 3 π μ d U and buoyancy ρ_f V g each
    let v = 4.0 / 3.0 * std::f64::consts::PI * R.powi(3);
    let each = 3.0 * std::f64::consts::PI * MU * 2.0 * R * U + RHO_F * v * 9.81;
    let n = header.len();
    assert_eq!(last[n - 3], 0.0);
    assert_eq!(last[n - 2], 0.0);
    assert!(
        (last[n - 1] - 2.0 * each).abs() < 1e-12 * each,
        "{} vs {}",
        last[n - 1],
        2.0 * each
    );

    drop(run);
    // resumed from the checkpoint at step 10: the same file, the same rows
    let ck = out.join("checkpoint_000000010.ckpt");
    let mut again = Runner::resume(&ck, Some(&out)).unwrap();
    again.run(RunOptions::default()).unwrap();
    assert_eq!(
        std::fs::read_to_string(out.join("thermo.csv")).unwrap(),
        text
    );
}

#[test]
fn thermo_fluid_force_in_a_grid_velocity_field() {
    // u = (0, 0, U (1 + x/L)), L = 0.01 m, on a grid over the domain; the
    // spheres held at x = 0 and x = 0.004 m see U and 1.4 U (trilinear
    // interpolation is exact for a linear field): the total is
    // 3 π μ d U (1 + 1.4) + 2 ρ_f V g
    let d = dir("grid");
    let mut csv = String::from("x,y,z,ux,uy,uz\n");
    for z in [0.0, 0.02] {
        for y in [-0.01, 0.01] {
            for x in [-0.01, 0.0, 0.01] {
                let uz = U * (1.0 + x / 0.01);
                csv += &format!("{x},{y},{z},0,0,{uz}\n");
            }
        }
    }
    std::fs::write(d.join("flow.csv"), csv).unwrap();
    let sc = scenario::load(&scenario_with_velocity(&d, "\"flow.csv\""))
        .unwrap_or_else(|e| panic!("{e}"));
    let out = d.join("out");
    let mut run = Runner::new(sc, &out).unwrap();
    run.run(RunOptions::default()).unwrap();
    let text = std::fs::read_to_string(out.join("thermo.csv")).unwrap();
    let fz = support::last_value(&out.join("thermo.csv"), "fluid_fz[N]");
    let v = 4.0 / 3.0 * std::f64::consts::PI * R.powi(3);
    let want = 3.0 * std::f64::consts::PI * MU * 2.0 * R * U * 2.4 + 2.0 * RHO_F * v * 9.81;
    assert!((fz - want).abs() < 1e-12 * want, "{fz} vs {want}");
    drop(run);
    // the resumed run reads the grid from the scenario again: same rows
    let ck = out.join("checkpoint_000000010.ckpt");
    let mut again = Runner::resume(&ck, Some(&out)).unwrap();
    again.run(RunOptions::default()).unwrap();
    assert_eq!(
        std::fs::read_to_string(out.join("thermo.csv")).unwrap(),
        text
    );
}
