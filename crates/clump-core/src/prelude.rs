//! What a driver of the engine needs, in one import:
//! `use clump_core::prelude::*;`. The world and its settings, bodies,
//! templates and walls, the contact law's inputs, the run loop's hooks and
//! events, the recorded contacts, and every error a driver may meet.

pub use crate::body::BodyInit;
pub use crate::boundary::Domain;
pub use crate::contact::{ContactError, ContactTable, Material, PairProperties};
pub use crate::insert::InsertError;
pub use crate::multi_contact::MultiContact;
pub use crate::recorded_contacts::{Contact, ContactsError, Partner};
pub use crate::rotation::RotationScheme;
pub use crate::shape::{ClumpTemplate, ShapeError, Sphere};
pub use crate::step::run::{Advance, Driver, Event, Flow, RunEnd, StepHook, StepReport, Steps};
pub use crate::step::StepError;
pub use crate::wall::{Wall, WallMotion, WallShape};
pub use crate::world::{AddedMass, World, WorldConfig, WorldError};
pub use glam::{DMat3, DQuat, DVec3};
