//! The bodies' mass properties and degrees of freedom as the step reads
//! them: per template a row of a small table, and whether every body takes
//! its own from there.
//!
//! The body arrays ([`crate::body::Bodies`]) are the public state, which a
//! driver may edit between calls. In the common case every body carries its
//! template's mass and moments, is free on every axis and has started; the
//! step then reads these through the body's 4-byte template index instead
//! of six per-body arrays (50 bytes a body, which a bed larger than the
//! caches brings from memory every step; see `crate::step::body_props`).
//! Both give the same values, so the same bits. Which holds is checked over
//! all bodies whenever steps begin at a step boundary
//! ([`PropsTable::refresh`]), so an edit between calls always takes effect.

use crate::body::{AxisFlags, Bodies};
use crate::shape::ClumpTemplate;
use crate::world::AddedMass;
use glam::DVec3;

/// Every axis free.
pub(crate) const FREE: AxisFlags = [true; 3];

/// A template's mass properties as the kicks use them.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct TemplateProps {
    /// Mass, kg.
    pub mass: f64,
    /// Principal moments of inertia, kg m².
    pub inertia: DVec3,
    /// Their inverses ([`crate::rotation::inverse_inertia`]), 1/(kg m²).
    pub inv_inertia: DVec3,
    /// Added-mass factor `1 + CAdd ρ_f / ρ_body`.
    pub factor: f64,
    /// The half kick's quotients `dt/(2 m f_a)` (s/kg) and `dt/(2 f_a)`
    /// (s) at the table's time step, as the step computes them (the same
    /// bits): a division a body and kick fewer.
    pub kick: (f64, f64),
}

/// A half kick's quotients `(dt/(2 m f_a), dt/(2 f_a))` from
/// `(dt, m, f_a)`, as the step computes them.
pub(crate) type KickQuotients = fn(f64, f64, f64) -> (f64, f64);

/// Per template its [`TemplateProps`], and whether every body takes its
/// own from there (scratch: derived from the bodies and templates).
#[derive(Debug, Default)]
pub(crate) struct PropsTable {
    /// Every body has its template's mass and moments (bit for bit), is
    /// free on every axis and has started by the step of the last refresh.
    pub uniform: bool,
    /// The check holds for the bodies as they are: set by a refresh, cleared
    /// wherever the bodies may have changed (a public call, a rank's bodies
    /// exchanged; `World::props_changed`).
    pub fresh: bool,
    /// Per template.
    pub rows: Vec<TemplateProps>,
    /// The time step of the rows' half kicks, s.
    pub dt: f64,
}

impl PropsTable {
    /// Whether the table holds for the bodies as they are and time step
    /// `dt` (s). Every public call clears `fresh` already; the time step is
    /// compared as well, so that no path that changes it between
    /// refreshes can leave the rows' kicks stale.
    pub(crate) fn holds(&self, dt: f64) -> bool {
        self.fresh && self.dt.to_bits() == dt.to_bits()
    }

    /// Rebuilds the table and the check for `bodies` at the start of step
    /// `step`, time step `dt` (s), whose half kicks `kick(dt, mass,
    /// factor)` gives. Valid until the bodies, the templates or the time
    /// step change.
    pub(crate) fn refresh(
        &mut self,
        bodies: &Bodies,
        templates: &[ClumpTemplate],
        added: AddedMass,
        step: u64,
        (dt, kick): (f64, KickQuotients),
    ) {
        self.rows.clear();
        self.rows.extend(templates.iter().map(|t| {
            let factor = mass_factor(added, t.density);
            TemplateProps {
                mass: t.mass,
                inertia: t.principal_inertia,
                inv_inertia: crate::rotation::inverse_inertia(t.principal_inertia),
                factor,
                kick: kick(dt, t.mass, factor),
            }
        }));
        self.dt = dt;
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
        self.uniform = !force_per_body()
            && (0..bodies.len()).all(|i| {
                let t = &self.rows[bodies.template[i] as usize];
                let j = bodies.inertia[i];
                same(bodies.mass[i], t.mass)
                    && same(j.x, t.inertia.x)
                    && same(j.y, t.inertia.y)
                    && same(j.z, t.inertia.z)
                    && bodies.force_flag[i] == FREE
                    && bodies.torque_flag[i] == FREE
                    && bodies.start_step[i] <= step
            });
        self.fresh = true;
    }
}

/// Tests only: every body read from the arrays.
#[inline(always)]
fn force_per_body() -> bool {
    #[cfg(test)]
    return PER_BODY.load(std::sync::atomic::Ordering::SeqCst);
    #[cfg(not(test))]
    false
}

/// Tests only: see [`force_per_body`].
#[cfg(test)]
pub(crate) static PER_BODY: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

/// Added-mass factor `1 + CAdd ρ_f / ρ_body` (1 without a fluid).
#[inline(always)]
pub(crate) fn mass_factor(a: AddedMass, rho: f64) -> f64 {
    if a.coefficient == 0.0 || a.fluid_density == 0.0 {
        1.0
    } else {
        1.0 + a.coefficient * a.fluid_density / rho
    }
}
