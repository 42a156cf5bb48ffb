//! # clump-core
//!
//! The engine of Clump, a Discrete Element Method (DEM) simulator for granular
//! materials made of rigid *clumps* of overlapping spheres (the multi-sphere
//! method).
//!
//! Conventions used throughout (SI units everywhere):
//! - A body's orientation is a unit quaternion `q = (w, x, y, z)` (glam's
//!   [`glam::DQuat`], scalar `w`), mapping **body frame → world frame**:
//!   `v_world = q · v_body · q*`. The seed's transformation matrix `A` maps world
//!   to body, so `A = R(q)ᵀ`.
//! - The body frame of a clump is its principal frame, origin at its centre of mass.
//! - Every vector field states its frame (`_world` / `_body`) in its docs.
//!
//! Data flows one way through a step (see [`step`]): bodies → spheres →
//! contacts → spheres → bodies.
#![warn(missing_docs)]

pub mod body;
pub mod boundary;
pub mod contact;
pub mod contacts;
pub mod dof;
pub mod health;
pub mod insert;
pub mod math;
pub mod multi_contact;
pub mod neighbor;
pub mod par;
pub mod rotation;
pub mod shape;
pub mod sphere;
pub mod state;
pub mod steer;
pub mod stats;
pub mod step;
#[cfg(any(test, feature = "testbed"))]
pub mod testbed;
pub mod thermo;
pub mod wall;
pub mod world;

pub use glam::{DMat3, DQuat, DVec3};
