//! Checkpoints of a run: what they hold ([`Checkpoint`]), writing one from
//! a [`Runner`], and rebuilding the simulation from one.

use super::error::rt;
use super::{DriverState, RunError, Runner, VERSION};
use crate::checkpoint::write_checkpoint;
use crate::scenario::{self, Files, Scenario};
use clump_core::shape::ClumpTemplate;
use clump_core::state::WorldState;
use clump_core::world::World;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Everything in a checkpoint file (stored as JSON inside the binary
/// container of [`crate::checkpoint`], so that tagged enums round-trip; f64
/// values are written in shortest round-trip form and read back exactly).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Checkpoint {
    /// Clump version that wrote it.
    pub version: String,
    /// The scenario file as given when the run started.
    pub scenario_path: String,
    /// The scenario text.
    pub scenario_text: String,
    /// Files the scenario refers to, keyed as written in the scenario.
    pub files: BTreeMap<String, Vec<u8>>,
    /// Output directory of the run.
    pub outdir: String,
    /// Templates added during the run (scaled copies), with their material.
    pub extra_templates: Vec<(ClumpTemplate, u16)>,
    /// The driver state.
    pub driver: DriverState,
    /// The world state.
    pub world: WorldState,
    /// Id of the run (see [`super::outdir`]; absent in older checkpoints).
    #[serde(default)]
    pub run_id: Option<String>,
    /// A checkpoint of a world split over MPI ranks: the pieces holding
    /// its bodies, one per rank (`world` then holds none; see
    /// [`super::pieces`]). `None`: `world` is the whole world.
    #[serde(default)]
    pub pieces: Option<Vec<super::pieces::PieceRef>>,
}
impl Runner {
    /// Writes a checkpoint of the current state into the output directory
    /// (`checkpoint_<step>.ckpt`); returns its path.
    pub fn write_checkpoint(&mut self) -> Result<PathBuf, RunError> {
        let path = self
            .out
            .dir
            .join(format!("checkpoint_{:09}.ckpt", self.world.step));
        self.write_checkpoint_to(&path)?;
        self.out.last_checkpoint = Some(path.clone());
        Ok(path)
    }

    /// Writes a checkpoint of the current state to `path` (any file; the
    /// output directory's checkpoints go through [`Runner::write_checkpoint`]).
    /// `clump resume` and [`Runner::resume`] continue from it bit for bit.
    pub fn write_checkpoint_to(&mut self, path: &Path) -> Result<(), RunError> {
        if self.world.is_split() {
            return self.write_split_checkpoint(path);
        }
        let world = self
            .world
            .save_state()
            .map_err(rt("cannot capture the state"))?;
        let run_id = (!self.out.run_id.is_empty()).then(|| self.out.run_id.clone());
        let ck = self.checkpoint_of(world, run_id);
        let json = serde_json::to_string(&ck).map_err(rt("cannot encode the checkpoint"))?;
        write_checkpoint(path, &json, self.scenario.fingerprint())
            .map_err(rt("cannot write the checkpoint"))?;
        tracing::info!(
            step = self.world.step,
            "checkpoint written to {}",
            path.display()
        );
        Ok(())
    }

    /// The checkpoint of this run with the world state `world`.
    pub(super) fn checkpoint_of(&self, world: WorldState, run_id: Option<String>) -> Checkpoint {
        let extra: Vec<(ClumpTemplate, u16)> = (self.n_scenario_templates
            ..self.world.templates.len())
            .map(|i| {
                (
                    self.world.templates[i].clone(),
                    self.world.templates.material(i),
                )
            })
            .collect();
        Checkpoint {
            version: VERSION.to_string(),
            scenario_path: self.scenario.path.display().to_string(),
            scenario_text: self.scenario.text.clone(),
            files: self.scenario.files.clone(),
            outdir: self.out.dir.display().to_string(),
            extra_templates: extra,
            driver: self.st.clone(),
            world,
            run_id,
            pieces: None,
        }
    }
}

