//! `clump bench`: the shared tetra-bed benchmark (../shared/bench/tetra-bed),
//! timed phase by phase, optionally side by side with LIGGGHTS; with
//! `--case stone-pile | stone-bed` the stone benchmarks of [`crate::bench_stone`].
//!
//! The case: 4-sphere tetrahedral clumps (r = 1 mm, edge 1.2 mm, ρ = 2500)
//! fall from a common initial condition into a 40 × 40 mm box and settle;
//! Hertz–Mindlin with history, E = 5e6, ν = 0.3, e = 0.5, μ = 0.5, LIGGGHTS'
//! damping law and unclamped (tensile) normal force as LIGGGHTS' default
//! `limitForce off` (for a like-for-like comparison), dt = 1e-5. Phase A (fall and
//! settle) and phase B (dense bed) are timed separately; throughput is
//! spheres × steps / wall seconds.

use anyhow::{bail, Context, Result};
use clap::Args;
use clump_core::world::World;
use clump_io::scenario::InsertSpec;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The benchmark case of `clump bench`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Case {
    /// The shared tetra bed (../shared/bench/tetra-bed).
    Tetra,
    /// 200 many-sphere stones falling into a cylinder r = 0.26 m (LIGGGHTS'
    /// stone tutorial's region and materials).
    StonePile,
    /// 2000 stones settled in a box, the dense bed timed on its own.
    StoneBed,
    /// 200 stones of two shapes in three sizes each (six templates) falling
    /// into the stone pile's cylinder.
    StoneMix,
}

/// Arguments of `clump bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// The case: `tetra` (the shared tetra bed), `stone-pile`, `stone-bed` or
    /// `stone-mix` (many-sphere stones, with the LIGGGHTS input generated
    /// from the same initial condition; see `--stone`; the mix takes the
    /// `--stone` and a procedural stone, each in three sizes).
    #[arg(long, value_enum, default_value_t = Case::Tetra)]
    pub case: Case,
    /// Stone cases: the stone. `liggghts`: LIGGGHTS' tutorial stone
    /// `stone1.multisphere` (50 spheres, from Debian's liggghts-doc; GPL data,
    /// not shipped); `procedural`: a shipped stand-in of the same size and
    /// sphere count; or a file of `x y z r` rows in mm.
    #[arg(long, default_value = "liggghts")]
    pub stone: String,
    /// Stone cases: number of stones (default 200 for the pile and the mix,
    /// 2000 for the bed).
    #[arg(long)]
    pub stones: Option<usize>,
    /// Stone cases: folder for the generated initial condition, Clump
    /// scenario and LIGGGHTS input (default `out/bench-<case>`); the settled
    /// stone bed is kept there and reused.
    #[arg(long)]
    pub work: Option<PathBuf>,
    /// Stone cases: Clump uses LIGGGHTS' tangential rule (`tangential =
    /// "liggghts"`, a scalar path) instead of its default, for the physics
    /// comparison.
    #[arg(long)]
    pub liggghts_tangential: bool,
    /// Stone pile and mix: seed of the stones' random poses. One pile is one
    /// sample of a random packing; several seeds give both codes the same
    /// ensemble, for the physics comparison.
    #[arg(long, default_value_t = crate::bench_stone::PILE_SEED)]
    pub pose_seed: u64,
    /// Stone bed: steps of the Clump-only settling that makes the common
    /// initial condition from the loose lattice (done once, kept in `--work`).
    #[arg(long, default_value_t = 40000)]
    pub bed_settle: u64,
    /// The benchmark folder (holds tetra.xyzr, ic_N.txt, liggghts/).
    #[arg(long, default_value = "../shared/bench/tetra-bed")]
    pub dir: PathBuf,
    /// Number of clumps: 2000 or 10000 (selects `benches/tetra_bed_<N>.toml`
    /// and, for LIGGGHTS, `ic_<N>.txt`).
    #[arg(long, default_value_t = 2000)]
    pub n: usize,
    /// The Clump scenario (default `benches/tetra_bed_<N>.toml`, relative to
    /// the current folder: run from the repository root).
    #[arg(long)]
    pub scenario: Option<PathBuf>,
    /// Steps of phase A, fall and settle (default: the scenario's first stage).
    #[arg(long)]
    pub na: Option<u64>,
    /// Steps of phase B, dense bed, timed on its own (default: the second stage).
    #[arg(long)]
    pub nb: Option<u64>,
    /// Threads for Clump (rayon).
    #[arg(long, default_value_t = 1)]
    pub threads: usize,
    /// Verlet skin, m (default: the engine's, 20 % of the smallest radius).
    #[arg(long)]
    pub skin: Option<f64>,
    /// Also run LIGGGHTS (if installed), alternating Clump and LIGGGHTS this many rounds.
    #[arg(long, default_value_t = 0)]
    pub liggghts_rounds: usize,
    /// Where to write the final sphere centres (LIGGGHTS dump format, for analyze.py).
    #[arg(long)]
    pub dump: Option<PathBuf>,
    /// Scaling study instead of the tetra-bed case: comma-separated target
    /// sphere counts, e.g. `10000,100000,1000000`. Each size is a dense
    /// periodic bed of tetra clumps: a tile of about 10⁴ spheres (`--layers`
    /// deep) settled for `--settle` steps and copied side by side to the
    /// size, the sizes timed in turns of `--steps` steps (see
    /// `--scaling-rounds`).
    #[arg(long, value_delimiter = ',', value_name = "SPHERES")]
    pub scaling: Vec<usize>,
    /// Scaling study: lattice layers of the bed.
    #[arg(long, default_value_t = 8)]
    pub layers: usize,
    /// Scaling study: settling steps of the tile before it is copied (the
    /// default lets 8 lattice layers fall and settle into a dense bed).
    #[arg(long, default_value_t = 20000)]
    pub settle: u64,
    /// Scaling study: timed steps per round. A smaller bed times the same
    /// steps several times over (from the state saved at the round's start)
    /// up to the largest bed's sphere-steps, so that every bed's round spans
    /// the same stretch of the simulation and lasts about as long.
    #[arg(long, default_value_t = 300)]
    pub steps: u64,
    /// Scaling study: timed rounds per size (of `--steps` steps each), the
    /// sizes taking turns. The row gives the best round (the cost with the
    /// least interference from the rest of the machine) and the median; the
    /// stage times are the best round's.
    #[arg(long, default_value_t = 5)]
    pub scaling_rounds: usize,
    /// Internal: run one timed Clump round in this process and print its
    /// figures (the bench runs each round as such a child process; see
    /// `bench_round`).
    #[arg(long, hide = true)]
    pub child_round: bool,
}

