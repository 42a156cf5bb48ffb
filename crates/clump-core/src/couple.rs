//! Coupling a world to a fluid solver at step boundaries (the loop of
//! CFD–DEM codes): the fluid ([`World::set_fluid`]), per-body fluid
//! velocity and void fraction, external forces and torques, the fluid
//! force of the last step and the void fraction on a grid. Arrays are in
//! storage order (`bodies.id[i]` names entry `i`), which changes only
//! inside a step. What is set here acts from the next force evaluation on
//! (the first half kick of the next step uses the load of the last one).

use crate::fluid::coupling::in_use;
use crate::fluid::void::VoidGrid;
use crate::fluid::{Fluid, FluidState, TemplateFluid};
use crate::world::{World, WorldError};
use glam::DVec3;

impl World {
    /// Sets the fluid (validated), or with `None` removes it; either way
    /// without a velocity grid ([`World::set_fluid_velocity_grid`]) or a
    /// void-fraction field ([`World::set_void_fraction_field`]).
    pub fn set_fluid(&mut self, fluid: Option<Fluid>) -> Result<(), WorldError> {
        let n = self.bodies.len();
        match fluid {
            None => {
                self.fluid = None;
                self.bodies.coupling.fluid_force = Vec::new();
            }
            Some(f) => {
                f.validate().map_err(WorldError::BadValue)?;
                let templates = self.templates.iter().map(TemplateFluid::of).collect();
                self.fluid = Some(FluidState {
                    fluid: f,
                    templates,
                    grid: None,
                    void_field: None,
                });
                in_use(&mut self.bodies.coupling.fluid_force, n, DVec3::ZERO);
            }
        }
        Ok(())
    }

    /// The fluid, if one is set.
    pub fn fluid(&self) -> Option<&Fluid> {
        self.fluid.as_ref().map(|f| &f.fluid)
    }

    /// What the fluid force reads of template `t` (volume, volume-equivalent
    /// diameter, sphericity), while a fluid is set.
    pub fn template_fluid(&self, t: usize) -> Option<TemplateFluid> {
        self.fluid
            .as_ref()
            .and_then(|f| f.templates.get(t).copied())
    }

    /// Sets the uniform fluid velocity, world frame, m/s (used for bodies
    /// without a per-body value).
    pub fn set_fluid_velocity(&mut self, velocity: DVec3) -> Result<(), WorldError> {
        let f = self.fluid.as_mut().ok_or_else(no_fluid)?;
        let mut new = f.fluid;
        new.velocity = velocity;
        new.validate().map_err(WorldError::BadValue)?;
        f.fluid = new;
        Ok(())
    }

    /// Sets (or with `None` removes) the fluid velocity field on a grid
    /// (T-83): each step a body without a per-body velocity is given the
    /// grid's trilinear interpolation at its centre of mass. Needs a fluid.
    pub fn set_fluid_velocity_grid(
        &mut self,
        grid: Option<std::sync::Arc<crate::fluid::VelocityGrid>>,
    ) -> Result<(), WorldError> {
        self.fluid.as_mut().ok_or_else(no_fluid)?.grid = grid;
        Ok(())
    }

    /// The fluid velocity grid, if one is set.
    pub fn fluid_velocity_grid(&self) -> Option<&crate::fluid::VelocityGrid> {
        self.fluid.as_ref().and_then(|f| f.grid.as_deref())
    }

    /// Sets (or with `None` removes) a void-fraction field computed by a
    /// coupled CFD code: each step a body without a per-body void fraction
    /// ([`World::set_body_void_fractions`]) takes the value of the field's
    /// cell that holds its centre of mass (1 outside the field's grid), and
    /// the drag laws read it instead of 1. Not kept in checkpoints (the
    /// driver sets it again after a resume). Needs a fluid.
    pub fn set_void_fraction_field(
        &mut self,
        field: Option<std::sync::Arc<crate::fluid::void::VoidField>>,
    ) -> Result<(), WorldError> {
        self.fluid.as_mut().ok_or_else(no_fluid)?.void_field = field;
        Ok(())
    }

