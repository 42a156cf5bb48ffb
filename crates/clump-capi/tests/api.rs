//! The C API called as a C host calls it (through the exported functions):
//! external loads against Newton's second law for a velocity-Verlet step,
//! the id order of the arrays and the sphere → body map against the
//! bodies file, the void fraction of a cell against the sphere's volume,
//! a checkpoint that continues bit for bit, and every kind of bad call
//! answered with a code and a message.

use clump_capi::*;
use std::ffi::{CStr, CString};
use std::path::{Path, PathBuf};
use std::ptr::{null, null_mut};

const R: f64 = 0.001; // ball radius, m
const RHO: f64 = 2500.0; // kg/m^3
const DT: f64 = 1e-5; // s

/// Two balls and one dimer (two spheres of R, centres 1.6 R apart), far
/// apart, no gravity, all moving at 5 cm/s along y (a run at rest would
/// trip the kinetic-energy-jump check on the first push); the file lists the dimer first, so ids follow the
/// rows: dimer 0, balls 1 and 2.
fn scenario(dir: &Path, fluid: &str) -> PathBuf {
    std::fs::write(
        dir.join("bodies.csv"),
        "template,x,y,z,vy\ndimer,0.0,0.0,0.01,0.05\nball,0.01,0.0,0.01,0.05\nball,-0.01,0.0,0.01,0.05\n",
    )
    .unwrap();
    let text = format!(
        r#"
[simulation]
dt = {DT}
gravity = [0.0, 0.0, 0.0]

[domain]
lo = [-0.02, -0.02, 0.0]
hi = [0.02, 0.02, 0.02]

[[material]]
name = "glass"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = {RHO}

[contact]
restitution = 0.5
friction = 0.4

[[template]]
name = "ball"
material = "glass"
spheres = [[0.0, 0.0, 0.0, {R}]]

[[template]]
name = "dimer"
material = "glass"
spheres = [[-0.0008, 0.0, 0.0, {R}], [0.0008, 0.0, 0.0, {R}]]

[[insert]]
kind = "file"
file = "bodies.csv"

[[stage]]
name = "run"
steps = 1000
{fluid}
"#
    );
    let p = dir.join("scenario.toml");
    std::fs::write(&p, text).unwrap();
    p
}

fn c(p: &Path) -> CString {
    CString::new(p.to_str().unwrap()).unwrap()
}

fn message(sim: *mut ClumpSim) -> String {
    unsafe { CStr::from_ptr(clump_sim_error_message(sim)) }
        .to_string_lossy()
        .into_owned()
}

/// A handle with the scenario of `dir` loaded.
fn open(dir: &Path, fluid: &str) -> *mut ClumpSim {
    let sim = clump_sim_new();
    let s = unsafe { clump_sim_load(sim, c(&scenario(dir, fluid)).as_ptr()) };
    assert_eq!(s, CLUMP_OK, "{}", message(sim));
    sim
}

fn body_field(sim: *mut ClumpSim, field: i32, n: usize) -> Vec<f64> {
    let mut v = vec![0.0; n * clump_body_field_width(field)];
    let s = unsafe { clump_sim_body_field(sim, field, v.as_mut_ptr(), v.len()) };
    assert_eq!(s, CLUMP_OK, "{}", message(sim));
    v
}

/// A call answered `CLUMP_ERR_VALUE` with a message holding `text`.
fn refused(sim: *mut ClumpSim, status: i32, text: &str) {
    assert_eq!(status, CLUMP_ERR_VALUE, "{}", message(sim));
    assert!(message(sim).contains(text), "{}", message(sim));
}

fn step(sim: *mut ClumpSim, n: u64) {
    let mut taken = 0;
    assert_eq!(
        unsafe { clump_sim_step(sim, n, &mut taken) },
        CLUMP_OK,
        "{}",
        message(sim)
    );
    assert_eq!(taken, n);
}

