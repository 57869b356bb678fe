"""One answer per face: every format of every job (ia, mi, regions, labels,
cut, stream), read back by its readers (numpy, septa.load, meshio, pyvista,
trimesh, the viewer's page data, to_pyvista, Gmsh .msh), gives each face the
patch, labels and cells that network.npz gives it.

The VTK files write triangles as VTK_TRIANGLE, quads as VTK_QUAD and larger
polygons as VTK_POLYGON grouped by size (io/result_vtk.rs), so a row is not
the npz's face: the cell data ``face`` says which face each row is.
meshio then reads one block per size."""
import json
import subprocess
import time

import numpy as np
import pytest
import septa
from conftest import SEPTA, need

meshio = pytest.importorskip("meshio")
trimesh = pytest.importorskip("trimesh")
pv = pytest.importorskip("pyvista")


def _run(*args, fmt="all"):
    need(SEPTA, "the septa binary (cargo build --release -p septa-cli)")
    cmd = [str(SEPTA), *map(str, args), "--json"] + (["--format", fmt] if fmt else [])
    out = subprocess.run(cmd, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.splitlines()[0])


def _faces(offsets, indices):
    return [indices[a:b].tolist() for a, b in zip(offsets[:-1], offsets[1:])]


def _view_data(folder):
    """The network the viewer shows for `folder` (`septa view`'s data.js)."""
    subprocess.run([str(SEPTA), "view", str(folder), "--no-open"], check=True, capture_output=True)
    text = (folder / "viewer" / "data.js").read_text()
    return json.loads(text.removeprefix("window.__SEPTA_DATA = ").rstrip().rstrip(";"))["network"]


def _meshio_rows(m):
    """meshio's blocks, in file order: per row its vertex list, and its cell
    data concatenated; also checks the blocks are one per size, ascending."""
    kinds = [(c.type, c.data.shape[1]) for c in m.cells]
    assert kinds == sorted(set(kinds), key=lambda k: k[1]), kinds  # one block per size, ascending
    assert all(t == {3: "triangle", 4: "quad"}.get(n, "polygon") for t, n in kinds), kinds
    rows = [r.tolist() for c in m.cells for r in c.data]
    data = {k: np.concatenate([np.asarray(a).reshape(len(a), -1) for a in v]) for k, v in m.cell_data.items()}
    return rows, data


def _check_rows(rows, data, faces, ref, what):
    """Rows (vertex lists) with cell data `face`, `patch`, `labels`, `cells`
    against the reference faces and their arrays."""
    face = data["face"].ravel()
    assert np.array_equal(np.sort(face), np.arange(len(faces))), what  # every face once
    assert all(rows[i] == faces[f] for i, f in enumerate(face)), what
    for key, r in ref.items():
        assert np.array_equal(data[key].reshape(len(face), -1), r[face].reshape(len(face), -1)), (what, key)


