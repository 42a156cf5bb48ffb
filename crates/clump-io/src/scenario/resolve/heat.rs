//! `[heat]` and the heat keys of `[[material]]`, `[[template]]`,
//! `[[wall]]` and `[[insert]]`: the engine's heat model
//! (`clump_core::heat`), checked key by key, and the thermal stability
//! limit of the time step (docs/theory.md T-57).

use super::diag::num;
use super::model::{HeatDef, MixDef, TemplateDef};
use super::raw::*;
use super::Seg::{self, I, K};
use super::{Cx, R};
use clump_core::contact::Material;
use clump_core::heat::{HeatModel, ThermalMaterial};
use clump_core::wall::Wall;

/// Contacts a sphere is assumed to have at most in the stability limit
/// (the kissing number of equal spheres).
pub const LIMIT_CONTACTS_PER_SPHERE: f64 = 12.0;

/// The settings [`heat`] builds from.
pub(super) struct HeatInput<'a> {
    pub templates: &'a [TemplateDef],
    pub mixes: &'a [MixDef],
    pub materials: &'a [Material],
    pub material_names: &'a [String],
    pub walls: &'a [Wall],
    /// The overlap guard's limit, overlap / radius.
    pub max_overlap_ratio: f64,
    pub dt: f64,
    pub dt_auto: bool,
}

/// The heat model, or `None` without `[heat]` (then no heat key may be
/// given).
pub(super) fn heat(cx: &mut Cx, raw: &RawScenario, inp: &HeatInput) -> R<Option<HeatDef>> {
    let file_temperature = file_temperatures(cx, raw)?;
    let Some(h) = &raw.heat else {
        if let Some(i) = file_temperature.iter().position(|t| t.is_some()) {
            return Err(cx
                .err(&[K("insert"), I(i), K("file")], "the body file has a 'temperature' column, but the scenario no [heat]: heat transfer is off")
                .label("has no effect")
                .note("help: add a [heat] table to turn heat transfer on (docs/scenario.md), or remove the column"));
        }
        return no_heat_keys(cx, raw).map(|()| None);
    };
    let default_t = h
        .temperature
        .map(|t| temperature(cx, &[K("heat"), K("temperature")], t))
        .transpose()?;
    let materials = thermal_materials(cx, raw)?;
    let mut template_temperature = Vec::new();
    let mut template_source = Vec::new();
    for (i, (t, rt)) in inp.templates.iter().zip(&raw.template).enumerate() {
        let p = |k: &'static str| [K("template"), I(i), K(k)];
        let m = &raw.material[t.material as usize];
        if m.thermal_conductivity.is_none() || m.specific_heat.is_none() {
            return Err(cx
                .err(&p("material"), format!("with [heat], the material '{}' of template '{}' needs thermal_conductivity and specific_heat", inp.material_names[t.material as usize], t.name))
                .label("no thermal properties")
                .note("help: add e.g. thermal_conductivity = 1.0 (W/(m K)) and specific_heat = 800 (J/(kg K)) to its [[material]]"));
        }
        let temp = match (rt.temperature, default_t) {
            (Some(x), _) => temperature(cx, &p("temperature"), x)?,
            (None, Some(x)) => x,
            (None, None) => {
                return Err(cx.missing(
                    &[K("template"), I(i)],
                    "[[template]] under [heat]",
                    "temperature",
                    "the initial temperature of its bodies in K, e.g. temperature = 293.15 (or one for all in [heat])",
                ))
            }
        };
        let q = match rt.heat_source {
            Some(q) if !q.is_finite() => {
                return Err(cx.err(
                    &p("heat_source"),
                    format!("'heat_source' must be finite W/m^3, found {}", num(q)),
                ))
            }
            q => q.unwrap_or(0.0),
        };
        template_temperature.push(temp);
        template_source.push(q);
    }
    let wall_temperature = walls(cx, raw, inp)?;
    let insert_temperature = raw
        .insert
        .iter()
        .enumerate()
        .map(|(i, ins)| {
            ins.temperature
                .map(|t| temperature(cx, &[K("insert"), I(i), K("temperature")], t))
                .transpose()
        })
        .collect::<R<Vec<_>>>()?;
    let model = HeatModel {
        conductance: h.conductance.unwrap_or_default(),
        materials,
        wall_temperature,
        template_temperature,
        template_source,
    };
    let (limit, limiting_template) = stability_limit(&model, inp);
    if inp.dt > limit {
        let path: &[Seg] = if inp.dt_auto {
            &[K("heat")]
        } else {
            &[K("simulation"), K("dt")]
        };
        return Err(cx
            .err(path, format!(
                "dt = {:e} s is above the thermal stability limit {limit:.3e} s of template '{limiting_template}' (m c_p over the conductance of {LIMIT_CONTACTS_PER_SPHERE} contacts a sphere at the overlap guard's {} of a radius)",
                inp.dt, inp.max_overlap_ratio
            ))
            .label("heat is explicit: dt must be at most m c_p / Σ H")
            .note(format!("help: use dt <= {limit:.3e} s, or a larger specific_heat or smaller thermal_conductivity")));
    }
    Ok(Some(HeatDef {
        model,
        insert_temperature,
        file_temperature,
        stability_limit: limit,
        limiting_template,
        // set with the [fluid] keys (`convection::fluid_heat`)
        convection: None,
    }))
}

