"""cells.vtu of `septa cut` read back by pyvista (VTK) and checked exactly by `septa cut FILE.vtu --verify`."""
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
SEPTA = ROOT / "target" / "release" / "septa"
pv = pytest.importorskip("pyvista")


def _icosphere_obj(path):
    s = pv.Icosphere(radius=1.0, nsub=2)
    faces = s.faces.reshape(-1, 4)[:, 1:]
    path.write_text("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in s.points.astype(float).tolist())
                    + "".join(f"f {a+1} {b+1} {c+1}\n" for a, b, c in faces.tolist()))
    return s


@pytest.mark.skipif(not SEPTA.exists(), reason="the command line is built by scripts/test.sh first")
def test_cells_vtu_reads_back_closed_cells_with_their_volumes(tmp_path):
    sphere = _icosphere_obj(tmp_path / "ball.obj")
    out = subprocess.run([str(SEPTA), "cut", str(tmp_path / "ball.obj"), "--random", "6", "--seed", "3",
                          "-o", str(tmp_path / "cut"), "--json", "--verify"], check=True, capture_output=True, text=True)
    info = json.loads(out.stdout.splitlines()[0])
    assert info["embedding"]["report"]["intersecting_pairs"] == 0
    assert info["verify_written_file"]["cells"] == info["cut_cells"]
    g = pv.read(tmp_path / "cut" / "cells.vtu")
    assert g.n_cells == info["cut_cells"]
    assert set(np.unique(g.celltypes)) == {42}  # VTK_POLYHEDRON
    vol = np.asarray(g.cell_data["volume"])
    assert np.all(vol > 0)
    for i in range(g.n_cells):
        surf = g.extract_cells([i]).extract_surface(algorithm="dataset_surface").triangulate()
        assert surf.n_open_edges == 0, i  # closed as VTK reads it
        assert abs(surf.volume - vol[i]) <= 1e-9 * abs(vol[i]) + 1e-15, i
    assert abs(vol.sum() - sphere.volume) < 1e-9
    # the file itself passes the exact check, and a corrupted copy does not
    ok = subprocess.run([str(SEPTA), "cut", str(tmp_path / "cut" / "cells.vtu"), "--verify"], capture_output=True)
    assert ok.returncode == 0
    g.points[0] = g.points[0] + 0.3 * (g.points.mean(axis=0) - g.points[0])
    bad = tmp_path / "bad.vtu"
    pv.UnstructuredGrid(g).save(bad, binary=False)
    res = subprocess.run([str(SEPTA), "cut", str(bad), "--verify"], capture_output=True, text=True)
    assert res.returncode != 0 and "violations" in res.stderr
