//! The statistics of a rank's step (the health check's input: counts,
//! energies, mass, the largest overlap and the most energetic body, the
//! first body not finite) and its wall loads, summed over the ranks by the
//! binomial tree of [`super::tree`]: the counts as integers, the energies,
//! mass and loads as exact sums of the ranks' partial sums (T-73's
//! accumulator, rounded once), the maxima and the first body not finite
//! as a fold in rank order would give them. The total is the same on every
//! rank and does not depend on the tree's shape. The ranks' stop requests
//! ride along (`Part::stop`).
//!
//! One message of about 100 B plus 25 B per sum goes up and one down per
//! rank and step (2⌈log₂ P⌉ rounds in all), where an all-gather sent every
//! rank's 170 B to every rank.

use super::tree::{all_reduce, TreeSum};
use crate::exact_sum::ExactSum;
use crate::stats::ContactStats;
use crate::wall::WallLoad;
use crate::world::World;
use glam::DVec3;

/// A rank's (or a run of ranks') share of a step's statistics.
struct StepTotals {
    /// Counts and maxima; its float sums are replaced by `sums`.
    stats: ContactStats,
    /// The elastic and kinetic energies, the mass, then per wall its force
    /// and torque components (world frame).
    sums: Vec<ExactSum>,
    /// A stop request of any of these ranks.
    stop: bool,
}

impl TreeSum for StepTotals {
    fn encode(&self) -> Vec<u8> {
        let sums: Vec<Vec<u8>> = self.sums.iter().map(ExactSum::to_compact).collect();
        postcard::to_stdvec(&(&self.stats, self.stop, sums)).unwrap_or_default()
    }

    fn decode(b: &[u8], from: usize) -> Result<Self, String> {
        let bad = |e: String| format!("rank {from} sent unreadable step statistics: {e}");
        let (stats, stop, sums): (ContactStats, bool, Vec<Vec<u8>>) =
            postcard::from_bytes(b).map_err(|e| bad(e.to_string()))?;
        let sums = sums
            .iter()
            .map(|c| match ExactSum::from_compact(c) {
                Some((s, n)) if n == c.len() => Ok(s),
                _ => Err(bad("a sum of another form".into())),
            })
            .collect::<Result<_, _>>()?;
        Ok(StepTotals { stats, stop, sums })
    }

    fn merge(&mut self, next: Self) {
        self.stats.merge(&next.stats);
        self.sums
            .iter_mut()
            .zip(&next.sums)
            .for_each(|(a, b)| a.merge(b));
        self.stop |= next.stop;
    }
}

/// Replaces this rank's statistics and wall loads (of its owned bodies and
/// of the pairs in their rows) by their totals over the ranks, and records
/// the ranks' stop requests or-ed. A message that cannot be read (ranks of
/// different builds) is an error.
pub(crate) fn reduce(w: &mut World) -> Result<(), String> {
    let part = w.part.as_mut().expect("a partitioned world");
    let s = &w.stats;
    let mut sums: Vec<ExactSum> = [s.elastic_energy, s.kinetic_energy, s.total_mass]
        .into_iter()
        .map(|x| {
            let mut e = ExactSum::new();
            e.add(x);
            e
        })
        .collect();
    for l in &w.walls.loads {
        for x in l.force.to_array().into_iter().chain(l.torque.to_array()) {
            let mut e = ExactSum::new();
            e.add(x);
            sums.push(e);
        }
    }
    let mine = StepTotals {
        stats: w.stats.clone(),
        sums,
        stop: part.stop.0,
    };
    part.traffic.reductions += 1;
    let t = all_reduce(&mut *part.comm, mine)?;
    let nw = w.walls.loads.len();
    if t.sums.len() != 3 + 6 * nw {
        return Err(format!("step statistics of {} sums, not {}", t.sums.len(), 3 + 6 * nw));
    }
    part.stop.1 = Some(t.stop);
    let v: Vec<f64> = t.sums.iter().map(ExactSum::value).collect();
    w.stats = ContactStats {
        elastic_energy: v[0],
        kinetic_energy: v[1],
        total_mass: v[2],
        ..t.stats
    };
    for (l, c) in w.walls.loads.iter_mut().zip(v[3..].chunks_exact(6)) {
        *l = WallLoad {
            force: DVec3::new(c[0], c[1], c[2]),
            torque: DVec3::new(c[3], c[4], c[5]),
        };
    }
    Ok(())
}
