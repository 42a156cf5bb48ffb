//! Convection from the fluid (docs/theory.md T-90 … T-93): the fluid's
//! thermal properties are set on a world that has heat and a fluid; the
//! heat stage (`step::heat`) then exchanges `h A (T_f − T)` between each
//! body and the fluid, with the Ranz–Marshall Nusselt number of the
//! body's volume-equivalent sphere at its slip speed
//! ([`crate::heat::convective_conductance`]).

use crate::heat::FluidHeat;
use crate::world::{World, WorldError};

impl World {
    /// Sets the fluid's temperature, thermal conductivity and specific heat
    /// (validated), turning convection on; `None` turns it off. Needs heat
    /// ([`World::enable_heat`]) and a fluid ([`World::set_fluid`]);
    /// convection acts while both are set.
    pub fn set_fluid_heat(&mut self, fluid_heat: Option<FluidHeat>) -> Result<(), WorldError> {
        if let Some(f) = &fluid_heat {
            f.validate().map_err(WorldError::BadValue)?;
            if self.fluid.is_none() {
                return Err(WorldError::BadValue(
                    "convection needs a fluid: set_fluid first".into(),
                ));
            }
        }
        let heat = self.heat.as_deref_mut().ok_or_else(|| {
            WorldError::BadValue("convection needs heat transfer: enable_heat first".into())
        })?;
        heat.convection = fluid_heat;
        Ok(())
    }

    /// The fluid's thermal properties, while convection is on.
    pub fn fluid_heat(&self) -> Option<FluidHeat> {
        self.heat.as_deref().and_then(|h| h.convection)
    }
}
