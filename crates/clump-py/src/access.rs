//! `sim.bodies` and `sim.spheres`: the state as numpy arrays (fresh copies,
//! sorted by id), and the body setters, which go through the engine's
//! steering methods (`clump_core::steer`) and are validated first: a bad
//! array changes nothing.

use crate::arrays::{column, quats, rows_in, vec3s, UNIT_TOLERANCE};
use crate::errors::value_error;
use crate::simulation::Simulation;
use clump_core::sphere::SPHERE_ID_BITS;
use glam::{DQuat, DVec3};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;

/// The bodies of a simulation (see the stub for units and frames).
#[pyclass(module = "clump._clump")]
pub struct Bodies {
    pub(crate) sim: Py<Simulation>,
}

/// Reads `value` as one row per body and applies `set(world, index, row)`
/// to every body, after checking all rows (shape, finiteness, `check`).
fn set_rows(
    py: Python<'_>,
    sim: &Py<Simulation>,
    value: &Bound<'_, PyAny>,
    width: usize,
    what: &str,
    check: impl Fn(usize, &[f64]) -> PyResult<()>,
    set: impl Fn(
        &mut clump_core::world::World,
        usize,
        &[f64],
    ) -> Result<(), clump_core::world::WorldError>,
) -> PyResult<()> {
    let mut s = sim.borrow_mut(py);
    let order = s.bodies_sorted().to_vec();
    let rows = rows_in(value, order.len(), width, what)?;
    for (r, row) in rows.chunks_exact(width).enumerate() {
        check(r, row)?;
    }
    let world = s.runner.world_mut();
    for (row, &i) in rows.chunks_exact(width).zip(&order) {
        set(world, i, row).map_err(|e| value_error(format!("{what}: {e}")))?;
    }
    Ok(())
}

/// Reads `value` as one number per body (a length-N sequence or array)
/// and applies `set(world, index, value)` to every body, after checking
/// them all (length, finiteness).
fn set_column(
    py: Python<'_>,
    sim: &Py<Simulation>,
    value: &Bound<'_, PyAny>,
    what: &str,
    check: impl Fn(usize, &[f64]) -> PyResult<()>,
    set: impl Fn(&mut clump_core::world::World, usize, f64) -> Result<(), clump_core::world::WorldError>,
) -> PyResult<()> {
    let np = py.import("numpy")?;
    let column = np
        .call_method1("asarray", (value, "float64"))
        .map_err(|_| {
            value_error(format!(
                "{what} must be a sequence of numbers, one per body"
            ))
        })?;
    let rows = column.call_method1("reshape", ((-1i64, 1i64),))?;
    set_rows(py, sim, &rows, 1, what, check, |w, i, r| set(w, i, r[0]))
}

fn v3(r: &[f64]) -> DVec3 {
    DVec3::new(r[0], r[1], r[2])
}

fn no_check(_: usize, _: &[f64]) -> PyResult<()> {
    Ok(())
}

#[pymethods]
impl Bodies {
    fn __len__(&self, py: Python<'_>) -> usize {
        self.sim.borrow(py).runner.world().bodies().len()
    }

