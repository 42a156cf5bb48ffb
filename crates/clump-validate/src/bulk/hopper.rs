//! Beverloo discharge of a flat-bottomed hopper: frictional spheres settle
//! in a square box on a floor with a circular orifice (a triangle-mesh
//! plate), the orifice is opened and the mass flow rate W is measured for
//! several orifice diameters D0. Beverloo's law (REFERENCE.md §4):
//! W = C ρ_b √g (D0 − k d)^{5/2}, C ≈ 0.58, k ≈ 1.4 to 1.6. World frame z up.

use super::{fill, rayleigh_dt, settle};
use crate::case::{Case, Group};
use crate::ode::slope;
use crate::plot::{draw, Chart, Series, Style};
use crate::setup::*;
use clump_core::boundary::Domain;
use clump_core::wall::{TriMesh, WallShape};
use glam::{DQuat, DVec3};
use std::f64::consts::TAU;
use std::path::Path;

const R: f64 = 1e-3;
const D: f64 = 2.0 * R;
/// Box edge (m) and number of spheres.
const WIDTH: f64 = 0.03;
const N: usize = 3000;
/// Orifice diameters, m.
const ORIFICES: [f64; 4] = [0.008, 0.0095, 0.011, 0.0125];

/// A square plate `[−w/2, w/2]²` at z = 0 with a 32-gon hole of radius
/// `r_hole` (m) at the centre.
fn plate_with_hole(w: f64, r_hole: f64) -> Result<TriMesh, String> {
    let n = 32; // a multiple of 8: the outer ring hits the square's corners
    let mut v = Vec::with_capacity(2 * n);
    for k in 0..n {
        let a = TAU * k as f64 / n as f64;
        let dir = DVec3::new(a.cos(), a.sin(), 0.0);
        v.push(dir * r_hole);
        v.push(dir * (0.5 * w / a.cos().abs().max(a.sin().abs())));
    }
    let mut t = Vec::with_capacity(2 * n);
    for k in 0..n as u32 {
        let k1 = (k + 1) % n as u32;
        let (i0, o0, i1, o1) = (2 * k, 2 * k + 1, 2 * k1, 2 * k1 + 1);
        t.push([i0, o0, o1]);
        t.push([i0, o1, i1]);
    }
    TriMesh::new(v, t).map_err(|e| e.to_string())
}

/// Discharge rate (kg/s) through an orifice of diameter `d0` (m), and the
/// bulk density of the settled fill (kg/m³).
fn discharge(d0: f64) -> Result<(f64, f64, Vec<(f64, f64)>), String> {
    let mat = material(5e6, 0.3, 2500.0);
    let dt = rayleigh_dt(&mat, R, 0.25);
    let h = 0.5 * WIDTH;
    let dom = Domain {
        lo: DVec3::new(-h, -h, -0.03),
        hi: DVec3::new(h, h, 0.1),
        periodic: [false; 3],
    };
    let mut w = world(mat, props(0.5, 0.5), dt, dom, DVec3::new(0.0, 0.0, -9.81))?;
    let t = w
        .add_template(coincident_spheres(1, R, mat.density)?, PARTICLE)
        .map_err(|e| e.to_string())?;
    for (p, nrm) in [
        (DVec3::X, -DVec3::X),
        (-DVec3::X, DVec3::X),
        (DVec3::Y, -DVec3::Y),
        (-DVec3::Y, DVec3::Y),
    ] {
        w.add_wall(plane(p * h, nrm)).map_err(|e| e.to_string())?;
    }
    let mesh = w.add_mesh(plate_with_hole(WIDTH, 0.5 * d0)?);
    w.add_wall(wall(
        "orifice plate",
        WallShape::Mesh {
            mesh,
            position: DVec3::ZERO,
            orientation: DQuat::IDENTITY,
        },
    ))
    .map_err(|e| e.to_string())?;
    let lid = w
        .add_wall(plane(DVec3::ZERO, DVec3::Z))
        .map_err(|e| e.to_string())?;
    let placed = fill(
        &mut w,
        t,
        DVec3::new(-h + R, -h + R, R),
        DVec3::new(h - R, h - R, 0.095),
        N,
        9,
    )?;
    if placed != N {
        return Err(format!("placed only {placed} of {N} spheres"));
    }
    let m = sphere_mass(R, mat.density);
    let t0 = std::time::Instant::now();
    let n_settle = settle(&mut w, 6_000, 20_000, 1e-3 * m * 9.81 * D)?;
    if std::env::var_os("CLUMP_VALIDATE_VERBOSE").is_some() {
        eprintln!(
            "hopper D0 {d0}: settled in {n_settle} steps, {:.1} s",
            t0.elapsed().as_secs_f64()
        );
    }
    let mut z: Vec<f64> = w.bodies.position.iter().map(|p| p.z).collect();
    z.sort_by(|a, b| a.total_cmp(b));
    let top = z[(0.95 * z.len() as f64) as usize];
    let rho_b = (N as f64 * m) / (WIDTH * WIDTH * (top + R));
    w.walls[lid].active = false;
    let t_open = w.time;
    let mass_above = |w: &clump_core::world::World| {
        w.bodies.position.iter().filter(|p| p.z > 0.0).count() as f64 * m
    };
    let m0 = mass_above(&w);
    let mut hist = Vec::new();
    let steps = (0.3 / dt) as u64;
    let every = (0.004 / dt).max(1.0) as u64;
    let mut k = 0;
    while k < steps {
        w.run(every).map_err(|e| e.to_string())?;
        k += every;
        hist.push((w.time - t_open, m0 - mass_above(&w)));
    }
    if std::env::var_os("CLUMP_VALIDATE_VERBOSE").is_some() {
        eprintln!(
            "hopper D0 {d0}: discharged {:.2} g, {:.1} s",
            hist.last().map_or(0.0, |p| p.1 * 1e3),
            t0.elapsed().as_secs_f64()
        );
    }
    let window: Vec<(f64, f64)> = hist.iter().copied().filter(|p| p.0 >= 0.05).collect();
    if window.len() < 5 {
        return Err("too few samples".into());
    }
    Ok((slope(&window), rho_b, hist))
}