/// Decodes checkpoint file bytes (`path` for messages) and rebuilds the
/// simulation they hold: the scenario, the world with its restored state,
/// and the driver state ([`load_checkpoint_with_id`] without the run id).
pub fn load_checkpoint(
    bytes: &[u8],
    checkpoint: &Path,
) -> Result<(Scenario, World, DriverState), RunError> {
    load_checkpoint_with_id(bytes, checkpoint).map(|(s, w, d, _)| (s, w, d))
}

/// Decodes checkpoint file bytes (`path` for messages) and rebuilds the
/// simulation they hold: the scenario (from the stored text and files), the
/// world with its restored state, and the driver state. Never panics on
/// bad bytes: every problem is an input error. Also returns the run id
/// stored in the checkpoint.
pub fn load_checkpoint_with_id(
    bytes: &[u8],
    checkpoint: &Path,
) -> Result<(Scenario, World, DriverState, Option<String>), RunError> {
    let (scenario, mut world, driver, run_id, pending) = load_manifest(bytes, checkpoint)?;
    if let Some(p) = pending {
        super::pieces::read_share(&mut world, &p)?;
    }
    Ok((scenario, world, driver, run_id))
}

/// What [`load_manifest`] gives: the scenario, the world, the driver state,
/// the run id, and the pieces still to read.
pub(super) type Manifest = (
    Scenario,
    World,
    DriverState,
    Option<String>,
    Option<super::pieces::Pending>,
);

/// [`load_checkpoint_with_id`] but for the pieces of a checkpoint in
/// pieces: the world then holds the manifest's global part (no bodies),
/// and the pieces are returned unread, for [`super::pieces::read_share`].
pub(super) fn load_manifest(bytes: &[u8], checkpoint: &Path) -> Result<Manifest, RunError> {
    let (json, fingerprint): (String, u64) =
        crate::checkpoint::decode_checkpoint(bytes, checkpoint)
            .map_err(|e| RunError::InputMessage(e.to_string()))?;
    let mut ck: Checkpoint = serde_json::from_str(&json).map_err(|e| {
        RunError::InputMessage(format!(
            "checkpoint {}: cannot decode the state: {e}",
            checkpoint.display()
        ))
    })?;
    drop(json);
    let scenario = scenario::parse(
        Path::new(&ck.scenario_path),
        ck.scenario_text.clone(),
        Files::embedded(ck.files.clone()),
    )
    .map_err(RunError::Input)?;
    if scenario.fingerprint() != fingerprint {
        return Err(RunError::InputMessage(format!(
                "checkpoint {}: its scenario fingerprint {fingerprint:016x} does not match the stored scenario ({:016x})",
                checkpoint.display(),
                scenario.fingerprint()
            )));
    }
    let mut world = scenario
        .build_world()
        .map_err(|e| RunError::InputMessage(format!("cannot set up the simulation: {e}")))?;
    for (t, m) in &ck.extra_templates {
        world
            .add_template(t.clone(), *m)
            .map_err(|e| RunError::InputMessage(e.to_string()))?;
    }
    let n_ins = scenario.inserts.len();
    let d = &ck.driver;
    if d.streams.len() != n_ins || d.inserted.len() != n_ins || d.stage > scenario.stages.len() {
        return Err(RunError::InputMessage(format!(
            "checkpoint {}: its driver state does not fit its scenario ({n_ins} insertions, {} stages)",
            checkpoint.display(),
            scenario.stages.len()
        )));
    }
    let pending = ck.pieces.take().map(|refs| super::pieces::Pending {
        checkpoint: checkpoint.to_path_buf(),
        run_id: ck.run_id.clone(),
        global: ck.world.clone().into_global(),
        refs,
        fingerprint,
    });
    // a manifest's world holds no bodies: its global part is taken here,
    // the share of the pieces once they are read
    let restored = match pending {
        Some(_) => world.restore_global_part(ck.world),
        None => world.restore_state(ck.world),
    };
    restored.map_err(|e| {
        RunError::InputMessage(format!(
            "checkpoint {} does not fit its scenario: {e}",
            checkpoint.display()
        ))
    })?;
    Ok((scenario, world, ck.driver, ck.run_id, pending))
}
