//! Atomic file writes: every output is written to a temporary sibling file
//! and renamed over its destination, so a reader never sees half a file and
//! a failed write leaves nothing behind.
//!
//! Durability is a separate choice ([`set_durable`]): the rename alone
//! already keeps a killed or interrupted run from leaving a partial file
//! (the kernel holds the written data whatever happens to the process);
//! flushing each file to the disk (`fsync`) before its rename also covers
//! a crash of the machine itself. That flush cost 1-3 ms per file here
//! (four files on a small `septa cut`, a fifth of its run), so it is off
//! unless asked for: `septa --fsync ...` or `SEPTA_FSYNC=1`.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU8, Ordering};

use crate::io::files::safe_write::{check_output_file, create_temp};

/// 0: not decided yet (read `SEPTA_FSYNC` on first use), 1: off, 2: on.
static DURABLE: AtomicU8 = AtomicU8::new(0);

/// Whether finished files are flushed to the disk before they are renamed
/// into place: as set by [`set_durable`], else `SEPTA_FSYNC` is set to a
/// value other than `0` (default: off).
fn durable() -> bool {
    match DURABLE.load(Ordering::Relaxed) {
        0 => {
            let on = std::env::var_os("SEPTA_FSYNC").is_some_and(|v| !v.is_empty() && v != "0");
            DURABLE.store(if on { 2 } else { 1 }, Ordering::Relaxed);
            on
        }
        state => state == 2,
    }
}

/// Turns the flush of every finished file to the disk on or off for the
/// rest of the process (see the module documentation).
pub fn set_durable(on: bool) {
    DURABLE.store(if on { 2 } else { 1 }, Ordering::Relaxed);
}

/// Flushes `file` to the disk when [`durable`] says so.
pub(crate) fn sync_if_durable(file: &File) -> std::io::Result<()> {
    if durable() {
        file.sync_all()
    } else {
        Ok(())
    }
}

/// Writes `path` atomically: `write` fills a temporary sibling file, which
/// is then renamed over `path`. On error the temporary file is removed.
/// `path` must be a regular file or absent: a link, FIFO, device or folder
/// there is refused ([`check_output_file`](crate::io::files::safe_write::check_output_file)),
/// and the temporary file is never opened through a link.
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    write_atomic_shown(path, path, write)
}

/// [`write_atomic_with`] whose errors name `shown` (the file's final name
/// when `path` is a staged name, [`crate::io::files::outdir`]).
pub(crate) fn write_atomic_shown(
    path: &Path,
    shown: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    check_output_file(path)?;
    let dir = path.parent().unwrap_or(Path::new("."));
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let tmp: PathBuf = dir.join(format!(".{name}.tmp{}", std::process::id()));
    pending().push(tmp.clone());
    // Removes the temporary file on every way out but a successful rename,
    // a panic inside `write` included (tests/io/atomic_failure.rs), and
    // takes it off the list a Ctrl-C handler cleans.
    struct Cleanup<'a>(&'a Path, bool);
    impl Drop for Cleanup<'_> {
        fn drop(&mut self) {
            if !self.1 {
                let _ = std::fs::remove_file(self.0);
            }
            pending().retain(|p| p != self.0);
        }
    }
    let mut cleanup = Cleanup(&tmp, false);
    let result = (|| {
        let mut w = BufWriter::with_capacity(1 << 20, create_temp(&tmp)?);
        write(&mut w)?;
        sync_if_durable(&w.into_inner().map_err(|e| e.into_error())?)?;
        check_output_file(path)?;
        std::fs::rename(&tmp, path)
    })();
    cleanup.1 = result.is_ok();
    // The error names the file it could not write (a full disk or a size
    // limit says nothing about which output failed) and keeps the system's
    // words ("No space left on device").
    result.map_err(|e| std::io::Error::new(e.kind(), format!("writing {}: {e}", shown.display())))
}

/// Temporary files being written now (by any thread), for [`remove_pending_temps`].
fn pending() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    static PENDING: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

/// Removes the temporary files of writes in progress and returns how many:
/// called by a Ctrl-C handler before exiting, so an interrupted run leaves
/// no hidden partial files.
pub fn remove_pending_temps() -> usize {
    let list = std::mem::take(&mut *pending());
    list.iter().filter(|p| std::fs::remove_file(p).is_ok()).count()
}

/// Writes `bytes` to `path` atomically (see [`write_atomic_with`]).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomic_with(path, |w| w.write_all(bytes))
}
