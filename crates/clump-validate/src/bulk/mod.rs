//! Bulk behaviour of many bodies (full suite only): random packings of
//! spheres, equipartition in an elastic gas of clumps, the angle of repose
//! of tetra-clump heaps, dry and cohesive, and Beverloo hopper discharge.
//! Sizes and time steps are chosen so that the whole group runs in minutes
//! on two cores (the independent runs of a series side by side, see
//! [`run_parallel`]); each case states them.
//! World frame: z up, gravity −z.

pub mod cohesive_heap;
pub mod equipartition;
pub mod hopper;
pub mod packing;
pub mod repose;

use crate::case::{Case, Group};
use crate::Selection;
use clump_core::contact::time_scale::rayleigh_time;
use clump_core::contact::Material;
use clump_core::insert::{pack, Mix, Orientation, PackSpec, PackTarget, Region};
use clump_core::world::World;
use glam::DVec3;
use std::path::Path;
use std::time::Instant;

/// Places `n` bodies of `template` in the box `[lo, hi]` (m) by random
/// sequential addition, random orientations, at rest.
pub fn fill(
    w: &mut World,
    template: u32,
    lo: DVec3,
    hi: DVec3,
    n: usize,
    seed: u64,
) -> Result<usize, String> {
    let spec = PackSpec {
        region: Region::Box { lo, hi },
        target: PackTarget::Count(n),
        mix: Mix::single(template),
        velocity: DVec3::ZERO,
        orientation: Orientation::Random,
        max_attempts_per_body: 2000,
        angular_velocity: Default::default(),
        dof: Vec::new(),
        plane: None,
    };
    let r = pack(w, &spec, seed).map_err(|e| e.to_string())?;
    Ok(r.placed)
}

/// Steps until the kinetic energy per body falls below `ke_per_body` (J),
/// checked every 500 steps after `min_steps`, or `max_steps`. Returns the
/// steps taken.
pub fn settle(
    w: &mut World,
    min_steps: u64,
    max_steps: u64,
    ke_per_body: f64,
) -> Result<u64, String> {
    let mut n = 0;
    while n < max_steps {
        w.run(500).map_err(|e| e.to_string())?;
        n += 500;
        if n >= min_steps {
            let t = w.thermo();
            let ke = t.kinetic_translational + t.kinetic_rotational;
            if ke < ke_per_body * w.bodies().len().max(1) as f64 {
                break;
            }
        }
    }
    Ok(n)
}

/// One independent run for [`run_parallel`].
pub type Job<'a, T> = Box<dyn FnOnce() -> T + Send + 'a>;

/// Runs independent jobs (separate worlds) side by side, one per thread of
/// the global rayon pool, each inside a one-thread pool of its own: small
/// worlds scale poorly over threads, independent runs well. A world's result
/// does not depend on its thread count (the engine's reductions use fixed
/// chunks), so this changes only the wall time. Results in job order.
pub fn run_parallel<T: Send>(jobs: Vec<Job<'_, T>>) -> Vec<T> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::Mutex;
    let n = jobs.len();
    let jobs: Vec<Mutex<Option<Job<'_, T>>>> =
        jobs.into_iter().map(|j| Mutex::new(Some(j))).collect();
    let out: Vec<Mutex<Option<T>>> = (0..n).map(|_| Mutex::new(None)).collect();
    let next = AtomicUsize::new(0);
    let workers = rayon::current_num_threads().clamp(1, n.max(1));
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(1)
                    .build()
                    .expect("one-thread pool");
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    if k >= n {
                        break;
                    }
                    let job = jobs[k].lock().unwrap().take().expect("each job runs once");
                    let r = pool.install(job);
                    *out[k].lock().unwrap() = Some(r);
                }
            });
        }
    });
    out.into_iter()
        .map(|m| m.into_inner().unwrap().expect("every job ran"))
        .collect()
}

/// Mean and standard error of the mean of `x` (the standard error is NaN
/// for fewer than two values).
pub fn mean_se(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0);
    (m, (var / n).sqrt())
}

/// `dt_fraction` × the Rayleigh time of a sphere of radius `r` of `mat`, s.
pub fn rayleigh_dt(mat: &Material, r: f64, dt_fraction: f64) -> f64 {
    dt_fraction * rayleigh_time(mat, r)
}

/// Runs the bulk group: nothing in the quick selection.
pub fn run(sel: Selection, dir: &Path) -> Group {
    let mut g = Group::default();
    if sel == Selection::Quick {
        g.notes.push(
            "Bulk cases run only in the full suite (`clump validate` without `--quick`).".into(),
        );
        return g;
    }
    type Part = fn(&mut Group, &Path) -> Result<(), String>;
    let parts: [(&str, &str, Part); 5] = [
        ("random packings", "REFERENCE.md §4", packing::run),
        ("equipartition", "equipartition theorem", equipartition::run),
        ("angle of repose", "published trend", repose::run),
        (
            "cohesive angle of repose",
            "published trend",
            cohesive_heap::run,
        ),
        ("hopper discharge", "REFERENCE.md §4", hopper::run),
    ];
    for (name, src, f) in parts {
        let t0 = Instant::now();
        if let Err(e) = f(&mut g, dir) {
            g.cases.push(Case::error(name, src, e));
        }
        g.notes.push(format!(
            "{name}: {:.1} s wall time",
            t0.elapsed().as_secs_f64()
        ));
    }
    g
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parallel_jobs_all_run_and_come_back_in_order() {
        let jobs: Vec<Job<usize>> = (0..7usize)
            .map(|k| Box::new(move || k * k) as Job<usize>)
            .collect();
        assert_eq!(run_parallel(jobs), vec![0, 1, 4, 9, 16, 25, 36]);
        // each job sees a pool of one thread
        let jobs: Vec<Job<usize>> = (0..3)
            .map(|_| Box::new(rayon::current_num_threads) as Job<usize>)
            .collect();
        assert_eq!(run_parallel(jobs), vec![1, 1, 1]);
    }

    #[test]
    fn mean_and_standard_error_by_hand() {
        // mean 2.5, sample variance 5/3, SE = √(5/3 / 4)
        let (m, se) = mean_se(&[1.0, 2.0, 3.0, 4.0]);
        assert!((m - 2.5).abs() < 1e-15);
        assert!((se - (5.0f64 / 12.0).sqrt()).abs() < 1e-15);
    }
}
