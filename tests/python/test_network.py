import json

import numpy as np
import pytest
import septa
from conftest import FIXTURE


def test_fixture_counts_and_invariants(fixture_net):
    net = fixture_net
    s = net.summary()
    # Two coordinate planes through the box centre (derived by hand).
    assert {k: s[k] for k in ("patches", "chains", "corners", "shells", "cells")} == {
        "patches": 4, "chains": 1, "corners": 2, "shells": 4, "cells": 4}
    assert net.points.dtype == np.float64 and net.indices.dtype == np.int64
    assert net.patch_labels.shape == (4, 2)
    # Every face bounds two different cells; every cell's shell holds exactly
    # the half-patches of the faces on its side.
    assert np.all(net.face_cells[:, 0] != net.face_cells[:, 1])
    for c, cell in enumerate(net.cells):
        half = {int(h) for sh in cell["shells"] for h in net.shells[sh]}
        faces_side = {2 * int(net.face_patch[f]) + (0 if net.face_cells[f, 0] == c else 1)
                      for f in range(len(net)) if c in net.face_cells[f]}
        assert half == faces_side
    # Triangulated view covers each polygon with n - 2 triangles.
    assert len(net.triangles) == int(np.sum(np.diff(net.offsets) - 2))


def test_save_roundtrip(tmp_path, fixture_net):
    meshio = pytest.importorskip("meshio")
    trimesh = pytest.importorskip("trimesh")
    net = fixture_net
    ntri = len(net.triangles)
    # PLY: the polygons as triangle fans, each naming its polygon and patch.
    # (meshio 5.3's binary PLY reader cannot read per-face properties, so
    # trimesh reads it; meshio reads the .plain.ply, test_formats.py.)
    net.save(tmp_path / "n.ply")
    t = trimesh.load(tmp_path / "n.ply", process=False)
    assert len(t.faces) == ntri and np.allclose(t.vertices, net.points)
    assert np.array_equal(t.faces, net.triangles)
    raw = t.metadata["_ply_raw"]["face"]["data"]
    assert np.array_equal(raw["face"].ravel(), net.triangle_face)
    assert np.array_equal(raw["patch"].ravel(), net.face_patch[net.triangle_face])
    assert np.array_equal(raw["labels_0"].ravel(), net.face_label[net.triangle_face, 0])
    assert np.array_equal(raw["cells_1"].ravel(), net.face_cells[net.triangle_face, 1])
    # The fixture's PLY (as the CLI writes it) reads the same way.
    ref = trimesh.load(FIXTURE / "network.ply", process=False)
    assert np.array_equal(ref.faces, t.faces)
    assert np.array_equal(ref.metadata["_ply_raw"]["face"]["data"]["face"].ravel(), net.triangle_face)
    # OBJ: a group per patch.
    net.save(tmp_path / "n.obj")
    t = trimesh.load(tmp_path / "n.obj", process=False, force="mesh")
    assert len(t.faces) == ntri
    assert (tmp_path / "n.obj").read_text().count("\ng patch_") == 4
    # VTU (the polygons) and MSH (triangles) through meshio, with patch ids as cell data.
    net.save(tmp_path / "n.vtu")
    m = meshio.read(tmp_path / "n.vtu")
    face = np.concatenate(m.cell_data["face"]).ravel()  # rows grouped by size: each row's face
    assert np.array_equal(np.sort(face), np.arange(len(net)))
    assert np.array_equal(np.concatenate(m.cell_data["patch"]).ravel(), net.face_patch[face])
    assert np.array_equal(np.concatenate(m.cell_data["labels"]), net.face_label[face])
    net.save(tmp_path / "n.msh")
    m = meshio.read(tmp_path / "n.msh")
    assert len(m.cells_dict["triangle"]) == ntri
    # Gmsh physical surfaces from 1 (0 is no group), named as the OBJ groups
    assert np.array_equal(np.concatenate(m.cell_data["gmsh:physical"]), net.face_patch[net.triangle_face] + 1)
    assert sorted(int(v[0]) for v in m.field_data.values()) == list(range(1, len(net.patch_labels) + 1))
    # JSON: the network contract itself.
    net.save(tmp_path / "n.json")
    back = septa.load(tmp_path / "n.json")
    assert back.summary() == net.summary()
    assert not list(tmp_path.glob("*.tmp"))


def test_converters(fixture_net):
    pytest.importorskip("meshio")
    pytest.importorskip("trimesh")
    m = fixture_net.to_meshio()
    assert m.cells[0].type == "triangle"
    t = fixture_net.to_trimesh()
    assert np.array_equal(t.faces, fixture_net.triangles)
    assert set(np.unique(t.face_attributes["patch"])) == {0, 1, 2, 3}


def test_to_pyvista_hint_or_mesh(fixture_net):
    try:
        import pyvista  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="pip install pyvista"):
            fixture_net.to_pyvista()
    else:
        mb = fixture_net.to_pyvista()
        assert mb["patches"].n_cells == len(fixture_net)
        assert mb["corners"].n_cells == 2 and mb["chains"].n_cells == len(fixture_net.chains[0]) - 1


def test_load_errors(tmp_path):
    with pytest.raises(septa.InputError, match="cannot read"):
        septa.load(tmp_path)
    (tmp_path / "network.json").write_text('{"points": [\n1,')
    with pytest.raises(septa.InputError, match=r"network.json:2: invalid JSON"):
        septa.load(tmp_path)
    with pytest.raises(septa.InputError, match="unknown extension"):
        septa.load(FIXTURE).save(tmp_path / "x.stl")


def test_fixture_generator_reproduces_committed_fixture():
    import make_fixture

    committed = json.loads((FIXTURE / "network.json").read_text())
    assert make_fixture.two_planes(4) == committed