def _check_network_folder(name, d):
    with np.load(d / "network.npz", allow_pickle=False) as f:
        z = dict(f)  # (an NpzFile reads a member again on every access)
    faces = _faces(z["offsets"], z["indices"])
    ref = {"patch": z["patch"], "labels": z["labels"], "cells": z["cells"]}
    nf = len(faces)

    # septa.load: the npz, and the JSON (what the viewer reads)
    for net in (septa.load(d), septa.load(d / "network.json")):
        assert _faces(net.offsets, net.indices) == faces
        for key, attr in (("patch", "face_patch"), ("labels", "face_label"), ("cells", "face_cells")):
            assert np.array_equal(getattr(net, attr), ref[key]), (name, attr)

    # the viewer's page data
    v = _view_data(d)
    assert v["faces"] == faces and v["face_patch"] == ref["patch"].tolist()
    assert v["face_cells"] == ref["cells"].tolist() and v["face_label"] == ref["labels"].tolist()

    # network.vtu by meshio and pyvista; the .vtm's patches and cells blocks
    rows, data = _meshio_rows(meshio.read(d / "network.vtu"))
    _check_rows(rows, data, faces, ref, (name, "vtu meshio"))
    sizes = {len(f) for f in faces}
    assert len(meshio.read(d / "network.vtu").cells) == len(sizes)
    g = pv.read(d / "network.vtu")
    prow = np.split(g.cell_connectivity, g.cell_offsets[1:-1])
    pdata = {k: np.asarray(g.cell_data[k]) for k in ("face", "patch", "labels", "cells")}
    _check_rows([r.tolist() for r in prow], pdata, faces, ref, (name, "vtu pyvista"))
    assert set(np.unique(g.celltypes)) <= {pv.CellType.TRIANGLE, pv.CellType.QUAD, pv.CellType.POLYGON}
    mb = pv.read(d / "network.vtm")
    p = mb["patches"]
    _check_rows([r.tolist() for r in np.split(p.cell_connectivity, p.cell_offsets[1:-1])],
                {k: np.asarray(p.cell_data[k]) for k in ("face", "patch", "labels", "cells")}, faces, ref,
                (name, "vtm patches"))
    # cells block: each row a face seen from one of its cells, facing out of it
    c = mb["cells"]
    crow = np.split(c.cell_connectivity, c.cell_offsets[1:-1])
    cface, ccell = np.asarray(c.cell_data["face"]), np.asarray(c.cell_data["cell"])
    assert len(crow) == int((z["cells"] >= 0).sum())
    for r, f, cell in zip(crow, cface, ccell):
        pos, neg = z["cells"][f]
        assert cell in (pos, neg)
        assert r.tolist() == (faces[f][::-1] if cell == pos and cell != neg else faces[f])
    assert np.array_equal(np.asarray(c.cell_data["patch"]), z["patch"][cface])
    rows, data = _meshio_rows(meshio.read(d / "network" / "cells.vtu"))
    assert np.array_equal(data["face"].ravel(), cface) and np.array_equal(data["cell"].ravel(), ccell)
    # to_pyvista: the file's blocks, rows and arrays
    mine = septa.load(d).to_pyvista()
    for block in ("patches", "cells"):
        assert np.array_equal(mine[block].cell_data["face"], mb[block].cell_data["face"]), block

    # PLY: per triangle its face, patch, labels, cells
    t = trimesh.load(d / "network.ply", process=False)
    raw = t.metadata["_ply_raw"]["face"]["data"]
    f = raw["face"].ravel()
    assert np.array_equal(raw["patch"].ravel(), z["patch"][f])
    for k in (0, 1):
        assert np.array_equal(raw[f"labels_{k}"].ravel(), z["labels"][f, k])
        assert np.array_equal(raw[f"cells_{k}"].ravel(), z["cells"][f, k])

    # OBJ: group p holds patch p's polygons, named as Network.patch_names()
    names = septa.load(d).patch_names()
    groups, group = {}, None
    for line in (d / "network.obj").read_text().splitlines():
        if line.startswith("g "):
            group = line[2:]
        elif line.startswith("f "):
            groups.setdefault(group, []).append([int(x) - 1 for x in line.split()[1:]])
    assert [g for g in groups] == [names[p] for p in range(len(names)) if (z["patch"] == p).any()]
    for p, gname in enumerate(names):
        assert groups.get(gname, []) == [faces[i] for i in np.flatnonzero(z["patch"] == p)], gname

    # Gmsh .msh (Python's save): physical surface p + 1 named as group p
    net = septa.load(d)
    net.save(d / "network.msh")
    m = meshio.read(d / "network.msh")
    tags = np.concatenate(m.cell_data["gmsh:physical"])
    assert np.array_equal(tags, z["patch"][net.triangle_face] + 1)
    assert {n: int(v[0]) for n, v in m.field_data.items()} == {n: p + 1 for p, n in enumerate(names)}
    return z


def _label_volume(tmp_path):
    vol = np.zeros((12, 12, 12), dtype=np.int64)
    vol[2:6, 2:8, 2:8] = 1
    vol[6:9, 2:8, 2:8] = 2
    vol[3:5, 3:5, 8:10] = 3
    np.save(tmp_path / "vol.npy", vol)
    (tmp_path / "names.json").write_text(json.dumps({"1": "liver", "2": "kidney", "3": "vessel"}))
    return tmp_path / "vol.npy"


