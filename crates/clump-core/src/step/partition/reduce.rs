//! Reductions of byte-encoded partial results over the ranks by the
//! binomial tree of [`super::tree`] (⌈log₂ P⌉ rounds up to rank 0 and, for
//! [`World::all_reduce`], as many back down): for outputs whose partial
//! results combine exactly (integer or fixed-point sums, maxima), so the
//! tree's shape changes no bit. The caller gives the merge.

use super::tree::{down, up};
use crate::world::World;

/// Merges a partial result received from rank `from` (the third
/// argument) into the first.
type Merge<'a> = &'a dyn Fn(&mut Vec<u8>, &[u8], usize) -> Result<(), String>;

impl World {
    /// Every rank's `mine` merged on rank 0 (a collective call): `Some` on
    /// rank 0, `None` on the others; `Some(mine)` on a world not split over
    /// ranks. `merge(acc, theirs, from)` merges rank `from`'s partial
    /// result into `acc`.
    pub fn reduce_to_root(
        &mut self,
        mine: Vec<u8>,
        merge: Merge,
    ) -> Result<Option<Vec<u8>>, String> {
        let Some(p) = self.part.as_mut() else {
            return Ok(Some(mine));
        };
        p.traffic.reductions += 1;
        let acc = up(&mut *p.comm, mine, Vec::clone, merge)?;
        Ok((p.comm.rank() == 0).then_some(acc))
    }

    /// Every rank's `mine` merged, on every rank (a collective call; see
    /// [`World::reduce_to_root`]).
    pub fn all_reduce(&mut self, mine: Vec<u8>, merge: Merge) -> Result<Vec<u8>, String> {
        let Some(p) = self.part.as_mut() else {
            return Ok(mine);
        };
        p.traffic.reductions += 1;
        let comm = &mut *p.comm;
        let acc = up(comm, mine, Vec::clone, merge)?;
        down(comm, acc, Vec::clone, |b, _| Ok(b.to_vec()))
    }
}
