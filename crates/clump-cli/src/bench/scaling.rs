//! `clump bench --scaling`: the cost per sphere-step of dense beds of
//! several sizes, timed in alternation.

use super::measure::{cpu_seconds, current_rss_mb, peak_rss_mb};
use super::BenchArgs;
use anyhow::{bail, Result};
use std::time::Instant;

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
    /// CPU seconds (user + system, all threads) of each round: on a shared
    /// machine whose cores other tenants' processes take turns on, the
    /// wall time also counts the turns of the others.
    cpu: Vec<f64>,
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
pub(super) fn scaling(args: &BenchArgs) -> Result<()> {
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
                cpu: Vec::new(),
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
                let mut cpu = 0.0;
                for rep in 0..bed.reps {
                    if let (Some(s), true) = (&saved, rep > 0) {
                        w.restore_state(s.clone()).map_err(|e| anyhow::anyhow!(e))?;
                    }
                    // a few untimed steps first: the bed's data back in the
                    // caches after the other beds' turns (and the lists
                    // rebuilt after a restore)
                    w.run(SCALING_WARM_STEPS)?;
                    w.stage_times = Default::default();
                    let (t0, c0, r0) = (Instant::now(), cpu_seconds(), w.rebuilds);
                    w.run(args.steps)?;
                    secs += t0.elapsed().as_secs_f64();
                    cpu += cpu_seconds() - c0;
                    times += w.stage_times;
                    bed.rebuilds += w.rebuilds - r0;
                }
                bed.rounds.push((secs, times));
                bed.cpu.push(cpu);
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
    let (mut costs, mut cpu_costs, mut stage_costs) = (Vec::new(), Vec::new(), Vec::new());
    for bed in beds.iter_mut() {
        let w = &bed.world;
        let ns = w.spheres().len();
        let steps = args.steps * bed.reps;
        let per = 1e9 / (ns as f64 * steps as f64);
        costs.push(bed.rounds.iter().map(|r| r.0 * per).collect::<Vec<_>>());
        cpu_costs.push(bed.cpu.iter().map(|c| c * per).collect::<Vec<_>>());
        stage_costs.push(cpu_by_stage(&bed.rounds, &bed.cpu, per));
        bed.rounds.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (best, times) = bed.rounds[0];
        let median = bed.rounds[bed.rounds.len() / 2].0;
        let stages = times.rows().map(|(_, t)| format!("{:.1}", t * per));
        let rate = ns as f64 * steps as f64 / best;
        outln!(
            "{:>9} {:>8} {:>20} {:>12} {:>14.3} {:>11.1} {:>13.1} {:>12.2} {:>13} {:>7.3} {:>9.0} {:>13.0}",
            ns,
            w.bodies().len(),
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
        let cpu: Vec<String> = bed.cpu.iter().map(|c| format!("{:.1}", c * per)).collect();
        outln!(
            "{:>9} CPU ns/sph-step (all threads) per round: {}",
            "",
            cpu.join(", ")
        );
        let split = stage_costs.last().map_or(Vec::new(), |rounds| {
            (0..4)
                .map(|s| format!("{:.1}", median_of(rounds.iter().map(|r| r[s]))))
                .collect()
        });
        outln!(
            "{:>9} CPU ns/sph-step by stage (each round's CPU time split as its stage wall times), median over rounds: {}",
            "",
            split.join(", ")
        );
    }
    ratio_line("wall", &costs);
    ratio_line("CPU", &cpu_costs);
    for (s, name) in [(2, "pair stage"), (3, "gather")] {
        let of_stage: Vec<Vec<f64>> = stage_costs
            .iter()
            .map(|rounds| rounds.iter().map(|r| r[s]).collect())
            .collect();
        ratio_line(&format!("CPU ({name})"), &of_stage);
    }
    outln!("process peak RSS {:.0} MB", peak_rss_mb());
    Ok(())
}

/// Each round's CPU ns per sphere-step split over the four stages (initial,
/// neighbour, pair, gather) in the proportions of the round's stage wall
/// times: the stages keep their own CPU clock only at a syscall per lap, and
/// the other tenants' turns on a shared core fall on the stages in
/// proportion to their length, so the split estimates each stage's CPU time.
fn cpu_by_stage(
    rounds: &[(f64, clump_core::stats::StageTimes)],
    cpu: &[f64],
    per: f64,
) -> Vec<[f64; 4]> {
    rounds
        .iter()
        .zip(cpu)
        .map(|((_, times), c)| {
            let rows = times.rows().map(|(_, t)| t);
            let total: f64 = rows.iter().sum();
            rows.map(|t| {
                if total > 0.0 {
                    c * per * t / total
                } else {
                    0.0
                }
            })
        })
        .collect()
}

/// The median of `xs` (the upper one of an even count); 0 when empty.
fn median_of(xs: impl Iterator<Item = f64>) -> f64 {
    let mut v: Vec<f64> = xs.collect();
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

/// The cost per sphere-step of the largest bed over the smallest's, round
/// by round, and their median, from `costs` (per bed, per round).
fn ratio_line(what: &str, costs: &[Vec<f64>]) {
    if let (Some(small), Some(large)) = (costs.first(), costs.last()) {
        if costs.len() > 1 {
            let mut ratios: Vec<f64> = small.iter().zip(large).map(|(a, b)| b / a).collect();
            let shown: Vec<String> = ratios.iter().map(|r| format!("{r:.3}")).collect();
            ratios.sort_by(f64::total_cmp);
            outln!(
                "{what} cost per sphere-step, largest bed / smallest, per round: {}; median {:.3}",
                shown.join(", "),
                ratios[ratios.len() / 2]
            );
        }
    }
}
