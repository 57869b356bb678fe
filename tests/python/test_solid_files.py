"""`--format stl` (and `solid.obj`, `solid.ply`): one closed, outward file
per closed region (label, cell) in OUT/regions/, named by its name; read
back watertight by trimesh after the float32 round trip, volumes equal to
the result's cell_volume, and the same surfaces as Python's save_regions."""
import json
import subprocess

import numpy as np
import pytest
import septa
from conftest import SEPTA, need

trimesh = pytest.importorskip("trimesh")


def _run(*args):
    need(SEPTA, "the septa binary (cargo build --release -p septa-cli)")
    out = subprocess.run([str(SEPTA), *map(str, args), "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.splitlines()[0])


def _check_folder(d, expect):
    """Every file of d/regions/ watertight, outward, of its cell's volume."""
    net = septa.load(d)
    stems = {p.stem for p in (d / "regions").glob("*.stl")}
    assert stems == set(expect), sorted(stems)
    ids = [int(c["label"][0]) for c in net.cells] if net.mode == "regions" else list(range(len(net.cells)))
    for stem, rid in expect.items():
        m = trimesh.load(d / "regions" / f"{stem}.stl")  # merges the corners
        assert m.is_watertight and m.is_winding_consistent, stem
        vol = net.cell_volume[ids.index(rid)]
        assert m.volume > 0 and m.volume == pytest.approx(vol, rel=1e-5), stem
        # the same surface as Python's float32 one
        v, t = net.region(rid, dtype=np.float32)
        assert len(m.faces) == len(t) and len(m.vertices) == len(v), stem
        for ext in ("obj", "ply"):
            s = trimesh.load(d / "regions" / f"{stem}.{ext}", process=False, force="mesh")
            v64, t64 = net.region(rid)
            assert np.array_equal(s.vertices, v64) and np.array_equal(s.faces, t64), (stem, ext)
    return net


def test_regions_and_labels_write_one_solid_per_closed_region(tmp_path):
    _run("regions", "builtin:cad-part", "-o", tmp_path / "cad", "--format", "npz,stl,solid.obj,solid.ply")
    net = _check_folder(tmp_path / "cad", {"part": 1})  # the outside reaches the box: no file
    # Python's save_regions: the same names and surfaces
    written = net.save_regions(tmp_path / "py")
    assert {rid: p.name for rid, p in written.items()} == {1: "part.stl"}

    vol = np.zeros((12, 12, 12), dtype=np.int64)
    vol[2:6, 2:8, 2:8] = 5
    vol[6:9, 2:8, 2:8] = 9
    np.save(tmp_path / "vol.npy", vol)
    (tmp_path / "names.json").write_text(json.dumps({"5": "liver", "9": "kidney"}))
    _run("labels", tmp_path / "vol.npy", "--names", tmp_path / "names.json", "-o", tmp_path / "lab",
         "--format", "npz,stl,solid.obj,solid.ply")
    net = _check_folder(tmp_path / "lab", {"liver": 5, "kidney": 9})
    # labels are not their place among the regions: region 9 is the third
    assert [int(c["label"][0]) for c in net.cells] == [0, 5, 9]


def test_ia_writes_the_closed_cells(tmp_path):
    """Two overlapping balls: their lens and their two other parts are
    closed cells (cell_<c>.stl); the cell around them reaches the box."""
    scene = {"grid": {"resolution": 20, "bounds": [[0, 0, 0], [1, 1, 1]]},
             "functions": [{"type": "sphere", "center": [0.5, 0.5, 0.5], "radius": 0.3},
                           {"type": "sphere", "center": [0.62, 0.5, 0.5], "radius": 0.25}]}
    (tmp_path / "s.json").write_text(json.dumps(scene))
    d = tmp_path / "ia"
    _run("ia", tmp_path / "s.json", "-o", d, "--format", "npz,stl")
    net = septa.load(d)
    closed = sorted(int(p.stem.removeprefix("cell_")) for p in (d / "regions").glob("*.stl"))
    assert len(closed) == 3 and len(net.cells) == 4
    for c in closed:
        m = trimesh.load(d / "regions" / f"cell_{c}.stl")
        assert m.is_watertight and m.volume == pytest.approx(net.cell_volume[c], rel=1e-5)
    (outside,) = set(range(len(net.cells))) - set(closed)
    with pytest.raises(septa.InputError, match="box"):
        net.region(outside)
