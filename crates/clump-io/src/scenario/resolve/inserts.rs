//! `[[insert]]`: bodies from a file, packed regions and streams.

use super::keys::{kind_keys, kind_specific, INSERT_KIND_KEYS, REGION_TYPE_KEYS};
use super::model::*;
use super::raw::*;
use super::source::Seg;
use super::Seg::{I, K};
use super::{dof, lookup, Cx, PACK_ERROR_FRACTION, R};
use crate::scenario::placement;
use clump_core::insert::{
    Mix, Orientation, PackSpec, PackTarget, Region, StreamRate, StreamSpec, RSA_LIMIT,
};
use glam::{DQuat, DVec3};

/// Most bodies one stream may insert (a larger number is a unit mistake;
/// memory runs out long before).
const MAX_STREAM_BODIES: f64 = 1e9;

/// The insertions, in file order.
#[allow(clippy::too_many_arguments)]
pub(super) fn inserts(
    cx: &mut Cx,
    raw: &RawScenario,
    stages: &[StageDef],
    templates: &[TemplateDef],
    template_names: &[String],
    mixes: &[MixDef],
    mix_names: &[String],
    dt: f64,
    domain: &clump_core::boundary::Domain,
) -> R<Vec<InsertDef>> {
    let stage_names: Vec<String> = stages.iter().map(|s| s.name.clone()).collect();

    // ---------------- inserts
    let mut inserts = Vec::new();
    for (i, ins) in raw.insert.iter().enumerate() {
        let def = build_insert(
            cx,
            i,
            ins,
            stages,
            &stage_names,
            templates,
            template_names,
            mixes,
            mix_names,
            dt,
        )
        .and_then(|def| {
            placement::check_insert(cx.src, i, &def, domain, &mut cx.warnings).map(|()| def)
        });
        match def {
            Ok(def) => inserts.push(def),
            Err(d) => cx.errors.push(d),
        }
    }
    cx.barrier()?;
    Ok(inserts)
}

