//! Output folders are never silently shared or mixed:
//!
//! - a run holds an OS-level lock (`flock`) on `.clump.lock` in its folder
//!   while it writes, so a second run or resume into the same folder is
//!   refused (the lock ends with the process, also after kill -9);
//! - a fresh run refuses a folder that holds another run's files unless
//!   `overwrite` is given, which then deletes those files (and only them:
//!   files Clump does not write are left alone);
//! - every run writes an id into `.clump-run`; checkpoints carry it, and a
//!   resume continues only in the folder with the same id, or in a folder
//!   without any run's files.

use super::RunError;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The lock file in an output folder.
pub const LOCK_FILE: &str = ".clump.lock";
/// The file holding the id of the run that owns an output folder.
pub const RUN_ID_FILE: &str = ".clump-run";

/// True for the names of files a run writes into its output folder.
pub fn is_run_file(name: &str) -> bool {
    const FIXED: [&str; 8] = [
        RUN_ID_FILE,
        "scenario.toml",
        "manifest.json",
        "final_state.json",
        "thermo.csv",
        "spheres.pvd",
        "bodies.pvd",
        "walls.pvd",
    ];
    let numbered = |prefix: &str, ext: &str| {
        name.strip_prefix(prefix)
            .and_then(|r| r.strip_suffix(ext))
            .is_some_and(|mid| !mid.is_empty() && mid.bytes().all(|b| b.is_ascii_digit()))
    };
    FIXED.contains(&name)
        || ["spheres_", "bodies_", "walls_"]
            .iter()
            .any(|p| numbered(p, ".vtp") || numbered(p, ".vtu"))
        || numbered("traj_", ".csv")
        || numbered("checkpoint_", ".ckpt")
        || is_piece_file(name)
        || crate::vtk_pieces::is_piece_file(name)
        // temporary files of crate::atomic (`.<name>.tmp.<pid>.<n>`)
        || (name.starts_with('.') && name.contains(".tmp."))
}

/// True for a rank's piece of a split checkpoint,
/// `checkpoint_<step>.rank<r>of<n>.piece` ([`super::pieces`]).
fn is_piece_file(name: &str) -> bool {
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    name.strip_prefix("checkpoint_")
        .and_then(|r| r.strip_suffix(".piece"))
        .and_then(|r| r.split_once(".rank"))
        .and_then(|(step, rn)| Some((step, rn.split_once("of")?)))
        .is_some_and(|(step, (r, n))| digits(step) && digits(r) && digits(n))
}

/// The run files in `dir` (sorted; none when `dir` does not exist).
pub fn run_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = match std::fs::read_dir(dir) {
        Ok(rd) => rd
            .filter_map(Result::ok)
            .filter(|e| e.file_name().to_str().is_some_and(is_run_file))
            .map(|e| e.path())
            .collect(),
        Err(_) => Vec::new(),
    };
    v.sort();
    v
}

/// The id of the run that owns `dir` (`None`: no `.clump-run` file).
pub fn folder_run_id(dir: &Path) -> Option<String> {
    std::fs::read_to_string(dir.join(RUN_ID_FILE))
        .ok()
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
}

/// A new run id: wall-clock nanoseconds and process id, in hex.
pub fn new_run_id() -> String {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    format!("{nanos:x}-{:x}", std::process::id())
}

/// An exclusive lock on an output folder, held until dropped (or the
/// process ends).
#[derive(Debug)]
pub struct FolderLock {
    _file: File,
}

fn names(files: &[PathBuf]) -> String {
    let n: Vec<String> = files
        .iter()
        .take(4)
        .filter_map(|p| p.file_name().map(|f| f.to_string_lossy().into_owned()))
        .collect();
    let more = files.len().saturating_sub(n.len());
    if more > 0 {
        format!("{} and {more} more", n.join(", "))
    } else {
        n.join(", ")
    }
}

/// Creates `dir` if needed and locks it; an error when another process
/// holds the lock.
pub fn lock(dir: &Path) -> Result<FolderLock, RunError> {
    std::fs::create_dir_all(dir).map_err(|e| {
        RunError::Runtime(format!(
            "cannot create output directory {}: {e}",
            dir.display()
        ))
    })?;
    let path = dir.join(LOCK_FILE);
    let mut file = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(false)
        .open(&path)
        .map_err(|e| RunError::Runtime(format!("cannot open {}: {e}", path.display())))?;
    if !try_lock(&file) {
        let holder = std::fs::read_to_string(&path).unwrap_or_default();
        let holder = holder.trim();
        return Err(RunError::InputMessage(format!(
            "output directory {} is in use by another clump run{}; two runs must not write into one folder\n  = help: wait for it to end, or choose another folder with -o",
            dir.display(),
            if holder.is_empty() { String::new() } else { format!(" (process {holder})") }
        )));
    }
    let _ = file.set_len(0);
    let _ = write!(file, "{}", std::process::id());
    let _ = file.flush();
    Ok(FolderLock { _file: file })
}

#[cfg(unix)]
fn try_lock(f: &File) -> bool {
    use std::os::unix::io::AsRawFd;
    // SAFETY: flock on a file descriptor this File owns; no memory is shared.
    unsafe { libc::flock(f.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) == 0 }
}

