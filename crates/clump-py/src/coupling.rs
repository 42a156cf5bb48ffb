//! `sim.coupling`: what a fluid solver (or any driver) exchanges with the
//! run between steps, as numpy arrays in body-id order (the order of
//! `sim.bodies`): external forces and torques (persistent or for the next
//! step), the fluid velocity and void fraction at each body, the fluid
//! force of the last step, the void fraction on a grid; and fields on
//! grids a CFD code computed (the fluid velocity at the nodes of a regular
//! grid, a void fraction per cell), read at each body. It goes through
//! the engine's coupling methods (`clump_core::couple`), which check every
//! array before anything changes.

use crate::arrays::{rows_in, vec3_in, vec3s};
use crate::errors::{value_error, SimulationError};
use crate::simulation::Simulation;
use clump_core::fluid::void::{VoidField, VoidGrid};
use clump_core::fluid::VelocityGrid;
use clump_core::world::{World, WorldError};
use glam::DVec3;
use numpy::ndarray::Array3;
use numpy::{AllowTypeChange, IntoPyArray, PyArray2, PyArray3, PyArrayLikeDyn};
use std::sync::Arc;
use pyo3::prelude::*;

/// The coupling arrays of a simulation (see the stub for units and timing).
#[pyclass(module = "clump._clump")]
pub struct Coupling {
    pub(crate) sim: Py<Simulation>,
}

fn engine_error(what: &str) -> impl FnOnce(WorldError) -> PyErr + '_ {
    move |e| value_error(format!("{what}: {e}"))
}

/// Rows given in id order, as storage-order vectors.
fn storage_vectors(order: &[usize], rows: &[f64]) -> Vec<DVec3> {
    let mut out = vec![DVec3::ZERO; order.len()];
    for (k, &i) in order.iter().enumerate() {
        out[i] = DVec3::from_slice(&rows[3 * k..3 * k + 3]);
    }
    out
}

/// An array of `ndim` dimensions (any array-like of finite numbers), its
/// shape and its values in the order x fastest (index [i, j, k, …] of an
/// (n0, n1, n2, …) array at `i + n0 (j + n1 k)`, the trailing axis of a
/// vector field innermost).
fn grid_values(value: &Bound<'_, PyAny>, ndim: usize, what: &str) -> PyResult<(Vec<usize>, Vec<f64>)> {
    let shape_text = if ndim == 4 { "(n0, n1, n2, 3)" } else { "(n0, n1, n2)" };
    let arr: PyArrayLikeDyn<f64, AllowTypeChange> = value
        .extract()
        .map_err(|_| value_error(format!("{what} must be an array of numbers of shape {shape_text}")))?;
    let a = arr.as_array();
    let shape = a.shape().to_vec();
    if shape.len() != ndim || (ndim == 4 && shape[3] != 3) || shape.contains(&0) {
        return Err(value_error(format!("{what} must have shape {shape_text}, got {shape:?}")));
    }
    let mut out = Vec::with_capacity(a.len());
    for k in 0..shape[2] {
        for j in 0..shape[1] {
            for i in 0..shape[0] {
                if ndim == 4 {
                    out.extend((0..3).map(|c| a[[i, j, k, c].as_slice()]));
                } else {
                    out.push(a[[i, j, k].as_slice()]);
                }
            }
        }
    }
    if let Some(p) = out.iter().position(|x| !x.is_finite()) {
        return Err(value_error(format!("{what}: value {p} is not finite ({})", out[p])));
    }
    Ok((shape, out))
}

impl Coupling {
    /// Runs `f` on the world with the body order, after the forces of the
    /// boundary are evaluated where the next step would do it at its start
    /// (`World::ready_forces`), so that what is set acts from the end of
    /// the next step at every boundary.
    fn with_world<T>(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&mut World, &[usize]) -> PyResult<T>,
    ) -> PyResult<T> {
        let mut s = self.sim.borrow_mut(py);
        // first: evaluating the forces may re-sort the bodies
        s.runner
            .world_mut()
            .ready_forces()
            .map_err(|e| SimulationError::new_err(format!("cannot evaluate the forces: {e}")))?;
        let order = s.bodies_sorted().to_vec();
        f(s.runner.world_mut(), &order)
    }
}

