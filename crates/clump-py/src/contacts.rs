//! `sim.contacts()`: the contacts of the last step as a dict of arrays,
//! read from `World::contacts` (the forces the kernels summed, bit for bit).

use crate::errors::SimulationError;
use clump_core::recorded_contacts::Partner;
use clump_core::world::World;
use numpy::ndarray::Array2;
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;

pub fn contacts<'py>(py: Python<'py>, world: &World) -> PyResult<Bound<'py, PyDict>> {
    let it = world.contacts().map_err(|e| {
        SimulationError::new_err(format!(
            "{e}; Simulation.run and step record them at every boundary they return at \
             (none before the first step or after bodies were added)"
        ))
    })?;
    let list: Vec<_> = it.collect();
    let n = list.len();
    let mut sphere_i = Vec::with_capacity(n);
    let mut sphere_j = Vec::with_capacity(n);
    let mut body_i = Vec::with_capacity(n);
    let mut body_j = Vec::with_capacity(n);
    let mut wall = Vec::with_capacity(n);
    let mut overlap = Vec::with_capacity(n);
    let mut point = Array2::<f64>::zeros((n, 3));
    let mut normal = Array2::<f64>::zeros((n, 3));
    let mut fnorm = Array2::<f64>::zeros((n, 3));
    let mut ftan = Array2::<f64>::zeros((n, 3));
    for (k, c) in list.iter().enumerate() {
        sphere_i.push(c.sphere_id as i64);
        body_i.push(c.body_id as i64);
        match c.partner {
            Partner::Sphere { sphere_id, body_id } => {
                sphere_j.push(sphere_id as i64);
                body_j.push(body_id as i64);
                wall.push(-1i64);
            }
            Partner::Wall { wall: w, .. } => {
                sphere_j.push(-1);
                body_j.push(-1);
                wall.push(w as i64);
            }
        }
        overlap.push(c.overlap);
        for (a, v) in [
            (&mut point, c.point),
            (&mut normal, c.normal),
            (&mut fnorm, c.force_normal),
            (&mut ftan, c.force_tangential),
        ] {
            a[[k, 0]] = v.x;
            a[[k, 1]] = v.y;
            a[[k, 2]] = v.z;
        }
    }
    let d = PyDict::new(py);
    d.set_item("sphere_i", sphere_i.into_pyarray(py))?;
    d.set_item("sphere_j", sphere_j.into_pyarray(py))?;
    d.set_item("body_i", body_i.into_pyarray(py))?;
    d.set_item("body_j", body_j.into_pyarray(py))?;
    d.set_item("wall", wall.into_pyarray(py))?;
    d.set_item("point", point.into_pyarray(py))?;
    d.set_item("normal", normal.into_pyarray(py))?;
    d.set_item("overlap", overlap.into_pyarray(py))?;
    d.set_item("force_normal", fnorm.into_pyarray(py))?;
    d.set_item("force_tangential", ftan.into_pyarray(py))?;
    Ok(d)
}
