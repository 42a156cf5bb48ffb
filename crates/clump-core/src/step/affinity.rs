//! Chunk-to-thread affinity and balance for the per-step loops.
//!
//! Each per-step loop (first half step, pair forces, gather) runs over fixed
//! chunks of bodies or spheres. Work stealing would hand the same bodies to
//! different threads from one stage to the next, and every stage would then
//! pull their data from the other core's cache. Here each thread takes one
//! contiguous run of chunks per loop, cut where the estimated cost is
//! shared equally: the first half step and the gather use the same chunks
//! and the same cost, so a thread moves the bodies whose forces it gathers,
//! and the pair loop's runs cover nearly the same spheres (bodies and their
//! spheres are stored in the same Morton order). Only pairs across the seam
//! between two runs touch the other core's data.
//!
//! The results do not depend on the thread count or on the cuts: chunk
//! boundaries are fixed sizes, every chunk writes its own outputs, and every
//! reduction over chunks runs in chunk order afterwards.

/// Cost of the body chunks `0..c` of `chunk` bodies each, from the
/// cumulative per-body cost `body_cost` (`World::body_cost`, `nb + 1`
/// entries); one unit per body when that is out of date.
pub(crate) fn body_chunk_cost(
    body_cost: &[u64],
    nb: usize,
    chunk: usize,
) -> impl Fn(usize) -> u64 + Sync + '_ {
    let current = body_cost.len() == nb + 1;
    move |c| {
        let b = (c * chunk).min(nb);
        if current {
            body_cost[b]
        } else {
            b as u64
        }
    }
}

/// Calls `f(s, c)` for every chunk `c` in `0..n`, each exactly once, with
/// one `&mut` scratch value `s` per thread made by `init` (once per call and
/// thread). `cost(c)` is the estimated cost of chunks `0..c` (non-decreasing,
/// `cost(0) = 0`): the chunks are cut into as many contiguous runs as the
/// current rayon pool has threads, run `t` of `T` holding the chunks whose
/// cost falls in `[C t/T, C (t+1)/T)`, `C = cost(n)`; each run goes to one
/// thread, in order. On one thread it is a plain loop. No allocation.
pub(crate) fn for_each_chunk_with<S>(
    n: usize,
    cost: impl Fn(usize) -> u64 + Sync,
    init: impl Fn() -> S + Sync,
    f: impl Fn(&mut S, usize) + Sync,
) {
    let threads = rayon::current_num_threads();
    if threads <= 1 || n <= 1 {
        let mut s = init();
        (0..n).for_each(|c| f(&mut s, c));
        return;
    }
    let total = cost(n) as u128;
    // first chunk whose cost before it reaches the share of thread t
    let start = |t: usize, nt: usize| {
        let share = (total * t as u128 / nt as u128) as u64;
        let (mut lo, mut hi) = (0, n);
        while lo < hi {
            let mid = (lo + hi) / 2;
            if cost(mid) < share {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        lo
    };
    let start = |t: usize| if t == threads { n } else { start(t, threads) };
    run_parts(0, threads, &start, &init, &f);
}

/// Runs the runs of threads `t0..t1` (see [`for_each_chunk_with`]),
/// splitting the thread range in halves with `rayon::join` (which does not
/// allocate, unlike a broadcast): the calling thread keeps the first half and
/// an idle thread takes the second, so with two threads each keeps its run
/// from one loop to the next.
fn run_parts<S>(
    t0: usize,
    t1: usize,
    start: &(impl Fn(usize) -> usize + Sync),
    init: &(impl Fn() -> S + Sync),
    f: &(impl Fn(&mut S, usize) + Sync),
) {
    if t1 - t0 == 1 {
        let mut s = init();
        (start(t0)..start(t1)).for_each(|c| f(&mut s, c));
        return;
    }
    let mid = (t0 + t1) / 2;
    rayon::join(
        || run_parts(t0, mid, start, init, f),
        || run_parts(mid, t1, start, init, f),
    );
}
