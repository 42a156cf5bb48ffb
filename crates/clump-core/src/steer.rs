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
        finite("velocity", velocity)?;
        let i = self.steer_index(id)?;
        self.bodies.velocity[i] = velocity;
        Ok(())
    }

    /// Sets body `id`'s angular velocity, world frame, rad/s (and its
    /// angular momentum `L = R I Rᵀ ω` to match).
    pub fn set_body_angular_velocity(&mut self, id: u64, omega: DVec3) -> Result<(), WorldError> {
        finite("angular velocity", omega)?;
        let i = self.steer_index(id)?;
        let b = &mut self.bodies;
        let q = b.orientation[i];
        b.angular_velocity[i] = omega;
        b.angular_momentum[i] = q * (b.inertia[i] * (q.inverse() * omega));
        Ok(())
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
        finite("position", position)?;
        let len = orientation.length();
        if !(len.is_finite() && len > 0.0) {
            return Err(WorldError::BadValue(format!(
                "orientation must be a finite, non-zero quaternion, got {orientation}"
            )));
        }
        let i = self.steer_index(id)?;
        let q = orientation / len;
        let b = &mut self.bodies;
        b.position[i] = position;
        b.orientation[i] = q;
        let omega = b.angular_velocity[i];
        b.angular_momentum[i] = q * (b.inertia[i] * (q.inverse() * omega));
        Ok(())
    }

    /// Removes body `id` with its spheres and their contacts.
    pub fn remove_body(&mut self, id: u64) -> Result<(), WorldError> {
        let i = self.steer_index(id)?;
        let keep: Vec<u32> = (0..self.bodies.len() as u32)
            .filter(|&k| k as usize != i)
            .collect();
        self.bodies.permute(&keep);
        self.lost.record(crate::lost::LossCause::Removed);
        self.phase.topology_dirty = true;
        self.phase.forces_ready = false;
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
