//! Angle of repose of tetra-clump heaps: a column of clumps settles
//! between two gates, the gates are removed and the column collapses into
//! a heap on the rough floor z = 0; the slope angle is fitted to the
//! surface profile. Published trend: the angle rises with sliding and
//! rolling friction. Periodic in y (a slab), world frame z up.

use super::{fill, rayleigh_dt, settle};
use crate::case::{Case, Group};
use crate::ode::slope;
use crate::plot::{draw, Chart, Series, Style};
use crate::setup::*;
use clump_core::boundary::Domain;
use clump_core::contact::{PairProperties, RollingLaw};
use clump_core::wall::WallShape;
use glam::DVec3;
use std::path::Path;

const R: f64 = 1e-3;
const HALF_WIDTH: f64 = 0.008;
const DEPTH: f64 = 0.012;

/// Heap angle (deg) for sliding friction `mu` and rolling friction `mu_r`,
/// the two flanks' angles (deg) and the surface profile `(x mm, height mm)`.
fn heap(mu: f64, mu_r: f64, n: usize) -> Result<(f64, (f64, f64), Vec<(f64, f64)>), String> {
    let mat = material(5e6, 0.3, 2500.0);
    let dt = rayleigh_dt(&mat, R, 0.2);
    let dom = Domain {
        lo: DVec3::new(-0.08, 0.0, -0.01),
        hi: DVec3::new(0.08, DEPTH, 0.2),
        periodic: [false, true, false],
    };
    let p = PairProperties {
        restitution: 0.3,
        friction: mu,
        rolling_friction: mu_r,
        rolling: if mu_r > 0.0 {
            RollingLaw::Cdt
        } else {
            RollingLaw::None
        },
        ..PairProperties::default()
    };
    let mut w = world(mat, p, dt, dom, DVec3::new(0.0, 0.0, -9.81))?;
    let t = w
        .add_template(tetra(R, 1.2e-3, mat.density)?, PARTICLE)
        .map_err(|e| e.to_string())?;
    w.add_wall(plane(DVec3::ZERO, DVec3::Z))
        .map_err(|e| e.to_string())?;
    let gates = [
        w.add_wall(wall(
            "gate-",
            WallShape::Plane {
                point: DVec3::new(-HALF_WIDTH, 0.0, 0.0),
                normal: DVec3::X,
            },
        ))
        .map_err(|e| e.to_string())?,
        w.add_wall(wall(
            "gate+",
            WallShape::Plane {
                point: DVec3::new(HALF_WIDTH, 0.0, 0.0),
                normal: -DVec3::X,
            },
        ))
        .map_err(|e| e.to_string())?,
    ];
    let br = w.templates[t as usize].bounding_radius;
    let placed = fill(
        &mut w,
        t,
        DVec3::new(-HALF_WIDTH, 0.0, 0.0),
        DVec3::new(HALF_WIDTH, DEPTH, 0.12),
        n,
        5,
    )?;
    if placed != n {
        return Err(format!("placed only {placed} of {n} clumps"));
    }
    let m = w.templates[t as usize].mass;
    let ke_tol = 1e-4 * m * 9.81 * 2.0 * R;
    settle(&mut w, 20_000, 60_000, ke_tol)?;
    for gi in gates {
        w.walls[gi].active = false;
    }
    settle(&mut w, 20_000, 60_000, ke_tol)?;
    // surface: highest sphere top per 2-mm bin in x
    let bin = 3.0 * R;
    let nb = (0.16 / bin) as usize;
    let mut top = vec![0.0f64; nb];
    for x in &w.bodies.position {
        let k = ((x.x + 0.08) / bin) as usize;
        if k < nb {
            top[k] = top[k].max(x.z + br);
        }
    }
    let profile: Vec<(f64, f64)> = top
        .iter()
        .enumerate()
        .filter(|(_, &h)| h > 0.0)
        .map(|(k, &h)| ((-0.08 + (k as f64 + 0.5) * bin) * 1e3, h * 1e3))
        .collect();
    let hmax = profile.iter().map(|p| p.1).fold(0.0, f64::max);
    // heights above the single layer left on the floor
    let base = profile.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let (lo, hi) = (base + 0.2 * (hmax - base), base + 0.8 * (hmax - base));
    let slope_of = |sign: f64| {
        let pts: Vec<(f64, f64)> = profile
            .iter()
            .copied()
            .filter(|p| p.0 * sign > 0.0 && p.1 > lo && p.1 < hi)
            .collect();
        if pts.len() < 3 {
            f64::NAN
        } else {
            (-sign * slope(&pts)).atan().to_degrees()
        }
    };
    let flanks = (slope_of(-1.0), slope_of(1.0));
    Ok((0.5 * (flanks.0 + flanks.1), flanks, profile))
}

