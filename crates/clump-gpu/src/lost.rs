//! Bodies that left the domain on the device, host side
//! (`shaders/lost.wgsl`): the device marks a body whose centre of mass is
//! beyond a non-periodic side and freezes it; a download removes the
//! marked bodies from the host world, each counted for its side as the
//! CPU path's list rebuild counts it (clump-core lost.rs).

use crate::device_world::{DeviceError, DeviceWorld, PU_LOST};
use clump_core::lost::LossCause;
use clump_core::world::World;

/// The lost bit of a body's DOF word (lost.wgsl LOST_BIT); its side + 1
/// is in bits 8-10.
const LOST_BIT: u32 = 128;
/// f64s per body in `bm` (common.wgsl), the DOF word last.
const BM_ROW: usize = 9;

impl DeviceWorld {
    /// The bodies the device marked lost, by id, with their side: read
    /// only when the flag in the parameters says there is one.
    pub fn lost_bodies(&self) -> Result<Vec<(u64, LossCause)>, DeviceError> {
        let pu: Vec<u32> = self.read_u32(1)?;
        if pu[PU_LOST] == 0 {
            return Ok(Vec::new());
        }
        let bm = self.read_f64(8)?;
        let mut out = Vec::new();
        for (i, &id) in self.ids.iter().enumerate() {
            let word = bm[BM_ROW * i + BM_ROW - 1] as u32;
            if word & LOST_BIT != 0 {
                let side = ((word >> 8) & 7) as usize - 1;
                let cause = LossCause::Side {
                    axis: side / 2,
                    high: side % 2 == 1,
                };
                out.push((id, cause));
            }
        }
        Ok(out)
    }

    /// Removes from `world` the bodies the device marked lost that it
    /// still holds, counting each for its side.
    pub(crate) fn remove_lost(&self, world: &mut World) -> Result<(), DeviceError> {
        for (id, cause) in self.lost_bodies()? {
            if world.bodies().id.contains(&id) {
                world
                    .remove_lost_body(id, cause)
                    .map_err(|e| DeviceError::Overflow(format!("removing lost body {id}: {e}")))?;
            }
        }
        Ok(())
    }
}
