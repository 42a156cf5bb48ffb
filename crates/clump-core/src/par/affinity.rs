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
//! spheres are stored in the same spatial order). Inside `World::run` the
//! pair stage and the gather share one cut ([`for_each_run_then`]), so a
//! thread gathers exactly the bodies whose rows it evaluated. Only pairs
//! across the seam between two runs touch the other core's data, and the
//! few gather chunks a thread done early takes from a run that has not
//! reached them (the end of a step's noise, which no learned share
//! foresees).
//!
//! The results do not depend on the thread count or on the cuts: chunk
//! boundaries are fixed sizes, every chunk writes its own outputs, and every
//! reduction over chunks runs in chunk order afterwards.

/// Index of the first half step's [`Balance`] in `World::balance`.
pub(crate) const INITIAL_LOOP: usize = 0;
/// Index of the pair loop's [`Balance`].
pub(crate) const PAIR_LOOP: usize = 1;
/// Index of the gather's [`Balance`].
pub(crate) const GATHER_LOOP: usize = 2;
/// Index of the [`Balance`] of the pair stage and the gather taken
/// together ([`for_each_run_then`]).
pub(crate) const FORCE_LOOP: usize = 3;
/// Index of the heat stage's pair loop's [`Balance`] (`step::heat_pairs`).
pub(crate) const HEAT_LOOP: usize = 4;
/// Number of [`Balance`]s, one per loop.
pub(crate) const LOOPS: usize = 5;

/// Spheres a body chunk aims at (see [`body_chunk`]).
const CHUNK_SPHERES: usize = 128;
/// Most bodies per chunk.
pub(crate) const MAX_BODY_CHUNK: usize = 32;

/// Bodies per chunk of the pair stage (the rows of their spheres), of the
/// gather and of the first half step, for clumps of up to `k` spheres:
/// about [`CHUNK_SPHERES`] spheres, at most [`MAX_BODY_CHUNK`] bodies (32
/// tetrahedra, 2 stones of 50 spheres). The threads' runs are cut at chunk
/// boundaries, so a chunk of 32 stones (1 600 spheres) left 200 stones in 7
/// chunks, which two threads cannot share evenly. Fixed by the templates,
/// never by the thread count, so that the chunked reductions of wall loads
/// and statistics are the same for any number of threads.
pub(crate) fn body_chunk(k: usize) -> usize {
    (CHUNK_SPHERES / k.max(1)).clamp(1, MAX_BODY_CHUNK)
}

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

/// How one per-step loop shares its chunks between threads: the fraction of
/// the estimated cost given to each run, learned from the time each run
/// took (a thread that also runs the serial parts of the step, or whose
/// chunks cost more than estimated, gets less). Only the cuts depend on it,
/// never the results.
#[derive(Debug, Default)]
pub(crate) struct Balance {
    /// Fraction of the cost per run (sums to 1).
    share: Vec<f64>,
    /// Wall time of each run in the last call, ns.
    time: Vec<std::sync::atomic::AtomicU64>,
    /// Per run: the number of the last call of [`for_each_run_then`] in
    /// which it has finished the first stage; a cache line each, as the
    /// other threads spin on it.
    done: Vec<Flag>,
    /// Per run: its chunks of the second stage of [`for_each_run_then`]
    /// not taken yet ([`take`]); a cache line each.
    left: Vec<Flag>,
    /// Per run: the cost units its thread got through in the last call of
    /// [`for_each_run_then`] (its own first stage, and the second stage of
    /// the chunks it took, its own or another run's).
    work: Vec<std::sync::atomic::AtomicU64>,
    /// Calls of [`for_each_run_then`] so far.
    call: u64,
}

/// An atomic on a cache line of its own (two, for the adjacent-line
/// prefetcher).
#[derive(Debug, Default)]
#[repr(align(128))]
struct Flag(std::sync::atomic::AtomicU64);

/// Most runs per loop (threads beyond this share the runs).
const MAX_RUNS: usize = 64;

/// Weight of the newest measurement in the running shares.
const BALANCE_GAIN: f64 = 0.2;

