//! End-to-end tests of `clump run` / `clump resume`: a run split by a
//! checkpoint repeats the uninterrupted run bit for bit, SIGTERM/SIGINT/SIGHUP
//! checkpoint and exit with 143/130/129, VTK series are complete, and bad input
//! exits with status 2.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn clump() -> Command {
    Command::new(env!("CARGO_BIN_EXE_clump"))
}

/// A fresh directory for one test, removed when the test ends.
fn tmp(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("clump-cli-run-{name}-"))
        .tempdir()
        .unwrap()
}

/// A few dozen clumps (tetrahedra and rods, scaled ±10 %) fall onto a
/// frictional floor in a box; in stage 2 gravity tilts and a stream adds
/// bodies. Rolling friction (EPSD) and sliding friction make contact
/// histories matter.
fn scenario(stage2_steps: u64) -> String {
    format!(
        r#"
[simulation]
dt = 4e-5
gravity = [0.0, 0.0, -9.81]

[domain]
lo = [-0.03, -0.03, -0.01]
hi = [0.03, 0.03, 0.1]

[[material]]
name = "rock"
youngs_modulus = 5e6
poisson_ratio = 0.3
density = 2500

[[material]]
name = "steel"
youngs_modulus = 5e7
poisson_ratio = 0.3
density = 7800

[contact]
restitution = 0.3
friction = 0.5
rolling_friction = 0.1
rolling = "epsd"

[[pair]]
materials = ["rock", "steel"]
friction = 0.4

[[template]]
name = "tetra"
material = "rock"
shape = "tetrahedron"
radius = 0.002
edge = 0.0025

[[template]]
name = "rod"
material = "rock"
shape = "rod"
n = 3
radius = 0.0015
spacing = 0.0015

[[mix]]
name = "m"
basis = "mass"
[[mix.component]]
template = "tetra"
fraction = 0.5
size = {{ distribution = "uniform", min = 0.9, max = 1.1 }}
[[mix.component]]
template = "rod"
fraction = 0.5

[[wall]]
name = "floor"
material = "steel"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[wall]]
name = "box"
material = "steel"
type = "box"
lo = [-0.012, -0.012, -0.005]
hi = [0.012, 0.012, 0.1]

[[stage]]
name = "fill"
steps = 600

[[stage]]
name = "tilt"
steps = {stage2_steps}
gravity = [2.0, 0.0, -9.81]

[[insert]]
kind = "pack"
stage = "fill"
mix = "m"
count = 60
region = {{ type = "box", lo = [-0.011, -0.011, 0.001], hi = [0.011, 0.011, 0.05] }}
velocity = [0.0, 0.0, -0.5]
seed = 11

[[insert]]
kind = "stream"
stage = "tilt"
mix = "m"
region = {{ type = "box", lo = [-0.01, -0.01, 0.06], hi = [0.01, 0.01, 0.09] }}
velocity = [0.0, 0.0, -0.5]
bodies_per_second = 1000
end = 0.02
seed = 5

[output]
vtk = {{ every_steps = 200 }}
thermo = {{ every_steps = 50 }}
checkpoint = {{ every_steps = 300 }}
trajectory = {{ bodies = [1, 2], every_steps = 10 }}
"#
    )
}

fn write_scenario(dir: &Path, stage2_steps: u64) -> PathBuf {
    let p = dir.join("fall.toml");
    std::fs::write(&p, scenario(stage2_steps)).unwrap();
    p
}

fn run_ok(cmd: &mut Command) -> String {
    let o = cmd.output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        o.status.success(),
        "{cmd:?} failed ({:?}):\n{err}\n{}",
        o.status,
        String::from_utf8_lossy(&o.stdout)
    );
    err
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn last_thermo(dir: &Path) -> Vec<String> {
    read(&dir.join("thermo.csv"))
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect()
}

