import subprocess

import numpy as np
import pytest
import septa
from septa import shapes


def test_version():
    assert septa.__version__ == "0.1.0"
    assert issubclass(septa.InputError, ValueError)


def test_nan_value_named():
    g = septa.grid.box(2)
    vals = shapes.sample([shapes.sphere([0.5] * 3, 0.3), shapes.constant(1)], g)
    vals[7, 1] = np.nan
    with pytest.raises(septa.InputError, match="function 1 at vertex 7 is not finite"):
        septa.arrangement(g, vals)


def test_bad_tets_named():
    g = septa.grid.box(1)
    tets = g.tets.copy()
    tets[3, 2] = 99
    with pytest.raises(septa.InputError, match="tet 3 refers to vertex 99"):
        septa.material_interface(g.vertices, tets, np.zeros((8, 2)))
    tets = g.tets.copy()
    tets[1, 1] = tets[1, 0]
    with pytest.raises(ValueError, match="tet 1 repeats a vertex"):
        septa.arrangement(g.vertices, tets, np.zeros(8))
    with pytest.raises(septa.InputError, match=r"values: expected shape \(8, k\)"):
        septa.arrangement(g, np.zeros((5, 2)))


def test_arrangement_two_planes_matches_hand_count():
    # Two coordinate planes through grid nodes (exactly degenerate):
    # 4 patches, 1 chain, 2 corners where it meets the boundary, 4 cells.
    g = septa.grid.box(4)
    vals = shapes.sample([shapes.plane([0.5] * 3, [1, 0, 0]), shapes.plane([0.5] * 3, [0, 1, 0])], g)
    net = septa.arrangement(g, vals)
    s = net.summary()
    assert (s["patches"], s["chains"], s["corners"], s["cells"], s["shells"]) == (4, 1, 2, 4, 4)
    assert net.points.dtype == np.float64 and net.indices.dtype == np.int64
    assert net.patch_labels.tolist() == [[0, 0], [0, 0], [1, 1], [1, 1]] or sorted(net.patch_labels[:, 0].tolist()) == [0, 0, 1, 1]
    # The general tet-mesh path gives the same network.
    s2 = septa.arrangement(g.vertices, g.tets, vals, cells="grouping").summary()
    assert {k: s2[k] for k in ("vertices", "faces", "patches", "chains", "corners", "cells")} == \
        {k: s[k] for k in ("vertices", "faces", "patches", "chains", "corners", "cells")}


def _counts(s):
    return {k: s[k] for k in ("vertices", "faces", "edges", "patches", "chains", "corners", "shells", "cells", "components")}


@pytest.mark.parametrize("case", ["ia4_R20", "mi4_R20"])
def test_reference_cases(case):
    import json

    from conftest import ISN, need

    path = need(ISN / f"{case}.npz", "shared test data")
    d = np.load(path)
    expected = json.loads((ISN / "expected.json").read_text())[case]
    g = septa.grid.box(int(d["grid_res"]), d["bbox"])
    job = septa.arrangement if case.startswith("ia") else septa.material_interface
    net = job(g, d["values"], threads=1)
    assert all(net.summary()[k] == expected[k] for k in ("vertices", "faces", "patches", "chains", "shells", "cells"))


def test_python_equals_command_line(tmp_path):
    from conftest import SEPTA, need

    exe = need(SEPTA, "the command line (scripts/test.sh builds it)")
    spec = [{"type": "sphere", "center": [0.4, 0.45, 0.5], "radius": 0.3},
            {"type": "sphere", "center": [0.6, 0.5, 0.55], "radius": 0.25},
            {"type": "plane", "point": [0.5, 0.5, 0.5], "normal": [0, 0, 1]}]
    (tmp_path / "f.json").write_text(__import__("json").dumps(spec))
    out = subprocess.run([str(exe), "ia", str(tmp_path / "f.json"), "--grid", "16", "--bounds", "0", "0", "0", "1", "1", "1", "-o", str(tmp_path / "o"), "--json"],
                         capture_output=True, text=True, check=True)
    cli = __import__("json").loads(out.stdout)
    g = septa.grid.box(16)
    fs = [shapes.sphere(s["center"], s["radius"]) if s["type"] == "sphere" else shapes.plane(s["point"], s["normal"]) for s in spec]
    py = septa.arrangement(g, shapes.sample(fs, g)).summary()
    assert _counts(py) == _counts(cli)
    # And the written network loads to the same summary.
    assert _counts(septa.load(tmp_path / "o").summary()) == _counts(cli)


def test_toml_scenes(tmp_path):
    """A scene may be TOML (``.toml``): the same network as its JSON twin,
    from septa.region_surfaces and septa.distributed; errors name the line."""
    import json as _json

    import septa
    from septa import distributed as sd

    from conftest import ROOT

    toml = (ROOT / "tests" / "fixtures" / "two-spheres.toml").read_text()
    import tomllib

    (tmp_path / "s.toml").write_text(toml)
    (tmp_path / "s.json").write_text(_json.dumps(tomllib.loads(toml)))
    a = septa.region_surfaces(str(tmp_path / "s.toml"))
    b = septa.region_surfaces(str(tmp_path / "s.json"))
    assert a.points.tobytes() == b.points.tobytes() and (a.indices == b.indices).all() and len(a) > 0
    c = sd.arrangement(tmp_path / "s.toml", client=None, block=4)
    d = sd.arrangement(tmp_path / "s.json", client=None, block=4)
    assert c.summary()["cells"] == d.summary()["cells"] == 4
    (tmp_path / "bad.toml").write_text(toml.replace("radius = 0.6", "radius = -0.6"))
    with pytest.raises(septa.InputError, match=r"bad.toml:20:10: functions\[1\].radius"):
        septa.region_surfaces(str(tmp_path / "bad.toml"))
