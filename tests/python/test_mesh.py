"""Certified embeddings (septa::mesh): every job checks its written doubles
exactly by default and says so in ``net.embedding``; ``certify=False``
gives the doubles as computed; the command line and Python agree bit for bit."""
import json
import subprocess

import numpy as np
import pytest

import septa
from conftest import SEPTA, need


def test_jobs_are_certified_by_default():
    g = septa.grid.box(12, [[-1, -1, -1], [1, 1, 1]])
    f = septa.shapes.sample([septa.shapes.sphere([0, 0, 0], 0.6), septa.shapes.sphere([0.3, 0.1, 0], 0.5)], g)
    net = septa.arrangement(g, f)
    e = net.embedding
    assert e["after"]["triangles"] == len(net.triangles) > 0
    assert e["after"]["coincident_points"] == e["after"]["degenerate_triangles"] == e["after"]["intersecting_pairs"] == 0
    raw = septa.arrangement(g, f, certify=False)
    assert raw.embedding is None
    # the same polygons (as vertex cycles), points at most slightly moved
    assert raw.summary()["faces"] == net.summary()["faces"] and len(raw.points) == len(net.points)
    assert np.abs(raw.points - net.points).max() < 1e-6
    r = septa.region_surfaces("builtin:cad-part")
    assert r.embedding["before"]["intersecting_pairs"] > 0 and r.embedding["after"]["intersecting_pairs"] == 0
    v = np.zeros((10, 10, 10), dtype=np.int32)
    v[2:6, 2:7, 3:8] = 1
    v[6:9, 2:7, 3:8] = 2
    lab = septa.label_surfaces(v, spacing=(0.5, 0.5, 2.0))
    assert lab.embedding["after"]["triangles"] > 0 and lab.embedding["after"]["cells_positive"] >= 2


def test_cli_and_python_write_the_same_certified_doubles(tmp_path):
    exe = need(SEPTA, "the command line (scripts/test.sh builds it)")
    subprocess.run([str(exe), "regions", "builtin:cad-part", "-o", str(tmp_path / "cli"), "-q"], check=True)
    doc = json.loads((tmp_path / "cli" / "network.json").read_text())
    net = septa.region_surfaces("builtin:cad-part")
    assert np.asarray(doc["points"], dtype=np.float64).tobytes() == net.points.tobytes()
    assert doc["counts"]["embedding"]["after"] == net.embedding["after"]
    subprocess.run([str(exe), "regions", "builtin:cad-part", "-o", str(tmp_path / "raw"), "-q", "--no-certify"],
                   check=True)
    raw = json.loads((tmp_path / "raw" / "network.json").read_text())
    assert raw["counts"]["embedding"] is None
    assert np.asarray(raw["points"]).tobytes() == septa.region_surfaces("builtin:cad-part", certify=False).points.tobytes()


def test_projection_in_python_is_the_cli_s(tmp_path):
    """``region_surfaces(..., project=True)`` writes the doubles of ``septa regions --project``."""
    exe = need(SEPTA, "the command line (scripts/test.sh builds it)")
    for scene in ("builtin:sphere-with-hole", "builtin:cad-part"):
        out = tmp_path / scene.split(":")[1]
        subprocess.run([str(exe), "regions", scene, "-o", str(out), "-q", "--project"], check=True)
        doc = json.loads((out / "network.json").read_text())
        net = septa.region_surfaces(scene, project=True)
        assert np.asarray(doc["points"], dtype=np.float64).tobytes() == net.points.tobytes()
        assert doc["counts"]["embedding"]["after"] == net.embedding["after"]
        p = net.embedding["projection"]
        assert p == doc["counts"]["embedding"]["projection"]
        assert p["moved"] > 0 and p["residual_after"] < p["residual_before"], p
        assert sum(net.embedding["after"][k] for k in ("coincident_points", "degenerate_triangles",
                                                         "intersecting_pairs", "nonfinite_points")) == 0
        plain = septa.region_surfaces(scene)
        topo = lambda n: ([(s["regions"], s["euler"], s["boundary_loops"]) for s in n.surfaces], len(n.points),
                          len(n.indices), {k: v for k, v in n.summary().items() if isinstance(v, int)})
        assert topo(plain) == topo(net) and not np.array_equal(plain.points, net.points)
    with pytest.raises(septa.InputError):
        septa.region_surfaces("builtin:cad-part", certify=False, project=True)
