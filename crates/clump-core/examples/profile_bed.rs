//! Profiling driver: a bed of tetra clumps, settled, then stepped.
//! `cargo run --release -p clump-core --example profile_bed -- NX SETTLE STEPS`

use clump_core::testbed::tetra_lattice_bed;
use clump_core::world::World;
use std::time::Instant;

/// A cubic bed of `nx³` tetra clumps, allowed to fall for `settle` steps.
fn bed(nx: usize, settle: u64) -> World {
    let mut w = tetra_lattice_bed(nx, nx, nx, Some(0.5e-3));
    w.run(settle).unwrap();
    w
}

#[inline(never)]
fn profiled(w: &mut World, steps: u64) {
    w.run(steps).unwrap();
}

fn main() {
    let a: Vec<u64> = std::env::args()
        .skip(1)
        .map(|x| x.parse().unwrap())
        .collect();
    let (nx, settle, steps) = (
        a.first().copied().unwrap_or(12),
        a.get(1).copied().unwrap_or(20000),
        a.get(2).copied().unwrap_or(2000),
    );
    let mut w = bed(nx as usize, settle);
    let r0 = w.rebuilds;
    println!("SETTLED");
    use std::io::Write;
    std::io::stdout().flush().unwrap();
    if std::env::var_os("PROFILE_WAIT").is_some() {
        std::thread::sleep(std::time::Duration::from_secs(3));
    }
    let t = Instant::now();
    profiled(&mut w, steps);
    let s = t.elapsed().as_secs_f64();
    let th = w.thermo();
    println!("{} spheres, {} steps in {s:.3} s: {:.3} M sphere-steps/s; rebuilds {}; contacts {}+{}; KE {:.3e}", w.spheres().len(), steps, w.spheres().len() as f64 * steps as f64 / s / 1e6, w.rebuilds - r0, th.pair_contacts, th.wall_contacts, th.kinetic_translational);
}
