import numpy as np
import pytest
import septa
from conftest import ISN, need


def volumes(g):
    p = g.vertices[g.tets]
    return np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), p[:, 3] - p[:, 0]) / 6


@pytest.mark.parametrize("split", [5, 6])
def test_box_counts_orientation_volume(split):
    g = septa.grid.box((3, 4, 2), [[0, -1, 0], [3, 1, 4]], split=split)
    assert g.vertices.shape == (4 * 5 * 3, 3) and g.vertices.dtype == np.float64
    assert g.tets.shape == (split * 24, 4) and g.tets.dtype == np.int64
    v = volumes(g)
    assert np.all(v > 0)
    assert np.isclose(v.sum(), 3 * 2 * 4, rtol=1e-12)
    # Vertex (i, j, k) sits at index i*(ny+1)*(nz+1) + j*(nz+1) + k.
    i, j, k = 2, 3, 1
    assert np.allclose(g.vertices[i * 15 + j * 3 + k], [2, -1 + 3 * 0.5, 2])


@pytest.mark.parametrize("split", [5, 6])
def test_box_faces_match(split):
    # A conforming grid: every interior triangle is shared by exactly two tets.
    g = septa.grid.box(3, split=split)
    faces = np.sort(g.tets[:, [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]].reshape(-1, 3), axis=1)
    _, counts = np.unique(faces, axis=0, return_counts=True)
    assert counts.max() == 2
    boundary = (counts == 1).sum()
    assert boundary == 6 * 9 * 2  # two triangles per boundary square


def test_box_equals_reference_grid():
    path = ISN / "ia4_R20.npz"
    need(path, "shared test data")
    ref = np.load(path)
    R = int(ref["grid_res"])
    g = septa.grid.box(R, ref["bbox"])
    assert np.allclose(g.vertices, ref["vertices"], rtol=0, atol=1e-12)
    assert {tuple(sorted(t)) for t in g.tets.tolist()} == {tuple(sorted(t)) for t in ref["tets"].tolist()}


def test_box_bad_input():
    with pytest.raises(septa.InputError, match="resolution"):
        septa.grid.box(0)
    with pytest.raises(septa.InputError, match="bounds"):
        septa.grid.box(2, [[0, 0, 0], [1, 0, 1]])
    with pytest.raises(ValueError, match="split"):
        septa.grid.box(2, split=4)