/// Figures of one timed run.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Figures {
    pub(crate) a_seconds: f64,
    pub(crate) b_seconds: f64,
    pub(crate) spheres: usize,
    pub(crate) peak_rss_mb: f64,
    /// A cache line's round trip between two cores just before and just
    /// after the run, ns (`core_latency`; multi-threaded Clump rounds only).
    pub(crate) cross_core_ns: [Option<f64>; 2],
}

/// The median of `key` over `v` (the upper one of an even count).
pub(crate) fn median(v: &[Figures], key: fn(&Figures) -> f64) -> f64 {
    let mut x: Vec<f64> = v.iter().map(key).collect();
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

/// Runs the benchmark.
pub fn run(args: &BenchArgs) -> Result<()> {
    if args.threads == 0 {
        bail!("--threads: the bench needs at least 1 thread (got 0)");
    }
    if args.child_round {
        return crate::bench_round::child(args);
    }
    if !args.scaling.is_empty() {
        return scaling(args);
    }
    match args.case {
        Case::Tetra => {}
        Case::StonePile => {
            return crate::bench_stone::run(args, crate::bench_stone::StoneCase::Pile)
        }
        Case::StoneBed => return crate::bench_stone::run(args, crate::bench_stone::StoneCase::Bed),
        Case::StoneMix => return crate::bench_stone::run(args, crate::bench_stone::StoneCase::Mix),
    }
    let rounds = args.liggghts_rounds.max(1);
    let lig = if args.liggghts_rounds > 0 {
        which("liggghts")
    } else {
        None
    };
    if args.liggghts_rounds > 0 && lig.is_none() {
        errln!("liggghts is not installed (apt-get install liggghts): running Clump only");
    }
    let (_, sa, sb) = build_world(&scenario_path(args), args.skin)?;
    let (na, nb) = (args.na.unwrap_or(sa), args.nb.unwrap_or(sb));
    outln!(
        "tetra-bed, {} clumps, phase A {na} steps, phase B {nb} steps, clump threads {}",
        args.n,
        args.threads
    );
    let mut clump = Vec::new();
    let mut peer = Vec::new();
    let scenario = scenario_path(args);
    for round in 0..rounds {
        let f = crate::bench_round::run(&crate::bench_round::Round {
            scenario: &scenario,
            threads: args.threads,
            skin: args.skin,
            na,
            nb,
            dump: args.dump.as_deref(),
        })?;
        report("clump", round, na, nb, &f);
        clump.push(f);
        if let Some(bin) = &lig {
            let f = run_liggghts(args, bin, na, nb)?;
            report("liggghts", round, na, nb, &f);
            peer.push(f);
        }
    }
    let med = |v: &[Figures], key: fn(&Figures) -> f64| {
        let mut x: Vec<f64> = v.iter().map(key).collect();
        x.sort_by(|a, b| a.partial_cmp(b).unwrap());
        x[x.len() / 2]
    };
    let tput = |s: f64, steps: u64, n: usize| n as f64 * steps as f64 / s;
    let ns = clump[0].spheres;
    let (ca, cb) = (
        tput(med(&clump, |f| f.a_seconds), na, ns),
        tput(med(&clump, |f| f.b_seconds), nb, ns),
    );
    outln!("clump    (threads {}): phase A {:.3} M sphere-steps/s, phase B {:.3} M sphere-steps/s, peak RSS {:.0} MB", args.threads, ca / 1e6, cb / 1e6, med(&clump, |f| f.peak_rss_mb));
    if !peer.is_empty() {
        let (la, lb) = (
            tput(med(&peer, |f| f.a_seconds), na, ns),
            tput(med(&peer, |f| f.b_seconds), nb, ns),
        );
        outln!("liggghts (serial):    phase A {:.3} M sphere-steps/s, phase B {:.3} M sphere-steps/s, peak RSS {:.0} MB", la / 1e6, lb / 1e6, med(&peer, |f| f.peak_rss_mb));
        outln!(
            "ratio clump/liggghts: phase A {:.2}x, phase B {:.2}x",
            ca / la,
            cb / lb
        );
        // each round's own ratio (the two codes ran back to back): on a
        // machine whose speed drifts, the median of these is the steadier
        // figure
        let mut per_round: Vec<f64> = clump
            .iter()
            .zip(&peer)
            .map(|(c, l)| l.b_seconds / c.b_seconds)
            .collect();
        let list: Vec<String> = per_round.iter().map(|r| format!("{r:.2}x")).collect();
        per_round.sort_by(|a, b| a.total_cmp(b));
        outln!(
            "phase B ratio per round: {}; median {:.2}x",
            list.join(", "),
            per_round[per_round.len() / 2]
        );
    }
    Ok(())
}

pub(crate) fn report(code: &str, round: usize, na: u64, nb: u64, f: &Figures) {
    let ns = f.spheres as f64;
    // which state the host's cores were in (crate::core_latency)
    let cores = match f.cross_core_ns {
        [None, None] => String::new(),
        [before, after] => {
            let shown = |x: Option<f64>| x.map_or("-".into(), |x| format!("{x:.0}"));
            format!(
                "  cross-core round trip {} / {} ns (before / after)",
                shown(before),
                shown(after)
            )
        }
    };
    outln!(
        "round {round} {code}: A {:.2} s ({:.3} M sph-steps/s)  B {:.2} s ({:.3} M sph-steps/s)  peak RSS {:.1} MB{cores}",
        f.a_seconds,
        ns * na as f64 / f.a_seconds / 1e6,
        f.b_seconds,
        ns * nb as f64 / f.b_seconds / 1e6,
        f.peak_rss_mb
    );
}

pub(crate) fn which(name: &str) -> Option<PathBuf> {
    std::env::var_os("PATH").and_then(|p| {
        std::env::split_paths(&p)
            .map(|d| d.join(name))
            .find(|f| f.is_file())
    })
}

/// The benchmark scenario for `n` clumps: `benches/tetra_bed_<n>.toml`.
pub fn scenario_path(args: &BenchArgs) -> PathBuf {
    args.scenario
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("benches/tetra_bed_{}.toml", args.n)))
}

