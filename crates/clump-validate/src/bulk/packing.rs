//! Random packings of monodisperse spheres (REFERENCE.md §4): frictionless
//! spheres compressed slowly under their own weight reach φ = 0.64 ± 0.01
//! (random close packing); frictional spheres poured under gravity reach
//! 0.58–0.62. Periodic in x and y, a rigid floor z = 0, gravity −z.

use super::{fill, rayleigh_dt, settle};
use crate::case::{Case, Group};
use crate::plot::{draw, Chart, Series, Style};
use crate::setup::*;
use clump_core::boundary::Domain;
use glam::DVec3;
use std::f64::consts::PI;
use std::path::Path;

/// Sphere radius, m; box edge in x and y, m; number of spheres.
const R: f64 = 1e-3;
const L: f64 = 0.02;
const N: usize = 1200;

/// Volume of the part of a sphere (centre height `z`, radius `r`) between
/// the planes `z0 < z1`, m³.
pub fn sphere_slab_volume(z: f64, r: f64, z0: f64, z1: f64) -> f64 {
    // integral of π(r² − (s − z)²) over s in [max(z0, z − r), min(z1, z + r)]
    let a = (z0 - z).max(-r);
    let b = (z1 - z).min(r);
    if b <= a {
        return 0.0;
    }
    PI * (r * r * (b - a) - (b.powi(3) - a.powi(3)) / 3.0)
}

/// Settles the bed; returns (φ in the core slab, slab bounds (m), φ(z) profile, max overlap / R).
fn bed(mu: f64, e: f64, seed: u64) -> Result<(f64, (f64, f64), Vec<(f64, f64)>, f64), String> {
    let mat = material(1e8, 0.3, 2500.0);
    let dt = rayleigh_dt(&mat, R, 0.25);
    let dom = Domain {
        lo: DVec3::new(0.0, 0.0, -0.01),
        hi: DVec3::new(L, L, 0.2),
        periodic: [true, true, false],
    };
    let mut w = world(mat, props(e, mu), dt, dom, DVec3::new(0.0, 0.0, -9.81))?;
    let t = w
        .add_template(coincident_spheres(1, R, mat.density)?, PARTICLE)
        .map_err(|e| e.to_string())?;
    w.add_wall(plane(DVec3::ZERO, DVec3::Z))
        .map_err(|e| e.to_string())?;
    let placed = fill(
        &mut w,
        t,
        DVec3::new(0.0, 0.0, R),
        DVec3::new(L, L, 0.055),
        N,
        seed,
    )?;
    if placed != N {
        return Err(format!("placed only {placed} of {N} spheres"));
    }
    let m = sphere_mass(R, mat.density);
    settle(&mut w, 40_000, 150_000, 1e-4 * m * 9.81 * 2.0 * R)?;
    let mut z: Vec<f64> = w.bodies().position.clone().iter().map(|p| p.z).collect();
    z.sort_by(|a, b| a.total_cmp(b));
    let top = z[(0.95 * z.len() as f64) as usize];
    let (z0, z1) = (6.0 * R, top - 4.0 * R);
    if z1 <= z0 + 2.0 * R {
        return Err(format!("bed too shallow: top {top:.4} m"));
    }
    let phi_in = |a: f64, b: f64| {
        z.iter()
            .map(|&zc| sphere_slab_volume(zc, R, a, b))
            .sum::<f64>()
            / (L * L * (b - a))
    };
    let profile: Vec<(f64, f64)> = (0..((top + 2.0 * R) / R) as usize)
        .map(|k| {
            let a = k as f64 * R;
            ((a + 0.5 * R) / (2.0 * R), phi_in(a, a + R))
        })
        .collect();
    Ok((
        phi_in(z0, z1),
        (z0, z1),
        profile,
        w.thermo().max_overlap_ratio,
    ))
}

/// Runs both packings.
pub fn run(g: &mut Group, dir: &Path) -> Result<(), String> {
    let mut series = Vec::new();
    for (label, mu, e, lo, hi) in [
        (
            "frictionless spheres settled slowly under gravity (μ = 0, e = 0.1)",
            0.0,
            0.1,
            0.63,
            0.65,
        ),
        (
            "frictional spheres poured under gravity (μ = 0.5, e = 0.5)",
            0.5,
            0.5,
            0.58,
            0.62,
        ),
    ] {
        let (phi, (z0, z1), profile, ov) = bed(mu, e, 7)?;
        g.cases.push(Case::range(
            format!("packing fraction, {label}"),
            "REFERENCE.md §4",
            lo,
            hi,
            phi,
            "",
        ));
        g.notes.push(format!(
            "packing, {label}: {N} spheres R = 1 mm, box 20 × 20 mm periodic in x, y; E = 1e8 Pa, dt = 0.25 t_R; φ measured between z = {:.1} and {:.1} mm (≥ 3 d above the floor, ≥ 2 d below the surface); largest overlap {:.2e} R",
            z0 * 1e3,
            z1 * 1e3,
            ov
        ));
        series.push(Series::new(
            if mu == 0.0 { "μ = 0" } else { "μ = 0.5" },
            profile,
            Style::LinePoints,
        ));
    }
    series.push(Series::new(
        "0.64",
        vec![(0.0, 0.64), (12.0, 0.64)],
        Style::Dashed,
    ));
    let c = Chart {
        title: "Packing fraction profile of settled sphere beds".into(),
        x_label: "height above the floor (sphere diameters)".into(),
        y_label: "packing fraction in 1-R slices".into(),
        series,
    };
    g.plot("bulk_packing_profile.png", "Packing fraction in slices of one radius: frictionless (expected 0.64 in the core) and frictional (0.58–0.62)", draw(&dir.join("bulk_packing_profile.png"), &c));
    Ok(())
}
