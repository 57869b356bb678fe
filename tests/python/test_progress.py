"""``progress=`` on every long Python call: label volumes, streams (local and
block by block here, as on a Dask cluster). Each callback counts up to the
blocks that are run, and a non-callable is refused before any work."""
import numpy as np
import pytest

import septa


def _recorder():
    calls = []
    return calls, lambda done, total: calls.append((done, total))


def _ends_at_all_blocks(calls):
    assert calls, "progress was never called"
    # Blocks finish on several threads: the calls may arrive out of order.
    assert max(d for d, _ in calls) == calls[0][1] > 0
    assert all(0 < d <= t for d, t in calls) and len({t for _, t in calls}) == 1


@pytest.mark.parametrize("sigma", [0.0, 0.8])
def test_label_surfaces_progress(sigma):
    v = np.zeros((24, 24, 24), dtype=np.int32)
    v[4:12, 4:20, 4:20] = 1
    v[12:20, 4:20, 4:20] = 2
    calls, cb = _recorder()
    net = septa.label_surfaces(v, sigma=sigma, progress=cb)
    assert sorted(s["regions"] for s in net.surfaces) == [[0, 1], [0, 2], [1, 2]]
    # Blocks finish on several threads: the counts arrive in any order, but
    # every block is counted once.
    assert len(calls) == calls[0][1] and sorted(d for d, _ in calls) == list(range(1, calls[0][1] + 1))
    with pytest.raises(septa.InputError, match="progress"):
        septa.label_surfaces(v, progress=1)


def test_stream_progress(tmp_path):
    spheres = [septa.shapes.sphere([0, 0, 0], 0.45), septa.shapes.sphere([0.31, 0, 0], 0.45)]
    calls, cb = _recorder()
    s = septa.stream.stream_ply(spheres, tmp_path / "a.ply", grid=16, block=4, progress=cb)
    assert len(calls) == calls[0][1] == s["blocks"]["total"] - s["blocks"]["skipped"]
    assert sorted(d for d, _ in calls) == list(range(1, len(calls) + 1))
    # Fed here in block order by the distributed form: counts only go up.
    calls2, cb2 = _recorder()
    s2 = septa.distributed.stream_ply(spheres, tmp_path / "b.ply", client=None, grid=16, block=4, batch=5,
                                      progress=cb2)
    assert s2["counts"] == s["counts"]
    _ends_at_all_blocks(calls2)
    assert calls2[-1][1] == calls[0][1] and [d for d, _ in calls2] == sorted(d for d, _ in calls2)
    with pytest.raises(septa.InputError, match="progress"):
        septa.stream.stream_ply(spheres, tmp_path / "c.ply", grid=16, block=4, progress="yes")
    assert not (tmp_path / "c.ply").exists()


def test_block_statistics_have_one_set_of_names(tmp_path):
    # The command line's --json and Python's summaries name the sparse block
    # statistics alike (Python's used to say "blocks" where the CLI says "total").
    import json
    import subprocess

    from conftest import SEPTA, need

    need(SEPTA, "the septa binary (cargo build --release -p septa-cli)")
    fs = [{"type": "sphere", "center": [0, 0, 0], "radius": 0.5}, {"type": "sphere", "center": [0.3, 0, 0], "radius": 0.5}]
    (tmp_path / "f.json").write_text(json.dumps(fs))
    out = subprocess.run([str(SEPTA), "ia", str(tmp_path / "f.json"), "--grid", "16", "--block", "4", "--json",
                          "--no-output"], check=True, capture_output=True, text=True)
    cli = json.loads(out.stdout)["blocks"]
    py = septa.distributed.arrangement(fs, client=None, grid=16, block=4).summary()["blocks"]
    assert set(cli) <= set(py) and cli["total"] == py["total"] == 64
    assert py["sampled"] + py["skipped"] == py["total"]