#[test]
fn split_run_is_bit_identical_to_uninterrupted_run() {
    let dir = tmp("split");
    let d = dir.path();
    let sc = write_scenario(d, 600);
    let (a, b, c) = (d.join("a"), d.join("b"), d.join("c"));
    // uninterrupted, 2 threads
    run_ok(
        clump()
            .arg("run")
            .arg(&sc)
            .arg("-o")
            .arg(&a)
            .args(["--threads", "2"]),
    );
    // first half on 1 thread, stopped at step 900 (inside the streaming stage)
    run_ok(clump().arg("run").arg(&sc).arg("-o").arg(&b).args([
        "--threads",
        "1",
        "--steps",
        "900",
    ]));
    let ck = b.join("checkpoint_000000900.ckpt");
    assert!(ck.is_file());
    let m: serde_json::Value = serde_json::from_str(&read(&b.join("manifest.json"))).unwrap();
    assert_eq!(m["status"], "step_limit");
    // resume needs nothing but the checkpoint: move the scenario away
    std::fs::rename(&sc, d.join("moved.toml")).unwrap();
    run_ok(clump().arg("resume").arg(&ck).args(["--threads", "2"]));
    let fa = read(&a.join("final_state.json"));
    let fb = read(&b.join("final_state.json"));
    assert!(
        fa == fb,
        "final states differ between the uninterrupted and the split run"
    );
    assert_eq!(
        read(&a.join("thermo.csv")),
        read(&b.join("thermo.csv")),
        "thermo.csv differs"
    );
    for id in [1, 2] {
        let f = format!("traj_{id}.csv");
        assert_eq!(read(&a.join(&f)), read(&b.join(&f)), "{f} differs");
    }
    // resuming at N/2 = 600 (1200 steps in all) from a periodic checkpoint of
    // the uninterrupted run, into a new folder
    run_ok(
        clump()
            .arg("resume")
            .arg(a.join("checkpoint_000000600.ckpt"))
            .arg("-o")
            .arg(&c)
            .args(["--threads", "2"]),
    );
    assert!(
        read(&c.join("final_state.json")) == fa,
        "resume from the periodic checkpoint differs"
    );
    // the run was not trivial: bodies were streamed in and touch each other and the walls
    let fs: serde_json::Value = serde_json::from_str(&fa).unwrap();
    assert!(
        fs["bodies"].as_array().unwrap().len() > 65,
        "the stream inserted nothing"
    );
    let last = last_thermo(&a);
    let pair: u64 = last[4].parse().unwrap();
    let wall: u64 = last[5].parse().unwrap();
    assert!(
        pair > 20 && wall > 20,
        "too few contacts for a meaningful test: {last:?}"
    );
}

#[test]
fn vtk_series_lists_every_frame() {
    let dir = tmp("vtk");
    let d = dir.path();
    let sc = write_scenario(d, 200);
    let out = d.join("out");
    run_ok(
        clump()
            .arg("run")
            .arg(&sc)
            .arg("-o")
            .arg(&out)
            .args(["--threads", "2"]),
    );
    for kind in ["spheres", "bodies", "walls"] {
        let pvd = read(&out.join(format!("{kind}.pvd")));
        let files: Vec<&str> = pvd
            .split("file=\"")
            .skip(1)
            .map(|s| s.split('"').next().unwrap())
            .collect();
        // every 200 steps over 800 steps: steps 0, 200, ..., 800
        assert_eq!(files.len(), 5, "{kind}.pvd: {pvd}");
        for (k, f) in files.iter().enumerate() {
            assert_eq!(*f, format!("{kind}_{:06}.vtp", 200 * k));
            let body = std::fs::read(out.join(f)).unwrap();
            assert!(
                body.starts_with(b"<?xml") || body.starts_with(b"<VTKFile"),
                "{f} is not VTK XML"
            );
        }
    }
    let m: serde_json::Value = serde_json::from_str(&read(&out.join("manifest.json"))).unwrap();
    assert_eq!(m["status"], "completed");
    assert_eq!(m["final_step"], 800);
    assert!(m["sphere_steps_per_s"].as_f64().unwrap() > 0.0);
    assert!(m["threads"].as_u64().unwrap() == 2);
    assert!(read(&out.join("scenario.toml")).contains("[[stage]]"));
    let header = read(&out.join("thermo.csv"))
        .lines()
        .next()
        .unwrap()
        .to_string();
    assert!(
        header.contains("floor_fz") && header.contains("box_fz"),
        "{header}"
    );
}

