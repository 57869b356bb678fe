//! Where a writer may write: nothing outside the output folder, nothing
//! but regular files.
//!
//! Two ways a write could leave the folder it was given, both closed here:
//! - a **link inside the output folder** (`OUT/network -> ../elsewhere`):
//!   a sub-folder Septa writes into, or a file it removes, is reached only
//!   through real folders ([`real_dir`], [`inside`]);
//! - a **special file or link at the destination** (`--stream OUT.ply`
//!   where `OUT.ply` is a FIFO, a device or a symbolic link): renaming a new
//!   file over it would replace the node itself (as root, `/dev/null`), so
//!   such a destination is refused ([`check_output_file`]).
//!
//! Temporary files are created with `O_EXCL | O_NOFOLLOW` ([`create_temp`]):
//! a link planted at a temporary name is never followed.

use std::fs::{File, OpenOptions};
use std::io::{Error, ErrorKind};
use std::path::{Component, Path, PathBuf};

/// What a path is, in words, when it is not a regular file or folder
/// (also the input layer's words, `input.rs`).
pub(crate) fn special_kind(ft: &std::fs::FileType) -> Option<&'static str> {
    if ft.is_symlink() {
        return Some("a symbolic link");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if ft.is_fifo() {
            return Some("a FIFO (named pipe)");
        }
        if ft.is_char_device() {
            return Some("a character device");
        }
        if ft.is_block_device() {
            return Some("a block device");
        }
        if ft.is_socket() {
            return Some("a socket");
        }
    }
    None
}

/// Checks that `path` may be replaced by a new regular file: it does not
/// exist or is a regular file. A symbolic link, FIFO, device, socket or
/// folder is refused with an error naming it (renaming over it would
/// replace the link or device node itself, not write through it).
pub fn check_output_file(path: &Path) -> std::io::Result<()> {
    match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == ErrorKind::NotFound => Ok(()),
        Err(e) => Err(Error::new(e.kind(), format!("{}: {e}", path.display()))),
        Ok(m) if m.is_file() => Ok(()),
        Ok(m) if m.is_dir() => Err(Error::new(
            ErrorKind::AlreadyExists,
            format!("{}: is a folder; give the path of a file to write", path.display()),
        )),
        Ok(m) => Err(Error::new(
            ErrorKind::InvalidInput,
            format!(
                "{}: is {}; Septa writes only regular files and does not replace links or special files (remove it or give another path)",
                path.display(),
                special_kind(&m.file_type()).unwrap_or("not a regular file")
            ),
        )),
    }
}

/// Creates the temporary file `path` for writing: never through a link
/// (`O_NOFOLLOW`), never into an existing file (`O_EXCL`). A file left at
/// that name (a killed run with the same process id, or a planted link) is
/// removed first: removing a link removes the link, not its target.
pub(crate) fn create_temp(path: &Path) -> std::io::Result<File> {
    let open = || {
        let mut o = OpenOptions::new();
        o.write(true).read(true).create_new(true);
        #[cfg(unix)]
        {
            use std::os::unix::fs::OpenOptionsExt;
            o.custom_flags(libc::O_NOFOLLOW | libc::O_CLOEXEC);
        }
        o.open(path)
    };
    match open() {
        Err(e) if e.kind() == ErrorKind::AlreadyExists => {
            std::fs::remove_file(path)?;
            open()
        }
        r => r,
    }
}

/// The components of a relative path inside a folder, or `None` for an
/// absolute path or one with `..` (it could leave the folder).
fn plain_components(rel: &Path) -> Option<Vec<&std::ffi::OsStr>> {
    rel.components()
        .filter(|c| !matches!(c, Component::CurDir))
        .map(|c| match c {
            Component::Normal(s) => Some(s),
            _ => None,
        })
        .collect()
}

