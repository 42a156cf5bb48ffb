//! Which degrees of freedom of a body the forces move (docs/theory.md T-15: LIGGGHTS'
//! `fflag`/`tflag`), and bodies whose motion is prescribed instead.
//!
//! - A `false` force flag freezes that world-frame component of the
//!   centre-of-mass velocity (it is never kicked); a `false` torque flag
//!   freezes that world-frame component of the angular momentum.
//! - A **driven** body never feels forces: its centre of mass moves at its
//!   initial velocity (world frame) and it turns at its initial angular
//!   velocity (world frame), `q ← exp(ω dt) q`, for the whole run. Contacts
//!   still act on the bodies it touches, and the force and torque the
//!   contacts exert on it are still summed in `Bodies::force`/`torque`
//!   (the load needed to keep it on its prescribed motion is their
//!   negative). A **fixed** body (LIGGGHTS `fix freeze`) is a driven body at
//!   rest: it never moves, to the bit.
//!
//! A driven body is stored as one whose start step never comes
//! ([`DRIVEN`]): the integration already leaves a body before its start step
//! free of forces, so the step loop tests nothing more for free bodies.

use crate::body::{AxisFlags, BodyInit};
use serde::{Deserialize, Serialize};

/// The start step of a driven body ([`Dof::driven`]): forces never act.
pub const DRIVEN: u64 = u64::MAX;

/// Degrees of freedom of a body (see the [module docs](self)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Dof {
    /// Force flags per world axis (LIGGGHTS `fflag`).
    pub force_flag: AxisFlags,
    /// Torque flags per world axis (LIGGGHTS `tflag`).
    pub torque_flag: AxisFlags,
    /// Velocity and world angular velocity held at their initial values.
    pub driven: bool,
}

impl Default for Dof {
    /// Every axis free, not driven.
    fn default() -> Self {
        Dof {
            force_flag: [true; 3],
            torque_flag: [true; 3],
            driven: false,
        }
    }
}

impl Dof {
    /// Writes these degrees of freedom into `init` (a driven body gets the
    /// start step [`DRIVEN`]).
    pub fn apply(&self, init: &mut BodyInit) {
        init.force_flag = self.force_flag;
        init.torque_flag = self.torque_flag;
        if self.driven {
            init.start_step = DRIVEN;
        }
    }

    /// The degrees of freedom of a body created from `init`.
    pub fn of(init: &BodyInit) -> Self {
        Dof {
            force_flag: init.force_flag,
            torque_flag: init.torque_flag,
            driven: init.start_step == DRIVEN,
        }
    }
}
