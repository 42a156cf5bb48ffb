//! `clump.Simulation`: a scenario's run, held by the same runner as
//! `clump run` and stepped through the same boundary work and run loop, so
//! its bits are those of `clump run`.

use crate::access::{Bodies, Spheres};
use crate::errors::{self, from_run, value_error};
use crate::simulation::{steps_for, Simulation, SIGNAL_POLL};
use crate::walls::Walls;
use clump_io::run::{Runner, Until};
use clump_io::scenario::{self, Files};
use clump_io::vtk::VtkSeries;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[pymethods]
impl Simulation {
    /// Reads and validates a scenario TOML file, as `clump run`. With
    /// `output_dir` the scenario's outputs are written there as by `clump run -o`.
    /// Raises ScenarioError.
    #[staticmethod]
    #[pyo3(signature = (path, output_dir=None, overwrite=false, device="cpu"))]
    fn from_file(
        py: Python<'_>,
        path: PathBuf,
        output_dir: Option<PathBuf>,
        overwrite: bool,
        device: &str,
    ) -> PyResult<Self> {
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        Self::open(
            py,
            scenario::load(&path),
            &text,
            output_dir,
            overwrite,
            device,
        )
    }

    /// A scenario from TOML text; files it names are relative to `base_dir`.
    /// Raises ScenarioError.
    #[staticmethod]
    #[pyo3(signature = (text, base_dir=PathBuf::from("."), output_dir=None, overwrite=false, name="<string>", device="cpu"))]
    fn from_toml(
        py: Python<'_>,
        text: String,
        base_dir: PathBuf,
        output_dir: Option<PathBuf>,
        overwrite: bool,
        name: &str,
        device: &str,
    ) -> PyResult<Self> {
        let sc = scenario::parse(&base_dir.join(name), text.clone(), Files::disk(&base_dir));
        Self::open(py, sc, &text, output_dir, overwrite, device)
    }

    /// A scenario from a dict shaped like the TOML file (read like a file:
    /// same validation and messages). Raises ScenarioError.
    #[staticmethod]
    #[pyo3(signature = (d, base_dir=PathBuf::from("."), output_dir=None, overwrite=false, device="cpu"))]
    fn from_dict(
        py: Python<'_>,
        d: &Bound<'_, PyDict>,
        base_dir: PathBuf,
        output_dir: Option<PathBuf>,
        overwrite: bool,
        device: &str,
    ) -> PyResult<Self> {
        let text = crate::dict::to_toml(d)?;
        Self::from_toml(py, text, base_dir, output_dir, overwrite, "<dict>", device)
    }

    /// The run saved in a checkpoint (`save_checkpoint` or `clump run`);
    /// it continues bit for bit. Raises ScenarioError.
    #[staticmethod]
    #[pyo3(signature = (path, output_dir=None, device="cpu"))]
    fn from_checkpoint(
        py: Python<'_>,
        path: PathBuf,
        output_dir: Option<PathBuf>,
        device: &str,
    ) -> PyResult<Self> {
        // the device's settings are checked on the checkpoint's world
        // before the output folder is touched
        let device = crate::simulation::device_for(device, || {
            let bytes = std::fs::read(&path)
                .map_err(|e| format!("cannot read checkpoint {}: {e}", path.display()))?;
            clump_io::run::load_checkpoint_with_id(&bytes, &path)
                .map(|(_, w, _, _)| w)
                .map_err(|e| e.to_string())
        })?;
        let mut runner = match output_dir {
            Some(d) => Runner::resume(&path, Some(&d)),
            None => Runner::detached_resume(&path),
        }
        .map_err(|e| from_run(py, e, None))?;
        if let Some(d) = device {
            runner.set_device(d);
        }
        Simulation::new(py, runner)
    }

