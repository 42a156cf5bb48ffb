//! The density in the bed along a depth profile against a closed form: a
//! two-tier heap of spheres on a simple cubic lattice (spacing = the
//! diameter) that covers only part of a wide floor has the bulk density
//! ρ_s π/6 inside each tier, while the cross-section average is that times
//! the tier's share of the floor.

use clump_core::boundary::Domain;
use clump_io::post::bed::{density_in_bed, occupied_fraction};
use clump_io::post::fields::coarse_grain;
use clump_io::post::frame::{BodyState, Frame};
use clump_io::post::grid::Grid;
use clump_io::post::kernel::Kernel;
use glam::{DQuat, DVec3};
use std::f64::consts::PI;

const D: f64 = 0.01; // sphere diameter = lattice spacing, m
const RHO_S: f64 = 2500.0; // solid density, kg/m³

fn sphere(id: u64, p: DVec3) -> BodyState {
    let v = PI / 6.0 * D * D * D;
    BodyState {
        id,
        template: 0,
        position: p,
        velocity: DVec3::ZERO,
        angular_velocity: DVec3::ZERO,
        orientation: DQuat::IDENTITY,
        mass: RHO_S * v,
        volume: v,
        inertia: DVec3::splat(0.1 * RHO_S * v * D * D),
        force: DVec3::ZERO,
        torque: DVec3::ZERO,
    }
}

/// A two-tier heap on a 20 × 20-column floor: a block of 16 × 16 stacks
/// `tier` layers high with a centred block of 8 × 8 stacks on it, `tier`
/// layers more; the lattice sits on the columns.
fn heap(tier: usize) -> Frame {
    let mut bodies = Vec::new();
    for l in 0..2 * tier {
        let (first, n) = if l < tier { (2, 16) } else { (6, 8) };
        for i in first..first + n {
            for j in first..first + n {
                let p = DVec3::new(i as f64 + 0.5, j as f64 + 0.5, l as f64 + 0.5) * D;
                bodies.push(sphere(bodies.len() as u64 + 1, p));
            }
        }
    }
    Frame {
        step: 0,
        time: 0.0,
        domain: Domain {
            lo: DVec3::ZERO,
            hi: DVec3::new(20.0, 20.0, 2.0 * tier as f64 + 4.0) * D,
            periodic: [false; 3],
        },
        bodies,
        contacts: None,
    }
}

fn profile(frame: &Frame, kernel: Kernel) -> Grid {
    Grid {
        axes: vec![2],
        lo: vec![0.0],
        hi: vec![frame.domain.hi.z],
        cells: vec![(frame.domain.hi.z / D) as usize * 4],
        kernel,
        width: D,
        domain: frame.domain,
    }
}

/// In each tier's interior (further than the kernel's support from the
/// tier's ends) the occupied share of the floor is exactly the tier's
/// footprint (256/400, then 64/400) and the density in the bed is the
/// lattice's bulk density to the lattice's ripple under the kernel; the
/// cross-section average is the bulk density times the footprint share.
/// The ripple (below 1e-3 at a kernel width of one spacing) is the
/// coarse-grained density's own: point deposits on a lattice under a kernel
/// of finite support; the occupancy carries none.
#[test]
fn heap_has_the_lattice_bulk_density_in_each_tier() {
    let bulk = RHO_S * PI / 6.0;
    let tier = 10;
    for kernel in [Kernel::Gaussian, Kernel::Lucy] {
        let frame = heap(tier);
        let grid = profile(&frame, kernel);
        let rho = coarse_grain(&frame, &grid).density;
        let occ = occupied_fraction(&frame, &grid);
        let bed = density_in_bed(&rho, &occ);
        let c = kernel.support(grid.width);
        let mut worst: f64 = 0.0;
        for (k, b) in bed.iter().enumerate() {
            let z = grid.centre(0, k);
            let share = if z > c + 0.5 * grid.spacing(0)
                && z < tier as f64 * D - c - 0.5 * grid.spacing(0)
            {
                0.64
            } else if z > tier as f64 * D + c + 0.5 * grid.spacing(0)
                && z < 2.0 * tier as f64 * D - c - 0.5 * grid.spacing(0)
            {
                0.16
            } else {
                continue;
            };
            assert!(
                (occ[k] - share).abs() < 1e-12,
                "{kernel:?} z = {z}: {}",
                occ[k]
            );
            let b = b.expect("defined inside the bed");
            assert!(
                (b - rho[k] / share).abs() <= 1e-12 * b,
                "{kernel:?} z = {z}"
            );
            worst = worst.max((b - bulk).abs() / bulk);
            assert!(
                (rho[k] / (share * bulk) - 1.0).abs() < 1e-3,
                "{kernel:?} z = {z}"
            );
        }
        eprintln!("{kernel:?}: largest relative deviation from ρ_s π/6 in the tiers' interiors {worst:.2e}");
        assert!(worst < 1e-3, "{kernel:?}: {worst}");
    }
}

#[test]
fn no_bodies_no_bed() {
    let mut frame = heap(2);
    frame.bodies.clear();
    let grid = profile(&frame, Kernel::Gaussian);
    assert!(occupied_fraction(&frame, &grid).iter().all(|&f| f == 0.0));
    assert!(density_in_bed(&[0.0; 4], &[0.0; 4])
        .iter()
        .all(Option::is_none));
}
