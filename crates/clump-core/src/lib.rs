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
//! ARCHITECTURE.md at the repository root; [`prelude`] has what a driver
//! needs.
//!
//! # Example
//!
//! Two soft beads (r = 1 mm, E = 5 MPa) meet head-on at 0.1 m/s each; they
//! touch from about step 100 for a few hundred steps of 1 µs (Hertz), and
//! at step 200 the contact's normal force is read from the step's records.
//!
//! ```
//! use clump_core::prelude::*;
//!
//! let soft = Material { youngs_modulus: 5e6, poisson_ratio: 0.3, density: 2500.0 };
//! let props = PairProperties { restitution: 0.9, friction: 0.3, ..PairProperties::default() };
//! let table = ContactTable::new(&[soft], |_, _| props)?;
//! let config = WorldConfig {
//!     domain: Domain { lo: DVec3::splat(-0.01), hi: DVec3::splat(0.01), periodic: [false; 3] },
//!     gravity: DVec3::ZERO,
//!     dt: 1e-6,
//!     rotation: RotationScheme::default(),
//!     added_mass: AddedMass::default(),
//!     skin: None,
//!     multi_contact: MultiContact::Sum,
//! };
//! let mut world = World::new(config, vec![soft], table);
//! let bead = ClumpTemplate::from_spheres("bead", &[Sphere::new(DVec3::ZERO, 1e-3)], 2500.0)?;
//! let t = world.add_template(bead, 0)?;
//! for (x, v) in [(-1.01e-3, 0.1), (1.01e-3, -0.1)] {
//!     let mut body = BodyInit::at_rest(t, DVec3::new(x, 0.0, 0.0), DQuat::IDENTITY);
//!     body.velocity = DVec3::new(v, 0.0, 0.0);
//!     world.add_body(&body)?;
//! }
//! // run to step 200, keeping the contacts of the last step
//! world.advance(Event { step: 200, contacts: true }, &mut ())?;
//! let c = world.contacts()?.next().expect("the beads touch");
//! assert!(c.overlap > 0.0);
//! // the normal force (N, world frame) pushes the beads apart along x
//! assert!(c.force_normal.x.abs() > 0.0 && c.normal.x.abs() > 0.999);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

pub mod body;
pub mod boundary;
pub mod contact;
pub mod convection;
pub mod couple;
pub mod dof;
pub mod exact_sum;
pub mod fluid;
pub mod health;
pub mod heat;
pub mod insert;
pub mod lost;
pub mod math;
pub mod multi_contact;
pub mod neighbor;
pub mod oscillation;
pub(crate) mod par;
pub mod partition;
pub mod prelude;
pub mod recorded_contacts;
pub mod rotation;
pub mod shape;
pub mod sphere;
pub mod state;
pub mod state_pieces;
pub mod state_share;
pub mod stats;
pub mod steer;
pub mod step;
#[cfg(any(test, feature = "testbed"))]
pub mod testbed;
pub mod thermo;
pub mod wall;
pub mod world;

pub use glam::{DMat3, DQuat, DVec3};
