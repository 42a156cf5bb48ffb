//! Reductions of byte-encoded partial results over the ranks by a binomial
//! tree (point-to-point messages, ⌈log₂ P⌉ rounds up to rank 0 and, for
//! [`World::all_reduce`], as many back down): for outputs whose partial
//! results combine exactly (integer or fixed-point sums, maxima), so the
//! tree's shape changes no bit. The caller gives the merge.

use crate::partition::Comm;
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
        merge: &dyn Fn(&mut Vec<u8>, &[u8], usize) -> Result<(), String>,
    ) -> Result<Option<Vec<u8>>, String> {
        let Some(p) = self.part.as_mut() else {
            return Ok(Some(mine));
        };
        p.traffic.reductions += 1;
        let acc = up(&mut *p.comm, mine, merge)?;
        Ok((p.comm.rank() == 0).then_some(acc))
    }

    /// Every rank's `mine` merged, on every rank (a collective call; see
    /// [`World::reduce_to_root`]).
    pub fn all_reduce(
        &mut self,
        mine: Vec<u8>,
        merge: &dyn Fn(&mut Vec<u8>, &[u8], usize) -> Result<(), String>,
    ) -> Result<Vec<u8>, String> {
        let Some(p) = self.part.as_mut() else {
            return Ok(mine);
        };
        p.traffic.reductions += 1;
        let comm = &mut *p.comm;
        let mut acc = up(comm, mine, merge)?;
        let (me, size) = (comm.rank(), comm.size());
        // down the same tree: from the highest level each rank took part in
        let mut k = size.next_power_of_two();
        while k > 1 {
            k /= 2;
            if me % (2 * k) == k {
                acc = comm.exchange(&[], &[me - k]).swap_remove(0);
            } else if me % (2 * k) == 0 && me + k < size {
                comm.exchange(&[(me + k, acc.clone())], &[]);
            }
        }
        Ok(acc)
    }
}

/// Up the binomial tree to rank 0: the merged result on rank 0, a partial
/// one (already sent) elsewhere.
fn up(comm: &mut dyn Comm, mut acc: Vec<u8>, merge: Merge) -> Result<Vec<u8>, String> {
    let (me, size) = (comm.rank(), comm.size());
    let mut k = 1;
    while k < size {
        if me % (2 * k) == k {
            comm.exchange(&[(me - k, acc.clone())], &[]);
            break;
        }
        if me % (2 * k) == 0 && me + k < size {
            let got = comm.exchange(&[], &[me + k]);
            merge(&mut acc, &got[0], me + k)?;
        }
        k *= 2;
    }
    Ok(acc)
}
