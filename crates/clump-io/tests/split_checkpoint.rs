//! Checkpoints of a world split over ranks, written in pieces without
//! gathering the world (ranks as threads of this process,
//! `clump_core::partition::ThreadComm`; `crates/clump-cli/tests/mpi.rs`
//! checks the same under `mpirun`): the merged pieces hold one process's
//! world at that step, one process resumes from them bit for bit, and a
//! missing, truncated or foreign piece is a clear error.

use clump_core::partition::ThreadComm;
use clump_io::run::{load_checkpoint, ResumeOptions, RunOptions, Runner};
use clump_io::scenario;
use std::path::{Path, PathBuf};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("clump-split-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Rods crossing the periodic sides of a box (the MPI test's case), a
/// thermo row and a VTK frame every 1 000 steps and a checkpoint every 300: the
/// checkpoints at 300 and 600 fall where nothing else is due.
fn scenario_file(d: &Path) -> PathBuf {
    let base = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../clump-cli/tests/fixtures/periodic_straddle.toml");
    let text = std::fs::read_to_string(base).unwrap();
    let head = &text[..text.find("[output]").unwrap()];
    let p = d.join("s.toml");
    std::fs::write(
        &p,
        format!("{head}[output]\nvtk = {{ every_steps = 1000 }}\nthermo = {{ every_steps = 1000 }}\ncheckpoint = {{ every_steps = 300 }}\n"),
    )
    .unwrap();
    p
}

fn run(sc: &Path, out: &Path, steps: u64) {
    let s = scenario::load(sc).unwrap_or_else(|e| panic!("{e}"));
    let mut r = Runner::new(s, out).unwrap();
    r.run(RunOptions {
        max_steps: Some(steps),
        ..Default::default()
    })
    .unwrap();
}

/// `n` ranks as threads; rank 0 writes into `out`.
fn run_ranks(sc: &Path, out: &Path, n: usize, steps: u64) {
    let handles: Vec<_> = ThreadComm::group(n)
        .into_iter()
        .enumerate()
        .map(|(r, comm)| {
            let sc = sc.to_path_buf();
            let d = if r == 0 {
                out.to_path_buf()
            } else {
                out.with_extension(format!("rank{r}"))
            };
            std::thread::spawn(move || {
                let s = scenario::load(&sc).unwrap_or_else(|e| panic!("{e}"));
                let mut runner = Runner::new_in(s, &d, true).unwrap();
                runner.partition(Box::new(comm));
                runner
                    .run(RunOptions {
                        max_steps: Some(steps),
                        ..Default::default()
                    })
                    .unwrap_or_else(|e| panic!("rank {r}: {e}"));
            })
        })
        .collect();
    for h in handles {
        h.join().unwrap();
    }
}

/// Resumes `ck` on `n` ranks as threads to step `steps` (rank 0 writes
/// into `out`); returns the bodies each rank held right after the resume.
fn resume_ranks(ck: &Path, out: &Path, n: usize, steps: u64) -> Vec<usize> {
    let handles: Vec<_> = ThreadComm::group(n)
        .into_iter()
        .enumerate()
        .map(|(r, comm)| {
            let ck = ck.to_path_buf();
            let d = if r == 0 {
                out.to_path_buf()
            } else {
                out.with_extension(format!("rank{r}"))
            };
            std::thread::spawn(move || {
                let opts = ResumeOptions {
                    outdir_given: true,
                    ..Default::default()
                };
                let mut runner = Runner::resume_split(&ck, Some(&d), opts, Some(Box::new(comm)))
                    .unwrap_or_else(|e| panic!("rank {r}: {e}"));
                let held = runner.world().bodies().len();
                runner
                    .run(RunOptions {
                        max_steps: Some(steps),
                        ..Default::default()
                    })
                    .unwrap_or_else(|e| panic!("rank {r}: {e}"));
                held
            })
        })
        .collect();
    handles.into_iter().map(|h| h.join().unwrap()).collect()
}

/// A checkpoint's world, part by part as bytes (statistics and wall loads
/// aside: a split checkpoint holds the rank's step's, see
/// `clump_core::state_pieces::RankPiece`).
fn world_of(ckpt: &Path) -> Vec<(&'static str, String)> {
    let bytes = std::fs::read(ckpt).unwrap();
    let (_, mut w, _) = load_checkpoint(&bytes, ckpt).unwrap_or_else(|e| panic!("{e}"));
    let s = w.save_state().unwrap();
    let j = |v: serde_json::Result<String>| v.unwrap();
    vec![
        ("bodies", j(serde_json::to_string(&s.bodies))),
        ("pair histories", j(serde_json::to_string(&s.pair_history))),
        (
            "wall slots",
            j(serde_json::to_string(&(&s.wall_key, &s.wall_hist))),
        ),
        ("build poses", j(serde_json::to_string(&s.reference_pose))),
        (
            "counters",
            format!(
                "{} {} {:?} {} {} {:016x}",
                s.step,
                s.rebuilds,
                s.lost,
                s.next_id,
                s.built_step,
                s.adapted_skin.to_bits()
            ),
        ),
    ]
}

fn assert_same_world(a: &Path, b: &Path) {
    for ((what, x), (_, y)) in world_of(a).into_iter().zip(world_of(b)) {
        assert!(
            x == y,
            "{}: {what} differ from {}",
            a.display(),
            b.display()
        );
    }
}

fn load_err(ckpt: &Path) -> String {
    let bytes = std::fs::read(ckpt).unwrap();
    match load_checkpoint(&bytes, ckpt) {
        Ok(_) => panic!("{} loaded", ckpt.display()),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_checkpoint_in_pieces_holds_one_process_world_and_resumes_bit_for_bit() {
    let d = dir("resume");
    let sc = scenario_file(&d);
    let serial = d.join("serial");
    run(&sc, &serial, 1000);
    let ranks = d.join("ranks");
    run_ranks(&sc, &ranks, 3, 700);
    for step in [300, 600, 700] {
        let m = ranks.join(format!("checkpoint_{step:09}.ckpt"));
        for r in 0..3 {
            let p = ranks.join(format!("checkpoint_{step:09}.rank{r}of3.piece"));
            assert!(p.is_file(), "no piece {}", p.display());
        }
        if step < 700 {
            assert_same_world(&m, &serial.join(format!("checkpoint_{step:09}.ckpt")));
        }
    }
    // one process resumes the 3 ranks' checkpoint and ends where one
    // process's run ends, bit for bit
    let resumed = d.join("resumed");
    let ck = ranks.join("checkpoint_000000700.ckpt");
    let mut r = Runner::resume(&ck, Some(&resumed)).unwrap_or_else(|e| panic!("{e}"));
    r.run(RunOptions {
        max_steps: Some(1000),
        ..Default::default()
    })
    .unwrap();
    let fin = |p: &Path| std::fs::read(p.join("final_state.json")).unwrap();
    assert!(fin(&resumed) == fin(&serial), "final states differ");
    assert_same_world(
        &resumed.join("checkpoint_000001000.ckpt"),
        &serial.join("checkpoint_000001000.ckpt"),
    );
    // 2 and 4 ranks resume it, each reading only its share, and end where
    // one process's run ends, bit for bit
    for n in [2, 4] {
        let out = d.join(format!("resumed{n}"));
        let held = resume_ranks(&ck, &out, n, 1000);
        assert!(
            fin(&out) == fin(&serial),
            "final states differ on {n} ranks"
        );
        assert_same_world(
            &out.join("checkpoint_000001000.ckpt"),
            &serial.join("checkpoint_000001000.ckpt"),
        );
        // every rank holds a share: fewer bodies than the world's 150, and
        // together at least every body once
        assert!(held.iter().all(|&b| b < 150), "{n} ranks held {held:?}");
        assert!(held.iter().sum::<usize>() >= 150, "{n} ranks held {held:?}");
    }
    // the ranks' run, stopped at a split event, ends with the whole world
    let serial700 = d.join("serial700");
    run(&sc, &serial700, 700);
    assert!(
        fin(&ranks) == fin(&serial700),
        "the ranks' final state differs"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_missing_truncated_or_foreign_piece_is_a_clear_error() {
    let d = dir("damage");
    let sc = scenario_file(&d);
    let ranks = d.join("ranks");
    run_ranks(&sc, &ranks, 2, 600);
    let m = ranks.join("checkpoint_000000600.ckpt");
    let piece = |step: u64, r: usize| ranks.join(format!("checkpoint_{step:09}.rank{r}of2.piece"));
    let keep = std::fs::read(piece(600, 1)).unwrap();
    // missing
    std::fs::remove_file(piece(600, 1)).unwrap();
    let e = load_err(&m);
    assert!(
        e.contains("piece 1 of 2") && e.contains("cannot be read"),
        "{e}"
    );
    // truncated
    std::fs::write(piece(600, 1), &keep[..keep.len() / 2]).unwrap();
    let e = load_err(&m);
    assert!(
        e.contains("truncated or damaged") && e.contains("rank1of2"),
        "{e}"
    );
    // the piece of another checkpoint of the run
    std::fs::copy(piece(300, 1), piece(600, 1)).unwrap();
    let e = load_err(&m);
    assert!(e.contains("belongs to another checkpoint"), "{e}");
    // put back, it loads
    std::fs::write(piece(600, 1), &keep).unwrap();
    let bytes = std::fs::read(&m).unwrap();
    let (_, w, _) = load_checkpoint(&bytes, &m).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(w.step, 600);
    assert_eq!(w.bodies().len(), 150);
    let _ = std::fs::remove_dir_all(&d);
}

/// A frame's arrays in the order of the points' body ids, as bits.
fn frame_bits(path: &Path) -> Vec<(String, Vec<u64>)> {
    clump_io::post::read::arrays_by_body(path)
        .unwrap_or_else(|e| panic!("{e}"))
        .into_iter()
        .map(|(k, v)| (k, v.iter().map(|x| x.to_bits()).collect()))
        .collect()
}

/// VTK frames of 3 ranks are written in pieces (`.pvtp` and one `.vtp`
/// per rank), also where nothing else is due (the world stays split): the
/// pieces' union, ordered by body id, is one process's frame bit for bit,
/// contact counts included; the walls frame and `final_state.json` are
/// one process's bytes.
#[test]
fn frames_in_pieces_hold_one_process_s_frames() {
    frames_in_pieces("frames", "vtp");
}

/// The same for frames in `.vtu` (`vtk_format = "vtu"`: `.pvtu` and one
/// `.vtu` per rank), and a series reopened for a resumed run at an earlier
/// frame deletes the later collections and every piece they list.
#[test]
fn vtu_frames_in_pieces_hold_one_process_s_frames_and_rewind() {
    let three = frames_in_pieces("frames-vtu", "vtu");
    let pvd = std::fs::read_to_string(three.join("spheres.pvd")).unwrap();
    let time_of = |name: &str| -> f64 {
        let line = pvd.lines().find(|l| l.contains(name)).unwrap();
        let t = &line[line.find("timestep=\"").unwrap() + 10..];
        t[..t.find('"').unwrap()].parse().unwrap()
    };
    clump_io::vtk::VtkSeries::resume(&three, time_of("spheres_000274.pvtu")).unwrap();
    for (step, kept) in [(274u64, true), (411, false), (685, false)] {
        for kind in ["spheres", "bodies"] {
            let mut names = vec![format!("{kind}_{step:06}.pvtu")];
            names.extend((0..3).map(|r| format!("{kind}_{step:06}.rank{r}of3.vtu")));
            for n in names {
                assert_eq!(three.join(&n).exists(), kept, "{n}");
            }
        }
    }
}

/// Runs the frames scenario (a frame every 137 steps, in `ext`) on one
/// process and on 3 ranks, compares the frames, returns the 3 ranks'
/// folder.
fn frames_in_pieces(name: &str, ext: &str) -> PathBuf {
    let d = dir(name);
    let base = scenario_file(&d);
    let text = std::fs::read_to_string(&base).unwrap();
    let sc = d.join("frames.toml");
    std::fs::write(
        &sc,
        text.replace(
            "vtk = { every_steps = 1000 }",
            &format!("vtk = {{ every_steps = 137 }}\nvtk_format = \"{ext}\""),
        ),
    )
    .unwrap();
    let (one, three) = (d.join("one"), d.join("three"));
    run(&sc, &one, 700);
    run_ranks(&sc, &three, 3, 700);
    let read = |p: PathBuf| std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
    assert!(read(one.join("final_state.json")) == read(three.join("final_state.json")));
    for step in [0u64, 137, 274, 411, 548, 685] {
        for kind in ["spheres", "bodies"] {
            let plain = one.join(format!("{kind}_{step:06}.{ext}"));
            let pieces = three.join(format!("{kind}_{step:06}.p{ext}"));
            assert!(!three.join(format!("{kind}_{step:06}.{ext}")).exists());
            let (a, b) = (frame_bits(&plain), frame_bits(&pieces));
            assert_eq!(a.len(), b.len(), "{kind} {step}: the arrays differ");
            for (x, y) in a.iter().zip(&b) {
                assert!(x == y, "{kind} {step}: array {} differs", x.0);
            }
        }
        let walls = format!("walls_{step:06}.{ext}");
        assert!(
            read(one.join(&walls)) == read(three.join(&walls)),
            "{walls}"
        );
    }
    let pvd = std::fs::read_to_string(three.join("bodies.pvd")).unwrap();
    assert_eq!(pvd.matches(&format!(".p{ext}\"")).count(), 6, "{pvd}");
    three
}
