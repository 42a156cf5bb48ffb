//! The ranks of a run started by `mpirun -np N` (built with the `mpi`
//! feature), or the one process of a plain run.
//!
//! Every rank builds the same scenario and takes the same decisions; the
//! world is split over the ranks ([`clump_core::partition`]). Rank 0 writes
//! the run's files and prints; the other ranks keep the same output
//! schedule in a scratch folder of the system's temporary directory,
//! removed at the end of the run (the events of the run loop, where the world is gathered whole,
//! must fall on the same steps on every rank).

use clump_io::run::Runner;
use std::path::{Path, PathBuf};

/// This process's place among the ranks.
pub struct Ranks {
    #[cfg(feature = "mpi")]
    mpi: Option<clump_mpi::Mpi>,
}

impl Ranks {
    /// Starts MPI when built with it (a plain start is one rank).
    pub fn start() -> Ranks {
        Ranks {
            #[cfg(feature = "mpi")]
            mpi: clump_mpi::Mpi::init(),
        }
    }

    /// This rank.
    pub fn rank(&self) -> usize {
        #[cfg(feature = "mpi")]
        if let Some(m) = &self.mpi {
            return m.rank();
        }
        0
    }

    /// Number of ranks.
    pub fn size(&self) -> usize {
        #[cfg(feature = "mpi")]
        if let Some(m) = &self.mpi {
            return m.size();
        }
        1
    }

    /// The output folder of this rank: `outdir` on rank 0, a scratch
    /// folder on the others.
    pub fn outdir(&self, outdir: &Path) -> PathBuf {
        match self.rank() {
            0 => outdir.to_path_buf(),
            r => std::env::temp_dir().join(format!("clump-rank{r}-{}", std::process::id())),
        }
    }

    /// True on the rank that prints and writes the run's files.
    pub fn is_root(&self) -> bool {
        self.rank() == 0
    }

    /// Splits the runner's world over the ranks when there are several.
    pub fn split(&self, runner: &mut Runner) -> Result<(), String> {
        if let Some(c) = self.comm() {
            runner.partition(c);
        }
        Ok(())
    }

    /// The communicator of the ranks when there are several.
    pub fn comm(&self) -> Option<Box<dyn clump_core::partition::Comm>> {
        #[cfg(feature = "mpi")]
        if let Some(m) = self.mpi.as_ref().filter(|m| m.size() > 1) {
            return Some(Box::new(m.comm()));
        }
        None
    }

    /// After the run: removes this rank's scratch folder.
    pub fn finish(&self, outdir: &Path) {
        if self.rank() > 0 {
            let _ = std::fs::remove_dir_all(outdir);
        }
    }

    /// A rank that failed stops every rank (its diagnosis is printed
    /// already); one process just returns.
    pub fn fail(&self, code: u8) {
        #[cfg(feature = "mpi")]
        if let Some(m) = self.mpi.as_ref().filter(|m| m.size() > 1) {
            m.abort(code as i32);
        }
        let _ = code;
    }
}
