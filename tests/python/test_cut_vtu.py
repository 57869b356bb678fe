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
    # a vertex sent to the far side of the ball: its faces then cross the ball and every
    # cell between (moving it a little inward could leave every cell valid)
    g.points[0] = 2.0 * g.points.mean(axis=0) - g.points[0]
    bad = tmp_path / "bad.vtu"
    pv.UnstructuredGrid(g).save(bad, binary=False)
    res = subprocess.run([str(SEPTA), "cut", str(bad), "--verify"], capture_output=True, text=True)
    assert res.returncode != 0 and "violations" in res.stderr


def _polyhedron_volume(points, faces):
    """Volume of a closed polyhedron given by outward polygons (fans from
    each polygon's first point; divergence theorem)."""
    v = 0.0
    for f in faces:
        p = points[np.asarray(f)]
        v += sum(np.dot(p[0], np.cross(p[i], p[i + 1])) for i in range(1, len(p) - 1))
    return v / 6.0


@pytest.mark.skipif(not SEPTA.exists(), reason="the command line is built by scripts/test.sh first")
def test_cells_vtu_reads_in_meshio_with_cell_data_on_the_right_cells(tmp_path):
    """meshio groups polyhedra by point count: the cube cut by 5 random
    planes (cells of 4 to 13 points, in an order meshio used to refuse with
    'Incompatible cell data') reads with every row's `volume` that of the
    polyhedron in that row, and `cell_id` naming each cut-cell once."""
    from conftest import SHARED, need
    meshio = pytest.importorskip("meshio")
    cube = need(SHARED / "meshes" / "cube.obj", "the shared meshes")
    out = subprocess.run([str(SEPTA), "cut", str(cube), "--random", "5", "--seed", "3", "-o", str(tmp_path / "cut"),
                          "--json"], check=True, capture_output=True, text=True)
    n = json.loads(out.stdout.splitlines()[0])["cut_cells"]
    m = meshio.read(tmp_path / "cut" / "cells.vtu")
    assert sum(len(b.data) for b in m.cells) == n and len(m.cells) > 1
    counts = [int(b.type[len("polyhedron"):]) for b in m.cells]
    assert counts == sorted(counts)
    ids = np.concatenate(m.cell_data["cell_id"])
    assert np.array_equal(np.sort(ids), np.arange(n))
    vols = np.concatenate(m.cell_data["volume"])
    rows = [c for b in m.cells for c in b.data]
    for b, k in zip(m.cells, counts):
        assert all(len(np.unique(np.concatenate(c))) == k for c in b.data)
    for c, v in zip(rows, vols):
        assert v > 0 and abs(_polyhedron_volume(m.points, c) - v) <= 1e-12, (v, _polyhedron_volume(m.points, c))
    # VTK reads the same file in its row order, cell_id mapping rows to cells
    g = pv.read(tmp_path / "cut" / "cells.vtu")
    assert g.n_cells == n and np.array_equal(np.asarray(g.cell_data["cell_id"]), ids)
    assert np.array_equal(np.asarray(g.cell_data["volume"]), vols)
    # cell_id names the cut-cell: cells.obj's group cell_<id> has the same volume
    verts, faces, group = [], {}, None
    for line in (tmp_path / "cut" / "cells.obj").read_text().splitlines():
        w = line.split()
        if w and w[0] == "v":
            verts.append([float(x) for x in w[1:4]])
        elif w and w[0] == "g":
            group = int(w[1][len("cell_"):])
        elif w and w[0] == "f":
            faces.setdefault(group, []).append([int(x.split("/")[0]) - 1 for x in w[1:]])
    verts = np.asarray(verts)
    assert sorted(faces) == list(range(n))
    for i, v in zip(ids, vols):
        assert abs(_polyhedron_volume(verts, faces[i]) - v) <= 1e-9, i
