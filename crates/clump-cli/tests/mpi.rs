//! `mpirun -np N clump run`: the world split over N ranks gives one
//! process's files bit for bit (bodies, spheres, walls, contacts, thermo,
//! the final state, the checkpoint's world), at 2 and 4 ranks, on the
//! examples in short versions (stones: stream insertion onto a floor;
//! drum: a rotating mesh wall), a periodic box with clumps crossing its
//! sides (also with heat and convection, at 2 and 3 ranks), a restart at
//! 3 ranks from a checkpoint written in pieces at 2, and SIGTERM on 2 ranks
//! (one checkpoint of the whole world, which resumes bit for bit); a rank
//! killed mid-run (the run stops; its last checkpoint resumes); 2 ranks of
//! 2 threads each.
//! Spheres and bodies frames are written in pieces on ranks (`.pvtp`, and
//! `.pvtu` for `vtk_format = "vtu"`): the union of the pieces, ordered by
//! body id, is one process's frame.
//! Built only with the `mpi` feature (scripts/test-all.sh runs it).
#![cfg(feature = "mpi")]

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn out_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("clump-mpi-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// `clump ARGS` on `np` ranks (`np = 0`: without mpirun), one thread each.
fn clump(np: usize, args: &[&str]) {
    clump_threads(np, 1, args);
}

/// [`clump`] with `threads` threads per rank.
fn clump_threads(np: usize, threads: usize, args: &[&str]) {
    let bin = env!("CARGO_BIN_EXE_clump");
    let mut c = if np == 0 {
        Command::new(bin)
    } else {
        let mut c = Command::new("mpirun");
        c.args([
            "--oversubscribe",
            "--allow-run-as-root",
            "-np",
            &np.to_string(),
            bin,
        ]);
        c
    };
    // shared memory without cross-memory attach (containers may forbid it)
    c.env("OMPI_MCA_btl_vader_single_copy_mechanism", "none");
    c.args(args)
        .args(["--threads", &threads.to_string()])
        .current_dir(repo());
    let out = c
        .output()
        .expect("mpirun (Debian: openmpi-bin) must be installed for the MPI tests");
    assert!(
        out.status.success(),
        "clump {args:?} on {np} ranks failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The world state of a checkpoint, part by part, as bytes (the checkpoint
/// file also holds the run's id and paths, which differ between runs).
fn world_of(checkpoint: &Path) -> Vec<(&'static str, Vec<u8>)> {
    let bytes = std::fs::read(checkpoint).unwrap();
    let (_, mut world, _) = clump_io::run::load_checkpoint(&bytes, checkpoint).unwrap();
    let s = world.save_state().unwrap();
    let j = |v: serde_json::Result<Vec<u8>>| v.unwrap();
    vec![
        ("bodies", j(serde_json::to_vec(&s.bodies))),
        ("pair histories", j(serde_json::to_vec(&s.pair_history))),
        (
            "wall slots",
            j(serde_json::to_vec(&(&s.wall_key, &s.wall_hist))),
        ),
        ("wall loads", j(serde_json::to_vec(&s.wall_loads))),
        ("walls' heat", j(serde_json::to_vec(&s.wall_heat))),
        ("build poses", j(serde_json::to_vec(&s.reference_pose))),
        ("statistics", j(serde_json::to_vec(&s.stats))),
        (
            "counters",
            j(serde_json::to_vec(&(
                s.step,
                s.rebuilds,
                s.lost,
                s.next_id,
                s.built_step,
            ))),
        ),
        ("skin", s.adapted_skin.to_bits().to_le_bytes().to_vec()),
    ]
}

/// True when `checkpoint` is the manifest of a checkpoint in pieces (one
/// per rank, written at an event with nothing else due).
fn in_pieces(checkpoint: &Path) -> bool {
    let first = format!(
        "{}.rank0of",
        checkpoint.file_stem().unwrap().to_string_lossy()
    );
    std::fs::read_dir(checkpoint.parent().unwrap())
        .unwrap()
        .flatten()
        .any(|e| e.file_name().to_string_lossy().starts_with(&first))
}

/// The parts of two checkpoints' worlds that differ. A checkpoint in
/// pieces holds the statistics and wall loads of a rank's step (summed
/// per rank, then over the ranks), not one process's: those two are not
/// compared there (`clump_core::state_pieces`).
fn differing(a: &Path, b: &Path) -> Vec<&'static str> {
    let pieces = in_pieces(a) || in_pieces(b);
    world_of(a)
        .into_iter()
        .zip(world_of(b))
        .filter(|(x, y)| x.1 != y.1)
        .map(|(x, _)| x.0)
        .filter(|&what| !(pieces && (what == "statistics" || what == "wall loads")))
        .collect()
}

/// A frame's arrays with every point in the order of its `body_id`
/// (`clump_io::post::read::arrays_by_body`: a `.pvtp` or `.pvtu` reads as
/// its pieces), as bits.
fn frame_by_body(path: &Path) -> Vec<(String, Vec<u64>)> {
    clump_io::post::read::arrays_by_body(path)
        .unwrap()
        .into_iter()
        .map(|(k, v)| (k, v.iter().map(|x| x.to_bits()).collect()))
        .collect()
}

/// The frame `s` of one process's run `a` and of the run on ranks `b`:
/// `b` holds it in pieces (`.pvtp`, `.pvtu` for a `.vtu` frame); the union
/// of the pieces, ordered by body id, is one process's frame value for
/// value, bit for bit.
fn assert_same_frame(a: &Path, b: &Path, s: &str, what: &str) {
    let pvtp = b.join(s.replace(".vtp", ".pvtp").replace(".vtu", ".pvtu"));
    assert!(pvtp.exists(), "{what}: {s} is not written in pieces");
    let (x, y) = (frame_by_body(&a.join(s)), frame_by_body(&pvtp));
    assert_eq!(
        x.iter().map(|e| &e.0).collect::<Vec<_>>(),
        y.iter().map(|e| &e.0).collect::<Vec<_>>(),
        "{what}: {s}: the arrays differ"
    );
    for ((name, u), (_, v)) in x.iter().zip(&y) {
        assert!(
            u == v,
            "{what}: {s}: array {name} differs from one process's"
        );
    }
}

/// The contact frame `s` of one process's run `a` and of the run on ranks
/// `b` (in pieces, `.pvtp`): the same contacts, each once, with the same
/// values bit for bit (every cell array and both line ends of each
/// contact, compared as sets of rows: the pieces hold the contacts in the
/// ranks' order).
fn assert_same_contacts(a: &Path, b: &Path, s: &str, what: &str) {
    let pvtp = b.join(s.replace(".vtp", ".pvtp"));
    assert!(pvtp.exists(), "{what}: {s} is not written in pieces");
    let rows = |p: &Path| {
        let a = clump_io::post::read::read_vtp(p).unwrap();
        let n = a["cell:body_i"].len();
        let mut names: Vec<&String> = a.keys().collect();
        names.sort();
        let mut rows: Vec<Vec<u64>> = (0..n)
            .map(|i| {
                names
                    .iter()
                    .flat_map(|k| {
                        let v = &a[*k];
                        let c = v.len() / n.max(1);
                        v[c * i..c * (i + 1)].iter().map(|x| x.to_bits())
                    })
                    .collect()
            })
            .collect();
        rows.sort();
        (names.into_iter().cloned().collect::<Vec<_>>(), rows)
    };
    let (x, y) = (rows(&a.join(s)), rows(&pvtp));
    assert_eq!(x.0, y.0, "{what}: {s}: the arrays differ");
    assert!(
        x.1 == y.1,
        "{what}: {s}: {} contacts in pieces, one process has {}, or their values differ",
        y.1.len(),
        x.1.len()
    );
}

/// Every file of `a` (one process's run) but the manifest (wall times,
/// paths) equals `b`'s; checkpoints compare by their world, spheres and
/// bodies frames by their values ([`assert_same_frame`]; `b`'s `.pvd`
/// lists the `.pvtp` (`.pvtu`) where `a`'s lists the `.vtp` (`.vtu`)).
fn assert_same_outputs(a: &Path, b: &Path, what: &str) {
    let mut names: Vec<_> = std::fs::read_dir(a)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    names.sort();
    let mut checked = 0;
    for n in names {
        let s = n.to_string_lossy();
        if s == "manifest.json" || s.starts_with('.') {
            continue;
        }
        let (fa, fb) = (a.join(&n), b.join(&n));
        let piece = (s.starts_with("spheres_") || s.starts_with("bodies_"))
            && (s.ends_with(".vtp") || s.ends_with(".vtu"));
        if piece {
            assert_same_frame(a, b, &s, what);
            checked += 1;
            continue;
        }
        if s.starts_with("contacts_") && s.ends_with(".vtp") {
            assert_same_contacts(a, b, &s, what);
            checked += 1;
            continue;
        }
        assert!(fb.exists(), "{what}: {s} is missing");
        if s == "spheres.pvd" || s == "bodies.pvd" || s == "contacts.pvd" {
            let text = std::fs::read_to_string(&fb).unwrap();
            assert!(
                std::fs::read_to_string(&fa).unwrap()
                    == text
                        .replace(".pvtp\"", ".vtp\"")
                        .replace(".pvtu\"", ".vtu\""),
                "{what}: {s} does not list one process's frames"
            );
        } else if s.ends_with(".ckpt") {
            let d = differing(&fa, &fb);
            assert!(
                d.is_empty(),
                "{what}: the checkpoint's world differs in {d:?}"
            );
        } else {
            assert!(
                std::fs::read(&fa).unwrap() == std::fs::read(&fb).unwrap(),
                "{what}: {s} differs from one process's"
            );
        }
        checked += 1;
    }
    assert!(checked > 5, "{what}: only {checked} files compared");
}

fn same_bits_at_2_and_4_ranks(name: &str, scenario: &str, steps: &str) {
    same_bits_at(name, scenario, steps, &[2, 4]);
}

/// `scenario` run `steps` steps on each of `ranks` ranks gives one
/// process's outputs.
fn same_bits_at(name: &str, scenario: &str, steps: &str, ranks: &[usize]) {
    let serial = out_dir(&format!("{name}-1"));
    clump(
        0,
        &[
            "run",
            scenario,
            "-o",
            serial.to_str().unwrap(),
            "--steps",
            steps,
        ],
    );
    for &np in ranks {
        let d = out_dir(&format!("{name}-{np}"));
        clump(
            np,
            &["run", scenario, "-o", d.to_str().unwrap(), "--steps", steps],
        );
        assert_same_outputs(&serial, &d, &format!("{name} on {np} ranks"));
        let _ = std::fs::remove_dir_all(&d);
    }
    let _ = std::fs::remove_dir_all(&serial);
}

#[test]
fn stream_insertion_onto_a_floor_has_the_same_bits() {
    same_bits_at_2_and_4_ranks("stones", "examples/stones.toml", "3000");
}

#[test]
fn a_rotating_drum_has_the_same_bits() {
    same_bits_at_2_and_4_ranks("drum", "examples/drum.toml", "1500");
}

#[test]
fn clumps_crossing_periodic_sides_have_the_same_bits() {
    same_bits_at_2_and_4_ranks(
        "periodic",
        "crates/clump-cli/tests/fixtures/periodic_straddle.toml",
        "1000",
    );
}

/// Frames where nothing else is due are written in pieces from the world
/// split over the ranks (no gather of the world before or after them):
/// the pieces' union is one process's frame, contact counts included.
#[test]
fn frames_of_a_split_world_are_one_process_s() {
    let scenario = "crates/clump-cli/tests/fixtures/periodic_frames.toml";
    same_bits_at("frames", scenario, "1000", &[3]);
    // the frames did not gather the world: one gather at the first split
    // of the world is all a run needs without events that gather it
    let (d, gathers) = two_rank_gathers("frames-gathers", scenario);
    let frames = files_ending(&d, ".pvtp") / 2;
    assert!(frames > 10, "only {frames} frames");
    assert!(
        gathers < frames / 2,
        "{gathers} whole-world gathers for {frames} frames written in pieces"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// `scenario` (a file without relative paths) with `vtk_format = "vtu"`
/// appended to its last table, `[output]`, in a temporary file.
fn with_vtu_frames(scenario: &str, name: &str) -> PathBuf {
    with_output(scenario, name, "vtk_format = \"vtu\"\n")
}

/// `scenario` (a file without relative paths) with `lines` appended to its
/// last table, `[output]`, in a temporary file.
fn with_output(scenario: &str, name: &str, lines: &str) -> PathBuf {
    let text = std::fs::read_to_string(repo().join(scenario)).unwrap();
    let last = text.trim_end().rsplit("\n[").next().unwrap();
    assert!(
        last.starts_with("output]"),
        "{scenario}: [output] is not last"
    );
    let p = std::env::temp_dir().join(format!("clump-mpi-{}-{name}.toml", std::process::id()));
    std::fs::write(&p, text + lines).unwrap();
    p
}

/// Contact frames are written in pieces, one per rank with the contacts
/// it counts (`.pvtp` in `contacts.pvd`), keeping the world split: the
/// pieces' union is one process's contacts, and `network_<step>.csv`
/// (edges sent to rank 0 only) is one process's bytes.
#[test]
fn contact_frames_of_a_split_world_are_one_process_s() {
    let toml = with_output(
        "crates/clump-cli/tests/fixtures/periodic_frames.toml",
        "contacts",
        "contacts = { every = 0.0041 }\n",
    );
    let scenario = toml.to_str().unwrap();
    same_bits_at("contact-frames", scenario, "1000", &[2, 3]);
    let (d, gathers) = two_rank_gathers("contacts-gathers", scenario);
    let contact_frames = std::fs::read_dir(&d)
        .unwrap()
        .filter(|e| {
            let n = e.as_ref().unwrap().file_name();
            let n = n.to_string_lossy();
            n.starts_with("contacts_") && n.ends_with(".pvtp")
        })
        .count();
    assert!(contact_frames > 10, "only {contact_frames} contact frames");
    let edges = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.to_string_lossy().contains("network_"))
        .map(|p| std::fs::read_to_string(p).unwrap().lines().count() - 1)
        .max();
    assert!(edges.is_some_and(|e| e > 0), "no frame with contacts");
    assert!(
        gathers < contact_frames / 2,
        "{gathers} whole-world gathers for {contact_frames} contact frames written in pieces"
    );
    let _ = std::fs::remove_dir_all(&d);
    let _ = std::fs::remove_file(&toml);
}

/// `.vtu` frames are written in pieces too (`.pvtu`, parallel
/// UnstructuredGrid), keeping the world split: the pieces' union is one
/// process's `.vtu` frame, and the walls frames are one process's bytes.
#[test]
fn vtu_frames_of_a_split_world_are_one_process_s() {
    let toml = with_vtu_frames(
        "crates/clump-cli/tests/fixtures/periodic_frames.toml",
        "vtu",
    );
    let scenario = toml.to_str().unwrap();
    same_bits_at("vtu-frames", scenario, "1000", &[3]);
    let (d, gathers) = two_rank_gathers("vtu-gathers", scenario);
    let frames = files_ending(&d, ".pvtu") / 2;
    assert!(frames > 10, "only {frames} frames");
    assert_eq!(files_ending(&d, ".pvtp") + files_ending(&d, ".vtp"), 0);
    assert!(
        gathers < frames / 2,
        "{gathers} whole-world gathers for {frames} frames written in pieces"
    );
    let _ = std::fs::remove_dir_all(&d);
    let _ = std::fs::remove_file(&toml);
}

/// Coarse-grained fields are fixed-point sums (T-74) reduced over the
/// ranks: a fields event keeps the world split, and every `fields_*.vti`,
/// `fields_*.csv` and the time average are one process's bytes
/// (`same_bits_at` compares every file).
#[test]
fn fields_of_a_split_world_are_one_process_s() {
    let toml = with_output(
        "crates/clump-cli/tests/fixtures/periodic_frames.toml",
        "fields",
        "contacts = { every = 0.0041 }\n\n[output.fields]\nevery = 0.0029\naxes = [\"z\"]\ncells = [12]\nwidth = 0.003\naverage = true\n",
    );
    let scenario = toml.to_str().unwrap();
    same_bits_at("fields", scenario, "1000", &[2, 3]);
    let (d, gathers) = two_rank_gathers("fields-gathers", scenario);
    let fields = files_ending(&d, ".vti") - 1;
    assert!(fields > 10, "only {fields} fields frames");
    let mean = std::fs::read_to_string(d.join("fields_mean.csv")).unwrap();
    assert!(mean.lines().count() == 13, "{mean}");
    assert!(
        gathers < fields / 2,
        "{gathers} whole-world gathers for {fields} fields frames summed over the ranks"
    );
    let _ = std::fs::remove_dir_all(&d);
    let _ = std::fs::remove_file(&toml);
}

/// Thermo rows come from exact sums reduced over the ranks (T-73) and
/// trajectory rows from the tracked bodies' owners: a row where nothing
/// else is due keeps the world split, and `thermo.csv` and every
/// `traj_<id>.csv` are one process's, byte for byte (`same_bits_at`
/// compares every file).
#[test]
fn thermo_and_trajectory_rows_of_a_split_world_are_one_process_s() {
    let scenario = "crates/clump-cli/tests/fixtures/periodic_thermo.toml";
    same_bits_at("thermo", scenario, "1000", &[2, 3]);
    let (d, gathers) = two_rank_gathers("thermo-gathers", scenario);
    let thermo = std::fs::read_to_string(d.join("thermo.csv")).unwrap();
    let rows = thermo.lines().count() - 1;
    assert!(rows > 15, "only {rows} thermo rows");
    let traj = std::fs::read_to_string(d.join("traj_77.csv")).unwrap();
    assert!(traj.lines().count() > 20, "{traj}");
    // before, every row gathered the world (and ran the step before it whole)
    assert!(
        gathers < rows / 4,
        "{gathers} whole-world gathers for {rows} thermo rows"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Stream insertion is decided on the world split over the ranks
/// (`clump_core::step::partition::insert`: the spheres near the insertion
/// region gathered from their owners, each new body kept by its owner): the
/// stones' insertion events (one every 37 steps) keep the world split.
/// Before, each one gathered the world on every rank and ran the step
/// before it whole. The bits are `stream_insertion_onto_a_floor_has_the_same_bits`'.
#[test]
fn insertion_events_keep_the_world_split() {
    let (d, gathers) = two_rank_gathers("insert-gathers", "examples/stones.toml");
    let state = std::fs::read_to_string(d.join("final_state.json")).unwrap();
    let inserted = state.matches("\"id\"").count();
    assert!(inserted > 20, "only {inserted} stones inserted");
    assert!(
        gathers < inserted / 4,
        "{gathers} whole-world gathers for {inserted} stones inserted one by one"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Stage changes (a wall switched off, gravity tilted, one rod's velocity
/// set, a floor belt started) and the packs and the stream that begin with
/// the stages are done on the world split over the ranks: one process's
/// files on 2 and 3 ranks, and no gather of the world in the whole run.
#[test]
fn stage_changes_and_insertions_keep_the_world_split() {
    let scenario = "crates/clump-cli/tests/fixtures/periodic_stages.toml";
    same_bits_at("stages", scenario, "650", &[2, 3]);
    let (d, gathers) = two_rank_gathers("stages-gathers", scenario);
    let state = std::fs::read_to_string(d.join("final_state.json")).unwrap();
    assert!(state.matches("\"id\"").count() > 80, "{state}");
    assert_eq!(
        gathers, 0,
        "whole-world gathers in a run with 2 stage changes"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Runs `scenario` for 1 000 steps on 2 ranks into the folder `name`;
/// returns the folder and the number of whole-world gathers rank 0
/// reported.
fn two_rank_gathers(name: &str, scenario: &str) -> (PathBuf, usize) {
    let d = out_dir(name);
    let out = Command::new("mpirun")
        .args(["--oversubscribe", "--allow-run-as-root", "-np", "2"])
        .arg(env!("CARGO_BIN_EXE_clump"))
        .args([
            "run",
            scenario,
            "-o",
            d.to_str().unwrap(),
            "--steps",
            "1000",
        ])
        .args(["--threads", "1"])
        .env("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
        .current_dir(repo())
        .output()
        .unwrap();
    let text =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    let gathers: usize = text
        .split(" whole-world gathers")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no gather count in the output:\n{text}"));
    (d, gathers)
}

/// Files in `d` whose names end with `suffix`.
fn files_ending(d: &Path, suffix: &str) -> usize {
    std::fs::read_dir(d)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .ends_with(suffix)
        })
        .count()
}

/// VTK's own readers and ParaView see every sphere and body of a 4-rank
/// run's frames once, with one process's values, for `.vtp` and `.vtu`
/// frames
/// (`scripts/check_pvtp.py` under ParaView's `pvpython`; skipped with a
/// note where it is not installed).
#[test]
fn paraview_reads_a_4_rank_run_s_frames_as_one_process_s() {
    let have = Command::new("sh")
        .args(["-c", "command -v pvpython"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !have {
        eprintln!("SKIPPED: pvpython not found (Debian: apt-get install paraview)");
        return;
    }
    let scenario = "crates/clump-cli/tests/fixtures/periodic_frames.toml";
    let vtu = with_vtu_frames(scenario, "pv-vtu");
    for (tag, scenario) in [("vtp", scenario), ("vtu", vtu.to_str().unwrap())] {
        let (one, four) = (
            out_dir(&format!("pv-{tag}-1")),
            out_dir(&format!("pv-{tag}-4")),
        );
        let (a, b) = (one.to_str().unwrap(), four.to_str().unwrap());
        clump(0, &["run", scenario, "-o", a, "--steps", "600"]);
        clump(4, &["run", scenario, "-o", b, "--steps", "600"]);
        let out = Command::new("pvpython")
            .arg(repo().join("scripts/check_pvtp.py"))
            .args([a, b])
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success()
                && text.contains("ParaView (OpenDataFile spheres.pvd)")
                && text.contains(&format!(".p{tag}: ")),
            "{tag}: {text}\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let _ = std::fs::remove_dir_all(&one);
        let _ = std::fs::remove_dir_all(&four);
    }
    let _ = std::fs::remove_file(&vtu);
}

/// Ranks × threads: 2 ranks of 2 threads each give one process's files
/// with one thread.
#[test]
fn two_ranks_of_two_threads_have_the_same_bits() {
    let scenario = "crates/clump-cli/tests/fixtures/periodic_straddle.toml";
    let serial = out_dir("threads-1");
    let two = out_dir("threads-2x2");
    let (s, t) = (serial.to_str().unwrap(), two.to_str().unwrap());
    clump(0, &["run", scenario, "-o", s, "--steps", "1000"]);
    clump_threads(2, 2, &["run", scenario, "-o", t, "--steps", "1000"]);
    assert_same_outputs(&serial, &two, "2 ranks × 2 threads");
    let _ = std::fs::remove_dir_all(&serial);
    let _ = std::fs::remove_dir_all(&two);
}

/// Heat on ranks: conduction through contacts and the floor, and
/// convection from the air; thermo.csv's temperatures and the floor's heat,
/// the bodies frames' temperatures and the checkpoint are one process's.
#[test]
fn heat_and_convection_have_the_same_bits_at_2_and_3_ranks() {
    let scenario = "crates/clump-cli/tests/fixtures/periodic_heat.toml";
    same_bits_at("heat", scenario, "1000", &[2, 3]);
    // the thermo rows (temperatures, heat, wall heat flow, fluid force)
    // come from reductions: they keep the world split
    let (d, gathers) = two_rank_gathers("heat-gathers", scenario);
    let thermo = std::fs::read_to_string(d.join("thermo.csv")).unwrap();
    assert!(thermo.lines().next().unwrap().contains("fluid_fz[N]"));
    let rows = thermo.lines().count() - 1;
    assert!(rows > 15, "only {rows} thermo rows");
    assert!(
        gathers < rows / 4,
        "{gathers} whole-world gathers for {rows} thermo rows"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_restart_on_3_ranks_from_a_checkpoint_of_2_continues_bit_for_bit() {
    let scenario = "crates/clump-cli/tests/fixtures/periodic_straddle.toml";
    let serial = out_dir("restart-1");
    clump(
        0,
        &[
            "run",
            scenario,
            "-o",
            serial.to_str().unwrap(),
            "--steps",
            "1000",
        ],
    );
    let two = out_dir("restart-2");
    clump(
        2,
        &[
            "run",
            scenario,
            "-o",
            two.to_str().unwrap(),
            "--steps",
            "517",
        ],
    );
    // step 517 has no output due: the checkpoint is written in pieces,
    // without gathering the world
    let ckpt = two.join("checkpoint_000000517.ckpt");
    assert!(
        ckpt.exists() && in_pieces(&ckpt),
        "no checkpoint in pieces at step 517 in {}",
        two.display()
    );
    clump(3, &["resume", ckpt.to_str().unwrap(), "--steps", "1000"]);
    let fin = |d: &Path| std::fs::read(d.join("final_state.json")).unwrap();
    assert!(
        fin(&two) == fin(&serial),
        "the final state resumed on 3 ranks differs from one process's"
    );
    let d = differing(
        &serial.join("checkpoint_000001000.ckpt"),
        &two.join("checkpoint_000001000.ckpt"),
    );
    assert!(
        d.is_empty(),
        "the run resumed on 3 ranks differs from one process's in {d:?}"
    );
    let _ = std::fs::remove_dir_all(&serial);
    let _ = std::fs::remove_dir_all(&two);
}

/// A checkpoint in pieces written on 4 ranks resumes on 2 ranks (each
/// reads only the pieces that hold its share) and in one process (every
/// piece), and both continue bit for bit.
#[test]
fn a_checkpoint_of_4_ranks_resumes_on_2_and_in_one_process_bit_for_bit() {
    let scenario = "crates/clump-cli/tests/fixtures/periodic_straddle.toml";
    let serial = out_dir("restart4-1");
    let sc = ["run", scenario, "-o", serial.to_str().unwrap()];
    clump(0, &[&sc[..], &["--steps", "1000"]].concat());
    let four = out_dir("restart4-4");
    clump(
        4,
        &[
            "run",
            scenario,
            "-o",
            four.to_str().unwrap(),
            "--steps",
            "517",
        ],
    );
    let ckpt = four.join("checkpoint_000000517.ckpt");
    assert!(ckpt.exists() && in_pieces(&ckpt), "no checkpoint in pieces");
    for (np, name) in [(2, "restart4-2"), (0, "restart4-0")] {
        let d = out_dir(name);
        let args = ["resume", ckpt.to_str().unwrap(), "-o", d.to_str().unwrap()];
        clump(np, &[&args[..], &["--steps", "1000"]].concat());
        let fin = |d: &Path| std::fs::read(d.join("final_state.json")).unwrap();
        assert!(fin(&d) == fin(&serial), "{name}: the final state differs");
        let c = "checkpoint_000001000.ckpt";
        let diff = differing(&serial.join(c), &d.join(c));
        assert!(
            diff.is_empty(),
            "{name}: {diff:?} differ from one process's"
        );
        let _ = std::fs::remove_dir_all(&d);
    }
    let _ = std::fs::remove_dir_all(&serial);
    let _ = std::fs::remove_dir_all(&four);
}

/// The `clump` processes whose parent is `pid` (Linux: from /proc; other
/// helpers mpirun may fork are left out).
fn children(pid: u32) -> Vec<u32> {
    let mut out = Vec::new();
    for e in std::fs::read_dir("/proc").unwrap().flatten() {
        let Ok(p) = e.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let Ok(stat) = std::fs::read_to_string(e.path().join("stat")) else {
            continue;
        };
        // "pid (comm) state ppid ...": the name may hold spaces
        let rest = &stat[stat.rfind(')').map_or(0, |i| i + 1)..];
        let ppid = rest
            .split_whitespace()
            .nth(1)
            .and_then(|x| x.parse::<u32>().ok());
        if ppid == Some(pid) && stat.contains("(clump)") {
            out.push(p);
        }
    }
    out.sort_unstable();
    out
}

/// `examples/stones.toml` on 2 ranks of one thread into `d`, started.
fn stones_on_two_ranks(d: &Path, stderr: std::process::Stdio) -> std::process::Child {
    Command::new("mpirun")
        .args(["--oversubscribe", "--allow-run-as-root", "-np", "2"])
        .arg(env!("CARGO_BIN_EXE_clump"))
        .args(["run", "examples/stones.toml", "-o", d.to_str().unwrap()])
        .args(["--threads", "1"])
        .env("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
        .current_dir(repo())
        .stdout(std::process::Stdio::null())
        .stderr(stderr)
        .spawn()
        .expect("mpirun must be installed")
}

/// Sends `signal` (`kill`'s option) to the second of mpirun's two rank
/// processes and waits up to 60 s for mpirun to end; on a hang kills every
/// rank and mpirun. Returns whether it hung.
fn signal_rank_1_and_wait(child: &mut std::process::Child, signal: &str) -> bool {
    // /proc may show the two ranks a moment late or miss one in a scan:
    // look again for up to 10 s while mpirun runs
    let t = std::time::Instant::now();
    let mut ranks = children(child.id());
    while ranks.len() != 2 && t.elapsed().as_secs() < 10 && child.try_wait().unwrap().is_none() {
        std::thread::sleep(std::time::Duration::from_millis(20));
        ranks = children(child.id());
    }
    assert_eq!(
        ranks.len(),
        2,
        "mpirun's children: {ranks:?} (mpirun's exit: {:?})",
        child.try_wait().unwrap()
    );
    let st = Command::new("kill")
        .args([signal, &ranks[1].to_string()])
        .status()
        .unwrap();
    assert!(st.success());
    let t = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if t.elapsed().as_secs() > 60 {
            for r in &ranks {
                let _ = Command::new("kill")
                    .args(["-KILL", &r.to_string()])
                    .status();
            }
            let _ = child.kill();
            return true;
        }
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    false
}

/// One process's uninterrupted stones run to step `steps`, in a new folder.
fn stones_straight_to(name: &str, steps: &str) -> PathBuf {
    let d = out_dir(name);
    clump(
        0,
        &[
            "run",
            "examples/stones.toml",
            "-o",
            d.to_str().unwrap(),
            "--steps",
            steps,
        ],
    );
    d
}

#[test]
fn sigterm_on_two_ranks_checkpoints_the_whole_world_at_one_step() {
    let d = out_dir("sigterm");
    let mut child = stones_on_two_ranks(&d, std::process::Stdio::null());
    // the handlers are installed before the first thermo row is written
    let t0 = std::time::Instant::now();
    while std::fs::read_to_string(d.join("thermo.csv")).map_or(0, |s| s.lines().count()) < 10 {
        assert!(t0.elapsed().as_secs() < 300, "no thermo rows after 300 s");
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    // the signal goes to one rank process, as docs/scaling.md tells users
    // (Open MPI 4.1's mpirun answers a SIGTERM of its own with SIGKILL to
    // the ranks a second later, which lost the checkpoint about one time in
    // ten here): every rank must stop at the same step, also the one
    // without a signal of its own
    // mpirun's own exit status is Open MPI's, the run's is in the manifest;
    // ranks that disagree on the stop hang (one waits in the step's
    // reduction, the other in MPI_Finalize)
    let hung = signal_rank_1_and_wait(&mut child, "-TERM");
    let _ = child.wait();
    assert!(!hung, "the ranks were still running 60 s after the signal");
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("manifest.json")).unwrap()).unwrap();
    assert!(
        m["status"].as_str().unwrap().starts_with("interrupted"),
        "{m}"
    );
    let step = m["final_step"].as_u64().unwrap();
    let ckpt = d.join(format!("checkpoint_{step:09}.ckpt"));
    assert!(ckpt.is_file(), "no checkpoint at the interrupt step {step}");
    // one process, resumed from it, repeats an uninterrupted run
    let target = (step + 200).to_string();
    clump(0, &["resume", ckpt.to_str().unwrap(), "--steps", &target]);
    let straight = stones_straight_to("sigterm-straight", &target);
    let d2 = differing(
        &d.join(format!("checkpoint_{:09}.ckpt", step + 200)),
        &straight.join(format!("checkpoint_{:09}.ckpt", step + 200)),
    );
    assert!(
        d2.is_empty(),
        "interrupted on 2 ranks and resumed: {d2:?} differ"
    );
    let _ = std::fs::remove_dir_all(&d);
    let _ = std::fs::remove_dir_all(&straight);
}

/// A rank killed mid-run (SIGKILL: no handler runs) stops the run: mpirun
/// exits with a failure naming the rank within a minute, the others do
/// not hang, and the last checkpoint the manifest lists stays complete: one
/// process resumes from it and repeats an uninterrupted run bit for bit.
#[test]
fn a_rank_killed_mid_run_stops_the_run_and_the_last_checkpoint_resumes() {
    let d = out_dir("killed");
    let mut child = stones_on_two_ranks(&d, std::process::Stdio::piped());
    // wait for the first periodic checkpoint (0.2 s of simulated time) to
    // be listed in the manifest
    let listed = || -> Option<PathBuf> {
        let text = std::fs::read_to_string(d.join("manifest.json")).ok()?;
        let m: serde_json::Value = serde_json::from_str(&text).ok()?;
        m["checkpoint"].as_str().map(PathBuf::from)
    };
    let t0 = std::time::Instant::now();
    let ckpt = loop {
        if let Some(c) = listed() {
            break c;
        }
        assert!(
            t0.elapsed().as_secs() < 300,
            "no checkpoint listed after 300 s"
        );
        std::thread::sleep(std::time::Duration::from_millis(50));
    };
    eprintln!(
        "checkpoint listed after {:.1} s",
        t0.elapsed().as_secs_f64()
    );
    let t1 = std::time::Instant::now();
    let hung = signal_rank_1_and_wait(&mut child, "-KILL");
    let out = child.wait_with_output().unwrap();
    eprintln!(
        "mpirun exited {:.1} s after the kill",
        t1.elapsed().as_secs_f64()
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !hung,
        "rank 0 was still running 60 s after rank 1 was killed"
    );
    assert!(!out.status.success(), "mpirun reported success");
    assert!(
        stderr.contains("signal 9") || stderr.contains("Killed") || stderr.contains("killed"),
        "mpirun's message does not name the killed rank:\n{stderr}"
    );
    // the checkpoint listed last (the manifest may have moved on before the
    // kill) loads, and one process resumed from it repeats a straight run
    let ckpt = listed().unwrap_or(ckpt);
    let bytes = std::fs::read(&ckpt).unwrap();
    let (_, world, _) = clump_io::run::load_checkpoint(&bytes, &ckpt)
        .unwrap_or_else(|e| panic!("{}: {e}", ckpt.display()));
    let step = world.step;
    let resumed = out_dir("killed-resumed");
    let target = (step + 200).to_string();
    clump(
        0,
        &[
            "resume",
            ckpt.to_str().unwrap(),
            "-o",
            resumed.to_str().unwrap(),
            "--steps",
            &target,
        ],
    );
    let straight = stones_straight_to("killed-straight", &target);
    let name = format!("checkpoint_{:09}.ckpt", step + 200);
    let diff = differing(&resumed.join(&name), &straight.join(&name));
    assert!(diff.is_empty(), "resumed after the kill: {diff:?} differ");
    for p in [&d, &resumed, &straight] {
        let _ = std::fs::remove_dir_all(p);
    }
}
