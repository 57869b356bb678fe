"""``Network.remesh(L)`` and ``septa remesh OUT L``: the same patches,
chains, corners, shells and cells after remeshing, quality triangles, the
exact check passing; the command line and Python give the same doubles."""
import json
import subprocess

import numpy as np

import septa
from conftest import SEPTA, need


def min_angle(net):
    """The smallest angle of any triangle, in degrees."""
    p = net.points[net.triangles]
    out = 180.0
    for k in range(3):
        a, b, c = p[:, k], p[:, (k + 1) % 3], p[:, (k + 2) % 3]
        u, v = b - a, c - a
        cos = np.einsum("ij,ij->i", u, v) / (np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1))
        out = min(out, float(np.degrees(np.arccos(np.clip(cos, -1, 1))).min()))
    return out


def enclosed(net, c):
    """The volume the triangles of cell ``c`` enclose (divergence theorem;
    the normal points into the positive side's cell)."""
    t, f = net.triangles, net.triangle_face
    p = net.points[t]
    six = np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2]))
    sign = (net.face_cells[f, 1] == c).astype(float) - (net.face_cells[f, 0] == c).astype(float)
    return float((six * sign).sum() / 6.0)


def topology(net):
    s = net.summary()
    return ({k: s[k] for k in ("patches", "chains", "corners", "shells", "cells")},
            net.patch_labels.tolist(), [c["label"] for c in net.cells], [len(c) > 0 for c in net.chains])


def two_spheres():
    g = septa.grid.box(16, [[-1, -1, -1], [1, 1, 1]])
    f = septa.shapes.sample([septa.shapes.sphere([0, 0, 0], 0.6), septa.shapes.sphere([0.35, 0.1, 0], 0.5)], g)
    return septa.arrangement(g, f)


def test_remesh_keeps_the_network_and_lifts_the_angles():
    net = two_spheres()
    out = net.remesh(0.15)
    assert topology(out) == topology(net)
    r = out.remeshing
    assert r["refused"] == 0 and r["patches_kept"]
    assert min_angle(net) < 5 and min_angle(out) >= 20 and abs(r["after"]["min_angle"] - min_angle(out)) < 1e-9
    assert r["after"]["triangles"] == len(out.triangles) < len(net.triangles)
    assert out.embedding["after"]["intersecting_pairs"] == out.embedding["after"]["degenerate_triangles"] == 0
    assert out.embedding["after"]["coincident_points"] == 0
    # chains keep their ends, corners their points; every chain a path of triangle edges
    for a, b in zip(net.chains, out.chains):
        assert np.array_equal(net.points[[a[0], a[-1]]], out.points[[b[0], b[-1]]])
    assert np.array_equal(net.points[net.corners], out.points[out.corners])
    edges = {tuple(sorted(e)) for t in out.triangles.tolist() for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))}
    assert all(tuple(sorted(e)) in edges for c in out.chains for e in zip(c[:-1].tolist(), c[1:].tolist()))
    # near the unremeshed surface; measures follow the triangles
    assert max(r["hausdorff"]) < 0.05
    # (chords cut into the spheres: volumes move by a few percent, the box's total stays)
    assert np.allclose(out.cell_volume, net.cell_volume, rtol=0.05)
    assert abs(out.cell_volume.sum() - net.cell_volume.sum()) < 1e-9
    for c in range(len(out.cells)):
        if c != int(np.argmax(out.cell_volume)):  # the cells inside the box: their triangles' volume
            assert abs(enclosed(out, c) - out.cell_volume[c]) < 1e-9
    assert np.allclose(out.patch_area, net.patch_area, rtol=0.03)
    assert len(out.chain_length) == len(net.chains)


def test_remesh_of_a_label_volume_and_bad_lengths():
    v = np.zeros((14, 14, 14), dtype=np.int32)
    v[2:9, 2:12, 3:11] = 1
    v[9:12, 2:12, 3:11] = 2
    net = septa.label_surfaces(v)
    out = net.remesh(1.5)
    assert topology(out) == topology(net) and out.remeshing["refused"] == 0
    assert min_angle(out) >= 20
    for bad in (0.0, -1.0, float("nan")):
        try:
            net.remesh(bad)
        except septa.InputError as e:
            assert "edge length" in str(e)
        else:
            raise AssertionError(f"remesh({bad}) was accepted")


def test_cli_remesh_rewrites_the_folder_as_python_does(tmp_path):
    exe = need(SEPTA, "the command line (scripts/test.sh builds it)")
    out = tmp_path / "out"
    subprocess.run([str(exe), "ia", "builtin:sphere-with-hole", "-o", str(out), "-q", "--format", "json,npz,ply,vtu"],
                   check=True)
    before = septa.load(out)
    want = before.remesh(0.15)
    rep = json.loads(subprocess.run([str(exe), "remesh", str(out), "0.15", "--json"], check=True,
                                    capture_output=True, text=True).stdout)
    assert rep["remesh"]["refused"] == 0
    files = sorted(f["name"] for f in json.loads((out / "manifest.json").read_text())["files"])
    assert files == ["network.json", "network.npz", "network.ply", "network.vtu"]
    assert not [p.name for p in out.iterdir() if p.name.startswith(".") and p.name != ".septa.lock"]
    got = septa.load(out)  # network.npz
    doc = septa.load(out / "network.json")
    for n in (got, doc):
        assert topology(n) == topology(before)
        assert n.points.tobytes() == want.points.tobytes() and np.array_equal(n.indices, want.indices)
    assert doc.data["remesh"]["after"]["min_angle"] >= 20 and min_angle(got) >= 20
    # a folder without a result is refused, naming it, and nothing is written
    r = subprocess.run([str(exe), "remesh", str(tmp_path), "0.1"], capture_output=True, text=True)
    assert r.returncode == 2 and str(tmp_path) in r.stderr and "network.npz" in r.stderr