    /// Global body ids (N,), ascending.
    #[getter]
    fn id<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let mut s = self.sim.borrow_mut(py);
        let order = s.bodies_sorted().to_vec();
        let b = &s.runner.world().bodies();
        column(py, &order, |i| b.id[i] as i64)
    }

    /// Template index of each body (N,).
    #[getter]
    fn template<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let mut s = self.sim.borrow_mut(py);
        let order = s.bodies_sorted().to_vec();
        let b = &s.runner.world().bodies();
        column(py, &order, |i| b.template[i] as i64)
    }

    /// Template name of each body.
    #[getter]
    fn template_name(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        let names: Vec<String> = self.sim.bind(py).getattr("template_names")?.extract()?;
        let mut s = self.sim.borrow_mut(py);
        let order = s.bodies_sorted().to_vec();
        let b = &s.runner.world().bodies();
        Ok(order
            .iter()
            .map(|&i| {
                names
                    .get(b.template[i] as usize)
                    .cloned()
                    .unwrap_or_default()
            })
            .collect())
    }

    /// Mass (N,), kg.
    #[getter]
    fn mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let mut s = self.sim.borrow_mut(py);
        let order = s.bodies_sorted().to_vec();
        let b = &s.runner.world().bodies();
        column(py, &order, |i| b.mass[i])
    }

    /// Temperature (N,), K. Settable (each > 0). Only with `[heat]`.
    #[getter]
    fn temperature<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.thermal(py, "temperature", |b| &b.temperature)
    }

    #[setter]
    fn set_temperature(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let above_zero = |r: usize, t: &[f64]| {
            if t[0] > 0.0 {
                Ok(())
            } else {
                Err(value_error(format!(
                    "temperature: row {r} is {} K; temperatures must be > 0 K",
                    t[0]
                )))
            }
        };
        set_column(
            py,
            &self.sim,
            value,
            "temperature",
            above_zero,
            |w, i, t| w.set_body_temperature_at(i, t),
        )
    }

    /// Heat source (N,), W. Settable. Only with `[heat]`.
    #[getter]
    fn heat_source<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.thermal(py, "heat_source", |b| &b.heat_source)
    }

    #[setter]
    fn set_heat_source(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        set_column(py, &self.sim, value, "heat_source", no_check, |w, i, q| {
            w.set_body_heat_source_at(i, q)
        })
    }

    /// Principal moments of inertia (N×3), body frame, kg m².
    #[getter]
    fn inertia<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.vectors(py, |b, i| b.inertia[i])
    }

    /// Total force, last force evaluation (N×3), world frame, N.
    #[getter]
    fn force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.vectors(py, |b, i| b.force[i])
    }

    /// Total torque about the centre of mass (N×3), world frame, N m.
    #[getter]
    fn torque<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.vectors(py, |b, i| b.torque[i])
    }

    /// Angular momentum about the centre of mass (N×3), world frame, kg m²/s.
    #[getter]
    fn angular_momentum<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.vectors(py, |b, i| b.angular_momentum[i])
    }

    /// Centre of mass (N×3), world frame, m. Settable.
    #[getter]
    fn position<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.vectors(py, |b, i| b.position[i])
    }

    #[setter]
    fn set_position(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        set_rows(py, &self.sim, value, 3, "position", no_check, |w, i, r| {
            w.set_body_position_at(i, v3(r))
        })
    }

    /// Centre-of-mass velocity (N×3), world frame, m/s. Settable.
    #[getter]
    fn velocity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.vectors(py, |b, i| b.velocity[i])
    }

    #[setter]
    fn set_velocity(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        set_rows(py, &self.sim, value, 3, "velocity", no_check, |w, i, r| {
            w.set_body_velocity_at(i, v3(r))
        })
    }

    /// Orientation (N×4: w, x, y, z), body → world. Settable (unit norm).
    #[getter]
    fn quaternion<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let mut s = self.sim.borrow_mut(py);
        let order = s.bodies_sorted().to_vec();
        let b = &s.runner.world().bodies();
        quats(py, &order, |i| b.orientation[i])
    }

    #[setter]
    fn set_quaternion(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let unit = |r: usize, q: &[f64]| {
            let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
            if (n - 1.0).abs() > UNIT_TOLERANCE {
                return Err(value_error(format!(
                    "quaternion: row {r} has norm {n}, not 1 (within {UNIT_TOLERANCE}); \
                     give unit quaternions (w, x, y, z)"
                )));
            }
            Ok(())
        };
        set_rows(py, &self.sim, value, 4, "quaternion", unit, |w, i, r| {
            let x = w.bodies().position[i];
            w.set_body_pose_at(i, x, DQuat::from_xyzw(r[1], r[2], r[3], r[0]))
        })
    }

    /// Angular velocity (N×3), world frame, rad/s. Settable.
    #[getter]
    fn omega<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.vectors(py, |b, i| b.angular_velocity[i])
    }

    #[setter]
    fn set_omega(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        set_rows(py, &self.sim, value, 3, "omega", no_check, |w, i, r| {
            w.set_body_angular_velocity_at(i, v3(r))
        })
    }

    /// Angular velocity (N×3), body frame, rad/s.
    #[getter]
    fn omega_body<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.vectors(py, |b, i| {
            b.orientation[i].inverse() * b.angular_velocity[i]
        })
    }

    /// Force flags per world axis (N×3, bool). Settable.
    #[getter]
    fn force_flag<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<bool>> {
        self.flags(py, |b, i| b.force_flag[i])
    }

    #[setter]
    fn set_force_flag(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        set_rows(
            py,
            &self.sim,
            value,
            3,
            "force_flag",
            flag_check,
            |w, i, r| {
                let t = w.bodies().torque_flag[i];
                w.set_body_dof_at(i, flags(r), t)
            },
        )
    }

    /// Torque flags per world axis (N×3, bool). Settable.
    #[getter]
    fn torque_flag<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<bool>> {
        self.flags(py, |b, i| b.torque_flag[i])
    }

    #[setter]
    fn set_torque_flag(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        set_rows(
            py,
            &self.sim,
            value,
            3,
            "torque_flag",
            flag_check,
            |w, i, r| {
                let f = w.bodies().force_flag[i];
                w.set_body_dof_at(i, f, flags(r))
            },
        )
    }
}

