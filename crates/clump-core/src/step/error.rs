//! Why a step could not be taken.

use thiserror::Error;

/// Why a step could not be taken.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum StepError {
    /// The neighbour grid could not be built (e.g. a periodic box too small).
    #[error("neighbour search: {0}")]
    Neighbor(String),
    /// A driver of [`crate::world::World::run_driven`] named an event that is not ahead.
    #[error("the driver's next event (step {event}) is not after the current step {step}")]
    Event {
        /// The world's step.
        step: u64,
        /// The event's step.
        event: u64,
    },
}
