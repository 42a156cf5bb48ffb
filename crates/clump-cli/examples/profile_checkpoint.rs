//! Profiling driver: loads a checkpoint (e.g. the settled tetra bed) and
//! steps it, timed, without output.
//! `cargo run --release -p clump-cli --example profile_checkpoint -- CKPT STEPS`
//! With `PROFILE_WAIT` set it sleeps 3 s after loading (to switch a
//! profiler's collection on, e.g. `callgrind_control -i on`); with
//! `PROFILE_NO_SQUISH` set it steps with the NO_SQUISH rotation scheme
//! instead of the checkpoint's (to compare the schemes' cost).

use std::time::Instant;

#[inline(never)]
fn profiled(w: &mut clump_core::world::World, steps: u64) {
    w.run(steps).expect("step failed");
}

fn main() {
    if std::env::var_os("PROFILE_MAIN_THREAD").is_some() {
        // one pool thread, the main one: a profiler then attributes every
        // stage's work to its caller
        rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .use_current_thread()
            .build_global()
            .expect("rayon pool");
    }
    let a: Vec<String> = std::env::args().skip(1).collect();
    let path = std::path::PathBuf::from(a.first().expect("usage: profile_checkpoint CKPT STEPS"));
    let steps: u64 = a.get(1).map_or(1000, |s| s.parse().expect("STEPS"));
    let bytes = std::fs::read(&path).expect("read checkpoint");
    let (_, mut w, _) = clump_io::run::load_checkpoint(&bytes, &path).expect("load checkpoint");
    if std::env::var_os("PROFILE_NO_SQUISH").is_some() {
        w.config.rotation = clump_core::rotation::RotationScheme::NoSquish;
    }
    w.prepare().expect("prepare");
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
    for (name, t) in w.stage_times.rows() {
        println!("  {name:>18}: {:7.1} ns per sphere-step", t / ss * 1e9);
    }
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
