"""region_surfaces and cut_mesh from Python: the same results as the command line."""
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

import septa
from conftest import need

ROOT = Path(__file__).resolve().parents[2]
SEPTA = ROOT / "target" / "release" / "septa"


def test_bloomenthal_sphere_plane_hole_topology():
    net = septa.region_surfaces("builtin:sphere-plane-hole")
    surfaces = sorted((tuple(s["regions"]), s["euler"], s["boundary_loops"]) for s in net.surfaces)
    assert surfaces == [((0, 2), 1, 1), ((0, 3), 1, 1), ((2, 3), 0, 2)]
    curves = sorted((tuple(c["regions"]), c["closed"]) for c in net.curves)
    assert curves == [((0, 1, 2), False), ((0, 1, 3), False), ((0, 2, 3), False), ((1, 2, 3), False), ((2, 3, 4), True)]
    assert net.points.dtype == np.float64 and net.points.shape[1] == 3


def test_region_rule_from_a_list_of_functions():
    # A solid: a box minus a sphere, as a CSG string over named functions.
    functions = [
        {"name": "box", "type": "box", "center": [0, 0, 0], "size": [1.2, 1.2, 1.2]},
        {"name": "ball", "type": "sphere", "center": [0, 0, 0.6], "radius": 0.5},
    ]
    net = septa.region_surfaces(functions, "box & !ball", grid={"resolution": 21, "bounds": [[-1] * 3, [1] * 3]})
    assert [(s["regions"], s["euler"], s["boundary_loops"]) for s in net.surfaces] == [([0, 1], 2, 0)]


def test_region_errors_name_the_field():
    with pytest.raises(septa.InputError, match="radius"):
        septa.region_surfaces([{"type": "sphere", "center": [0, 0, 0], "radius": -1}], [{"region": 0}])


def test_cut_matches_the_command_line(tmp_path):
    need(SEPTA, "the command line (scripts/test.sh builds it)")
    # A corner tetrahedron cut by 5 planes per axis at exact quarters: 20 cells
    # (cubes with i + j + k <= 3), with planes through its vertices and edges.
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    obj = tmp_path / "tet.obj"
    obj.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in v) + "".join(f"f {a+1} {b+1} {c+1}\n" for a, b, c in t))
    out = subprocess.run([str(SEPTA), "cut", str(obj), "--grid", "5", "-o", str(tmp_path / "cut"), "--json"],
                         check=True, capture_output=True, text=True)
    cli = json.loads(out.stdout.splitlines()[0])
    planes = []
    for axis in range(3):
        for j in range(5):
            p = [0.0, 0.0, 0.0, -j / 4]
            p[axis] = 1.0
            planes.append(p)
    r = septa.cut_mesh(v, t, planes)
    s = r.summary()
    for k in ("cut_vertices", "cut_edges", "cut_faces", "cut_cells"):
        assert s[k] == cli[k], k
    assert s["cut_cells"] == 20
    assert abs(r.cell_volumes.sum() - 1 / 6) < 1e-12
    assert len(r.cells) == s["cut_cells"]


def test_cut_rejects_bad_planes():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    with pytest.raises(septa.InputError):
        septa.cut_mesh(v, t, [[1, 0, 0]])
    with pytest.raises(septa.InputError):
        septa.cut_mesh(v, t, [[np.nan, 0, 0, 1]])


