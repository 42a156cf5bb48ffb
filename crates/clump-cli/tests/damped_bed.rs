//! A strongly damped bed of asymmetric clumps (restitution 0.1) must come
//! to rest at the default time step (docs/theory.md T-52).
//!
//! The clump is a large sphere with two small ones on an arm: at a contact
//! on the far small sphere the clump responds like a body κ = 6.8 times
//! lighter (T-51), so its mass-scaled dashpot damps that contact far above
//! its calibrated ratio and the one-contact stability limit dt_c falls to
//! 0.38 t_R. At the Rayleigh-only default (0.2 t_R = 0.52 dt_c)
//! the bed's kinetic energy levels off near 10⁻⁷ of its peak; at the
//! default (0.4 dt_c) it falls to round-off. What a user sees: `clump check`
//! names the limit; `clump run` with `dt = "auto"` settles.

use std::path::Path;
use std::process::Command;

const BED: &str = r#"
[simulation]
dt = DT
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [-0.02, -0.02, -0.002]
hi = [0.02, 0.02, 0.06]
periodic = ["x", "y"]
[[material]]
name = "rock"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2500
[contact]
restitution = 0.1
friction = 0.5
[[template]]
name = "club"
material = "rock"
spheres = [[0.0, 0.0, 0.0, 0.002], [0.0026, 0.0, 0.0, 0.0008], [0.0038, 0.0, 0.0, 0.0006]]
[[wall]]
name = "floor"
material = "rock"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
[[stage]]
name = "fill"
duration = 0.8
[[insert]]
kind = "pack"
template = "club"
count = 150
region = { type = "box", lo = [-0.018, -0.018, 0.001], hi = [0.018, 0.018, 0.05] }
seed = 3
[output]
thermo = { every_steps = 100 }
vtk = { every = 0.8 }
trajectory = { bodies = IDS, every = 0.8, loads = true }
"#;

/// Runs the bed with time step `dt` (TOML value) in `dir`; returns the peak
/// and final kinetic energy (J) and the largest net force on a clump over
/// its weight at the end.
fn run_bed(dir: &Path, dt: &str) -> (f64, f64, f64) {
    let ids: Vec<String> = (1..=150).map(|i| i.to_string()).collect();
    let text = BED
        .replace("DT", dt)
        .replace("IDS", &format!("[{}]", ids.join(", ")));
    let sc = dir.join("bed.toml");
    std::fs::write(&sc, text).unwrap();
    let out = dir.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_clump"))
        .args([
            "run".as_ref(),
            sc.as_os_str(),
            "-o".as_ref(),
            out.as_os_str(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let thermo = std::fs::read_to_string(out.join("thermo.csv")).unwrap();
    let ke: Vec<f64> = thermo
        .lines()
        .skip(1)
        .map(|l| {
            let c: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            c[6] + c[7]
        })
        .collect();
    let peak = ke.iter().cloned().fold(0.0, f64::max);
    let last = *ke.last().unwrap();
    // the trajectory's last row: the net force (contacts plus gravity)
    let mass = body_mass();
    let mut worst: f64 = 0.0;
    for i in 1..=150 {
        let t = std::fs::read_to_string(out.join(format!("traj_{i}.csv"))).unwrap();
        let row: Vec<f64> = t
            .lines()
            .last()
            .unwrap()
            .split(',')
            .map(|x| x.parse().unwrap())
            .collect();
        let f = (row[17] * row[17] + row[18] * row[18] + row[19] * row[19]).sqrt();
        worst = worst.max(f / (mass * 9.81));
    }
    (peak, last, worst)
}

/// A lower bound of the clump's mass, kg: its large sphere alone,
/// 2500 kg/m³ × 4/3 π (2 mm)³ (the arm adds under 10 %), so that the force
/// bound below is if anything stricter than stated.
fn body_mass() -> f64 {
    2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.002f64.powi(3)
}

#[test]
fn damped_bed_comes_to_rest_at_the_default_step() {
    let dir = tempfile::tempdir().unwrap();
    let (peak, last, force) = run_bed(dir.path(), "\"auto\"");
    eprintln!("default dt: peak KE {peak:.3e} J, final {last:.3e} J, max |F|/mg {force:.3e}");
    assert!(peak > 1e-4, "the bed never moved: peak KE {peak:e} J");
    assert!(
        last < 1e-12 * peak,
        "kinetic energy only fell from {peak:e} to {last:e} J"
    );
    assert!(
        force < 1e-6,
        "a clump keeps a net force of {force:e} × its weight"
    );
}

/// The control: at the Rayleigh-only step of before (0.2 t_R = 0.52 dt_c,
/// to the bit) this bed does not settle, so the test above can fail. The
/// margin is thin: at 0.52 dt_c four of five other packing seeds, and this
/// seed at dt rounded to 1.0385e-5 s, do settle — a bed near the limit
/// settles or not by the details of its packing.
#[test]
fn damped_bed_does_not_settle_above_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    // 0.2 × t_R of the 0.6 mm sphere, the default dt before T-52
    let (peak, last, force) = run_bed(dir.path(), "1.038477990626825e-05");
    eprintln!("0.2 t_R: peak KE {peak:.3e} J, final {last:.3e} J, max |F|/mg {force:.3e}");
    assert!(
        last > 1e-12 * peak,
        "settled above the limit: {peak:e} → {last:e} J"
    );
}
