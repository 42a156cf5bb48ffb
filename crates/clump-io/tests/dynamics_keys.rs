//! The dynamics keys a user reaches from a scenario (docs/scenario.md):
//! force/torque flags per template, per insert and per body-file column,
//! fixed and driven bodies, z-x-z Euler angles and body-frame angular
//! velocities in body files, start steps, a template's given centre of mass.
//! Checked against closed forms (the matrix A, docs/theory.md T-3; Coulomb drag
//! on a driven sphere; the weight a fixed body carries).

mod support;
use clump_io::run::{RunOptions, Runner};
use clump_io::scenario::{self, Files, InsertSpec};
use glam::{DMat3, DVec3};
use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::path::Path;

const G: f64 = 9.81;
const E: f64 = 1e7;
const NU: f64 = 0.3;
const RHO: f64 = 2500.0;
const BIG: f64 = 0.05;
const SMALL: f64 = 0.01;

fn text(template_extra: &str, insert_extra: &str, stage: &str) -> String {
    format!(
        r#"
[simulation]
dt = 1e-5
gravity = [0.0, 0.0, -{G}]
[domain]
lo = [-0.5, -0.5, -0.5]
hi = [0.5, 0.5, 0.5]
[[material]]
name = "m"
youngs_modulus = {E}
poisson_ratio = {NU}
density = {RHO}
[contact]
restitution = 0.3
friction = 0.3
[[template]]
name = "big"
material = "m"
shape = "sphere"
radius = {BIG}
[[template]]
name = "small"
material = "m"
shape = "sphere"
radius = {SMALL}
{template_extra}
[[insert]]
kind = "file"
file = "bodies.csv"
{insert_extra}
[[stage]]
{stage}
"#
    )
}

fn parse(t: &str, bodies: &str) -> Result<scenario::Scenario, String> {
    let mut files = BTreeMap::new();
    files.insert("bodies.csv".to_string(), bodies.as_bytes().to_vec());
    scenario::parse(Path::new("t.toml"), t.to_string(), Files::embedded(files))
        .map_err(|e| e.to_string())
}

fn file_bodies(sc: &scenario::Scenario) -> &[clump_core::body::BodyInit] {
    let InsertSpec::File { bodies } = &sc.inserts[0].kind else {
        panic!("expected a file insertion")
    };
    bodies
}

/// Flags: the template's, overridden by the insert's, overridden per body
/// by the file's columns.
#[test]
fn flags_resolve_template_then_insert_then_column() {
    let sc = parse(
        &text(
            "force_flags = [true, false, true]\ntorque_flags = [false, false, true]",
            "torque_flags = [true, true, false]",
            "steps = 1",
        ),
        "template,x,y,z,ffz,tfx\nsmall,0,0,0,0,0\nsmall,0.1,0,0,1,1\nbig,0.3,0,0,1,1\n",
    )
    .unwrap();
    let b = file_bodies(&sc);
    assert_eq!(b[0].force_flag, [true, false, false]);
    assert_eq!(b[0].torque_flag, [false, true, false]);
    assert_eq!(b[1].force_flag, [true, false, true]);
    assert_eq!(b[1].torque_flag, [true, true, false]);
    // the big template gives no flags: free, then the insert's torque flags
    assert_eq!(b[2].force_flag, [true, true, true]);
    assert_eq!(b[2].torque_flag, [true, true, false]);
}