/// The folder `root/rel`, created if missing, reached through real folders
/// only: an error naming the first component of `rel` that is a link (or
/// a file) instead of a folder. `root` itself is the user's choice and may
/// be a link.
pub(crate) fn real_dir(root: &Path, rel: &Path) -> std::io::Result<PathBuf> {
    let parts = plain_components(rel).ok_or_else(|| {
        Error::new(
            ErrorKind::InvalidInput,
            format!("{}: a folder inside {} was expected", rel.display(), root.display()),
        )
    })?;
    let mut at = root.to_path_buf();
    for part in parts {
        at.push(part);
        match std::fs::symlink_metadata(&at) {
            Ok(m) if m.is_dir() => {}
            Ok(m) => {
                let what = special_kind(&m.file_type()).unwrap_or("a file");
                return Err(Error::new(
                    ErrorKind::InvalidInput,
                    format!(
                        "{}: is {what}, not a folder; Septa writes into its output folder only through real folders (remove it)",
                        at.display()
                    ),
                ));
            }
            Err(e) if e.kind() == ErrorKind::NotFound => match std::fs::create_dir(&at) {
                Ok(()) => {}
                // made meanwhile by another thread of this run: check it again
                Err(e) if e.kind() == ErrorKind::AlreadyExists && at.symlink_metadata()?.is_dir() => {}
                Err(e) => return Err(Error::new(e.kind(), format!("{}: cannot create the folder: {e}", at.display()))),
            },
            Err(e) => return Err(Error::new(e.kind(), format!("{}: {e}", at.display()))),
        }
    }
    Ok(at)
}

/// Whether `root/rel` is reached from `root` through real folders only
/// (no component before the last is a link), so that removing it cannot
/// touch anything outside `root`. The last component may be anything: a
/// link there is removed itself.
pub(crate) fn inside(root: &Path, rel: &Path) -> bool {
    let Some(parts) = plain_components(rel) else { return false };
    let Some((_, dirs)) = parts.split_last() else { return false };
    let mut at = root.to_path_buf();
    dirs.iter().all(|d| {
        at.push(d);
        std::fs::symlink_metadata(&at).is_ok_and(|m| m.is_dir())
    })
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("septa-safe-write-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn links_and_special_files_are_refused() {
        let d = scratch("special");
        let out = d.join("elsewhere");
        std::fs::create_dir(&out).unwrap();
        std::fs::write(out.join("victim"), "keep").unwrap();
        std::os::unix::fs::symlink(out.join("victim"), d.join("link.ply")).unwrap();
        let fifo = d.join("fifo.ply");
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        for (p, what) in [(d.join("link.ply"), "symbolic link"), (fifo, "FIFO"), (out.clone(), "folder")] {
            let e = check_output_file(&p).unwrap_err().to_string();
            assert!(e.contains(what) && e.contains(p.to_str().unwrap()), "{e}");
        }
        check_output_file(&d.join("new.ply")).unwrap();
        std::fs::write(d.join("old.ply"), "x").unwrap();
        check_output_file(&d.join("old.ply")).unwrap();
        // A link planted at a temporary name is removed, never followed.
        std::os::unix::fs::symlink(out.join("victim"), d.join(".t.tmp1")).unwrap();
        drop(create_temp(&d.join(".t.tmp1")).unwrap());
        assert_eq!(std::fs::read_to_string(out.join("victim")).unwrap(), "keep");
        assert!(!std::fs::symlink_metadata(d.join(".t.tmp1")).unwrap().file_type().is_symlink());
        // Sub-folders: a link refused, a real one made and kept.
        std::os::unix::fs::symlink(&out, d.join("network")).unwrap();
        let e = real_dir(&d, Path::new("network")).unwrap_err().to_string();
        assert!(e.contains("network") && e.contains("symbolic link"), "{e}");
        assert_eq!(real_dir(&d, Path::new("viewer/a")).unwrap(), d.join("viewer/a"));
        assert!(real_dir(&d, Path::new("../x")).is_err());
        assert!(inside(&d, Path::new("viewer/a/f")) && inside(&d, Path::new("network")));
        assert!(!inside(&d, Path::new("network/victim")) && !inside(&d, Path::new("../elsewhere/victim")));
        let _ = std::fs::remove_dir_all(&d);
    }
}
