//! Coarse-grained fields against values from outside the code, on a small
//! settled bed in a laterally periodic box: mass conservation, momentum
//! balance `σ_zz(z) = g ∫_z^top ρ dz'`, the floor's load per area from
//! thermo.csv, Love–Weber's `Σ f ⊗ l / V`, and an isotropic order tensor
//! for random orientations.

mod post;

use clump_io::post::fields::coarse_grain;
use clump_io::post::frame::Frame;
use clump_io::post::grid::Grid;
use clump_io::post::kernel::Kernel;
use glam::{DMat3, DVec3};

fn grid_z(frame: &Frame, kernel: Kernel, width: f64, lo: f64, hi: f64, cells: usize) -> Grid {
    Grid {
        axes: vec![2],
        lo: vec![lo],
        hi: vec![hi],
        cells: vec![cells],
        kernel,
        width,
        domain: frame.domain,
    }
}

#[test]
fn settled_bed_mass_momentum_balance_floor_and_love_weber() {
    let d = post::dir("cg");
    let r = post::run(
        &post::bed_text(120, 7, "thermo = { every = 0.01 }\nvtk = { every = 1.0 }"),
        &d,
    );
    let w = r.world();
    let frame = Frame::capture(w);
    assert!(frame.contacts.is_some());
    let total: f64 = frame.bodies.iter().map(|b| b.mass).sum();
    let g = 9.81;
    let area = 0.02 * 0.02;
    let ke: f64 = frame
        .bodies
        .iter()
        .map(|b| 0.5 * b.mass * b.velocity.length_squared())
        .sum();
    eprintln!(
        "kinetic energy {ke:e} J, potential scale {:e} J",
        total * g * 0.01
    );

    // mass: Σ ρ V over the cells is the total mass (both kernels, 1D and 3D)
    for kernel in [Kernel::Gaussian, Kernel::Lucy] {
        let gz = grid_z(&frame, kernel, 0.0015, -0.02, 0.07, 90);
        let f = coarse_grain(&frame, &gz);
        let m: f64 = f.density.iter().sum::<f64>() * gz.cell_volume();
        assert!(
            (m - total).abs() <= 1e-10 * total,
            "{kernel:?}: {m} vs {total}"
        );
        let g3 = Grid {
            axes: vec![0, 1, 2],
            lo: vec![0.0, 0.0, -0.02],
            hi: vec![0.02, 0.02, 0.07],
            cells: vec![5, 4, 30],
            kernel,
            width: 0.0015,
            domain: frame.domain,
        };
        let f3 = coarse_grain(&frame, &g3);
        let m3: f64 = f3.density.iter().sum::<f64>() * g3.cell_volume();
        assert!(
            (m3 - total).abs() <= 1e-10 * total,
            "3D {kernel:?}: {m3} vs {total}"
        );
    }

    // momentum balance in the bulk, more than two widths from the floor
    // and the free surface
    let width = 0.001;
    let gz = grid_z(&frame, Kernel::Gaussian, width, -0.01, 0.05, 240);
    let f = coarse_grain(&frame, &gz);
    let h = gz.spacing(0);
    let s = f.stress();
    let top = frame
        .bodies
        .iter()
        .map(|b| b.position.z + 0.0023)
        .fold(f64::MIN, f64::max);
    let mut above = 0.0;
    let mut checked = 0;
    let mut worst: f64 = 0.0;
    for k in (0..gz.len()).rev() {
        let z = gz.centre(0, k);
        let load = g * (above + 0.5 * f.density[k] * h);
        above += f.density[k] * h;
        if std::env::var("CG_PROFILE").is_ok() {
            eprintln!(
                "{z:.5} {:.4} {:.4} {:.2}",
                s[k].z_axis.z, load, f.density[k]
            );
        }
        if z > 2.0 * width + 0.0015
            && z < top - 2.0 * width - 0.003
            && std::env::var("CG_PROFILE").is_err()
        {
            let e = (s[k].z_axis.z - load).abs() / load;
            worst = worst.max(e);
            checked += 1;
            assert!(e < 0.03, "z = {z}: σ_zz {} vs g∫ρ {load}", s[k].z_axis.z);
        }
    }
    eprintln!(
        "momentum balance: {checked} cells, worst {:.3} %",
        100.0 * worst
    );
    assert!(checked > 20, "{checked} cells in the bulk (top {top})");

    // the floor: in the layer between the floor and the lowest centres
    // only floor contacts carry stress; σ_zz = −floor_fz / A
    let thermo = d.join("run/thermo.csv");
    let fz = post::last_column(&thermo, "floor_fz[N]");
    let narrow = 0.00008;
    let gf = grid_z(&frame, Kernel::Gaussian, narrow, 0.0, 0.0012, 12);
    let ff = coarse_grain(&frame, &gf);
    let sf = ff.stress();
    let lowest = frame
        .bodies
        .iter()
        .map(|b| b.position.z)
        .fold(f64::MAX, f64::min);
    assert!(lowest > 0.0014, "lowest centre {lowest}");
    for k in 0..gf.len() {
        let z = gf.centre(0, k);
        if z > 3.0 * narrow + 0.0001 && z < 0.0012 - 3.0 * narrow {
            let e = (sf[k].z_axis.z + fz / area).abs() / (fz / area).abs();
            assert!(
                e < 1e-3,
                "z = {z}: σ_zz {} vs floor {}",
                sf[k].z_axis.z,
                -fz / area
            );
        }
    }

    // Love–Weber: the volume average of the contact stress is
    // −Σ_contacts Σ_sides f ⊗ l / V, with l from each body's centre of mass
    // to the contact point (the engine's contacts and bodies directly)
    let g3 = Grid {
        axes: vec![0, 1, 2],
        lo: vec![0.0, 0.0, -0.02],
        hi: vec![0.02, 0.02, 0.07],
        cells: vec![4, 4, 36],
        kernel: Kernel::Lucy,
        width: 0.0012,
        domain: frame.domain,
    };
    let f3 = coarse_grain(&frame, &g3);
    let volume = 0.02 * 0.02 * 0.09;
    let avg =
        f3.contact_stress.iter().fold(DMat3::ZERO, |a, b| a + *b) * (g3.cell_volume() / volume);
    let mut love = DMat3::ZERO;
    let l_of = |id: u64, p: DVec3| {
        let i = w.body_index(id).unwrap();
        let mut l = p - w.bodies().position[i];
        for a in 0..2 {
            l[a] -= 0.02 * (l[a] / 0.02).round();
        }
        l
    };
    let outer = |f: DVec3, l: DVec3| DMat3::from_cols(f * l.x, f * l.y, f * l.z);
    for c in w.contacts().unwrap() {
        love -= outer(c.force(), l_of(c.body_id, c.point));
        if let clump_core::recorded_contacts::Partner::Sphere { body_id, .. } = c.partner {
            love -= outer(-c.force(), l_of(body_id, c.point));
        }
    }
    love = love / volume;
    let scale = love.z_axis.z.abs();
    for (a, b) in [
        (avg.x_axis, love.x_axis),
        (avg.y_axis, love.y_axis),
        (avg.z_axis, love.z_axis),
    ] {
        assert!(
            (a - b).length() <= 1e-10 * scale,
            "CG {a} vs Love–Weber {b}"
        );
    }
    assert!(scale > 0.0);
    let _ = std::fs::remove_dir_all(&d);
}

