//! The fault suite of the `clump` program: closed and full stdout/stderr,
//! output folders shared or reused, resume into a foreign folder, a full
//! disk. Each case states the expected exit status and message.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn clump() -> Command {
    Command::new(env!("CARGO_BIN_EXE_clump"))
}

/// A fresh directory for one test, removed when the test ends.
fn tmp(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("clump-faults-{name}-"))
        .tempdir()
        .unwrap()
}

/// The shared small scenario (see `common`) with VTK, thermo and
/// trajectory output every `every` steps, written as `dir/fall.toml`.
fn scenario(dir: &Path, steps: u64, every: u64) -> PathBuf {
    let p = dir.join("fall.toml");
    let output = format!(
        "vtk = {{ every_steps = {every} }}\nthermo = {{ every_steps = {every} }}\ntrajectory = {{ bodies = [1, 2], every_steps = {every} }}\n"
    );
    std::fs::write(&p, common::fall(steps, &output)).unwrap();
    p
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn no_panic(o: &Output) {
    let err = text(&o.stderr);
    assert!(
        !err.contains("panicked") && o.status.code() != Some(101),
        "panic: {:?}\n{err}",
        o.status
    );
}

/// A pipe whose reading end is already closed: writes to it fail with EPIPE.
fn closed_pipe() -> Stdio {
    let mut fds = [0; 2];
    // SAFETY: pipe fills two descriptors, which we then own.
    assert_eq!(unsafe { libc::pipe(fds.as_mut_ptr()) }, 0);
    // SAFETY: fds[0] is ours and used nowhere else.
    unsafe { libc::close(fds[0]) };
    use std::os::unix::io::FromRawFd;
    // SAFETY: fds[1] is an open descriptor owned by nothing else.
    unsafe { Stdio::from_raw_fd(fds[1]) }
}

fn dev_full() -> Stdio {
    std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap()
        .into()
}

/// `clump check X | head -1` after head exited: quiet, status 141.
#[test]
fn check_into_a_closed_pipe_exits_141_quietly() {
    let dir = tmp("check-epipe");
    let d = dir.path();
    let sc = scenario(d, 100, 10);
    let o = clump()
        .arg("check")
        .arg(&sc)
        .stdout(closed_pipe())
        .output()
        .unwrap();
    no_panic(&o);
    assert_eq!(o.status.code(), Some(141), "{}", text(&o.stderr));
    assert_eq!(
        text(&o.stderr),
        "",
        "a closed pipe is not an error to report"
    );
}

/// `clump check X > /dev/full`: status 1 and a message naming stdout.
#[test]
fn check_into_a_full_device_exits_1_naming_stdout() {
    let dir = tmp("check-full");
    let d = dir.path();
    let sc = scenario(d, 100, 10);
    let o = clump()
        .arg("check")
        .arg(&sc)
        .stdout(dev_full())
        .output()
        .unwrap();
    no_panic(&o);
    assert_eq!(o.status.code(), Some(1));
    let err = text(&o.stderr);
    assert!(
        err.contains("error: cannot write to stdout: No space left on device"),
        "{err}"
    );
}

fn complete(dir: &Path, rows: usize) {
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("manifest.json")).unwrap()).unwrap();
    assert_eq!(m["status"], "completed");
    let thermo = std::fs::read_to_string(dir.join("thermo.csv")).unwrap();
    assert_eq!(thermo.lines().count(), rows + 1, "{thermo}");
}

/// A run whose stderr (log, progress) is full or closed still runs to the
/// end: `clump run X 2>/dev/full` exits 0; `clump run X 2>&1 | head` after
/// head exited writes every output and ends with 141 (the summary on stdout
/// could not be shown).
#[test]
fn run_survives_a_full_or_closed_stderr() {
    let dir = tmp("run-stderr");
    let d = dir.path();
    let sc = scenario(d, 200, 20);
    let o = clump()
        .arg("run")
        .arg(&sc)
        .arg("-o")
        .arg(d.join("full"))
        .stderr(dev_full())
        .stdout(Stdio::null())
        .output()
        .unwrap();
    no_panic(&o);
    assert_eq!(o.status.code(), Some(0));
    complete(&d.join("full"), 11);

    let pipe = closed_pipe();
    let o = clump()
        .arg("run")
        .arg(&sc)
        .arg("-o")
        .arg(d.join("pipe"))
        .env("RUST_LOG", "debug")
        .stderr(closed_pipe())
        .stdout(pipe)
        .output()
        .unwrap();
    no_panic(&o);
    assert_eq!(o.status.code(), Some(141));
    complete(&d.join("pipe"), 11);
}

