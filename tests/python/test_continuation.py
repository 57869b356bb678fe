"""septa.continuation on Python callables: equal to the dense path when the
seeds reach every component; a separate unseeded component is missed by
design; errors in the callable are clear InputErrors."""
import json
from pathlib import Path

import numpy as np
import pytest

import septa
from septa import continuation

SPECS = Path(__file__).resolve().parents[2] / "data" / "specs"


def spheres(centres, radii):
    c = np.asarray(centres, dtype=np.float64)
    r = np.asarray(radii, dtype=np.float64)

    def f(p):
        d = p[:, None, :] - c[None, :, :]
        return r[None, :] - np.sqrt(d[..., 0] * d[..., 0] + d[..., 1] * d[..., 1] + d[..., 2] * d[..., 2])

    return f


def spec(name):
    fs = json.loads((SPECS / f"{name}.json").read_text())
    return spheres([s["center"] for s in fs], [s["radius"] for s in fs]), len(fs)


def assert_same(a, b, what):
    assert a.points.tobytes() == b.points.tobytes(), f"{what}: points"
    for name in ("offsets", "indices", "face_patch", "face_cells", "face_label", "patch_labels", "corners"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), f"{what}: {name}"
    assert len(a.shells) == len(b.shells) and all(np.array_equal(x, y) for x, y in zip(a.shells, b.shells)), what
    assert a.cells == b.cells, f"{what}: cells"


@pytest.mark.parametrize("name, job", [("ia18", continuation.arrangement), ("mi18", continuation.material_interface)])
def test_coarse_scan_equals_dense(name, job):
    f, k = spec(name)
    net = job(f, k, grid=20, block=4)
    ref = job(f, k, grid=20, block=4, dense=True)
    assert_same(net, ref, name)
    b = net.summary()["blocks"]
    assert b["seeds"] > 0 and not b["dense_fallback"] and b["sampled"] + b["skipped"] == 125
    assert net.summary()["faces"] > 0


def test_unseeded_component_is_missed_by_design():
    centres = [[-0.61, -0.58, -0.63], [0.57, 0.53, -0.49], [0.013, 0.62, 0.59], [0.56, -0.61, 0.52]]
    f = spheres(centres, [0.21, 0.24, 0.22, 0.25])
    ref = continuation.arrangement(f, 4, grid=32, block=4, dense=True)
    assert ref.summary()["components"] == 4
    full = continuation.arrangement(f, 4, grid=32, block=4, seeds=centres)
    assert_same(full, ref, "all seeded")
    assert full.summary()["blocks"]["skipped"] > full.summary()["blocks"]["sampled"]
    part = continuation.arrangement(f, 4, grid=32, block=4, seeds=centres[:3])
    s = part.summary()
    assert s["components"] == 3 and s["blocks"]["seeds"] == 3
    assert not np.any(part.face_label[:, 0] == 3)
    assert s["faces"] == int(np.sum(ref.face_label[:, 0] != 3))


def test_callable_errors_are_input_errors():
    def boom(p):
        raise ValueError("no values today")

    with pytest.raises(septa.InputError, match="no values today"):
        continuation.arrangement(boom, 1, grid=8, block=4)
    with pytest.raises(septa.InputError, match="shape"):
        continuation.arrangement(lambda p: np.zeros((len(p), 3)), 2, grid=8, block=4)
    with pytest.raises(septa.InputError, match="not finite"):
        continuation.arrangement(lambda p: np.full(len(p), np.nan), 1, grid=8, block=4)
    with pytest.raises(septa.InputError, match="outside the grid"):
        continuation.arrangement(spheres([[0, 0, 0]], [0.5]), 1, grid=8, block=4, seeds=[(3, 0, 0)])
