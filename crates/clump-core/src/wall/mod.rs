//! Walls: boundaries that spheres touch.
//!
//! A wall has a [`WallShape`] (plane, cylinder, axis-aligned box, or a
//! triangle [`mesh`] at a pose), a material,
//! a [`WallMotion`] and a several-contact treatment. Walls have infinite mass:
//! their motion is prescribed. The force and torque that the spheres exert on
//! each wall are recorded every step ([`WallLoad`]).

pub mod mesh;
mod set;
mod shape;

pub use mesh::{MeshError, TriMesh};
pub use set::WallSet;
pub use shape::{WallShape, WallTouch, MAX_TOUCHES_PER_WALL};

/// Most walls a world may have: a sphere–wall contact slot key holds the wall
/// index in 16 bits.
pub const MAX_WALLS: usize = 0xFFFF;

use crate::multi_contact::MultiContact;
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};

/// Prescribed rigid motion of a wall.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct WallMotion {
    /// Translation velocity, world frame, m/s. Moves the geometry.
    pub velocity: DVec3,
    /// Angular velocity, world frame, rad/s, about `center`. Rotates the
    /// geometry (planes, cylinders and meshes) and gives the surface velocity ω × (x − c).
    pub angular_velocity: DVec3,
    /// Centre of rotation, world frame, m (moves with `velocity`).
    pub center: DVec3,
    /// Extra tangential surface velocity, world frame, m/s, that does not move
    /// the geometry (a conveyor belt). Its component along the contact normal
    /// is ignored.
    pub surface_velocity: DVec3,
}

/// One wall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Wall {
    /// User-facing name (for thermo columns and messages).
    pub name: String,
    /// Geometry, world frame.
    pub shape: WallShape,
    /// Material index.
    pub material: u16,
    /// Prescribed motion.
    pub motion: WallMotion,
    /// Several-contact treatment between this wall and one body.
    pub multi_contact: MultiContact,
    /// An inactive wall exerts no force (e.g. a gate removed at a stage).
    pub active: bool,
}

impl Wall {
    /// Velocity of the wall surface at the world point `x`, m/s (world).
    #[inline]
    pub fn surface_velocity_at(&self, x: DVec3) -> DVec3 {
        self.motion.velocity
            + self.motion.angular_velocity.cross(x - self.motion.center)
            + self.motion.surface_velocity
    }

    /// Advances the geometry by `dt` seconds of the prescribed motion.
    pub fn advance(&mut self, dt: f64) {
        let m = &mut self.motion;
        let shift = m.velocity * dt;
        let w = m.angular_velocity;
        let rot = if w.length_squared() > 0.0 {
            Some(DQuat::from_scaled_axis(w * dt))
        } else {
            None
        };
        let c = m.center;
        self.shape.transform(shift, rot, c);
        m.center += shift;
    }
}

/// Force and torque that the spheres exert on one wall.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct WallLoad {
    /// Total force on the wall, world frame, N.
    pub force: DVec3,
    /// Total torque on the wall about its motion centre, world frame, N m.
    pub torque: DVec3,
}
