//! `[[material]]`: elastic constants and densities.

use super::diag::Diagnostic;
use super::raw::{RawMaterial, RawScenario};
use super::Seg::{I, K};
use super::{unique_name, Cx, R};
use crate::scenario::diag::num;
use clump_core::contact::Material;

/// The materials with their names, in file order.
pub(super) fn materials(cx: &mut Cx, raw: &RawScenario) -> R<(Vec<String>, Vec<Material>)> {
    // ---------------- materials
    let mut material_names: Vec<String> = Vec::new();
    let mut materials: Vec<Material> = Vec::new();
    if raw.material.is_empty() {
        return Err(Diagnostic::new(super::diag::Severity::Error, &cx.src.path, "no [[material]] defined")
            .note("help: add at least one, e.g.\n[[material]]\nname = \"glass\"\nyoungs_modulus = 5e6\npoisson_ratio = 0.3\ndensity = 2500"));
    }
    for (i, m) in raw.material.iter().enumerate() {
        match material(cx, i, m, &material_names) {
            Ok((name, mat)) => {
                material_names.push(name);
                materials.push(mat);
            }
            Err(d) => cx.errors.push(d),
        }
    }
    cx.barrier()?;
    Ok((material_names, materials))
}

/// One `[[material]]` entry, checked.
fn material(cx: &Cx, i: usize, m: &RawMaterial, seen: &[String]) -> R<(String, Material)> {
    let p = |k: &'static str| [K("material"), I(i), K(k)];
    let t = [K("material"), I(i)];
    let name = m
        .name
        .clone()
        .ok_or_else(|| cx.missing(&t, "[[material]]", "name", "name = \"glass\""))?;
    unique_name(cx, &p("name"), "material", &name, seen)?;
    let e = m.youngs_modulus.ok_or_else(|| {
        cx.missing(
            &t,
            "[[material]]",
            "youngs_modulus",
            "Young's modulus in Pa, e.g. youngs_modulus = 5e6",
        )
    })?;
    let nu = m.poisson_ratio.ok_or_else(|| {
        cx.missing(
            &t,
            "[[material]]",
            "poisson_ratio",
            "e.g. poisson_ratio = 0.3",
        )
    })?;
    let rho = m.density.ok_or_else(|| {
        cx.missing(
            &t,
            "[[material]]",
            "density",
            "density in kg/m^3, e.g. density = 2500",
        )
    })?;
    if !(e > 0.0) || e.is_nan() {
        return Err(cx
            .err(
                &p("youngs_modulus"),
                format!(
                    "youngs_modulus must be > 0 Pa (inf for a rigid wall material), found {}",
                    num(e)
                ),
            )
            .label("must be positive"));
    }
    if !(nu < 0.5) {
        return Err(cx
                .err(&p("poisson_ratio"), format!("poisson_ratio must be < 0.5, found {}", num(nu)))
                .label("must lie in (-1, 0.5)")
                .note("note: ν = 0.5 is an incompressible solid, for which the Hertz–Mindlin shear modulus terms break down"));
    }
    if !(nu > -1.0) {
        return Err(cx
            .err(
                &p("poisson_ratio"),
                format!("poisson_ratio must be > -1, found {}", num(nu)),
            )
            .label("must lie in (-1, 0.5)"));
    }
    let rigid = e == f64::INFINITY;
    if !(rho.is_finite() && (rho > 0.0 || (rigid && rho >= 0.0))) {
        return Err(cx
            .err(
                &p("density"),
                format!("density must be > 0 kg/m^3, found {}", num(rho)),
            )
            .label("must be positive"));
    }
    Ok((
        name,
        Material {
            youngs_modulus: e,
            poisson_ratio: nu,
            density: rho,
        },
    ))
}
