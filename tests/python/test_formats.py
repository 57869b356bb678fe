"""Every format from every command, read back by meshio, trimesh and pyvista.

One vocabulary everywhere (crates/septa/src/io/writers/result.rs): per polygon
``patch``, ``labels`` (2 components), ``cells`` (2 components); PLY splits
the pairs into ``labels_0``/``labels_1`` and ``cells_0``/``cells_1``; chains
and corners are line and vertex cells. The reference for every array is
``network.npz`` (numpy alone), itself checked against the command's own
``--json`` counts.
"""
import json
import subprocess

import numpy as np
import pytest
import septa
from conftest import ROOT

SEPTA = ROOT / "target" / "release" / "septa"
meshio = pytest.importorskip("meshio")
trimesh = pytest.importorskip("trimesh")
pv = pytest.importorskip("pyvista")


def _run(*args):
    if not SEPTA.exists():
        pytest.skip("target/release/septa not built (scripts/test.sh builds it)")
    out = subprocess.run([str(SEPTA), *map(str, args), "--format", "all", "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def _run_plain(*args):
    """A command with --json and no --format (cut writes its one set of files)."""
    if not SEPTA.exists():
        pytest.skip("target/release/septa not built (scripts/test.sh builds it)")
    out = subprocess.run([str(SEPTA), *map(str, args), "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.splitlines()[0])


def _jobs(tmp_path):
    """(name, folder, --json) of each command on a small input."""
    vol = np.zeros((10, 10, 10), dtype=np.int64)
    vol[2:6, 2:7, 2:7] = 1
    vol[6:8, 2:7, 2:7] = 2
    np.save(tmp_path / "vol.npy", vol)
    jobs = [
        ("ia", ["ia", "builtin:cad-part"]),
        ("mi", ["mi", "builtin:apollonius-18"]),
        ("regions", ["regions", "builtin:sphere-plane-hole"]),
        ("labels", ["labels", tmp_path / "vol.npy"]),
    ]
    return [(name, tmp_path / name, _run(*args, "-o", tmp_path / name)) for name, args in jobs]


def _cat(mesh, name):
    """A meshio cell-data array over all cell blocks (meshio splits polygons by size)."""
    return np.concatenate([np.asarray(a).reshape(len(a), -1) for a in mesh.cell_data[name]])


def _check_folder(name, d, summary):
    z = np.load(d / "network.npz", allow_pickle=False)
    meta = json.loads(str(z["meta"]))
    nf = len(z["offsets"]) - 1
    tri = np.diff(z["offsets"]) - 2
    ntri = int(tri.sum())
    nchain_edges = int((np.diff(z["chain_offsets"]) - 1).clip(min=0).sum())
    face_of_tri = np.repeat(np.arange(nf), tri)
    counts = summary["network"] if name in ("regions", "labels") else summary
    if name in ("ia", "mi"):
        assert nf == counts["faces"] and len(z["points"]) == counts["vertices"]
        assert len(z["patch_labels"]) == counts["patches"] and len(z["cell_labels"]) == counts["cells"]
        assert len(z["chain_offsets"]) - 1 == counts["chains"] and len(z["corners"]) == counts["corners"]
    else:
        assert nf == summary["faces"] and len(z["patch_labels"]) == len(summary["surfaces"])
        assert len(z["chain_offsets"]) - 1 == len(summary["curves"])
    assert meta["mode"] == ("regions" if name in ("regions", "labels") else name)
    # Every polygon's labels are its patch's labels; cells are real cells.
    assert np.array_equal(z["patch_labels"][z["patch"]], z["labels"])
    assert z["cells"].max() < len(z["cell_labels"])

    # VTU: meshio and pyvista, polygons with patch, labels, cells; rows
    # grouped by size, `face` their face in the npz (test_face_ids.py).
    m = meshio.read(d / "network.vtu")
    assert sum(len(c.data) for c in m.cells) == nf
    face = _cat(m, "face").ravel()
    assert np.array_equal(np.sort(face), np.arange(nf))
    for key, ref in (("patch", z["patch"]), ("labels", z["labels"]), ("cells", z["cells"])):
        assert np.array_equal(_cat(m, key).reshape(ref.shape), ref[face]), key
    g = pv.read(d / "network.vtu")
    assert g.n_cells == nf and g.n_points == len(z["points"])
    assert np.array_equal(g.cell_data["face"], face)
    assert np.array_equal(g.cell_data["labels"], z["labels"][face]) and np.array_equal(g.cell_data["cells"], z["cells"][face])

    # PLY: trimesh reads every per-face array; pyvista the triangles and colours.
    t = trimesh.load(d / "network.ply", process=False)
    assert len(t.faces) == ntri and len(t.vertices) == len(z["points"])
    raw = t.metadata["_ply_raw"]["face"]["data"]
    assert np.array_equal(raw["face"].ravel(), face_of_tri)
    assert np.array_equal(raw["patch"].ravel(), z["patch"][face_of_tri])
    for k in (0, 1):
        assert np.array_equal(raw[f"labels_{k}"].ravel(), z["labels"][face_of_tri, k])
        assert np.array_equal(raw[f"cells_{k}"].ravel(), z["cells"][face_of_tri, k])
    assert pv.read(d / "network.ply").n_cells == ntri
    # plain.ply: the triangles only, which meshio 5.3 can read (and the others).
    m = meshio.read(d / "network.plain.ply")
    assert np.array_equal(m.cells_dict["triangle"], t.faces)
    assert len(trimesh.load(d / "network.plain.ply", process=False).faces) == ntri
    assert pv.read(d / "network.plain.ply").n_cells == ntri

    # OBJ: the polygons (meshio: one group id per patch), chains as l, corners as p.
    m = meshio.read(d / "network.obj")
    assert sum(len(c.data) for c in m.cells) == nf
    groups = np.concatenate(m.cell_data["obj:group_ids"])
    assert np.array_equal(np.sort(groups), np.sort(z["patch"]))  # group p holds patch p's polygons
    t = trimesh.load(d / "network.obj", process=False, force="mesh", group_material=False, split_object=False)
    assert len(t.faces) == ntri
    nchains = len(z["chain_offsets"]) - 1
    assert pv.read(d / "network.obj").n_cells == nf + nchains + (1 if len(z["corners"]) else 0)

    # VTM: the four blocks, with the same arrays; each piece also read by meshio.
    mb = pv.read(d / "network.vtm")
    assert np.array_equal(mb["patches"].cell_data["face"], face)
    assert np.array_equal(mb["patches"].cell_data["labels"], z["labels"][face])
    assert np.array_equal(mb["patches"].cell_data["patch"], z["patch"][face])
    if nchains:
        assert mb["chains"].n_cells == nchain_edges
        assert np.array_equal(np.bincount(mb["chains"].cell_data["chain"], minlength=nchains),
                              np.diff(z["chain_offsets"]) - 1)
        assert meshio.read(d / "network" / "chains.vtu").cells_dict["line"].shape == (nchain_edges, 2)
    if len(z["corners"]):
        assert mb["corners"].n_cells == len(z["corners"])
        assert np.array_equal(meshio.read(d / "network" / "corners.vtu").cells_dict["vertex"].ravel(), z["corners"])
    both = int((z["cells"] >= 0).sum())
    assert mb["cells"].n_cells == both
    assert np.array_equal(np.sort(mb["cells"].cell_data["cell"]), np.sort(z["cells"][z["cells"] >= 0]))
    assert sum(len(c.data) for c in meshio.read(d / "network" / "cells.vtu").cells) == both

    # septa.load reads the npz and gives the same arrays as the JSON.
    a, b = septa.load(d), septa.load(d / "network.json")
    assert a.source.name == "network.npz"
    for key in ("points", "offsets", "indices", "face_patch", "patch_labels", "corners"):
        assert np.array_equal(getattr(a, key), getattr(b, key)), key
    assert [c.tolist() for c in a.chains] == [c.tolist() for c in b.chains]
    # Per-face ids: the JSON (what the viewer reads) says what the npz says,
    # for region and label results too (cells index `cells`, the regions).
    assert np.array_equal(a.face_label, b.face_label) and np.array_equal(a.face_cells, b.face_cells)
    assert np.array_equal(b.face_label, z["labels"]) and np.array_equal(b.face_cells, z["cells"])
    assert a.cells == b.cells and [s.tolist() for s in a.shells] == [s.tolist() for s in b.shells]
    if name in ("regions", "labels"):
        # each face's cells are the regions of its labels (lesser first, the positive side)
        region = np.array([c["label"][0] for c in b.cells])
        assert np.array_equal(region[b.face_cells], b.face_label)
    return z


def _check_surfaces_obj(d, z):
    """regions/labels surfaces.obj: a group per surface (its polygons) and
    per curve (its `l` lines), read by all three."""
    nf, nchains = len(z["offsets"]) - 1, len(z["chain_offsets"]) - 1
    m = meshio.read(d / "surfaces.obj")
    assert sum(len(c.data) for c in m.cells) == nf  # (meshio keeps the faces only)
    groups = np.concatenate(m.cell_data["obj:group_ids"])
    assert len(np.unique(groups)) == len(z["patch_labels"])  # one group per surface
    t = trimesh.load(d / "surfaces.obj", process=False, force="mesh", group_material=False, split_object=False)
    assert len(t.faces) == int((np.diff(z["offsets"]) - 2).sum())  # the polygons as triangles
    assert pv.read(d / "surfaces.obj").n_cells == nf + nchains


def _check_stream(tmp_path):
    """`ia --stream`: the PLY (trimesh with --triangles, pyvista) and the .vtu
    (meshio, pyvista) hold the same polygons, in the same order, with the
    same arrays; counts are the command's and the topology file's."""
    d = tmp_path / "stream"
    d.mkdir()
    runs = {}
    for name, extra in (("s.ply", []), ("t.ply", ["--triangles"]), ("s.vtu", [])):
        runs[name] = _run_plain("ia", "builtin:sphere-with-hole", "--stream", d / name, *extra)
    nf, nv = runs["s.vtu"]["faces"], runs["s.vtu"]["vertices"]
    assert all(r["faces"] == nf and r["vertices"] == nv for r in runs.values())
    topo = json.loads((d / "s.topology.json").read_text())
    m = meshio.read(d / "s.vtu")
    assert len(m.points) == nv and sum(len(c.data) for c in m.cells) == nf
    g = pv.read(d / "s.vtu")
    assert g.n_cells == nf and g.n_points == nv
    labels, cells, patch = (np.asarray(g.cell_data[k]) for k in ("labels", "cells", "patch"))
    assert labels.shape == (nf, 2) and cells.shape == (nf, 2)
    # meshio reads one block per polygon size, in file order.
    for key, ref in (("patch", patch), ("labels", labels), ("cells", cells), ("block", g.cell_data["block"])):
        assert np.array_equal(_cat(m, key).reshape(nf, -1), np.asarray(ref).reshape(nf, -1)), key
    assert np.allclose(m.points, g.points)
    # Every face has its patch and both cells (the topology's counts); IA labels are the function twice.
    assert np.array_equal(np.bincount(patch), [p["faces"] for p in topo["patches"]])
    assert cells.min() >= 0 and cells.max() == topo["counts"]["cells"] - 1
    assert np.all(labels[:, 0] == labels[:, 1])
    # The PLY triangle fans, read by trimesh: the same arrays per polygon
    # (the .vtu's rows grouped by size: `face` is the polygon's place in the PLY).
    t = trimesh.load(d / "t.ply", process=False)
    face = np.asarray(g.cell_data["face"])
    assert np.array_equal(np.sort(face), np.arange(nf))
    back = np.argsort(face)  # stream order
    labels, cells, patch = labels[back], cells[back], patch[back]
    sizes = np.diff(g.cell_offsets)[back]
    of_tri = np.repeat(np.arange(nf), sizes - 2)
    assert len(t.faces) == len(of_tri) and len(t.vertices) == nv
    raw = t.metadata["_ply_raw"]["face"]["data"]
    assert np.array_equal(raw["patch"].ravel(), patch[of_tri])
    for k in (0, 1):
        assert np.array_equal(raw[f"labels_{k}"].ravel(), labels[of_tri, k])
        assert np.array_equal(raw[f"cells_{k}"].ravel(), cells[of_tri, k])
    assert np.allclose(t.vertices, g.points)
    # pyvista reads both PLYs' geometry (VTK's PLY reader keeps no face properties).
    assert pv.read(d / "s.ply").n_cells == nf and pv.read(d / "t.ply").n_cells == len(of_tri)


def _check_cut(tmp_path):
    """`septa cut`: cells.vtu (polyhedra) read by meshio and pyvista with
    cell_id and volume; cells.obj by all three (one group per cell)."""
    # A corner tetrahedron cut by 5 planes per axis at exact quarters: 20
    # cells (the cubes with i + j + k <= 3).
    obj = tmp_path / "tet.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    d = tmp_path / "cut"
    summary = _run_plain("cut", obj, "--grid", 5, "-o", d)
    n = summary["cut_cells"]
    assert n == 20
    m = meshio.read(d / "cells.vtu")
    assert sum(len(c.data) for c in m.cells) == n
    ids = np.concatenate([np.asarray(a).ravel() for a in m.cell_data["cell_id"]])
    assert np.array_equal(np.sort(ids), np.arange(n))
    vols = np.concatenate([np.asarray(a).ravel() for a in m.cell_data["volume"]])
    assert np.all(vols > 0)
    g = pv.read(d / "cells.vtu")
    # the same rows as meshio's blocks (cells by point count), cell_id naming each cut-cell
    assert g.n_cells == n and np.array_equal(g.cell_data["cell_id"], ids)
    assert np.array_equal(g.cell_data["volume"], vols)
    o = meshio.read(d / "cells.obj")
    groups = np.concatenate(o.cell_data["obj:group_ids"])
    assert len(np.unique(groups)) == n
    nobj = sum(len(c.data) for c in o.cells)
    t = trimesh.load(d / "cells.obj", process=False, force="mesh", group_material=False, split_object=False)
    assert len(t.faces) >= nobj
    assert pv.read(d / "cells.obj").n_cells == nobj


# VTK's OBJ reader makes chains and corners cells but sizes its GroupIds for faces only.
@pytest.mark.filterwarnings("ignore:PolyData mesh is not valid")
def test_every_format_from_every_command(tmp_path):
    for name, d, summary in _jobs(tmp_path):
        z = _check_folder(name, d, summary)
        if name in ("regions", "labels"):
            _check_surfaces_obj(d, z)
    _check_stream(tmp_path)
    _check_cut(tmp_path)


def test_python_save_uses_the_same_writers(tmp_path):
    """Network.save writes what the command writes, byte for byte (one set of writers)."""
    if not SEPTA.exists():
        pytest.skip("target/release/septa not built")
    _run("mi", "builtin:apollonius-18", "-o", tmp_path / "cli")
    net = septa.load(tmp_path / "cli" / "network.json")
    for ext in ("ply", "plain.ply", "obj", "vtu"):
        net.save(tmp_path / f"py.{ext}")
        assert (tmp_path / f"py.{ext}").read_bytes() == (tmp_path / "cli" / f"network.{ext}").read_bytes(), ext
    net.save(tmp_path / "py.vtm")
    for block in ("patches", "chains", "corners", "cells"):
        assert (tmp_path / "py" / f"{block}.vtu").read_bytes() == (tmp_path / "cli" / "network" / f"{block}.vtu").read_bytes()
    net.save(tmp_path / "py.npz")
    back = septa.load(tmp_path / "py.npz")
    assert back.summary()["patches"] == net.summary()["patches"] and back.cells == net.cells
    assert not list(tmp_path.glob(".*tmp*"))


def test_region_arrays_without_json():
    """Region surfaces come back as arrays (no JSON text) in the same vocabulary."""
    net = septa.region_surfaces("builtin:sphere-plane-hole")
    assert net.face_label.shape == (len(net), 2)
    assert np.all(net.face_label[:, 0] < net.face_label[:, 1])  # lesser region first (BoundaryLabels)
    assert np.array_equal(net.patch_labels[net.face_patch], net.face_label)
    assert sorted(s["regions"] for s in net.surfaces) == [[0, 2], [0, 3], [2, 3]]


def test_to_pyvista_multiblock(tmp_path):
    net = septa.region_surfaces("builtin:sphere-plane-hole")
    mb = net.to_pyvista()
    assert list(mb.keys()) == ["patches", "chains", "corners", "cells"]
    assert mb["patches"].n_cells == len(net)
    face = mb["patches"].cell_data["face"]  # rows grouped by size, as the .vtm
    assert np.array_equal(mb["patches"].cell_data["labels"], net.face_label[face])
    assert mb["chains"].n_cells == sum(len(c) - 1 for c in net.chains)
    assert mb["corners"].n_cells == len(net.corners) == 2
    assert mb["cells"].n_cells == int((net.face_cells >= 0).sum())


def test_repr_html_is_self_contained():
    net = septa.region_surfaces("builtin:sphere-with-hole")
    html = net._repr_html_()
    assert html.startswith("<iframe srcdoc=") and "__SEPTA_DATA" in html
    assert "src=&quot;http" not in html and 'src="http' not in html


def test_region_rule_with_shapes_primitives():
    """septa.shapes primitives go into a region rule as they are (named by index)."""
    from septa import shapes

    net = septa.region_surfaces([shapes.sphere([0, 0, 0], 0.6), shapes.sphere([0, 0, 0.6], 0.3)],
                                [{"when": "1", "region": 1}, {"when": "0", "region": 2}, {"region": 0}],
                                surfaces=[[0, 2]], grid={"resolution": 17, "bounds": [[-1] * 3, [1] * 3]})
    assert [(s["regions"], s["euler"], s["boundary_loops"]) for s in net.surfaces] == [([0, 2], 1, 1)]


def test_progress_callback_and_logger(caplog):
    import logging

    from septa import shapes

    g = septa.grid.box(40)
    f = shapes.sample([shapes.sphere([0.5] * 3, 0.3), shapes.plane([0.5] * 3, [0, 0, 1])], g)
    calls = []
    with caplog.at_level(logging.INFO, logger="septa"):
        net = septa.arrangement(g, f, progress=lambda done, total: calls.append((done, total)))
    # Blocks finish on several threads, so the calls may arrive out of order;
    # they reach all blocks.
    assert calls and max(d for d, _ in calls) == calls[0][1] and all(d <= t for d, t in calls)
    assert any(f"{len(net)} faces" in r.getMessage() for r in caplog.records)
    with pytest.raises(septa.InputError, match="progress"):
        septa.arrangement(g, f, progress=3)


def test_region_progress_callback_and_logger(caplog):
    import logging

    calls = []
    with caplog.at_level(logging.INFO, logger="septa"):
        net = septa.region_surfaces("builtin:sphere-plane-hole", progress=lambda done, total: calls.append((done, total)))
    # Every block counted once (threads may report out of order).
    assert calls and sorted(d for d, _ in calls) == list(range(1, calls[0][1] + 1))
    assert any(f"{len(net)} faces" in r.getMessage() for r in caplog.records)
    with pytest.raises(septa.InputError, match="progress"):
        septa.region_surfaces("builtin:sphere-plane-hole", progress="yes")