/// Bodies packed with uniformly random orientations: every component of
/// the order tensor of their long axes is zero within four standard errors
/// (for isotropic unit vectors, var Q_ii = 1/5, var Q_ij = 3/20 per body).
#[test]
fn random_orientations_give_an_isotropic_order_tensor() {
    let d = post::dir("order");
    let r = post::run(
        &post::bed_text_steps(160, 11, 1, "thermo = { every_steps = 1 }"),
        &d,
    );
    let frame = Frame::capture(r.world());
    let n = frame.bodies.len() as f64;
    assert!(n >= 160.0, "{n} bodies");
    let g = Grid {
        axes: vec![2],
        lo: vec![-0.05],
        hi: vec![0.1],
        cells: vec![1],
        kernel: Kernel::Gaussian,
        width: 0.001,
        domain: frame.domain,
    };
    let f = coarse_grain(&frame, &g);
    let q = f.order()[0];
    for i in 0..3 {
        for j in 0..3 {
            let var = if i == j { 0.2 } else { 0.15 };
            let v = q.col(j)[i];
            assert!(v.abs() < 4.0 * (var / n).sqrt(), "Q[{i}][{j}] = {v}");
        }
    }
    assert!((q.x_axis.x + q.y_axis.y + q.z_axis.z).abs() < 1e-12);
    let _ = std::fs::remove_dir_all(&d);
}
