//! Broad phase: cell lists with a Verlet skin, spatial sorting, and the half
//! list of sphere pairs from different bodies.
//!
//! - [`grid`]: the uniform cell grid (cell edge ≥ largest sphere diameter + skin).
//! - [`sort`]: sort of bodies by cell, in slabs across the longest axis, so
//!   spatial neighbours are memory neighbours; each body's spheres stay
//!   contiguous.
//! - [`pairs`]: the half pair list, built allocation-free after warm-up,
//!   with same-body pairs excluded by construction; contact history is keyed
//!   by the global sphere ids and survives rebuilds and re-sorting.
//! - [`topo`]: one candidate pair's partner, image, live flag and row step.
//! - [`skin`]: the rebuild trigger: any sphere displaced by more than half the
//!   skin since the last build, which counts rotation because it measures the
//!   sphere centres themselves.
//! - `body_search`: the pair search by body pairs on many-sphere bodies,
//!   binned by their bounding spheres (`body_bounds`); its rows ascend.
//! - `carry`: contact histories carried across a rebuild that re-sorts
//!   the bodies, by storage index (global ids for a checkpoint or ranks).
//! - [`walls`]: the wall Verlet list, the spheres with a wall to test and
//!   their sphere–wall contact slots.

mod body_bounds;
mod body_search;
mod build_input;
pub(crate) mod carry;
pub mod grid;
pub mod pairs;
pub mod skin;
pub mod sort;
mod state;
pub mod topo;
pub mod walls;

pub use grid::CellGrid;
pub(crate) use pairs::PairBody;
pub use pairs::{BodyLoad, PairList};
pub(crate) use state::NeighborState;
pub use topo::PairTopo;
