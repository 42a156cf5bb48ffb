//! Append-only logs (`thermo.csv`, `traj_<id>.csv`) that always end at a
//! whole record: each record is written straight to the file (no buffer
//! left to flush), and when a write fails part-way (e.g. a full disk) the
//! file is cut back to its length before the record. Errors name the file.

use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// An append-only file of whole records.
#[derive(Debug)]
pub struct AppendLog {
    path: PathBuf,
    file: File,
    len: u64,
}

impl AppendLog {
    /// Opens the existing file `path` for appending.
    pub fn open(path: impl AsRef<Path>) -> io::Result<Self> {
        let path = path.as_ref().to_path_buf();
        let named = |e: io::Error| {
            io::Error::new(
                e.kind(),
                format!("cannot open {} for appending: {e}", path.display()),
            )
        };
        let file = OpenOptions::new().append(true).open(&path).map_err(named)?;
        let len = file.metadata().map_err(named)?.len();
        Ok(AppendLog { path, file, len })
    }

    /// The file path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Appends one whole `record`, or leaves the file as it was and returns
    /// the error (naming the file).
    pub fn append(&mut self, record: &[u8]) -> io::Result<()> {
        match self.file.write_all(record) {
            Ok(()) => {
                self.len += record.len() as u64;
                Ok(())
            }
            Err(e) => {
                let cut = match self.file.set_len(self.len) {
                    Ok(()) => "; the file ends at its last whole row".to_string(),
                    Err(e2) => format!("; cutting it back to its last whole row failed too: {e2}"),
                };
                Err(io::Error::new(
                    e.kind(),
                    format!("cannot write {}: {e}{cut}", self.path.display()),
                ))
            }
        }
    }
}
