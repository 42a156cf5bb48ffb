//! `Simulation.from_dict`: a dict shaped like the scenario TOML, written
//! as TOML text and then read exactly as a file (same validation, same
//! messages; lines refer to that text, `.key` names the key).

use crate::errors::scenario_error;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// The TOML text of `d`.
pub fn to_toml(d: &Bound<'_, PyDict>) -> PyResult<String> {
    let table = table(d, "")?;
    toml::to_string(&table)
        .map_err(|e| bad(d.py(), "", format!("cannot write the dict as TOML: {e}")))
}

fn bad(py: Python<'_>, key: &str, message: String) -> PyErr {
    let key = (!key.is_empty()).then(|| key.to_string());
    scenario_error(py, message, Some("<dict>".into()), None, None, key)
}

fn table(d: &Bound<'_, PyDict>, path: &str) -> PyResult<toml::Table> {
    let mut t = toml::Table::new();
    for (k, v) in d.iter() {
        let k: String = k.extract().map_err(|_| {
            bad(
                d.py(),
                path,
                format!("keys must be strings, found {k:?} in '{path}'"),
            )
        })?;
        let p = if path.is_empty() {
            k.clone()
        } else {
            format!("{path}.{k}")
        };
        t.insert(k, value(&v, &p)?);
    }
    Ok(t)
}

fn value(v: &Bound<'_, PyAny>, path: &str) -> PyResult<toml::Value> {
    let py = v.py();
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Integer(v.extract().map_err(|_| {
            bad(py, path, format!("'{path}': integer out of range"))
        })?));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(v.extract()?));
    }
    if let Ok(d) = v.downcast::<PyDict>() {
        return Ok(toml::Value::Table(table(d, path)?));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() || v.hasattr("tolist")? {
        // numpy arrays and scalars: through their Python values
        let v = if v.hasattr("tolist")? {
            v.call_method0("tolist")?
        } else {
            v.clone()
        };
        if !(v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>()) {
            return value(&v, path);
        }
        let mut out = Vec::new();
        for (i, x) in v.try_iter()?.enumerate() {
            out.push(value(&x?, &format!("{path}[{i}]"))?);
        }
        return Ok(toml::Value::Array(out));
    }
    Err(bad(
        py,
        path,
        format!(
            "'{path}': cannot be written as TOML (a {}); use numbers, strings, booleans, lists and dicts",
            v.get_type().name()?
        ),
    ))
}
