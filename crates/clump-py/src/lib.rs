//! The Python module `clump._clump` (re-exported by the package `clump`):
//! scenarios run by the same runner as `clump run` ([`clump_io::run::Runner`],
//! stepped with `Runner::step_until`), the world's state as numpy arrays,
//! steering through the engine's setters (`clump_core::steer`), contacts
//! (`World::contacts`), templates. The Python-facing documentation is in
//! `python/clump/__init__.pyi` and docs/python.md.

mod access;
mod arrays;
mod contacts;
mod coupling;
mod dict;
mod errors;
mod order;
mod sim;
mod simulation;
mod template;
mod walls;

use pyo3::prelude::*;

#[pymodule]
fn _clump(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("ScenarioError", py.get_type::<errors::ScenarioError>())?;
    m.add("SimulationError", py.get_type::<errors::SimulationError>())?;
    m.add("UnstableError", py.get_type::<errors::UnstableError>())?;
    m.add_class::<simulation::Simulation>()?;
    m.add_class::<access::Bodies>()?;
    m.add_class::<access::Spheres>()?;
    m.add_class::<walls::Walls>()?;
    m.add_class::<coupling::Coupling>()?;
    m.add_class::<walls::Wall>()?;
    m.add_class::<template::Template>()?;
    m.add("__version__", clump_io::run::VERSION)?;
    Ok(())
}
