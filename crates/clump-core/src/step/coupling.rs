//! The gather's coupling stage (between the walls and the final kick):
//! a body's external force and torque (persistent, and for this step
//! only) and its fluid force, added to its load. Built only when a fluid
//! is set or an external array is in use; otherwise the gather skips the
//! stage and its loads are those of a world without coupling, bit for bit.
//!
//! With a fluid, the whole load is scaled by the exponential drag
//! integrator's factor (docs/theory.md T-68, [`relaxation_factor`]), so the
//! drag stays stable when the particle response time `m'/β` is shorter
//! than the step: both half kicks use the load, and the half-step
//! velocity then relaxes over a step by exactly `exp(−β dt/m')` towards
//! its terminal value (the drag coefficient, the fluid velocity and the
//! other forces held over the step).

use crate::fluid::{body_load, relaxation_factor, BodyCoupling, FluidState};
use crate::par::shared::SharedMut;
use glam::DVec3;

/// What the stage reads and writes; the arrays are the bodies', each
/// body's entries written only by the chunk that holds it.
pub(crate) struct CouplingPass<'a> {
    fluid: Option<&'a FluidState>,
    template: &'a [u32],
    force: &'a [DVec3],
    torque: &'a [DVec3],
    once_force: SharedMut<DVec3>,
    once_torque: SharedMut<DVec3>,
    /// This evaluation ends the step: the next-step-only loads are used up.
    consume: bool,
    fluid_velocity: &'a [DVec3],
    void_fraction: &'a [f64],
    fluid_force: SharedMut<DVec3>,
    /// m/s², world frame.
    gravity: DVec3,
    /// s.
    dt: f64,
}

/// The arrays the stage writes, taken from the bodies before the shared
/// borrows of the gather.
pub(crate) struct CouplingWrites {
    once_force: SharedMut<DVec3>,
    once_torque: SharedMut<DVec3>,
    fluid_force: SharedMut<DVec3>,
}

impl CouplingWrites {
    /// The arrays of `c` for `n` bodies; the fluid force's sized for them
    /// with a fluid (allocates only when the bodies changed in number).
    pub(crate) fn new(fluid: bool, c: &mut BodyCoupling, n: usize) -> Self {
        if fluid {
            crate::fluid::coupling::in_use(&mut c.fluid_force, n, DVec3::ZERO);
        }
        CouplingWrites {
            once_force: SharedMut::new(&mut c.once_force),
            once_torque: SharedMut::new(&mut c.once_torque),
            fluid_force: SharedMut::new(&mut c.fluid_force),
        }
    }
}

impl<'a> CouplingPass<'a> {
    /// The stage for these bodies (`c` the arrays `w` was taken from), or
    /// None when there is nothing to add.
    pub(crate) fn new(
        fluid: Option<&'a FluidState>,
        c: &'a BodyCoupling,
        w: CouplingWrites,
        template: &'a [u32],
        gravity: DVec3,
        dt: f64,
        consume: bool,
    ) -> Option<Self> {
        if fluid.is_none() && c.is_empty() {
            return None;
        }
        Some(CouplingPass {
            fluid,
            template,
            force: &c.force,
            torque: &c.torque,
            once_force: w.once_force,
            once_torque: w.once_torque,
            consume,
            fluid_velocity: &c.fluid_velocity,
            void_fraction: &c.void_fraction,
            fluid_force: w.fluid_force,
            gravity,
            dt,
        })
    }

    /// Body `bi`'s load `(f, m)` (N, N m, world frame) with its external
    /// and fluid loads, at its velocity `v` (m/s) and kicked mass `m_eff`
    /// (kg, with the added-mass factor); `x` its centre of mass (world
    /// frame, m), where a velocity grid and a void-fraction field are read.
    ///
    /// # Safety
    /// Body `bi` is the calling chunk's.
    #[inline]
    pub(crate) unsafe fn apply(
        &self,
        bi: usize,
        (mut f, mut m): (DVec3, DVec3),
        v: DVec3,
        x: DVec3,
        m_eff: f64,
    ) -> (DVec3, DVec3) {
        if !self.force.is_empty() {
            f += self.force[bi];
        }
        if !self.torque.is_empty() {
            m += self.torque[bi];
        }
        if self.once_force.len() != 0 {
            f += self.once_force.read(bi);
            if self.consume {
                *self.once_force.get(bi) = DVec3::ZERO;
            }
        }
        if self.once_torque.len() != 0 {
            m += self.once_torque.read(bi);
            if self.consume {
                *self.once_torque.get(bi) = DVec3::ZERO;
            }
        }
        let Some(fs) = self.fluid else {
            return (f, m);
        };
        let u = match (self.fluid_velocity.get(bi), &fs.grid) {
            (Some(&u), _) => u,
            (None, Some(g)) => g.sample(x),
            (None, None) => fs.fluid.velocity,
        };
        let eps = match (self.void_fraction.get(bi), &fs.void_field) {
            (Some(&e), _) => e,
            (None, Some(v)) => v.at(x),
            (None, None) => 1.0,
        };
        let t = &fs.templates[self.template[bi] as usize];
        let (beta, other) = body_load(&fs.fluid, t, self.gravity, v, u, eps);
        let fluid = other + beta * (u - v);
        if self.fluid_force.len() != 0 {
            *self.fluid_force.get(bi) = fluid;
        }
        let c = relaxation_factor(beta * self.dt / m_eff);
        ((f + fluid) * c, m)
    }
}
