"""septa.distributed on a real dask.distributed LocalCluster (two worker
processes): every output array identical to the single-process sparse run
and to the dense path; results merge the same in any order; bad bytes are
refused with a clear error."""
import json
import random
from pathlib import Path

import numpy as np
import pytest

import septa
from septa import _septa
from septa import distributed as sd
from septa.network import Network

SPECS = Path(__file__).resolve().parents[2] / "data" / "specs"


@pytest.fixture(scope="module")
def client():
    dd = pytest.importorskip(
        "dask.distributed", reason="dask.distributed is not installed (pip install 'dask[distributed]')"
    )
    cluster = dd.LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None)
    c = dd.Client(cluster)
    yield c
    c.close()
    cluster.close()


def assert_same(a: Network, b: Network, what: str):
    """Every array of the two networks is equal (points bit for bit)."""
    assert a.mode == b.mode, what
    assert a.points.tobytes() == b.points.tobytes(), f"{what}: points"
    for name in ("offsets", "indices", "face_patch", "face_cells", "face_label", "patch_labels", "corners"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), f"{what}: {name}"
    assert np.array_equal(a._patch_faces, b._patch_faces), f"{what}: patch faces"
    for name in ("chains", "chain_patches", "shells"):
        la, lb = getattr(a, name), getattr(b, name)
        assert len(la) == len(lb) and all(np.array_equal(x, y) for x, y in zip(la, lb)), f"{what}: {name}"
    assert a.cells == b.cells, f"{what}: cells"
    sa, sb = a.summary(), b.summary()
    for k in ("vertices", "faces", "patches", "chains", "corners", "shells", "cells", "components", "active_tets"):
        assert sa[k] == sb[k], f"{what}: {k}"


def dense(job: dict) -> Network:
    return Network._from_core(_septa.sparse_network(json.dumps(job), dense=True))


@pytest.mark.parametrize(
    "spec, mode", [("ia18", "ia"), ("mi18", "mi"), ("separate8", "ia"), ("nested8", "ia")]
)
def test_distributed_equals_local_and_dense(client, spec, mode):
    job_fn = sd.arrangement if mode == "ia" else sd.material_interface
    path = SPECS / f"{spec}.json"
    dist = job_fn(path, client=client, grid=24, block=8)
    local = job_fn(path, client=None, grid=24, block=8)
    assert_same(dist, local, f"{spec} distributed vs local")
    assert_same(dist, dense(sd.job_spec(path, mode=mode, grid=24, block=8)), f"{spec} distributed vs dense")
    blocks = dist.summary()["blocks"]
    assert blocks == local.summary()["blocks"] and blocks["bytes"] > 0
    assert blocks["total"] == 27 and blocks["sampled"] + blocks["skipped"] == 27
    assert blocks["active"] > 0 and not blocks["dense_fallback"]
    assert dist.summary()["faces"] > 0


def test_one_block_per_task_and_any_arrival_order(client):
    # Separate spheres: blocks between them are skipped; cells are bounded
    # by several shells, found by rays across skipped blocks.
    job = sd.job_spec(SPECS / "separate8.json", mode="ia", grid=32, block=4)
    text = json.dumps(job)
    plan = _septa.sparse_plan(text)
    blocks, kept, is_dense = plan
    assert blocks == 512 and 0 < len(kept) < blocks and not is_dense
    futures = client.map(sd._run_blocks, [text] * len(kept), [[i] for i in kept], pure=False)
    results = [b for part in client.gather(futures) for b in part]
    random.Random(6).shuffle(results)
    shuffled = Network._from_core(_septa.sparse_finish(text, plan, results))
    assert_same(shuffled, dense(job), "shuffled")
    assert_same(shuffled, sd.arrangement(SPECS / "separate8.json", client=client, grid=32, block=4, batch=1), "batch 1")


def test_region_surfaces_distributed(client):
    net = sd.region_surfaces("builtin:sphere-with-hole", client=client, block=8)
    ref = septa.region_surfaces("builtin:sphere-with-hole")
    assert net.surfaces == ref.surfaces and net.curves == ref.curves
    assert net.points.tobytes() == ref.points.tobytes()
    assert np.array_equal(net.indices, ref.indices)
    # Normals (one copy per vertex and region pair) the same as the local run's.
    net = sd.region_surfaces("builtin:sphere-with-hole", client=client, block=8, normals=True)
    ref = septa.region_surfaces("builtin:sphere-with-hole", normals=True)
    assert all(np.array_equal(net.normals[k], ref.normals[k]) for k in ("vertex", "regions", "normal"))
    assert np.array_equal(net.indices_normal, ref.indices_normal)


