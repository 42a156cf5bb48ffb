//! `sim.walls`: the walls by name, with the load the particles exert on
//! each and its motion, which may be changed between steps.

use crate::arrays::{vec3_in, vec3_out};
use crate::errors::value_error;
use crate::simulation::Simulation;
use numpy::PyArray1;
use pyo3::exceptions::PyKeyError;
use pyo3::prelude::*;

/// The walls of a simulation, a mapping from name to [`Wall`].
#[pyclass(module = "clump._clump", mapping)]
pub struct Walls {
    pub(crate) sim: Py<Simulation>,
}

#[pymethods]
impl Walls {
    fn __len__(&self, py: Python<'_>) -> usize {
        self.sim.borrow(py).runner.world().walls.len()
    }

    fn __getitem__(&self, py: Python<'_>, name: &str) -> PyResult<Wall> {
        let s = self.sim.borrow(py);
        let walls = &s.runner.world().walls;
        match walls.iter().position(|w| w.name == name) {
            Some(index) => Ok(Wall {
                sim: self.sim.clone_ref(py),
                index,
            }),
            None => Err(PyKeyError::new_err(format!(
                "no wall named '{name}'; the walls are: {:?}",
                walls.iter().map(|w| w.name.as_str()).collect::<Vec<_>>()
            ))),
        }
    }

    fn __contains__(&self, py: Python<'_>, name: &str) -> bool {
        self.keys(py).iter().any(|n| n == name)
    }

    fn __iter__(&self, py: Python<'_>) -> PyResult<PyObject> {
        let names = self.keys(py).into_pyobject(py)?;
        Ok(names.try_iter()?.into_any().unbind())
    }

    /// Wall names, in scenario order.
    fn keys(&self, py: Python<'_>) -> Vec<String> {
        let s = self.sim.borrow(py);
        s.runner
            .world()
            .walls
            .iter()
            .map(|w| w.name.clone())
            .collect()
    }
}

/// One wall.
#[pyclass(module = "clump._clump")]
pub struct Wall {
    sim: Py<Simulation>,
    index: usize,
}

impl Wall {
    fn with<T>(&self, py: Python<'_>, f: impl FnOnce(&clump_core::world::World, usize) -> T) -> T {
        let s = self.sim.borrow(py);
        f(s.runner.world(), self.index)
    }

    fn motion(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&mut clump_core::wall::WallMotion),
    ) -> PyResult<()> {
        let mut s = self.sim.borrow_mut(py);
        let walls = &mut s.runner.world_mut().walls;
        let w = walls
            .get_mut(self.index)
            .ok_or_else(|| value_error("the wall no longer exists"))?;
        f(&mut w.motion);
        Ok(())
    }
}

#[pymethods]
impl Wall {
    /// Wall name.
    #[getter]
    fn name(&self, py: Python<'_>) -> String {
        self.with(py, |w, i| w.walls[i].name.clone())
    }

    /// Index in scenario order.
    #[getter]
    fn index(&self) -> usize {
        self.index
    }

    /// Force the particles exert on the wall (3,), world frame, N.
    #[getter]
    fn force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let f = self.with(py, |w, i| {
            w.walls.loads().get(i).map(|l| l.force).unwrap_or_default()
        });
        vec3_out(py, f)
    }

    /// Torque the particles exert about the wall's centre (3,), world frame, N m.
    #[getter]
    fn torque<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let t = self.with(py, |w, i| {
            w.walls.loads().get(i).map(|l| l.torque).unwrap_or_default()
        });
        vec3_out(py, t)
    }

    /// Translation velocity (3,), world frame, m/s. Settable.
    #[getter]
    fn velocity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let v = self.with(py, |w, i| w.walls[i].motion.velocity);
        vec3_out(py, v)
    }

    #[setter]
    fn set_velocity(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let v = vec3_in(value, "wall velocity")?;
        self.motion(py, |m| m.velocity = v)
    }

    /// Angular velocity about `center` (3,), world frame, rad/s. Settable.
    #[getter]
    fn angular_velocity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let v = self.with(py, |w, i| w.walls[i].motion.angular_velocity);
        vec3_out(py, v)
    }

    #[setter]
    fn set_angular_velocity(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let v = vec3_in(value, "wall angular velocity")?;
        self.motion(py, |m| m.angular_velocity = v)
    }

    /// Centre of rotation (3,), world frame, m.
    #[getter]
    fn center<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let v = self.with(py, |w, i| w.walls[i].motion.center);
        vec3_out(py, v)
    }

    /// An inactive wall exerts no force. Settable.
    #[getter]
    fn active(&self, py: Python<'_>) -> bool {
        self.with(py, |w, i| w.walls[i].active)
    }

    #[setter]
    fn set_active(&self, py: Python<'_>, value: bool) -> PyResult<()> {
        let mut s = self.sim.borrow_mut(py);
        let walls = &mut s.runner.world_mut().walls;
        walls
            .get_mut(self.index)
            .ok_or_else(|| value_error("the wall no longer exists"))?
            .active = value;
        Ok(())
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        format!("<clump.Wall '{}'>", self.name(py))
    }
}