/// The `temperature` column of each CSV body file (`None` for other
/// inserts and files without one).
fn file_temperatures(cx: &mut Cx, raw: &RawScenario) -> R<Vec<Option<Vec<f64>>>> {
    let mut out = Vec::new();
    for (i, ins) in raw.insert.iter().enumerate() {
        let csv = ins.format.unwrap_or_default() == super::bodies_file::BodyFileFormat::Csv;
        let t = match (&ins.kind, &ins.file) {
            (Some(InsertKind::File), Some(f)) if csv => {
                let path = [K("insert"), I(i), K("file")];
                let bytes = cx.read_file(&path, "body", f)?;
                super::bodies_file::temperature_column(&bytes).map_err(|(line, msg)| {
                    cx.err(&path, format!("{f}:{line}: {msg}"))
                        .label("in this file")
                })?
            }
            _ => None,
        };
        out.push(t);
    }
    Ok(out)
}

/// A temperature key: finite and above 0 K.
pub(super) fn temperature(cx: &Cx, path: &[Seg], t: f64) -> R<f64> {
    if t.is_finite() && t > 0.0 {
        Ok(t)
    } else {
        Err(cx
            .err(
                path,
                format!("temperature must be > 0 K (absolute), found {}", num(t)),
            )
            .label("must be above absolute zero"))
    }
}

/// Each material's thermal properties, checked where given.
fn thermal_materials(cx: &Cx, raw: &RawScenario) -> R<Vec<Option<ThermalMaterial>>> {
    let mut out = Vec::new();
    for (i, m) in raw.material.iter().enumerate() {
        let p = |k: &'static str| [K("material"), I(i), K(k)];
        let k = m
            .thermal_conductivity
            .map(|k| {
                cx.nonneg(
                    &p("thermal_conductivity"),
                    k,
                    "thermal_conductivity",
                    "W/(m K)",
                )
            })
            .transpose()?;
        let c = m
            .specific_heat
            .map(|c| cx.positive(&p("specific_heat"), c, "specific_heat", "J/(kg K)"))
            .transpose()?;
        out.push(match (k, c) {
            (None, None) => None,
            (k, c) => Some(ThermalMaterial {
                conductivity: k.unwrap_or(0.0),
                specific_heat: c.unwrap_or(0.0),
            }),
        });
    }
    Ok(out)
}

