//! Instability detection: a cheap per-step check of the statistics the force
//! stage already gathers ([`crate::stats::ContactStats`]: non-finite body
//! state, the largest overlap, the kinetic energy), and a diagnosis of the
//! likely cause from the contact time scales.
//!
//! [`HealthMonitor::check`] reads a handful of numbers (no pass over the
//! bodies), so it can run after every step. Everything it looks at is a
//! deterministic reduction, so the step at which it fires is the same for
//! any thread count and across checkpoint/restart (the monitor's own state is
//! serializable and belongs in checkpoints).

use crate::contact::time_scale::rayleigh_time;
use crate::stats::ContactStats;
use crate::world::World;
use serde::{Deserialize, Serialize};
use std::fmt;

/// Default largest overlap / smaller radius before a run is stopped.
pub const DEFAULT_MAX_OVERLAP_RATIO: f64 = 0.15;
/// Default factor by which the kinetic energy may grow between checks.
pub const DEFAULT_KINETIC_JUMP: f64 = 1e3;
/// Steps between two kinetic-energy reference points.
pub const KINETIC_WINDOW: u64 = 100;

/// Thresholds of the check.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HealthLimits {
    /// Largest accepted overlap divided by the smaller radius of the contact
    /// (dimensionless). Real contacts overlap by ≲ 1–5 %.
    pub max_overlap_ratio: f64,
    /// Largest accepted ratio of the kinetic energy to its value at the last
    /// reference point (dimensionless, > 1).
    pub kinetic_jump: f64,
    /// Kinetic energy per kilogram of bodies below which growth is not
    /// suspicious, J/kg: what the bodies may legitimately gain (free fall
    /// across the domain, insertion and wall speeds). The reference energy
    /// is never below this × the total body mass.
    pub specific_energy_floor: f64,
}

impl Default for HealthLimits {
    fn default() -> Self {
        HealthLimits {
            max_overlap_ratio: DEFAULT_MAX_OVERLAP_RATIO,
            kinetic_jump: DEFAULT_KINETIC_JUMP,
            specific_energy_floor: 0.0,
        }
    }
}

/// What went wrong.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum InstabilityKind {
    /// A body's position, velocity, angular momentum, force or torque is NaN
    /// or infinite.
    NonFinite {
        /// Global id of the first such body (storage order).
        body: u64,
    },
    /// A contact overlaps by more than the limit.
    Overlap {
        /// Overlap / smaller radius.
        ratio: f64,
        /// The limit.
        limit: f64,
        /// Global ids of the two bodies (second 0 against a wall).
        bodies: [u64; 2],
        /// Wall index for a sphere–wall contact.
        wall: Option<usize>,
    },
    /// The kinetic energy grew by more than the limit since the reference.
    KineticJump {
        /// Kinetic energy at the reference point, J.
        from: f64,
        /// Kinetic energy now, J.
        to: f64,
        /// Step of the reference point.
        since_step: u64,
        /// Body with the largest kinetic energy now.
        body: u64,
    },
    /// The contacts' elastic energy rose and fell in turn at every step
    /// for many steps: a bounded period-two oscillation of the contact
    /// forces ([`crate::oscillation`]).
    PeriodTwo {
        /// Steps in a row it alternated.
        steps: u64,
        /// Its smallest change in those steps, relative to it.
        relative_change: f64,
    },
}

/// An instability found by [`HealthMonitor::check`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Instability {
    /// Step at which it was seen (the state after this many steps).
    pub step: u64,
    /// Simulated time, s.
    pub time: f64,
    /// What was seen.
    pub kind: InstabilityKind,
}

impl Instability {
    /// Global ids of the bodies involved.
    pub fn bodies(&self) -> Vec<u64> {
        match &self.kind {
            InstabilityKind::NonFinite { body } | InstabilityKind::KineticJump { body, .. } => {
                vec![*body]
            }
            InstabilityKind::Overlap { bodies, .. } => {
                bodies.iter().copied().filter(|&b| b != 0).collect()
            }
            InstabilityKind::PeriodTwo { .. } => Vec::new(),
        }
    }
}

