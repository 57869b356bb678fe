//! An output folder written as one set: a reader never sees a mix of two
//! runs, a half-written file, or a killed run's leftovers as a result
//! (before: a SIGKILL left ~80 MB of hidden temp files that no later run
//! removed; two runs into one folder could end with files from both).
//!
//! - **Lock.** `DIR/.septa.lock` is locked (`flock`) for the whole write; a
//!   second writer is refused with an error naming the folder. The kernel
//!   drops the lock when the process dies, however it dies.
//! - **Stale temporaries.** While holding the lock, no other writer can be
//!   writing: every `.NAME.tmpPID` left by a killed run is removed.
//! - **Staged, then swapped, manifest last.** Each new file is written to a
//!   hidden staging name (`.NAME.stagedPID`); a run that fails or is killed
//!   while writing leaves the old set whole (its manifest too). Only
//!   [`OutputDir::finish`] removes the old manifest and the old set's other
//!   files, renames the staged files in, and renames the new
//!   `manifest.json` (job, files and sizes) in last. A folder with a lock
//!   file but no manifest is a run killed inside that short swap
//!   ([`check_complete`]); readers refuse it.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::io::files::atomic::{write_atomic_shown, write_atomic_with};
use crate::io::files::safe_write::{inside, real_dir};

/// Name of the lock file.
pub const LOCK: &str = ".septa.lock";
/// Name of the manifest, written last.
pub const MANIFEST: &str = "manifest.json";

/// Files Septa writes as results; removed when a new run starts in a folder
/// so that the new set never mixes with an old one (also from runs older
/// than manifests).
const RESULT_FILES: [&str; 14] = [
    "network.json",
    "network.ply",
    "network.obj",
    "network.vtu",
    "network.vtm",
    "network/patches.vtu",
    "network/chains.vtu",
    "network/corners.vtu",
    "network/cells.vtu",
    "surfaces.obj",
    "cells.vtu",
    "cells.obj",
    "cut.json",
    "viewer/data.js",
];

/// An output folder being written; see the module documentation.
#[derive(Debug)]
pub struct OutputDir {
    dir: PathBuf,
    job: String,
    files: Vec<(String, u64)>,
    _lock: File,
}

fn ctx(path: &Path, what: &str, e: std::io::Error) -> std::io::Error {
    std::io::Error::new(e.kind(), format!("{}: {what}: {e}", path.display()))
}

/// Whether `name` is a temporary file of [`write_atomic_with`]
/// (`.X.tmpPID`) or a staged file of this module (`.X.stagedPID`).
fn is_temp(name: &str) -> bool {
    let digits_after = |tag: &str| {
        name.rfind(tag).is_some_and(|i| {
            let pid = &name[i + tag.len()..];
            !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit())
        })
    };
    name.starts_with('.') && (digits_after(".tmp") || digits_after(".staged"))
}

/// The hidden staging name of `name` (kept in the same folder, so the
/// final rename is atomic).
fn staged(name: &str) -> String {
    match name.rsplit_once('/') {
        Some((dir, file)) => format!("{dir}/.{file}.staged{}", std::process::id()),
        None => format!(".{name}.staged{}", std::process::id()),
    }
}

