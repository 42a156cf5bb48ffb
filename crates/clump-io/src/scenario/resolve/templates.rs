//! `[[template]]` and `[[mix]]`: clump shapes and particle mixes.

use super::diag::Diagnostic;
use super::model::*;
use super::raw::*;
use super::source::Seg;
use super::Seg::{I, K};
use super::{dof, lookup, unique_name, Cx, MAX_ROD_SPHERES, R};
use crate::scenario::diag::num;
use clump_core::contact::Material;
use clump_core::insert::{Mix, MixEntry, SizeDistribution};
use clump_core::shape::{self, ClumpTemplate, ShapeError, Sphere};
use glam::{DMat3, DVec3};

/// Sphere radii a template may have, m: outside, the volume and inertia
/// integrals under- or overflow (`r³`, `r⁵`) and the error would not name
/// the radius.
const RADIUS_RANGE: (f64, f64) = (1e-9, 1e6);
/// Above this many spheres the mass-property integration is announced.
const SLOW_TEMPLATE_SPHERES: usize = 10_000;

/// The templates with their names, in file order.
pub(super) fn templates(
    cx: &mut Cx,
    raw: &RawScenario,
    material_names: &[String],
    materials: &[Material],
) -> R<(Vec<String>, Vec<TemplateDef>)> {
    // ---------------- templates
    let mut template_names: Vec<String> = Vec::new();
    let mut templates: Vec<TemplateDef> = Vec::new();
    for (i, t) in raw.template.iter().enumerate() {
        match build_template(cx, i, t, material_names, materials, &template_names) {
            Ok(td) => {
                template_names.push(td.name.clone());
                templates.push(td);
            }
            Err(d) => cx.errors.push(d),
        }
    }
    cx.barrier()?;
    Ok((template_names, templates))
}

/// The mixes with their names, in file order.
pub(super) fn mixes(
    cx: &mut Cx,
    raw: &RawScenario,
    template_names: &[String],
) -> R<(Vec<String>, Vec<MixDef>)> {
    // ---------------- mixes
    let mut mix_names: Vec<String> = Vec::new();
    let mut mixes: Vec<MixDef> = Vec::new();
    for (i, m) in raw.mix.iter().enumerate() {
        let t = [K("mix"), I(i)];
        let name = m
            .name
            .clone()
            .ok_or_else(|| cx.missing(&t, "[[mix]]", "name", "name = \"rocks\""))?;
        unique_name(cx, &[K("mix"), I(i), K("name")], "mix", &name, &mix_names)?;
        if m.component.is_empty() {
            return Err(cx.err(&t, format!("mix '{name}' has no [[mix.component]]")).note(
                "help: add components, e.g.\n[[mix.component]]\ntemplate = \"stone_a\"\nfraction = 0.5",
            ));
        }
        let mut entries = Vec::new();
        for (j, c) in m.component.iter().enumerate() {
            let cp = |k: &'static str| [K("mix"), I(i), K("component"), I(j), K(k)];
            let ct = [K("mix"), I(i), K("component"), I(j)];
            let tn = c.template.as_ref().ok_or_else(|| {
                cx.missing(&ct, "[[mix.component]]", "template", "template = \"name\"")
            })?;
            let ti = lookup(cx, &cp("template"), "template", tn, template_names)?;
            let fraction = c.fraction.unwrap_or(1.0);
            cx.positive(&cp("fraction"), fraction, "fraction", "")?;
            let size = match &c.size {
                None => SizeDistribution::default(),
                Some(s) => {
                    size_distribution(cx, &[K("mix"), I(i), K("component"), I(j), K("size")], s)?
                }
            };
            entries.push(MixEntry {
                template: ti as u32,
                fraction,
                size,
            });
        }
        mix_names.push(name.clone());
        mixes.push(MixDef {
            name,
            mix: Mix {
                basis: m.basis.unwrap_or_default(),
                entries,
            },
        });
    }
    Ok((mix_names, mixes))
}

