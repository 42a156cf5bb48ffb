//! Reductions over the ranks by a binomial tree: each rank's value goes up
//! to rank 0 in ⌈log₂ P⌉ rounds of point-to-point messages, every merge
//! folding the totals of the next ranks (higher, in rank order) into those
//! of the lower ones, and the total comes back down the same tree in
//! ⌈log₂ P⌉ more: every rank gets the same bits. Each rank's subtree holds
//! a run of consecutive ranks, so a merge that is associative (integer and
//! exact sums, maxima with ties to the lower rank, the first of the ranks)
//! gives what a fold in rank order gives, whatever the tree's shape.

use crate::partition::Comm;

/// A value reduced over the ranks by [`all_reduce`].
pub(crate) trait TreeSum: Sized {
    /// Its bytes, for a message.
    fn encode(&self) -> Vec<u8>;
    /// The value of [`TreeSum::encode`]'s bytes, from rank `from`.
    fn decode(b: &[u8], from: usize) -> Result<Self, String>;
    /// Folds `next`, the total of the ranks just above this one's, in.
    fn merge(&mut self, next: Self);
}

/// The total of every rank's `mine` (see the module's doc), on every rank.
pub(crate) fn all_reduce<T: TreeSum>(comm: &mut dyn Comm, mine: T) -> Result<T, String> {
    let mine = up(comm, mine, T::encode, |acc, b, from| {
        acc.merge(T::decode(b, from)?);
        Ok(())
    })?;
    down(comm, mine, T::encode, T::decode)
}

/// Up the tree to rank 0: `absorb(acc, bytes, from)` folds rank `from`'s
/// subtree total in. The total on rank 0; elsewhere the rank's partial
/// total, already sent up.
pub(crate) fn up<T>(
    comm: &mut dyn Comm,
    mut mine: T,
    encode: impl Fn(&T) -> Vec<u8>,
    mut absorb: impl FnMut(&mut T, &[u8], usize) -> Result<(), String>,
) -> Result<T, String> {
    let (me, size) = (comm.rank(), comm.size());
    let mut k = 1;
    while k < size {
        if me % (2 * k) == k {
            comm.exchange(&[(me - k, encode(&mine))], &[]);
            break;
        }
        if me % (2 * k) == 0 && me + k < size {
            let got = comm.exchange(&[], &[me + k]);
            absorb(&mut mine, &got[0], me + k)?;
        }
        k *= 2;
    }
    Ok(mine)
}

/// Rank 0's total down the same tree, from the highest level each rank
/// took part in: every rank returns it.
pub(crate) fn down<T>(
    comm: &mut dyn Comm,
    mut mine: T,
    encode: impl Fn(&T) -> Vec<u8>,
    decode: impl Fn(&[u8], usize) -> Result<T, String>,
) -> Result<T, String> {
    let (me, size) = (comm.rank(), comm.size());
    let mut k = size.next_power_of_two();
    while k > 1 {
        k /= 2;
        if me % (2 * k) == k {
            let got = comm.exchange(&[], &[me - k]);
            mine = decode(&got[0], me - k)?;
        } else if me % (2 * k) == 0 && me + k < size {
            comm.exchange(&[(me + k, encode(&mine))], &[]);
        }
    }
    Ok(mine)
}
