//! Nothing outside the output folder, nothing but regular files:
//! links inside an output folder, special files at an output path, and
//! special files or pipes as inputs. Every link and FIFO is made in a
//! temporary folder; no test touches a real device node.
#![cfg(unix)]
use std::os::unix::fs::{symlink, FileTypeExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-hostile-files-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_septa")).current_dir(dir).args(args).stdin(Stdio::null()).output().unwrap()
}

#[track_caller]
fn refused(dir: &Path, args: &[&str], needles: &[&str]) {
    let out = run(dir, args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: message lacks {n:?}: {err}");
    }
}

#[track_caller]
fn succeeds(dir: &Path, args: &[&str]) -> String {
    let out = run(dir, args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn mkfifo(p: &Path) {
    let c = std::ffi::CString::new(p.to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0, "mkfifo {}", p.display());
}

fn is_fifo(p: &Path) -> bool {
    std::fs::symlink_metadata(p).is_ok_and(|m| m.file_type().is_fifo())
}

fn is_link(p: &Path) -> bool {
    std::fs::symlink_metadata(p).is_ok_and(|m| m.file_type().is_symlink())
}

const SPHERE: &str = r#"[{"type":"sphere","center":[0.1,0.05,0.02],"radius":0.5}]"#;

const CUBE: &str = "v 0 0 0\nv 0 0 1\nv 0 1 0\nv 0 1 1\nv 1 0 0\nv 1 0 1\nv 1 1 0\nv 1 1 1\n\
f 2 4 1\nf 5 2 1\nf 1 4 3\nf 3 5 1\nf 2 8 4\nf 6 2 5\nf 6 8 2\nf 4 8 3\nf 7 5 3\nf 3 8 7\nf 7 6 5\nf 8 6 7\n";

/// A folder outside the output folder holding a file that must survive.
fn victim(d: &Path) -> PathBuf {
    let out = d.join("elsewhere");
    std::fs::create_dir_all(&out).unwrap();
    for name in ["patches.vtu", "victim.txt"] {
        std::fs::write(out.join(name), "keep").unwrap();
    }
    out
}

fn intact(elsewhere: &Path) {
    for name in ["patches.vtu", "victim.txt"] {
        assert_eq!(std::fs::read_to_string(elsewhere.join(name)).unwrap(), "keep", "{name} was touched");
    }
    let n = std::fs::read_dir(elsewhere).unwrap().count();
    assert_eq!(n, 2, "files were added outside the output folder");
}

#[test]
fn links_inside_the_output_folder_are_never_followed() {
    let d = scratch("links");
    std::fs::write(d.join("f.json"), SPHERE).unwrap();
    let elsewhere = victim(&d);
    // A multiblock piece folder that is a link out of the folder: refused
    // (was: the pieces written through it, overwriting elsewhere/patches.vtu).
    std::fs::create_dir_all(d.join("o")).unwrap();
    symlink("../elsewhere", d.join("o/network")).unwrap();
    refused(&d, &["ia", "f.json", "--grid", "6", "-o", "o", "--format", "vtm"], &["o/network", "symbolic link"]);
    intact(&elsewhere);
    assert!(is_link(&d.join("o/network")));
    // The viewer folder likewise.
    std::fs::create_dir_all(d.join("v")).unwrap();
    symlink("../elsewhere", d.join("v/viewer")).unwrap();
    succeeds(&d, &["ia", "f.json", "--grid", "6", "-o", "v", "--format", "json"]);
    refused(&d, &["view", "v", "--no-open"], &["viewer", "symbolic link"]);
    intact(&elsewhere);
    // A manifest listing a file through a linked folder: the stale-file
    // clean-up leaves it (was: elsewhere/victim.txt deleted).
    std::fs::create_dir_all(d.join("m")).unwrap();
    symlink("../elsewhere", d.join("m/sub")).unwrap();
    let manifest = r#"{"septa":"0","job":"ia","files":[{"name":"sub/victim.txt","bytes":4},{"name":"network/patches.vtu","bytes":4}]}"#;
    std::fs::write(d.join("m/manifest.json"), manifest).unwrap();
    symlink("../elsewhere", d.join("m/network")).unwrap();
    succeeds(&d, &["ia", "f.json", "--grid", "6", "-o", "m", "--format", "json"]);
    intact(&elsewhere);
    // A link planted at the lock file's name is not followed either.
    std::fs::create_dir_all(d.join("l")).unwrap();
    symlink("../elsewhere/victim.txt", d.join("l/.septa.lock")).unwrap();
    refused(&d, &["ia", "f.json", "--grid", "6", "-o", "l"], &["l"]);
    intact(&elsewhere);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn special_files_and_links_are_never_replaced_by_outputs() {
    let d = scratch("outputs");
    std::fs::write(d.join("f.json"), SPHERE).unwrap();
    let elsewhere = victim(&d);
    mkfifo(&d.join("fifo.ply"));
    symlink("elsewhere/victim.txt", d.join("link.ply")).unwrap();
    // --stream onto a FIFO or a link: refused before the run, both left as they were.
    for (out, check) in [("fifo.ply", is_fifo as fn(&Path) -> bool), ("link.ply", is_link)] {
        refused(&d, &["ia", "f.json", "--grid", "6", "--stream", out], &[out]);
        assert!(check(&d.join(out)), "{out} was replaced");
    }
    // The topology file beside the stream likewise.
    mkfifo(&d.join("s.topology.json"));
    refused(&d, &["ia", "f.json", "--grid", "6", "--stream", "s.ply"], &["s.topology.json", "FIFO"]);
    assert!(is_fifo(&d.join("s.topology.json")) && !d.join("s.ply").exists());
    // A file of an output folder that is a FIFO or a link: refused, kept.
    std::fs::create_dir_all(d.join("f")).unwrap();
    mkfifo(&d.join("f/network.json"));
    refused(&d, &["ia", "f.json", "--grid", "6", "-o", "f", "--format", "json"], &["f/network.json", "FIFO"]);
    assert!(is_fifo(&d.join("f/network.json")));
    // Nothing else was refused: a plain output folder beside them.
    succeeds(&d, &["ia", "f.json", "--grid", "6", "-o", "ok", "--format", "json"]);
    intact(&elsewhere);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn inputs_must_be_regular_files_or_a_pipe_on_purpose() {
    let d = scratch("inputs");
    std::fs::write(d.join("f.json"), SPHERE).unwrap();
    std::fs::write(d.join("cube.obj"), CUBE).unwrap();
    mkfifo(&d.join("fifo.json"));
    mkfifo(&d.join("fifo.obj"));
    symlink("fifo.obj", d.join("to-fifo.obj")).unwrap();
    std::fs::create_dir_all(d.join("folder.json")).unwrap();
    // FIFOs (directly or through a link) and folders: refused at once
    // (was: a FIFO blocked forever, /dev/zero grew until killed).
    refused(&d, &["ia", "fifo.json", "--grid", "4", "-o", "o"], &["fifo.json", "FIFO"]);
    refused(&d, &["cut", "fifo.obj", "--grid", "2", "-o", "c"], &["fifo.obj", "FIFO"]);
    refused(&d, &["cut", "to-fifo.obj", "--grid", "2", "-o", "c"], &["to-fifo.obj", "FIFO"]);
    refused(&d, &["ia", "folder.json", "--grid", "4", "-o", "o"], &["folder.json", "folder"]);
    // A scene's mesh primitive and a result folder's network.json.
    let scene =
        r#"{"grid":{"resolution":4,"bounds":[[-1,-1,-1],[1,1,1]]},"functions":[{"type":"mesh","path":"fifo.obj"}]}"#;
    std::fs::write(d.join("scene.json"), scene).unwrap();
    refused(&d, &["ia", "scene.json", "-o", "o"], &["fifo.obj", "FIFO"]);
    std::fs::create_dir_all(d.join("r")).unwrap();
    mkfifo(&d.join("r/network.json"));
    refused(&d, &["view", "r", "--no-open"], &["network.json", "FIFO"]);
    // A size cap: SEPTA_MAX_INPUT below the file's size.
    let out = Command::new(env!("CARGO_BIN_EXE_septa"))
        .current_dir(&d)
        .args(["cut", "cube.obj", "--grid", "2", "-o", "c"])
        .env("SEPTA_MAX_INPUT", "100")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("cube.obj") && err.contains("input limit"), "{err}");
    assert!(!d.join("o").exists() && !d.join("c").exists());
    let _ = std::fs::remove_dir_all(&d);
}

/// `cat scene | septa ia /dev/stdin` (and `-`): the input is read once
/// (was: "EOF while parsing", the scene being read a second time).
#[test]
fn a_scene_on_standard_input_is_read_once() {
    let d = scratch("stdin");
    let scene = r#"{"grid":{"resolution":6,"bounds":[[-1,-1,-1],[1,1,1]]},"functions":[{"type":"sphere","center":[0,0,0],"radius":0.5}]}"#;
    std::fs::write(d.join("s.json"), scene).unwrap();
    let want = succeeds(&d, &["ia", "s.json", "--no-output", "--json"]);
    let count = |s: &str| serde_json::from_str::<serde_json::Value>(s).unwrap()["faces"].clone();
    for (cmd, input) in [("ia", "/dev/stdin"), ("ia", "-"), ("regions", "/dev/stdin")] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_septa"))
            .current_dir(&d)
            .args(if cmd == "ia" {
                vec![cmd, input, "--no-output", "--json"]
            } else {
                vec![cmd, input, "-o", "r", "--json"]
            })
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        use std::io::Write;
        child.stdin.take().unwrap().write_all(scene.as_bytes()).unwrap();
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{cmd} {input}: {err}");
        if cmd == "ia" {
            assert_eq!(count(&String::from_utf8_lossy(&out.stdout)), count(&want), "{input}");
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// `ulimit -f`: a write past the limit is an error naming the final file
/// and saying "File too large" (was: SIGXFSZ killed the run silently and
/// left a staged file); nothing hidden is left behind.
#[test]
fn a_file_size_limit_is_an_error_naming_the_file() {
    use std::os::unix::process::CommandExt;
    let d = scratch("fsize");
    std::fs::write(d.join("f.json"), SPHERE).unwrap();
    let mut c = Command::new(env!("CARGO_BIN_EXE_septa"));
    c.current_dir(&d).args(["ia", "f.json", "--grid", "12", "-o", "o", "--format", "json"]);
    // SAFETY: only async-signal-safe calls between fork and exec.
    unsafe {
        c.pre_exec(|| {
            let lim = libc::rlimit { rlim_cur: 4096, rlim_max: 4096 };
            libc::setrlimit(libc::RLIMIT_FSIZE, &lim);
            Ok(())
        });
    }
    let out = c.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{:?} {err}", out.status);
    assert!(err.contains("File too large") && err.contains("network.json") && !err.contains("staged"), "{err}");
    let hidden: Vec<String> = std::fs::read_dir(d.join("o"))
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp") || n.contains(".staged"))
        .collect();
    assert!(hidden.is_empty(), "{hidden:?}");
    let _ = std::fs::remove_dir_all(&d);
}
