//! The device as a runner's [`StepDevice`] (crate clump-io): the GPU path
//! of `clump run|resume --device gpu` and of Python's `device="gpu"`.

use crate::context::Gpu;
use crate::support::unsupported_settings;
use crate::transfer::DeviceStepper;
use clump_core::world::World;
use clump_io::run::device::StepDevice;

/// The steps between a runner's events on the GPU ([`DeviceStepper`]),
/// with the adapter's name.
pub struct GpuSteps {
    stepper: DeviceStepper,
    adapter: String,
}

impl StepDevice for GpuSteps {
    fn advance(
        &mut self,
        world: &mut World,
        to: u64,
        stop: &mut dyn FnMut() -> bool,
    ) -> Result<u64, String> {
        self.stepper
            .advance(world, to, stop)
            .map_err(|e| e.to_string())
    }

    fn describe(&self) -> String {
        self.adapter.clone()
    }
}

/// The GPU for a runner of `world`: an error naming each setting of
/// `world` the device path does not run (by scenario key, with what is
/// allowed), or that no adapter with f64 shaders opened.
pub fn gpu_steps(world: &World) -> Result<Box<dyn StepDevice>, String> {
    let refused = unsupported_settings(world);
    if !refused.is_empty() {
        let lines: Vec<String> = refused.iter().map(|u| u.to_string()).collect();
        return Err(format!(
            "the GPU path cannot run this scenario:\n  {}",
            lines.join("\n  ")
        ));
    }
    let gpu = Gpu::new().map_err(|e| e.to_string())?;
    let adapter = gpu.describe();
    Ok(Box::new(GpuSteps {
        stepper: DeviceStepper::new(gpu),
        adapter,
    }))
}