#[test]
fn arrays_are_in_id_order_with_the_sphere_to_body_map() {
    let tmp = tempfile::tempdir().unwrap();
    let sim = open(tmp.path(), "");
    let (mut nb, mut ns) = (0usize, 0usize);
    assert_eq!(unsafe { clump_sim_counts(sim, &mut nb, &mut ns) }, CLUMP_OK);
    assert_eq!((nb, ns), (3, 4));
    let mut ids = [0u64; 3];
    assert_eq!(
        unsafe { clump_sim_body_ids(sim, ids.as_mut_ptr(), 3) },
        CLUMP_OK
    );
    assert!(ids[0] < ids[1] && ids[1] < ids[2], "{ids:?}");
    let x = body_field(sim, CLUMP_BODY_POSITION, 3);
    assert_eq!(&x[..], &[0.0, 0.0, 0.01, 0.01, 0.0, 0.01, -0.01, 0.0, 0.01]);
    // volumes: the ball's 4/3 π R³ exactly, the dimer's the union of two
    // spheres whose centres are d = 1.6 R apart: 2 V − lens, lens =
    // π (4R + d)(2R − d)² / 12
    let v = body_field(sim, CLUMP_BODY_VOLUME, 3);
    let ball = 4.0 / 3.0 * std::f64::consts::PI * R.powi(3);
    let d = 1.6 * R;
    let lens = std::f64::consts::PI * (4.0 * R + d) * (2.0 * R - d).powi(2) / 12.0;
    assert!((v[1] - ball).abs() < 1e-12 * ball, "{v:?}");
    assert!((v[0] - (2.0 * ball - lens)).abs() < 1e-2 * ball, "{v:?}");
    let mut map = [9usize; 4];
    assert_eq!(
        unsafe { clump_sim_sphere_body(sim, map.as_mut_ptr(), 4) },
        CLUMP_OK
    );
    assert_eq!(map, [0, 0, 1, 2]);
    let mut r = [0.0; 4];
    let s = unsafe { clump_sim_sphere_field(sim, CLUMP_SPHERE_RADIUS, r.as_mut_ptr(), 4) };
    assert_eq!(s, CLUMP_OK);
    assert_eq!(r, [R; 4]);
    let mut p = [0.0; 12];
    let s = unsafe { clump_sim_sphere_field(sim, CLUMP_SPHERE_POSITION, p.as_mut_ptr(), 12) };
    assert_eq!(s, CLUMP_OK);
    // the dimer's two spheres sit 1.6 R apart about its centre; the balls at theirs
    let gap = ((p[0] - p[3]).powi(2) + (p[1] - p[4]).powi(2) + (p[2] - p[5]).powi(2)).sqrt();
    assert!((gap - 1.6 * R).abs() < 1e-15, "{p:?}");
    assert!(((p[0] + p[3]) / 2.0).abs() < 1e-15 && ((p[2] + p[5]) / 2.0 - 0.01).abs() < 1e-15);
    assert_eq!(&p[6..], &x[3..]);
    unsafe { clump_sim_free(sim) };
}

