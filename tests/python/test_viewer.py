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