    /// The void-fraction field a driver set, if any.
    pub fn void_fraction_field(&self) -> Option<&crate::fluid::void::VoidField> {
        self.fluid.as_ref().and_then(|f| f.void_field.as_deref())
    }

    /// Sets the interstitial fluid velocity at each body (storage order,
    /// world frame, m/s), as a CFD code interpolates it.
    pub fn set_body_fluid_velocities(&mut self, u: &[DVec3]) -> Result<(), WorldError> {
        self.check_len("fluid velocities", u.len())?;
        if let Some(k) = u.iter().position(|x| !x.is_finite()) {
            return Err(WorldError::BadValue(format!(
                "fluid velocity of body at index {k} must be finite, got {}",
                u[k]
            )));
        }
        let n = self.bodies.len();
        in_use(&mut self.bodies.coupling.fluid_velocity, n, DVec3::ZERO).copy_from_slice(u);
        Ok(())
    }

    /// Sets the local void fraction at each body (storage order), each in (0, 1].
    pub fn set_body_void_fractions(&mut self, eps: &[f64]) -> Result<(), WorldError> {
        self.check_len("void fractions", eps.len())?;
        if let Some(k) = eps.iter().position(|&e| !(e > 0.0 && e <= 1.0)) {
            return Err(WorldError::BadValue(format!(
                "void fraction of body at index {k} must be in (0, 1], got {}",
                eps[k]
            )));
        }
        let n = self.bodies.len();
        in_use(&mut self.bodies.coupling.void_fraction, n, 1.0).copy_from_slice(eps);
        Ok(())
    }

    /// Sets each body's void fraction to that of the `field` cell of `grid`
    /// that holds its centre, clamped to `[min, 1]` (a body outside the
    /// grid gets 1).
    pub fn set_body_void_fractions_from(
        &mut self,
        grid: &VoidGrid,
        field: &[f64],
        min: f64,
    ) -> Result<(), WorldError> {
        if field.len() != grid.len() || !(min > 0.0 && min <= 1.0) {
            return Err(WorldError::BadValue(format!(
                "void-fraction field has {} cells for a grid of {}, minimum {min} (must be in (0, 1])",
                field.len(),
                grid.len()
            )));
        }
        self.catch_up_bodies();
        let n = self.bodies.len();
        let pos = &self.bodies.position;
        let eps = in_use(&mut self.bodies.coupling.void_fraction, n, 1.0);
        for (e, p) in eps.iter_mut().zip(pos) {
            *e = grid.cell_of(*p).map_or(1.0, |c| field[c].clamp(min, 1.0));
        }
        Ok(())
    }

    /// The void fraction of every cell of `grid` from the bodies as they
    /// are (T-69), into `out`.
    pub fn void_fraction(&mut self, grid: &VoidGrid, out: &mut Vec<f64>) {
        self.catch_up_bodies();
        let (b, t) = (&self.bodies, &self.templates);
        let bodies = (0..b.len()).map(|i| {
            let (x, q) = (b.position[i], b.orientation[i]);
            t[b.template[i] as usize]
                .spheres
                .iter()
                .map(move |s| (x + q * s.center, s.radius))
        });
        grid.void_fraction(bodies, out);
    }

    /// Sets the persistent external force (N) and torque about the centre
    /// of mass (N m) on each body, storage order, world frame; they act at
    /// every step until set again or cleared.
    pub fn set_external_loads(
        &mut self,
        force: &[DVec3],
        torque: &[DVec3],
    ) -> Result<(), WorldError> {
        self.set_loads(force, torque, false)
    }

    /// Sets the external force and torque on each body for the next step
    /// only (used up by its force evaluation).
    pub fn set_next_step_loads(
        &mut self,
        force: &[DVec3],
        torque: &[DVec3],
    ) -> Result<(), WorldError> {
        self.set_loads(force, torque, true)
    }