fn flag_check(r: usize, row: &[f64]) -> PyResult<()> {
    if row.iter().all(|&x| x == 0.0 || x == 1.0) {
        Ok(())
    } else {
        Err(value_error(format!(
            "flags: row {r} must hold booleans (0/1), got {row:?}"
        )))
    }
}

fn flags(r: &[f64]) -> [bool; 3] {
    [r[0] != 0.0, r[1] != 0.0, r[2] != 0.0]
}

impl Bodies {
    /// A heat array `f(bodies)` in id order; an error without `[heat]`.
    fn thermal<'py>(
        &self,
        py: Python<'py>,
        what: &str,
        f: impl Fn(&clump_core::body::Bodies) -> &Vec<f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let mut s = self.sim.borrow_mut(py);
        if s.runner.world().heat.is_none() {
            return Err(value_error(format!(
                "{what}: the scenario has no [heat], so the bodies have no {what}"
            )));
        }
        let order = s.bodies_sorted().to_vec();
        let v = f(s.runner.world().bodies());
        Ok(column(py, &order, |i| v[i]))
    }

    /// An N×3 array of `f(bodies, storage index)`, in id order.
    fn vectors<'py>(
        &self,
        py: Python<'py>,
        f: impl Fn(&clump_core::body::Bodies, usize) -> DVec3,
    ) -> Bound<'py, PyArray2<f64>> {
        let mut s = self.sim.borrow_mut(py);
        let order = s.bodies_sorted().to_vec();
        let b = &s.runner.world().bodies();
        vec3s(py, &order, |i| f(b, i))
    }

    fn flags<'py>(
        &self,
        py: Python<'py>,
        f: impl Fn(&clump_core::body::Bodies, usize) -> [bool; 3],
    ) -> Bound<'py, PyArray2<bool>> {
        let mut s = self.sim.borrow_mut(py);
        let order = s.bodies_sorted().to_vec();
        let b = &s.runner.world().bodies();
        let mut a = Array2::<bool>::from_elem((order.len(), 3), false);
        for (r, &i) in order.iter().enumerate() {
            let v = f(b, i);
            for c in 0..3 {
                a[[r, c]] = v[c];
            }
        }
        a.into_pyarray(py)
    }
}

/// The spheres of a simulation (read only).
#[pyclass(module = "clump._clump")]
pub struct Spheres {
    pub(crate) sim: Py<Simulation>,
}

#[pymethods]
impl Spheres {
    fn __len__(&self, py: Python<'_>) -> usize {
        self.sim.borrow(py).runner.world().spheres().len()
    }

    /// Global sphere ids (M,), ascending.
    #[getter]
    fn id<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let mut s = self.sim.borrow_mut(py);
        let order = s.spheres_sorted().to_vec();
        let sp = s.runner.world().spheres();
        column(py, &order, |i| sp.gid[i] as i64)
    }

    /// Sphere centres (M×3), world frame, m.
    #[getter]
    fn position<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let mut s = self.sim.borrow_mut(py);
        let order = s.spheres_sorted().to_vec();
        let sp = s.runner.world().spheres();
        vec3s(py, &order, |i| sp.position(i))
    }

    /// Radii (M,), m.
    #[getter]
    fn radius<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let mut s = self.sim.borrow_mut(py);
        let order = s.spheres_sorted().to_vec();
        let sp = s.runner.world().spheres();
        column(py, &order, |i| sp.radius[i])
    }

    /// Body id of each sphere (M,).
    #[getter]
    fn body<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let mut s = self.sim.borrow_mut(py);
        let order = s.spheres_sorted().to_vec();
        let sp = s.runner.world().spheres();
        column(py, &order, |i| (sp.gid[i] >> SPHERE_ID_BITS) as i64)
    }
}