/// Builds the tetra-bed world from its scenario (which reads the shared
/// template and initial-condition files): the scenario's materials, walls
/// and settings, and the bodies of its file insertion. Returns the world and
/// the step counts of its two stages (phase A, phase B).
pub fn build_world(path: &Path, skin: Option<f64>) -> Result<(World, u64, u64)> {
    // the scenario's diagnostic starts with its own "error: ", which the
    // bench's caller prints once for every error
    let sc = clump_io::scenario::load(path).map_err(|e| {
        let text = e.to_string();
        anyhow::anyhow!(
            "{}",
            text.strip_prefix("error: ").unwrap_or(&text).trim_end()
        )
    })?;
    if sc.stages.len() != 2 {
        bail!(
            "{}: the benchmark needs two stages (fall, dense), found {}",
            path.display(),
            sc.stages.len()
        );
    }
    let mut w = sc
        .build_world()
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    if skin.is_some() {
        w.config.skin = skin;
    }
    for ins in &sc.inserts {
        match &ins.kind {
            InsertSpec::File { bodies } if ins.stage == 0 => {
                for b in bodies {
                    w.add_body(b)?;
                }
            }
            _ => bail!(
                "{}: the benchmark takes its bodies from one file insertion in the first stage",
                path.display()
            ),
        }
    }
    Ok((w, sc.stages[0].steps, sc.stages[1].steps))
}

