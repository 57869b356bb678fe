import numpy as np
import pytest
import septa
from septa import shapes


def test_values_on_arrays():
    p = np.array([[0.0, 0, 0], [2, 0, 0], [0, 0, 3]])
    assert shapes.sphere([0, 0, 0], 1)(p).tolist() == [1.0, -1.0, -2.0]
    assert np.allclose(shapes.plane([0, 0, 1], [0, 0, 2])(p), [-1, -1, 2])
    assert np.allclose(shapes.halfspace([0, 0, 1], [0, 0, 1])(p), [1, 1, -2])
    assert np.allclose(shapes.box([0, 0, 0], [1, 1, 1])(p), [1, -1, -2])
    assert np.allclose(shapes.box([0, 0, 0], [1, 1, 1])([2, 2, 0]), -np.sqrt(2))
    assert np.allclose(shapes.cylinder([0, 0, 0], [0, 0, 1], 1)(p), [1, -1, 1])
    assert np.allclose(shapes.torus([0, 0, 0], [0, 0, 1], 2, 0.5)([[2, 0, 0], [0, 0, 0]]), [0.5, -1.5])
    assert np.allclose(shapes.capsule([0, 0, 0], [0, 0, 1], 0.5)([[0, 0, 2], [1, 0, 0.5]]), [-0.5, -0.5])
    assert shapes.constant(0)(p).tolist() == [0, 0, 0]


def test_sample_and_spec():
    g = septa.grid.box(4)
    fs = [shapes.sphere([0.5, 0.5, 0.5], 0.3), shapes.plane([0.5, 0.5, 0.5], [1, 0, 0])]
    vals = shapes.sample(fs, g)
    assert vals.shape == (125, 2) and vals.flags.c_contiguous
    assert shapes.sphere([1, 2, 3], 4).to_spec() == {"type": "sphere", "center": [1.0, 2.0, 3.0], "radius": 4.0}


def test_bad_parameters():
    with pytest.raises(septa.InputError, match="radius"):
        shapes.sphere([0, 0, 0], -1)
    with pytest.raises(septa.InputError, match="center"):
        shapes.sphere([0, 0], 1)
    with pytest.raises(septa.InputError, match="zero vector"):
        shapes.plane([0, 0, 0], [0, 0, 0])
