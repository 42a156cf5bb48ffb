//! Driver for cache and instruction counts of the scaling beds under
//! callgrind (docs/performance.md, section 6): the settled ~10⁴-sphere
//! tile of `clump bench --scaling` (its defaults) copied `K × K` times.
//!
//! `cache_bed GO_FILE K:STEPS...`: settles the tile (20 000 steps); then,
//! for each `K:STEPS`, copies it `K × K` times and runs 200 steps (lists
//! and histories rebuilt). Before the first bed's measured steps it prints
//! `READY` and waits for `GO_FILE` to exist (meanwhile `callgrind_control
//! -i on PID` turns the simulation on; started with `--instr-atstart=no`,
//! the settling runs without it). Each bed then runs 3 steps (the caches
//! warm) and STEPS fused steps in [`measured`], whose counts
//! `--dump-before=*measured* --dump-after=*measured*` put in a file of
//! their own.
//!
//! `cargo build --release -p clump-cli --example cache_bed`

use clump_core::testbed::{tetra_lattice_bed, tile_xy};
use clump_core::world::World;
use std::io::Write;

/// Lattice layers and cells a side of the scaling study's tile (10 368
/// spheres; `clump bench --scaling` with its defaults).
const LAYERS: usize = 8;
const NX: usize = 18;

/// The steps whose counts are taken.
#[inline(never)]
fn measured(w: &mut World, steps: u64) {
    w.run(steps).expect("steps");
}

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: cache_bed GO_FILE K:STEPS...";
    let go = std::path::Path::new(a.first().expect(usage));
    let beds: Vec<(usize, u64)> = a[1..]
        .iter()
        .map(|s| {
            let (k, n) = s.split_once(':').expect(usage);
            (k.parse().expect(usage), n.parse().expect(usage))
        })
        .collect();
    let mut tile = tetra_lattice_bed(NX, NX, LAYERS, None);
    tile.run(20_000).expect("settling");
    for (n, &(k, steps)) in beds.iter().enumerate() {
        let mut w = tile_xy(&tile, k, k);
        w.run(200).expect("warm-up");
        if n == 0 {
            println!("READY {}", std::process::id());
            std::io::stdout().flush().expect("stdout");
            while !go.exists() {
                std::thread::sleep(std::time::Duration::from_millis(200));
            }
        }
        w.run(3).expect("warm-up");
        let r0 = w.rebuilds;
        measured(&mut w, steps);
        let th = w.thermo();
        println!(
            "K {k}: {} spheres, {steps} steps, rebuilds {}, contacts {}",
            w.spheres().len(),
            w.rebuilds - r0,
            th.pair_contacts
        );
    }
}
