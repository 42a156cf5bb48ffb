//! Whole-system quantities for the thermo output.

use crate::wall::WallLoad;
use crate::world::World;
use serde::{Deserialize, Serialize};

/// A snapshot of global quantities (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Thermo {
    /// Simulated time, s.
    pub time: f64,
    /// Step number.
    pub step: u64,
    /// Number of bodies.
    pub bodies: usize,
    /// Touching sphere–sphere contacts.
    pub pair_contacts: u64,
    /// Touching sphere–wall contacts.
    pub wall_contacts: u64,
    /// Translational kinetic energy Σ ½ m |v|², J.
    pub kinetic_translational: f64,
    /// Rotational kinetic energy Σ ½ ω·L (full clump inertia), J.
    pub kinetic_rotational: f64,
    /// Elastic energy stored in contacts, J.
    pub elastic: f64,
    /// Gravitational potential energy −Σ m g·x, J (zero at the origin).
    pub potential: f64,
    /// Largest overlap / smaller radius over all contacts.
    pub max_overlap_ratio: f64,
    /// Bodies lost so far, all causes (see [`crate::lost::LostBodies`]).
    pub lost_bodies: u64,
    /// Load on each wall (force and torque exerted by the particles), world frame.
    pub wall_loads: Vec<WallLoad>,
}

impl World {
    /// Global quantities at the current step. Sums run in storage order.
    pub fn thermo(&self) -> Thermo {
        let b = &self.bodies;
        let g = self.config.gravity;
        let mut kt = 0.0;
        let mut kr = 0.0;
        let mut pe = 0.0;
        for i in 0..b.len() {
            kt += 0.5 * b.mass[i] * b.velocity[i].length_squared();
            kr += 0.5 * b.angular_velocity[i].dot(b.angular_momentum[i]);
            pe -= b.mass[i] * g.dot(b.position[i]);
        }
        Thermo {
            time: self.time,
            step: self.step,
            bodies: b.len(),
            pair_contacts: self.stats.pair_contacts,
            wall_contacts: self.stats.wall_contacts,
            kinetic_translational: kt,
            kinetic_rotational: kr,
            elastic: self.stats.elastic_energy,
            potential: pe,
            max_overlap_ratio: self.stats.max_overlap_ratio,
            lost_bodies: self.lost.total(),
            wall_loads: self.walls.loads.clone(),
        }
    }
}
