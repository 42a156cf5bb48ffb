//! A persistent team of helper threads for the per-step loops.
//!
//! Each step runs one to three parallel loops (inside `World::run` one
//! call for the pair stage and the gather, which also takes the next
//! step's first half; else the first half step, the pair forces and the
//! gather), each a few hundred microseconds long on a bed of a few
//! thousand bodies. Handing a run to a rayon worker costs a wake-up when
//! that worker has gone to sleep between the loops: measured at 17–40 µs
//! per loop on two threads on the settled 2 000-clump bed, 12–25 % of the
//! step. The helpers here spin for a short while after each run (then
//! park), so the next run starts within a fraction of a microsecond, and
//! helper `t` always takes run `t + 1`, which keeps its bodies in its
//! core's cache.
//!
//! The team is one per process and serves one loop at a time: a loop that
//! finds it busy (another world stepping on another thread, as in parallel
//! tests) runs on rayon instead. Which threads run the runs never changes
//! the results (see [`super::affinity`]).

use std::cell::UnsafeCell;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};
use std::thread::Thread;
use std::time::{Duration, Instant};

/// How long a helper spins for the next run before it parks. Longer than
/// the serial work between two loops of a step (a few microseconds), far
/// shorter than the output and bookkeeping between batches of steps.
const SPIN_LIMIT: Duration = Duration::from_micros(200);

/// Most helpers (runs beyond the team's size go to rayon).
const MAX_HELPERS: usize = 63;

/// A type-erased `&dyn Fn(usize)` with the run number to call it with.
#[derive(Clone, Copy)]
struct Job {
    data: *const (),
    call: unsafe fn(*const (), usize),
    run: usize,
}

/// What the master and one helper share.
struct Slot {
    /// Incremented by the master to post a job (helpers live as long as
    /// the process).
    posted: AtomicU64,
    /// The last job number the helper finished.
    done: AtomicU64,
    /// Set while the helper is (about to be) parked.
    sleeping: AtomicBool,
    /// Set when the helper's job panicked.
    panicked: AtomicBool,
    /// The job; written by the master before `posted` is incremented, read
    /// by the helper after it sees the increment.
    job: UnsafeCell<Option<Job>>,
}

// SAFETY: `job` is written only by the master while the helper waits for
// the next number in `posted`, and read by the helper only after it (with
// acquire ordering) sees that number; the pointers in it are valid until
// the master has seen `done` reach that number.
unsafe impl Sync for Slot {}
unsafe impl Send for Slot {}

struct Helper {
    slot: Arc<Slot>,
    thread: Thread,
}

/// The helpers.
pub(crate) struct Team {
    helpers: Vec<Helper>,
}

fn team() -> &'static Mutex<Team> {
    static TEAM: OnceLock<Mutex<Team>> = OnceLock::new();
    TEAM.get_or_init(|| {
        Mutex::new(Team {
            helpers: Vec::new(),
        })
    })
}

/// Calls `f(t)` for every run `t` in `0..n`, each on its own thread: the
/// calling thread runs `0`, helper `t − 1` runs `t`. Returns false (and
/// runs nothing) when there are more runs than processor cores (spinning
/// threads would then take turns on a core: measured 2.4 times slower than
/// rayon with three runs on two cores), when the team is busy serving
/// another loop, or when it cannot grow to the size needed; the caller
/// then runs the runs some other way.
pub(crate) fn run(n: usize, f: &(dyn Fn(usize) + Sync)) -> bool {
    static CORES: OnceLock<usize> = OnceLock::new();
    let cores = *CORES.get_or_init(|| std::thread::available_parallelism().map_or(1, |c| c.get()));
    if n < 2 || n > cores || n - 1 > MAX_HELPERS {
        return false;
    }
    let Ok(mut team) = team().try_lock() else {
        return false;
    };
    while team.helpers.len() < n - 1 {
        match spawn(team.helpers.len()) {
            Some(h) => team.helpers.push(h),
            None => return false,
        }
    }
    /// Calls the `&dyn Fn` behind `data`.
    unsafe fn call(data: *const (), t: usize) {
        // SAFETY: `data` is the `&&dyn Fn` passed below, alive until the
        // master has seen every helper finish.
        let f = unsafe { *(data as *const &(dyn Fn(usize) + Sync)) };
        f(t)
    }
    let fref: &(dyn Fn(usize) + Sync) = f;
    let data = &fref as *const &(dyn Fn(usize) + Sync) as *const ();
    let mut numbers = [0u64; MAX_HELPERS];
    for (t, h) in team.helpers.iter().take(n - 1).enumerate() {
        // SAFETY: the helper is idle (its last job is done: the previous
        // call waited for it), so nothing reads the job now.
        unsafe {
            *h.slot.job.get() = Some(Job {
                data,
                call,
                run: t + 1,
            })
        };
        numbers[t] = h.slot.posted.fetch_add(1, Ordering::SeqCst) + 1;
        if h.slot.sleeping.load(Ordering::SeqCst) {
            h.thread.unpark();
        }
    }
    let master = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| f(0)));
    let mut helper_panicked = false;
    for (t, h) in team.helpers.iter().take(n - 1).enumerate() {
        wait_for(&h.slot.done, numbers[t]);
        helper_panicked |= h.slot.panicked.swap(false, Ordering::Relaxed);
    }
    drop(team);
    if let Err(p) = master {
        std::panic::resume_unwind(p);
    }
    assert!(!helper_panicked, "a helper thread's run panicked");
    true
}

