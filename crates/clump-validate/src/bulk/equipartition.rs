//! Equipartition in an elastic, frictionless gas of tetrahedral clumps in a
//! fully periodic box: started with translation only, the time-averaged
//! rotational and translational kinetic energies become equal (three
//! degrees of freedom each, classical equipartition theorem).

use super::{fill, rayleigh_dt};
use crate::case::{Case, Group};
use crate::plot::{draw, Chart, Series, Style};
use crate::setup::*;
use clump_core::boundary::Domain;
use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::Path;

/// Runs the case.
pub fn run(g: &mut Group, dir: &Path) -> Result<(), String> {
    let mat = material(5e6, 0.3, 2500.0);
    let r = 1e-3;
    let l = 0.02;
    let n = 120;
    let dt = rayleigh_dt(&mat, r, 0.1);
    let dom = Domain {
        lo: DVec3::ZERO,
        hi: DVec3::splat(l),
        periodic: [true; 3],
    };
    let mut w = world(mat, props(1.0, 0.0), dt, dom, DVec3::ZERO)?;
    let t = w
        .add_template(tetra(r, 1.2e-3, mat.density)?, PARTICLE)
        .map_err(|e| e.to_string())?;
    let placed = fill(&mut w, t, DVec3::ZERO, DVec3::splat(l), n, 3)?;
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut mean = DVec3::ZERO;
    let mut v: Vec<DVec3> = (0..w.bodies().len())
        .map(|_| {
            DVec3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            ) * 0.5
        })
        .collect();
    for vi in &v {
        mean += *vi / placed as f64;
    }
    for (i, vi) in v.iter_mut().enumerate() {
        *vi -= mean;
        w.set_body_velocity_at(i, *vi).map_err(|e| e.to_string())?;
    }
    w.prepare().map_err(|e| e.to_string())?;
    let steps = 60_000u64;
    let every = 200;
    let (mut tr, mut ro) = (Vec::new(), Vec::new());
    let (mut sum_t, mut sum_r) = (0.0, 0.0);
    for k in 1..=steps / every {
        w.run(every).map_err(|e| e.to_string())?;
        let th = w.thermo();
        tr.push((w.time, th.kinetic_translational * 1e6));
        ro.push((w.time, th.kinetic_rotational * 1e6));
        if k * every > steps / 3 {
            sum_t += th.kinetic_translational;
            sum_r += th.kinetic_rotational;
        }
    }
    g.cases.push(Case::relative(
        "elastic gas of tetra clumps: time-averaged KE_rot / KE_trans",
        "equipartition theorem (3 + 3 degrees of freedom)",
        1.0,
        sum_r / sum_t,
        0.05,
        "",
    ));
    g.notes.push(format!(
        "equipartition: {placed} tetra clumps (4 spheres R = 1 mm, centres 1.2 mm apart), periodic box 20 mm, solid fraction ≈ {:.2}, e = 1, μ = 0, E = 5e6 Pa, dt = 0.1 t_R = {dt:.2e} s, {steps} steps; average over the last two thirds; start: |v| components uniform in ±0.5 m/s, ω = 0",
        placed as f64 * w.templates[t as usize].volume / (l * l * l)
    ));
    let c = Chart {
        title: "Elastic gas of tetra clumps: kinetic energies".into(),
        x_label: "time (s)".into(),
        y_label: "kinetic energy (µJ)".into(),
        series: vec![
            Series::new("translational", tr, Style::Line),
            Series::new("rotational", ro, Style::Line),
        ],
    };
    g.plot(
        "bulk_equipartition.png",
        "Translational and rotational kinetic energy of the gas (started without rotation)",
        draw(&dir.join("bulk_equipartition.png"), &c),
    );
    Ok(())
}
