//! Post-processing of a run's frames, during the run or afterwards from
//! its saved files: the contact network, coarse-grained continuum fields
//! and flow measurement.
//!
//! It lives in `clump-io` because the same code serves the scenario runner
//! (fields and flow written while the run goes on, from the world) and
//! `clump post` (from the saved `.vtp` frames), through one [`frame::Frame`]
//! type; a separate crate would need both sides' types.

pub mod bed;
pub mod fields;
pub mod fields_sum;
pub mod flow;
pub mod frame;
pub mod grid;
pub mod kernel;
pub mod network;
pub mod read;
pub mod spec;
pub mod write;