impl OutputDir {
    /// Opens `dir` for the job `job` (e.g. `"ia"`): creates it, takes the
    /// lock, removes stale temporaries, the old manifest and the old result
    /// set. Errors name the folder and say what to do.
    pub fn create(dir: &Path, job: &str) -> std::io::Result<OutputDir> {
        if dir.exists() && !dir.is_dir() {
            return Err(std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                format!("{}: exists and is not a folder; give -o a folder path", dir.display()),
            ));
        }
        std::fs::create_dir_all(dir).map_err(|e| ctx(dir, "cannot create the output folder", e))?;
        let lock_path = dir.join(LOCK);
        let mut lock = std::fs::OpenOptions::new();
        lock.create(true).truncate(false).write(true);
        // a link planted at the lock's name is not followed (ELOOP)
        #[cfg(unix)]
        std::os::unix::fs::OpenOptionsExt::custom_flags(&mut lock, libc::O_NOFOLLOW | libc::O_CLOEXEC);
        let lock = lock.open(&lock_path).map_err(|e| ctx(dir, "cannot write into the output folder", e))?;
        match lock.try_lock() {
            Ok(()) => {}
            Err(std::fs::TryLockError::WouldBlock) => {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::WouldBlock,
                    format!(
                        "{}: another septa run is writing into this folder (it holds {LOCK}); wait for it to finish or give another output folder",
                        dir.display()
                    ),
                ))
            }
            Err(std::fs::TryLockError::Error(e)) => return Err(ctx(&lock_path, "cannot lock", e)),
        }
        let out = OutputDir { dir: dir.to_path_buf(), job: job.to_string(), files: Vec::new(), _lock: lock };
        out.clean()?;
        Ok(out)
    }

    /// Removes stale temporaries and staged files of killed runs.
    fn clean(&self) -> std::io::Result<()> {
        // `regions/`: the per-cell solids (writers/solids_out.rs `SOLIDS_DIR`)
        for sub in ["", "viewer", "network", "regions"] {
            // never through a link: a linked `network/` is not this folder's
            if !sub.is_empty() && !std::fs::symlink_metadata(self.dir.join(sub)).is_ok_and(|m| m.is_dir()) {
                continue;
            }
            let Ok(entries) = std::fs::read_dir(self.dir.join(sub)) else { continue };
            for e in entries.flatten() {
                if is_temp(&e.file_name().to_string_lossy()) {
                    let _ = std::fs::remove_file(e.path());
                }
            }
        }
        Ok(())
    }

    /// The old set's files: the previous manifest's and the known result names.
    fn old_set(&self) -> Vec<String> {
        let mut old: Vec<String> = RESULT_FILES.iter().map(|s| s.to_string()).collect();
        if let Ok(text) = crate::io::files::input::read_input_text(&self.dir.join(MANIFEST)) {
            if let Ok(v) = serde_json::from_str::<serde_json::Value>(&text) {
                for f in v["files"].as_array().into_iter().flatten() {
                    if let Some(name) = f["name"].as_str().filter(|n| safe_name(n)) {
                        old.push(name.to_string());
                    }
                }
            }
        }
        old
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// Writes `name` (a plain file name in the folder) atomically and adds
    /// it to the set. Errors name the file.
    pub fn write_with(
        &mut self,
        name: &str,
        write: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
    ) -> std::io::Result<()> {
        let path = self.dir.join(staged(name));
        self.make_parent(name)?;
        // the final name too: never a link or special file replaced
        crate::io::files::safe_write::check_output_file(&self.dir.join(name))?;
        write_atomic_shown(&path, &self.dir.join(name), write)?;
        let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        self.files.push((name.to_string(), size));
        Ok(())
    }

    /// Runs a path-based writer (which must write atomically, as every
    /// `io` writer does) for `name` and adds the file to the set.
    pub fn write_path(&mut self, name: &str, write: impl FnOnce(&Path) -> std::io::Result<()>) -> std::io::Result<()> {
        let path = self.dir.join(staged(name));
        self.make_parent(name)?;
        // the final name too: never a link or special file replaced
        crate::io::files::safe_write::check_output_file(&self.dir.join(name))?;
        crate::io::files::safe_write::check_output_file(&path)?;
        let result = write(&path);
        if let Err(e) = result {
            let _ = std::fs::remove_file(&path);
            // the error names the file the user will look for, not its staged name
            let text = e.to_string().replace(&path.display().to_string(), &self.dir.join(name).display().to_string());
            return Err(std::io::Error::new(e.kind(), text));
        }
        let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        self.files.push((name.to_string(), size));
        Ok(())
    }

    /// Creates the sub-folder a file `a/b` of the set goes into (`viewer/`, a
    /// multiblock's pieces): through real folders only, never a link that
    /// could lead out of the output folder ([`real_dir`]).
    fn make_parent(&self, name: &str) -> std::io::Result<()> {
        match Path::new(name).parent().filter(|p| !p.as_os_str().is_empty()) {
            Some(sub) => real_dir(&self.dir, sub).map(drop),
            None => Ok(()),
        }
    }

    /// Where file `name` of this set is before [`OutputDir::finish`] moves
    /// it in (to read back what was written, e.g. `septa cut --verify`).
    pub fn staged_path(&self, name: &str) -> PathBuf {
        self.dir.join(staged(name))
    }

    /// [`OutputDir::write_with`] for bytes.
    pub fn write(&mut self, name: &str, bytes: &[u8]) -> std::io::Result<()> {
        self.write_with(name, |w| w.write_all(bytes))
    }

    /// Swaps the new set in: removes the old manifest (from here the folder
    /// reads as incomplete), the old set's files, renames the staged files
    /// to their names, writes the manifest last and releases the lock.
    pub fn finish(self) -> std::io::Result<()> {
        let manifest = self.dir.join(MANIFEST);
        let old = self.old_set();
        match std::fs::remove_file(&manifest) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(ctx(&manifest, "cannot remove the old manifest", e))
            }
            _ => {}
        }
        for name in old.iter().filter(|o| !self.files.iter().any(|(n, _)| n == *o)) {
            // a listed path through a linked folder is not this folder's file
            if inside(&self.dir, Path::new(name)) {
                let _ = std::fs::remove_file(self.dir.join(name));
            }
        }
        for (name, _) in &self.files {
            let (from, to) = (self.dir.join(staged(name)), self.dir.join(name));
            std::fs::rename(&from, &to).map_err(|e| ctx(&to, "cannot move the new file in", e))?;
        }
        let files: Vec<_> = self.files.iter().map(|(n, s)| serde_json::json!({ "name": n, "bytes": s })).collect();
        let doc = serde_json::json!({
            "septa": env!("CARGO_PKG_VERSION"),
            "job": self.job,
            "files": files,
        });
        let path = manifest;
        let text = serde_json::to_string_pretty(&doc).map_err(std::io::Error::other)?;
        write_atomic_with(&path, |w| w.write_all(text.as_bytes())).map_err(|e| ctx(&path, "cannot write", e))
    }
}