    /// Advances `steps` steps, `time` s, or to the end of the stages (never
    /// past it), fused and without the GIL; `callback(sim)` runs at every
    /// `every`-th step boundary and may read and steer; `False` stops.
    /// Ctrl-C raises KeyboardInterrupt at a step boundary, state intact.
    /// Returns the steps taken.
    #[pyo3(signature = (steps=None, time=None, callback=None, every=1))]
    fn run(
        slf: &Bound<'_, Self>,
        steps: Option<u64>,
        time: Option<f64>,
        callback: Option<PyObject>,
        every: u64,
    ) -> PyResult<u64> {
        let py = slf.py();
        if every == 0 {
            return Err(value_error("every must be >= 1"));
        }
        let (start, dt) = {
            let s = slf.borrow();
            (s.runner.world().step, s.runner.world().config.dt)
        };
        let end = match (steps, time) {
            (Some(_), Some(_)) => return Err(value_error("give steps or time, not both")),
            (Some(n), None) => start.saturating_add(n),
            (None, Some(t)) => start.saturating_add(steps_for(t, dt)?),
            (None, None) => u64::MAX,
        };
        let mut next_callback = if callback.is_some() {
            start.saturating_add(every)
        } else {
            u64::MAX
        };
        loop {
            let target = end.min(next_callback);
            let (until, step) = {
                let mut s = slf.borrow_mut();
                let text = s.text();
                let Simulation { runner, tally, .. } = &mut *s;
                let until = loop {
                    let deadline = Instant::now() + SIGNAL_POLL;
                    let r =
                        py.allow_threads(|| runner.step_until(target, true, Some(deadline), tally));
                    match r.map_err(|e| from_run(py, e, Some(&text)))? {
                        Until::Paused => py.check_signals()?,
                        u => break u,
                    }
                };
                (until, runner.world().step)
            };
            if step == next_callback {
                if let Some(cb) = &callback {
                    next_callback = next_callback.saturating_add(every);
                    let r = cb.call1(py, (slf,))?;
                    if r.bind(py).is(&*pyo3::types::PyBool::new(py, false)) {
                        break;
                    }
                }
            }
            if until == Until::Completed || step >= end {
                break;
            }
        }
        Ok(slf.borrow().runner.world().step - start)
    }

    /// One step (see `run`).
    fn step(slf: &Bound<'_, Self>) -> PyResult<u64> {
        Self::run(slf, Some(1), None, None, 1)
    }

    /// Simulated time, s.
    #[getter]
    fn time(&self) -> f64 {
        self.runner.world().time
    }

    /// Steps taken since the start of the run (also across checkpoints).
    #[getter]
    fn step_count(&self) -> u64 {
        self.runner.world().step
    }

    /// Time step, s.
    #[getter]
    fn dt(&self) -> f64 {
        self.runner.world().config.dt
    }

    /// Steps the scenario's stages take in all.
    #[getter]
    fn total_steps(&self) -> u64 {
        self.runner.scenario().total_steps()
    }

    /// True once all stages are done.
    #[getter]
    fn finished(&self) -> bool {
        self.runner.finished()
    }

    /// Name of the current stage (None once finished).
    #[getter]
    fn stage(&self) -> Option<String> {
        self.runner
            .scenario()
            .stages
            .get(self.runner.stage())
            .map(|s| s.name.clone())
    }

