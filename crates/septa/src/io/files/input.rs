//! The one way every reader opens an input file (meshes, scenes, function
//! lists, tet meshes, `.npz`, label volumes, `.vtu` for `cut --verify`,
//! result folders):
//!
//! - **Regular files only.** A FIFO would block the run forever, a device
//!   such as `/dev/zero` would fill the memory; both (and folders, sockets)
//!   are refused with an error saying what the path is. A link to a regular
//!   file is followed (reading through a link touches nothing).
//! - **Pipes on purpose.** `-`, `/dev/stdin` and `/dev/fd/N` (what a shell's
//!   `<(...)` gives) are read once into memory, and a second read of the
//!   same name returns the same bytes (a reader that looks at a file twice,
//!   to tell a scene from a function list, sees one input).
//! - **A size cap.** Nothing larger than [`input_limit`] is read: the
//!   memory budget of [`crate::grid::memory`], or `SEPTA_MAX_INPUT`.
//!
//! Counts read from a file are then checked against the bytes it has left
//! before anything is reserved ([`check_count`]), so a header of a few
//! bytes cannot ask for terabytes.

use std::collections::HashMap;
use std::io::{Error, ErrorKind, Read};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// The largest input read into memory, in bytes: `SEPTA_MAX_INPUT` (bytes,
/// or with a `K`/`M`/`G` suffix) when set, else the memory budget.
pub fn input_limit() -> u64 {
    if let Some(b) = std::env::var("SEPTA_MAX_INPUT").ok().and_then(|s| crate::grid::memory::parse_size(&s)) {
        return b;
    }
    crate::grid::memory::budget().0
}

/// Whether `path` names a pipe given on purpose: standard input or an open
/// file descriptor of this process.
fn explicit_stream(path: &Path) -> bool {
    let s = path.to_string_lossy();
    s == "-"
        || s == "/dev/stdin"
        || s.strip_prefix("/dev/fd/")
            .or_else(|| s.strip_prefix("/proc/self/fd/"))
            .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
}

/// What `path` is when it is not a regular file, in words.
fn not_regular(meta: &std::fs::Metadata) -> Option<&'static str> {
    let ft = meta.file_type();
    if ft.is_file() {
        None
    } else if ft.is_dir() {
        Some("a folder")
    } else {
        Some(crate::io::files::safe_write::special_kind(&ft).unwrap_or("not a regular file"))
    }
}

fn too_large(size: u64, limit: u64) -> Error {
    Error::new(
        ErrorKind::InvalidData,
        format!(
            "{} is larger than the input limit of {} (the memory budget, or SEPTA_MAX_INPUT)",
            if size == u64::MAX { "the input".to_string() } else { format!("{size} bytes") },
            crate::grid::memory::human(limit)
        ),
    )
}

/// Reads at most `limit` bytes of `r`; an error if there are more.
fn read_capped(r: impl Read, limit: u64, hint: u64) -> std::io::Result<Vec<u8>> {
    let mut out = Vec::with_capacity(hint.min(limit).min(1 << 30) as usize);
    r.take(limit.saturating_add(1)).read_to_end(&mut out)?;
    if out.len() as u64 > limit {
        return Err(too_large(u64::MAX, limit));
    }
    Ok(out)
}

/// Pipes read so far, by name (see the module documentation).
fn streams() -> std::sync::MutexGuard<'static, HashMap<PathBuf, Arc<Vec<u8>>>> {
    static READ: std::sync::OnceLock<Mutex<HashMap<PathBuf, Arc<Vec<u8>>>>> = std::sync::OnceLock::new();
    READ.get_or_init(Mutex::default).lock().unwrap_or_else(|e| e.into_inner())
}

/// The bytes of the input file `path` (module documentation). Errors say
/// what is wrong without the path; callers name the file.
pub fn read_input(path: &Path) -> std::io::Result<Vec<u8>> {
    read_input_shared(path).map(|b| Arc::try_unwrap(b).unwrap_or_else(|b| (*b).clone()))
}