/// Prints (stderr) the bodies, contacts, lost bodies, kinetic energy and
/// rebuilds of `w` at the end of a timed run, and its state fingerprint.
pub(crate) fn print_end_state(w: &World) {
    let th = w.thermo();
    errln!(
        "clump: {} bodies, {} contacts, lost {}, KE {:.3e} J, rebuilds {}",
        th.bodies,
        th.pair_contacts + th.wall_contacts,
        th.lost_bodies,
        th.kinetic_translational + th.kinetic_rotational,
        w.rebuilds
    );
    errln!("clump: state fingerprint {:016x}", state_fingerprint(w));
}

/// FNV-1a hash of every body's position, velocity, angular momentum and
/// orientation bits (storage order): equal fingerprints mean the same state
/// bit for bit, to compare builds and thread counts.
pub fn state_fingerprint(w: &World) -> u64 {
    let mut h = 0xcbf29ce484222325u64;
    let b = &w.bodies;
    let mut mix = |x: f64| {
        h ^= x.to_bits();
        h = h.wrapping_mul(0x100000001b3);
    };
    for i in 0..b.len() {
        for v in [b.position[i], b.velocity[i], b.angular_momentum[i]] {
            v.to_array().into_iter().for_each(&mut mix);
        }
        b.orientation[i].to_array().into_iter().for_each(&mut mix);
    }
    h
}

/// Final sphere centres in the LIGGGHTS/LAMMPS dump format, ordered by body
/// id, every number as Rust writes f64 (it reads back exactly).
pub(crate) fn write_dump(w: &World, path: &Path) -> Result<()> {
    use std::fmt::Write;
    let sp = w.spheres();
    let mut order: Vec<usize> = (0..w.bodies.len()).collect();
    order.sort_by_key(|&b| w.bodies.id[b]);
    let mut s = String::new();
    writeln!(
        s,
        "ITEM: TIMESTEP\n{}\nITEM: NUMBER OF ATOMS\n{}",
        w.step,
        sp.len()
    )?;
    let d = w.config.domain;
    writeln!(
        s,
        "ITEM: BOX BOUNDS ff ff ff\n{} {}\n{} {}\n{} {}",
        d.lo.x, d.hi.x, d.lo.y, d.hi.y, d.lo.z, d.hi.z
    )?;
    writeln!(s, "ITEM: ATOMS id mol x y z radius")?;
    let mut id = 1;
    for b in order {
        for k in sp.of_body(b) {
            let x = sp.position(k);
            writeln!(
                s,
                "{id} {} {:e} {:e} {:e} {:e}",
                w.bodies.id[b], x.x, x.y, x.z, sp.radius[k]
            )?;
            id += 1;
        }
    }
    std::fs::write(path, s)?;
    Ok(())
}

