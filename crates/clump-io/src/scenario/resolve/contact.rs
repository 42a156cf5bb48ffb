//! `[contact]` and `[[pair]]`: contact laws and their coefficients.

use super::raw::*;
use super::source::Seg;
use super::Seg::{I, K};
use super::{lookup, Cx, R};
use crate::scenario::diag::num;
use clump_core::contact::{
    CohesionLaw, NormalLaw, PairProperties, RollingLaw, TangentialLaw, TwistingLaw,
};
use std::collections::HashMap;

/// The contact properties of every pair of materials, row-major
/// (`nmat × nmat`): `[contact]`, overridden by `[[pair]]` entries.
pub(super) fn pair_table(
    cx: &mut Cx,
    raw: &RawScenario,
    material_names: &[String],
    nmat: usize,
) -> R<Vec<PairProperties>> {
    // ---------------- contact properties
    let default_props = contact_props(
        cx,
        &[K("contact")],
        "[contact]",
        &raw.contact,
        &PairProperties::default(),
    )?;
    let mut pair_table = vec![default_props; nmat * nmat];
    let mut pair_set: HashMap<(usize, usize), usize> = HashMap::new();
    for (i, pr) in raw.pair.iter().enumerate() {
        let t = [K("pair"), I(i)];
        let mp = [K("pair"), I(i), K("materials")];
        let ms = pr
            .materials
            .as_ref()
            .ok_or_else(|| cx.missing(&t, "[[pair]]", "materials", "materials = [\"a\", \"b\"]"))?;
        if ms.len() != 2 {
            return Err(cx.err(
                &mp,
                format!(
                    "'materials' must name exactly 2 materials, found {}",
                    ms.len()
                ),
            ));
        }
        let a = lookup(
            cx,
            &[K("pair"), I(i), K("materials"), I(0)],
            "material",
            &ms[0],
            material_names,
        )?;
        let b = lookup(
            cx,
            &[K("pair"), I(i), K("materials"), I(1)],
            "material",
            &ms[1],
            material_names,
        )?;
        let key = (a.min(b), a.max(b));
        if let Some(prev) = pair_set.insert(key, i) {
            return Err(cx
                .err(&mp, format!("pair {} – {} is defined twice", ms[0], ms[1]))
                .note(format!(
                    "note: first defined in [[pair]] number {}",
                    prev + 1
                )));
        }
        let props = contact_props(cx, &t, "[[pair]]", &pr.law(), &default_props)?;
        pair_table[a * nmat + b] = props;
        pair_table[b * nmat + a] = props;
    }
    Ok(pair_table)
}