def test_every_format_of_every_network_job_gives_the_npz_face_ids(tmp_path):
    vol = _label_volume(tmp_path)
    # named functions, small: the arrangement of a ball, a box and a plane
    scene = {"grid": {"resolution": 14, "bounds": [[-1, -1, -1], [1, 1, 1]]},
             "functions": [{"name": "ball", "type": "sphere", "center": [0.1, 0, 0], "radius": 0.6},
                           {"name": "slab", "type": "plane", "point": [0, 0, 0.2], "normal": [0, 0.3, 1]},
                           {"type": "sphere", "center": [-0.3, 0.2, 0], "radius": 0.4}]}
    (tmp_path / "scene.json").write_text(json.dumps(scene))
    jobs = {
        "ia": ["ia", tmp_path / "scene.json"],
        "mi": ["mi", "builtin:apollonius-18"],
        "regions": ["regions", "builtin:cad-part"],
        "labels": ["labels", vol, "--names", tmp_path / "names.json"],
    }
    for name, args in jobs.items():
        _run(*args, "-o", tmp_path / name)
        _check_network_folder(name, tmp_path / name)
    # names reach the groups: the scene's functions (ia; the unnamed one by
    # its ids), regions, labels
    ia = septa.load(tmp_path / "ia")
    assert {n.split("_", 2)[2] for n in ia.patch_names()} == {"ball", "slab", "labels_2_2"}
    assert septa.load(tmp_path / "regions").patch_names() == ["patch_0_outside_part"]
    assert "patch_0_0_liver" in septa.load(tmp_path / "labels").patch_names()


def test_meshio_reads_the_apollonius_result_in_one_block_per_polygon_size(tmp_path):
    """meshio.read of builtin:apollonius-18's network.vtu: one block per
    polygon size (triangles, quads, pentagons, hexagons: 4; it was 5,865
    runs of one size); the triangles write to an STL."""
    _run("mi", "builtin:apollonius-18", "-o", tmp_path / "a", fmt="npz,vtu")
    z = np.load(tmp_path / "a" / "network.npz")
    sizes = np.unique(np.diff(z["offsets"]))
    t0 = time.perf_counter()
    m = meshio.read(tmp_path / "a" / "network.vtu")
    print(f"meshio.read: {len(m.cells)} blocks in {time.perf_counter() - t0:.3f} s")
    assert [c.data.shape[1] for c in m.cells] == sizes.tolist()
    assert [c.type for c in m.cells][:2] == ["triangle", "quad"]
    assert len(m.cells) <= 4
    tri = meshio.Mesh(m.points, [m.cells[0]])
    assert tri.cells_dict["triangle"].shape == (int((np.diff(z["offsets"]) == 3).sum()), 3)
    meshio.write(tmp_path / "tri.stl", tri)
    assert len(trimesh.load(tmp_path / "tri.stl").faces) == len(m.cells[0].data)


def test_a_result_of_triangles_and_quads_has_cells_dict(tmp_path):
    """A label volume's walls are triangles and quads (voxel faces split
    between voxel centres): two blocks, so cells_dict works."""
    vol = _label_volume(tmp_path)
    _run("labels", vol, "-o", tmp_path / "l", fmt="npz,vtu")
    z = np.load(tmp_path / "l" / "network.npz")
    m = meshio.read(tmp_path / "l" / "network.vtu")
    sizes = set(np.diff(z["offsets"]).tolist())
    assert len(m.cells) == len(sizes)
    if sizes <= {3, 4}:
        d = m.cells_dict
        assert sum(len(v) for v in d.values()) == len(z["offsets"]) - 1


