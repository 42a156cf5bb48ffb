//! The parallel machinery of the step, fenced off from the physics: shared
//! mutable slices for disjoint parallel writes, the chunk-to-thread
//! affinity and balance of the per-step loops, the persistent thread team,
//! SIMD level detection and prefetch hints. Nothing here changes a result:
//! which thread runs which chunk, and which instruction set evaluates a
//! contact, give the same bits.

pub(crate) mod affinity;
pub(crate) mod prefetch;
pub(crate) mod shared;
pub mod simd;
mod team;