fn contact_props(
    cx: &mut Cx,
    base: &[Seg],
    what: &str,
    f: &RawContact,
    dflt: &PairProperties,
) -> R<PairProperties> {
    let p = |k: &'static str| {
        let mut v = base.to_vec();
        v.push(K(k));
        v
    };
    let mut out = *dflt;
    if let Some(e) = f.restitution {
        if !(0.0..=1.0).contains(&e) {
            return Err(cx
                .err(
                    &p("restitution"),
                    format!("restitution must lie in [0, 1], found {}", num(e)),
                )
                .label("outside [0, 1]")
                .note("note: e = 1 is perfectly elastic, e = 0 perfectly plastic"));
        }
        out.restitution = e;
    }
    if let Some(mu) = f.friction {
        out.friction = cx.nonneg(&p("friction"), mu, "friction", "")?;
    }
    if let Some(mu) = f.rolling_friction {
        out.rolling_friction = cx.nonneg(&p("rolling_friction"), mu, "rolling_friction", "")?;
    }
    if let Some(d) = f.damping {
        out.damping = d;
    }
    if let Some(r) = f.rolling {
        out.rolling = r;
    }
    if let Some(t) = f.tensile {
        out.tensile = t;
    }
    if let Some(t) = f.tangential {
        out.tangential = t;
    }
    out.cohesion = cohesion(cx, base, what, f, dflt.cohesion)?;
    if let Some(t) = f.twisting {
        out.twisting = t;
    }
    let law = f.law.unwrap_or(match dflt.normal {
        NormalLaw::Hertz => LawName::Hertz,
        NormalLaw::Linear { .. } => LawName::Linear,
    });
    match law {
        LawName::Hertz => {
            for (k, v) in [("kn", f.kn), ("kt", f.kt)] {
                if v.is_some() {
                    return Err(cx
                        .src
                        .error_at_key(&p(k), format!("'{k}' is only used with law = \"linear\" (this {what} uses the Hertz law)"))
                        .note("help: add law = \"linear\", or remove the stiffness (Hertz stiffness follows from the materials)"));
                }
            }
            out.normal = NormalLaw::Hertz;
        }
        LawName::Linear => {
            let (dkn, dkt) = match dflt.normal {
                NormalLaw::Linear { kn, kt } => (Some(kn), Some(kt)),
                NormalLaw::Hertz => (None, None),
            };
            let kn = f.kn.or(dkn).ok_or_else(|| {
                cx.missing(
                    base,
                    what,
                    "kn",
                    "law = \"linear\" needs the normal stiffness in N/m, e.g. kn = 1e5",
                )
            })?;
            let kn = cx.positive(&p("kn"), kn, "kn", "N/m")?;
            let kt = match f.kt {
                Some(kt) => cx.nonneg(&p("kt"), kt, "kt", "N/m")?,
                None => dkt.filter(|_| f.kn.is_none()).unwrap_or(2.0 / 7.0 * kn),
            };
            out.normal = NormalLaw::Linear { kn, kt };
        }
    }
    if matches!(out.cohesion, CohesionLaw::Jkr { .. }) && out.normal != NormalLaw::Hertz {
        let key = if f.cohesion.is_some() {
            "cohesion"
        } else {
            "law"
        };
        return Err(cx
            .src
            .error_at_key(&p(key), format!("cohesion = \"jkr\" needs the Hertz normal law (this {what} uses law = \"linear\")"))
            .note("help: remove law = \"linear\" (JKR's force follows from the materials and the work of adhesion), or use cohesion = \"sjkr\""));
    }
    // the micro-slip models need the Hertz law; Thornton–Yin's
    // (contact::micro_slip) also keeps its turning points in the rolling
    // and twisting history slots, the exact one (contact::mdr) its profile
    // beside the histories
    let slip_law = match out.tangential {
        TangentialLaw::MindlinDeresiewicz => Some("mindlin_deresiewicz"),
        TangentialLaw::Mdr => Some("mdr"),
        _ => None,
    };
    if let Some(law) = slip_law {
        let ty = out.tangential == TangentialLaw::MindlinDeresiewicz;
        let clash = [
            (
                "law",
                out.normal != NormalLaw::Hertz,
                "law = \"linear\"",
                "it needs the Hertz contact radius",
            ),
            (
                "cohesion",
                out.cohesion != CohesionLaw::None,
                "cohesion",
                if ty {
                    "its normal force is Hertz's"
                } else {
                    "its slip limit follows Hertz's pressure"
                },
            ),
            (
                "rolling",
                ty && out.rolling == RollingLaw::Epsd,
                "rolling = \"epsd\"",
                "it stores its turning points in the rolling spring's history slot",
            ),
            (
                "twisting",
                ty && out.twisting != TwistingLaw::None,
                "twisting resistance",
                "it stores its turning points in the twisting spring's history slot",
            ),
        ];
        if let Some(&(other, _, name, why)) = clash.iter().find(|c| c.1) {
            let key = if f.tangential.is_some() {
                "tangential"
            } else {
                other
            };
            return Err(cx
                .src
                .error_at_key(&p(key), format!("tangential = \"{law}\" cannot be combined with {name} (this {what}): {why}"))
                .note(format!("help: remove '{other}', or use tangential = \"clump\" or \"liggghts\"")));
        }
    }
    if out.rolling != RollingLaw::None && out.rolling_friction == 0.0 && f.rolling.is_some() {
        let w = cx.src.warning_at(
            &p("rolling"),
            format!(
                "rolling = {:?} with rolling_friction = 0 has no effect",
                out.rolling
            )
            .to_lowercase(),
        );
        cx.warnings.push(w);
    }
    if out.rolling == RollingLaw::None && out.rolling_friction > 0.0 && f.rolling_friction.is_some()
    {
        let w = cx
            .src
            .warning_at(
                &p("rolling_friction"),
                format!(
                    "rolling_friction = {} has no effect without a rolling model",
                    out.rolling_friction
                ),
            )
            .label("ignored")
            .note("help: add rolling = \"epsd\" (or \"cdt\") to resist rolling");
        cx.warnings.push(w);
    }
    Ok(out)
}

