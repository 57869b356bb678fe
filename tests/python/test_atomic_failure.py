"""Failure injection for the Python writers (architecture invariant 3):
``Network.save`` (.json .ply .obj), ``septa.viewer.write_viewer`` and
``septa.stream.stream_ply`` (the Rust streaming writer) are run in a child
process under a real I/O error, a file-size limit (RLIMIT_FSIZE, SIGXFSZ
ignored so that write(2) fails with EFBIG instead of killing the process).
Each must raise, leave the old file byte for byte, and leave no temporary
file. The Rust writers' own test is crates/septa/tests/io/atomic_failure.rs,
the CLI's crates/septa-cli/tests/atomic_failure.rs."""

import json
import subprocess
import sys
import textwrap

import pytest

resource = pytest.importorskip("resource")  # POSIX only; the CI runs on Linux

LIMIT = 64  # bytes: every new output below is larger

CHILD = textwrap.dedent("""
    import resource, signal, sys, json
    import septa, septa.viewer, septa.stream
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    what, target, fixture, spec = sys.argv[1:5]
    net = septa.load(fixture)
    resource.setrlimit(resource.RLIMIT_FSIZE, ({limit}, {limit}))
    try:
        if what == "viewer":
            septa.viewer.write_viewer(net, target)
        elif what == "stream":
            septa.stream.stream_ply(json.load(open(spec)), target, grid=16, mode="ia")
        else:
            net.save(target)
    except Exception as e:  # the test checks what was raised
        print(json.dumps({{"error": type(e).__name__, "errno": getattr(e, "errno", None), "message": str(e)}}))
        sys.exit(3)
    print(json.dumps({{"error": None}}))
""").format(limit=LIMIT)


def _listing(d):
    return sorted(p.relative_to(d).as_posix() for p in d.rglob("*") if p.is_file())


def _run(what, target, spec):
    from conftest import FIXTURE

    return subprocess.run([sys.executable, "-c", CHILD, what, str(target), str(FIXTURE), str(spec)],
                          capture_output=True, text=True)


@pytest.mark.parametrize("what", ["network.json", "walls.ply", "walls.obj", "viewer", "stream"])
def test_a_failing_write_leaves_the_old_file_and_no_temporary(tmp_path, what):
    from conftest import ROOT

    spec = ROOT / "data" / "specs" / "ia18.json"
    old = b"old file, complete\n" * 2  # smaller than LIMIT: written before the limit applies
    if what == "viewer":
        target = tmp_path / "viewer"
        target.mkdir()
        for name in ("index.html", "viewer.js", "data.js"):
            (target / name).write_bytes(old)
        check = [target / n for n in ("index.html", "viewer.js", "data.js")]
        folder = target
    else:
        target = tmp_path / ("s.ply" if what == "stream" else what)
        target.write_bytes(old)
        check = [target]
        folder = tmp_path
    before = _listing(folder)
    r = _run(what, target, spec)
    assert r.returncode == 3, f"expected an OSError, got rc {r.returncode}: {r.stdout} {r.stderr}"
    err = json.loads(r.stdout)
    # the injected failure (EFBIG), not another one, and as an OSError
    assert err["errno"] == 27 or "too large" in err["message"].lower(), err
    assert err["error"] in ("OSError", "InputError", "SeptaError") or "Error" in err["error"], err
    for p in check:
        assert p.read_bytes() == old, f"{p.name} changed by a failed write"
    after = _listing(folder)
    assert after == before, f"left behind: {sorted(set(after) - set(before))}"
