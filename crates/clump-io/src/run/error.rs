//! Why a run failed: bad input, a runtime failure, or an instability with
//! its diagnosis (step, bodies, likely cause, last good outputs).

use super::{RunSummary, Runner};
use crate::scenario::ScenarioError;
use clump_core::health::Instability;
use std::fmt;
use std::path::PathBuf;

/// Why a run failed.
#[derive(Debug)]
pub enum RunError {
    /// Bad input (scenario, checkpoint that does not fit): exit status 2.
    Input(ScenarioError),
    /// Bad input without a scenario location (e.g. an unreadable checkpoint).
    InputMessage(String),
    /// Failure while running (I/O, engine): exit status 1.
    Runtime(String),
    /// The simulation became unstable (NaN/Inf state, excessive overlap,
    /// kinetic-energy blow-up); the message names the step, the bodies, the
    /// likely cause and the last good checkpoint and output. Exit status 1.
    Unstable(Box<UnstableRun>),
}

/// An instability that stopped a run, with what is needed to report it.
#[derive(Debug, Clone)]
pub struct UnstableRun {
    /// What was detected.
    pub instability: Instability,
    /// The likely cause, with a remedy.
    pub cause: String,
    /// Where the time step is set in the scenario (`file:line`, key).
    pub dt_location: String,
    /// The last checkpoint written before the instability (a good state),
    /// with its step.
    pub last_checkpoint: Option<(PathBuf, u64)>,
    /// The output directory.
    pub outdir: PathBuf,
    /// Step of the last thermo row written (a good state).
    pub last_thermo: Option<u64>,
    /// Step of the last VTK frame written (a good state).
    pub last_vtk: Option<u64>,
}

impl fmt::Display for UnstableRun {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let i = &self.instability;
        writeln!(f, "error: the simulation became unstable {i}")?;
        let ids: Vec<String> = i.bodies().iter().map(|b| b.to_string()).collect();
        if !ids.is_empty() {
            writeln!(f, "  bodies involved: {}", ids.join(", "))?;
        }
        writeln!(f, "  likely cause: {}", self.cause)?;
        writeln!(f, "  time step: {}", self.dt_location)?;
        match &self.last_checkpoint {
            Some((p, step)) => writeln!(
                f,
                "  last good checkpoint: {} (step {step}; `clump resume {}` continues from it)",
                p.display(),
                p.display()
            )?,
            None => writeln!(
                f,
                "  last good checkpoint: none was written (add [output] checkpoint = {{ every_steps = N }})"
            )?,
        }
        let step = |s: Option<u64>| s.map_or_else(|| "none".to_string(), |s| format!("step {s}"));
        writeln!(
            f,
            "  last good output in {}: thermo.csv up to {}, VTK frames up to {}",
            self.outdir.display(),
            step(self.last_thermo),
            step(self.last_vtk)
        )?;
        write!(
            f,
            "  = note: the unstable state was not written: no checkpoint or output was overwritten"
        )
    }
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RunError::Input(e) => write!(f, "{e}"),
            RunError::InputMessage(m) => write!(f, "error: {m}"),
            RunError::Runtime(m) => write!(f, "error: {m}"),
            RunError::Unstable(u) => write!(f, "{u}"),
        }
    }
}

impl std::error::Error for RunError {}

impl RunError {
    /// True for bad input (exit status 2).
    pub fn is_input(&self) -> bool {
        !matches!(self, RunError::Runtime(_) | RunError::Unstable(_))
    }
}

/// Maps an error to a runtime failure, prefixed with `what`.
pub(super) fn rt<E: fmt::Display>(what: &str) -> impl FnOnce(E) -> RunError + '_ {
    move |e| RunError::Runtime(format!("{what}: {e}"))
}

impl Runner {
    /// Stops a run at an instability: keeps every output and checkpoint as
    /// they are (the thermo and trajectory files are flushed row by row; the
    /// bad state is not written anywhere), records the status in the
    /// manifest and returns the report.
    pub(super) fn unstable(
        &mut self,
        inst: Instability,
        summary: &RunSummary,
        threads: usize,
    ) -> RunError {
        use crate::scenario::Seg::K;
        let since = self
            .st
            .last_insert_step
            .map(|s| self.world.step.saturating_sub(s));
        let cause = self.world.diagnose(&inst, since);
        tracing::error!(step = inst.step, "unstable: {inst}");
        let src = crate::scenario::Source::new(&self.scenario.path, self.scenario.text.clone());
        let path = self.scenario.path.display();
        let dt = self.world.config.dt;
        let at = |k: &str| {
            let p = [K("simulation"), K(k)];
            src.has(&p).then(|| src.error_at(&p, "").line()).flatten()
        };
        let dt_location = match (at("dt"), at("dt_fraction")) {
            (Some(l), _) => format!("dt = {dt:e} s is set at {path}:{l} ([simulation] dt)"),
            (None, Some(l)) => {
                format!("dt = {dt:e} s follows from {path}:{l} ([simulation] dt_fraction)")
            }
            _ => format!("dt = {dt:e} s (dt = \"auto\"; set [simulation] dt in {path})"),
        };
        let last_checkpoint = self.out.last_checkpoint.clone().map(|p| {
            let step = p
                .file_stem()
                .and_then(|s| s.to_str())
                .and_then(|s| s.strip_prefix("checkpoint_"))
                .and_then(|s| s.parse::<u64>().ok())
                .unwrap_or(0);
            (p, step)
        });
        let report = UnstableRun {
            instability: inst,
            cause,
            dt_location,
            last_checkpoint,
            outdir: self.out.dir.clone(),
            last_thermo: self.st.last_thermo,
            last_vtk: self.st.last_vtk,
        };
        let status = format!("unstable at step {}", report.instability.step);
        if let Err(e) = self.write_manifest_status(summary, threads, &status) {
            tracing::warn!("cannot write manifest.json: {e}");
        }
        RunError::Unstable(Box::new(report))
    }
}