/// CPU time (user + system, all threads) of this process so far, s (Linux
/// /proc/self/stat, 100 ticks per second): a load-independent companion of
/// the wall times on a shared machine.
pub(crate) fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            // the command name may hold spaces: fields after the last ')'
            let rest = &s[s.rfind(')')? + 2..];
            let f: Vec<&str> = rest.split_whitespace().collect();
            Some((f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?) / 100.0)
        })
        .unwrap_or(f64::NAN)
}

/// Peak resident set size of this process so far, MB (Linux VmHWM).
pub(crate) fn peak_rss_mb() -> f64 {
    proc_status_mb("VmHWM:")
}

/// Resident memory of this process now, MB (Linux; NaN elsewhere).
fn current_rss_mb() -> f64 {
    proc_status_mb("VmRSS:")
}

/// A memory figure of `/proc/self/status` (its line `key`), MB.
fn proc_status_mb(key: &str) -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with(key))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn run_liggghts(args: &BenchArgs, bin: &Path, na: u64, nb: u64) -> Result<Figures> {
    let work = std::env::temp_dir().join(format!("clump-bench-liggghts-{}", std::process::id()));
    // the shared layout: the case files in the folder, the LIGGGHTS input
    // in liggghts/ (gen_liggghts.py reads ../ic_N.txt)
    let run_dir = work.join("liggghts");
    std::fs::create_dir_all(&run_dir)?;
    let src = args.dir.join("liggghts");
    for f in ["in.bench", "tetra.multisphere", "gen_liggghts.py"] {
        std::fs::copy(src.join(f), run_dir.join(f))
            .with_context(|| format!("copying {}", src.join(f).display()))?;
    }
    for f in std::fs::read_dir(&args.dir)? {
        let p = f?.path();
        if let (true, Some(name)) = (p.is_file(), p.file_name()) {
            std::fs::copy(&p, work.join(name))?;
        }
    }
    let work_root = work;
    let work = run_dir;
    let ztop = if args.n <= 2000 { "0.2" } else { "0.31" };
    let ok = std::process::Command::new("python3")
        .arg("gen_liggghts.py")
        .arg(args.n.to_string())
        .current_dir(&work)
        .status()?;
    if !ok.success() {
        bail!("gen_liggghts.py failed");
    }
    let vars = [
        ("N", args.n.to_string()),
        ("ZTOP", ztop.to_string()),
        ("NA", na.to_string()),
        ("NB", nb.to_string()),
    ];
    // the insertion include runs many 1-step loops first; phase A and B are
    // the last loops of NA and NB steps
    let figures = run_liggghts_input(bin, &work, "in.bench", &vars, na, nb, 4 * args.n)?;
    if let Some(p) = &args.dump {
        let f = work.join(format!("final_{}.dump", args.n));
        let _ = std::fs::copy(f, p.with_extension("liggghts.dump"));
    }
    let _ = std::fs::remove_dir_all(&work_root);
    Ok(figures)
}

/// Runs LIGGGHTS on `input` in `dir` with `vars` (`-var NAME VALUE`),
/// under `/usr/bin/time` for its peak memory; phase A and B are the last
/// loops of `na` and `nb` steps.
pub(crate) fn run_liggghts_input(
    bin: &Path,
    dir: &Path,
    input: &str,
    vars: &[(&str, String)],
    na: u64,
    nb: u64,
    spheres: usize,
) -> Result<Figures> {
    let mut cmd = std::process::Command::new("/usr/bin/time");
    cmd.args(["-f", "MAXRSS_KB %M"])
        .arg(bin)
        .args(["-in", input]);
    for (k, v) in vars {
        cmd.args(["-var", k, v]);
    }
    let out = cmd
        .current_dir(dir)
        .output()
        .with_context(|| format!("running {} under /usr/bin/time", bin.display()))?;
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    // "Loop time of T on P procs for N steps with M atoms": phase B is the
    // last loop of `nb` steps, phase A the last loop of `na` steps before it
    // (also when na = nb)
    let loops: Vec<(u64, f64)> = text
        .lines()
        .filter(|l| l.starts_with("Loop time of"))
        .filter_map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            Some((w.get(8)?.parse().ok()?, w.get(3)?.parse().ok()?))
        })
        .collect();
    let ib = loops.iter().rposition(|l| l.0 == nb);
    let ia = ib.and_then(|ib| loops[..ib].iter().rposition(|l| l.0 == na));
    let rss = text
        .lines()
        .find(|l| l.starts_with("MAXRSS_KB"))
        .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        .unwrap_or(f64::NAN)
        / 1024.0;
    match (ia, ib) {
        (Some(a), Some(b)) if out.status.success() => Ok(Figures {
            a_seconds: loops[a].1,
            b_seconds: loops[b].1,
            spheres,
            peak_rss_mb: rss,
            cross_core_ns: [None; 2],
        }),
        _ => bail!(
            "LIGGGHTS failed or its loop times could not be read (input {}); its output ends with:\n{}",
            dir.join(input).display(),
            text.lines()
                .rev()
                .take(20)
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .collect::<Vec<_>>()
                .join("\n")
        ),
    }
}