#[pymethods]
impl Coupling {
    /// Sets the external force (N×3, N) and torque about the centre of
    /// mass (N×3, N m; None: zero) of every body, id order, world frame;
    /// `persistent`: they act at every step until set again, else in the
    /// next step only (on top of the persistent ones).
    #[pyo3(signature = (force, torque=None, persistent=true))]
    fn set_external_loads(
        &self,
        py: Python<'_>,
        force: &Bound<'_, PyAny>,
        torque: Option<&Bound<'_, PyAny>>,
        persistent: bool,
    ) -> PyResult<()> {
        self.with_world(py, |w, order| {
            let n = order.len();
            let f = storage_vectors(order, &rows_in(force, n, 3, "force")?);
            let t = match torque {
                Some(t) => storage_vectors(order, &rows_in(t, n, 3, "torque")?),
                None => vec![DVec3::ZERO; n],
            };
            if persistent {
                w.set_external_loads(&f, &t)
            } else {
                w.set_next_step_loads(&f, &t)
            }
            .map_err(engine_error("external loads"))
        })
    }

    /// Sets the fluid velocity (m/s, world frame): a 3-vector sets the
    /// uniform `[fluid] velocity`, an N×3 array the interstitial velocity
    /// at each body (id order), which the drag then uses instead.
    fn set_fluid_velocity(&self, py: Python<'_>, velocity: &Bound<'_, PyAny>) -> PyResult<()> {
        self.with_world(py, |w, order| {
            // a 1-D sequence of 3 numbers: the uniform velocity (an N×3
            // array never reads as one, whatever N)
            if let Ok(u) = vec3_in(velocity, "fluid velocity") {
                return w
                    .set_fluid_velocity(u)
                    .map_err(engine_error("fluid velocity"));
            }
            let u = storage_vectors(order, &rows_in(velocity, order.len(), 3, "fluid velocity")?);
            w.set_body_fluid_velocities(&u)
                .map_err(engine_error("fluid velocity"))
        })
    }

    /// Sets the void fraction at each body (N values in (0, 1], id order);
    /// the hindered drag laws (di_felice, beetstra, gidaspow) read it.
    fn set_void_fractions(&self, py: Python<'_>, eps: &Bound<'_, PyAny>) -> PyResult<()> {
        self.with_world(py, |w, order| {
            let np = py.import("numpy")?;
            let col = np
                .call_method1("asarray", (eps, "float64"))
                .and_then(|a| a.call_method1("reshape", ((-1i64, 1i64),)))
                .map_err(|_| {
                    value_error("void fractions must be a sequence of numbers, one per body")
                })?;
            let e = rows_in(&col, order.len(), 1, "void fractions")?;
            let mut stored = vec![1.0; order.len()];
            for (&v, &i) in e.iter().zip(order) {
                stored[i] = v;
            }
            w.set_body_void_fractions(&stored)
                .map_err(engine_error("void fractions"))
        })
    }

    /// Sets the fluid velocity field on a regular grid of nodes: node
    /// [i, j, k] of `velocity` (an (n0, n1, n2, 3) array, m/s, world frame)
    /// at `origin + (i, j, k) * spacing` (m). Each step a body without a
    /// per-body velocity gets the trilinear interpolation at its centre of
    /// mass (outside the grid, the value at its nearest point). None
    /// removes the grid. Needs a `[fluid]`; not kept in checkpoints.
    #[pyo3(signature = (origin, spacing, velocity))]
    fn set_fluid_velocity_grid(
        &self,
        py: Python<'_>,
        origin: &Bound<'_, PyAny>,
        spacing: &Bound<'_, PyAny>,
        velocity: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let grid = match velocity {
            None => None,
            Some(v) => {
                let o = vec3_in(origin, "origin")?;
                let h = vec3_in(spacing, "spacing")?;
                let (shape, vals) = grid_values(v, 4, "velocity")?;
                let u = vals.chunks_exact(3).map(DVec3::from_slice).collect();
                let g = VelocityGrid::regular(o, h, [shape[0], shape[1], shape[2]], u)
                    .map_err(|e| value_error(format!("velocity grid: {e}")))?;
                Some(Arc::new(g))
            }
        };
        self.with_world(py, |w, _| {
            w.set_fluid_velocity_grid(grid)
                .map_err(engine_error("velocity grid"))
        })
    }

