//! Profiling driver: loads a checkpoint (e.g. the settled tetra bed) and
//! steps it, timed, without output.
//! `cargo run --release -p clump-cli --example profile_checkpoint -- CKPT STEPS`
//! With `PROFILE_WAIT` set it sleeps 3 s after loading (to switch a
//! profiler's collection on, e.g. `callgrind_control -i on`); with
//! `PROFILE_NO_SQUISH` set it steps with the NO_SQUISH rotation scheme
//! instead of the checkpoint's (to compare the schemes' cost).
//! `PROFILE_SKIN` (m) overrides the Verlet skin. `PROFILE_REBUILDS=K`
//! times K neighbour rebuilds (`World::prepare`) instead of stepping.
//! `PROFILE_THREADS` sets the thread count (default 1); the main thread is
//! one of the pool's, so a profiler sees every stage under `profiled`.
//! `PROFILE_ALTERNATE=T` steps the checkpoint in stretches of 500 steps,
//! alternately on one thread and on `T` threads, in one process, and reports
//! each side's wall and CPU time, stage times and the speed-up: the host's
//! drift over minutes, larger than the effects sought, then falls on both
//! sides alike.

use std::time::Instant;

#[inline(never)]
fn profiled(w: &mut clump_core::world::World, steps: u64) {
    w.run(steps).expect("step failed");
}

fn main() {
    // the stepping runs inside the pool (as `clump run` and `clump bench`
    // do): a caller outside it would pay a cross-thread hand-off per stage
    let threads: usize = std::env::var("PROFILE_THREADS")
        .ok()
        .map_or(1, |s| s.parse().expect("PROFILE_THREADS"));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .use_current_thread()
        .build()
        .expect("rayon pool");
    pool.install(body);
}

fn body() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let path = std::path::PathBuf::from(a.first().expect("usage: profile_checkpoint CKPT STEPS"));
    let steps: u64 = a.get(1).map_or(1000, |s| s.parse().expect("STEPS"));
    let bytes = std::fs::read(&path).expect("read checkpoint");
    let (_, mut w, _) = clump_io::run::load_checkpoint(&bytes, &path).expect("load checkpoint");
    if std::env::var_os("PROFILE_NO_SQUISH").is_some() {
        w.config.rotation = clump_core::rotation::RotationScheme::NoSquish;
    }
    if let Some(skin) = std::env::var("PROFILE_SKIN").ok() {
        w.config.skin = Some(skin.parse().expect("PROFILE_SKIN"));
    }
    w.prepare().expect("prepare");
    if let Some(k) = std::env::var("PROFILE_REBUILDS").ok() {
        // time k neighbour rebuilds (each with a force evaluation) instead
        let k: u32 = k.parse().expect("PROFILE_REBUILDS");
        let t = Instant::now();
        for _ in 0..k {
            w.prepare().expect("prepare");
        }
        let s = t.elapsed().as_secs_f64() / k as f64;
        println!(
            "{} spheres: {:.3} ms per rebuild and force evaluation; {} candidate pairs",
            w.spheres().len(),
            s * 1e3,
            w.pairs().len()
        );
        return;
    }
    if let Ok(t) = std::env::var("PROFILE_ALTERNATE") {
        alternate(&mut w, steps, t.parse().expect("PROFILE_ALTERNATE"));
        return;
    }
    let r0 = w.rebuilds;
    w.stage_times = Default::default();
    if std::env::var_os("PROFILE_WAIT").is_some() {
        println!("LOADED");
        std::thread::sleep(std::time::Duration::from_secs(3));
    }
    let t = Instant::now();
    let c0 = cpu_seconds();
    profiled(&mut w, steps);
    let s = t.elapsed().as_secs_f64();
    let cpu = cpu_seconds() - c0;
    let th = w.thermo();
    println!(
        "{} spheres, {steps} steps in {s:.3} s: {:.3} M sphere-steps/s; rebuilds {}; contacts {}+{}",
        w.spheres().len(),
        w.spheres().len() as f64 * steps as f64 / s / 1e6,
        w.rebuilds - r0,
        th.pair_contacts,
        th.wall_contacts
    );
    let ss = w.spheres().len() as f64 * steps as f64;
    println!(
        "  candidate pairs {} ({:.2} per sphere)",
        w.pairs().len(),
        w.pairs().len() as f64 / w.spheres().len() as f64
    );
    println!(
        "  CPU time {cpu:.3} s: {:.1} ns CPU per sphere-step",
        cpu / ss * 1e9
    );
    // a fingerprint of the final state, to compare builds bit for bit
    let mut h = 0xcbf29ce484222325u64;
    let b = w.bodies();
    let mut mix = |x: f64| {
        h ^= x.to_bits();
        h = h.wrapping_mul(0x100000001b3);
    };
    for i in 0..b.len() {
        for v in [b.position[i], b.velocity[i], b.angular_momentum[i]] {
            v.to_array().into_iter().for_each(&mut mix);
        }
        b.orientation[i].to_array().into_iter().for_each(&mut mix);
    }
    println!("  state fingerprint {h:016x}");
    for (name, t) in w.stage_times.rows() {
        println!("  {name:>18}: {:7.1} ns per sphere-step", t / ss * 1e9);
    }
}

