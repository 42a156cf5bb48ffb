//! numpy conversions: state arrays out (always fresh copies, in the order
//! the caller gives), validated arrays in.

use crate::errors::value_error;
use glam::{DQuat, DVec3};
use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, IntoPyArray, PyArray1, PyArray2, PyArrayLike2};
use pyo3::prelude::*;

/// An N×3 array of `f(k)` for `k` in `order`.
pub fn vec3s<'py>(
    py: Python<'py>,
    order: &[usize],
    f: impl Fn(usize) -> DVec3,
) -> Bound<'py, PyArray2<f64>> {
    let mut a = Array2::<f64>::zeros((order.len(), 3));
    for (r, &i) in order.iter().enumerate() {
        let v = f(i);
        a[[r, 0]] = v.x;
        a[[r, 1]] = v.y;
        a[[r, 2]] = v.z;
    }
    a.into_pyarray(py)
}

/// An N×4 array of quaternions (w, x, y, z).
pub fn quats<'py>(
    py: Python<'py>,
    order: &[usize],
    f: impl Fn(usize) -> DQuat,
) -> Bound<'py, PyArray2<f64>> {
    let mut a = Array2::<f64>::zeros((order.len(), 4));
    for (r, &i) in order.iter().enumerate() {
        let q = f(i);
        a[[r, 0]] = q.w;
        a[[r, 1]] = q.x;
        a[[r, 2]] = q.y;
        a[[r, 3]] = q.z;
    }
    a.into_pyarray(py)
}

/// A 1-D array of `f(k)` for `k` in `order`.
pub fn column<'py, T: numpy::Element>(
    py: Python<'py>,
    order: &[usize],
    f: impl Fn(usize) -> T,
) -> Bound<'py, PyArray1<T>> {
    order
        .iter()
        .map(|&i| f(i))
        .collect::<Vec<T>>()
        .into_pyarray(py)
}

/// Reads an `n`×`width` float array (any array-like) into one row-major
/// vector, refusing other shapes and non-finite values; `what` names it in
/// messages.
pub fn rows_in(value: &Bound<'_, PyAny>, n: usize, width: usize, what: &str) -> PyResult<Vec<f64>> {
    let arr: PyArrayLike2<f64, AllowTypeChange> = value.extract().map_err(|_| {
        value_error(format!(
            "{what} must be a 2-D array of numbers of shape ({n}, {width})"
        ))
    })?;
    let a = arr.as_array();
    if a.shape() != [n, width] {
        return Err(value_error(format!(
            "{what} must have shape ({n}, {width}), got {:?}",
            a.shape()
        )));
    }
    let out: Vec<f64> = a.iter().copied().collect();
    if let Some(k) = out.iter().position(|x| !x.is_finite()) {
        return Err(value_error(format!(
            "{what}: row {} holds a non-finite value ({}); values must be finite",
            k / width,
            out[k]
        )));
    }
    Ok(out)
}

/// Reads a 3-vector (any sequence of 3 finite numbers).
pub fn vec3_in(value: &Bound<'_, PyAny>, what: &str) -> PyResult<DVec3> {
    let v: Vec<f64> = value
        .extract()
        .map_err(|_| value_error(format!("{what} must be a sequence of 3 numbers")))?;
    if v.len() != 3 {
        return Err(value_error(format!(
            "{what} must have 3 components, got {}",
            v.len()
        )));
    }
    let v = DVec3::new(v[0], v[1], v[2]);
    if !v.is_finite() {
        return Err(value_error(format!("{what} must be finite, got {v}")));
    }
    Ok(v)
}

/// A 3-vector as a numpy array.
pub fn vec3_out(py: Python<'_>, v: DVec3) -> Bound<'_, PyArray1<f64>> {
    v.to_array().to_vec().into_pyarray(py)
}

/// Largest accepted deviation of a quaternion's norm from 1 (a float32
/// round trip stays inside it; a typo does not).
pub const UNIT_TOLERANCE: f64 = 1e-6;