    /// Sets a void-fraction field computed by a CFD code: `eps` an (n0,
    /// n1, n2) array of values in (0, 1], cell [i, j, k] of edges `cell`
    /// (m) from the corner `lo` (m, world frame), as `void_fraction` lays
    /// them out. Each step a body without a per-body void fraction takes
    /// the value of the cell holding its centre of mass (1 outside the
    /// grid). None removes the field. Needs a `[fluid]`; not kept in checkpoints.
    #[pyo3(signature = (lo, cell, eps))]
    fn set_void_fraction_field(
        &self,
        py: Python<'_>,
        lo: &Bound<'_, PyAny>,
        cell: &Bound<'_, PyAny>,
        eps: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let field = match eps {
            None => None,
            Some(e) => {
                let (shape, vals) = grid_values(e, 3, "void fractions")?;
                let grid = VoidGrid {
                    lo: vec3_in(lo, "lo")?,
                    cell: vec3_in(cell, "cell")?,
                    n: [shape[0], shape[1], shape[2]],
                    periodic: [false; 3],
                };
                let f = VoidField::new(grid, vals)
                    .map_err(|e| value_error(format!("void-fraction field: {e}")))?;
                Some(Arc::new(f))
            }
        };
        self.with_world(py, |w, _| {
            w.set_void_fraction_field(field)
                .map_err(engine_error("void-fraction field"))
        })
    }

    /// Removes every external load and per-body fluid velocity and void fraction.
    fn clear(&self, py: Python<'_>) {
        self.sim
            .borrow_mut(py)
            .runner
            .world_mut()
            .clear_coupling_arrays();
    }

    /// The fluid force of the last step on each body (N×3, N, world frame,
    /// id order): drag, buoyancy and pressure gradient; zeros without a fluid.
    #[getter]
    fn fluid_force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let mut s = self.sim.borrow_mut(py);
        let order = s.bodies_sorted().to_vec();
        let f = s.runner.world().fluid_forces();
        vec3s(py, &order, |i| f.get(i).copied().unwrap_or(DVec3::ZERO))
    }

    /// The void fraction of every cell of a grid of `n` = (n0, n1, n2)
    /// cells of edges `cell` (m) from the corner `lo` (m, world frame), as
    /// an (n0, n1, n2) array indexed [i, j, k], from the bodies as they
    /// are (theory T-69). Not clamped: overlapping bodies can make a cell
    /// overfull (below 0). `periodic` per axis: the solid beyond the grid
    /// wraps into it (for a grid spanning a periodic axis of the domain).
    #[pyo3(signature = (lo, cell, n, periodic=(false, false, false)))]
    fn void_fraction<'py>(
        &self,
        py: Python<'py>,
        lo: &Bound<'_, PyAny>,
        cell: &Bound<'_, PyAny>,
        n: (usize, usize, usize),
        periodic: (bool, bool, bool),
    ) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let lo = vec3_in(lo, "lo")?;
        let cell = vec3_in(cell, "cell")?;
        let n = [n.0, n.1, n.2];
        if cell.min_element() <= 0.0 || n.contains(&0) {
            return Err(value_error(format!(
                "grid cells must have positive edges and counts, got {cell} m and {n:?}"
            )));
        }
        let grid = VoidGrid {
            lo,
            cell,
            n,
            periodic: [periodic.0, periodic.1, periodic.2],
        };
        let mut v = Vec::new();
        self.sim
            .borrow_mut(py)
            .runner
            .world_mut()
            .void_fraction(&grid, &mut v);
        let mut a = Array3::<f64>::zeros((n[0], n[1], n[2]));
        for ((i, j, k), x) in a.indexed_iter_mut() {
            *x = v[i + n[0] * (j + n[1] * k)];
        }
        Ok(a.into_pyarray(py))
    }
}
