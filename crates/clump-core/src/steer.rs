//! Steering a world at a step boundary: the public mutations of body state,
//! each keeping what the step derives from it consistent.
//!
//! Between two steps the world holds positions, velocities and forces of
//! the same instant; the next step's first half kick uses the forces of the
//! last evaluation, as a stage change in a scenario does (velocity Verlet
//! resumes from the new state). Sphere centres, the packed per-body record
//! of the pair stage and the neighbour lists are derived by the next step
//! from the bodies: a pose change further than half the Verlet skin makes
//! that step rebuild the lists, and adding or removing a body marks the
//! topology for a rebuild.

use crate::body::AxisFlags;
use crate::world::{World, WorldError};
use glam::{DQuat, DVec3};

impl World {
    /// Storage index of body `id`, or an error naming it.
    fn steer_index(&self, id: u64) -> Result<usize, WorldError> {
        self.body_index(id)
            .ok_or_else(|| WorldError::BadReference(format!("no body with id {id}")))
    }

    /// Sets body `id`'s centre-of-mass velocity, world frame, m/s.
    pub fn set_body_velocity(&mut self, id: u64, velocity: DVec3) -> Result<(), WorldError> {
        let i = self.steer_index(id)?;
        self.set_body_velocity_at(i, velocity)
    }

    /// Sets body `id`'s angular velocity, world frame, rad/s (and its
    /// angular momentum `L = R I Rᵀ ω` to match).
    pub fn set_body_angular_velocity(&mut self, id: u64, omega: DVec3) -> Result<(), WorldError> {
        let i = self.steer_index(id)?;
        self.set_body_angular_velocity_at(i, omega)
    }

    /// Moves body `id`: centre of mass (world frame, m) and orientation
    /// (body → world; normalised here, refused when zero or not finite).
    /// The angular velocity is kept; the angular momentum follows the new
    /// orientation.
    pub fn set_body_pose(
        &mut self,
        id: u64,
        position: DVec3,
        orientation: DQuat,
    ) -> Result<(), WorldError> {
        let i = self.steer_index(id)?;
        self.set_body_pose_at(i, position, orientation)
    }

    /// Sets body `id`'s temperature, K (`> 0`); an error when the world
    /// has no heat.
    pub fn set_body_temperature(&mut self, id: u64, temperature: f64) -> Result<(), WorldError> {
        let i = self.steer_index(id)?;
        self.set_body_temperature_at(i, temperature)
    }

    /// [`Self::set_body_temperature`] for the body at storage index `i`.
    pub fn set_body_temperature_at(
        &mut self,
        i: usize,
        temperature: f64,
    ) -> Result<(), WorldError> {
        self.check_heat_value(
            i,
            "temperature",
            temperature > 0.0 && temperature.is_finite(),
            "> 0 K and finite",
            temperature,
        )?;
        self.bodies.temperature[i] = temperature;
        Ok(())
    }

    /// Sets the heat source of the body at storage index `i`, W (finite);
    /// an error when the world has no heat.
    pub fn set_body_heat_source_at(&mut self, i: usize, power: f64) -> Result<(), WorldError> {
        self.check_heat_value(i, "heat source (W)", power.is_finite(), "finite", power)?;
        self.bodies.heat_source[i] = power;
        Ok(())
    }

    /// Refuses a thermal value for body `i` when the world has no heat,
    /// the index is out of range or the value is not `allowed`.
    fn check_heat_value(
        &self,
        i: usize,
        what: &str,
        ok: bool,
        allowed: &str,
        v: f64,
    ) -> Result<(), WorldError> {
        if self.heat.is_none() {
            return Err(WorldError::BadValue(format!(
                "the world has no heat transfer (no [heat] in the scenario): no {what} to set"
            )));
        }
        if !ok {
            return Err(WorldError::BadValue(format!(
                "{what} must be {allowed}, got {v}"
            )));
        }
        self.check_index(i)
    }

    /// [`Self::set_body_velocity`] for the body at storage index `i` (the
    /// index into `bodies`' arrays at this boundary): for drivers that set
    /// many bodies at once.
    pub fn set_body_velocity_at(&mut self, i: usize, velocity: DVec3) -> Result<(), WorldError> {
        finite("velocity", velocity)?;
        self.check_index(i)?;
        self.bodies.velocity[i] = velocity;
        Ok(())
    }

