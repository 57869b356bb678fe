"""One answer from Python on degenerate inputs: round numbers put values
exactly 0 (IA) or ties (MI) on grid vertices. Each scene is run on the
sparse path (locally and on a dask.distributed cluster), on the dense path,
from values sampled in Python on the same grid (the tet-mesh path) and
streamed with topology (locally and on the cluster): every array identical,
the streamed counts equal, and the counts the geometry gives."""
import json

import numpy as np
import pytest

import septa
from septa import _septa
from septa import distributed as sd
from septa.network import Network

from test_distributed import assert_same, client  # noqa: F401  (fixture)

SPHERES = [
    {"type": "sphere", "center": [0, 0, 0], "radius": 0.5},
    {"type": "sphere", "center": [0.5, 0, 0], "radius": 0.5},
    {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5},
    {"type": "sphere", "center": [0, 0, 0.5], "radius": 0.5},
]
PLANES_AND_SPHERE = [
    {"type": "plane", "point": [0, 0, 0], "normal": [1, 0, 0]},
    {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]},
    {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]},
    {"type": "sphere", "center": [0, 0, 0], "radius": 0.5},
]
BOUNDS = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]

# (name, functions, mode, grid resolution, counts)
CASES = [
    ("round spheres IA", SPHERES, "ia", 16, {"patches": 32, "chains": 24, "corners": 8, "cells": 16}),
    ("round spheres MI", SPHERES, "mi", 16, {"patches": 6, "chains": 4, "corners": 5, "cells": 4}),
    ("planes and sphere IA", PLANES_AND_SPHERE, "ia", 8, {"patches": 32, "chains": 24, "corners": 13, "cells": 16}),
    ("plane through nodes IA", PLANES_AND_SPHERE[2:3], "ia", 6, {"patches": 1, "chains": 0, "cells": 2}),
    ("tied materials MI", SPHERES[:1] * 2, "mi", 4, {"vertices": 0, "faces": 0, "patches": 0, "cells": 1}),
    # A diagonal plane through grid vertex 0 (the sink of ray shooting) and a sphere.
    (
        "plane through the sink IA",
        [{"type": "plane", "point": [-1, -1, -1], "normal": [1, -1, 0]}, SPHERES[0]],
        "ia",
        8,
        {"patches": 4, "chains": 1, "corners": 0, "shells": 4, "cells": 4},
    ),
    # Materials 1 and 2 tie on the grid plane x = -0.25; a ball wins on a disc of it.
    (
        "tie over part of a tet face MI",
        [
            {"type": "sphere", "center": [-0.75, 0.5, 0.5], "radius": 0.25},
            {"type": "plane", "point": [0.25, 0.25, 0.5], "normal": [1, 0, 0]},
            {"type": "plane", "point": [-0.75, 0, -1], "normal": [-2, 0, 0]},
        ],
        "mi",
        8,
        {"patches": 4, "chains": 2, "corners": 4, "shells": 3, "cells": 3},
    ),
]


def _grid(n):
    return {"resolution": n, "bounds": BOUNDS, "split": 5}


def _shape(spec):
    if spec["type"] == "sphere":
        return septa.shapes.sphere(spec["center"], spec["radius"])
    return septa.shapes.plane(spec["point"], spec["normal"])


def _runs(functions, mode, n):
    job_fn = sd.arrangement if mode == "ia" else sd.material_interface
    job = sd.job_spec(functions, mode=mode, grid=_grid(n), block=4)
    runs = {
        "sparse": job_fn(functions, client=None, grid=_grid(n), block=4),
        "dense": Network._from_core(_septa.sparse_network(json.dumps(job), dense=True)),
        "shapes": job_fn([_shape(f) for f in functions], client=None, grid=_grid(n), block=4),
    }
    return runs


@pytest.mark.parametrize("name, functions, mode, n, counts", CASES, ids=[c[0] for c in CASES])
def test_every_python_path_gives_one_answer(name, functions, mode, n, counts, tmp_path):
    runs = _runs(functions, mode, n)
    dense = runs["dense"]
    summary = dense.summary()
    for k, v in counts.items():
        assert summary[k] == v, f"{name}: {k} = {summary[k]}, expected {v}"
    for path, net in runs.items():
        assert_same(dense, net, f"{name}: {path} vs dense")
    # Values sampled in Python at the grid's vertices, through the tet-mesh
    # path: the same evaluator, so the same zeros and ties, the same counts.
    g = septa.grid.box(n, BOUNDS, split=5)
    values = septa.shapes.sample([_shape(f) for f in functions], g)
    fn = septa.arrangement if mode == "ia" else septa.material_interface
    mesh = fn(g, values)
    ms = mesh.summary()
    for k in ("vertices", "faces", "patches", "chains", "corners", "shells", "cells", "components"):
        assert ms[k] == summary[k], f"{name}: {k} from sampled values {ms[k]} != {summary[k]}"
    # Streamed with topology: faces lying in tet faces are paired in and across blocks.
    streamed = septa.stream.stream_ply(functions, tmp_path / "s.ply", grid=_grid(n), mode=mode, block=4)
    for k in ("vertices", "faces", "patches", "chains", "corners", "shells", "cells", "components"):
        assert streamed["counts"][k] == summary[k], f"{name}: streamed {k} {streamed['counts'][k]} != {summary[k]}"


DASK_CASES = CASES[:3] + CASES[-2:]


@pytest.mark.parametrize("name, functions, mode, n, counts", DASK_CASES, ids=[c[0] for c in DASK_CASES])
def test_dask_gives_the_same_answer_on_round_inputs(client, name, functions, mode, n, counts, tmp_path):  # noqa: F811
    job_fn = sd.arrangement if mode == "ia" else sd.material_interface
    local = job_fn(functions, client=None, grid=_grid(n), block=4)
    dist = job_fn(functions, client=client, grid=_grid(n), block=4)
    assert_same(local, dist, f"{name}: dask vs local")
    # The stream on the cluster: the same bytes as the local stream.
    a = septa.stream.stream_ply(functions, tmp_path / "local.ply", grid=_grid(n), mode=mode, block=4)
    b = sd.stream_ply(functions, tmp_path / "dist.ply", client=client, grid=_grid(n), mode=mode, block=4, batch=3)
    assert a["counts"] == b["counts"], name
    assert (tmp_path / "local.ply").read_bytes() == (tmp_path / "dist.ply").read_bytes(), name