def test_bad_block_results_are_clear_errors():
    job = sd.job_spec(SPECS / "ia18.json", mode="ia", grid=12, block=4)
    text = json.dumps(job)
    plan = _septa.sparse_plan(text)
    results = _septa.sparse_blocks(text, plan[1])
    with pytest.raises(septa.InputError, match="truncated"):
        _septa.sparse_finish(text, plan, results[:-1] + [results[-1][:100]])
    with pytest.raises(septa.InputError, match="checksum"):
        bad = bytearray(results[0])
        bad[len(bad) // 2] ^= 1
        _septa.sparse_finish(text, plan, [bytes(bad)] + results[1:])
    with pytest.raises(septa.InputError, match="block results"):
        _septa.sparse_finish(text, plan, results[1:])
    other = json.dumps({**job, "mode": "mi"})
    with pytest.raises(septa.InputError, match="another job"):
        _septa.sparse_finish(other, plan, results)
    with pytest.raises(septa.InputError, match="grid"):
        sd.arrangement([septa.shapes.sphere([0, 0, 0], 0.5)], client=None)


def test_continuation_of_a_python_function_on_the_cluster(client):
    # A closure over numpy arrays, pickled to the workers by Dask.
    from septa import continuation

    c = np.array([[0.013, -0.007, 0.004], [0.4113, 0.3687, -0.2209]])
    r = np.array([0.61, 0.3317])

    def f(p):
        d = p[:, None, :] - c[None]
        return r[None] - np.sqrt(d[..., 0] * d[..., 0] + d[..., 1] * d[..., 1] + d[..., 2] * d[..., 2])

    # IA: a point on sphere 0; MI: the point of the centres' segment where both are equal.
    u = (c[1] - c[0]) / np.linalg.norm(c[1] - c[0])
    t = (r[0] - r[1] + np.linalg.norm(c[1] - c[0])) / 2
    for job, seed in ((continuation.arrangement, [c[0] + [r[0], 0, 0]]), (continuation.material_interface, [c[0] + t * u])):
        dist = job(f, 2, grid=32, block=4, seeds=seed, client=client)
        local = job(f, 2, grid=32, block=4, seeds=seed)
        assert_same(dist, local, f"{job.__name__} continuation")
        assert_same(dist, job(f, 2, grid=32, block=4, dense=True), f"{job.__name__} continuation vs dense")
        b, lb = dist.summary()["blocks"], local.summary()["blocks"]
        assert b["rounds"] == lb["rounds"] > 3 and b["seeds"] == lb["seeds"] == 1
        assert b["sampled"] == lb["sampled"] and b["skipped"] > 0


def test_distributed_stream_writes_the_local_files(client, tmp_path):
    """Blocks on the cluster, fed in order here: the PLY and the topology
    JSON are byte for byte those of the single-process stream."""
    spec = SPECS / "ia18.json"
    local = septa.stream.stream_ply(spec, tmp_path / "local.ply", grid=24, block=6, mode="ia")
    dist = sd.stream_ply(spec, tmp_path / "dist.ply", client=client, grid=24, block=6, mode="ia", batch=3, in_flight=2)
    assert dist["counts"] == local["counts"] and dist["counts"]["cells"] > 1
    assert (tmp_path / "dist.ply").read_bytes() == (tmp_path / "local.ply").read_bytes()
    strip = lambda p: json.loads(p.read_text()) | {"seconds": None}
    assert strip(tmp_path / "dist.topology.json") == strip(tmp_path / "local.topology.json")
    net = sd.arrangement(spec, client=client, grid=24, block=6)
    s = net.summary()
    assert all(dist["counts"][k] == s[k] for k in ("vertices", "faces", "patches", "chains", "shells", "cells"))
    # A plane through grid vertices (faces lying in tet faces, some on block
    # boundaries) streams on the cluster as it does here.
    planes = [septa.shapes.plane([0, 0, 0], [1, 0, 0]), septa.shapes.sphere([0, 0, 0], 0.5)]
    local = septa.stream.stream_ply(planes, tmp_path / "plane.ply", grid=8, block=4, mode="ia")
    dist = sd.stream_ply(planes, tmp_path / "dplane.ply", client=client, grid=8, block=4, mode="ia")
    assert dist["counts"] == local["counts"] and dist["counts"]["cells"] == 4
    assert (tmp_path / "dplane.ply").read_bytes() == (tmp_path / "plane.ply").read_bytes()
    # Two spheres touching at a grid vertex (sheets meeting at a point, their
    # shells linked there): the same answer as in memory.
    tangent = [septa.shapes.sphere([-0.5, 0, 0], 0.5), septa.shapes.sphere([0.5, 0, 0], 0.5)]
    net = dense(sd.job_spec(tangent, grid=8, block=4))
    local = septa.stream.stream_ply(tangent, tmp_path / "tangent.ply", grid=8, block=4, mode="ia")
    dist = sd.stream_ply(tangent, tmp_path / "dtangent.ply", client=client, grid=8, block=4)
    assert dist["counts"] == local["counts"] and local["counts"]["cells"] == len(net.cells) == 3
    assert (tmp_path / "dtangent.ply").read_bytes() == (tmp_path / "tangent.ply").read_bytes()
    # A job stopped part way (an error raised from the progress callback
    # after the first results) leaves no file.
    def stop(done, total):
        raise RuntimeError("stopped by the test")

    with pytest.raises(RuntimeError, match="stopped by the test"):
        sd.stream_ply(tangent, tmp_path / "bad.ply", client=client, grid=8, block=4, progress=stop)
    assert not list(tmp_path.glob("*bad*")) and not list(tmp_path.glob(".bad*"))
