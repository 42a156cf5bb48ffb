//! One candidate pair's topology in the half list: its partner, periodic
//! image, live flag and the step from the previous pair's row to its own.
//!
//! The pair kernel walks a thread's pairs in one flat loop (a loop per row
//! would end, after a varying 0–4 candidates, in a mispredicted branch per
//! sphere), so it needs each pair's row `i`. A stored `u32` row per pair
//! would add 4 bytes to the 8 a candidate streams in the detect pass.
//! Instead the row follows from the previous pair's by a step of 0 to 126
//! kept in the spare bits of the flag byte (`RowWalk`); a longer step (a
//! run of more than a hundred spheres without candidates, as in a dilute
//! gas) is looked up in the row offsets.

/// The partner of one pair in sphere `i`'s row of the half list (8 bytes:
/// the pair kernel's detect pass reads only this for the common
/// non-touching pair).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairTopo {
    /// Sphere index of the partner, `j > i` in storage order.
    pub j: u32,
    /// Periodic image shift: the separation is `x_i − x_j + shift·L`.
    pub shift: [i8; 3],
    /// Bit 7: live ([`PairTopo::live`]). Bits 0–6: the row step
    /// ([`set_row_steps`]).
    flags: u8,
}

/// The live bit of [`PairTopo::flags`].
const LIVE: u8 = 0x80;

/// The row-step bits of [`PairTopo::flags`]; a step of this value or more
/// is stored as this value and looked up ([`RowWalk::next`]).
const FAR: u8 = 0x7f;

impl PairTopo {
    /// A pair with partner `j` across the periodic image `shift`, not live.
    #[inline(always)]
    pub fn new(j: u32, shift: [i8; 3]) -> Self {
        PairTopo { j, shift, flags: 0 }
    }

    /// The pair touched at its last evaluation, or its history was restored
    /// (checkpoint or rebuild) and it has not been evaluated since: its
    /// history and `j`-side load may be non-zero and must be cleared when it
    /// is found not touching.
    #[inline(always)]
    pub fn live(self) -> bool {
        self.flags & LIVE != 0
    }

    /// Sets the live flag.
    #[inline(always)]
    pub fn set_live(&mut self, live: bool) {
        self.flags = (self.flags & !LIVE) | ((live as u8) << 7);
    }

    /// The row step, `FAR` when it has to be looked up.
    #[inline(always)]
    fn row_step(self) -> u8 {
        self.flags & FAR
    }
}

/// Writes each pair's row step: its row minus the previous pair's (the
/// first pair's: minus row 0), or [`FAR`] from 127 on. `topo` holds the
/// rows `row_start` describes, in order.
pub(crate) fn set_row_steps(row_start: &[u32], topo: &mut [PairTopo]) {
    let mut prev = 0usize;
    for i in 0..row_start.len().saturating_sub(1) {
        for t in &mut topo[row_start[i] as usize..row_start[i + 1] as usize] {
            let step = (i - prev).min(FAR as usize) as u8;
            t.flags = (t.flags & LIVE) | step;
            prev = i;
        }
    }
}

/// The row (sphere `i`) of pair `p`: the last row starting at or before
/// it (empty rows start where the next one does).
#[inline]
pub(crate) fn row_of(row_start: &[u32], p: usize) -> usize {
    debug_assert!(p < *row_start.last().unwrap_or(&0) as usize);
    row_start.partition_point(|&s| s as usize <= p) - 1
}

/// The rows of consecutive pairs, followed from their steps.
pub(crate) struct RowWalk<'a> {
    row_start: &'a [u32],
    /// The row of the pair last walked (before the first: that pair's row
    /// minus its step).
    i: usize,
}

impl<'a> RowWalk<'a> {
    /// A walk from the list's first pair.
    pub(crate) fn new(row_start: &'a [u32]) -> Self {
        RowWalk { row_start, i: 0 }
    }

    /// A walk whose first pair is `p`, whose topology is `t`.
    #[inline]
    pub(crate) fn at(row_start: &'a [u32], p: usize, t: PairTopo) -> Self {
        let i = match t.row_step() {
            FAR => 0,
            s => row_of(row_start, p) - s as usize,
        };
        RowWalk { row_start, i }
    }

    /// The row of pair `p` (with topology `t`), the pair after the one last
    /// walked (or the first).
    #[inline(always)]
    pub(crate) fn next(&mut self, p: usize, t: PairTopo) -> usize {
        self.i = match t.row_step() {
            FAR => row_of(self.row_start, p),
            s => self.i + s as usize,
        };
        debug_assert_eq!(self.i, row_of(self.row_start, p));
        self.i
    }
}

