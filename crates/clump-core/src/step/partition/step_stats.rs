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
        return Err(format!(
            "step statistics of {} sums, not {}",
            t.sums.len(),
            3 + 6 * nw
        ));
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::partition::ThreadComm;

    /// Rank `r`'s share: an energy whose `f64` fold in rank order loses its
    /// small term, an overlap tie between ranks 1 and 3, a body not finite
    /// on ranks 2 and 4, a stop request on the last rank.
    fn share(r: usize, n: usize) -> StepTotals {
        // 1 on rank 0, then +1e17, −1e17, … : a fold in rank order loses the 1
        let big = match r {
            0 => 1.0,
            r if r % 2 == 1 => 1e17,
            _ => -1e17,
        };
        let e = |x: f64| {
            let mut s = ExactSum::new();
            s.add(x);
            s
        };
        let last = r == n - 1;
        StepTotals {
            stats: ContactStats {
                pair_contacts: r as u64 + 1,
                max_overlap_ratio: if r == 1 || r == 3 { 0.5 } else { 0.1 },
                max_overlap_bodies: [r as u64, 0],
                non_finite_body: if r == 2 || r == 4 { r as u64 } else { 0 },
                ..ContactStats::default()
            },
            sums: vec![e(big), e(1.0)],
            stop: last,
        }
    }

    #[test]
    fn the_tree_gives_exact_sums_and_a_rank_order_fold_s_maxima_on_1_to_6_ranks() {
        for n in 1..=6 {
            let handles: Vec<_> = ThreadComm::group(n)
                .into_iter()
                .enumerate()
                .map(|(r, mut c)| std::thread::spawn(move || all_reduce(&mut c, share(r, n))))
                .collect();
            for h in handles {
                let t = h.join().unwrap().unwrap();
                // the ±1e17 cancel in pairs; an unpaired one leaves 1e17 + 1
                let first = if n % 2 == 1 { 1.0 } else { 1e17 };
                assert_eq!(t.sums[0].value(), first, "{n} ranks");
                assert_eq!(t.sums[1].value(), n as f64, "{n} ranks");
                assert_eq!(t.stats.pair_contacts, (n * (n + 1) / 2) as u64);
                let tie = if n > 1 { (0.5, 1) } else { (0.1, 0) };
                assert_eq!(t.stats.max_overlap_ratio, tie.0);
                assert_eq!(
                    t.stats.max_overlap_bodies[0], tie.1,
                    "the lower rank's on a tie"
                );
                assert_eq!(t.stats.non_finite_body, if n > 2 { 2 } else { 0 });
                assert!(t.stop);
            }
        }
    }
}