    /// Checks `force` and `torque` (one per body) and stores them as the
    /// persistent loads, or with `once` as the next step's.
    fn set_loads(
        &mut self,
        force: &[DVec3],
        torque: &[DVec3],
        once: bool,
    ) -> Result<(), WorldError> {
        self.check_loads(force, torque)?;
        let (n, c) = (self.bodies.len(), &mut self.bodies.coupling);
        let (f, t) = if once {
            (&mut c.once_force, &mut c.once_torque)
        } else {
            (&mut c.force, &mut c.torque)
        };
        in_use(f, n, DVec3::ZERO).copy_from_slice(force);
        in_use(t, n, DVec3::ZERO).copy_from_slice(torque);
        Ok(())
    }

    /// Sets the persistent external force and torque of the body at
    /// storage index `i` (the others keep theirs, 0 where never set).
    pub fn set_external_load_at(
        &mut self,
        i: usize,
        force: DVec3,
        torque: DVec3,
    ) -> Result<(), WorldError> {
        if !(force.is_finite() && torque.is_finite()) {
            return Err(WorldError::BadValue(format!(
                "external load must be finite, got force {force}, torque {torque}"
            )));
        }
        self.check_index(i)?;
        let (n, c) = (self.bodies.len(), &mut self.bodies.coupling);
        in_use(&mut c.force, n, DVec3::ZERO)[i] = force;
        in_use(&mut c.torque, n, DVec3::ZERO)[i] = torque;
        Ok(())
    }

    /// Evaluates the forces of the current state where the next step
    /// would do it at its start (the first step after bodies were added or
    /// removed, or after a restart): the same computation at the same
    /// state, so no result changes. A coupling driver calls it at a step
    /// boundary so that loads it sets there always act from the force
    /// evaluation at the end of the next step; without it they would act
    /// from the start of such a step (a next-step load then counted 1.5 times).
    pub fn ready_forces(&mut self) -> Result<(), crate::step::StepError> {
        if self.phase.forces_ready() {
            return Ok(());
        }
        self.prepare()
    }

    /// The coupling arrays and the fluid's uniform velocity of a checkpoint
    /// (`World::restore_state`, its bodies already in place).
    pub(crate) fn restore_coupling(
        &mut self,
        coupling: Option<crate::fluid::BodyCoupling>,
        fluid_velocity: Option<DVec3>,
    ) -> Result<(), String> {
        if let Some(u) = fluid_velocity.filter(|u| !u.is_finite()) {
            return Err(format!("checkpoint fluid velocity {u} is not finite"));
        }
        self.bodies.coupling = coupling.unwrap_or_default();
        if let Some(f) = self.fluid.as_mut() {
            if let Some(u) = fluid_velocity {
                f.fluid.velocity = u;
            }
            let n = self.bodies.len();
            in_use(&mut self.bodies.coupling.fluid_force, n, DVec3::ZERO);
        }
        Ok(())
    }

    /// Removes all external loads and per-body fluid fields.
    pub fn clear_coupling_arrays(&mut self) {
        let c = &mut self.bodies.coupling;
        let keep = std::mem::take(&mut c.fluid_force);
        *c = Default::default();
        c.fluid_force = keep;
    }

    /// The fluid force of the last force evaluation on each body (drag,
    /// buoyancy, pressure gradient; N, world frame, storage order); empty
    /// without a fluid.
    pub fn fluid_forces(&self) -> &[DVec3] {
        &self.bodies.coupling.fluid_force
    }

    fn check_len(&self, what: &str, len: usize) -> Result<(), WorldError> {
        if len == self.bodies.len() {
            Ok(())
        } else {
            Err(WorldError::BadValue(format!(
                "{len} {what} given for {} bodies",
                self.bodies.len()
            )))
        }
    }

    fn check_loads(&self, force: &[DVec3], torque: &[DVec3]) -> Result<(), WorldError> {
        self.check_len("forces", force.len())?;
        self.check_len("torques", torque.len())?;
        match force.iter().chain(torque).position(|x| !x.is_finite()) {
            Some(k) => Err(WorldError::BadValue(format!(
                "external load entry {k} must be finite"
            ))),
            None => Ok(()),
        }
    }
}

fn no_fluid() -> WorldError {
    WorldError::BadValue("no fluid is set (set_fluid first)".into())
}