/// The cohesion model of a `[contact]` or `[[pair]]` table from `cohesion`
/// and its parameter (`cohesion_energy_density` for SJKR, `surface_energy`
/// for JKR); keys left out keep `dflt` (the `[contact]` model for a pair).
fn cohesion(
    cx: &mut Cx,
    base: &[Seg],
    what: &str,
    f: &RawContact,
    dflt: CohesionLaw,
) -> R<CohesionLaw> {
    let p = |k: &'static str| {
        let mut v = base.to_vec();
        v.push(K(k));
        v
    };
    let name = f.cohesion.unwrap_or(match dflt {
        CohesionLaw::None => CohesionName::None,
        CohesionLaw::Sjkr { .. } => CohesionName::Sjkr,
        CohesionLaw::Jkr { .. } => CohesionName::Jkr,
    });
    let (dk, dg) = match dflt {
        CohesionLaw::Sjkr { energy_density } => (Some(energy_density), None),
        CohesionLaw::Jkr { surface_energy } => (None, Some(surface_energy)),
        CohesionLaw::None => (None, None),
    };
    // a parameter of another model is an error, not silently ignored
    let stray = |k: &'static str, model: &str| {
        cx.src
            .error_at_key(&p(k), format!("'{k}' is only used with cohesion = \"{model}\" (this {what} has cohesion = \"{}\")", format!("{name:?}").to_lowercase()))
            .note(format!("help: add cohesion = \"{model}\", or remove '{k}'"))
    };
    if f.cohesion_energy_density.is_some() && name != CohesionName::Sjkr {
        return Err(stray("cohesion_energy_density", "sjkr"));
    }
    if f.surface_energy.is_some() && name != CohesionName::Jkr {
        return Err(stray("surface_energy", "jkr"));
    }
    Ok(match name {
        CohesionName::None => CohesionLaw::None,
        CohesionName::Sjkr => {
            let k = f.cohesion_energy_density.or(dk).ok_or_else(|| {
                cx.missing(
                    base,
                    what,
                    "cohesion_energy_density",
                    "cohesion = \"sjkr\" needs the cohesion energy density in J/m^3 (LIGGGHTS' cohesionEnergyDensity), e.g. cohesion_energy_density = 3e5",
                )
            })?;
            let k = cx.nonneg(
                &p("cohesion_energy_density"),
                k,
                "cohesion_energy_density",
                "J/m^3",
            )?;
            CohesionLaw::Sjkr { energy_density: k }
        }
        CohesionName::Jkr => {
            let g = f.surface_energy.or(dg).ok_or_else(|| {
                cx.missing(
                    base,
                    what,
                    "surface_energy",
                    "cohesion = \"jkr\" needs the work of adhesion in J/m^2, e.g. surface_energy = 0.05",
                )
            })?;
            let g = cx.nonneg(&p("surface_energy"), g, "surface_energy", "J/m^2")?;
            CohesionLaw::Jkr { surface_energy: g }
        }
    })
}