fn shape_error(cx: &Cx, i: usize, e: ShapeError, inline: bool) -> Diagnostic {
    let t = [K("template"), I(i)];
    match e {
        ShapeError::NonPositiveRadius { index, radius } if inline => cx
            .err(
                &[K("template"), I(i), K("spheres"), I(index)],
                format!("sphere {index} of template has radius {radius} m; radii must be > 0"),
            )
            .label("radius must be positive"),
        ShapeError::NonFiniteSphere { index, .. } if inline => cx.err(
            &[K("template"), I(i), K("spheres"), I(index)],
            format!("sphere {index} has a non-finite centre or radius"),
        ),
        ShapeError::InvalidMass { mass } => cx.err(
            &[K("template"), I(i), K("mass")],
            format!("mass must be > 0 kg, found {}", num(mass)),
        ),
        ShapeError::InvalidInertia { reason } => cx.err(
            &[K("template"), I(i), K("inertia")],
            format!("invalid inertia tensor (kg m^2, about the centre of mass): {reason}"),
        ),
        other => cx.err(&t, format!("invalid template: {other}")),
    }
}

fn build_template(
    cx: &mut Cx,
    i: usize,
    t: &RawTemplate,
    material_names: &[String],
    materials: &[Material],
    seen: &[String],
) -> R<TemplateDef> {
    let tp = [K("template"), I(i)];
    let p = |k: &'static str| [K("template"), I(i), K(k)];
    let name = t
        .name
        .clone()
        .ok_or_else(|| cx.missing(&tp, "[[template]]", "name", "name = \"stone\""))?;
    unique_name(cx, &p("name"), "template", &name, seen)?;
    let mname = t.material.as_ref().ok_or_else(|| {
        cx.missing(
            &tp,
            "[[template]]",
            "material",
            "the name of a [[material]]",
        )
    })?;
    let mi = lookup(cx, &p("material"), "material", mname, material_names)?;
    let density = materials[mi].density;
    if !(density > 0.0 && density.is_finite()) {
        return Err(cx.err(&p("material"), format!("material '{mname}' has density {density}; a particle material needs a finite density > 0")));
    }
    let sources = [t.spheres.is_some(), t.file.is_some(), t.shape.is_some()];
    let nsrc = sources.iter().filter(|&&b| b).count();
    if nsrc != 1 {
        let d = if nsrc == 0 {
            cx.err(
                &tp,
                format!("template '{name}' needs its spheres: one of 'spheres', 'file' or 'shape'"),
            )
        } else {
            // point at the source key given last
            let k = ["spheres", "file", "shape"]
                .into_iter()
                .zip(sources)
                .filter(|(_, present)| *present)
                .map(|(k, _)| k)
                .max_by_key(|k| cx.src.key_span(&p(k)).map_or(0, |s| s.start))
                .unwrap_or("shape");
            cx.src.error_at_key(
                &p(k),
                format!("template '{name}' gives more than one of 'spheres', 'file', 'shape'"),
            )
        };
        return Err(d.note("help: spheres = [[x, y, z, r], ...] (m), file = \"stone.txt\" (LIGGGHTS x y z r), or shape = \"sphere\"|\"rod\"|\"tetrahedron\"|\"cube_octet\""));
    }
    // keys that belong to built-in shapes only
    if t.shape.is_none() {
        for (k, v) in [
            ("radius", t.radius.is_some()),
            ("n", t.n.is_some()),
            ("spacing", t.spacing.is_some()),
            ("edge", t.edge.is_some()),
        ] {
            if v {
                return Err(cx.src.error_at_key(
                    &p(k),
                    format!("'{k}' only applies to templates with a built-in 'shape'"),
                ));
            }
        }
    }
    let mut inline = false;
    let spheres: Vec<Sphere> = if let Some(sp) = &t.spheres {
        inline = true;
        if sp.is_empty() {
            return Err(cx.err(
                &p("spheres"),
                "'spheres' is empty; give at least one [x, y, z, r] (m)",
            ));
        }
        sp.iter()
            .map(|s| Sphere::new(DVec3::new(s[0], s[1], s[2]), s[3]))
            .collect()
    } else if let Some(f) = &t.file {
        let bytes = cx.read_file(&p("file"), "template", f)?;
        crate::template_file::parse_template_bytes(&bytes, std::path::Path::new(f))
            .map_err(|e| cx.err(&p("file"), format!("template file '{f}' is invalid: {e}")))?
    } else {
        let shape = t.shape.expect("one source");
        let radius = t.radius.ok_or_else(|| {
            cx.missing(
                &tp,
                "[[template]]",
                "radius",
                "sphere radius in m, e.g. radius = 0.001",
            )
        })?;
        let radius = cx.positive(&p("radius"), radius, "radius", "m")?;
        let need = |cx: &Cx, k: &'static str, v: Option<f64>, what: &str| -> R<f64> {
            let x = v.ok_or_else(|| cx.missing(&tp, "[[template]]", k, what))?;
            cx.positive(&p(k), x, k, "m")
        };
        let forbid = |cx: &Cx, k: &'static str, present: bool, s: &str| -> R<()> {
            if present {
                Err(cx
                    .src
                    .error_at_key(&p(k), format!("'{k}' does not apply to shape = \"{s}\"")))
            } else {
                Ok(())
            }
        };
        match shape {
            ShapeName::Sphere => {
                forbid(cx, "n", t.n.is_some(), "sphere")?;
                forbid(cx, "spacing", t.spacing.is_some(), "sphere")?;
                forbid(cx, "edge", t.edge.is_some(), "sphere")?;
                shape::single_sphere(radius)
            }
            ShapeName::Rod => {
                forbid(cx, "edge", t.edge.is_some(), "rod")?;
                let n = t.n.ok_or_else(|| {
                    cx.missing(&tp, "[[template]]", "n", "number of spheres, e.g. n = 4")
                })?;
                if n == 0 {
                    return Err(cx.err(&p("n"), "a rod needs n >= 1 spheres"));
                }
                if u64::from(n) > MAX_ROD_SPHERES {
                    return Err(cx
                        .err(&p("n"), format!("a rod may have at most {MAX_ROD_SPHERES} spheres, found {n}"))
                        .note("note: a clump's mass properties are computed over the union of its spheres; use a template file for unusual shapes"));
                }
                let spacing = need(
                    cx,
                    "spacing",
                    t.spacing,
                    "centre spacing in m, e.g. spacing = 0.001",
                )?;
                shape::rod(n as usize, radius, spacing)
            }
            ShapeName::Tetrahedron | ShapeName::CubeOctet => {
                let s = if shape == ShapeName::Tetrahedron {
                    "tetrahedron"
                } else {
                    "cube_octet"
                };
                forbid(cx, "n", t.n.is_some(), s)?;
                forbid(cx, "spacing", t.spacing.is_some(), s)?;
                let edge = need(cx, "edge", t.edge, "edge length in m, e.g. edge = 0.0012")?;
                if shape == ShapeName::Tetrahedron {
                    shape::tetrahedron(radius, edge)
                } else {
                    shape::cube_octet(radius, edge)
                }
            }
        }
    };
    let scale = t.scale.unwrap_or(1.0);
    let scale = cx.positive(&p("scale"), scale, "scale", "")?;
    let spheres: Vec<Sphere> = spheres
        .iter()
        .map(|s| Sphere::new(s.center * scale, s.radius * scale))
        .collect();
    if let Some((k, s)) = spheres
        .iter()
        .enumerate()
        // non-positive and non-finite radii are reported below, at their row
        .find(|(_, s)| {
            s.radius > 0.0
                && s.radius.is_finite()
                && !(RADIUS_RANGE.0..=RADIUS_RANGE.1).contains(&s.radius)
        })
    {
        return Err(cx
            .err(&p(if t.spheres.is_some() { "spheres" } else { "scale" }), format!(
                "template '{name}': sphere {k} has radius {} m (after scale), outside the range [{:e}, {:e}] m the mass properties can be computed in",
                num(s.radius),
                RADIUS_RANGE.0,
                RADIUS_RANGE.1
            ))
            .note("help: give radii in metres (a file in mm needs scale = 0.001)"));
    }
    if spheres.len() > SLOW_TEMPLATE_SPHERES && t.mass.is_none() {
        tracing::warn!(
            "template '{name}' has {} spheres: its exact mass properties can take minutes when the spheres overlap densely (progress with the time left follows). To skip the integration give mass, inertia (and center_of_mass) in its [[template]]",
            spheres.len()
        );
    }
    let template = match (t.mass, t.inertia) {
        (None, None) => {
            dof::template_center_of_mass(cx, i, t, scale)?;
            ClumpTemplate::from_spheres(&name, &spheres, density)
        }
        (Some(m), Some(inertia)) => {
            cx.positive(&p("mass"), m, "mass", "kg")?;
            let mat = DMat3::from_cols_array_2d(&inertia).transpose();
            match dof::template_center_of_mass(cx, i, t, scale)? {
                Some(c) => ClumpTemplate::with_override_about(&name, &spheres, density, m, mat, c),
                None => ClumpTemplate::with_override(&name, &spheres, density, m, mat),
            }
        }
        (Some(_), None) => {
            return Err(cx
                .src
                .error_at_key(
                    &p("mass"),
                    "'mass' needs 'inertia' too (3×3 tensor in kg m^2 about the centre of mass)",
                )
                .note("help: inertia = [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]]"))
        }
        (None, Some(_)) => {
            return Err(cx
                .src
                .error_at_key(&p("inertia"), "'inertia' needs 'mass' too (kg)"))
        }
    }
    .map_err(|e| {
        let mut d = shape_error(cx, i, e, inline);
        d.message = format!("template '{name}': {}", d.message);
        d
    })?;
    Ok(TemplateDef {
        name,
        material: mi as u16,
        template,
        dof: dof::template_dof(t),
        given_mass_properties: t.mass.is_some(),
    })
}

