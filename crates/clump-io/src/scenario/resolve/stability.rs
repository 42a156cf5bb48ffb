//! The damped-contact stability limit of a scenario's templates
//! (docs/theory.md T-52): the smallest `dt_c` over the contacts its bodies
//! can make, each body responding at the contact point with its effective
//! mass `m/κ` (rotation included).

use super::model::*;
use clump_core::contact::stability::contact_step_limit;
use clump_core::contact::{ContactModel, Material, PairProperties};
use clump_core::health::DEFAULT_MAX_OVERLAP_RATIO;
use clump_core::shape::mobility::sphere_mobility;

/// Spheres of each template tried against the spheres of every other
/// template (those with the smallest limit against an immovable wall).
const CANDIDATES: usize = 8;

/// One surface sphere of a template, as a contact partner: radius (m), mass
/// of its body (kg), mobility factor `κ`, material.
#[derive(Clone, Copy)]
struct Partner {
    radius: f64,
    mass: f64,
    kappa: f64,
    material: u16,
}

/// `dt_c` (s) of a contact of `a` with `b`, or with an immovable wall of
/// `wall_material` when `b` is `None`, at the overlap the health check
/// allows by default (the stiffest a running contact gets).
fn limit(
    a: &Partner,
    b: Option<&Partner>,
    wall_material: u16,
    models: &dyn Fn(u16, u16) -> Option<ContactModel>,
) -> Option<f64> {
    let (mb, r_star, m_star, inv_meff, r_min) = match b {
        Some(b) => (
            b.material,
            a.radius * b.radius / (a.radius + b.radius),
            a.mass * b.mass / (a.mass + b.mass),
            a.kappa / a.mass + b.kappa / b.mass,
            a.radius.min(b.radius),
        ),
        None => (wall_material, a.radius, a.mass, a.kappa / a.mass, a.radius),
    };
    let model = models(a.material, mb)?;
    let overlap = DEFAULT_MAX_OVERLAP_RATIO * r_min;
    let dt = contact_step_limit(&model, r_star, overlap, m_star, 1.0 / inv_meff);
    dt.is_finite().then_some(dt)
}

/// The smallest damped-contact stability limit over every template (at its
/// smallest size in the mixes, `scales`) against every wall material
/// (`wall_materials`) and every other template; `None` when no contact
/// model can be built. `pairs[a·n + b]` are the pair properties.
pub(super) fn stability_limit(
    templates: &[TemplateDef],
    scales: &[f64],
    materials: &[Material],
    pairs: &[PairProperties],
    material_names: &[String],
    wall_materials: &[u16],
) -> Option<StabilityLimit> {
    let n = materials.len();
    let models = |a: u16, b: u16| {
        let p = pairs.get(a as usize * n + b as usize)?;
        ContactModel::new(&materials[a as usize], &materials[b as usize], p).ok()
    };
    let mut best: Option<StabilityLimit> = None;
    let mut consider = |dt: Option<f64>, what: &dyn Fn() -> String, kappa: f64| {
        if let Some(dt) = dt {
            if best.as_ref().map_or(true, |b| dt < b.dt) {
                best = Some(StabilityLimit {
                    dt,
                    contact: what(),
                    kappa,
                });
            }
        }
    };
    // each template's candidate spheres, by their limit against its own material
    let mut cands: Vec<Vec<(usize, Partner)>> = Vec::with_capacity(templates.len());
    for (def, &s) in templates.iter().zip(scales) {
        let tp = &def.template;
        let kappa = sphere_mobility(tp);
        let mut list: Vec<(f64, usize, Partner)> = Vec::new();
        for (i, (sp, &k)) in tp.spheres.iter().zip(&kappa).enumerate() {
            if k <= 0.0 {
                continue; // buried: never touches anything
            }
            let p = Partner {
                radius: sp.radius * s,
                mass: tp.mass * s * s * s,
                kappa: k,
                material: def.material,
            };
            for &wm in wall_materials {
                let what = || {
                    format!(
                        "template '{}' (sphere {i}, κ = {k:.2}) on a wall of material '{}'",
                        def.name, material_names[wm as usize]
                    )
                };
                consider(limit(&p, None, wm, &models), &what, k);
            }
            let own = limit(&p, None, def.material, &models).unwrap_or(f64::INFINITY);
            list.push((own, i, p));
        }
        list.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        list.truncate(CANDIDATES);
        cands.push(list.into_iter().map(|(_, i, p)| (i, p)).collect());
    }
    for (t, ct) in cands.iter().enumerate() {
        for (u, cu) in cands.iter().enumerate().skip(t) {
            for (i, a) in ct {
                for (j, b) in cu {
                    let what = || {
                        format!(
                            "templates '{}' (sphere {i}, κ = {:.2}) and '{}' (sphere {j}, κ = {:.2})",
                            templates[t].name, a.kappa, templates[u].name, b.kappa
                        )
                    };
                    consider(limit(a, Some(b), 0, &models), &what, a.kappa.max(b.kappa));
                }
            }
        }
    }
    best
}