/// Leaves out of a list being built the pairs between two bodies that are
/// not `owned` (a rank's part: two ghosts, whose pair is evaluated by the
/// ranks that own them). `topo` holds the rows in order, row `i`'s count at
/// `counts[i]` (`body[i]` its body); both are compacted in place, the pairs
/// kept in their order. Returns the number of pairs left out.
pub(crate) fn keep_owned_pairs(
    counts: &mut [u32],
    topo: &mut Vec<PairTopo>,
    body: &[u32],
    owned: &[bool],
) -> usize {
    let (mut read, mut write) = (0usize, 0usize);
    for (i, count) in counts.iter_mut().enumerate() {
        let n = *count as usize;
        if owned[body[i] as usize] {
            topo.copy_within(read..read + n, write);
            write += n;
        } else {
            let start = write;
            for p in read..read + n {
                let t = topo[p];
                if owned[body[t.j as usize] as usize] {
                    topo[write] = t;
                    write += 1;
                }
            }
            *count = (write - start) as u32;
        }
        read += n;
    }
    topo.truncate(write);
    read - write
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows with 0–3 pairs, empty runs of up to 300 rows (past the longest
    /// stored step), and a list starting with empty rows: a walk from any
    /// pair finds every later pair's row as the offsets give it.
    #[test]
    fn walked_rows_are_the_offsets_rows() {
        let counts: Vec<u32> = (0..2000u32)
            .map(|i| match i {
                // steps of 126 (stored), 127 and 128 (looked up), 301
                0..=4 | 400..=524 | 1300..=1425 | 700..=826 | 900..=1199 => 0,
                399 | 525 | 1299 | 1426 | 699 | 827 | 899 | 1200 => 2,
                _ => (i * 7 + i / 3) % 4,
            })
            .collect();
        let mut row_start = vec![0u32];
        for c in &counts {
            row_start.push(row_start.last().unwrap() + c);
        }
        let np = *row_start.last().unwrap() as usize;
        let mut topo = vec![PairTopo::new(0, [0; 3]); np];
        for (p, t) in topo.iter_mut().enumerate() {
            t.set_live(p % 3 == 0);
        }
        set_row_steps(&row_start, &mut topo);
        // the steps keep the live flags, and use both encodings
        assert!(topo
            .iter()
            .enumerate()
            .all(|(p, t)| t.live() == (p % 3 == 0)));
        assert!(topo.iter().any(|t| t.row_step() == FAR));
        assert!(topo.iter().any(|t| t.row_step() == FAR - 1));
        let mut expected = Vec::new();
        for (i, &c) in counts.iter().enumerate() {
            expected.extend(std::iter::repeat(i).take(c as usize));
        }
        let mut walk = RowWalk::new(&row_start);
        for p in 0..np {
            assert_eq!(
                walk.next(p, topo[p]),
                expected[p],
                "pair {p} from the start"
            );
        }
        for p0 in (0..np).step_by(37).chain([np - 1]) {
            let mut walk = RowWalk::at(&row_start, p0, topo[p0]);
            for p in p0..np {
                assert_eq!(walk.next(p, topo[p]), expected[p], "pair {p} from {p0}");
            }
        }
    }

    /// Of rows of bodies owned and not, only the pairs between two bodies
    /// not owned go, the others keep their order.
    #[test]
    fn pairs_between_two_bodies_not_owned_are_left_out() {
        // spheres 0..6, bodies 0 0 1 1 2 3; bodies 1 and 3 not owned
        let body = [0u32, 0, 1, 1, 2, 3];
        let owned = [true, false, true, false];
        let rows: [&[u32]; 6] = [&[2, 4], &[3, 5], &[4, 5], &[4, 5], &[5], &[]];
        let mut counts: Vec<u32> = rows.iter().map(|r| r.len() as u32).collect();
        let mut topo: Vec<PairTopo> = rows
            .iter()
            .flat_map(|r| r.iter().map(|&j| PairTopo::new(j, [0; 3])))
            .collect();
        let out = keep_owned_pairs(&mut counts, &mut topo, &body, &owned);
        // spheres 2 and 3 (body 1) to sphere 5 (body 3): both not owned
        assert_eq!(out, 2);
        assert_eq!(counts, [2, 2, 1, 1, 1, 0]);
        let js: Vec<u32> = topo.iter().map(|t| t.j).collect();
        assert_eq!(js, [2, 4, 3, 5, 4, 4, 5]);
    }
}