fn read_input_shared(path: &Path) -> std::io::Result<Arc<Vec<u8>>> {
    let limit = input_limit();
    if explicit_stream(path) {
        if let Some(b) = streams().get(path) {
            return Ok(b.clone());
        }
        let bytes = if path.as_os_str() == "-" {
            read_capped(std::io::stdin().lock(), limit, 0)?
        } else {
            read_capped(std::fs::File::open(path)?, limit, 0)?
        };
        let bytes = Arc::new(bytes);
        streams().insert(path.to_path_buf(), bytes.clone());
        return Ok(bytes);
    }
    let file = open_regular(path)?;
    let size = file.metadata()?.len();
    if size > limit {
        return Err(too_large(size, limit));
    }
    Ok(Arc::new(read_capped(file, limit, size)?))
}

/// [`read_input`] as UTF-8 text.
pub fn read_input_text(path: &Path) -> std::io::Result<String> {
    String::from_utf8(read_input(path)?).map_err(|e| {
        Error::new(
            ErrorKind::InvalidData,
            format!("not UTF-8 text (byte {} is not part of a character)", e.utf8_error().valid_up_to()),
        )
    })
}

/// Opens `path` for reading when it is a regular file (or a link to one):
/// the type is checked before opening (opening a FIFO would wait for a
/// writer) and again on the open file (the name could change meanwhile;
/// `O_NONBLOCK` keeps that open from waiting). For readers that stream a
/// file instead of reading it whole; they bound what they reserve by the
/// file's length.
pub fn open_regular(path: &Path) -> std::io::Result<std::fs::File> {
    if explicit_stream(path) {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            "a pipe cannot be read here: this input needs a regular file (it is read more than once)",
        ));
    }
    let refuse = |what: &str| {
        Error::new(
            ErrorKind::InvalidInput,
            format!("is {what}, not a regular file (Septa reads regular files; give `-` to read standard input)"),
        )
    };
    if let Some(what) = not_regular(&std::fs::metadata(path)?) {
        return Err(refuse(what));
    }
    let mut o = std::fs::OpenOptions::new();
    o.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        o.custom_flags(libc::O_NONBLOCK | libc::O_CLOEXEC);
    }
    let file = o.open(path)?;
    if let Some(what) = not_regular(&file.metadata()?) {
        return Err(refuse(what));
    }
    Ok(file)
}

/// Checks a count read from a file against the bytes left after it, before
/// anything is reserved: `count` items of at least `min_bytes` each must fit
/// in `left` bytes. The error names `what` and both numbers.
pub fn check_count(count: u64, min_bytes: u64, left: usize, what: &str) -> Result<usize, String> {
    match count.checked_mul(min_bytes.max(1)) {
        Some(need) if need <= left as u64 => Ok(count as usize),
        _ => Err(format!(
            "{what}: {count} declared, but the {left} bytes left in the file hold at most {}",
            left as u64 / min_bytes.max(1)
        )),
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    #[test]
    fn only_regular_files() {
        let d = std::env::temp_dir().join(format!("septa-input-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("a.json"), "[1]").unwrap();
        std::os::unix::fs::symlink(d.join("a.json"), d.join("link.json")).unwrap();
        assert_eq!(read_input(&d.join("link.json")).unwrap(), b"[1]");
        let fifo = d.join("fifo.json");
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        std::os::unix::fs::symlink(&fifo, d.join("to-fifo.json")).unwrap();
        for (p, what) in [(fifo, "FIFO"), (d.join("to-fifo.json"), "FIFO"), (d.clone(), "folder")] {
            let e = read_input(&p).unwrap_err().to_string();
            assert!(e.contains(what), "{e}");
        }
        assert!(check_count(10, 4, 40, "x").is_ok());
        let e = check_count(u64::MAX, 8, 40, "element vertex").unwrap_err();
        assert!(e.contains("element vertex") && e.contains("at most 5"), "{e}");
        assert!(explicit_stream(Path::new("/dev/fd/63")) && explicit_stream(Path::new("-")));
        assert!(!explicit_stream(Path::new("/dev/fd/")) && !explicit_stream(Path::new("/dev/zero")));
        let _ = std::fs::remove_dir_all(&d);
    }
}