impl Drop for OutputDir {
    /// A run that stops before [`OutputDir::finish`] (an error) removes what
    /// it staged: the old set stays whole and nothing hidden is left.
    fn drop(&mut self) {
        for (name, _) in &self.files {
            let _ = std::fs::remove_file(self.dir.join(staged(name)));
        }
    }
}

/// A manifest entry must stay inside the folder.
fn safe_name(n: &str) -> bool {
    !n.is_empty() && !n.starts_with('/') && !n.split(['/', '\\']).any(|c| c == "..")
}

/// Whether a folder holds a complete result set: `Ok(Some(files))` from its
/// manifest (the files of the set); `Ok(None)` for a folder written before
/// manifests existed (no lock file either); an error naming the folder when
/// a run was interrupted (lock file, no manifest), is still writing, or the
/// manifest is unreadable.
pub fn check_complete(dir: &Path) -> Result<Option<Vec<String>>, String> {
    let manifest = dir.join(MANIFEST);
    match crate::io::files::input::read_input(&manifest) {
        Ok(bytes) => {
            let v: serde_json::Value = serde_json::from_slice(&bytes)
                .map_err(|e| format!("{}: not a septa manifest: {e}", manifest.display()))?;
            let files = v["files"]
                .as_array()
                .ok_or_else(|| format!("{}: no \"files\" list", manifest.display()))?
                .iter()
                .filter_map(|f| f["name"].as_str().map(str::to_string))
                .collect();
            Ok(Some(files))
        }
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(format!("{}: cannot read: {e}", manifest.display())),
        Err(_) if dir.join(LOCK).exists() => {
            let busy = File::open(dir.join(LOCK)).ok().is_some_and(|f| f.try_lock_shared().is_err());
            if busy {
                Err(format!("{}: a septa run is still writing into this folder", dir.display()))
            } else {
                Err(format!(
                    "{}: incomplete result: a run was interrupted before writing {MANIFEST}; run the job again",
                    dir.display()
                ))
            }
        }
        Err(_) => Ok(None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temp_names() {
        assert!(is_temp(".network.ply.tmp1234") && is_temp(".network.ply.staged77"));
        assert_eq!(staged("viewer/data.js"), format!("viewer/.data.js.staged{}", std::process::id()));
        assert!(!is_temp("network.ply"));
        assert!(!is_temp(".network.tmp"));
        assert!(!is_temp(".x.tmp12a"));
        assert!(safe_name("network.json") && safe_name("viewer/data.js"));
        assert!(!safe_name("../x") && !safe_name("/etc/passwd") && !safe_name("a/../../b"));
    }
}