    /// Gravity, world frame, m/s² (settable between steps).
    #[getter]
    fn gravity<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        crate::arrays::vec3_out(py, self.runner.world().config.gravity)
    }

    #[setter]
    fn set_gravity(&mut self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let g = crate::arrays::vec3_in(value, "gravity")?;
        self.runner.world_mut().config.gravity = g;
        Ok(())
    }

    /// Template names, by template index (`bodies.template`).
    #[getter]
    fn template_names(&self) -> Vec<String> {
        let sc = self.runner.scenario();
        let n = self.runner.world().templates.len();
        (0..n)
            .map(|i| {
                sc.templates
                    .get(i)
                    .map_or_else(|| format!("template_{i}"), |t| t.name.clone())
            })
            .collect()
    }

    /// The bodies (sorted by id; arrays are copies; SI, world frame).
    #[getter]
    fn bodies(slf: &Bound<'_, Self>) -> Bodies {
        Bodies {
            sim: slf.clone().unbind(),
        }
    }

    /// The spheres (sorted by sphere id; arrays are copies).
    #[getter]
    fn spheres(slf: &Bound<'_, Self>) -> Spheres {
        Spheres {
            sim: slf.clone().unbind(),
        }
    }

    /// The walls by name: load (N, N m, world frame) and motion setters.
    #[getter]
    fn walls(slf: &Bound<'_, Self>) -> Walls {
        Walls {
            sim: slf.clone().unbind(),
        }
    }

    /// The coupling arrays: external loads, fluid velocity and void
    /// fraction per body, fluid forces, the void fraction on a grid.
    #[getter]
    fn coupling(slf: &Bound<'_, Self>) -> crate::coupling::Coupling {
        crate::coupling::Coupling {
            sim: slf.clone().unbind(),
        }
    }

    /// The contacts of the last step: a dict of arrays (ids, point m,
    /// normal, overlap m, force_normal and force_tangential N on sphere i;
    /// world frame; copies).
    fn contacts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        crate::contacts::contacts(py, self.runner.world())
    }

    /// The current thermo row: thermo.csv's columns (names with units) and values.
    fn thermo<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (names, t, power) = self.runner.thermo_row();
        let mut values: Vec<PyObject> = Vec::with_capacity(names.len());
        let f = |v: f64| v.into_pyobject(py).map(|o| o.into_any().unbind());
        let n = |v: u64| v.into_pyobject(py).map(|o| o.into_any().unbind());
        values.push(f(t.time)?);
        for v in [
            t.step,
            t.bodies as u64,
            t.pair_contacts + t.wall_contacts,
            t.pair_contacts,
            t.wall_contacts,
        ] {
            values.push(n(v)?);
        }
        for v in [
            t.kinetic_translational,
            t.kinetic_rotational,
            t.elastic,
            t.potential,
            t.max_overlap_ratio,
        ] {
            values.push(f(v)?);
        }
        values.push(n(t.lost_bodies)?);
        // per wall: six load columns, then its power column where thermo.csv has one
        let mut power = power.into_iter();
        for l in &t.wall_loads {
            for v in [
                l.force.x, l.force.y, l.force.z, l.torque.x, l.torque.y, l.torque.z,
            ] {
                values.push(f(v)?);
            }
            if names
                .get(values.len())
                .is_some_and(|c| c.ends_with("_power[W]"))
            {
                values.push(f(power.next().unwrap_or(0.0))?);
            }
        }
        if let Some(h) = &t.heat {
            for v in clump_io::thermo_csv::ThermoWriter::heat_values(h) {
                values.push(f(v)?);
            }
        }
        if let Some(ff) = t.fluid_force {
            for v in ff.to_array() {
                values.push(f(v)?);
            }
        }
        let d = PyDict::new(py);
        for (k, v) in names.into_iter().zip(values) {
            d.set_item(k, v)?;
        }
        Ok(d)
    }

    /// Writes the current state as one VTK frame into `directory`
    /// (`spheres_<step>.vtp`, `bodies_…`, `walls_…` and the `.pvd` series
    /// files, continued by later calls with the same folder).
    fn write_vtk(&mut self, directory: PathBuf) -> PyResult<()> {
        let k = match self.vtk.iter().position(|(d, _)| d == &directory) {
            Some(k) => k,
            None => {
                std::fs::create_dir_all(&directory).map_err(io_error(&directory))?;
                let s = VtkSeries::new(&directory).map_err(io_error(&directory))?;
                self.vtk.push((directory.clone(), s));
                self.vtk.len() - 1
            }
        };
        let world = self.runner.world();
        self.vtk[k]
            .1
            .write_frame(world, world.step)
            .map_err(io_error(&directory))
    }

    /// Writes a checkpoint to `path` (`clump resume` and
    /// `Simulation.from_checkpoint` continue from it bit for bit).
    fn save_checkpoint(&mut self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        self.runner
            .write_checkpoint_to(&path)
            .map_err(|e| from_run(py, e, None))
    }

    /// Every body's state with exact bit patterns, as `final_state.json`.
    fn final_state_json(&self) -> String {
        clump_io::run::final_state_json(self.runner.world())
    }

    /// Number of bodies.
    fn __len__(&self) -> usize {
        self.runner.world().bodies().len()
    }

    fn __repr__(&self) -> String {
        let w = self.runner.world();
        format!(
            "<clump.Simulation '{}': step {} of {}, t = {} s, {} bodies>",
            self.runner.scenario().path.display(),
            w.step,
            self.runner.scenario().total_steps(),
            w.time,
            w.bodies().len()
        )
    }
}

fn io_error(dir: &Path) -> impl FnOnce(std::io::Error) -> PyErr + '_ {
    move |e| errors::SimulationError::new_err(format!("{}: {e}", dir.display()))
}
