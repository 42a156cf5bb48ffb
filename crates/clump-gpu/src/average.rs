//! `average` multi-contact on the device, host side (`shaders/average.wgsl`):
//! the pairs' switch in the integer parameters. A wall's own switch is in
//! its row (walls.rs).

use clump_core::multi_contact::MultiContact;
use clump_core::world::World;

/// Index of the pairs' switch in the integer parameters (average.wgsl
/// PU_AVERAGE), after periodic.wgsl's PU_PERIODIC.
pub(crate) const PU_AVERAGE: usize = crate::periodic::PU_PERIODIC + 1;

/// Whether `world`'s sphere pairs average their forces per body pair
/// (`simulation.multi_contact = "average"`).
pub(crate) fn pairs_average(world: &World) -> bool {
    world.config.multi_contact == MultiContact::Average
}
