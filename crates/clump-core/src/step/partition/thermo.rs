//! The thermo row of a world split over ranks, without the whole world:
//! each rank's exact partial sums (its owned bodies' energies, its counted
//! contacts' elastic energy and wall loads, [`crate::exact_sum`]) and body
//! count are summed over the ranks by a binomial tree (2 ⌈log₂ P⌉ rounds
//! of point-to-point messages of about 0.6 kB per sum), and every rank
//! rounds the same exact totals: one process's row, bit for bit (T-73).
//! The step's counts and largest overlap are already the ranks' sums and
//! maximum (`super::step_stats::reduce`: integers and a maximum, exact in any
//! order).

use super::tree::{all_reduce, TreeSum};
use crate::exact_sum::ExactSum;
use crate::partition::Comm;
use crate::thermo::Thermo;
use crate::world::World;

impl World {
    /// The thermo row of this rank's world (a collective call on a split
    /// world: every rank makes it and gets the same row); [`World::thermo`]
    /// on a whole one. An error when the split world's last step made no
    /// exact sums. With heat or a fluid, the temperature and heat sums and
    /// the fluid force are exact sums over the owned bodies too, the
    /// lowest and highest temperature a minimum and maximum over the ranks,
    /// the walls' heat flows every rank's already (T-94).
    pub fn thermo_of_ranks(&mut self) -> Result<Thermo, String> {
        if !self.is_split() {
            return Ok(self.thermo());
        }
        let Some((elastic, walls)) = self.neighbors.records.sums.at_step(self.step) else {
            return Err(format!(
                "the step that ended at {} made no exact sums for the thermo row",
                self.step
            ));
        };
        let owned = &self.part.as_ref().expect("a split world").owned;
        let count = owned.iter().filter(|&&o| o).count() as u64;
        let mut sums = self.body_energy_sums(Some(owned)).to_vec();
        sums.push(elastic);
        let n_walls = walls.len();
        sums.extend(walls.iter().flatten());
        let mut extra = self.body_extra_sums(Some(owned));
        sums.extend(extra.sums.iter().cloned());
        let part = self.part.as_mut().expect("a split world");
        part.traffic.reductions += 1;
        let (sums, count) = all_sum(&mut *part.comm, sums, count)?;
        let k = 4 + 6 * n_walls;
        extra.sums = std::array::from_fn(|i| sums[k + i].clone());
        if self.heat.is_some() {
            (extra.lo, extra.hi) = temperature_range(self, extra.lo, extra.hi)?;
        }
        let mut t = self.thermo();
        t.bodies = count as usize;
        t.kinetic_translational = sums[0].value();
        t.kinetic_rotational = sums[1].value();
        t.potential = sums[2].value();
        t.elastic = sums[3].value();
        t.heat = self.heat_thermo_of(&extra, count);
        t.fluid_force = self.fluid_force_of(&extra);
        let walls: Vec<_> = sums[4..k]
            .chunks_exact(6)
            .map(|c| std::array::from_fn(|k| c[k]))
            .collect();
        t.wall_loads = crate::contact::step_sums::wall_loads(&walls);
        Ok(t)
    }
}

/// A list of exact sums and a count, summed over the ranks.
struct Sums(Vec<ExactSum>, u64);

/// The lowest and highest temperature over the ranks (every rank's `lo`
/// and `hi`, reduced up and down a binomial tree: exact in any order).
fn temperature_range(w: &mut World, lo: f64, hi: f64) -> Result<(f64, f64), String> {
    let bytes = [lo.to_le_bytes(), hi.to_le_bytes()].concat();
    let pair = |b: &[u8]| -> Option<(f64, f64)> {
        let lo = f64::from_le_bytes(b.get(..8)?.try_into().ok()?);
        Some((lo, f64::from_le_bytes(b.get(8..16)?.try_into().ok()?)))
    };
    let merge = |acc: &mut Vec<u8>, theirs: &[u8], from: usize| -> Result<(), String> {
        let bad = || {
            format!(
                "rank {from} sent a temperature range of {} bytes",
                theirs.len()
            )
        };
        let ((a, b), (c, d)) = (pair(acc).ok_or_else(bad)?, pair(theirs).ok_or_else(bad)?);
        *acc = [a.min(c).to_le_bytes(), b.max(d).to_le_bytes()].concat();
        Ok(())
    };
    let all = w.all_reduce(bytes, &merge)?;
    pair(&all).ok_or_else(|| "a temperature range of the wrong size".into())
}

impl TreeSum for Sums {
    fn encode(&self) -> Vec<u8> {
        let mut b = self.1.to_le_bytes().to_vec();
        self.0.iter().for_each(|s| b.extend(s.to_bytes()));
        b
    }

    fn decode(b: &[u8], from: usize) -> Result<Self, String> {
        let bad = || format!("rank {from} sent a thermo sum of {} bytes", b.len());
        let size = crate::exact_sum::LIMBS * 8 + 1;
        if b.len() < 8 || (b.len() - 8) % size != 0 {
            return Err(bad());
        }
        let count = u64::from_le_bytes(b[..8].try_into().map_err(|_| bad())?);
        let sums = b[8..]
            .chunks_exact(size)
            .map(|c| ExactSum::from_bytes(c).ok_or_else(bad))
            .collect::<Result<_, _>>()?;
        Ok(Sums(sums, count))
    }

    fn merge(&mut self, next: Self) {
        self.0.iter_mut().zip(&next.0).for_each(|(a, b)| a.merge(b));
        self.1 += next.1;
    }
}

/// The element-wise total of every rank's `sums` and `count`, on every
/// rank, by a binomial tree. Exact sums: the tree's shape changes no bit.
fn all_sum(
    comm: &mut dyn Comm,
    sums: Vec<ExactSum>,
    count: u64,
) -> Result<(Vec<ExactSum>, u64), String> {
    let n = sums.len();
    let t = all_reduce(comm, Sums(sums, count))?;
    if t.0.len() != n {
        return Err(format!("a thermo sum of {} values, not {n}", t.0.len()));
    }
    Ok((t.0, t.1))
}
