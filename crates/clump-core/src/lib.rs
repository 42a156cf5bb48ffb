//! # clump-core
//!
//! The engine of Clump, a Discrete Element Method (DEM) simulator for granular
//! materials made of rigid *clumps* of overlapping spheres (the multi-sphere
//! method).
//!
//! Conventions used throughout (SI units everywhere):
//! - A body's orientation is a unit quaternion `q = (w, x, y, z)` (glam's
//!   [`glam::DQuat`], scalar `w`), mapping **body frame → world frame**:
//!   `v_world = q · v_body · q*`. The transformation matrix `A` (docs/theory.md
//!   T-2) maps world to body, so `A = R(q)ᵀ`.
//! - The body frame of a clump is its principal frame, origin at its centre of mass.
//! - Every vector field states its frame (`_world` / `_body`) in its docs.
//!
//! A [`world::World`] is a set of named sets (bodies, templates, spheres,
//! walls, the neighbour state with the contact store, scratch); the step
//! pipeline ([`step`]) works on them, and every driver advances a world
//! through one run loop ([`step::run`]) with hooks at step boundaries.
//! Data flows one way through a step: bodies → sphere centres → contacts →
//! body loads (force and torque about each centre of mass) → bodies. Read
//! the contacts of a step with [`world::World::contacts`]; steer between
//! steps with the methods of [`steer`]. The map of the code is
//! ARCHITECTURE.md at the repository root.
#![warn(missing_docs)]

pub mod body;
pub mod boundary;
pub mod contact;
pub mod contacts;
pub mod dof;
pub mod health;
pub mod heat;
pub mod insert;
pub mod lost;
pub mod math;
pub mod multi_contact;
pub mod neighbor;
pub mod par;
pub mod partition;
pub mod rotation;
pub mod shape;
pub mod sphere;
pub mod state;
pub mod stats;
pub mod steer;
pub mod step;
#[cfg(any(test, feature = "testbed"))]
pub mod testbed;
pub mod thermo;
pub mod wall;
pub mod world;

pub use glam::{DMat3, DQuat, DVec3};