/// Euler columns give A (docs/theory.md T-3, written out here): the body's
/// rotation matrix (body → world) is Aᵀ; body-frame angular velocity
/// columns give ω_world = Aᵀ ω_b; start_time becomes ⌈t/dt⌉.
#[test]
fn euler_and_body_frame_columns_follow_the_seed() {
    let (phi, theta, psi): (f64, f64, f64) = (0.4, 1.1, -2.3 + 2.0 * PI);
    let wb = DVec3::new(1.0, -2.0, 3.0);
    let sc = parse(
        &text("", "", "steps = 1"),
        &format!(
            "template,x,y,z,phi,theta,psi,wbx,wby,wbz,start_time\nsmall,0,0,0,{phi},{theta},{psi},{},{},{},0.0012345\n",
            wb.x, wb.y, wb.z
        ),
    )
    .unwrap();
    let b = file_bodies(&sc)[0];
    let (sf, cf, st, ct, sp, cp) = (
        phi.sin(),
        phi.cos(),
        theta.sin(),
        theta.cos(),
        psi.sin(),
        psi.cos(),
    );
    // rows of A (docs/theory.md T-3)
    let a = DMat3::from_cols(
        DVec3::new(cf * cp - sf * ct * sp, sf * cp + cf * ct * sp, st * sp),
        DVec3::new(-cf * sp - sf * ct * cp, -sf * sp + cf * ct * cp, st * cp),
        DVec3::new(sf * st, -cf * st, ct),
    )
    .transpose();
    let r = DMat3::from_quat(b.orientation);
    assert!(
        (r - a.transpose())
            .abs()
            .to_cols_array()
            .iter()
            .all(|&e| e < 1e-15),
        "{r} vs {}",
        a.transpose()
    );
    assert!((b.angular_velocity - a.transpose() * wb).length() < 1e-14);
    assert_eq!(b.start_step, 124);
    // bad inputs name the column
    for (file, want) in [
        (
            "template,x,y,z,phi,theta\nsmall,0,0,0,0,0\n",
            "needs all of the columns phi, theta, psi",
        ),
        (
            "template,x,y,z,qw,phi,theta,psi\nsmall,0,0,0,1,0,0,0\n",
            "not both",
        ),
        (
            "template,x,y,z,wx,wbx,wby,wbz\nsmall,0,0,0,1,0,0,0\n",
            "not both",
        ),
        (
            "template,x,y,z,ffx\nsmall,0,0,0,2\n",
            "column 'ffx': expected 1 or 0",
        ),
        (
            "template,x,y,z,theta_\nsmall,0,0,0,2\n",
            "did you mean 'theta'",
        ),
        (
            "template,x,y,z,phi,theta,psi\nsmall,0,0,0,0,4,0\n",
            "[0, pi]",
        ),
    ] {
        let e = parse(&text("", "", "steps = 1"), file).unwrap_err();
        assert!(e.contains("bodies.csv:") && e.contains(want), "{file}: {e}");
    }
}

/// Static Hertz overlap of spheres `BIG` and `SMALL` pressed by `load` (N).
fn hertz_overlap(load: f64) -> f64 {
    let e_star = E / (2.0 * (1.0 - NU * NU));
    let r_star = BIG * SMALL / (BIG + SMALL);
    (load / (4.0 / 3.0 * e_star * r_star.sqrt())).powf(2.0 / 3.0)
}