fn wait_for_rows(child: &mut std::process::Child, path: &Path, rows: usize, timeout: Duration) {
    let t = Instant::now();
    while t.elapsed() < timeout {
        if let Some(st) = child.try_wait().unwrap() {
            let mut err = String::new();
            use std::io::Read;
            child
                .stderr
                .take()
                .unwrap()
                .read_to_string(&mut err)
                .unwrap();
            panic!("the run ended early ({st:?}):\n{err}");
        }
        if std::fs::read_to_string(path)
            .map(|s| s.lines().count() > rows)
            .unwrap_or(false)
        {
            return;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    panic!(
        "{} did not reach {rows} rows in {timeout:?}",
        path.display()
    );
}

fn interrupt_and_resume(signal: &str, code: i32) {
    let dir = tmp(&format!("sig{signal}"));
    let d = dir.path();
    let sc = write_scenario(d, 1_000_000);
    let out = d.join("out");
    let mut child = clump()
        .arg("run")
        .arg(&sc)
        .arg("-o")
        .arg(&out)
        .args(["--threads", "2"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // the signal handlers are installed before the first thermo row
    wait_for_rows(
        &mut child,
        &out.join("thermo.csv"),
        20,
        Duration::from_secs(120),
    );
    let st = Command::new("kill")
        .arg(format!("-{signal}"))
        .arg(child.id().to_string())
        .status()
        .unwrap();
    assert!(st.success());
    let o = child.wait_with_output().unwrap();
    assert_eq!(
        o.status.code(),
        Some(code),
        "stderr:\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let m: serde_json::Value = serde_json::from_str(&read(&out.join("manifest.json"))).unwrap();
    assert!(
        m["status"].as_str().unwrap().starts_with("interrupted"),
        "{m}"
    );
    let step = m["final_step"].as_u64().unwrap();
    let ck = out.join(format!("checkpoint_{step:09}.ckpt"));
    assert!(ck.is_file(), "no checkpoint at the interrupt step {step}");
    assert_eq!(m["checkpoint"].as_str().unwrap(), ck.display().to_string());
    check_flushed_at(&out, step);
    // resume a little further and compare with an uninterrupted run to the same step
    let target = (step + 300).to_string();
    run_ok(
        clump()
            .arg("resume")
            .arg(&ck)
            .args(["--threads", "1", "--steps", &target]),
    );
    let straight = d.join("straight");
    run_ok(clump().arg("run").arg(&sc).arg("-o").arg(&straight).args([
        "--threads",
        "2",
        "--steps",
        &target,
    ]));
    assert!(
        read(&out.join("final_state.json")) == read(&straight.join("final_state.json")),
        "interrupted + resumed run differs from the uninterrupted one"
    );
    // every output of the resumed run repeats the uninterrupted one
    for f in [
        "thermo.csv",
        "traj_1.csv",
        "traj_2.csv",
        "spheres.pvd",
        "bodies.pvd",
    ] {
        assert!(
            read(&out.join(f)) == read(&straight.join(f)),
            "{f} of the interrupted + resumed run differs"
        );
    }
    let last_frame = format!("spheres_{:06}.vtp", (step + 300) / 200 * 200);
    assert!(
        std::fs::read(out.join(&last_frame)).unwrap()
            == std::fs::read(straight.join(&last_frame)).unwrap(),
        "{last_frame} differs"
    );
}

/// After an interruption at `step` (the checkpoint step), every output is
/// complete on disk: `thermo.csv` (every 50 steps) and the trajectories
/// (every 10 steps) hold every row up to `step`, each whole, and each `.pvd`
/// series is a complete XML file listing every frame (every 200 steps) up
/// to `step`, each of which exists.
fn check_flushed_at(out: &Path, step: u64) {
    let thermo = read(&out.join("thermo.csv"));
    assert!(thermo.ends_with('\n'), "thermo.csv ends mid-row");
    let lines: Vec<&str> = thermo.lines().collect();
    let fields = lines[0].split(',').count();
    assert_eq!(
        lines.len() as u64 - 1,
        step / 50 + 1,
        "thermo rows at step {step}"
    );
    for l in &lines[1..] {
        assert_eq!(l.split(',').count(), fields, "incomplete thermo row {l}");
    }
    let last: u64 = lines
        .last()
        .unwrap()
        .split(',')
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(last, step / 50 * 50);
    for id in [1, 2] {
        let t = read(&out.join(format!("traj_{id}.csv")));
        assert!(t.ends_with('\n'), "traj_{id}.csv ends mid-row");
        assert_eq!(
            t.lines().count() as u64 - 1,
            step / 10 + 1,
            "traj_{id}.csv rows"
        );
    }
    for kind in ["spheres", "bodies", "walls"] {
        let pvd = read(&out.join(format!("{kind}.pvd")));
        assert!(
            pvd.trim_end().ends_with("</VTKFile>"),
            "{kind}.pvd incomplete"
        );
        let files: Vec<&str> = pvd
            .split("file=\"")
            .skip(1)
            .map(|s| s.split('"').next().unwrap())
            .collect();
        assert_eq!(files.len() as u64, step / 200 + 1, "{kind}.pvd: {pvd}");
        for f in files {
            // frames hold raw appended binary data: compare bytes
            let x = std::fs::read(out.join(f)).unwrap();
            let end = x.iter().rposition(|b| !b.is_ascii_whitespace()).unwrap();
            assert!(x[..=end].ends_with(b"</VTKFile>"), "{f} incomplete");
        }
    }
}

#[test]
fn sigterm_checkpoints_and_exits_143_then_resumes() {
    interrupt_and_resume("TERM", 143);
}

/// A closed terminal (SIGHUP) stops the run like SIGTERM: a checkpoint at
/// the stop, every output flushed, exit status 129, and it resumes bit for bit.
#[test]
fn sighup_checkpoints_and_exits_129_then_resumes() {
    interrupt_and_resume("HUP", 129);
}

#[test]
fn sigint_checkpoints_and_exits_130() {
    interrupt_and_resume("INT", 130);
}

#[test]
fn bad_input_exits_with_status_2() {
    let dir = tmp("bad");
    let d = dir.path();
    let p = d.join("bad.toml");
    std::fs::write(
        &p,
        scenario(10).replace("restitution = 0.3", "restitutoin = 0.3"),
    )
    .unwrap();
    for sub in ["run", "check"] {
        let o = clump().arg(sub).arg(&p).arg("-o").arg(d.join("o")).output();
        let o = match sub {
            "check" => clump().arg(sub).arg(&p).output().unwrap(),
            _ => o.unwrap(),
        };
        assert_eq!(o.status.code(), Some(2), "{sub}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("unknown key 'restitutoin' in [contact]") && err.contains("bad.toml:23:"),
            "{err}"
        );
        assert!(err.contains("did you mean 'restitution'?"), "{err}");
    }
    // a missing scenario, a missing and a corrupt checkpoint
    let o = clump()
        .args(["run", "/nonexistent/x.toml"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let o = clump()
        .args(["resume", "/nonexistent/c.ckpt"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let junk = d.join("junk.ckpt");
    std::fs::write(
        &junk,
        b"not a checkpoint at all, but long enough to have a header",
    )
    .unwrap();
    let o = clump().arg("resume").arg(&junk).output().unwrap();
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // unknown command-line option
    let o = clump().args(["run", "--bogus"]).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
}

/// Without a terminal, `clump run` prints plain progress lines (simulated
/// time, steps/s, bodies, contacts, ETA) instead of a bar, and a summary.
#[test]
fn plain_progress_lines_without_a_tty() {
    let dir = tmp("progress");
    let d = dir.path();
    let sc = write_scenario(d, 100);
    let err = run_ok(clump().arg("run").arg(&sc).arg("-o").arg(d.join("o")));
    let line = err
        .lines()
        .find(|l| l.starts_with("progress 100.0%"))
        .unwrap_or_else(|| panic!("no final progress line in:\n{err}"));
    for want in ["t = ", "steps/s", "bodies", "contacts", "ETA"] {
        assert!(line.contains(want), "{want:?} missing from {line:?}");
    }
    assert!(!err.contains('\r'), "no bar redraws without a terminal");
}

/// `clump check` prints the derived quantities; the Rayleigh time is checked
/// against the closed form t_R = πR√(ρ/G)/(0.1631ν + 0.8766) for the smallest
/// sphere (the rod's, R = 1.5 mm, rock: E = 5e6, ν = 0.3, ρ = 2500).
#[test]
fn check_prints_derived_quantities() {
    let dir = tmp("check");
    let d = dir.path();
    let sc = write_scenario(d, 100);
    let o = clump().arg("check").arg(&sc).output().unwrap();
    assert!(o.status.success());
    let out = String::from_utf8_lossy(&o.stdout);
    let g: f64 = 5e6 / (2.0 * 1.3);
    let t_r = std::f64::consts::PI * 0.0015 * (2500.0 / g).sqrt() / (0.1631 * 0.3 + 0.8766);
    let want_tr = format!("t_R = {t_r:.4e} s");
    let want_frac = format!("= {:.3} t_R", 4e-5 / t_r);
    eprintln!("{out}");
    for want in [
        want_tr.as_str(),
        want_frac.as_str(),
        "total: 700 steps",
        "expected in total:",
        "estimated memory:",
        "mass ",
    ] {
        assert!(out.contains(want), "{want:?} missing from:\n{out}");
    }
}