fn build_region(cx: &Cx, base: &[Seg], r: &RawRegion) -> R<Region> {
    let p = |k: &'static str| {
        let mut v = base.to_vec();
        v.push(K(k));
        v
    };
    let kind = r.kind.ok_or_else(|| {
        cx.missing(
            base,
            "region",
            "type",
            "type = \"box\" (lo, hi) or \"cylinder\" (base, axis, radius, height)",
        )
    })?;
    let kname = match kind {
        RegionKind::Box => "box",
        RegionKind::Cylinder => "cylinder",
    };
    let allowed = kind_keys(REGION_TYPE_KEYS, kname);
    for k in kind_specific(REGION_TYPE_KEYS) {
        if cx.src.has(&p(k)) && !allowed.contains(&k) {
            return Err(cx.src.error_at_key(
                &p(k),
                format!(
                    "'{k}' does not apply to a region of type \"{kname}\" (it uses {})",
                    allowed.join(", ")
                ),
            ));
        }
    }
    match kind {
        RegionKind::Box => {
            let lo =
                r.lo.ok_or_else(|| cx.missing(base, "region", "lo", "lower corner in m"))?;
            let hi =
                r.hi.ok_or_else(|| cx.missing(base, "region", "hi", "upper corner in m"))?;
            let (lo, hi) = (cx.vec3(&p("lo"), lo, "lo")?, cx.vec3(&p("hi"), hi, "hi")?);
            if hi.cmple(lo).any() {
                return Err(cx.err(
                    &p("hi"),
                    format!("region 'hi' {hi} must be above 'lo' {lo} on every axis"),
                ));
            }
            Ok(Region::Box { lo, hi })
        }
        RegionKind::Cylinder => {
            let b = r.base.ok_or_else(|| {
                cx.missing(base, "region", "base", "centre of the bottom disc in m")
            })?;
            let b = cx.vec3(&p("base"), b, "base")?;
            let axis = cx.unit(&p("axis"), r.axis.unwrap_or([0.0, 0.0, 1.0]), "axis")?;
            let radius = r
                .radius
                .ok_or_else(|| cx.missing(base, "region", "radius", "radius in m"))?;
            let height = r
                .height
                .ok_or_else(|| cx.missing(base, "region", "height", "height in m"))?;
            let radius = cx.positive(&p("radius"), radius, "radius", "m")?;
            let height = cx.positive(&p("height"), height, "height", "m")?;
            Ok(Region::Cylinder {
                base: b,
                axis,
                radius,
                height,
            })
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn build_insert(
    cx: &mut Cx,
    i: usize,
    ins: &RawInsert,
    stages: &[StageDef],
    stage_names: &[String],
    templates: &[TemplateDef],
    template_names: &[String],
    mixes: &[MixDef],
    mix_names: &[String],
    dt: f64,
) -> R<InsertDef> {
    let tp = [K("insert"), I(i)];
    let p = |k: &'static str| [K("insert"), I(i), K(k)];
    let kind = ins.kind.ok_or_else(|| {
        cx.missing(
            &tp,
            "[[insert]]",
            "kind",
            "kind = \"pack\" (or \"stream\", \"file\")",
        )
    })?;
    let kname = match kind {
        InsertKind::File => "file",
        InsertKind::Pack => "pack",
        InsertKind::Stream => "stream",
    };
    let stage = match &ins.stage {
        Some(s) => lookup(cx, &p("stage"), "stage", s, stage_names)?,
        None => 0,
    };
    let allowed = kind_keys(INSERT_KIND_KEYS, kname);
    for k in kind_specific(INSERT_KIND_KEYS) {
        if cx.src.has(&p(k)) && !allowed.contains(&k) {
            return Err(cx
                .src
                .error_at_key(&p(k), format!("'{k}' does not apply to kind = \"{kname}\""))
                .note(format!(
                    "note: kind = \"{kname}\" uses: stage, {}",
                    allowed.join(", ")
                )));
        }
    }
    let dynamics = dof::insert_dynamics(cx, i, ins, kind, templates)?;
    if kind == InsertKind::File {
        let f = ins.file.as_ref().ok_or_else(|| {
            cx.missing(
                &tp,
                "[[insert]] of kind \"file\"",
                "file",
                "a CSV file of bodies, relative to the scenario",
            )
        })?;
        let bytes = cx.read_file(&p("file"), "body", f)?;
        let default_template = match &ins.template {
            Some(t) => Some(lookup(cx, &p("template"), "template", t, template_names)? as u32),
            None => None,
        };
        let format = ins.format.unwrap_or_default();
        let mut bodies = super::bodies_file::parse(
            &bytes,
            format,
            template_names,
            default_template,
            &super::bodies_file::RowDefaults {
                dof: dynamics.by_template.clone(),
                dt,
            },
        )
        .map_err(|(line, msg)| {
            cx.err(&p("file"), format!("{f}:{line}: {msg}"))
                .label("in this file")
        })?;
        if let (true, Some((k, what))) = (dynamics.fixed, dof::moving_body(&bodies)) {
            return Err(cx.err(
                &p("fixed"),
                format!("fixed bodies are at rest, but body {k} of '{f}' has a {what}"),
            ));
        }
        if ins.orientation_frame == Some(super::raw::OrientationFrame::Input) {
            // q_input maps (x_input − com) to world; x_input − com =
            // input_to_body⁻¹ x_body, so body → world is q_input · input_to_body⁻¹.
            for b in &mut bodies {
                let t = &templates[b.template as usize].template;
                b.orientation = (b.orientation * t.input_to_body.conjugate()).normalize();
            }
        }
        return Ok(InsertDef {
            stage,
            kind: InsertSpec::File { bodies },
        });
    }
    // mix or template
    let mix = match (&ins.mix, &ins.template) {
        (Some(_), Some(_)) => {
            return Err(cx
                .src
                .error_at_key(&p("template"), "give either 'mix' or 'template', not both"))
        }
        (Some(m), None) => mixes[lookup(cx, &p("mix"), "mix", m, mix_names)?]
            .mix
            .clone(),
        (None, Some(t)) => {
            Mix::single(lookup(cx, &p("template"), "template", t, template_names)? as u32)
        }
        (None, None) => {
            return Err(cx.missing(
                &tp,
                &format!("[[insert]] of kind \"{kname}\""),
                "mix",
                "mix = \"name\" or template = \"name\"",
            ))
        }
    };
    let region_raw = ins.region.as_ref().ok_or_else(|| {
        cx.missing(
            &tp,
            &format!("[[insert]] of kind \"{kname}\""),
            "region",
            "region = { type = \"box\", lo = [..], hi = [..] }",
        )
    })?;
    let region = build_region(cx, &p("region"), region_raw)?;
    let velocity = match ins.velocity {
        Some(v) => cx.vec3(&p("velocity"), v, "velocity")?,
        None => DVec3::ZERO,
    };
    let orientation = match ins.orientation {
        None if dynamics.euler.is_some() => Orientation::Fixed {
            quaternion: dynamics.euler.unwrap_or_default(),
        },
        None => Orientation::Random,
        Some(q) => {
            let q = DQuat::from_xyzw(q[1], q[2], q[3], q[0]);
            if !q.is_finite() || q.length() < 1e-12 {
                return Err(cx.err(
                    &p("orientation"),
                    "orientation must be a non-zero quaternion [w, x, y, z]",
                ));
            }
            Orientation::Fixed {
                quaternion: q.normalize(),
            }
        }
    };
    let seed = ins.seed.unwrap_or(1 + i as u64);
    // expected body volume
    let (mean_volume, mean_mass) = {
        let mut wsum = 0.0;
        let mut v = 0.0;
        let mut m = 0.0;
        for e in &mix.entries {
            let t = &templates[e.template as usize].template;
            let c = e.size.mean_cube();
            let w = match mix.basis {
                clump_core::insert::FractionBasis::Number => e.fraction,
                clump_core::insert::FractionBasis::Mass => e.fraction / (t.mass * c),
            };
            wsum += w;
            v += w * t.volume * c;
            m += w * t.mass * c;
        }
        (v / wsum, m / wsum)
    };
    let region_volume = region.volume();
    match kind {
        InsertKind::Pack => {
            let target = match (ins.count, ins.volume_fraction) {
                (Some(_), Some(_)) => {
                    return Err(cx.src.error_at_key(
                        &p("volume_fraction"),
                        "give either 'count' or 'volume_fraction', not both",
                    ))
                }
                (Some(n), None) => {
                    let phi = n as f64 * mean_volume / region_volume;
                    if phi > PACK_ERROR_FRACTION {
                        let cap = (RSA_LIMIT * region_volume / mean_volume).floor();
                        return Err(cx
                            .err(&p("count"), format!(
                                "the region cannot hold {n} bodies: they need a solid volume fraction of {phi:.2} of the region ({region_volume:.3e} m^3), but random packing reaches about {RSA_LIMIT}"
                            ))
                            .label(format!("at most about {cap} bodies fit"))
                            .note("help: enlarge the region, lower the count, or insert in several stages or with a stream"));
                    }
                    if phi > 0.3 {
                        let w = cx.src.warning_at(&p("count"), format!("packing {n} bodies fills {phi:.2} of the region; random packing may fail above about {RSA_LIMIT}"));
                        cx.warnings.push(w);
                    }
                    PackTarget::Count(n as usize)
                }
                (None, Some(f)) => {
                    let f = cx.positive(&p("volume_fraction"), f, "volume_fraction", "")?;
                    if f > PACK_ERROR_FRACTION {
                        return Err(cx
                            .err(&p("volume_fraction"), format!("volume_fraction {f} cannot be reached by random packing (about {RSA_LIMIT} at most)"))
                            .label("too dense"));
                    }
                    PackTarget::VolumeFraction(f)
                }
                (None, None) => {
                    return Err(cx.missing(
                        &tp,
                        "[[insert]] of kind \"pack\"",
                        "count",
                        "count = 500 (or volume_fraction = 0.3)",
                    ))
                }
            };
            let expected = match target {
                PackTarget::Count(n) => n as f64,
                PackTarget::VolumeFraction(f) => f * region_volume / mean_volume,
            };
            let spec = PackSpec {
                region,
                target,
                mix,
                velocity,
                orientation,
                max_attempts_per_body: ins.max_attempts.unwrap_or(1000),
                angular_velocity: dynamics.angular_velocity,
                dof: dynamics.by_template.clone(),
                plane: None,
            };
            Ok(InsertDef {
                stage,
                kind: InsertSpec::Pack {
                    spec,
                    seed,
                    expected_bodies: expected,
                },
            })
        }
        InsertKind::Stream => {
            let rate = match (ins.bodies_per_second, ins.kg_per_second) {
                (Some(_), Some(_)) => {
                    return Err(cx.src.error_at_key(
                        &p("kg_per_second"),
                        "give either 'bodies_per_second' or 'kg_per_second', not both",
                    ))
                }
                (Some(r), None) => StreamRate::BodiesPerSecond(cx.positive(
                    &p("bodies_per_second"),
                    r,
                    "bodies_per_second",
                    "1/s",
                )?),
                (None, Some(r)) => StreamRate::MassPerSecond(cx.positive(
                    &p("kg_per_second"),
                    r,
                    "kg_per_second",
                    "kg/s",
                )?),
                (None, None) => {
                    return Err(cx.missing(
                        &tp,
                        "[[insert]] of kind \"stream\"",
                        "bodies_per_second",
                        "bodies_per_second = 1000 (or kg_per_second = 0.5)",
                    ))
                }
            };
            let body_rate = match rate {
                StreamRate::BodiesPerSecond(r) => r,
                StreamRate::MassPerSecond(m) => m / mean_mass,
            };
            let st = &stages[stage];
            let t0 = st.first_step as f64 * dt;
            let t_stage_end = (st.first_step + st.steps) as f64 * dt;
            let start = cx.nonneg(&p("start"), ins.start.unwrap_or(0.0), "start", "s")?;
            let mut end = match ins.end {
                Some(e) => {
                    let e = cx.nonneg(&p("end"), e, "end", "s")?;
                    if e < start {
                        return Err(cx.err(
                            &p("end"),
                            format!("stream 'end' ({e} s) is before its 'start' ({start} s)"),
                        ));
                    }
                    t0 + e
                }
                None => t_stage_end,
            };
            if t0 + start >= t_stage_end {
                return Err(cx
                    .err(&p("start"), format!(
                        "the stream starts {start} s into stage '{}', which lasts {:.6e} s: it would insert nothing",
                        st.name,
                        t_stage_end - t0
                    ))
                    .note("help: 'start' and 'end' count from the start of the insert's stage; give a start inside it, or move the insert to a later stage with stage = \"NAME\""));
            }
            if let Some(n) = ins.count {
                end = end.min(t0 + start + n as f64 / body_rate);
            }
            let expected = body_rate * (end - t0 - start);
            if !(expected <= MAX_STREAM_BODIES) {
                let key = if ins.bodies_per_second.is_some() {
                    "bodies_per_second"
                } else {
                    "kg_per_second"
                };
                return Err(cx
                    .err(&p(key), format!(
                        "the stream would insert {expected:.3e} bodies ({body_rate:.3e} per second for {:.3e} s), above the limit of {MAX_STREAM_BODIES:.0e}",
                        end - t0 - start
                    ))
                    .note("help: check the rate's unit (bodies per second), or set count = N"));
            }
            let vol_rate = body_rate * mean_volume;
            // the region must be able to take the stream: bodies leave at |v|
            let exit_normal = if velocity.length() > 0.0 {
                Some(velocity.normalize())
            } else {
                None
            };
            let flux_cap = match (exit_normal, region) {
                (Some(n), Region::Box { lo, hi }) => {
                    let d = hi - lo;
                    let area =
                        (d.y * d.z * n.x.abs() + d.x * d.z * n.y.abs() + d.x * d.y * n.z.abs())
                            .max(1e-300);
                    Some(RSA_LIMIT * area * velocity.length())
                }
                (
                    Some(n),
                    Region::Cylinder {
                        axis,
                        radius,
                        height,
                        ..
                    },
                ) => {
                    let c = n.dot(axis).abs();
                    let area = std::f64::consts::PI * radius * radius * c
                        + 2.0 * radius * height * (1.0 - c * c).sqrt();
                    Some(RSA_LIMIT * area * velocity.length())
                }
                (None, _) => None,
            };
            if let Some(cap) = flux_cap {
                if vol_rate > cap {
                    return Err(cx
                        .err(&p(if ins.bodies_per_second.is_some() { "bodies_per_second" } else { "kg_per_second" }), format!(
                            "the stream region cannot pass this rate: {vol_rate:.3e} m^3/s of solid through a region that lets through at most about {cap:.3e} m^3/s at {:.3} m/s",
                            velocity.length()
                        ))
                        .note("help: enlarge the region across the flow, raise the velocity, or lower the rate"));
                }
            }
            let spec = StreamSpec {
                region,
                mix,
                rate,
                velocity,
                start: t0 + start,
                end: Some(end),
                exit_normal,
                orientation,
                max_attempts_per_body: ins.max_attempts.unwrap_or(20),
                angular_velocity: dynamics.angular_velocity,
                dof: dynamics.by_template.clone(),
                start_after: ins.start_after,
                plane: None,
            };
            let expected = (body_rate * (end - t0 - start)).max(0.0).floor();
            Ok(InsertDef {
                stage,
                kind: InsertSpec::Stream {
                    spec,
                    seed,
                    expected_bodies: expected,
                },
            })
        }
        InsertKind::File => unreachable!(),
    }
}
