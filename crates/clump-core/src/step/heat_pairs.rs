//! The heat stage's sphere–sphere pass on several threads with one
//! thread's bits: each pair-list entry's conductance and heat flow (T-53 …
//! T-55) are computed in parallel, rows split between threads, each entry
//! written by its row only; the stage then adds them to the bodies in
//! pair-list order on one thread, so every sum meets the same terms in the
//! same order whatever the thread count.

use crate::heat::{harmonic_conductivity, pair_conductance, HeatModel};
use crate::par::affinity::{for_each_run, Balance};
use crate::par::shared::SharedMut;
use crate::world::World;

/// Marks an entry whose spheres do not touch (its sum adds nothing).
pub(super) const APART: f64 = -1.0;

/// Each pair-list entry's `(H, q)`: its conductance (W/K) and the heat
/// flow from its column sphere's body into its row sphere's (W), or
/// `(APART, 0)` where the spheres do not touch; into `out`, one per entry.
/// The rows are cut into one run per thread of the current pool, balanced
/// on their pair counts by `balance` (no allocation after the first call).
pub(super) fn pair_flows(
    w: &World,
    model: &HeatModel,
    out: &mut Vec<(f64, f64)>,
    balance: &mut Balance,
) {
    let pairs = &w.neighbors.pairs;
    let n = pairs.topo.len();
    if out.capacity() < n {
        // room to grow, so that a slowly growing list reallocates seldom
        out.reserve(n + n / 4 - out.len());
    }
    out.clear();
    out.resize(n, (APART, 0.0));
    let sp = &w.spheres;
    let temp = &w.bodies.temperature;
    let domain = &w.config.domain;
    let shared = SharedMut::new(out);
    let rows = &pairs.row_start;
    let cost = |c: usize| rows[c] as u64 + c as u64;
    for_each_run(sp.len(), cost, balance, |run| {
        for i in run {
            let (p0, p1) = (pairs.row_start[i] as usize, pairs.row_start[i + 1] as usize);
            let (xi, ri) = (sp.position(i), sp.state[i].radius);
            let ti = temp[sp.body[i] as usize];
            let ki = model.conductivity(sp.material[i]);
            for p in p0..p1 {
                let t = &pairs.topo[p];
                let j = t.j as usize;
                let mut xj = sp.position(j);
                if t.shift != [0; 3] {
                    xj -= domain.shift_vector(t.shift);
                }
                let rj = sp.state[j].radius;
                let dist = (xi - xj).length();
                if dist >= ri + rj {
                    continue;
                }
                let k = harmonic_conductivity(ki, model.conductivity(sp.material[j]));
                let h = pair_conductance(model.conductance, k, ri, rj, dist);
                let q = h * (temp[sp.body[j] as usize] - ti);
                // SAFETY: entry p belongs to row i only.
                unsafe { *shared.get(p) = (h, q) };
            }
        }
    });
}
