//! A device that takes the steps between the runner's events (the GPU
//! path of `clump run|resume --device gpu`, crate clump-gpu). The runner
//! keeps its order of work: at each event the world is on the host, whole,
//! and the last step before the event is the CPU path's own, so that the
//! event's outputs (thermo statistics and wall loads, contact frames, the
//! health check) are computed exactly as on the CPU path. The steps before
//! it go to the device, which takes the world with its springs and hands
//! it back with them.

use clump_core::world::World;

/// The steps between events on another device. `Sync` because a runner
/// lives in a Python object (PyO3 classes are shared between threads).
pub trait StepDevice: Send + Sync {
    /// Takes `world` from its step to step `to` (> its step), polling
    /// `stop` between batches of steps; returns the steps taken (fewer
    /// when `stop` answered true). Afterwards `world` holds the state the
    /// device reached: bodies, the forces of its last evaluation, contact
    /// springs, step and time.
    fn advance(
        &mut self,
        world: &mut World,
        to: u64,
        stop: &mut dyn FnMut() -> bool,
    ) -> Result<u64, String>;

    /// The device, in words (for the run's messages).
    fn describe(&self) -> String;
}
