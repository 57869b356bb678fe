"""Volumes, areas and lengths in every result and every format: the same
numbers from Python, the command line's --json, network.json, network.npz,
the VTK files and septa.load."""
import json
import subprocess

import numpy as np
import pytest
import septa
from conftest import ROOT

SEPTA = ROOT / "target" / "release" / "septa"


def test_sphere_in_a_box_region_volumes():
    net = septa.region_surfaces([{"name": "ball", "type": "sphere", "center": [0.01, -0.02, 0.03], "radius": 0.5}],
                                "ball", grid={"resolution": 24, "bounds": [[-1] * 3, [1] * 3]})
    regions = {r["region"]: r for r in net.summary()["regions"]}
    assert regions[0]["name"] == "outside" and regions[1]["name"] == "inside"
    exact = 4 / 3 * np.pi * 0.5 ** 3
    assert 0 < exact - regions[1]["volume"] < 0.02 * exact
    assert net.cell_volume.sum() == pytest.approx(8.0, rel=1e-12)
    assert np.array_equal(net.cell_volume, [regions[0]["volume"], regions[1]["volume"]])
    assert net.patch_area[0] == pytest.approx(4 * np.pi * 0.25, rel=0.02)


def test_label_volumes_placed_by_an_affine():
    v = np.zeros((12, 10, 9), dtype=np.int32)
    v[:5] = 1  # label 1 up to x = 4.5 in voxel coordinates: exact
    plain = septa.label_surfaces(v)
    assert np.allclose(plain.cell_volume, [6.5 * 9 * 8, 4.5 * 9 * 8], rtol=1e-12)
    placed = septa.label_surfaces(v, spacing=(0.5, 2.0, 3.0), origin=(1, 2, 3))
    assert np.allclose(placed.cell_volume, plain.cell_volume * 3.0, rtol=1e-12)
    assert np.allclose(placed.patch_area, plain.patch_area * 6.0, rtol=1e-12)


def test_measures_in_every_format(tmp_path):
    if not SEPTA.exists():
        pytest.skip("target/release/septa not built (scripts/test.sh builds it)")
    out = subprocess.run([str(SEPTA), "regions", "builtin:box-minus-cylinder", "-o", tmp_path / "r", "--format", "all",
                          "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    summary = json.loads(out.stdout)
    volumes = [r["volume"] for r in summary["regions"]]
    assert sum(volumes) == pytest.approx(8.0, rel=1e-12)
    assert volumes[1] == pytest.approx(1 - np.pi * 0.25 ** 2, abs=0.003)
    areas = [s["area"] for s in summary["surfaces"]]
    lengths = [c["length"] for c in summary["curves"]]
    d = tmp_path / "r"
    doc = json.loads((d / "network.json").read_text())
    assert doc["measures"]["cell_volume"] == volumes and doc["measures"]["patch_area"] == areas
    assert doc["measures"]["chain_length"] == lengths
    z = np.load(d / "network.npz")
    assert np.array_equal(z["cell_volume"], volumes) and np.array_equal(z["chain_length"], lengths)
    for net in (septa.load(d), septa.load(d / "network.json")):
        assert np.array_equal(net.cell_volume, volumes) and np.array_equal(net.patch_area, areas)
    pv = pytest.importorskip("pyvista")
    mb = pv.read(d / "network.vtm")
    cells = mb["cells"]
    assert np.array_equal(cells.cell_data["volume"], np.asarray(volumes)[cells.cell_data["cell"]])
    chains = mb["chains"]
    assert np.array_equal(chains.cell_data["length"], np.asarray(lengths)[chains.cell_data["chain"]])
    g = pv.read(d / "network.vtu")
    assert np.bincount(g.cell_data["patch"], weights=g.cell_data["area"]) == pytest.approx(areas, rel=1e-12)
    # Saved again from Python: the same measures.
    net = septa.load(d)
    net.save(tmp_path / "again.npz")
    assert np.array_equal(np.load(tmp_path / "again.npz")["cell_volume"], volumes)


def test_network_cell_volumes_sum_to_the_box(tmp_path):
    g = septa.grid.box(10, [[0, 0, 0], [2, 1, 1]])
    f = septa.shapes.sample([septa.shapes.sphere([0.7, 0.5, 0.5], 0.3), septa.shapes.sphere([1.2, 0.5, 0.5], 0.4)], g)
    net = septa.material_interface(g, f)
    assert len(net.cell_volume) == len(net.cells) and net.cell_volume.sum() == pytest.approx(2.0, rel=1e-12)
    assert (net.cell_volume > 0).all()
    # A tet mesh (no box known): cells reaching its boundary have no volume.
    # The ball's volume is the same as on the box grid (the same polygons).
    ball = septa.shapes.sample([septa.shapes.sphere([1, 0.5, 0.5], 0.3)], g)
    mesh, box = septa.arrangement(g.vertices, g.tets, ball), septa.arrangement(g, ball)
    assert np.isnan(mesh.cell_volume).sum() == 1 and box.cell_volume.sum() == pytest.approx(2.0, rel=1e-12)
    inside = [i for i, c in enumerate(box.cells) if c["label"][0]][0]
    assert np.nanmax(mesh.cell_volume) == pytest.approx(box.cell_volume[inside], rel=1e-12)
