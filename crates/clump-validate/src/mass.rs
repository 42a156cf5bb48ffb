//! Mass properties of overlapping spheres (REFERENCE.md §2): the two-sphere
//! table (overlap-exact and naive), the closed-form dimer formulas at SI
//! scale, the lens volume, and coincident spheres.

use crate::case::{Case, Group};
use crate::setup::{coincident_spheres, dimer};
use crate::Selection;
use clump_core::shape::{mass_properties, Sphere};
use glam::DVec3;
use std::f64::consts::PI;
use std::path::Path;

const SRC2: &str = "REFERENCE.md §2";

/// Overlap-exact volume, axial and transverse moment (about the centre of
/// mass) of two equal spheres of radius `r` at `±a` with density `rho`
/// (REFERENCE.md §2 formulas): `(V m³, I_axis kg m², I_trans kg m²)`.
pub fn dimer_formula(r: f64, a: f64, rho: f64) -> (f64, f64, f64) {
    let v = 2.0 * PI / 3.0 * (2.0 * r - a) * (r + a).powi(2);
    let ia = rho
        * PI
        * (8.0 * r.powi(5) / 15.0 + r.powi(4) * a - 2.0 / 3.0 * r * r * a.powi(3)
            + a.powi(5) / 5.0);
    let it = rho
        * PI
        * (8.0 * r.powi(5) / 15.0
            + 1.5 * r.powi(4) * a
            + 4.0 / 3.0 * r.powi(3) * a * a
            + r * r * a.powi(3) / 3.0
            + a.powi(5) / 30.0);
    (v, ia, it)
}

fn table(g: &mut Group) -> Result<(), String> {
    // d, V, I_axis, I_trans, naive V, naive I_axis, naive I_trans (R = 1, ρ = 1)
    let rows = [
        (
            0.5, 5.726862, 2.428803, 3.131877, 8.377580, 3.351032, 3.874631,
        ),
        (
            1.0, 7.068583, 3.004148, 5.213080, 8.377580, 3.351032, 5.445427,
        ),
        (
            1.5, 8.017606, 3.297241, 8.032639, 8.377580, 3.351032, 8.063421,
        ),
    ];
    // the table has 7 significant digits
    let tol = 1e-6;
    for (d, v, ia, it, nv, nia, nit) in rows {
        let t = dimer(1.0, d / 2.0, 1.0)?;
        let p = &t.properties;
        let pm = p.principal_moments;
        let npm = p.naive_principal_moments;
        let src = format!("{SRC2} table, d = {d}");
        for (what, exp, got) in [
            ("V", v, p.volume),
            ("I_axis", ia, pm.x),
            ("I_trans", it, pm.y),
            ("I_trans (2nd)", it, pm.z),
            ("naive V", nv, p.naive_volume),
            ("naive I_axis", nia, npm.x),
            ("naive I_trans", nit, npm.y),
        ] {
            g.cases.push(Case::relative(
                format!("two unit spheres, d = {d}: {what}"),
                src.clone(),
                exp,
                got,
                tol,
                "",
            ));
        }
    }
    Ok(())
}

fn si_dimer(g: &mut Group) -> Result<(), String> {
    // SI scale: R = 1.5 mm, centres 1.8 mm apart, ρ = 2500 kg/m³.
    let (r, a, rho) = (1.5e-3, 0.9e-3, 2500.0);
    let (v, ia, it) = dimer_formula(r, a, rho);
    let t = dimer(r, a, rho)?;
    let src = format!("{SRC2} closed-form dimer formulas");
    g.cases.push(Case::relative(
        "dimer R = 1.5 mm, d = 1.8 mm: mass",
        src.clone(),
        rho * v * 1e6,
        t.mass * 1e6,
        1e-9,
        "mg",
    ));
    g.cases.push(Case::relative(
        "dimer R = 1.5 mm, d = 1.8 mm: I_axis",
        src.clone(),
        ia * 1e12,
        t.principal_inertia.x * 1e12,
        1e-9,
        "mg mm²",
    ));
    g.cases.push(Case::relative(
        "dimer R = 1.5 mm, d = 1.8 mm: I_trans",
        src,
        it * 1e12,
        t.principal_inertia.y * 1e12,
        1e-9,
        "mg mm²",
    ));
    Ok(())
}

fn lens(g: &mut Group) -> Result<(), String> {
    let (r1, r2, d) = (1.0, 0.5, 1.0);
    let s = [
        Sphere {
            center: DVec3::ZERO,
            radius: r1,
        },
        Sphere {
            center: DVec3::new(0.0, 0.0, d),
            radius: r2,
        },
    ];
    let p = mass_properties(&s, 1.0).map_err(|e| e.to_string())?;
    let lens = 4.0 / 3.0 * PI * (r1.powi(3) + r2.powi(3)) - p.volume;
    g.cases.push(Case::absolute(
        "lens volume R1 = 1, R2 = 0.5, d = 1 (V1 + V2 − V_union)",
        format!("{SRC2} lens formula"),
        0.212712,
        lens,
        5e-7,
        "",
    ));
    Ok(())
}

fn coincident(g: &mut Group) -> Result<(), String> {
    let (r, rho) = (2e-3, 2500.0);
    let one = coincident_spheres(1, r, rho)?;
    let four = coincident_spheres(4, r, rho)?;
    let m = rho * 4.0 / 3.0 * PI * r.powi(3);
    let i = 0.4 * m * r * r;
    let src = format!("{SRC2} (coincident spheres)");
    for (what, exp, got, unit) in [
        ("1 sphere R = 2 mm: mass", m * 1e6, one.mass * 1e6, "mg"),
        (
            "4 coincident spheres R = 2 mm: mass",
            m * 1e6,
            four.mass * 1e6,
            "mg",
        ),
        (
            "4 coincident spheres R = 2 mm: largest moment",
            i * 1e12,
            four.principal_inertia.max_element() * 1e12,
            "mg mm²",
        ),
        (
            "4 coincident spheres R = 2 mm: smallest moment",
            i * 1e12,
            four.principal_inertia.min_element() * 1e12,
            "mg mm²",
        ),
    ] {
        g.cases
            .push(Case::relative(what, src.clone(), exp, got, 1e-12, unit));
    }
    Ok(())
}

/// Runs the mass-properties group.
pub fn run(_sel: Selection, _dir: &Path) -> Group {
    let mut g = Group::default();
    let parts: [(&str, fn(&mut Group) -> Result<(), String>); 4] = [
        ("table", table),
        ("SI dimer", si_dimer),
        ("lens", lens),
        ("coincident", coincident),
    ];
    for (name, f) in parts {
        if let Err(e) = f(&mut g) {
            g.cases.push(Case::error(name, SRC2, e));
        }
    }
    g
}
