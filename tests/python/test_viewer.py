import hashlib
import json

import septa
from conftest import FIXTURE, ROOT


def source_hash():
    """Same algorithm as viewer/build.mjs."""
    h = hashlib.sha256()
    src = ROOT / "viewer" / "src"
    for f in sorted(p.name for p in src.iterdir()):
        h.update(f.encode() + b"\0" + (src / f).read_bytes() + b"\0")
    lock = json.loads((ROOT / "viewer" / "package-lock.json").read_text())
    for pkg in ("three", "esbuild"):
        h.update(f"{pkg}@{lock['packages']['node_modules/' + pkg]['version']}\0".encode())
    return h.hexdigest()


def test_committed_bundle_built_from_current_sources():
    assert (ROOT / "viewer" / "dist" / "SOURCE_HASH").read_text().strip() == source_hash(), \
        "viewer/dist is stale: run `npm run build` in viewer/ and commit dist/"


def test_view_writes_self_contained_folder(tmp_path, fixture_net):
    index = septa.view(fixture_net, tmp_path / "v", open=False)
    assert index.name == "index.html" and index.exists()
    # The package embeds the same committed bundle as the command line.
    assert (tmp_path / "v" / "viewer.js").read_bytes() == (ROOT / "viewer" / "dist" / "viewer.js").read_bytes()
    data = (tmp_path / "v" / "data.js").read_text()
    payload = json.loads(data.removeprefix("window.__SEPTA_DATA = ").rstrip().rstrip(";"))
    assert len(payload["network"]["patches"]) == 4
    assert "https://" not in index.read_text()


def test_view_of_folder(tmp_path):
    import shutil

    shutil.copy(FIXTURE / "network.json", tmp_path / "network.json")
    index = septa.view(tmp_path, open=False)
    assert index == (tmp_path / "viewer" / "index.html").resolve()


def _data(folder):
    text = (folder / "data.js").read_text()
    return json.loads(text.removeprefix("window.__SEPTA_DATA = ").rstrip().rstrip(";"))


def test_python_and_command_line_write_the_same_viewer(tmp_path):
    # One writer: a folder viewed from Python and with `septa view` gives
    # the same three files, byte for byte.
    import shutil
    import subprocess

    from conftest import SEPTA, need

    need(SEPTA, "the septa binary (cargo build --release -p septa-cli)")
    for d in ("cli", "py"):
        (tmp_path / d).mkdir()
        shutil.copy(FIXTURE / "network.json", tmp_path / d / "network.json")
    subprocess.run([str(SEPTA), "view", str(tmp_path / "cli"), "--no-open", "--title", "t"], check=True,
                   capture_output=True)
    septa.view(tmp_path / "py", open=False, title="t")
    for name in ("index.html", "viewer.js", "data.js"):
        assert (tmp_path / "py" / "viewer" / name).read_bytes() == (tmp_path / "cli" / "viewer" / name).read_bytes()
    # A loaded Network gives the same page data as its folder.
    net = septa.load(tmp_path / "py")
    septa.view(net, tmp_path / "mem", open=False, title="t")
    assert _data(tmp_path / "mem")["network"]["faces"] == _data(tmp_path / "py" / "viewer")["network"]["faces"]
    assert "__SEPTA_DATA" in septa.viewer.inline_html(net)


def test_view_of_a_vtu_stream(tmp_path):
    # A stream written as .vtu (the meshio / ParaView form) is viewed like
    # the PLY one: before, `septa view` refused such a folder.
    spheres = [septa.shapes.sphere([0, 0, 0], 0.45), septa.shapes.sphere([0.31, 0, 0], 0.45)]
    for name in ("s.vtu", "s.ply"):
        (tmp_path / name[2:]).mkdir()
        septa.stream.stream_ply(spheres, tmp_path / name[2:] / name, grid=16, block=4)
        septa.view(tmp_path / name[2:], open=False)
    vtu, ply = _data(tmp_path / "vtu" / "viewer")["network"], _data(tmp_path / "ply" / "viewer")["network"]
    assert len(vtu["patches"]) == 4 and len(vtu["cells"]) == 4
    for k in ("points", "faces", "face_patch", "face_cells", "face_label", "patches", "cells"):
        assert vtu[k] == ply[k], k
    index = septa.view(tmp_path / "vtu" / "s.vtu", open=False)
    assert index == (tmp_path / "vtu" / "viewer" / "index.html").resolve()
