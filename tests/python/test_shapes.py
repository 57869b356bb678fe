import json

import numpy as np
import pytest
import septa
from conftest import ISN, need
from septa import _septa, shapes


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


def bits(a):
    """The float64 array as its bit patterns: equal only if bit for bit equal (0.0 != -0.0)."""
    return np.ascontiguousarray(a, dtype=np.float64).view(np.int64)


# Round inputs: centres, normals and radii that put values exactly 0 (or
# ties) on grid nodes of a [-1, 1]^3 grid of 16 cubes per side.
ROUND = [
    {"type": "sphere", "center": [0, 0, 0], "radius": 0.5},
    {"type": "sphere", "center": [0.5, 0, 0], "radius": 0.5},
    {"type": "plane", "point": [0, 0, 0], "normal": [1, 0, 0]},
    {"type": "plane", "point": [0, 0.25, 0], "normal": [0, 0, 2]},
    {"type": "halfspace", "point": [0, 0, 0.5], "normal": [0, 1, 0]},
    {"type": "box", "center": [0, 0, 0], "half_size": [0.5, 0.25, 0.75]},
    {"type": "constant", "value": 0.0},
]


def _from_spec(s):
    args = {k: v for k, v in s.items() if k != "type"}
    return getattr(shapes, s["type"])(**args)


def test_python_primitives_are_the_library_scene_functions(tmp_path):
    # The values a scene file with these primitives samples (read through
    # the library's reader) and the values the Python objects give: bit for bit.
    g = septa.grid.box(16, [[-1, -1, -1], [1, 1, 1]])
    fs = [_from_spec(s) for s in ROUND]
    py = shapes.sample(fs, g)
    scene_json = json.dumps([{**s, "type": "half_space" if s["type"] == "halfspace" else s["type"]} for s in ROUND])
    lib = _septa.sample_functions(scene_json, g.vertices)
    assert np.array_equal(bits(py), bits(lib))
    # One at a time and on any (..., 3) shape: the same numbers.
    for j, f in enumerate(fs):
        assert np.array_equal(bits(f(g.vertices.reshape(17, 289, 3)).reshape(-1)), bits(py[:, j]))
    # Round inputs give the exact values the geometry says (computed here
    # independently with numpy's correctly rounded sqrt): zeros on nodes.
    p = g.vertices
    expect = np.stack([
        0.5 - np.sqrt((p * p).sum(1)),
        0.5 - np.sqrt(((p - [0.5, 0, 0]) ** 2).sum(1)),
        p[:, 0],
        p[:, 2],
        -p[:, 1],
    ], axis=1)
    assert np.array_equal(bits(py[:, :5] + 0.0), bits(expect + 0.0))
    assert (py[:, 0] == 0).sum() == 6 and (py[:, 2] == 0).sum() == 17 * 17
    assert np.all(py[:, 6] == 0)


def test_python_grid_is_the_library_grid():
    # The vertices a scene's grid gives (the reference formula, exactly hi at
    # the last node): bounds whose formula misses the top by an ulp.
    g = septa.grid.box((3, 5, 7), [[-0.3, -0.3, 0.1], [0.9, 0.9, 0.7]], split=5)
    assert g.vertices[:, 0].max() == 0.9 and g.vertices[:, 2].max() == 0.7
    i = np.arange(6)
    assert np.array_equal(bits(np.unique(g.vertices[:, 1])), bits(np.where(i == 5, 0.9, -0.3 + 1.2 * i / 5)))


@pytest.mark.parametrize("case", ["ia4_R20", "mi4_R20", "shifted4_ia_eps1e-7_R20_s0"])
def test_sampling_equals_reference_inputs_bit_for_bit(case):
    # The reference implementation's sampled values (which the library
    # reproduces) from the same spheres on the same grid.
    path = need(ISN / f"{case}.npz", "shared test data")
    ref = np.load(path)
    g = septa.grid.box(int(ref["grid_res"]), ref["bbox"])
    assert np.array_equal(bits(g.vertices), bits(ref["vertices"]))
    fs = [shapes.sphere(s["center"], s["radius"]) for s in json.loads(str(ref["spec_json"]))]
    assert np.array_equal(bits(shapes.sample(fs, g)), bits(ref["values"]))


def test_to_spec_is_a_scene_entry():
    # Every Python primitive's spec is read by the scene reader (cylinder and
    # torus field names used to be Python's own and failed there).
    fs = [shapes.cylinder([0, 0, 0], [0, 0, 1], 0.5), shapes.torus([0, 0, 0], [0, 0, 1], 0.5, 0.25),
          shapes.capsule([0, 0, 0], [0, 0, 1], 0.5)]
    net = septa.region_surfaces(fs, "0", grid={"resolution": 8, "bounds": [[-1, -1, -1], [1, 1, 1]]})
    assert len(net.surfaces) == 1