/// Fits log W = log A + n log(D0 − k d) over k by least squares; returns (n, k, A).
fn fit_beverloo(data: &[(f64, f64)]) -> (f64, f64, f64) {
    let mut best = (f64::INFINITY, 0.0, 0.0, 0.0);
    let dmin = data.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
    let kmax = (dmin / D - 0.05).min(3.5);
    let steps = 3500;
    for i in 0..=steps {
        let k = kmax * i as f64 / steps as f64;
        let pts: Vec<(f64, f64)> = data
            .iter()
            .map(|&(d0, wr)| ((d0 - k * D).ln(), wr.ln()))
            .collect();
        let n = slope(&pts);
        let np = pts.len() as f64;
        let la = pts.iter().map(|p| p.1 - n * p.0).sum::<f64>() / np;
        let res: f64 = pts.iter().map(|p| (p.1 - la - n * p.0).powi(2)).sum();
        if res < best.0 {
            best = (res, n, k, la.exp());
        }
    }
    (best.1, best.2, best.3)
}

/// Runs the hopper series.
pub fn run(g: &mut Group, dir: &Path) -> Result<(), String> {
    let mut data = Vec::new();
    let mut curves = Vec::new();
    let mut rho = 0.0;
    for d0 in ORIFICES {
        let (wr, rho_b, hist) = discharge(d0)?;
        data.push((d0, wr));
        rho += rho_b / ORIFICES.len() as f64;
        curves.push(Series::new(
            format!("D0 = {} mm: W = {:.1} g/s", d0 * 1e3, wr * 1e3),
            hist.iter().map(|p| (p.0, p.1 * 1e3)).collect(),
            Style::Line,
        ));
    }
    let (n, k, a) = fit_beverloo(&data);
    let c_fit = a / (rho * 9.81f64.sqrt());
    g.cases.push(Case::absolute(
        "hopper discharge: fitted Beverloo exponent",
        "Beverloo's law, REFERENCE.md §4",
        2.5,
        n,
        0.15,
        "",
    ));
    g.cases.push(Case::range(
        "hopper discharge: fitted k (D0 − k d)",
        "Beverloo's law, REFERENCE.md §4 (k ≈ 1.4–1.6)",
        1.2,
        1.8,
        k,
        "",
    ));
    g.notes.push(format!(
        "hopper: {N} spheres d = 2 mm, box 30 × 30 mm, flat floor with a circular orifice (32-gon, triangle mesh), μ = 0.5, e = 0.5, E = 5e6 Pa, dt = 0.25 t_R; W = slope of the discharged mass for t ≥ 50 ms after opening, over 300 ms; measured W (g/s): {}; three-parameter fit: n = {n:.3}, k = {k:.3}, C = {c_fit:.3} with the fill's bulk density ρ_b = {rho:.0} kg/m³ (Beverloo C ≈ 0.58)",
        data.iter().map(|p| format!("D0 {} mm: {:.2}", p.0 * 1e3, p.1 * 1e3)).collect::<Vec<_>>().join(", ")
    ));
    let c = Chart {
        title: "Hopper discharge: mass out vs time".into(),
        x_label: "time after opening (s)".into(),
        y_label: "discharged mass (g)".into(),
        series: curves,
    };
    g.plot(
        "bulk_hopper_discharge.png",
        "Discharged mass against time for each orifice",
        draw(&dir.join("bulk_hopper_discharge.png"), &c),
    );
    let fit_line: Vec<(f64, f64)> = (0..=40)
        .map(|i| 0.007 + 0.0065 * i as f64 / 40.0)
        .filter(|&d0| d0 > k * D)
        .map(|d0| (d0 * 1e3, a * (d0 - k * D).powf(n) * 1e3))
        .collect();
    let bev: Vec<(f64, f64)> = (0..=40)
        .map(|i| 0.007 + 0.0065 * i as f64 / 40.0)
        .map(|d0| {
            (
                d0 * 1e3,
                0.58 * rho * 9.81f64.sqrt() * (d0 - 1.5 * D).powf(2.5) * 1e3,
            )
        })
        .collect();
    let c = Chart {
        title: "Hopper discharge rate vs orifice diameter".into(),
        x_label: "orifice diameter D0 (mm)".into(),
        y_label: "mass flow rate W (g/s)".into(),
        series: vec![
            Series::new(
                "engine",
                data.iter().map(|p| (p.0 * 1e3, p.1 * 1e3)).collect(),
                Style::Points,
            ),
            Series::new(
                format!("fit W = A (D0 − {k:.2} d)^{n:.2}"),
                fit_line,
                Style::Line,
            ),
            Series::new("Beverloo C = 0.58, k = 1.5, n = 2.5", bev, Style::Dashed),
        ],
    };
    g.plot(
        "bulk_hopper_beverloo.png",
        "Discharge rate against orifice diameter with the fitted and the published Beverloo law",
        draw(&dir.join("bulk_hopper_beverloo.png"), &c),
    );
    Ok(())
}