impl Balance {
    /// Makes room for `threads` runs (equal shares at first).
    fn reset(&mut self, threads: usize) {
        if self.share.len() != threads {
            self.share = vec![1.0 / threads as f64; threads];
            self.time = (0..threads)
                .map(|_| std::sync::atomic::AtomicU64::new(0))
                .collect();
            self.done = (0..threads).map(|_| Flag::default()).collect();
            self.left = (0..threads).map(|_| Flag::default()).collect();
            self.work = (0..threads)
                .map(|_| std::sync::atomic::AtomicU64::new(0))
                .collect();
        }
    }

    /// Moves the shares toward the cost each run got through per unit time.
    fn learn(&mut self, run_cost: impl Fn(usize) -> u64) {
        let mut rates = [0.0f64; MAX_RUNS];
        let mut sum = 0.0;
        for (r, rate) in rates.iter_mut().enumerate().take(self.share.len()) {
            let ns = self.time[r].load(std::sync::atomic::Ordering::Relaxed);
            *rate = run_cost(r) as f64 / ns as f64;
            // an empty or unmeasured run says nothing: keep the shares
            if !(*rate > 0.0 && rate.is_finite()) {
                return;
            }
            sum += *rate;
        }
        // no run drops below a quarter of an equal share (a run left empty
        // would never be measured again)
        let floor = 0.25 / self.share.len() as f64;
        for (s, r) in self.share.iter_mut().zip(rates) {
            *s = ((1.0 - BALANCE_GAIN) * *s + BALANCE_GAIN * r / sum).max(floor);
        }
        let total: f64 = self.share.iter().sum();
        self.share.iter_mut().for_each(|s| *s /= total);
    }
}

/// Calls `f(s, c)` for every chunk `c` in `0..n`, each exactly once, with
/// one `&mut` scratch value `s` per thread made by `init` (once per call and
/// thread), the chunks of a run in ascending order (see [`for_each_run`]).
/// On one thread it is a plain loop. No allocation after the first call.
pub(crate) fn for_each_chunk_with<S>(
    n: usize,
    cost: impl Fn(usize) -> u64 + Sync,
    balance: &mut Balance,
    init: impl Fn() -> S + Sync,
    f: impl Fn(&mut S, usize) + Sync,
) {
    for_each_run(n, cost, balance, |run| {
        let mut s = init();
        run.for_each(|c| f(&mut s, c));
    });
}

/// Whether [`for_each_run`] cuts `n` chunks into several runs in the
/// current rayon pool (else it makes the one run `0..n`).
pub(crate) fn several_runs(n: usize) -> bool {
    rayon::current_num_threads() > 1 && n > 1
}

/// Calls `f(run)` for contiguous runs of chunks that together cover `0..n`
/// once, one run per thread. `cost(c)` is the estimated cost of chunks
/// `0..c` (non-decreasing, `cost(0) = 0`): the chunks are cut into as many
/// runs as the current rayon pool has threads, run `t` holding the chunks
/// whose cost falls in its share of the total (see [`Balance`]). On one
/// thread it is `f(0..n)`. No allocation after the first call.
pub(crate) fn for_each_run(
    n: usize,
    cost: impl Fn(usize) -> u64 + Sync,
    balance: &mut Balance,
    f: impl Fn(std::ops::Range<usize>) + Sync,
) {
    if !several_runs(n) {
        f(0..n);
        return;
    }
    let (cuts, runs) = cut(n, &cost, balance);
    let cuts = &cuts[..=runs];
    let time = &balance.time;
    // one run per thread of the persistent team, or through rayon when the
    // team is busy with another world's loop
    let timed = |t: usize| {
        let clock = std::time::Instant::now();
        f(cuts[t]..cuts[t + 1]);
        time[t].store(
            clock.elapsed().as_nanos() as u64,
            std::sync::atomic::Ordering::Relaxed,
        );
    };
    if !super::team::run(runs, &timed) {
        run_parts(0, runs, &timed);
    }
    balance.learn(|r| cost(cuts[r + 1]) - cost(cuts[r]));
}

/// [`for_each_run_then`] on one thread: the `n` chunks in blocks of
/// `block` chunks, each through `first` and then through `then`, so that
/// the second stage of a chunk finds in the caches what the first stage
/// has just read and written of it (in a bed larger than the caches, the
/// whole run's first stage would have pushed it out). Returns the time
/// spent in `first`.
fn one_run_in_blocks<S>(
    n: usize,
    block: usize,
    first: impl Fn(std::ops::Range<usize>, std::ops::Range<usize>),
    init: impl Fn() -> S,
    then: impl Fn(&mut S, usize),
) -> std::time::Duration {
    let mut first_time = std::time::Duration::ZERO;
    let mut s = init();
    for c0 in (0..n).step_by(block.max(1)) {
        let block = c0..(c0 + block.max(1)).min(n);
        let clock = std::time::Instant::now();
        first(0..n, block.clone());
        first_time += clock.elapsed();
        block.for_each(|c| then(&mut s, c));
    }
    first_time
}

