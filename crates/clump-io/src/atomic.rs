//! Atomic file output: every file Clump writes is first written to a
//! temporary file in the same directory, flushed to disk (`fsync`) and then
//! renamed over the target, so a reader (or a crash) never sees a partial
//! file.

use std::fs::{self, File};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// The temporary path used for `path`: `.<name>.tmp.<pid>.<n>` next to it.
fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let tmp = format!(".{name}.tmp.{}.{n}", std::process::id());
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.join(tmp),
        _ => PathBuf::from(tmp),
    }
}

/// Writes `bytes` to `path` atomically (temp file in the same directory,
/// fsync, rename). The directory must exist. Errors carry the path.
pub fn write_atomic(path: impl AsRef<Path>, bytes: &[u8]) -> io::Result<()> {
    let mut w = AtomicWriter::create(path)?;
    w.write_all(bytes)?;
    w.commit()
}

/// A writer to a temporary file that replaces the target file on
/// [`AtomicWriter::commit`]. Dropped without committing, it removes the
/// temporary file and leaves the target untouched.
pub struct AtomicWriter {
    target: PathBuf,
    tmp: PathBuf,
    file: Option<io::BufWriter<File>>,
}

impl AtomicWriter {
    /// Starts writing a replacement for `path`.
    pub fn create(path: impl AsRef<Path>) -> io::Result<Self> {
        let target = path.as_ref().to_path_buf();
        let tmp = temp_path(&target);
        let file =
            File::create(&tmp).map_err(|e| with_path(e, &tmp, "cannot create temporary file"))?;
        Ok(AtomicWriter {
            target,
            tmp,
            file: Some(io::BufWriter::new(file)),
        })
    }

    /// The final path.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Flushes, syncs and renames the temporary file over the target. On
    /// failure (e.g. a full disk while flushing) the temporary file is
    /// removed and the target left untouched.
    pub fn commit(mut self) -> io::Result<()> {
        let buf = self.file.take().expect("not yet committed");
        let done = buf
            .into_inner()
            .map_err(|e| with_path(e.into_error(), &self.target, "cannot write"))
            .and_then(|file| {
                file.sync_all()
                    .map_err(|e| with_path(e, &self.tmp, "cannot sync"))
            })
            .and_then(|()| {
                fs::rename(&self.tmp, &self.target)
                    .map_err(|e| with_path(e, &self.target, "cannot rename temporary file onto"))
            });
        if done.is_err() {
            let _ = fs::remove_file(&self.tmp);
        }
        done?;
        // Make the rename durable where the platform allows syncing a directory.
        if let Some(dir) = self.target.parent().filter(|p| !p.as_os_str().is_empty()) {
            if let Ok(d) = File::open(dir) {
                let _ = d.sync_all();
            }
        }
        Ok(())
    }
}

impl Write for AtomicWriter {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let target = &self.target;
        self.file
            .as_mut()
            .expect("not yet committed")
            .write(buf)
            .map_err(|e| with_path(e, target, "cannot write"))
    }
    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        let target = &self.target;
        self.file
            .as_mut()
            .expect("not yet committed")
            .write_all(buf)
            .map_err(|e| with_path(e, target, "cannot write"))
    }
    fn flush(&mut self) -> io::Result<()> {
        self.file.as_mut().expect("not yet committed").flush()
    }
}

impl Drop for AtomicWriter {
    fn drop(&mut self) {
        if self.file.take().is_some() {
            let _ = fs::remove_file(&self.tmp);
        }
    }
}

fn with_path(e: io::Error, path: &Path, what: &str) -> io::Error {
    io::Error::new(e.kind(), format!("{what} {}: {e}", path.display()))
}
