//! The step pipeline, in order (velocity Verlet, as LIGGGHTS `fix multisphere`):
//!
//! 1. [`integrate::initial`]: half kick of v and L, drift of the centre of
//!    mass, free-rotation drift of the orientation (the chosen rotation scheme);
//!    walls move.
//! 2. [`kinematics::update_spheres`]: sphere positions and velocities from the
//!    body poses, r = r_cm + Aᵀ r_b, v = v_cm + ω × (r − r_cm).
//! 3. Neighbour search ([`rebuild`]), only when a sphere moved more than half
//!    the skin. Bodies are wrapped, lost bodies removed and the rest Morton-sorted
//!    here. A future MPI layer exchanges ghost spheres at this stage.
//! 4. [`force`]: per-pair forces (sphere pairs of different bodies), then a
//!    per-body gather in a fixed order with sphere–wall contacts and gravity.
//!    F = Σ f, M = Σ (x_c − r_cm) × f (seed eq. 4.87–4.88).
//! 5. [`integrate::final_kick`]: second half kick.
//!
//! Every parallel loop writes disjoint outputs and every reduction runs over
//! fixed-size chunks in a fixed order, so the results are bit-identical for
//! any thread count.

pub mod force;
pub mod integrate;
pub mod kinematics;
pub mod rebuild;
pub(crate) mod shared;

use crate::world::World;
use thiserror::Error;

/// Why a step could not be taken.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum StepError {
    /// The neighbour grid could not be built (e.g. a periodic box too small).
    #[error("neighbour search: {0}")]
    Neighbor(String),
}

impl World {
    /// Computes sphere positions, the neighbour list and the forces at the
    /// current state, so that the first step starts with valid forces. Called
    /// automatically by [`World::step`].
    pub fn prepare(&mut self) -> Result<(), StepError> {
        rebuild::rebuild(self, true)?;
        force::compute(self);
        self.forces_ready = true;
        Ok(())
    }

    /// Advances the simulation by one time step.
    pub fn step(&mut self) -> Result<(), StepError> {
        if !self.forces_ready {
            self.prepare()?;
        }
        let dt = self.config.dt;
        integrate::initial(self);
        for w in &mut self.walls {
            w.advance(dt);
        }
        self.wall_cull &= rebuild::static_walls(&self.walls);
        kinematics::update_spheres(self);
        if self.topology_dirty
            || crate::neighbor::skin::needs_rebuild(
                &self.spheres.position,
                &self.reference_position,
                self.skin(),
            )
        {
            rebuild::rebuild(self, true)?;
        }
        force::compute(self);
        integrate::final_kick(self);
        self.step += 1;
        self.time = self.step as f64 * dt;
        Ok(())
    }

    /// Advances by `n` steps.
    pub fn run(&mut self, n: u64) -> Result<(), StepError> {
        for _ in 0..n {
            self.step()?;
        }
        Ok(())
    }
}
