//! `clump bench`: the shared tetra-bed benchmark (../shared/bench/tetra-bed),
//! timed phase by phase, optionally side by side with LIGGGHTS; with
//! `--case stone-pile | stone-bed` the stone benchmarks of [`stone`].
//!
//! The case: 4-sphere tetrahedral clumps (r = 1 mm, edge 1.2 mm, ρ = 2500)
//! fall from a common initial condition into a 40 × 40 mm box and settle;
//! Hertz–Mindlin with history, E = 5e6, ν = 0.3, e = 0.5, μ = 0.5, LIGGGHTS'
//! damping law and unclamped (tensile) normal force as LIGGGHTS' default
//! `limitForce off` (for a like-for-like comparison), dt = 1e-5. Phase A (fall and
//! settle) and phase B (dense bed) are timed separately; throughput is
//! spheres × steps / wall seconds.

mod measure;
mod round;
mod scaling;
mod stone;

use measure::{build_world, Figures};

use anyhow::{bail, Result};
use clap::Args;
use measure::{report, run_liggghts, scenario_path, which};
use std::path::PathBuf;

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
    #[arg(long, default_value_t = stone::PILE_SEED)]
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
    /// Where Clump's step runs. `gpu`: the world of `--scenario` (e.g.
    /// benches/tetra_bed_2000.toml), else a box bed of about `--n` tetra
    /// clumps, `--nb` steps (default 1000) on the device and on the CPU
    /// path, sphere-steps/s of both and their largest position difference
    /// (needs the `gpu` feature).
    #[arg(long, value_enum, default_value_t = crate::device::Device::Cpu)]
    pub device: crate::device::Device,
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
    /// `round`).
    #[arg(long, hide = true)]
    pub child_round: bool,
}

/// Runs the benchmark.
pub fn run(args: &BenchArgs) -> Result<()> {
    if args.threads == 0 {
        bail!("--threads: the bench needs at least 1 thread (got 0)");
    }
    if args.child_round {
        return round::child(args);
    }
    if !args.scaling.is_empty() {
        return scaling::scaling(args);
    }
    if args.device == crate::device::Device::Gpu {
        // with --scenario, its world (e.g. the shared tetra bed); else the
        // box bed of clump_gpu::bed with about --n clumps
        let world = match &args.scenario {
            Some(_) => Some(build_world(&scenario_path(args), args.skin)?.0),
            None => None,
        };
        return crate::device::bench(args.n, args.nb.unwrap_or(1000), args.threads, world);
    }
    match args.case {
        Case::Tetra => {}
        Case::StonePile => return stone::run(args, stone::StoneCase::Pile),
        Case::StoneBed => return stone::run(args, stone::StoneCase::Bed),
        Case::StoneMix => return stone::run(args, stone::StoneCase::Mix),
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
        let f = round::run(&round::Round {
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