/// Two stages over the same runs of `n` chunks, one run per thread:
/// `first(run, run)`, then `then(scratch, c)` for each chunk `c` of the run
/// (the pair stage and the gather: `step::force`). A chunk's `then` may
/// read what the `first` of its own and earlier runs wrote, and write what
/// the `first` of earlier runs read only where `after_earlier(c)` says so
/// (asked on the thread whose `first` has just taken the chunk's run); it
/// never touches what the `first` of later runs touches. Each thread takes
/// its run through `first`, then through `then` from its last chunk down,
/// and waits for the `first` of the earlier runs only before the first
/// chunk that needs it: the chunks far from the seam with the earlier run
/// come first, and by the time the thread reaches the seam the earlier runs
/// are through their `first`. So the threads wait for each other once per
/// call, at its end, and the two stages share one cut, balanced on their
/// sum (`first_cost + then_cost`, each cumulative over chunks as for
/// [`for_each_run`]).
///
/// A thread done with its own chunks takes the chunks another run has
/// not reached yet, from the bottom of that run (its seam with the run
/// before), once the `first` of that run and of every earlier run is over
/// ([`take`]): the balance learned from the steps before cannot foresee
/// the noise of this one, and every chunk so taken shortens the wait at
/// the end. The order of the chunks and the thread that takes one change
/// no result: every chunk writes its own outputs. When the team is busy,
/// the runs go to rayon as two loops. Returns the time the calling thread
/// spent in `first` (for the stage times; on one thread, exactly the
/// first stage's).
///
/// On one thread the run is all `n` chunks, taken in blocks of
/// `one_run_block` chunks ([`one_run_in_blocks`]; `n` or more: the whole
/// run at once): `first(0..n, block)` for each block in order, each
/// followed by the `then` of its chunks. This
/// needs of the stages what the pair stage and the gather give: `first`
/// of a block completes what the `then` of its chunks read, and `then(c)`
/// touches nothing that the `first` of later blocks reads or writes.
#[allow(clippy::too_many_arguments)]
pub(crate) fn for_each_run_then<S>(
    n: usize,
    first_cost: impl Fn(usize) -> u64 + Sync,
    then_cost: impl Fn(usize) -> u64 + Sync,
    balance: &mut Balance,
    one_run_block: usize,
    first: impl Fn(std::ops::Range<usize>, std::ops::Range<usize>) + Sync,
    after_earlier: impl Fn(usize) -> bool + Sync,
    init: impl Fn() -> S + Sync,
    then: impl Fn(&mut S, usize) + Sync,
) -> std::time::Duration {
    use std::sync::atomic::{AtomicU64, Ordering};
    let start = std::time::Instant::now();
    if !several_runs(n) {
        return one_run_in_blocks(n, one_run_block, first, init, then);
    }
    let cost = |c: usize| first_cost(c) + then_cost(c);
    let (cuts, runs) = cut(n, &cost, balance);
    let cuts = &cuts[..=runs];
    balance.call += 1;
    let (done, call, time, work) = (&balance.done, balance.call, &balance.time, &balance.work);
    let left = &balance.left;
    for (t, l) in left.iter().enumerate().take(runs) {
        l.0.store(take::pack(cuts[t]..cuts[t + 1]), Ordering::Relaxed);
    }
    let first_time = AtomicU64::new(0);
    /// Marks a run's `first` finished when dropped, also when it panics
    /// (the team then reports the panic; no run may wait for ever).
    struct Done<'a>(&'a AtomicU64, u64);
    impl Drop for Done<'_> {
        fn drop(&mut self) {
            self.0.store(self.1, Ordering::Release);
        }
    }
    // the `first` of runs 0..=u is over
    let firsts_over = |u: usize| {
        done[..=u]
            .iter()
            .all(|d| d.0.load(Ordering::Acquire) == call)
    };
    let run = |t: usize| {
        let chunks = cuts[t]..cuts[t + 1];
        let clock = std::time::Instant::now();
        let mark = Done(&done[t].0, call);
        first(chunks.clone(), chunks.clone());
        drop(mark);
        let f = clock.elapsed();
        if t == 0 {
            first_time.store(f.as_nanos() as u64, Ordering::Relaxed);
        }
        let mut busy = f;
        let mut units = first_cost(chunks.end) - first_cost(chunks.start);
        let mut waited = t == 0;
        let mut s = init();
        let mut clock = std::time::Instant::now();
        while let Some(c) = take::top(&left[t].0) {
            if !waited && after_earlier(c) {
                busy += clock.elapsed();
                done[..t]
                    .iter()
                    .for_each(|d| super::team::wait_for(&d.0, call));
                waited = true;
                clock = std::time::Instant::now();
            }
            then(&mut s, c);
            units += then_cost(c + 1) - then_cost(c);
        }
        // the other runs' chunks not reached yet, the nearest runs first
        for u in (t + 1..runs).chain((0..t).rev()) {
            if !firsts_over(u) {
                continue;
            }
            while let Some(c) = take::bottom(&left[u].0) {
                then(&mut s, c);
                units += then_cost(c + 1) - then_cost(c);
            }
        }
        busy += clock.elapsed();
        time[t].store(busy.as_nanos() as u64, Ordering::Relaxed);
        work[t].store(units, Ordering::Relaxed);
    };
    if !super::team::run(runs, &run) {
        // rayon may run several runs one after another on one thread, and
        // a run's wait could then be for a run queued behind it
        time.iter().for_each(|t| t.store(0, Ordering::Relaxed));
        let timed = |t: usize, stage: &dyn Fn(std::ops::Range<usize>)| {
            let clock = std::time::Instant::now();
            stage(cuts[t]..cuts[t + 1]);
            time[t].fetch_add(clock.elapsed().as_nanos() as u64, Ordering::Relaxed);
        };
        run_parts(0, runs, &|t| timed(t, &|run| first(run.clone(), run)));
        first_time.store(start.elapsed().as_nanos() as u64, Ordering::Relaxed);
        run_parts(0, runs, &|t| {
            timed(t, &|chunks: std::ops::Range<usize>| {
                let mut s = init();
                chunks.for_each(|c| then(&mut s, c));
            })
        });
        for (t, w) in work.iter().enumerate().take(runs) {
            w.store(cost(cuts[t + 1]) - cost(cuts[t]), Ordering::Relaxed);
        }
    }
    let mut got = [0u64; MAX_RUNS];
    for (g, w) in got.iter_mut().zip(work) {
        *g = w.load(Ordering::Relaxed);
    }
    balance.learn(|r| got[r]);
    std::time::Duration::from_nanos(first_time.into_inner())
}