#[cfg(not(unix))]
fn try_lock(_f: &File) -> bool {
    true
}

/// Prepares `dir` for a fresh run of the scenario at `scenario_path`:
/// locks it, refuses another run's files unless `overwrite` (which deletes
/// them, except the scenario file itself), and writes a new run id.
/// Returns the lock and the id.
pub fn prepare_fresh(
    dir: &Path,
    overwrite: bool,
    scenario_path: &Path,
) -> Result<(FolderLock, String), RunError> {
    let lock = lock(dir)?;
    let keep = std::fs::canonicalize(scenario_path).ok();
    let files: Vec<PathBuf> = run_files(dir)
        .into_iter()
        .filter(|p| keep.is_none() || std::fs::canonicalize(p).ok() != keep)
        .collect();
    if !files.is_empty() {
        if !overwrite {
            return Err(RunError::InputMessage(format!(
                "output directory {} already holds the files of another run ({}); a new run would mix its output with them\n  = help: pass --overwrite to delete those files first, or choose another folder with -o",
                dir.display(),
                names(&files)
            )));
        }
        for f in &files {
            std::fs::remove_file(f)
                .map_err(|e| RunError::Runtime(format!("cannot delete {}: {e}", f.display())))?;
        }
        tracing::info!(
            files = files.len(),
            "--overwrite: deleted the previous run's files in {}",
            dir.display()
        );
    }
    let id = new_run_id();
    write_id(dir, &id)?;
    Ok((lock, id))
}

/// The last step the run in `dir` recorded (`final_step` of its
/// `manifest.json`), if any. A run that became unstable is not counted: its
/// output after the last good checkpoint is what a resume recomputes (the
/// instability message points there).
fn last_step(dir: &Path) -> Option<u64> {
    let text = std::fs::read_to_string(dir.join("manifest.json")).ok()?;
    let v: serde_json::Value = serde_json::from_str(&text).ok()?;
    let status = v.get("status").and_then(|s| s.as_str()).unwrap_or("");
    if status.starts_with("unstable") {
        return None;
    }
    v.get("final_step")?.as_u64()
}

fn write_id(dir: &Path, id: &str) -> Result<(), RunError> {
    crate::atomic::write_atomic(dir.join(RUN_ID_FILE), format!("{id}\n").as_bytes())
        .map_err(|e| RunError::Runtime(format!("cannot write the run id: {e}")))
}

/// Prepares `dir` for resuming the run with id `run_id` (`None`: a
/// checkpoint of an older version) from `checkpoint`, at `step`: locks it
/// and accepts it when it is that run's folder, or holds no run's files.
/// Refused before anything is written: a folder whose run went past `step`
/// (unless `opts.rewind`), and a default folder (no `-o`) that is not a run
/// folder. Returns the lock and the id to continue with.
pub fn prepare_resume(
    dir: &Path,
    run_id: Option<&str>,
    checkpoint: &Path,
    step: u64,
    opts: super::ResumeOptions,
) -> Result<(FolderLock, String), RunError> {
    // before the lock, which would leave its file in the folder
    if !opts.outdir_given && run_files(dir).is_empty() && folder_run_id(dir).is_none() {
        return Err(RunError::InputMessage(format!(
            "{} is not in a run folder: resuming it there would write the run's outputs (thermo.csv, VTK frames, checkpoints) into {}\n  = help: name the output folder: clump resume {} -o DIR",
            checkpoint.display(),
            std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf()).display(),
            checkpoint.display()
        )));
    }
    let lock = lock(dir)?;
    let files = run_files(dir);
    let owner = folder_run_id(dir);
    let same_folder = || {
        let parent = checkpoint.parent().filter(|p| !p.as_os_str().is_empty());
        let parent = parent.unwrap_or(Path::new("."));
        match (std::fs::canonicalize(parent), std::fs::canonicalize(dir)) {
            (Ok(a), Ok(b)) => a == b,
            _ => false,
        }
    };
    let ok = match (run_id, owner.as_deref()) {
        _ if files.is_empty() => true,
        (Some(a), Some(b)) => a == b,
        // an older checkpoint or folder without ids: only the checkpoint's own folder
        (None, _) | (_, None) => owner.is_none() && same_folder(),
    };
    if !ok {
        return Err(RunError::InputMessage(format!(
            "output directory {} holds the files of another run ({}); resuming {} there would mix the two runs' output\n  = help: resume into the checkpoint's own run folder (the default, without -o), or into an empty folder",
            dir.display(),
            names(&files),
            checkpoint.display()
        )));
    }
    if let (Some(last), false) = (last_step(dir).filter(|&s| s > step), opts.rewind) {
        return Err(RunError::InputMessage(format!(
            "the run in {} went on to step {last}, past the checkpoint's step {step}: resuming there would replace its thermo and trajectory rows, VTK frames, manifest and final state after step {step} (nothing was changed)\n  = help: pass --rewind to continue from step {step} anyway, or resume into a new folder with -o DIR",
            dir.display()
        )));
    }
    let id = run_id.map(str::to_string).unwrap_or_else(new_run_id);
    write_id(dir, &id)?;
    Ok((lock, id))
}
