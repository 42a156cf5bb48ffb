//! The state behind `clump.Simulation`: the scenario's runner, the id
//! orders of its bodies and spheres, the VTK series started from Python; how
//! it is opened. Its Python methods are in `sim.rs`; the array views
//! (`access.rs`, `walls.rs`) hold a reference to it.

use crate::errors::{self, from_run, value_error};
use clump_io::run::device::StepDevice;
use clump_io::run::{Runner, Tally};
use clump_io::scenario;
use clump_io::vtk::VtkSeries;
use pyo3::prelude::*;
use std::path::PathBuf;
use std::time::Duration;

/// How long the engine steps without the GIL before it looks for Ctrl-C.
pub(crate) const SIGNAL_POLL: Duration = Duration::from_millis(100);

/// A scenario's run: the runner of `clump run`, stepped from Python (SI
/// units; vectors in the world frame unless named `_body`).
#[pyclass(module = "clump._clump")]
pub struct Simulation {
    pub(crate) runner: Runner,
    /// Steps and wall time since the simulation was made (for the manifest).
    pub(crate) tally: Tally,
    /// Body storage indices sorted by id (see `order`).
    pub(crate) body_order: Vec<usize>,
    /// Sphere storage indices sorted by sphere id.
    pub(crate) sphere_order: Vec<usize>,
    /// VTK series started by `write_vtk`, by folder.
    pub(crate) vtk: Vec<(PathBuf, VtkSeries)>,
}

impl Simulation {
    /// The simulation of `runner`, with the boundary work of its current
    /// step done (stage start, insertions, outputs), as a step would begin.
    pub(crate) fn new(py: Python<'_>, mut runner: Runner) -> PyResult<Self> {
        let text = runner.scenario().text.clone();
        let step = runner.world().step;
        let mut tally = Tally::start(&runner);
        runner
            .step_until(step, true, None, &mut tally)
            .map_err(|e| from_run(py, e, Some(&text)))?;
        Ok(Simulation {
            runner,
            tally,
            body_order: Vec::new(),
            sphere_order: Vec::new(),
            vtk: Vec::new(),
        })
    }

    /// Body storage indices in id order.
    pub(crate) fn bodies_sorted(&mut self) -> &[usize] {
        crate::order::ascending(&self.runner.world().bodies().id, &mut self.body_order);
        &self.body_order
    }

    /// Sphere storage indices in sphere-id order.
    pub(crate) fn spheres_sorted(&mut self) -> &[usize] {
        crate::order::ascending(&self.runner.world().spheres().gid, &mut self.sphere_order);
        &self.sphere_order
    }

    /// The run of a parsed scenario, with an output folder or without,
    /// its steps between events on `device` ([`device_for`]).
    pub(crate) fn open(
        py: Python<'_>,
        sc: Result<scenario::Scenario, scenario::ScenarioError>,
        text: &str,
        output_dir: Option<PathBuf>,
        overwrite: bool,
        device: &str,
    ) -> PyResult<Self> {
        let sc = sc.map_err(|e| errors::from_scenario(py, &e, Some(text)))?;
        let device = device_for(device, || sc.build_world().map_err(|e| e.to_string()))?;
        let mut runner = match output_dir {
            Some(d) => Runner::new_in(sc, &d, overwrite),
            None => Runner::detached(sc),
        }
        .map_err(|e| from_run(py, e, Some(text)))?;
        if let Some(d) = device {
            runner.set_device(d);
        }
        Simulation::new(py, runner)
    }

    pub(crate) fn text(&self) -> String {
        self.runner.scenario().text.clone()
    }
}

/// `device="cpu"` (None: the CPU path takes every step) or `"gpu"`: the
/// GPU path takes the steps between events (crate clump-gpu, the `gpu`
/// feature), refused before anything is written when it does not run a
/// setting of the world that `world` builds.
pub(crate) fn device_for(
    device: &str,
    world: impl FnOnce() -> Result<clump_core::world::World, String>,
) -> PyResult<Option<Box<dyn StepDevice>>> {
    match device {
        "cpu" => Ok(None),
        "gpu" => gpu_steps(world).map(Some),
        other => Err(value_error(format!(
            "device must be \"cpu\" or \"gpu\", got {other:?}"
        ))),
    }
}

#[cfg(feature = "gpu")]
fn gpu_steps(
    world: impl FnOnce() -> Result<clump_core::world::World, String>,
) -> PyResult<Box<dyn StepDevice>> {
    let w = world().map_err(value_error)?;
    clump_gpu::steps::gpu_steps(&w).map_err(|e| value_error(format!("device=\"gpu\": {e}")))
}

#[cfg(not(feature = "gpu"))]
fn gpu_steps(
    _world: impl FnOnce() -> Result<clump_core::world::World, String>,
) -> PyResult<Box<dyn StepDevice>> {
    Err(value_error(
        "device=\"gpu\": this clump package was built without the GPU path; build it with \
         `MATURIN_PEP517_ARGS=\"--features gpu\" pip install ./crates/clump-py` (needs a Vulkan, \
         Metal or DX12 driver with f64 shaders; on Linux without a GPU, Mesa's lavapipe: \
         package mesa-vulkan-drivers)",
    ))
}

/// Steps for `time` seconds at `dt`: the smallest whole number of steps
/// that covers it (to a relative 1e-9, so that 1 s at 1e-4 s is 10 000).
pub(crate) fn steps_for(time: f64, dt: f64) -> PyResult<u64> {
    if !(time.is_finite() && time >= 0.0) {
        return Err(value_error(format!(
            "time must be finite and >= 0 (s), got {time}"
        )));
    }
    Ok((time / dt * (1.0 - 1e-9)).ceil().max(0.0) as u64)
}