def test_ctrl_c_stops_a_long_arrangement():
    import os
    import signal
    import threading
    import time

    # A deliberately slow job (cell grouping, no tables): about 0.4 s.
    g = septa.grid.box(64)
    rng = np.random.default_rng(0)
    centres = rng.uniform(-0.6, 0.6, (16, 3))
    values = np.stack([0.35 - np.linalg.norm(g.vertices - c, axis=1) for c in centres], axis=1)
    slow = dict(threads=1, cells="grouping", lookup=False)
    t0 = time.perf_counter()
    septa.arrangement(g, values, **slow)
    full = time.perf_counter() - t0
    timer = threading.Timer(0.03, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        septa.arrangement(g, values, **slow)
    stopped = time.perf_counter() - t0
    timer.join()
    # Signals are polled every 20 ms and the core stops at its next block.
    assert stopped < 0.5 * full, (stopped, full)


def test_region_normals_one_copy_per_vertex_and_region_pair(tmp_path):
    """Bloomenthal 4.5.3.2: a vertex on two surfaces gets one normal per
    region pair; normals are unit gradients pointing into the lesser region;
    network.json and surfaces.obj carry them (vn, f v//vn)."""
    from conftest import ROOT

    net = septa.region_surfaces("builtin:sphere-with-hole", normals=True)
    n = net.normals
    assert len(n["vertex"]) > 0 and np.allclose(np.linalg.norm(n["normal"], axis=1), 1.0)
    # The sphere's surface separates regions 0 and 2; its normals point into
    # region 0, the lesser one: here outwards from the centre.
    assert (n["regions"] == [0, 2]).all()
    assert (np.einsum("ij,ij->i", n["normal"], net.points[n["vertex"]]) > 0).all()
    # Every polygon corner refers to the copy of its own vertex.
    assert np.array_equal(n["vertex"][net.indices_normal], net.indices)
    # A shape whose surfaces meet along curves: a curve's vertices get one
    # copy per surface of interest among its three region pairs (the saucer's
    # rim [1, 2, 3] three, the square's edge on the outside [0, 2, 3] one).
    sq = septa.region_surfaces("builtin:saucer-square", normals=True)
    copies = np.bincount(sq.normals["vertex"], minlength=len(sq.points))
    kept = {tuple(s["regions"]) for s in sq.surfaces}
    assert {tuple(p) for p in sq.normals["regions"].tolist()} == kept
    for chain, curve in zip(sq.chains, sq.curves):
        a, b, c = curve["regions"]
        want = sum(p in kept for p in ((a, b), (a, c), (b, c)))
        assert (copies[chain] == want).all(), (curve, want)
    assert copies.max() == 3
    # Without normals: None.
    assert septa.region_surfaces("builtin:sphere-with-hole").normals is None
    # The command line writes them: network.json rows and OBJ vn / f v//vn.
    exe = need(ROOT / "target" / "release" / "septa", "the command line (scripts/test.sh builds it)")
    out = tmp_path / "r"
    subprocess.run([str(exe), "regions", "builtin:saucer-square", "--normals", "-o", str(out)], check=True,
                   capture_output=True)
    doc = json.loads((out / "network.json").read_text())
    assert len(doc["normals"]["vertex"]) == len(sq.normals["vertex"])
    obj = (out / "surfaces.obj").read_text().splitlines()
    vn = [l for l in obj if l.startswith("vn ")]
    faces = [l for l in obj if l.startswith("f ")]
    assert len(vn) == len(sq.normals["vertex"]) and faces and all("//" in f for f in faces)
    trimesh = pytest.importorskip("trimesh")
    m = trimesh.load(str(out / "surfaces.obj"), process=False, force="mesh")
    assert len(m.faces) >= len(faces)


def test_region_clean_up_keeps_topology_and_reports(tmp_path):
    """clean=0.2: small and thin triangles collapsed (Bloomenthal 4.5.3.1),
    the same surfaces (regions, Euler characteristic, boundary loops) and
    curves; polygons become triangles; bad factors are clear errors."""
    raw = septa.region_surfaces("builtin:saucer-square")
    net = septa.region_surfaces("builtin:saucer-square", clean=0.2, normals=True)
    topo = lambda n: sorted((tuple(s["regions"]), s["euler"], s["boundary_loops"]) for s in n.surfaces)
    assert topo(net) == topo(raw)
    assert [(c["regions"], c["closed"]) for c in net.curves] == [(c["regions"], c["closed"]) for c in raw.curves]
    c = net.summary()["clean"]
    assert c["collapsed"] > 0 and c["triangles_after"] == len(net) < c["triangles_before"]
    assert (np.diff(net.offsets) == 3).all()
    assert np.array_equal(net.normals["vertex"][net.indices_normal], net.indices)
    with pytest.raises(septa.InputError, match="clean"):
        septa.region_surfaces("builtin:saucer-square", clean=-1.0)


def _two_boxes():
    v = np.zeros((10, 9, 8), dtype=np.int16)
    v[2:5, 2:7, 2:6] = 3
    v[5:8, 2:7, 2:6] = 7
    return v


def test_label_surfaces_numpy_and_files_match_the_command_line(tmp_path):
    """septa.label_surfaces on a numpy volume equals `septa labels` on the
    same .npy; .nrrd (pynrrd) and .nii (nibabel) files give the same
    surfaces, placed by their spacing and origin."""
    from conftest import ROOT

    v = _two_boxes()
    net = septa.label_surfaces(v)
    assert sorted(s["regions"] for s in net.surfaces) == [[0, 3], [0, 7], [3, 7]]
    # Two boxes meeting on a face: each pair's surface is one disk or one sphere-like piece.
    assert all(s["boundary_loops"] <= 1 for s in net.surfaces)
    np.save(tmp_path / "v.npy", v.astype(np.int64))
    exe = need(ROOT / "target" / "release" / "septa", "the command line (scripts/test.sh builds it)")
    out = subprocess.run([str(exe), "labels", str(tmp_path / "v.npy"), "--json", "-o", str(tmp_path / "out")],
                         capture_output=True, text=True, check=True)
    cli = json.loads(out.stdout)
    assert [(s["regions"], s["euler"], s["boundary_loops"], s["faces"]) for s in cli["surfaces"]] == \
        [(s["regions"], s["euler"], s["boundary_loops"], s["faces"]) for s in net.surfaces]
    from_npy = septa.label_surfaces(tmp_path / "v.npy")
    assert from_npy.points.tobytes() == net.points.tobytes() and np.array_equal(from_npy.indices, net.indices)
    # Spacing and origin place the points; the combinatorics do not move.
    placed = septa.label_surfaces(v, spacing=(0.5, 2.0, 1.0), origin=(10.0, 0.0, -1.0))
    assert np.array_equal(placed.indices, net.indices)
    assert np.allclose(placed.points, net.points * [0.5, 2.0, 1.0] + [10.0, 0.0, -1.0])
    nrrd = pytest.importorskip("nrrd")
    nrrd.write(str(tmp_path / "v.nrrd"), v, {"space directions": np.diag([0.5, 2.0, 1.0]), "space origin": [10.0, 0, -1.0],
                                             "space": "left-posterior-superior"})
    a = septa.label_surfaces(tmp_path / "v.nrrd")
    assert np.array_equal(a.indices, net.indices) and np.allclose(a.points, placed.points)
    nib = pytest.importorskip("nibabel")
    affine = np.diag([0.5, 2.0, 1.0, 1.0])
    affine[:3, 3] = [10.0, 0.0, -1.0]
    nib.save(nib.Nifti1Image(v, affine), str(tmp_path / "v.nii.gz"))
    b = septa.label_surfaces(tmp_path / "v.nii.gz")
    assert np.array_equal(b.indices, net.indices) and np.allclose(b.points, placed.points)
    # Bad input: clear errors.
    with pytest.raises(septa.InputError, match="not a whole number"):
        septa.label_surfaces(v.astype(np.float64) + 0.5)
    with pytest.raises(septa.InputError, match="expected a .npy"):
        septa.label_surfaces(tmp_path / "v.txt")
    with pytest.raises(septa.InputError, match="at least 2 voxels"):
        septa.label_surfaces(np.zeros((1, 4, 4), dtype=np.int64))
