//! The cost of a body for the balance of the ranks' regions: counted, not
//! timed, so that the regions are a function of the state and the same on
//! every rank and every run. A body costs its spheres (the gather, the
//! first half: 22 ns a sphere-step) and the candidate pairs of its spheres
//! in the last build's list (the pair stage: 26 ns a sphere-step at 1.15
//! candidate pairs a sphere, so 23 ns a pair, half of it to each of the
//! pair's two bodies), the one-thread stage costs
//! of the settled tetra bed in docs/performance.md ("Where the time
//! goes"). A bed whose density varies (a heap, a half-filled box) then has
//! regions of even work rather than of even sphere counts.

use crate::world::World;

/// Cost of a sphere, half-ns a step.
pub(crate) const SPHERE_COST: u32 = 44;
/// Cost of a candidate pair to each of its two bodies, half-ns a step
/// (a pair is evaluated once: half of its 23 ns goes to each body).
pub(crate) const PAIR_END_COST: u32 = 23;

/// Per body of `w`, its cost: `SPHERE_COST` a sphere and `PAIR_END_COST`
/// a candidate pair of one of its spheres in the current pair list (each
/// pair counted for both its bodies). A list that was built for other spheres
/// (its rows do not match them, after bodies were added or removed) is
/// not counted: the spheres alone then.
pub(crate) fn body_costs(w: &World) -> Vec<u32> {
    let first = &w.spheres.body_first;
    let nb = first.len().saturating_sub(1);
    let ns = w.spheres.len();
    let mut pairs = vec![0u32; nb];
    let p = &w.neighbors.pairs;
    let body = &w.spheres.body;
    if p.row_start.len() == ns + 1 && body.len() == ns {
        for i in 0..ns {
            let row = p.row_start[i] as usize..p.row_start[i + 1] as usize;
            for t in p.topo.get(row).unwrap_or(&[]) {
                pairs[body[i] as usize] += 1;
                if let Some(&bj) = body.get(t.j as usize) {
                    pairs[bj as usize] += 1;
                }
            }
        }
    }
    (0..nb)
        .map(|b| SPHERE_COST * (first[b + 1] - first[b]) + PAIR_END_COST * pairs[b])
        .collect()
}