/// The chunks of a run's second stage not taken yet, `lo..hi`, as one
/// atomic word (`lo` in the low half, `hi` in the high half): the run's own
/// thread takes them from the top ([`top`]), a thread done with its own
/// from the bottom ([`bottom`]), each chunk exactly once. The word only
/// shares out the chunks; what the chunks read and write is ordered by the
/// runs' `done` flags and the team's wait at the end.
mod take {
    use std::sync::atomic::{AtomicU64, Ordering};

    /// The word of the chunks `r` (each bound below 2³²).
    pub(super) fn pack(r: std::ops::Range<usize>) -> u64 {
        debug_assert!(r.end <= u32::MAX as usize);
        r.start as u64 | (r.end as u64) << 32
    }

    /// Takes the highest chunk left, if any.
    #[inline]
    pub(super) fn top(w: &AtomicU64) -> Option<usize> {
        take(w, |lo, hi| (hi - 1, (lo, hi - 1)))
    }

    /// Takes the lowest chunk left, if any.
    #[inline]
    pub(super) fn bottom(w: &AtomicU64) -> Option<usize> {
        take(w, |lo, hi| (lo, (lo + 1, hi)))
    }

    /// Takes chunk `pick(lo, hi).0`, leaving `pick(lo, hi).1`, when
    /// `lo < hi`.
    #[inline(always)]
    fn take(w: &AtomicU64, pick: impl Fn(u64, u64) -> (u64, (u64, u64))) -> Option<usize> {
        let mut cur = w.load(Ordering::Relaxed);
        loop {
            let (lo, hi) = (cur & 0xffff_ffff, cur >> 32);
            if lo >= hi {
                return None;
            }
            let (c, (lo, hi)) = pick(lo, hi);
            match w.compare_exchange_weak(cur, lo | hi << 32, Ordering::Relaxed, Ordering::Relaxed)
            {
                Ok(_) => return Some(c as usize),
                Err(now) => cur = now,
            }
        }
    }
}