impl fmt::Display for Instability {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "at step {} (t = {:.6e} s): ", self.step, self.time)?;
        match &self.kind {
            InstabilityKind::NonFinite { body } => {
                write!(f, "body {body} has a NaN or infinite state")
            }
            InstabilityKind::Overlap {
                ratio,
                limit,
                bodies,
                wall,
            } => match wall {
                Some(w) => write!(
                    f,
                    "body {} overlaps wall {w} by {ratio:.3} of its sphere radius (limit max_overlap_ratio = {limit})",
                    bodies[0]
                ),
                None => write!(
                    f,
                    "bodies {} and {} overlap by {ratio:.3} of the smaller sphere radius (limit max_overlap_ratio = {limit})",
                    bodies[0], bodies[1]
                ),
            },
            InstabilityKind::KineticJump {
                from,
                to,
                since_step,
                body,
            } => write!(
                f,
                "the kinetic energy jumped from {from:.3e} J at step {since_step} to {to:.3e} J (×{:.1e}); body {body} has the most",
                to / from.max(f64::MIN_POSITIVE)
            ),
            InstabilityKind::PeriodTwo {
                steps,
                relative_change,
            } => write!(
                f,
                "the contacts' elastic energy rose and fell in turn at each of the last {steps} steps (by at least {relative_change:.1e} of it each step): contact forces flip sign every step, a period-two oscillation that stays bounded, so the bodies never come to rest"
            ),
        }
    }
}

/// The per-step check, with the kinetic-energy reference it carries from
/// window to window (save it in checkpoints for an identical detection
/// after a restart).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HealthMonitor {
    /// Thresholds.
    pub limits: HealthLimits,
    /// Kinetic energy at the last reference point, J (`None` before the first).
    pub reference_energy: Option<f64>,
    /// Step of the last reference point.
    pub reference_step: u64,
    /// The watch for a period-two oscillation.
    #[serde(default)]
    pub zigzag: crate::oscillation::ZigZag,
}

impl HealthMonitor {
    /// A monitor with `limits` and no reference yet.
    pub fn new(limits: HealthLimits) -> Self {
        HealthMonitor {
            limits,
            reference_energy: None,
            reference_step: 0,
            zigzag: Default::default(),
        }
    }

    /// Checks the state after a step from the world's statistics of the last
    /// force evaluation. O(1): reads [`World::stats`] only.
    pub fn check(&mut self, w: &World) -> Result<(), Instability> {
        self.check_step(w.step, w.time, &w.stats)
    }

    /// [`Self::check`] from a step's statistics (as the run loop reports
    /// them after every step, [`crate::step::run::StepReport`]): `step` and
    /// `time` (s) after the step.
    pub fn check_step(
        &mut self,
        step: u64,
        time: f64,
        s: &ContactStats,
    ) -> Result<(), Instability> {
        let fail = |kind| Err(Instability { step, time, kind });
        if s.non_finite_body != 0 || !s.kinetic_energy.is_finite() {
            return fail(InstabilityKind::NonFinite {
                body: s.non_finite_body,
            });
        }
        // NaN overlaps never compare greater; a NaN state is caught above.
        if s.max_overlap_ratio > self.limits.max_overlap_ratio {
            return fail(InstabilityKind::Overlap {
                ratio: s.max_overlap_ratio,
                limit: self.limits.max_overlap_ratio,
                bodies: s.max_overlap_bodies,
                wall: s.max_overlap_wall.checked_sub(1).map(|x| x as usize),
            });
        }
        let ke = s.kinetic_energy;
        match self.reference_energy {
            Some(r) => {
                let base = r.max(self.limits.specific_energy_floor * s.total_mass);
                if base > 0.0 && ke > self.limits.kinetic_jump * base {
                    return fail(InstabilityKind::KineticJump {
                        from: r,
                        to: ke,
                        since_step: self.reference_step,
                        body: s.max_kinetic_body,
                    });
                }
                if step >= self.reference_step + KINETIC_WINDOW {
                    self.reference_energy = Some(ke);
                    self.reference_step = step;
                }
            }
            None => {
                self.reference_energy = Some(ke);
                self.reference_step = step;
            }
        }
        if let Some((steps, relative_change)) = self.zigzag.add(s.elastic_energy) {
            return fail(InstabilityKind::PeriodTwo {
                steps,
                relative_change,
            });
        }
        Ok(())
    }
}