/// Runs the friction and rolling-friction series.
pub fn run(g: &mut Group, dir: &Path) -> Result<(), String> {
    let n = 300;
    let mut profiles = Vec::new();
    let mut flanks = Vec::new();
    let mut trend = |label: &str,
                     runs: &[(f64, f64)],
                     key: fn(&(f64, f64)) -> f64,
                     profiles: &mut Vec<Series>|
     -> Result<Vec<(f64, f64)>, String> {
        let mut out = Vec::new();
        for r in runs {
            let (a, fl, prof) = heap(r.0, r.1, n)?;
            out.push((key(r), a));
            flanks.push(format!(
                "μ {} μ_r {}: {:.1}° / {:.1}°",
                r.0, r.1, fl.0, fl.1
            ));
            profiles.push(Series::new(
                format!("μ = {}, μ_r = {}: {a:.1}°", r.0, r.1),
                prof,
                Style::Line,
            ));
        }
        let rising = out.windows(2).all(|p| p[1].1 > p[0].1);
        let list: Vec<String> = out.iter().map(|p| format!("{:.1}°", p.1)).collect();
        g.cases.push(Case {
            name: format!("tetra-clump heap: angle rises with {label}"),
            source: "published trend (e.g. Zhou et al. 2002, angle of repose vs sliding and rolling friction)".into(),
            expected: "strictly increasing".into(),
            measured: list.join(" < ? "),
            tolerance: "monotonic".into(),
            pass: rising && out.iter().all(|p| p.1.is_finite()),
        });
        Ok(out)
    };
    let by_mu = trend(
        "sliding friction μ (μ_r = 0)",
        &[(0.1, 0.0), (0.3, 0.0), (0.6, 0.0)],
        |r| r.0,
        &mut profiles,
    )?;
    let by_mur = trend(
        "rolling friction μ_r (μ = 0.3, CDT law)",
        &[(0.3, 0.05), (0.3, 0.15)],
        |r| r.1,
        &mut profiles,
    )?;
    let mut by_mur_full = vec![(0.0, by_mu[1].1)];
    by_mur_full.extend(by_mur.iter().copied());
    if let Some(c) = g.cases.last_mut() {
        let rising = by_mur_full.windows(2).all(|p| p[1].1 > p[0].1);
        c.measured = by_mur_full
            .iter()
            .map(|p| format!("μ_r {}: {:.1}°", p.0, p.1))
            .collect::<Vec<_>>()
            .join(", ");
        c.pass = rising;
    }
    if let Some(c) = g.cases.iter_mut().rev().nth(1) {
        c.measured = by_mu
            .iter()
            .map(|p| format!("μ {}: {:.1}°", p.0, p.1))
            .collect::<Vec<_>>()
            .join(", ");
    }
    g.notes.push(format!("angle of repose, left / right flank of each heap (their difference shows the scatter of one realisation): {}", flanks.join("; ")));
    if g.cases.iter().rev().take(2).any(|c| !c.pass) {
        g.notes.push("angle of repose, investigation of the FAIL: a step of the series smaller than the left/right flank difference of the same heap is within the measurement scatter of one small realisation (a heap about four clumps high, fitted over a few 3-mm bins); the column collapse measures a runout angle, lower than a static angle of repose; and tetra clumps interlock, which already resists rolling, so CDT rolling friction changes the angle far less than for spheres. A resolved trend needs several realisations and a larger heap, beyond this budget. The expected trend is not changed.".into());
    }
    g.notes.push(format!("angle of repose: {n} tetra clumps (4 spheres R = 1 mm, centres 1.2 mm apart), slab 12 mm deep periodic in y, column 16 mm wide between two gates, settled, gates removed, settled again; E = 5e6 Pa, e = 0.3, dt = 0.2 t_R; angle = mean of the two flanks' least-squares slopes of the highest clump top per 3-mm bin, between 20 % and 80 % of the heap height above the floor layer"));
    let c = Chart {
        title: "Angle of repose vs friction (tetra clumps)".into(),
        x_label: "friction coefficient".into(),
        y_label: "heap angle (deg)".into(),
        series: vec![
            Series::new("sliding friction μ (μ_r = 0)", by_mu, Style::LinePoints),
            Series::new(
                "rolling friction μ_r (μ = 0.3)",
                by_mur_full,
                Style::LinePoints,
            ),
        ],
    };
    g.plot(
        "bulk_repose_trend.png",
        "Heap angle of tetra clumps against sliding and rolling friction",
        draw(&dir.join("bulk_repose_trend.png"), &c),
    );
    let c = Chart {
        title: "Heap surface profiles".into(),
        x_label: "x (mm)".into(),
        y_label: "surface height (mm)".into(),
        series: profiles,
    };
    g.plot(
        "bulk_repose_profiles.png",
        "Surface profiles of the heaps (highest clump top per 3-mm bin)",
        draw(&dir.join("bulk_repose_profiles.png"), &c),
    );
    Ok(())
}