fn run(args: &[&std::ffi::OsStr]) -> Output {
    let o = clump().args(args).output().unwrap();
    no_panic(&o);
    o
}

/// A second run into a folder of an earlier run is refused (status 2)
/// unless `--overwrite`, which deletes the earlier run's files (a longer
/// earlier run's later frames do not survive) and nothing else.
#[test]
fn rerun_into_a_used_folder_needs_overwrite() {
    let dir = tmp("rerun");
    let d = dir.path();
    let out = d.join("out");
    let long = scenario(d, 200, 20);
    let o = run(&[
        "run".as_ref(),
        long.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    assert!(out.join("spheres_000200.vtp").exists());
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let short = scenario(d, 100, 20);
    let o = run(&[
        "run".as_ref(),
        short.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = text(&o.stderr);
    assert!(
        err.contains("already holds the files of another run") && err.contains("pass --overwrite"),
        "{err}"
    );
    let o = run(&[
        "run".as_ref(),
        short.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "--overwrite".as_ref(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    assert!(out.join("spheres_000100.vtp").exists());
    assert!(
        !out.join("spheres_000200.vtp").exists(),
        "the earlier run's later frame survived --overwrite"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "mine"
    );
    complete(&out, 6);
}

/// While a run writes into a folder, a second run into it is refused
/// (status 2, the folder lock), and so is a resume.
#[test]
fn two_runs_cannot_share_a_folder() {
    let dir = tmp("lock");
    let d = dir.path();
    let out = d.join("out");
    let sc = scenario(d, 2_000_000, 1000);
    let mut first = clump()
        .arg("run")
        .arg(&sc)
        .arg("-o")
        .arg(&out)
        .args(["--threads", "1"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while !out.join("thermo.csv").exists() && t0.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(50));
    }
    for extra in [&[][..], &["--overwrite".as_ref()][..]] {
        let mut args: Vec<&std::ffi::OsStr> = vec![
            "run".as_ref(),
            sc.as_os_str(),
            "-o".as_ref(),
            out.as_os_str(),
        ];
        args.extend_from_slice(extra);
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2));
        let err = text(&o.stderr);
        assert!(err.contains("is in use by another clump run"), "{err}");
    }
    let _ = first.kill();
    let _ = first.wait();
    // the lock ends with its process (even after kill -9)
    let o = run(&[
        "run".as_ref(),
        sc.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "--overwrite".as_ref(),
        "--steps".as_ref(),
        "10".as_ref(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
}

/// `resume A/checkpoint -o B` where B holds another run is refused (B's
/// thermo.csv is untouched); `resume --steps N` at or below the checkpoint
/// step is refused; the checkpoint's own folder resumes.
#[test]
fn resume_continues_only_in_its_own_folder() {
    let dir = tmp("resume");
    let d = dir.path();
    let sc = scenario(d, 200, 20);
    let (a, b) = (d.join("a"), d.join("b"));
    for (dir, steps) in [(&a, "100"), (&b, "200")] {
        let o = run(&[
            "run".as_ref(),
            sc.as_os_str(),
            "-o".as_ref(),
            dir.as_os_str(),
            "--steps".as_ref(),
            steps.as_ref(),
        ]);
        assert!(o.status.success(), "{}", text(&o.stderr));
    }
    let ck = a.join("checkpoint_000000100.ckpt");
    let b_thermo = std::fs::read(b.join("thermo.csv")).unwrap();
    let o = run(&[
        "resume".as_ref(),
        ck.as_os_str(),
        "-o".as_ref(),
        b.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = text(&o.stderr);
    assert!(err.contains("holds the files of another run"), "{err}");
    assert_eq!(std::fs::read(b.join("thermo.csv")).unwrap(), b_thermo);

    let o = run(&[
        "resume".as_ref(),
        ck.as_os_str(),
        "--steps".as_ref(),
        "50".as_ref(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = text(&o.stderr);
    assert!(
        err.contains("--steps 50 is not after the checkpoint's step 100"),
        "{err}"
    );
    // a fresh folder is fine, and so is the checkpoint's own
    let c = d.join("c");
    let o = run(&[
        "resume".as_ref(),
        ck.as_os_str(),
        "-o".as_ref(),
        c.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let o = run(&["resume".as_ref(), ck.as_os_str()]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    complete(&a, 11);
}

/// `--threads` above the number of cores is capped, with a warning.
#[test]
fn threads_above_the_cores_are_capped() {
    let dir = tmp("threads");
    let d = dir.path();
    let sc = scenario(d, 20, 10);
    let o = run(&[
        "run".as_ref(),
        sc.as_os_str(),
        "-o".as_ref(),
        d.join("o").as_os_str(),
        "--threads".as_ref(),
        "100000".as_ref(),
    ]);
    assert_eq!(o.status.code(), Some(0));
    let err = text(&o.stderr);
    let cores = std::thread::available_parallelism().unwrap().get();
    assert!(
        err.contains(&format!(
            "warning: --threads 100000 is more than the {cores} cores of this machine; using {cores}"
        )),
        "{err}"
    );
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("o/manifest.json")).unwrap()).unwrap();
    assert_eq!(m["threads"].as_u64(), Some(cores as u64));
}

/// A full disk (a 256 kB tmpfs; needs root, else the test prints a note
/// and passes) stops the run with status 1 and a message naming the file;
/// thermo.csv and traj_*.csv end with a whole row; no temporary file is
/// left; the run writes a checkpoint if there is room (one that resumes)
/// and says so, or says that there was none.
#[test]
fn full_disk_stops_the_run_naming_the_file() {
    let dir = tmp("enospc");
    let d = dir.path();
    let mnt = d.join("mnt");
    std::fs::create_dir_all(&mnt).unwrap();
    let mounted = Command::new("mount")
        .args(["-t", "tmpfs", "-o", "size=256k", "tmpfs"])
        .arg(&mnt)
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !mounted {
        eprintln!("note: cannot mount a tmpfs (not root?); full-disk test skipped");
        return;
    }
    let sc = scenario(d, 100_000, 10);
    let o = run(&[
        "run".as_ref(),
        sc.as_os_str(),
        "-o".as_ref(),
        mnt.as_os_str(),
    ]);
    let files: Vec<(PathBuf, String)> = std::fs::read_dir(&mnt)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "csv"))
        .map(|p| {
            let t = std::fs::read_to_string(&p).unwrap();
            (p, t)
        })
        .collect();
    // what the run says about a checkpoint, and every file it left there
    let left: Vec<PathBuf> = std::fs::read_dir(&mnt)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    let saved = d.join("saved");
    std::fs::create_dir_all(&saved).unwrap();
    for p in &left {
        if p.is_file() {
            std::fs::copy(p, saved.join(p.file_name().unwrap())).unwrap();
        }
    }
    let _ = Command::new("umount").arg(&mnt).status();
    assert_eq!(o.status.code(), Some(1), "{}", text(&o.stderr));
    let err = text(&o.stderr);
    let temporaries: Vec<_> = left
        .iter()
        .filter(|p| p.file_name().unwrap().to_string_lossy().contains(".tmp"))
        .collect();
    assert!(
        temporaries.is_empty(),
        "temporary files left: {temporaries:?}"
    );
    eprintln!("full disk: {err}");
    if err.contains("there was no room for a checkpoint") {
        assert!(!left
            .iter()
            .any(|p| p.extension().is_some_and(|e| e == "ckpt")));
    } else {
        // the checkpoint named is whole: it resumes on a disk with room
        assert!(err.contains("a checkpoint of step"), "{err}");
        let ck = left
            .iter()
            .find(|p| p.extension().is_some_and(|e| e == "ckpt"))
            .expect("the checkpoint named");
        let step: u64 = ck.file_stem().unwrap().to_string_lossy()["checkpoint_".len()..]
            .parse()
            .unwrap();
        let r = run(&[
            "resume".as_ref(),
            saved.join(ck.file_name().unwrap()).as_os_str(),
            "--steps".as_ref(),
            (step + 20).to_string().as_ref(),
        ]);
        assert!(r.status.success(), "{}", text(&r.stderr));
    }
    let err = text(&o.stderr);
    assert!(
        err.contains("No space left on device") && err.contains(&mnt.display().to_string()),
        "{err}"
    );
    assert!(files.len() >= 3);
    for (p, t) in files {
        assert!(t.ends_with('\n'), "{} ends mid-row", p.display());
        let cols = t.lines().next().unwrap().split(',').count();
        for l in t.lines() {
            assert_eq!(l.split(',').count(), cols, "{}: {l}", p.display());
        }
    }
}

/// The run summary says what became of the bodies asked for: a pack places
/// all it asked for; a stream into a region too small for its rate warns
/// with the counts.
#[test]
fn run_summary_counts_asked_and_placed_bodies() {
    let dir = tmp("counts");
    let d = dir.path();
    let sc = scenario(d, 100, 50);
    let o = run(&[
        "run".as_ref(),
        sc.as_os_str(),
        "-o".as_ref(),
        d.join("pack").as_os_str(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let out = text(&o.stdout);
    assert!(
        out.contains("insert #1 (pack): asked 20, placed 20\n"),
        "{out}"
    );

    let stream = std::fs::read_to_string(&sc).unwrap().replace(
        "kind = \"pack\"\ntemplate = \"tetra\"\ncount = 20\nregion = { type = \"box\", lo = [-0.02, -0.02, 0.005], hi = [0.02, 0.02, 0.05] }",
        "kind = \"stream\"\ntemplate = \"tetra\"\nbodies_per_second = 200000\nvelocity = [0.0, 0.0, 0.0]\nregion = { type = \"box\", lo = [-0.005, -0.005, 0.05], hi = [0.005, 0.005, 0.06] }",
    );
    assert!(stream.contains("stream"));
    let sc2 = d.join("stream.toml");
    std::fs::write(&sc2, stream).unwrap();
    let o = run(&[
        "run".as_ref(),
        sc2.as_os_str(),
        "-o".as_ref(),
        d.join("stream").as_os_str(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    // insertion runs before each of the 100 steps, the last at t = 99 dt:
    // floor(200 000/s × 99 × 2e-5 s) = 396 due
    let out = text(&o.stdout);
    let line = out
        .lines()
        .find(|l| l.starts_with("insert #1 (stream): asked 396, placed "))
        .unwrap_or_else(|| panic!("{out}"));
    let placed: u64 = line
        .split("placed ")
        .nth(1)
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(placed < 396, "{line}");
    let err = text(&o.stderr);
    assert!(
        err.contains(&format!(
            "warning: insert #1 (stream) placed {placed} of the 396 bodies asked for; {} found no room",
            396 - placed
        )),
        "{err}"
    );
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("stream/manifest.json")).unwrap())
            .unwrap();
    assert_eq!(m["insertions"][0]["waiting"].as_u64(), Some(396 - placed));
}

/// A pack that places more spheres than memory can hold is refused by
/// `check` and `run` before anything is allocated, saying how much it
/// needs; a stream that could bring that many is warned about.
#[test]
fn bodies_beyond_memory_are_refused_before_allocating() {
    let dir = tmp("memory");
    let d = dir.path();
    let sc = scenario(d, 100, 50);
    let text = std::fs::read_to_string(&sc).unwrap();
    let text = text
        .replace("lo = [-0.03, -0.03, -0.01]", "lo = [-50.0, -50.0, -0.01]")
        .replace("hi = [0.03, 0.03, 0.1]", "hi = [50.0, 50.0, 100.0]")
        .replace(
            "count = 20\nregion = { type = \"box\", lo = [-0.02, -0.02, 0.005], hi = [0.02, 0.02, 0.05] }",
            "count = 2000000000000\nregion = { type = \"box\", lo = [-49.0, -49.0, 1.0], hi = [49.0, 49.0, 99.0] }",
        );
    assert!(text.contains("count = 2000000000000"), "{text}");
    let big = d.join("big.toml");
    std::fs::write(&big, text).unwrap();
    let out = d.join("o");
    for args in [
        vec!["check".as_ref(), big.as_os_str()],
        vec![
            "run".as_ref(),
            big.as_os_str(),
            "-o".as_ref(),
            out.as_os_str(),
        ],
    ] {
        let cmd = args[0].to_string_lossy().into_owned();
        let o = run(&args);
        let err = text_of(&o);
        no_panic(&o);
        assert_eq!(o.status.code(), Some(2), "{cmd}: {err}");
        assert!(
            err.contains("GB of memory is available") && err.contains("big.toml"),
            "{cmd}: {err}"
        );
    }
}

fn text_of(o: &Output) -> String {
    text(&o.stderr)
}

/// Every file of `dir` with its bytes, sorted by name.
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file() && !p.ends_with(".clump.lock"))
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read(&p).unwrap())
        })
        .collect();
    v.sort();
    v
}

/// A completed run with a checkpoint every 100 of its 400 steps.
fn completed_run(d: &Path) -> (PathBuf, PathBuf) {
    let sc = d.join("fall.toml");
    let output = "vtk = { every_steps = 100 }\nthermo = { every_steps = 20 }\ncheckpoint = { every_steps = 100 }\n";
    std::fs::write(&sc, common::fall(400, output)).unwrap();
    let out = d.join("out");
    let o = run(&[
        "run".as_ref(),
        sc.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    (sc, out)
}

/// What the user sees: `clump resume CKPT --steps N` with N not after the
/// checkpoint exits 2 and says no file was touched; and none was (the
/// completed run's thermo.csv, manifest and final state keep their bytes).
#[test]
fn refused_resume_touches_no_file() {
    let dir = tmp("resume-steps");
    let (_, out) = completed_run(dir.path());
    let before = snapshot(&out);
    let ck = out.join("checkpoint_000000200.ckpt");
    let o = run(&[
        "resume".as_ref(),
        ck.as_os_str(),
        "--steps".as_ref(),
        "100".as_ref(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = text(&o.stderr);
    assert!(
        err.contains("--steps 100 is not after the checkpoint's step 200"),
        "{err}"
    );
    assert!(err.contains("no file was touched"), "{err}");
    assert!(
        snapshot(&out) == before,
        "a refused resume changed the run folder"
    );
}

/// What the user sees: resuming a completed run from an earlier checkpoint
/// is refused (exit 2) naming the step the run reached and `--rewind`, and
/// changes nothing; with `--rewind` it runs, and no frame of the rewound
/// run is left on disk unlisted by its `.pvd` (the resumed run here stops
/// at step 300, so the frame of step 400 must go).
#[test]
fn rewinding_resume_needs_rewind_and_leaves_no_orphans() {
    let dir = tmp("resume-rewind");
    let (_, out) = completed_run(dir.path());
    let before = snapshot(&out);
    let ck = out.join("checkpoint_000000200.ckpt");
    let o = run(&["resume".as_ref(), ck.as_os_str()]);
    assert_eq!(o.status.code(), Some(2));
    let err = text(&o.stderr);
    assert!(
        err.contains("went on to step 400, past the checkpoint's step 200"),
        "{err}"
    );
    assert!(err.contains("--rewind"), "{err}");
    assert!(
        snapshot(&out) == before,
        "a refused resume changed the run folder"
    );
    // into a new folder it is no rewind
    let fresh = dir.path().join("fresh");
    let o = run(&[
        "resume".as_ref(),
        ck.as_os_str(),
        "-o".as_ref(),
        fresh.as_os_str(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    assert!(
        snapshot(&out) == before,
        "a resume into another folder changed the run folder"
    );
    let o = run(&[
        "resume".as_ref(),
        ck.as_os_str(),
        "--rewind".as_ref(),
        "--steps".as_ref(),
        "300".as_ref(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    for series in ["spheres", "bodies", "walls"] {
        let pvd = std::fs::read_to_string(out.join(format!("{series}.pvd"))).unwrap();
        for e in std::fs::read_dir(&out).unwrap() {
            let name = e.unwrap().file_name().to_string_lossy().into_owned();
            if name.starts_with(&format!("{series}_")) && name.ends_with(".vtp") {
                assert!(
                    pvd.contains(&name),
                    "{name} is on disk but not in {series}.pvd"
                );
            }
        }
        assert!(!out.join(format!("{series}_000400.vtp")).exists());
    }
}

/// What the user sees: a checkpoint saved outside any run folder (as
/// Python's `save_checkpoint("x.ckpt")` in the current folder) is not
/// resumed into that folder without `-o`: exit 2, a message naming `-o`,
/// and no file is added there.
#[test]
fn resume_outside_a_run_folder_needs_o() {
    let dir = tmp("resume-loose");
    let (_, out) = completed_run(dir.path());
    let loose = dir.path().join("loose");
    std::fs::create_dir(&loose).unwrap();
    let ck = loose.join("mine.ckpt");
    std::fs::copy(out.join("checkpoint_000000200.ckpt"), &ck).unwrap();
    let o = run(&["resume".as_ref(), ck.as_os_str()]);
    assert_eq!(o.status.code(), Some(2));
    let err = text(&o.stderr);
    assert!(err.contains("is not in a run folder"), "{err}");
    assert!(err.contains("-o DIR"), "{err}");
    let names: Vec<String> = snapshot(&loose).into_iter().map(|(n, _)| n).collect();
    assert_eq!(names, vec!["mine.ckpt".to_string()]);
}