/// Smallest Rayleigh time over the templates in use, s, with the sphere
/// radius (m) and template index it belongs to.
pub fn smallest_rayleigh_time(w: &World) -> Option<(f64, f64, usize)> {
    let mut best: Option<(f64, f64, usize)> = None;
    for (t, tmpl) in w.templates.iter().enumerate() {
        let m = &w.materials[w.templates.material(t) as usize];
        for s in &tmpl.spheres {
            let tr = rayleigh_time(m, s.radius);
            if tr.is_finite() && best.map_or(true, |b| tr < b.0) {
                best = Some((tr, s.radius, t));
            }
        }
    }
    best
}

impl World {
    /// The likely cause of `inst`, as a sentence with a remedy, from the
    /// time step against the contact time scales (Rayleigh time, linear and
    /// Hertz contact durations at the bodies' speeds), the walls' motion and
    /// the contact stiffness. `steps_since_insertion`: steps since bodies
    /// were last added (0 or 1 when the instability shows right after an
    /// insertion, pointing at an overlapping placement).
    pub fn diagnose(&self, inst: &Instability, steps_since_insertion: Option<u64>) -> String {
        let dt = self.config.dt;
        if let InstabilityKind::PeriodTwo { .. } = inst.kind {
            return format!(
                "dt = {dt:.3e} s is above the stability limit of a damped contact (docs/theory.md T-51, T-52): a strongly damped contact on a clump that responds there like a much lighter body (far from its centre of mass) over-corrects every step; `clump check` prints that limit (dt_c); use dt = \"auto\" (at most 0.4 dt_c) or halve dt, or raise the restitution (less damping)"
            );
        }
        let (bodies, wall) = match &inst.kind {
            InstabilityKind::Overlap { bodies, wall, .. } => (bodies.to_vec(), *wall),
            k => (
                match k {
                    InstabilityKind::NonFinite { body }
                    | InstabilityKind::KineticJump { body, .. } => vec![*body],
                    _ => vec![],
                },
                None,
            ),
        };
        let idx: Vec<usize> = bodies
            .iter()
            .filter(|&&b| b != 0)
            .filter_map(|&b| self.body_index(b))
            .collect();
        // 1. an overlapping placement shows at once
        if let (InstabilityKind::Overlap { ratio, .. }, Some(k)) =
            (&inst.kind, steps_since_insertion)
        {
            if k <= 1 {
                return format!(
                    "overlapping initial placement: the bodies overlap by {ratio:.3} of the radius right after they were inserted (step {}); move them apart (bodies file, insertion region or orientation)",
                    inst.step.saturating_sub(k)
                );
            }
        }
        // 2. the time step against the Rayleigh time
        if let Some((tr, r, t)) = smallest_rayleigh_time(self) {
            if dt > 0.5 * tr {
                return format!(
                    "dt = {dt:.3e} s is {:.2}× the Rayleigh time {tr:.3e} s of the smallest sphere (r = {r:.3e} m, template '{}'); use dt ≤ {:.1e} s",
                    dt / tr,
                    self.templates[t].name,
                    0.2 * tr
                );
            }
        }
        // 3. the time step against the contact duration of the bodies involved
        //    (and of the lightest body, for linear springs)
        let speed = self.relative_speed(&idx, wall);
        let mut worst: Option<(f64, String)> = None; // (contact time, what)
        for (mat_a, mat_b, m_star, r_star, _, what) in self.contact_partners(&idx, wall) {
            let model = self.contact_table.get(mat_a, mat_b);
            let tc = model.contact_time(r_star, m_star, speed.max(1e-3));
            if tc.is_finite() && worst.as_ref().map_or(true, |w| tc < w.0) {
                worst = Some((tc, what));
            }
        }
        if let Some((tc, what)) = &worst {
            if dt > 0.1 * tc {
                return format!(
                    "dt = {dt:.3e} s is {:.2}× the contact duration {tc:.3e} s of {what} at {speed:.3e} m/s (a contact needs ≳ 20 steps); use dt ≤ {:.1e} s",
                    dt / tc,
                    tc / 50.0
                );
            }
        }
        // 4. a wall moving into the particles
        if let Some(wi) = wall {
            let wl = &self.walls[wi];
            if wl.motion.velocity != glam::DVec3::ZERO
                || wl.motion.angular_velocity != glam::DVec3::ZERO
            {
                return format!(
                    "wall '{}' moves (|v| = {:.3e} m/s, |ω| = {:.3e} rad/s) into the particles faster than the contacts can push them away; slow it down, stiffen the contact or use a smaller dt (now {dt:.3e} s)",
                    wl.name,
                    wl.motion.velocity.length(),
                    wl.motion.angular_velocity.length()
                );
            }
        }
        // 5. contacts too soft for the impact speed
        if let InstabilityKind::Overlap { limit, .. } = inst.kind {
            for (mat_a, mat_b, m_star, r_star, r_min, what) in self.contact_partners(&idx, wall) {
                let model = self.contact_table.get(mat_a, mat_b);
                let e = model.effective_modulus();
                if model.properties().normal == crate::contact::NormalLaw::Hertz && e.is_finite() {
                    let d = crate::contact::normal::hertz_max_overlap(e, r_star, m_star, speed);
                    let ratio = d / r_min;
                    if ratio > 0.5 * limit {
                        return format!(
                            "the contacts are too soft for the impact speed {speed:.3e} m/s: a Hertz impact of {what} overlaps by about {ratio:.3} of the radius (E* = {e:.3e} Pa); raise youngs_modulus or lower the speeds"
                        );
                    }
                }
            }
        }
        let tr = smallest_rayleigh_time(self).map(|x| x.0);
        match tr {
            Some(tr) => format!(
                "no single cause found; dt = {dt:.3e} s is {:.2}× the Rayleigh time {tr:.3e} s of the smallest sphere: try a smaller dt (e.g. {:.1e} s) and check the initial placement and wall motions",
                dt / tr,
                0.1 * tr
            ),
            None => format!("no single cause found; try a smaller dt (now {dt:.3e} s)"),
        }
    }

