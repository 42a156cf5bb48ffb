//! Scenario files: a TOML description of a whole simulation (materials,
//! contact laws, clump templates, particle mixes, insertion, walls, stages,
//! output), in SI units. See `docs/scenario.md` for the key-by-key reference.
//!
//! [`load`] reads and validates a file and returns a resolved [`Scenario`];
//! every problem is reported as a [`Diagnostic`] with the file, line and
//! column, the key and what is allowed. [`Scenario::build_world`] creates the
//! engine's [`World`] (materials, contact table, templates, walls; no bodies —
//! insertion is done by the run driver, [`crate::run`]).
#![allow(clippy::result_large_err)]

mod bodies_file;
pub mod bounds;
pub mod diag;
mod exact;
pub mod guard;
pub mod keys;
mod model;
mod placement;
pub mod raw;
mod raw_output;
mod resolve;
mod source;
pub mod units;

pub use bodies_file::BodyFileFormat;
pub use diag::{Diagnostic, Location, ScenarioError, Severity};
pub use model::*;
pub use resolve::{DT_ERROR_FRACTION, DT_STABLE_FRACTION, DT_WARN_FRACTION, PACK_ERROR_FRACTION};
pub use source::{Seg, Source};

use clump_core::contact::ContactTable;
use clump_core::world::{World, WorldError};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Why [`Scenario::build_world`] failed: the engine refused what the
/// validation let through (the messages are the engine's).
#[derive(Debug, thiserror::Error)]
pub enum BuildWorldError {
    /// The contact model of a pair of materials could not be built.
    #[error("{0}")]
    ContactTable(String),
    /// A template or wall names a material that does not exist.
    #[error(transparent)]
    World(#[from] WorldError),
}

/// Where the files a scenario refers to come from: the disk (relative to the
/// scenario's folder) or, when resuming, the copies stored in a checkpoint.
pub struct Files {
    base: PathBuf,
    embedded: Option<BTreeMap<String, Vec<u8>>>,
    pub(crate) loaded: BTreeMap<String, Vec<u8>>,
}

impl Files {
    /// Files on disk, relative to `base`.
    pub fn disk(base: &Path) -> Self {
        Files {
            base: base.to_path_buf(),
            embedded: None,
            loaded: BTreeMap::new(),
        }
    }

    /// Files stored in a checkpoint.
    pub fn embedded(files: BTreeMap<String, Vec<u8>>) -> Self {
        Files {
            base: PathBuf::from("<checkpoint>"),
            embedded: Some(files),
            loaded: BTreeMap::new(),
        }
    }

    /// Reads `rel` (as written in the scenario).
    pub fn read(&mut self, rel: &str) -> std::io::Result<Vec<u8>> {
        let bytes = match &self.embedded {
            Some(m) => m.get(rel).cloned().ok_or_else(|| {
                std::io::Error::new(std::io::ErrorKind::NotFound, "not stored in the checkpoint")
            })?,
            None => std::fs::read(self.base.join(rel))?,
        };
        self.loaded.insert(rel.to_string(), bytes.clone());
        Ok(bytes)
    }

    fn base_display(&self) -> String {
        let s = self.base.display().to_string();
        if s.is_empty() {
            ".".into()
        } else {
            s
        }
    }
}

/// Reads, parses and validates the scenario file at `path`.
pub fn load(path: &Path) -> Result<Scenario, ScenarioError> {
    let bytes = std::fs::read(path).map_err(|e| {
        ScenarioError::one(Diagnostic::new(
            Severity::Error,
            path,
            format!("cannot read scenario file '{}': {e}", path.display()),
        ))
    })?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let (line, column) = diag::utf8_position(e.as_bytes(), &e.utf8_error());
        ScenarioError::one(Diagnostic::new(
            Severity::Error,
            path,
            format!(
                "scenario file '{}' is not valid UTF-8 text: invalid byte at line {line}, column {column} ({}:{line}:{column})",
                path.display(),
                path.display()
            ),
        ).note("help: save the file as UTF-8 (TOML files are UTF-8)"))
    })?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    parse(path, text, Files::disk(&base))
}

/// Parses and validates scenario `text` (named `path` in messages), reading
/// referenced files from `files`.
pub fn parse(path: &Path, text: String, mut files: Files) -> Result<Scenario, ScenarioError> {
    let src = Source::new(path, text);
    let raw: raw::RawScenario =
        toml::from_str(&src.text).map_err(|e| ScenarioError::one(src.from_toml_error(&e)))?;
    resolve::resolve(&src, raw, &mut files)
}

impl Scenario {
    /// A 64-bit fingerprint (FNV-1a) of the scenario text and every file it
    /// refers to.
    pub fn fingerprint(&self) -> u64 {
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        let mut eat = |b: &[u8]| {
            for &x in b {
                h ^= x as u64;
                h = h.wrapping_mul(0x0100_0000_01b3);
            }
            h ^= 0xff;
            h = h.wrapping_mul(0x0100_0000_01b3);
        };
        eat(self.text.as_bytes());
        for (k, v) in &self.files {
            eat(k.as_bytes());
            eat(v);
        }
        h
    }

    /// Builds the engine world: materials, contact table, templates and
    /// walls (no bodies).
    pub fn build_world(&self) -> Result<World, BuildWorldError> {
        let n = self.materials.len();
        let table = ContactTable::new(&self.materials, |a, b| self.pair_table[a * n + b])
            .map_err(|e| BuildWorldError::ContactTable(e.to_string()))?;
        let mut world = World::new(self.config, self.materials.clone(), table);
        for t in &self.templates {
            world.add_template(t.template.clone(), t.material)?;
        }
        for m in &self.meshes {
            world.add_mesh(m.clone());
        }
        for w in &self.walls {
            world.add_wall(w.clone())?;
        }
        if let Some(h) = &self.heat {
            world.enable_heat(h.model.clone())?;
        }
        world.set_fluid(self.fluid)?;
        if self.fluid.is_some() {
            world.set_fluid_velocity_grid(self.fluid_grid.clone())?;
        }
        if let Some(c) = self.heat.as_ref().and_then(|h| h.convection) {
            world.set_fluid_heat(Some(c))?;
        }
        Ok(world)
    }

    /// An error located at `[[insert]]` number `index` (0-based), for
    /// insertion failures found while running.
    pub fn insert_error(&self, index: usize, message: impl Into<String>) -> ScenarioError {
        let src = Source::new(&self.path, self.text.clone());
        let key = match &self.inserts[index].kind {
            InsertSpec::Pack { spec, .. } => match spec.target {
                clump_core::insert::PackTarget::Count(_) => "count",
                clump_core::insert::PackTarget::VolumeFraction(_) => "volume_fraction",
            },
            InsertSpec::Stream { .. } => "region",
            InsertSpec::File { .. } => "file",
        };
        ScenarioError::one(src.error_at(&[Seg::K("insert"), Seg::I(index), Seg::K(key)], message))
    }

    /// An error at `[[stage]]` `stage`'s `[[stage.body]]` entry `index`
    /// (its `id`), for problems found when the stage begins.
    pub fn stage_body_error(
        &self,
        stage: usize,
        index: usize,
        message: impl Into<String>,
    ) -> ScenarioError {
        let src = Source::new(&self.path, self.text.clone());
        let at = [
            Seg::K("stage"),
            Seg::I(stage),
            Seg::K("body"),
            Seg::I(index),
            Seg::K("id"),
        ];
        ScenarioError::one(src.error_at(&at, message))
    }
}