/// Each wall's fixed temperature; a rigid wall of a material with heat
/// keys must have one (else it would conduct to nothing).
fn walls(cx: &Cx, raw: &RawScenario, inp: &HeatInput) -> R<Vec<Option<f64>>> {
    let mut out = Vec::new();
    for (i, (w, rw)) in inp.walls.iter().zip(&raw.wall).enumerate() {
        let p = |k: &'static str| [K("wall"), I(i), K(k)];
        let m = &raw.material[w.material as usize];
        let mname = &inp.material_names[w.material as usize];
        let thermal = m.thermal_conductivity.is_some() || m.specific_heat.is_some();
        match rw.temperature {
            Some(t) => {
                let t = temperature(cx, &p("temperature"), t)?;
                if m.thermal_conductivity.is_none() {
                    return Err(cx
                        .err(&p("temperature"), format!("wall '{}' has a temperature but its material '{mname}' no thermal_conductivity", w.name))
                        .label("conducts nothing")
                        .note("help: add thermal_conductivity (W/(m K)) to the wall's [[material]]"));
                }
                out.push(Some(t));
            }
            None => {
                if thermal && inp.materials[w.material as usize].is_rigid() {
                    return Err(cx
                        .err(&p("material"), format!("the material '{mname}' of the rigid wall '{}' has heat keys, but the wall has no temperature", w.name))
                        .label("a wall without temperature is adiabatic")
                        .note("help: give the wall a fixed temperature = ... (K), or use a material without thermal_conductivity and specific_heat for an adiabatic wall"));
                }
                out.push(None);
            }
        }
    }
    Ok(out)
}

/// Without `[heat]`: the first heat key given is an error.
fn no_heat_keys(cx: &Cx, raw: &RawScenario) -> R<()> {
    let mut given: Vec<[Seg; 3]> = Vec::new();
    for (i, m) in raw.material.iter().enumerate() {
        if m.thermal_conductivity.is_some() {
            given.push([K("material"), I(i), K("thermal_conductivity")]);
        }
        if m.specific_heat.is_some() {
            given.push([K("material"), I(i), K("specific_heat")]);
        }
    }
    for (i, t) in raw.template.iter().enumerate() {
        if t.temperature.is_some() {
            given.push([K("template"), I(i), K("temperature")]);
        }
        if t.heat_source.is_some() {
            given.push([K("template"), I(i), K("heat_source")]);
        }
    }
    for (i, w) in raw.wall.iter().enumerate() {
        if w.temperature.is_some() {
            given.push([K("wall"), I(i), K("temperature")]);
        }
    }
    for (i, w) in raw.insert.iter().enumerate() {
        if w.temperature.is_some() {
            given.push([K("insert"), I(i), K("temperature")]);
        }
    }
    match given.first() {
        None => Ok(()),
        Some(p) => Err(cx
            .err(p, "a heat key without [heat]: heat transfer is off")
            .label("has no effect")
            .note("help: add a [heat] table to turn heat transfer on (docs/scenario.md), or remove the key")),
    }
}

/// The largest stable time step (s) and the template that sets it: over
/// the templates (at their smallest size in any mix), `m c_p / Σ H` with
/// [`LIMIT_CONTACTS_PER_SPHERE`] contacts a sphere, each at the overlap
/// guard's limit against the most conductive partner of at least the
/// sphere's radius (T-57).
pub fn stability_limit(model: &HeatModel, inp: &HeatInput) -> (f64, String) {
    use clump_core::heat::{harmonic_conductivity, wall_conductance};
    let k_max = model
        .materials
        .iter()
        .flatten()
        .map(|t| t.conductivity)
        .fold(0.0, f64::max);
    let mut best = (f64::INFINITY, String::new());
    for (ti, t) in inp.templates.iter().enumerate() {
        let s = super::model::template_sizes(inp.mixes, ti)
            .map(|z| z.min_scale())
            .fold(1.0, f64::min);
        let Some(tm) = model.materials[t.material as usize] else {
            continue;
        };
        let c = t.template.mass * s * s * s * tm.specific_heat;
        let k = harmonic_conductivity(tm.conductivity, k_max);
        let sum_h: f64 = t
            .template
            .spheres
            .iter()
            .map(|sp| {
                let r = sp.radius * s;
                // the wall form is the largest: a partner of infinite radius
                let h = wall_conductance(model.conductance, k, r, inp.max_overlap_ratio * r);
                LIMIT_CONTACTS_PER_SPHERE * h
            })
            .sum();
        let limit = if sum_h > 0.0 {
            c / sum_h
        } else {
            f64::INFINITY
        };
        if limit < best.0 {
            best = (limit, t.name.clone());
        }
    }
    best
}
