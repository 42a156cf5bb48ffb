//! The `ClumpSim` handle: making and freeing it, loading a scenario or a
//! checkpoint into it, stepping, scalar queries, the error message, and
//! the boundary guard every exported function runs through.

use crate::{
    CLUMP_ERR_NO_SIMULATION, CLUMP_ERR_NULL, CLUMP_ERR_PANIC, CLUMP_ERR_RUNTIME,
    CLUMP_ERR_SCENARIO, CLUMP_ERR_UNSTABLE, CLUMP_ERR_VALUE, CLUMP_OK,
};
use clump_io::run::{RunError, Runner, Tally, Until};
use std::ffi::{c_char, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;

/// A simulation driven from C (opaque): a scenario's run and the last
/// error message. Made by `clump_sim_new`, freed by `clump_sim_free`; one
/// thread at a time.
pub struct ClumpSim {
    pub(crate) run: Option<Run>,
    message: CString,
}

/// A loaded run: the runner and the session's step tally.
pub(crate) struct Run {
    pub(crate) runner: Runner,
    tally: Tally,
    /// Body storage indices in id order (refreshed on every read).
    pub(crate) body_order: Vec<usize>,
}

/// An error inside the API: a status code and its message.
pub(crate) struct Fail(pub(crate) i32, pub(crate) String);

impl Fail {
    pub(crate) fn value(m: impl Into<String>) -> Self {
        Fail(CLUMP_ERR_VALUE, m.into())
    }
}

fn from_run(e: RunError) -> Fail {
    let code = match &e {
        RunError::Input(_) | RunError::InputMessage(_) => CLUMP_ERR_SCENARIO,
        RunError::Runtime(_) => CLUMP_ERR_RUNTIME,
        RunError::Unstable(_) => CLUMP_ERR_UNSTABLE,
    };
    Fail(code, e.to_string())
}

/// Runs `f` on the handle behind `sim`, keeps the message of a failure
/// (or of a panic) in it, and returns the status code. The guard of every
/// exported function that takes a handle.
pub(crate) fn guard(sim: *mut ClumpSim, f: impl FnOnce(&mut ClumpSim) -> Result<(), Fail>) -> i32 {
    // SAFETY: a non-NULL handle comes from clump_sim_new and is used by one thread.
    let Some(h) = (unsafe { sim.as_mut() }) else {
        return CLUMP_ERR_NULL;
    };
    let r = catch_unwind(AssertUnwindSafe(|| f(h))).unwrap_or_else(|p| {
        let what = p
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| p.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into());
        Err(Fail(CLUMP_ERR_PANIC, format!("clump panicked: {what}")))
    });
    match r {
        Ok(()) => {
            h.message = CString::default();
            CLUMP_OK
        }
        Err(Fail(code, m)) => {
            h.message = CString::new(m.replace('\0', " ")).unwrap_or_default();
            code
        }
    }
}

/// Runs `f` on the loaded run of the handle (`CLUMP_ERR_NO_SIMULATION` without one).
pub(crate) fn with_run(sim: *mut ClumpSim, f: impl FnOnce(&mut Run) -> Result<(), Fail>) -> i32 {
    guard(sim, |h| match h.run.as_mut() {
        Some(r) => f(r),
        None => Err(Fail(
            CLUMP_ERR_NO_SIMULATION,
            "no simulation is loaded (clump_sim_load or clump_sim_resume first)".into(),
        )),
    })
}

/// `*out = v`, or `CLUMP_ERR_NULL` as a failure.
pub(crate) fn put<T>(out: *mut T, v: T) -> Result<(), Fail> {
    // SAFETY: a non-NULL `out` points to a writable T (the caller's contract).
    match unsafe { out.as_mut() } {
        Some(o) => {
            *o = v;
            Ok(())
        }
        None => Err(Fail(CLUMP_ERR_NULL, "output pointer is NULL".into())),
    }
}

fn path_arg(path: *const c_char) -> Result<PathBuf, Fail> {
    if path.is_null() {
        return Err(Fail(CLUMP_ERR_NULL, "path is NULL".into()));
    }
    // SAFETY: a non-NULL path is a NUL-terminated string (the caller's contract).
    let s = unsafe { CStr::from_ptr(path) };
    s.to_str()
        .map(PathBuf::from)
        .map_err(|_| Fail::value("path is not UTF-8"))
}

impl Run {
    /// The run of `runner` with the boundary work of its step done.
    fn start(mut runner: Runner) -> Result<Self, Fail> {
        let mut tally = Tally::start(&runner);
        let step = runner.world().step;
        runner
            .step_until(step, false, None, &mut tally)
            .map_err(from_run)?;
        ready(&mut runner)?;
        Ok(Run {
            runner,
            tally,
            body_order: Vec::new(),
        })
    }
}

/// The forces of the boundary evaluated where the next step would do it at
/// its start (`World::ready_forces`), so that loads the host sets now act
/// from the end of the next step at every boundary.
fn ready(runner: &mut Runner) -> Result<(), Fail> {
    if runner.finished() {
        return Ok(());
    }
    runner.world_mut().ready_forces().map_err(|e| {
        Fail(
            CLUMP_ERR_RUNTIME,
            format!("cannot evaluate the forces: {e}"),
        )
    })
}

/// A new handle holding no simulation (never NULL).
#[no_mangle]
pub extern "C" fn clump_sim_new() -> *mut ClumpSim {
    Box::into_raw(Box::new(ClumpSim {
        run: None,
        message: CString::default(),
    }))
}