fn size_distribution(cx: &Cx, base: &[Seg], s: &RawSize) -> R<SizeDistribution> {
    let p = |k: &'static str| {
        let mut v = base.to_vec();
        v.push(K(k));
        v
    };
    let kind = s.distribution.ok_or_else(|| {
        cx.missing(
            base,
            "size",
            "distribution",
            "distribution = \"uniform\" (or \"normal\", \"fixed\")",
        )
    })?;
    let req = |k: &'static str, v: Option<f64>| -> R<f64> {
        let x = v.ok_or_else(|| {
            cx.missing(
                base,
                "size",
                k,
                &format!("the {k} scale factor (dimensionless)"),
            )
        })?;
        cx.positive(&p(k), x, k, "")
    };
    let forbid = |k: &'static str, present: bool, d: &str| -> R<()> {
        if present {
            Err(cx.src.error_at_key(
                &p(k),
                format!("'{k}' does not apply to distribution = \"{d}\""),
            ))
        } else {
            Ok(())
        }
    };
    let d = match kind {
        SizeKind::Fixed => {
            forbid("min", s.min.is_some(), "fixed")?;
            forbid("max", s.max.is_some(), "fixed")?;
            forbid("mean", s.mean.is_some(), "fixed")?;
            forbid("std", s.std.is_some(), "fixed")?;
            SizeDistribution::Fixed {
                scale: req("scale", s.scale)?,
            }
        }
        SizeKind::Uniform => {
            forbid("scale", s.scale.is_some(), "uniform")?;
            forbid("mean", s.mean.is_some(), "uniform")?;
            forbid("std", s.std.is_some(), "uniform")?;
            SizeDistribution::Uniform {
                min: req("min", s.min)?,
                max: req("max", s.max)?,
            }
        }
        SizeKind::Normal => {
            forbid("scale", s.scale.is_some(), "normal")?;
            let mean = req("mean", s.mean)?;
            let std = s.std.ok_or_else(|| {
                cx.missing(
                    base,
                    "size",
                    "std",
                    "standard deviation of the scale factor",
                )
            })?;
            let std = cx.nonneg(&p("std"), std, "std", "")?;
            let min = s
                .min
                .map(|m| cx.positive(&p("min"), m, "min", ""))
                .transpose()?
                .unwrap_or((mean - 3.0 * std).max(0.1 * mean));
            let max = s
                .max
                .map(|m| cx.positive(&p("max"), m, "max", ""))
                .transpose()?
                .unwrap_or(mean + 3.0 * std);
            SizeDistribution::Normal {
                mean,
                std,
                min,
                max,
            }
        }
    };
    match d {
        SizeDistribution::Uniform { min, max } | SizeDistribution::Normal { min, max, .. }
            if max < min =>
        {
            Err(cx.err(
                &p("max"),
                format!("size 'max' ({max}) is below 'min' ({min})"),
            ))
        }
        _ => Ok(d),
    }
}