    /// Moves the body at storage index `i` to `position` (centre of mass,
    /// world frame, m), keeping its orientation and angular momentum bit
    /// for bit ([`Self::set_body_pose_at`] with the same orientation would
    /// renormalise it).
    pub fn set_body_position_at(&mut self, i: usize, position: DVec3) -> Result<(), WorldError> {
        finite("position", position)?;
        self.check_index(i)?;
        self.bodies.position[i] = position;
        Ok(())
    }

    /// [`Self::set_body_angular_velocity`] for storage index `i`.
    pub fn set_body_angular_velocity_at(
        &mut self,
        i: usize,
        omega: DVec3,
    ) -> Result<(), WorldError> {
        finite("angular velocity", omega)?;
        self.check_index(i)?;
        let b = &mut self.bodies;
        let q = b.orientation[i];
        b.angular_velocity[i] = omega;
        b.angular_momentum[i] = q * (b.inertia[i] * (q.inverse() * omega));
        Ok(())
    }

    /// [`Self::set_body_pose`] for storage index `i`.
    pub fn set_body_pose_at(
        &mut self,
        i: usize,
        position: DVec3,
        orientation: DQuat,
    ) -> Result<(), WorldError> {
        finite("position", position)?;
        let len = orientation.length();
        if !(len.is_finite() && len > 0.0) {
            return Err(WorldError::BadValue(format!(
                "orientation must be a finite, non-zero quaternion, got {orientation}"
            )));
        }
        self.check_index(i)?;
        let q = orientation / len;
        let b = &mut self.bodies;
        b.position[i] = position;
        b.orientation[i] = q;
        let omega = b.angular_velocity[i];
        b.angular_momentum[i] = q * (b.inertia[i] * (q.inverse() * omega));
        Ok(())
    }

    /// Sets the angular velocity `omega` (rad/s) and angular momentum `l`
    /// (kg m²/s), world frame, of the body at storage index `i` as given,
    /// neither derived from the other: the state of a restart from another
    /// code, which carries both.
    pub fn set_body_angular_state_at(
        &mut self,
        i: usize,
        omega: DVec3,
        l: DVec3,
    ) -> Result<(), WorldError> {
        finite("angular velocity", omega)?;
        finite("angular momentum", l)?;
        self.check_index(i)?;
        self.bodies.angular_velocity[i] = omega;
        self.bodies.angular_momentum[i] = l;
        Ok(())
    }

    /// Sets the DOF flags of the body at storage index `i`: per world axis,
    /// whether the force (`force_flag`) and the torque (`torque_flag`)
    /// component acts (LIGGGHTS `fflag`/`tflag`; a frozen component keeps
    /// its velocity or angular-momentum component).
    pub fn set_body_dof_at(
        &mut self,
        i: usize,
        force_flag: AxisFlags,
        torque_flag: AxisFlags,
    ) -> Result<(), WorldError> {
        self.check_index(i)?;
        self.bodies.force_flag[i] = force_flag;
        self.bodies.torque_flag[i] = torque_flag;
        Ok(())
    }

    pub(crate) fn check_index(&self, i: usize) -> Result<(), WorldError> {
        if i < self.bodies.len() {
            Ok(())
        } else {
            Err(WorldError::BadReference(format!(
                "no body at storage index {i} ({} bodies)",
                self.bodies.len()
            )))
        }
    }

    /// Removes body `id` with its spheres and their contacts.
    pub fn remove_body(&mut self, id: u64) -> Result<(), WorldError> {
        self.remove_lost_body(id, crate::lost::LossCause::Removed)
    }

    /// Removes body `id` as [`Self::remove_body`] does, counting it as
    /// lost for `cause` (another device found it beyond a side).
    pub fn remove_lost_body(
        &mut self,
        id: u64,
        cause: crate::lost::LossCause,
    ) -> Result<(), WorldError> {
        let i = self.steer_index(id)?;
        let keep: Vec<u32> = (0..self.bodies.len() as u32)
            .filter(|&k| k as usize != i)
            .collect();
        self.bodies.permute(&keep);
        self.lost.record(cause);
        self.phase.topology_changed();
        Ok(())
    }
}

fn finite(what: &str, v: DVec3) -> Result<(), WorldError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(WorldError::BadValue(format!(
            "{what} must be finite, got {v}"
        )))
    }
}