#[test]
fn external_loads_follow_newtons_second_law() {
    let tmp = tempfile::tempdir().unwrap();
    let sim = open(tmp.path(), "");
    let m = body_field(sim, CLUMP_BODY_MASS, 3);
    let ball = 4.0 / 3.0 * std::f64::consts::PI * R.powi(3) * RHO;
    assert!((m[1] - ball).abs() < 1e-12 * ball);
    // persistent: F on ball 1, torque on ball 2; next step only: F on the dimer
    let (fx, tz) = (2e-5, 3e-11);
    let force = [0.0, 0.0, 0.0, fx, 0.0, 0.0, 0.0, 0.0, 0.0];
    let torque = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, tz];
    let s = unsafe {
        clump_sim_set_external_loads(
            sim,
            force.as_ptr(),
            torque.as_ptr(),
            9,
            CLUMP_LOAD_PERSISTENT,
        )
    };
    assert_eq!(s, CLUMP_OK, "{}", message(sim));
    let once = [0.0, 0.0, fx, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let s = unsafe {
        clump_sim_set_external_loads(sim, once.as_ptr(), null(), 9, CLUMP_LOAD_NEXT_STEP)
    };
    assert_eq!(s, CLUMP_OK, "{}", message(sim));
    let n = 40u64;
    step(sim, n);
    // velocity Verlet: a load set between steps enters the force
    // evaluation at the end of the next step (its second half kick and the
    // first half kick of the step after), so N steps of a persistent load
    // give an impulse F (N − ½) dt, a one-step load F dt
    let v = body_field(sim, CLUMP_BODY_VELOCITY, 3);
    let expect = fx * (n as f64 - 0.5) * DT / m[1];
    assert!(
        (v[3] - expect).abs() < 1e-12 * expect,
        "{} vs {expect}",
        v[3]
    );
    let expect_once = fx * DT / m[0];
    assert!(
        (v[2] - expect_once).abs() < 1e-12 * expect_once,
        "{} vs {expect_once}",
        v[2]
    );
    let w = body_field(sim, CLUMP_BODY_ANGULAR_VELOCITY, 3);
    let inertia = 0.4 * m[2] * R * R; // dL/dt = T, I = 2/5 m R²
    let expect_w = tz * (n as f64 - 0.5) * DT / inertia;
    assert!(
        (w[8] - expect_w).abs() < 1e-12 * expect_w,
        "{} vs {expect_w}",
        w[8]
    );
    // doubled now, the next N steps take the old load
    // for the first half kick and the new one for N − ½ steps
    let force2: Vec<f64> = force.iter().map(|f| 2.0 * f).collect();
    let torque2: Vec<f64> = torque.iter().map(|t| 2.0 * t).collect();
    let s = unsafe {
        clump_sim_set_external_loads(
            sim,
            force2.as_ptr(),
            torque2.as_ptr(),
            9,
            CLUMP_LOAD_PERSISTENT,
        )
    };
    assert_eq!(s, CLUMP_OK, "{}", message(sim));
    step(sim, n);
    let v2 = body_field(sim, CLUMP_BODY_VELOCITY, 3);
    let w2 = body_field(sim, CLUMP_BODY_ANGULAR_VELOCITY, 3);
    let gain = 0.5 + 2.0 * (n as f64 - 0.5);
    let expect = fx * gain * DT / m[1];
    assert!(
        (v2[3] - v[3] - expect).abs() < 1e-9 * expect,
        "{} vs {expect}",
        v2[3] - v[3]
    );
    let expect_w = tz * gain * DT / inertia;
    assert!(
        (w2[8] - w[8] - expect_w).abs() < 1e-9 * expect_w,
        "{} vs {expect_w}",
        w2[8] - w[8]
    );
    let v = v2;
    // the sphere velocity of the spinning ball: v + ω × arm with a zero arm
    let mut sv = [0.0; 12];
    let s = unsafe { clump_sim_sphere_field(sim, CLUMP_SPHERE_VELOCITY, sv.as_mut_ptr(), 12) };
    assert_eq!(s, CLUMP_OK);
    assert_eq!(&sv[6..9], &v[3..6]);
    // cleared: no more acceleration
    assert_eq!(unsafe { clump_sim_clear_coupling(sim) }, CLUMP_OK);
    step(sim, 2);
    let v2 = body_field(sim, CLUMP_BODY_VELOCITY, 3);
    let tail = 2.0 * fx * 0.5 * DT / m[1]; // the half kick of the load still in the last force evaluation
    assert!(
        (v2[3] - (v[3] + tail)).abs() < 1e-12 * expect,
        "{} vs {}",
        v2[3],
        v[3] + tail
    );
    unsafe { clump_sim_free(sim) };
}

