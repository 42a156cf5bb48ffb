//! The dynamics keys of templates and inserts: force and torque flags
//! (`force_flags`, `torque_flags`), fixed and driven bodies, a given centre
//! of mass, the initial angular velocity, Euler-angle orientations and the
//! stream's `start_after`.

use super::Seg::{I, K};
use super::{Cx, InsertKind, RawInsert, RawTemplate, TemplateDef, R};
use clump_core::dof::Dof;
use glam::{DQuat, DVec3};

/// The flags a template gives its bodies (free where not given).
pub(super) fn template_dof(t: &RawTemplate) -> Dof {
    let d = Dof::default();
    Dof {
        force_flag: t.force_flags.unwrap_or(d.force_flag),
        torque_flag: t.torque_flags.unwrap_or(d.torque_flag),
        driven: false,
    }
}

/// The template's `center_of_mass` (input frame, times `scale`), which
/// needs `mass` and `inertia`.
pub(super) fn template_center_of_mass(
    cx: &Cx,
    i: usize,
    t: &RawTemplate,
    scale: f64,
) -> R<Option<DVec3>> {
    let Some(c) = t.center_of_mass else {
        return Ok(None);
    };
    let path = [K("template"), I(i), K("center_of_mass")];
    if t.mass.is_none() || t.inertia.is_none() {
        return Err(cx
            .src
            .error_at_key(
                &path,
                "'center_of_mass' needs 'mass' and 'inertia' too (the inertia is taken about it)",
            )
            .note("help: mass = 0.01, inertia = [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]] (kg m^2 about the given centre)"));
    }
    Ok(Some(cx.vec3(&path, c, "center_of_mass")? * scale))
}

/// What an insert's dynamics keys resolve to.
pub(super) struct InsertDynamics {
    /// Degrees of freedom by template index: the template's flags, with the
    /// insert's flags and `fixed`/`driven` over them.
    pub by_template: Vec<Dof>,
    /// Initial angular velocity, world frame, rad/s.
    pub angular_velocity: DVec3,
    /// `fixed = true`: the bodies must be at rest.
    pub fixed: bool,
    /// The orientation from `euler` (body → world), when given.
    pub euler: Option<DQuat>,
}

/// Reads the insert's dynamics keys (which ones apply to its kind is
/// checked by the caller).
pub(super) fn insert_dynamics(
    cx: &Cx,
    i: usize,
    ins: &RawInsert,
    kind: InsertKind,
    templates: &[TemplateDef],
) -> R<InsertDynamics> {
    let p = |k: &'static str| [K("insert"), I(i), K(k)];
    let fixed = ins.fixed.unwrap_or(false);
    let driven = ins.driven.unwrap_or(false) || fixed;
    if ins.fixed == Some(true) && ins.driven.is_some() {
        return Err(cx.src.error_at_key(
            &p("driven"),
            "give either 'fixed' (bodies at rest) or 'driven' (bodies keep their velocity and angular velocity), not both",
        ));
    }
    if driven {
        for (k, given) in [
            ("force_flags", ins.force_flags.is_some()),
            ("torque_flags", ins.torque_flags.is_some()),
            ("start_after", ins.start_after.is_some()),
        ] {
            if given {
                return Err(cx.src.error_at_key(
                    &p(k),
                    format!(
                        "'{k}' does not apply to fixed or driven bodies: forces never move them"
                    ),
                ));
            }
        }
    }
    let angular_velocity = match ins.angular_velocity {
        Some(w) => cx.vec3(&p("angular_velocity"), w, "angular_velocity")?,
        None => DVec3::ZERO,
    };
    if fixed {
        for (k, v) in [
            ("velocity", ins.velocity.map(DVec3::from_array)),
            ("angular_velocity", Some(angular_velocity)),
        ] {
            if v.is_some_and(|v| v != DVec3::ZERO) {
                return Err(cx
                    .src
                    .error_at_key(
                        &p(k),
                        format!("fixed bodies are at rest: '{k}' must be zero"),
                    )
                    .note("help: use driven = true for bodies that keep a prescribed velocity"));
            }
        }
    }
    if let Some(t) = ins.start_after {
        cx.nonneg(&p("start_after"), t, "start_after", "s")?;
        if kind != InsertKind::Stream {
            return Err(cx.src.error_at_key(
                &p("start_after"),
                "'start_after' applies to kind = \"stream\" (a body file has the columns start_step, start_time)",
            ));
        }
    }
    let euler = match ins.euler {
        None => None,
        Some([phi, theta, psi]) => {
            if ins.orientation.is_some() {
                return Err(cx.src.error_at_key(
                    &p("euler"),
                    "give the orientation either as 'orientation' (quaternion) or as 'euler' (z-x-z angles), not both",
                ));
            }
            let e = cx.vec3(&p("euler"), [phi, theta, psi], "euler")?;
            if !(0.0..=std::f64::consts::PI).contains(&e.y) {
                return Err(cx
                    .err(
                        &p("euler"),
                        format!(
                            "euler = [phi, theta, psi]: theta lies in [0, pi] rad, found {}",
                            e.y
                        ),
                    )
                    .label("nutation angle out of range"));
            }
            Some(clump_core::math::euler_to_quat(e.x, e.y, e.z))
        }
    };
    let by_template = templates
        .iter()
        .map(|t| Dof {
            force_flag: ins.force_flags.unwrap_or(t.dof.force_flag),
            torque_flag: ins.torque_flags.unwrap_or(t.dof.torque_flag),
            driven,
        })
        .collect();
    Ok(InsertDynamics {
        by_template,
        angular_velocity,
        fixed,
        euler,
    })
}

/// A fixed insert's bodies from a file must be at rest: the first that is
/// not, as `(1-based body index, what moves)`.
pub(super) fn moving_body(bodies: &[clump_core::body::BodyInit]) -> Option<(usize, &'static str)> {
    bodies.iter().enumerate().find_map(|(k, b)| {
        if b.velocity != DVec3::ZERO {
            Some((k + 1, "velocity"))
        } else if b.angular_velocity != DVec3::ZERO {
            Some((k + 1, "angular velocity"))
        } else {
            None
        }
    })
}