def test_stream_vtu_and_ply_give_one_answer(tmp_path):
    """`ia --stream`: the .vtu (grouped by size, `face` = the stream's polygon
    order) and the triangle PLY (in that order) hold the same polygons with
    the same arrays; `septa view` of the .vtu shows the PLY's faces."""
    runs = {}
    for d, name, extra in (("v", "s.vtu", []), ("p", "s.ply", []), ("t", "t.ply", ["--triangles"])):
        (tmp_path / d).mkdir()
        runs[d] = _run("ia", "builtin:sphere-with-hole", "--stream", tmp_path / d / name, *extra, fmt=None)
    nf = runs["v"]["faces"]
    m = meshio.read(tmp_path / "v" / "s.vtu")
    rows, data = _meshio_rows(m)
    face = data["face"].ravel()
    assert np.array_equal(np.sort(face), np.arange(nf))
    g = pv.read(tmp_path / "v" / "s.vtu")
    assert np.array_equal(np.asarray(g.cell_data["face"]), face)
    # the triangle PLY, per polygon in stream order
    t = trimesh.load(tmp_path / "t" / "t.ply", process=False)
    raw = t.metadata["_ply_raw"]["face"]["data"]
    sizes = np.array([len(r) for r in rows])
    by_face = np.empty(nf, dtype=np.int64)
    by_face[face] = sizes
    first_tri = np.concatenate([[0], np.cumsum(by_face - 2)[:-1]])
    for key in ("patch",):
        assert np.array_equal(raw[key].ravel()[first_tri[face]], data[key].ravel())
    for k in (0, 1):
        assert np.array_equal(raw[f"labels_{k}"].ravel()[first_tri[face]], data["labels"][:, k])
        assert np.array_equal(raw[f"cells_{k}"].ravel()[first_tri[face]], data["cells"][:, k])
    # the viewer: the same network from either stream file
    v, p = _view_data(tmp_path / "v"), _view_data(tmp_path / "p")
    for k in ("points", "faces", "face_patch", "face_cells", "face_label"):
        assert v[k] == p[k], k
    assert [v["faces"][f] for f in face] == rows


def test_cut_cells_give_one_answer(tmp_path):
    """`septa cut`: cells.vtu (meshio, pyvista), cells.obj and the viewer's
    page name each cut-cell as Python's cut_mesh does (same volumes)."""
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    obj = tmp_path / "tet.obj"
    obj.write_text("".join(f"v {a} {b} {c}\n" for a, b, c in v) + "".join(f"f {a+1} {b+1} {c+1}\n" for a, b, c in t))
    d = tmp_path / "cut"
    summary = _run("cut", obj, "--grid", 5, "-o", d, fmt=None)
    n = summary["cut_cells"]
    # --grid 5: five planes per axis from the box's min to its max
    planes = [[float(a == i) for i in range(3)] + [-x] for a in range(3) for x in (0, 0.25, 0.5, 0.75, 1)]
    py = septa.cut_mesh(v, t, planes)
    assert len(py.cell_volumes) == n
    m = meshio.read(d / "cells.vtu")
    ids = np.concatenate([np.asarray(a).ravel() for a in m.cell_data["cell_id"]])
    vols = np.concatenate([np.asarray(a).ravel() for a in m.cell_data["volume"]])
    assert np.array_equal(np.sort(ids), np.arange(n))
    assert np.allclose(vols, py.cell_volumes[ids], rtol=1e-12, atol=0)
    g = pv.read(d / "cells.vtu")
    assert np.array_equal(g.cell_data["cell_id"], ids)
    # cells.obj: group cell_<id> holds that cell's polygons (as Python's)
    # (by coordinates: the file numbers its points its own way)
    polys = py.cell_polygons()
    groups, group, pts = {}, None, []
    for line in (d / "cells.obj").read_text().splitlines():
        if line.startswith("v "):
            pts.append(tuple(float(x) for x in line.split()[1:4]))
        elif line.startswith("g "):
            group = line[2:]
        elif line.startswith("f "):
            groups.setdefault(group, []).append(sorted(pts[int(x) - 1] for x in line.split()[1:]))
    assert sorted(groups) == sorted(f"cell_{c}" for c in range(n))
    for c in range(n):
        mine = sorted(sorted(tuple(py.points[v]) for v in p) for p in polys[c])
        assert sorted(groups[f"cell_{c}"]) == mine, c
    # the viewer: patch = cell, one face per written polygon
    vd = _view_data(d)
    assert np.array_equal(np.bincount(vd["face_patch"], minlength=n), [len(p) for p in polys])
