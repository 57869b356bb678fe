"""`septa ia|mi --stream OUT.ply`: the streamed PLY loads with
plyfile (a general PLY reader) and holds exactly the faces and vertices of
the in-memory run, with per-face labels and block indices.

trimesh's binary PLY reader needs every face list to have one length: it
reads the `--triangles` file. meshio reads a face element with more than one
property wrongly: it reads `--stream OUT.vtu` (test_formats.py).
"""

import json
import subprocess

import pytest

plyfile = pytest.importorskip("plyfile")
np = pytest.importorskip("numpy")


@pytest.mark.parametrize("mode,spec,n", [("ia", "ia18", 24), ("mi", "mi18", 20)])
def test_streamed_ply_loads_with_plyfile(tmp_path, mode, spec, n):
    from conftest import ROOT, need

    exe = need(ROOT / "target" / "release" / "septa", "the command line (scripts/test.sh builds it)")
    spec_path = ROOT / "data" / "specs" / f"{spec}.json"
    out = tmp_path / "s.ply"
    run = lambda *a: json.loads(subprocess.run([str(exe), mode, str(spec_path), "--grid", str(n), "--block", "8", "--json", *a],
                                               capture_output=True, text=True, check=True).stdout)
    streamed = run("--stream", str(out), "--window", "3")
    full = run("-o", str(tmp_path / "full"))
    assert streamed["faces"] == full["faces"] > 0
    assert streamed["vertices"] == full["vertices"]
    assert streamed["blocks"] == full["blocks"]
    ply = plyfile.PlyData.read(str(out))
    faces, verts = ply["face"].data, ply["vertex"].data
    assert len(faces) == full["faces"] and len(verts) == full["vertices"]
    # Same polygons as point sets, with the same labels, as the in-memory network.json.
    ref = json.loads((tmp_path / "full" / "network.json").read_text())
    ref_pts = np.asarray(ref["points"], dtype=np.float64)
    pts = np.stack([verts[c] for c in ("x", "y", "z")], axis=1)
    mine = sorted((tuple(sorted(map(tuple, pts[vs].tolist()))), int(a), int(b))
                  for vs, a, b in zip(faces["vertex_indices"], faces["labels_0"], faces["labels_1"]))
    theirs = sorted((tuple(sorted(map(tuple, ref_pts[vs].tolist()))), int(a), int(b))
                    for vs, (a, b) in zip(ref["faces"], ref["face_label"]))
    assert mine == theirs
    # The topology assembled while streaming: the in-memory counts, and per
    # face the same patch and cells up to numbering (one-to-one maps).
    assert streamed["counts"] == {k: full[k] for k in streamed["counts"]}
    topo = json.loads((tmp_path / "s.topology.json").read_text())
    assert topo["counts"] == streamed["counts"] and len(topo["cells"]) == full["cells"]
    ref_of = {tuple(sorted(map(tuple, ref_pts[vs].tolist()))): f for f, vs in enumerate(ref["faces"])}
    pairs = {"patch": set(), "cell": set()}
    for vs, p, c0, c1 in zip(faces["vertex_indices"], faces["patch"], faces["cells_0"], faces["cells_1"]):
        f = ref_of[tuple(sorted(map(tuple, pts[vs].tolist())))]
        pairs["patch"].add((int(p), ref["face_patch"][f]))
        pairs["cell"].update({(int(c0), ref["face_cells"][f][0]), (int(c1), ref["face_cells"][f][1])})
    for name, ps in pairs.items():
        assert len({a for a, _ in ps}) == len({b for _, b in ps}) == len(ps), name
    assert len(pairs["patch"]) == full["patches"] and min(a for a, _ in pairs["patch"]) == 0
    # The in-memory run's network.ply (polygons as triangle fans) loads in trimesh.
    trimesh = pytest.importorskip("trimesh")
    t = trimesh.load(str(tmp_path / "full" / "network.ply"), process=False)
    assert len(t.faces) == sum(len(f) - 2 for f in ref["faces"]) and len(t.vertices) == len(ref_pts)
    face_of = t.metadata["_ply_raw"]["face"]["data"]["face"].ravel()
    assert (np.diff(face_of) >= 0).all() and face_of.max() == len(ref["faces"]) - 1
    blocks = faces["block"]
    assert (np.diff(blocks) >= 0).all() and blocks.min() >= 0 and blocks.max() < streamed["blocks"]["total"]
    assert not list(tmp_path.glob(".s.ply*")), "no temporary file left"


def test_triangulated_stream_loads_with_trimesh(tmp_path):
    from conftest import ROOT, need

    trimesh = pytest.importorskip("trimesh")
    exe = need(ROOT / "target" / "release" / "septa", "the command line (scripts/test.sh builds it)")
    out = tmp_path / "t.ply"
    s = json.loads(subprocess.run([str(exe), "ia", str(ROOT / "data" / "specs" / "ia18.json"), "--grid", "20", "--json",
                                   "--stream", str(out), "--triangles"], capture_output=True, text=True, check=True).stdout)
    assert s["ply_faces"] > s["faces"] > 0
    m = trimesh.load(str(out), process=False)
    assert len(m.faces) == s["ply_faces"] and len(m.vertices) == s["vertices"]
    # Every polygon becomes a fan: the triangles cover the vertices, none degenerate by index.
    assert len(np.unique(m.faces)) == s["vertices"]
    assert (m.faces[:, 0] != m.faces[:, 1]).all() and (m.faces[:, 1] != m.faces[:, 2]).all()


def test_python_stream_matches_the_in_memory_network(tmp_path):
    import septa

    spec = json.loads((__import__("conftest").ROOT / "data" / "specs" / "mi18.json").read_text())
    out = tmp_path / "p.ply"
    s = septa.stream.stream_ply(spec, out, grid=20, mode="mi", block=8, window=2)
    net = septa.distributed.material_interface(spec, client=None, grid=20, block=8)
    assert s["faces"] == len(net) > 0 and s["vertices"] == len(net.points)
    assert s["blocks"]["total"] == 27 and s["blocks"]["sampled"] + s["blocks"]["skipped"] == 27
    ply = plyfile.PlyData.read(str(out))
    assert len(ply["face"].data) == len(net) and len(ply["vertex"].data) == len(net.points)
    # Same label pairs, polygon for polygon up to order.
    got = sorted(zip(ply["face"].data["labels_0"].tolist(), ply["face"].data["labels_1"].tolist()))
    want = sorted(map(tuple, net.face_label.tolist()))
    assert got == want
    # Bad input: a clear error and no file.
    with pytest.raises(septa.InputError, match="grid"):
        septa.stream.stream_ply(spec, tmp_path / "bad.ply", mode="mi")
    assert not (tmp_path / "bad.ply").exists()