/// From a scenario: a large sphere driven about x at ω (body-file columns
/// `wx`, `driven`) under a small sphere held in x, y and in rotation by its
/// template's flags. Coulomb drag: the contacts' torque on the driven body
/// is −μ m g (R − δ/2) x̂; the driven body does not move.
#[test]
fn driven_sphere_from_a_scenario_feels_the_coulomb_torque() {
    let ms = RHO * 4.0 / 3.0 * PI * SMALL.powi(3);
    let delta = hertz_overlap(ms * G);
    let d = std::env::temp_dir().join(format!("clump_dyn_keys_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(
        d.join("bodies.csv"),
        format!(
            "template,x,y,z,wx,driven\nbig,0,0,0,2.0,1\nsmall,0,0,{},0,0\n",
            BIG + SMALL - delta
        ),
    )
    .unwrap();
    std::fs::write(
        d.join("s.toml"),
        text(
            "force_flags = [false, false, true]\ntorque_flags = [false, false, false]",
            "[output.trajectory]\nbodies = [1]\nevery_steps = 20000\nloads = true",
            "steps = 20000",
        ),
    )
    .unwrap();
    let sc = scenario::load(&d.join("s.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut run = Runner::new(sc, &d.join("out")).unwrap();
    run.run(RunOptions::default()).unwrap();
    let w = run.world();
    let b = w.body_index(1).unwrap();
    let theory = -0.3 * ms * G * (BIG - 0.5 * delta);
    eprintln!(
        "driven torque {} (theory {theory:.6e})",
        w.bodies().torque[b]
    );
    assert_eq!(w.bodies().position[b], DVec3::ZERO);
    assert!(((w.bodies().torque[b].x - theory) / theory).abs() < 1e-6);
    // the same load in the driven body's trajectory (last row, column mx)
    let traj = d.join("out").join("traj_1.csv");
    let mx = support::last_value(&traj, "mx");
    assert_eq!(support::last_value(&traj, "time"), 0.2);
    assert!(((mx - theory) / theory).abs() < 1e-6, "trajectory mx {mx}");
    let s = w.body_index(2).unwrap();
    assert_eq!(
        (w.bodies().position[s].x, w.bodies().position[s].y),
        (0.0, 0.0)
    );
}

/// `fixed = true` on an insert: those bodies never move and carry what
/// rests on them; velocities on a fixed insert are refused.
#[test]
fn fixed_insert_keeps_its_bodies_still() {
    let d = std::env::temp_dir().join(format!("clump_dyn_fixed_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("bodies.csv"), "template,x,y,z\nbig,0.01,0.02,0.03\n").unwrap();
    std::fs::write(
        d.join("top.csv"),
        format!(
            "template,x,y,z\nsmall,0.01,0.02,{}\n",
            0.03 + BIG + SMALL + 0.001
        ),
    )
    .unwrap();
    let t = text(
        "",
        "fixed = true\n[[insert]]\nkind = \"file\"\nfile = \"top.csv\"",
        "steps = 30000",
    );
    std::fs::write(d.join("s.toml"), &t).unwrap();
    let sc = scenario::load(&d.join("s.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut run = Runner::new(sc, &d.join("out")).unwrap();
    run.run(RunOptions::default()).unwrap();
    let w = run.world();
    let b = w.body_index(1).unwrap();
    assert_eq!(w.bodies().position[b], DVec3::new(0.01, 0.02, 0.03));
    let ms = RHO * 4.0 / 3.0 * PI * SMALL.powi(3);
    let mb = RHO * 4.0 / 3.0 * PI * BIG.powi(3);
    let contact = w.bodies().force[b].z + mb * G;
    eprintln!("fixed body carries {contact:.9} N, weight {:.9} N", ms * G);
    assert!((contact + ms * G).abs() < 1e-6 * ms * G);
    let e = parse(
        &text("", "fixed = true", "steps = 1"),
        "template,x,y,z,vx\nbig,0,0,0,1\n",
    )
    .unwrap_err();
    assert!(e.contains("fixed bodies are at rest"), "{e}");
    let e = parse(
        &text("", "fixed = true\ndriven = true", "steps = 1"),
        "template,x,y,z\nbig,0,0,0\n",
    )
    .unwrap_err();
    assert!(e.contains("not both"), "{e}");
    let e = parse(
        &text("", "fixd = true", "steps = 1"),
        "template,x,y,z\nbig,0,0,0\n",
    )
    .unwrap_err();
    assert!(e.contains("fixed"), "{e}");
}

/// A template's given centre of mass: the body frame's origin is that
/// point, and its inertia is the one given about it.
#[test]
fn template_center_of_mass_is_the_given_point() {
    let t = text(
        "[[template]]\nname = \"offset\"\nmaterial = \"m\"\nspheres = [[0.0, 0.0, 0.0, 0.01], [0.02, 0.0, 0.0, 0.01]]\nmass = 0.02\ninertia = [[1e-6, 0, 0], [0, 2e-6, 0], [0, 0, 3e-6]]\ncenter_of_mass = [0.005, 0.0, 0.0]",
        "",
        "steps = 1",
    );
    let sc = parse(&t, "template,x,y,z\nbig,0,0,0\n").unwrap();
    let tp = &sc.templates[2].template;
    assert_eq!(tp.input_center_of_mass, DVec3::new(0.005, 0.0, 0.0));
    assert_eq!(tp.principal_inertia, DVec3::new(1e-6, 2e-6, 3e-6));
    // sphere centres relative to the given centre: -0.005 and +0.015 along x
    let xs: Vec<f64> = tp.spheres.iter().map(|s| s.center.x).collect();
    assert!(
        (xs[0] + 0.005).abs() < 1e-15 && (xs[1] - 0.015).abs() < 1e-15,
        "{xs:?}"
    );
    let e = parse(
        &text("[[template]]\nname = \"o\"\nmaterial = \"m\"\nshape = \"sphere\"\nradius = 0.01\ncenter_of_mass = [0.0, 0.0, 0.0]", "", "steps = 1"),
        "template,x,y,z\nbig,0,0,0\n",
    )
    .unwrap_err();
    assert!(
        e.contains("'center_of_mass' needs 'mass' and 'inertia'"),
        "{e}"
    );
}

/// Trajectory Euler output against a closed form: a body driven to turn
/// about world Z at Ω, from Euler angles (φ0, θ0, ψ0) given in the body
/// file, has φ(t) = φ0 + Ω t, θ and ψ constant (a rotation about Z
/// composes with the first z-x-z rotation), and the written rows of A are
/// docs/theory.md T-3 at those angles.
#[test]
fn trajectory_euler_columns_of_a_body_turning_about_z() {
    let (phi0, theta0, psi0, om) = (0.3f64, 1.2f64, 2.5f64, 1.5f64);
    let d = std::env::temp_dir().join(format!("clump_dyn_euler_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(
        d.join("bodies.csv"),
        format!(
            "template,x,y,z,phi,theta,psi,wz,driven\nsmall,0,0,0,{phi0},{theta0},{psi0},{om},1\n"
        ),
    )
    .unwrap();
    let t = text(
        "",
        "[output.trajectory]\nbodies = [1]\nevery_steps = 1000\neuler = true",
        "steps = 20000",
    );
    std::fs::write(d.join("s.toml"), &t).unwrap();
    let sc = scenario::load(&d.join("s.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut run = Runner::new(sc, &d.join("out")).unwrap();
    run.run(RunOptions::default()).unwrap();
    let text = std::fs::read_to_string(d.join("out").join("traj_1.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|c| *c == n).unwrap();
    let mut rows = 0;
    for line in lines {
        let r: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let time = r[col("time")];
        let phi = (phi0 + om * time).rem_euclid(2.0 * PI);
        let dphi = (r[col("phi")] - phi + PI).rem_euclid(2.0 * PI) - PI;
        assert!(
            dphi.abs() < 1e-12,
            "t {time}: phi {} vs {phi}",
            r[col("phi")]
        );
        assert!((r[col("theta")] - theta0).abs() < 1e-12);
        assert!((r[col("psi")] - psi0).abs() < 1e-12);
        let (sf, cf, st, ct, sp, cp) = (
            phi.sin(),
            phi.cos(),
            theta0.sin(),
            theta0.cos(),
            psi0.sin(),
            psi0.cos(),
        );
        let a = [
            [cf * cp - sf * ct * sp, sf * cp + cf * ct * sp, st * sp],
            [-cf * sp - sf * ct * cp, -sf * sp + cf * ct * cp, st * cp],
            [sf * st, -cf * st, ct],
        ];
        for (i, row) in ["ex", "ey", "ez"].iter().enumerate() {
            for (j, c) in ["x", "y", "z"].iter().enumerate() {
                let v = r[col(&format!("{row}{c}"))];
                assert!((v - a[i][j]).abs() < 1e-12, "{row}{c} {v} vs {}", a[i][j]);
            }
        }
        rows += 1;
    }
    assert!(rows >= 20, "{rows} rows");
}