    /// Largest speed of the bodies `idx` relative to each other (one body: its
    /// speed relative to the wall `wall`, or its own speed), m/s.
    fn relative_speed(&self, idx: &[usize], wall: Option<usize>) -> f64 {
        let b = &self.bodies;
        let v = match (idx, wall) {
            ([i, j], _) => (b.velocity[*i] - b.velocity[*j]).length(),
            ([i], Some(w)) => {
                let wl = &self.walls[w];
                (b.velocity[*i] - wl.surface_velocity_at(b.position[*i])).length()
            }
            ([i], None) => b.velocity[*i].length(),
            _ => 0.0,
        };
        if v.is_finite() {
            v
        } else {
            0.0
        }
    }

    /// (material a, material b, m*, R*, smaller radius, description) of the contacts the
    /// bodies `idx` make: with each other (or the wall), using each body's
    /// smallest sphere; without bodies, the lightest body against itself.
    fn contact_partners(
        &self,
        idx: &[usize],
        wall: Option<usize>,
    ) -> Vec<(u16, u16, f64, f64, f64, String)> {
        let b = &self.bodies;
        let small = |i: usize| {
            let t = b.template[i] as usize;
            let r = self.templates[t]
                .spheres
                .iter()
                .map(|s| s.radius)
                .fold(f64::INFINITY, f64::min);
            (self.templates.material(t), r, b.mass[i])
        };
        let mut out = Vec::new();
        match (idx, wall) {
            ([i, j], _) => {
                let ((ma, ra, ma_), (mb, rb, mb_)) = (small(*i), small(*j));
                out.push((
                    ma,
                    mb,
                    ma_ * mb_ / (ma_ + mb_),
                    ra * rb / (ra + rb),
                    ra.min(rb),
                    format!("bodies {} and {}", b.id[*i], b.id[*j]),
                ));
            }
            ([i], Some(w)) => {
                let (ma, ra, m) = small(*i);
                out.push((
                    ma,
                    self.walls[w].material,
                    m,
                    ra,
                    ra,
                    format!("body {} on wall '{}'", b.id[*i], self.walls[w].name),
                ));
            }
            _ => {
                let lightest = (0..b.len()).min_by(|&x, &y| b.mass[x].total_cmp(&b.mass[y]));
                if let Some(i) = idx.first().copied().or(lightest) {
                    let (ma, ra, m) = small(i);
                    out.push((
                        ma,
                        ma,
                        0.5 * m,
                        0.5 * ra,
                        ra,
                        format!("two bodies like body {}", b.id[i]),
                    ));
                }
            }
        }
        out
    }
}
