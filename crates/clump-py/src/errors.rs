//! The exceptions: `ScenarioError` (bad input, a `ValueError` with the
//! location of the first problem), `SimulationError` (a failure while
//! running), `UnstableError` (the run became unstable).

use clump_io::run::RunError;
use clump_io::scenario::{ScenarioError as ScenarioDiag, Source};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    clump,
    ScenarioError,
    PyValueError,
    "Bad input: a scenario, checkpoint or template that cannot be used. \
     The message is the CLI's; `.file`, `.line`, `.column` (1-based, or None) \
     and `.key` (dotted, e.g. 'simulation.dt', or None) locate the first problem."
);
pyo3::create_exception!(
    clump,
    SimulationError,
    PyRuntimeError,
    "A failure while running (I/O, the engine)."
);
pyo3::create_exception!(
    clump,
    UnstableError,
    SimulationError,
    "The simulation became unstable (NaN/Inf, excessive overlap, energy \
     blow-up); the message names the step, the bodies and the likely cause."
);

/// A `ScenarioError` with the given attributes.
pub fn scenario_error(
    py: Python<'_>,
    message: String,
    file: Option<String>,
    line: Option<usize>,
    column: Option<usize>,
    key: Option<String>,
) -> PyErr {
    let err = ScenarioError::new_err(message);
    let v = err.value(py);
    let set = |k: &str, o: PyObject| {
        let _ = v.setattr(k, o);
    };
    set(
        "file",
        file.into_pyobject(py)
            .map_or(py.None(), |o| o.into_any().unbind()),
    );
    set(
        "line",
        line.into_pyobject(py)
            .map_or(py.None(), |o| o.into_any().unbind()),
    );
    set(
        "column",
        column
            .into_pyobject(py)
            .map_or(py.None(), |o| o.into_any().unbind()),
    );
    set(
        "key",
        key.into_pyobject(py)
            .map_or(py.None(), |o| o.into_any().unbind()),
    );
    err
}

/// The dotted key on 1-based line `line` of `text` (`[simulation]` +
/// `dt` → `simulation.dt`).
fn key_at(file: &std::path::Path, text: &str, line: usize) -> Option<String> {
    let start: usize = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum();
    let rest = text.get(start..)?;
    // the end of the located line: `key_at` reads the key before its `=`
    // (or on the nearest line above, inside a multi-line value)
    let pos = start + rest.find('\n').unwrap_or(rest.len());
    let src = Source::new(file, text.to_string());
    let key = src.key_at(pos);
    let table = src
        .table_at(pos)
        .map(|t| t.trim_matches(|c| c == '[' || c == ']').trim().to_string());
    match (table, key) {
        (Some(t), Some(k)) => Some(format!("{t}.{k}")),
        (None, Some(k)) => Some(k),
        (Some(t), None) => Some(t),
        (None, None) => None,
    }
}

/// A scenario error as `ScenarioError`; `text` is the scenario text (for the key).
pub fn from_scenario(py: Python<'_>, e: &ScenarioDiag, text: Option<&str>) -> PyErr {
    let d = e.first();
    let (line, column) = d
        .location
        .as_ref()
        .map_or((None, None), |l| (Some(l.line), Some(l.column)));
    let key = match (text, line) {
        (Some(t), Some(l)) => key_at(&d.file, t, l),
        _ => None,
    };
    scenario_error(
        py,
        e.to_string(),
        Some(d.file.display().to_string()),
        line,
        column,
        key,
    )
}

/// A run error as the matching exception.
pub fn from_run(py: Python<'_>, e: RunError, text: Option<&str>) -> PyErr {
    match e {
        RunError::Input(s) => from_scenario(py, &s, text),
        RunError::InputMessage(m) => scenario_error(py, m, None, None, None, None),
        RunError::Runtime(m) => SimulationError::new_err(m),
        RunError::Unstable(u) => UnstableError::new_err(u.to_string()),
    }
}

/// A `ValueError` for a bad argument.
pub fn value_error(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(message.into())
}