/// The chunk boundaries of the runs of a loop over `n` chunks: run `t`
/// holds the chunks `cuts[t]..cuts[t + 1]`, whose cost falls in its share
/// of the total (see [`Balance`]); also the number of runs, one per thread
/// of the current rayon pool (at most [`MAX_RUNS`]).
fn cut(
    n: usize,
    cost: &impl Fn(usize) -> u64,
    balance: &mut Balance,
) -> ([usize; MAX_RUNS + 1], usize) {
    let threads = rayon::current_num_threads();
    let runs = threads.min(MAX_RUNS);
    balance.reset(runs);
    let total = cost(n) as f64;
    // the chunk boundary nearest to the shares of runs 0..t: with few
    // chunks (200 stones are 7 chunks), the first boundary past the target
    // gave the first run 4 chunks of 7 for an even share, and the learned
    // shares, which weigh the cost each run got through per unit time,
    // never moved it back
    let start = |t: usize| {
        if t == runs {
            return n;
        }
        let target = total * balance.share[..t].iter().sum::<f64>();
        let (mut lo, mut hi) = (0, n);
        while lo < hi {
            let mid = (lo + hi) / 2;
            if (cost(mid) as f64) < target {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        let (below, above) = (
            target - cost(lo.saturating_sub(1)) as f64,
            cost(lo) as f64 - target,
        );
        if lo > 0 && below < above {
            lo - 1
        } else {
            lo
        }
    };
    let mut cuts = [0usize; MAX_RUNS + 1];
    for (t, c) in cuts.iter_mut().enumerate().take(runs + 1) {
        *c = start(t);
    }
    (cuts, runs)
}

/// Runs the runs `t0..t1` through `timed` (see [`for_each_run`]), splitting
/// the range in halves with `rayon::join` (which does not allocate, unlike a
/// broadcast): the calling thread keeps the first half and an idle thread
/// takes the second.
fn run_parts(t0: usize, t1: usize, timed: &(impl Fn(usize) + Sync)) {
    if t1 - t0 == 1 {
        timed(t0);
        return;
    }
    let mid = (t0 + t1) / 2;
    rayon::join(|| run_parts(t0, mid, timed), || run_parts(mid, t1, timed));
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
    use std::sync::Mutex;

    /// On one thread, `for_each_run_then` takes the chunks in blocks: the
    /// first stage of each block (of the one run of all chunks), in order,
    /// then the second stage of its chunks; every chunk through each stage
    /// once, and through the second only after its first.
    #[test]
    fn one_thread_takes_the_chunks_in_blocks() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        const BLOCK: usize = 8;
        for n in [0, 1, BLOCK, 2 * BLOCK + 3] {
            let log = Mutex::new(Vec::new());
            pool.install(|| {
                for_each_run_then(
                    n,
                    |c| c as u64,
                    |c| c as u64,
                    &mut Balance::default(),
                    BLOCK,
                    |run, part| {
                        assert_eq!(run, 0..n);
                        log.lock().unwrap().extend(part.map(|c| (0, c)));
                    },
                    |_| false,
                    || (),
                    |_, c| log.lock().unwrap().push((1, c)),
                );
            });
            // each block: its first stages, then its second stages
            let want: Vec<_> = (0..n)
                .step_by(BLOCK)
                .flat_map(|c0| {
                    let block = c0..(c0 + BLOCK).min(n);
                    block.clone().map(|c| (0, c)).chain(block.map(|c| (1, c)))
                })
                .collect();
            assert_eq!(log.into_inner().unwrap(), want, "{n} chunks");
        }
    }

    /// `for_each_run_then` runs each chunk's two stages once, the second
    /// after the first, and the chunk that depends on the earlier runs
    /// (here the first chunk of each run) only after their first stage: on
    /// the team (two runs on two cores) and on rayon (more runs than
    /// cores), also after the helpers have parked.
    #[test]
    fn second_stage_waits_where_it_depends_on_earlier_runs() {
        for threads in [2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut balance = Balance::default();
                for pause in [0, 1, 0] {
                    let n = 40;
                    let flags = |v: bool| (0..n).map(|_| AtomicBool::new(v)).collect::<Vec<_>>();
                    let counts = || (0..n).map(|_| AtomicUsize::new(0)).collect::<Vec<_>>();
                    let (first_done, run_start) = (flags(false), flags(false));
                    let (firsts, thens) = (counts(), counts());
                    for_each_run_then(
                        n,
                        |c| c as u64,
                        |c| c as u64,
                        &mut balance,
                        n,
                        |run, part| {
                            run_start[run.start].store(true, Ordering::Relaxed);
                            for c in part {
                                // the lower chunks slower: a second stage
                                // that did not wait would overtake them
                                let us = if c < n / 2 { 200 } else { 20 };
                                std::thread::sleep(std::time::Duration::from_micros(us));
                                firsts[c].fetch_add(1, Ordering::Relaxed);
                                first_done[c].store(true, Ordering::Release);
                            }
                        },
                        |c| run_start[c].load(Ordering::Relaxed),
                        || (),
                        |_, c| {
                            thens[c].fetch_add(1, Ordering::Relaxed);
                            assert!(first_done[c].load(Ordering::Acquire));
                            if run_start[c].load(Ordering::Relaxed) {
                                assert!(
                                    (0..c).all(|k| first_done[k].load(Ordering::Acquire)),
                                    "chunk {c} ran before the earlier runs' first stage"
                                );
                            }
                        },
                    );
                    assert!(firsts.iter().all(|x| x.load(Ordering::Relaxed) == 1));
                    assert!(thens.iter().all(|x| x.load(Ordering::Relaxed) == 1));
                    std::thread::sleep(std::time::Duration::from_millis(pause));
                }
            });
        }
    }

    /// A thread done with its own chunks takes the second stage of the
    /// chunks another run has not reached, and only once the first stage of
    /// that run and of the runs before it is over; every chunk still runs
    /// each stage exactly once.
    #[test]
    fn a_thread_done_early_takes_the_chunks_left_in_another_run() {
        if std::thread::available_parallelism().map_or(1, |c| c.get()) < 2 {
            return; // the team is not used on one core
        }
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        pool.install(|| {
            let mut balance = Balance::default();
            let n = 40;
            let mut taken = 0;
            // a test running beside this one may hold the team, and a call
            // then goes to rayon, which takes no chunks: a few calls
            for _ in 0..50 {
                let ids = || (0..n).map(|_| Mutex::new(None)).collect::<Vec<_>>();
                let (first_by, then_by) = (ids(), ids());
                let first_done = (0..n).map(|_| AtomicBool::new(false)).collect::<Vec<_>>();
                let thens = (0..n).map(|_| AtomicUsize::new(0)).collect::<Vec<_>>();
                for_each_run_then(
                    n,
                    |c| c as u64,
                    |c| c as u64,
                    &mut balance,
                    n,
                    |_, part| {
                        for c in part {
                            *first_by[c].lock().unwrap() = Some(std::thread::current().id());
                            first_done[c].store(true, Ordering::Release);
                        }
                    },
                    |_| false,
                    || (),
                    |_, c| {
                        thens[c].fetch_add(1, Ordering::Relaxed);
                        let me = std::thread::current().id();
                        *then_by[c].lock().unwrap() = Some(me);
                        if *first_by[c].lock().unwrap() != Some(me) {
                            // taken from another run: the first stage of
                            // every chunk up to it is over
                            assert!(
                                (0..=c).all(|k| first_done[k].load(Ordering::Acquire)),
                                "chunk {c} taken before the first stage of its run"
                            );
                        }
                        // the upper half slow: their run's thread falls behind
                        if c >= n / 2 {
                            std::thread::sleep(std::time::Duration::from_micros(300));
                        }
                    },
                );
                assert!(thens.iter().all(|x| x.load(Ordering::Relaxed) == 1));
                taken += (0..n)
                    .filter(|&c| *first_by[c].lock().unwrap() != *then_by[c].lock().unwrap())
                    .count();
                if taken > 0 {
                    break;
                }
            }
            assert!(
                taken > 0,
                "no chunk was taken by the other thread in 50 calls"
            );
        });
    }
}