/// Frees a handle and its simulation (NULL is ignored).
///
/// # Safety
/// `sim` is NULL or a handle from `clump_sim_new` not freed before.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_free(sim: *mut ClumpSim) {
    if !sim.is_null() {
        let _ = catch_unwind(AssertUnwindSafe(|| drop(Box::from_raw(sim))));
    }
}

/// Reads and validates the scenario TOML file at `path` (as `clump run`)
/// and loads its run into the handle, replacing any earlier one. Nothing
/// is written to disk (no output folder). `CLUMP_ERR_SCENARIO` with the
/// file, line and key of the first error.
///
/// # Safety
/// `sim` is a live handle; `path` a NUL-terminated UTF-8 string.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_load(sim: *mut ClumpSim, path: *const c_char) -> i32 {
    guard(sim, |h| {
        h.run = None;
        let sc = clump_io::scenario::load(&path_arg(path)?)
            .map_err(|e| Fail(CLUMP_ERR_SCENARIO, e.to_string()))?;
        h.run = Some(Run::start(Runner::detached(sc).map_err(from_run)?)?);
        Ok(())
    })
}

/// Loads the run saved in a checkpoint file (`clump_sim_save_checkpoint`
/// or `clump run`); it continues bit for bit.
///
/// # Safety
/// `sim` is a live handle; `path` a NUL-terminated UTF-8 string.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_resume(sim: *mut ClumpSim, path: *const c_char) -> i32 {
    guard(sim, |h| {
        h.run = None;
        let runner = Runner::detached_resume(&path_arg(path)?).map_err(from_run)?;
        h.run = Some(Run::start(runner)?);
        Ok(())
    })
}

/// Writes a checkpoint of the run to `path`.
///
/// # Safety
/// `sim` is a live handle; `path` a NUL-terminated UTF-8 string.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_save_checkpoint(sim: *mut ClumpSim, path: *const c_char) -> i32 {
    with_run(sim, |r| {
        let p = path_arg(path)?;
        r.runner.write_checkpoint_to(&p).map_err(from_run)
    })
}

/// Advances `steps` steps, or to the end of the scenario's stages (never
/// past it); `*taken` (may be NULL) receives the steps taken.
///
/// # Safety
/// `sim` is a live handle; `taken` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_step(sim: *mut ClumpSim, steps: u64, taken: *mut u64) -> i32 {
    with_run(sim, |r| {
        let start = r.runner.world().step;
        let target = start.saturating_add(steps);
        let res = r
            .runner
            .step_until(target, false, None, &mut r.tally)
            .map(|u| debug_assert!(u != Until::Paused));
        if !taken.is_null() {
            put(taken, r.runner.world().step - start)?;
        }
        res.map_err(from_run)?;
        ready(&mut r.runner)
    })
}

/// Writes simulated time (s), the step count and the time step (s); any
/// pointer may be NULL.
///
/// # Safety
/// `sim` is a live handle; each pointer NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_clock(
    sim: *mut ClumpSim,
    time: *mut f64,
    step: *mut u64,
    dt: *mut f64,
) -> i32 {
    with_run(sim, |r| {
        let w = r.runner.world();
        if !time.is_null() {
            put(time, w.time)?;
        }
        if !step.is_null() {
            put(step, w.step)?;
        }
        if !dt.is_null() {
            put(dt, w.config.dt)?;
        }
        Ok(())
    })
}

/// Writes 1 to `*finished` once all stages are done, else 0.
///
/// # Safety
/// `sim` is a live handle; `finished` writable.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_finished(sim: *mut ClumpSim, finished: *mut i32) -> i32 {
    with_run(sim, |r| put(finished, i32::from(r.runner.finished())))
}

/// The message of the last failed call on `sim` ("" after a success),
/// valid until the next call on it. NULL for a NULL handle.
///
/// # Safety
/// `sim` is NULL or a live handle.
#[no_mangle]
pub unsafe extern "C" fn clump_sim_error_message(sim: *const ClumpSim) -> *const c_char {
    match sim.as_ref() {
        Some(h) => h.message.as_ptr(),
        None => std::ptr::null(),
    }
}

/// A static name of a status code ("CLUMP_OK", "CLUMP_ERR_VALUE", …).
#[no_mangle]
pub extern "C" fn clump_status_name(status: i32) -> *const c_char {
    let s: &'static CStr = match status {
        CLUMP_OK => c"CLUMP_OK",
        CLUMP_ERR_NULL => c"CLUMP_ERR_NULL",
        CLUMP_ERR_SCENARIO => c"CLUMP_ERR_SCENARIO",
        CLUMP_ERR_VALUE => c"CLUMP_ERR_VALUE",
        CLUMP_ERR_RUNTIME => c"CLUMP_ERR_RUNTIME",
        CLUMP_ERR_UNSTABLE => c"CLUMP_ERR_UNSTABLE",
        CLUMP_ERR_NO_SIMULATION => c"CLUMP_ERR_NO_SIMULATION",
        CLUMP_ERR_PANIC => c"CLUMP_ERR_PANIC",
        _ => c"unknown status",
    };
    s.as_ptr()
}

/// The version of Clump (a static string).
#[no_mangle]
pub extern "C" fn clump_version() -> *const c_char {
    static V: std::sync::OnceLock<CString> = std::sync::OnceLock::new();
    V.get_or_init(|| CString::new(clump_io::run::VERSION).unwrap_or_default())
        .as_ptr()
}
