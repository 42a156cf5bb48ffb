//! The void fraction among the coarse-grained fields (T-84,
//! `ε = 1 − Σ_a V_a φ_a`) against exact values: a sphere whose kernel lies
//! wholly inside one cell leaves `1 − V/V_cell` there and 1 elsewhere; a
//! periodic simple cubic packing of touching spheres gives `1 − π/6` in
//! every cell of a grid aligned with its lattice planes, whatever the
//! kernel's width (the cells tile one lattice period, so each cell holds
//! one plane's whole deposit).

use clump_core::boundary::Domain;
use clump_io::post::fields::coarse_grain;
use clump_io::post::frame::{BodyState, Frame};
use clump_io::post::grid::Grid;
use clump_io::post::kernel::Kernel;
use clump_io::post::write::csv_1d;
use glam::{DQuat, DVec3};
use std::f64::consts::PI;

/// A body at rest at `x`: a sphere of radius `r`, density 2500 kg/m³.
fn ball(id: u64, x: DVec3, r: f64) -> BodyState {
    let volume = 4.0 / 3.0 * PI * r.powi(3);
    let mass = 2500.0 * volume;
    BodyState {
        id,
        template: 0,
        position: x,
        velocity: DVec3::ZERO,
        angular_velocity: DVec3::ZERO,
        orientation: DQuat::IDENTITY,
        mass,
        volume,
        inertia: DVec3::splat(0.4 * mass * r * r),
        force: DVec3::ZERO,
        torque: DVec3::ZERO,
    }
}

fn frame(domain: Domain, bodies: Vec<BodyState>) -> Frame {
    Frame {
        step: 0,
        time: 0.0,
        domain,
        bodies,
        contacts: None,
    }
}

fn grid(domain: Domain, axes: Vec<usize>, cells: Vec<usize>, kernel: Kernel, width: f64) -> Grid {
    let lo = axes.iter().map(|&a| domain.lo[a]).collect();
    let hi = axes.iter().map(|&a| domain.hi[a]).collect();
    Grid {
        axes,
        lo,
        hi,
        cells,
        kernel,
        width,
        domain,
    }
}

#[test]
fn a_sphere_inside_a_cell_gives_one_minus_its_volume_over_the_cell() {
    let h = 0.01;
    let domain = Domain {
        lo: DVec3::ZERO,
        hi: DVec3::splat(3.0 * h),
        periodic: [false; 3],
    };
    let r = 0.002;
    // Lucy's kernel reaches w √10.5 = 3.24 mm < h/2 from the cell's centre
    let f = frame(domain, vec![ball(1, DVec3::splat(1.5 * h), r)]);
    let g = grid(domain, vec![0, 1, 2], vec![3, 3, 3], Kernel::Lucy, 0.001);
    let eps = coarse_grain(&f, &g).void_fraction();
    let expect = 1.0 - 4.0 / 3.0 * PI * r.powi(3) / h.powi(3);
    for (c, e) in eps.iter().enumerate() {
        if c == 13 {
            assert!((e - expect).abs() < 1e-15, "{e} vs {expect}");
        } else {
            assert_eq!(*e, 1.0, "cell {c}");
        }
    }
}

#[test]
fn simple_cubic_packing_gives_one_minus_pi_over_six() {
    // 4 × 4 × 4 touching spheres (r = a/2) in a periodic box of 4a
    let a = 0.002;
    let n = 4;
    let domain = Domain {
        lo: DVec3::ZERO,
        hi: DVec3::splat(n as f64 * a),
        periodic: [true; 3],
    };
    let mut bodies = Vec::new();
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let x = (DVec3::new(i as f64, j as f64, k as f64) + 0.5) * a;
                bodies.push(ball(bodies.len() as u64 + 1, x, a / 2.0));
            }
        }
    }
    let f = frame(domain, bodies);
    let expect = 1.0 - PI / 6.0;
    for (axes, cells, kernel, width) in [
        (vec![2], vec![n], Kernel::Gaussian, 0.6 * a),
        (vec![0, 2], vec![n, n], Kernel::Lucy, 0.3 * a),
        (vec![0, 1, 2], vec![n, n, n], Kernel::Gaussian, 0.25 * a),
    ] {
        let g = grid(domain, axes.clone(), cells, kernel, width);
        let eps = coarse_grain(&f, &g).void_fraction();
        for e in &eps {
            assert!((e - expect).abs() < 1e-12, "{axes:?}: {e} vs {expect}");
        }
    }
    // written beside the other fields, last column of the 1D CSV
    let g = grid(domain, vec![2], vec![n], Kernel::Gaussian, 0.6 * a);
    let csv = csv_1d(&g, &coarse_grain(&f, &g));
    let mut lines = csv.lines();
    assert!(lines.next().unwrap().ends_with(",void_fraction"));
    for l in lines {
        let e: f64 = l.rsplit(',').next().unwrap().parse().unwrap();
        assert!((e - expect).abs() < 1e-12, "{l}");
    }
}