/// Spheres in the settled tile of the scaling study (about 10⁴).
const SCALING_TILE_SPHERES: f64 = 1e4;

/// Untimed steps of a scaling bed before each of its timed rounds.
const SCALING_WARM_STEPS: u64 = 20;

/// One bed of the scaling study, with its timed rounds.
struct ScalingBed {
    /// Copies of the tile along x and y.
    k: usize,
    world: clump_core::world::World,
    /// Resident memory added by building and warming up this bed, MB.
    rss_mb: f64,
    /// Repetitions per round of the same `--steps` steps (from the state
    /// saved at the round's start), so that every bed's round holds about as
    /// many sphere-steps as the largest bed's.
    reps: u64,
    /// Seconds and stage times of each round.
    rounds: Vec<(f64, clump_core::stats::StageTimes)>,
    /// Neighbour rebuilds during the timed rounds.
    rebuilds: u64,
}

/// The scaling study. A periodic tile of about 10⁴ spheres (`--layers`
/// lattice layers deep) is settled into a dense bed for `--settle` steps,
/// then copied side by side ([`clump_core::testbed::tile_xy`]) to each
/// size, and each bed runs 200 steps to rebuild its lists and contact
/// histories: every size times the same dense bed. The beds are then timed
/// in alternation, one round each per turn (after [`SCALING_WARM_STEPS`]
/// untimed steps), so that all sizes see the same state of the machine (its
/// speed drifts by tens of per cent over minutes). A round is `--steps`
/// steps of every bed; a smaller bed repeats them from the state saved at
/// the round's start ([`World::save_state`], bit-identical repetitions) up
/// to the largest bed's sphere-steps. So every bed's round covers the same
/// stretch of simulated time (the beds keep settling, and a bed that ran
/// longer would rebuild its lists less often) and lasts about as long on
/// the clock (a short round of a small bed would often miss the slow spells
/// that a long round of the large bed always contains). Each row gives the
/// best and the median round,
/// and the last line the cost of the largest bed over the smallest's,
/// round by round. Memory per sphere is the resident memory that building
/// and warming up the bed added.
fn scaling(args: &BenchArgs) -> Result<()> {
    if args.steps == 0 {
        bail!("--steps: the scaling study needs at least 1 timed step per round (got 0)");
    }
    if let Some(n) = args.scaling.iter().find(|&&n| n == 0) {
        bail!("--scaling: sphere counts must be positive (got {n})");
    }
    outln!(
        "scaling: dense periodic tetra beds (a ~1e4-sphere tile of {} layers settled {} steps, copied side by side), {} alternating rounds of {} steps (repeated from the same state by the smaller beds up to the largest's sphere-steps), threads {}",
        args.layers, args.settle, args.scaling_rounds.max(1), args.steps, args.threads
    );
    let nz = args.layers.max(1);
    let nx = ((SCALING_TILE_SPHERES / (4.0 * nz as f64)).sqrt().round() as usize).max(4);
    let tile_spheres = 4 * nx * nx * nz;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()?;
    let mut beds = pool.install(|| -> Result<Vec<ScalingBed>> {
        let mut tile = clump_core::testbed::tetra_lattice_bed(nx, nx, nz, args.skin);
        tile.run(args.settle)?;
        let mut beds = Vec::new();
        for &n in &args.scaling {
            let k = ((n as f64 / tile_spheres as f64).sqrt().round() as usize).max(1);
            let r0 = current_rss_mb();
            let mut world = clump_core::testbed::tile_xy(&tile, k, k);
            world.run(200)?;
            beds.push(ScalingBed {
                k,
                world,
                rss_mb: current_rss_mb() - r0,
                reps: 1,
                rounds: Vec::new(),
                rebuilds: 0,
            });
        }
        let largest = beds
            .iter()
            .map(|b| b.world.spheres().len())
            .max()
            .unwrap_or(1);
        for bed in beds.iter_mut() {
            let ns = bed.world.spheres().len().max(1);
            bed.reps = (largest as f64 / ns as f64).round().max(1.0) as u64;
        }
        for _ in 0..args.scaling_rounds.max(1) {
            for bed in beds.iter_mut() {
                let w = &mut bed.world;
                let saved = if bed.reps > 1 {
                    Some(w.save_state()?)
                } else {
                    None
                };
                let (mut secs, mut times) = (0.0, clump_core::stats::StageTimes::default());
                for rep in 0..bed.reps {
                    if let (Some(s), true) = (&saved, rep > 0) {
                        w.restore_state(s.clone()).map_err(|e| anyhow::anyhow!(e))?;
                    }
                    // a few untimed steps first: the bed's data back in the
                    // caches after the other beds' turns (and the lists
                    // rebuilt after a restore)
                    w.run(SCALING_WARM_STEPS)?;
                    w.stage_times = Default::default();
                    let (t0, r0) = (Instant::now(), w.rebuilds);
                    w.run(args.steps)?;
                    secs += t0.elapsed().as_secs_f64();
                    times += w.stage_times;
                    bed.rebuilds += w.rebuilds - r0;
                }
                bed.rounds.push((secs, times));
            }
        }
        Ok(beds)
    })?;
    outln!(
        "{:>9} {:>8} {:>20} {:>12} {:>14} {:>11} {:>13} {:>12} {:>13} {:>7} {:>9} {:>13}   ns/sph-step by stage (best round): initial, neighbour, pair, gather",
        "spheres",
        "clumps",
        "bed",
        "timed steps",
        "M sph-steps/s",
        "ns/sph-step",
        "(median ns)",
        "contacts/sph",
        "steps/rebuild",
        "skin/r",
        "RSS MB",
        "RSS B/sphere"
    );
    // ns per sphere-step of each round of each bed
    let mut costs = Vec::new();
    for bed in beds.iter_mut() {
        let w = &bed.world;
        let ns = w.spheres().len();
        let steps = args.steps * bed.reps;
        let per = 1e9 / (ns as f64 * steps as f64);
        costs.push(bed.rounds.iter().map(|r| r.0 * per).collect::<Vec<_>>());
        bed.rounds.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (best, times) = bed.rounds[0];
        let median = bed.rounds[bed.rounds.len() / 2].0;
        let stages = times.rows().map(|(_, t)| format!("{:.1}", t * per));
        let rate = ns as f64 * steps as f64 / best;
        outln!(
            "{:>9} {:>8} {:>20} {:>12} {:>14.3} {:>11.1} {:>13.1} {:>12.2} {:>13} {:>7.3} {:>9.0} {:>13.0}",
            ns,
            w.bodies.len(),
            format!("{}x{} of {nx}x{nx}x{nz}", bed.k, bed.k),
            format!("{}x{}", bed.reps, args.steps),
            rate / 1e6,
            1e9 / rate,
            median * per,
            2.0 * w.thermo().pair_contacts as f64 / ns as f64,
            // none during the timed steps: more than all of them
            match bed.rebuilds {
                0 => format!(">{}", steps * bed.rounds.len() as u64),
                r => format!("{:.0}", (steps * bed.rounds.len() as u64) as f64 / r as f64),
            },
            w.skin() / w.min_radius(),
            bed.rss_mb,
            bed.rss_mb * 1024.0 * 1024.0 / ns as f64
        );
        outln!("{:>153}", stages.join(", "));
    }
    if let (Some(small), Some(large)) = (costs.first(), costs.last()) {
        if costs.len() > 1 {
            let mut ratios: Vec<f64> = small.iter().zip(large).map(|(a, b)| b / a).collect();
            let shown: Vec<String> = ratios.iter().map(|r| format!("{r:.3}")).collect();
            ratios.sort_by(f64::total_cmp);
            outln!(
                "cost per sphere-step, largest bed / smallest, per round: {}; median {:.3}",
                shown.join(", "),
                ratios[ratios.len() / 2]
            );
        }
    }
    outln!("process peak RSS {:.0} MB", peak_rss_mb());
    Ok(())
}