/// `steps` steps of `w` in stretches of [`STRETCH`] steps, alternately on one
/// thread and on `threads` threads (a pool each; the stepping runs inside
/// the pool, as in `clump run`), with each side's totals.
fn alternate(w: &mut clump_core::world::World, steps: u64, threads: usize) {
    const STRETCH: u64 = 500;
    assert!(
        steps >= 2 * STRETCH && threads >= 1,
        "PROFILE_ALTERNATE needs STEPS ≥ {} (a stretch of {STRETCH} steps each way) and T ≥ 1",
        2 * STRETCH
    );
    let counts = [1, threads];
    let pools = counts.map(|t| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build()
            .expect("rayon pool")
    });
    // per side: wall s, CPU s, and the stage times (s, the calling thread's)
    let mut wall = [0.0f64; 2];
    let mut cpu = [0.0f64; 2];
    let mut stages = [[0.0f64; 4]; 2];
    let mut done = [0u64; 2];
    for k in 0..steps.div_ceil(STRETCH) {
        let side = (k % 2) as usize;
        let n = STRETCH.min(steps - k * STRETCH);
        let before = w.stage_times.rows();
        let (t, c0) = (Instant::now(), cpu_seconds());
        pools[side].install(|| w.run(n).expect("step failed"));
        wall[side] += t.elapsed().as_secs_f64();
        cpu[side] += cpu_seconds() - c0;
        for (q, ((_, a), (_, b))) in w.stage_times.rows().iter().zip(before).enumerate() {
            stages[side][q] += a - b;
        }
        done[side] += n;
    }
    let spheres = w.spheres().len() as f64;
    for side in 0..2 {
        let ss = spheres * done[side] as f64;
        println!(
            "{} thread(s), {} steps: {:.3} s, {:.3} M sphere-steps/s; CPU {:.1} ns per sphere-step",
            counts[side],
            done[side],
            wall[side],
            ss / wall[side] / 1e6,
            cpu[side] / ss * 1e9
        );
        for (q, (name, _)) in w.stage_times.rows().iter().enumerate() {
            println!(
                "  {name:>18}: {:7.1} ns per sphere-step",
                stages[side][q] / ss * 1e9
            );
        }
    }
    let rate = |side: usize| done[side] as f64 / wall[side];
    println!(
        "speed-up on {threads} threads: {:.3} (efficiency {:.3})",
        rate(1) / rate(0),
        rate(1) / rate(0) / threads as f64
    );
}

/// CPU time (user + system, all threads) of this process, s.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let rest = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<f64> = rest
        .split_whitespace()
        .map(|x| x.parse().unwrap_or(0.0))
        .collect();
    (f.get(11).copied().unwrap_or(0.0) + f.get(12).copied().unwrap_or(0.0)) / 100.0
}