#[test]
fn void_fraction_of_a_cell_holding_one_ball() {
    let tmp = tempfile::tempdir().unwrap();
    let sim = open(tmp.path(), "");
    // one cell of 4 mm around ball 1 (at x = 0.01) alone
    let (lo, cell, n) = ([0.008, -0.002, 0.008], [0.004; 3], [1usize, 1, 1]);
    let mut eps = [0.0];
    let s = unsafe {
        clump_sim_void_fraction_grid(
            sim,
            lo.as_ptr(),
            cell.as_ptr(),
            n.as_ptr(),
            null(),
            eps.as_mut_ptr(),
            1,
        )
    };
    assert_eq!(s, CLUMP_OK, "{}", message(sim));
    let expect = 1.0 - 4.0 / 3.0 * std::f64::consts::PI * R.powi(3) / 0.004f64.powi(3);
    assert!((eps[0] - expect).abs() < 1e-12, "{} vs {expect}", eps[0]);
    // the solid on a grid is conserved when its seam cuts a body and the
    // axis is periodic: 8 cells of 5 mm along x from -10.5 mm cut the ball
    // at x = -10 mm; periodic, its cut-off cap wraps to the far end
    let solid = |lo_x: f64, periodic: *const i32| -> f64 {
        let (lo, cell, n) = ([lo_x, -0.002, 0.008], [0.005, 0.004, 0.004], [8usize, 1, 1]);
        let mut e = [0.0; 8];
        let s = unsafe {
            let (lo, cell) = (lo.as_ptr(), cell.as_ptr());
            clump_sim_void_fraction_grid(sim, lo, cell, n.as_ptr(), periodic, e.as_mut_ptr(), 8)
        };
        assert_eq!(s, CLUMP_OK, "{}", message(sim));
        e.iter().map(|x| (1.0 - x) * 0.005 * 0.004 * 0.004).sum()
    };
    let whole = solid(-0.015, null()); // the grid holds every body whole
    let wrapped = solid(-0.0105, [1, 0, 0].as_ptr());
    let cut = solid(-0.0105, null());
    let ball = 4.0 / 3.0 * std::f64::consts::PI * R.powi(3);
    assert!(
        (wrapped - whole).abs() < 1e-12 * whole,
        "{wrapped} vs {whole}"
    );
    assert!(whole - cut > 0.1 * ball, "{cut} vs {whole}");
    unsafe { clump_sim_free(sim) };
}

#[test]
fn a_checkpoint_continues_bit_for_bit() {
    let tmp = tempfile::tempdir().unwrap();
    let fluid = "[fluid]\ndensity = 1000\nviscosity = 1e-3\nvelocity = [0.0, 0.0, 0.01]\n";
    let a = open(tmp.path(), fluid);
    step(a, 10);
    // the coupling arrays travel in the checkpoint: persistent loads, a
    // next-step load, fluid velocities and void fractions, the uniform velocity
    let f = [1e-6, 0.0, 0.0, 0.0, 2e-6, 0.0, 0.0, 0.0, -1e-6];
    let t = [0.0, 0.0, 1e-12, 0.0, 0.0, 0.0, 1e-12, 0.0, 0.0];
    let u = [0.0, 0.0, 0.02, 0.001, 0.0, 0.01, 0.0, 0.0, 0.0];
    let eps = [0.9, 0.7, 1.0];
    let uniform = [0.0, 0.0, 0.005];
    unsafe {
        assert_eq!(
            clump_sim_set_external_loads(a, f.as_ptr(), t.as_ptr(), 9, CLUMP_LOAD_PERSISTENT),
            CLUMP_OK
        );
        assert_eq!(
            clump_sim_set_external_loads(a, t.as_ptr(), f.as_ptr(), 9, CLUMP_LOAD_NEXT_STEP),
            CLUMP_OK
        );
        assert_eq!(clump_sim_set_fluid_velocities(a, u.as_ptr(), 9), CLUMP_OK);
        assert_eq!(clump_sim_set_void_fractions(a, eps.as_ptr(), 3), CLUMP_OK);
        assert_eq!(
            clump_sim_set_uniform_fluid_velocity(a, uniform.as_ptr()),
            CLUMP_OK
        );
    }
    let ck = tmp.path().join("at10.ckpt");
    assert_eq!(
        unsafe { clump_sim_save_checkpoint(a, c(&ck).as_ptr()) },
        CLUMP_OK,
        "{}",
        message(a)
    );
    step(a, 30);
    let b = clump_sim_new();
    assert_eq!(
        unsafe { clump_sim_resume(b, c(&ck).as_ptr()) },
        CLUMP_OK,
        "{}",
        message(b)
    );
    step(b, 30);
    for f in [
        CLUMP_BODY_POSITION,
        CLUMP_BODY_VELOCITY,
        CLUMP_BODY_FLUID_FORCE,
    ] {
        let (x, y) = (body_field(a, f, 3), body_field(b, f, 3));
        assert!(
            x.iter().zip(&y).all(|(p, q)| p.to_bits() == q.to_bits()),
            "{x:?} {y:?}"
        );
    }
    // the fluid lifts the bodies in an upward flow: drag towards +z (the
    // third sees the uniform 5 mm/s, as set, not the scenario's 10 mm/s)
    let ff = body_field(a, CLUMP_BODY_FLUID_FORCE, 3);
    assert!(ff[2] > 0.0 && ff[5] > 0.0 && ff[8] > 0.0, "{ff:?}");
    unsafe {
        clump_sim_free(a);
        clump_sim_free(b);
    }
}

