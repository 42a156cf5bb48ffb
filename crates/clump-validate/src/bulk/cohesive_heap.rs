//! Angle of repose of cohesive heaps: the tetra-clump heap of
//! [`super::repose`] (μ = 0.3, no rolling resistance) with JKR cohesion
//! between every pair of spheres, clump–pedestal included, at granular
//! Bond numbers Bo = F_pull / (m g): the JKR pull-off force of two of the
//! clumps' spheres, (3/2) π Γ R* with R* = R/2, over one clump's weight.
//! Published trend: the angle of repose rises with the interparticle
//! cohesion relative to the weight (Forsyth, Hutton & Rhodes 2001, with
//! magnetically cohesive beads; Nase, Vargas, Abatan & McCarthy 2001, by
//! DEM with the granular Bond number). World frame as in the repose case.

use super::repose::{heap, rises, HeapSpec, Stat, SEEDS};
use crate::case::{Case, Group};
use crate::plot::{draw, Chart, Series, Style};
use std::path::Path;

/// Sliding friction of every pair.
const MU: f64 = 0.3;
/// The Bond numbers of the series (0: the non-cohesive heap).
const BONDS: [f64; 4] = [0.0, 0.3, 1.0, 3.0];

/// The heap of Bond number `bond` and `seed`.
pub fn spec(bond: f64, seed: u64) -> HeapSpec {
    HeapSpec {
        bond,
        ..HeapSpec::new(MU, 0.0, seed)
    }
}

/// Runs the Bond-number series.
pub fn run(g: &mut Group, dir: &Path) -> Result<(), String> {
    let mut jobs: Vec<super::Job<_>> = Vec::new();
    for bond in BONDS {
        for seed in SEEDS {
            jobs.push(Box::new(move || heap(&spec(bond, seed))));
        }
    }
    let mut results = super::run_parallel(jobs).into_iter();
    let mut stats = Vec::new();
    let mut per_seed = Vec::new();
    for bond in BONDS {
        let heaps = (&mut results)
            .take(SEEDS.len())
            .collect::<Result<Vec<_>, String>>()?;
        stats.push(Stat::of(&heaps.iter().map(|h| h.angle).collect::<Vec<_>>()));
        per_seed.push(format!(
            "Bo {bond}: {}",
            heaps
                .iter()
                .map(|h| format!("{:.1}/{}/{}", h.angle, h.poured, h.clumps_left))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let (pass, steps) = rises(&stats);
    let measured: Vec<String> = BONDS
        .iter()
        .zip(&stats)
        .map(|(b, a)| format!("Bo {b}: {:.1} ± {:.1}°", a.mean, a.se))
        .collect();
    let s = spec(1.0, 1);
    g.cases.push(Case {
        name: format!(
            "cohesive tetra-clump heap on a rough pedestal (fixed base, r_p = {:.0} mm, μ = {MU}, JKR): angle of repose rises with the Bond number",
            s.pedestal_radius * 1e3
        ),
        source: "published trend (Forsyth, Hutton & Rhodes 2001; Nase et al. 2001: angle of repose vs cohesion over weight)".into(),
        expected: "strictly increasing".into(),
        measured: format!("{} (steps {steps})", measured.join(", ")),
        tolerance: format!(
            "each step > 2σ, σ = √(SE₁² + SE₂²), SE = standard error of the mean of {} seeds",
            SEEDS.len()
        ),
        pass,
    });
    g.notes.push(format!(
        "cohesive angle of repose: the repose case's heap (μ = {MU}, μ_r = 0, {} seeds) with JKR cohesion (Hertz law, work of adhesion Γ = Bo m g / ((3/4) π R) for every pair, clump–pedestal included: the pull-off force (3/2) π Γ R* of two spheres R = 1 mm, R* = R/2, is Bo times a clump's weight m g). Per seed, cone angle (deg) / clumps poured / clumps left on the pedestal: {}",
        SEEDS.len(),
        per_seed.join("; ")
    ));
    let c = Chart {
        title: "Angle of repose vs Bond number (tetra clumps, JKR)".into(),
        x_label: "Bond number Bo = F_pull / (m g)".into(),
        y_label: "angle of repose (deg), mean ± SE".into(),
        series: vec![Series::with_errors(
            format!("μ = {MU}, μ_r = 0"),
            BONDS
                .iter()
                .zip(&stats)
                .map(|(&b, a)| (b, a.mean))
                .collect(),
            stats.iter().map(|a| a.se).collect(),
            Style::LinePoints,
        )],
    };
    g.plot(
        "bulk_repose_cohesion.png",
        "Angle of repose of cohesive tetra-clump heaps (JKR) against the Bond number (mean ± standard error of 4 seeds)",
        draw(&dir.join("bulk_repose_cohesion.png"), &c),
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One heap per Bond number of `CLUMP_BONDS` (comma-separated, default
    /// the series), seed 1, for their cost and angle
    /// (`cargo test --release -p clump-validate cohesive_heap -- --ignored --nocapture`).
    #[test]
    #[ignore]
    fn one_cohesive_heap() {
        let bonds: Vec<f64> = std::env::var("CLUMP_BONDS").map_or(BONDS.to_vec(), |v| {
            v.split(',').map(|b| b.trim().parse().unwrap()).collect()
        });
        for bond in bonds {
            let t = std::time::Instant::now();
            let h = heap(&spec(bond, 1)).unwrap();
            eprintln!(
                "Bo {bond}: angle {:.1}°, {} poured, {} left, {} steps, {:.1} s",
                h.angle,
                h.poured,
                h.clumps_left,
                h.steps,
                t.elapsed().as_secs_f64()
            );
        }
    }
}