/// Spins until `flag` holds `value`, which another thread of the team
/// stores (acquire: what it wrote before is visible after the wait). That
/// thread runs on a core of its own, but may have been descheduled: after
/// a while the wait yields the core.
pub(super) fn wait_for(flag: &AtomicU64, value: u64) {
    let mut spins = 0u32;
    while flag.load(Ordering::Acquire) != value {
        spins = spins.saturating_add(1);
        if spins < 1 << 16 {
            std::hint::spin_loop();
        } else {
            std::thread::yield_now();
        }
    }
}

/// Starts helper number `index`.
fn spawn(index: usize) -> Option<Helper> {
    let slot = Arc::new(Slot {
        posted: AtomicU64::new(0),
        done: AtomicU64::new(0),
        sleeping: AtomicBool::new(false),
        panicked: AtomicBool::new(false),
        job: UnsafeCell::new(None),
    });
    let s = Arc::clone(&slot);
    let handle = std::thread::Builder::new()
        .name(format!("clump-helper-{index}"))
        .spawn(move || helper_loop(&s))
        .ok()?;
    Some(Helper {
        slot,
        thread: handle.thread().clone(),
    })
}

/// A helper: wait for the next job number (spinning, then parked), run the
/// job, publish its number.
fn helper_loop(slot: &Slot) {
    let mut seen = 0u64;
    loop {
        let mut since = Instant::now();
        let mut spins = 0u32;
        let next = loop {
            let p = slot.posted.load(Ordering::Acquire);
            if p != seen {
                break p;
            }
            spins = spins.wrapping_add(1);
            std::hint::spin_loop();
            if spins % 256 == 0 && since.elapsed() > SPIN_LIMIT {
                slot.sleeping.store(true, Ordering::SeqCst);
                if slot.posted.load(Ordering::SeqCst) == seen {
                    std::thread::park();
                }
                slot.sleeping.store(false, Ordering::SeqCst);
                since = Instant::now();
            }
        };
        seen = next;
        // SAFETY: the master wrote the job before posting `next` (acquire
        // above) and does not touch it until `done` reaches `next`.
        if let Some(job) = unsafe { *slot.job.get() } {
            // SAFETY: see `Job`: the master keeps `data` alive until done.
            let ok = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| unsafe {
                (job.call)(job.data, job.run)
            }))
            .is_ok();
            if !ok {
                slot.panicked.store(true, Ordering::Relaxed);
            }
        }
        slot.done.store(next, Ordering::Release);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;

    /// Every range is run exactly once, also after the helpers have parked.
    #[test]
    fn runs_every_range_once() {
        if std::thread::available_parallelism().map_or(1, |c| c.get()) < 2 {
            return; // the team is not used on one core
        }
        for pause in [0, 1, 0] {
            let hits: Vec<AtomicUsize> = (0..40).map(|_| AtomicUsize::new(0)).collect();
            let ranges = [0..17, 17..40];
            let f = |t: usize| {
                for i in ranges[t].clone() {
                    hits[i].fetch_add(1, Ordering::Relaxed);
                }
            };
            // the team may be busy with another test's world: then retry
            while !run(ranges.len(), &f) {
                std::thread::yield_now();
            }
            assert!(hits.iter().all(|h| h.load(Ordering::Relaxed) == 1));
            // and on another thread than the caller's
            let caller = std::thread::current().id();
            let other = std::sync::Mutex::new(None);
            let g = |t: usize| {
                if t == 1 {
                    *other.lock().unwrap() = Some(std::thread::current().id());
                }
            };
            while !run(2, &g) {
                std::thread::yield_now();
            }
            assert!(other.into_inner().unwrap().is_some_and(|id| id != caller));
            std::thread::sleep(Duration::from_millis(pause));
        }
    }
}