#[test]
fn bad_calls_return_a_code_and_a_message() {
    let tmp = tempfile::tempdir().unwrap();
    // a handle without a simulation
    let sim = clump_sim_new();
    assert_eq!(
        unsafe { clump_sim_step(sim, 1, null_mut()) },
        CLUMP_ERR_NO_SIMULATION
    );
    assert!(message(sim).contains("no simulation is loaded"));
    // NULL handle and NULL arguments
    assert_eq!(
        unsafe { clump_sim_step(null_mut(), 1, null_mut()) },
        CLUMP_ERR_NULL
    );
    assert_eq!(unsafe { clump_sim_load(sim, null()) }, CLUMP_ERR_NULL);
    // a scenario with an unknown drag law: the file, line and key
    let bad = tmp.path().join("bad.toml");
    let text = std::fs::read_to_string(scenario(
        tmp.path(),
        "[fluid]\ndensity = 1000\nviscosity = 1e-3\ndrag = \"difelice\"\n",
    ))
    .unwrap();
    std::fs::write(&bad, text).unwrap();
    assert_eq!(
        unsafe { clump_sim_load(sim, c(&bad).as_ptr()) },
        CLUMP_ERR_SCENARIO
    );
    let m = message(sim);
    assert!(
        m.contains("bad.toml") && m.contains("difelice") && m.contains("di_felice"),
        "{m}"
    );
    let missing = tmp.path().join("missing.toml");
    assert_eq!(
        unsafe { clump_sim_load(sim, c(&missing).as_ptr()) },
        CLUMP_ERR_SCENARIO
    );
    assert!(message(sim).contains("missing.toml"), "{}", message(sim));
    unsafe { clump_sim_free(sim) };

    let sim = open(tmp.path(), "");
    let mut v = [0.0; 8];
    let s = unsafe { clump_sim_body_field(sim, CLUMP_BODY_POSITION, v.as_mut_ptr(), 8) };
    assert_eq!(s, CLUMP_ERR_VALUE);
    assert!(
        message(sim).contains("holds 8 values, 9 are needed"),
        "{}",
        message(sim)
    );
    assert_eq!(
        unsafe { clump_sim_body_field(sim, 99, v.as_mut_ptr(), 8) },
        CLUMP_ERR_VALUE
    );
    let nan = [0.0, 0.0, f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let s = unsafe { clump_sim_set_fluid_velocities(sim, nan.as_ptr(), 9) };
    assert_eq!(s, CLUMP_ERR_VALUE);
    assert!(message(sim).contains("not finite"), "{}", message(sim));
    let s = unsafe { clump_sim_set_external_loads(sim, nan.as_ptr(), null(), 9, 7) };
    assert_eq!(s, CLUMP_ERR_VALUE);
    assert!(
        message(sim).contains("unknown load mode 7"),
        "{}",
        message(sim)
    );
    let eps = [0.5, 1.5, 0.5];
    assert_eq!(
        unsafe { clump_sim_set_void_fractions(sim, eps.as_ptr(), 3) },
        CLUMP_ERR_VALUE
    );
    assert!(message(sim).contains("(0, 1]"), "{}", message(sim));
    // no [fluid]: no uniform fluid velocity to set
    let u = [0.0, 0.0, 1.0];
    assert_eq!(
        unsafe { clump_sim_set_uniform_fluid_velocity(sim, u.as_ptr()) },
        CLUMP_ERR_VALUE
    );
    assert!(message(sim).contains("no fluid"), "{}", message(sim));
    // a failed call changed nothing; the next good call clears the message
    step(sim, 1);
    assert_eq!(message(sim), "");
    let name = unsafe { CStr::from_ptr(clump_status_name(CLUMP_ERR_VALUE)) };
    assert_eq!(name.to_str().unwrap(), "CLUMP_ERR_VALUE");
    unsafe { clump_sim_free(sim) };
}

#[test]
fn stepping_in_pieces_gives_the_bits_of_one_run() {
    // the C example's scenario: 40 clumps packed at the start, settling
    // in water onto a floor (contacts, insertion, fluid)
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/c/settling.toml");
    let sim = clump_sim_new();
    assert_eq!(
        unsafe { clump_sim_load(sim, c(&path).as_ptr()) },
        CLUMP_OK,
        "{}",
        message(sim)
    );
    for _ in 0..30 {
        step(sim, 7);
    }
    let sc = clump_io::scenario::load(&path).unwrap();
    let mut runner = clump_io::run::Runner::detached(sc).unwrap();
    let mut tally = clump_io::run::Tally::start(&runner);
    runner.step_until(210, false, None, &mut tally).unwrap();
    let w = runner.world();
    let mut order: Vec<usize> = (0..w.bodies().len()).collect();
    order.sort_by_key(|&i| w.bodies().id[i]);
    let x = body_field(sim, CLUMP_BODY_POSITION, order.len());
    let v = body_field(sim, CLUMP_BODY_VELOCITY, order.len());
    for (k, &i) in order.iter().enumerate() {
        let (p, q) = (w.bodies().position[i], w.bodies().velocity[i]);
        for a in 0..3 {
            assert_eq!(x[3 * k + a].to_bits(), p[a].to_bits(), "body {k}");
            assert_eq!(v[3 * k + a].to_bits(), q[a].to_bits(), "body {k}");
        }
    }
    unsafe { clump_sim_free(sim) };
}

/// After one step (the grid set at a boundary acts from the force
/// evaluation at the end of the step, at the half-step velocity, whose z
/// component is still 0: nothing pushed along z before): a Stokes ball in
/// a grid field `u_z = a + b x` feels `3π μ d u_z(x)` along z (Stokes
/// 1851), the linear field interpolated exactly.
#[test]
fn fluid_velocity_grid_from_the_host_gives_stokes_drag() {
    let tmp = tempfile::tempdir().unwrap();
    let mu = 1e-3;
    let sim = open(
        tmp.path(),
        "[fluid]\ndensity = 1000\nviscosity = 1e-3\ndrag = \"stokes\"\n",
    );
    let (a, b) = (2e-3, 0.05);
    let (o, h, n) = ([-0.02, -0.02, 0.0], [0.01, 0.04, 0.02], [5usize, 2, 2]);
    let mut u = Vec::new();
    for _k in 0..n[2] {
        for _j in 0..n[1] {
            for i in 0..n[0] {
                u.extend([0.0, 0.0, a + b * (o[0] + i as f64 * h[0])]);
            }
        }
    }
    let s = unsafe {
        clump_sim_set_fluid_velocity_grid(
            sim,
            o.as_ptr(),
            h.as_ptr(),
            n.as_ptr(),
            u.as_ptr(),
            u.len(),
        )
    };
    assert_eq!(s, CLUMP_OK, "{}", message(sim));
    step(sim, 1);
    let f = body_field(sim, CLUMP_BODY_FLUID_FORCE, 3);
    let x = body_field(sim, CLUMP_BODY_POSITION, 3);
    let beta = 3.0 * std::f64::consts::PI * mu * 2.0 * R;
    for k in [1, 2] {
        let fz = beta * (a + b * x[3 * k]);
        assert!(
            (f[3 * k + 2] - fz).abs() < 1e-12 * fz,
            "{} vs {fz}",
            f[3 * k + 2]
        );
    }
    // removed (NULL velocity): the uniform velocity again, zero, so the
    // drag now opposes the rise the grid gave (it pushed up before)
    let s = unsafe { clump_sim_set_fluid_velocity_grid(sim, null(), null(), null(), null(), 0) };
    assert_eq!(s, CLUMP_OK, "{}", message(sim));
    step(sim, 1);
    let v = body_field(sim, CLUMP_BODY_VELOCITY, 3);
    let f = body_field(sim, CLUMP_BODY_FLUID_FORCE, 3);
    assert!(v[5] > 0.0 && f[5] < 0.0, "v_z {} F_z {}", v[5], f[5]);
    // refused: a short array, a zero spacing, a grid without a fluid
    let bad = |sim, h: [f64; 3], len: usize| unsafe {
        clump_sim_set_fluid_velocity_grid(sim, o.as_ptr(), h.as_ptr(), n.as_ptr(), u.as_ptr(), len)
    };
    refused(sim, bad(sim, h, u.len() - 3), "60 are needed");
    refused(
        sim,
        bad(sim, [0.01, 0.0, 0.02], u.len()),
        "spacing along y must be > 0",
    );
    let tmp2 = tempfile::tempdir().unwrap();
    let dry = open(tmp2.path(), "");
    refused(dry, bad(dry, h, u.len()), "no fluid is set");
    unsafe {
        clump_sim_free(sim);
        clump_sim_free(dry);
    }
}

/// A void-fraction field from the host, read at each body: the Di Felice
/// (1994) drag at slip `w` = 5 cm/s at the field's ε, against the law's
/// closed form (Dallavalle's `C_d`). The scenario's fluid moves with the
/// bodies (no slip, no load before the step), the host then sets a flow
/// `w` faster along z: the slip at the end of the first step is `w` exactly.
#[test]
fn void_fraction_field_from_the_host_sets_the_hindered_drag() {
    let tmp = tempfile::tempdir().unwrap();
    let (rho, mu, w, d) = (1000.0, 1e-3, 0.05, 2.0 * R);
    let sim = open(
        tmp.path(),
        "[fluid]\ndensity = 1000\nviscosity = 1e-3\ndrag = \"di_felice\"\nvelocity = [0.0, 0.05, 0.0]\n",
    );
    let flow = [0.0, 0.05, w];
    assert_eq!(
        unsafe { clump_sim_set_uniform_fluid_velocity(sim, flow.as_ptr()) },
        CLUMP_OK
    );
    // two cells along x: ball 2 (x = -10 mm) in the first, ball 1 (x = 10
    // mm) in the second; the dimer at x = 0 is in the second
    let (lo, cell, n) = ([-0.02, -0.02, 0.0], [0.02, 0.04, 0.02], [2usize, 1, 1]);
    let eps = [0.6, 0.85];
    let s = unsafe {
        clump_sim_set_void_fraction_field(
            sim,
            lo.as_ptr(),
            cell.as_ptr(),
            n.as_ptr(),
            eps.as_ptr(),
            2,
        )
    };
    assert_eq!(s, CLUMP_OK, "{}", message(sim));
    step(sim, 1);
    let f = body_field(sim, CLUMP_BODY_FLUID_FORCE, 3);
    let di_felice = |e: f64| {
        let re = rho * e * w * d / mu;
        let cd = (0.63 + 4.8 / re.sqrt()).powi(2);
        let chi = 3.7 - 0.65 * (-(1.5 - re.log10()).powi(2) / 2.0).exp();
        std::f64::consts::PI / 8.0 * rho * d * d * cd * (e * w).powi(2) * e.powf(-chi)
    };
    for (k, e) in [(1, eps[1]), (2, eps[0])] {
        let expect = di_felice(e);
        assert!(
            (f[3 * k + 2] - expect).abs() < 1e-12 * expect,
            "ε = {e}: {} vs {expect}",
            f[3 * k + 2]
        );
        assert_eq!(f[3 * k + 1], 0.0);
    }
    // refused: a value outside (0, 1], a NULL count array
    let bad = [0.6, 1.5];
    let s = unsafe {
        clump_sim_set_void_fraction_field(
            sim,
            lo.as_ptr(),
            cell.as_ptr(),
            n.as_ptr(),
            bad.as_ptr(),
            2,
        )
    };
    refused(sim, s, "cell 1 must be in (0, 1]");
    let s = unsafe {
        clump_sim_set_void_fraction_field(sim, lo.as_ptr(), cell.as_ptr(), null(), eps.as_ptr(), 2)
    };
    assert_eq!(s, CLUMP_ERR_NULL);
    unsafe { clump_sim_free(sim) };
}
