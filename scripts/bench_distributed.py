"""Distributed (dask LocalCluster) vs single-process time of one sparse job.

    .venv/bin/python scripts/bench_distributed.py [spec] [mode] [resolution] [block] [workers]

defaults: data/specs/ia18.json ia 60 16 2. Prints the seconds of each run
and their ratio against the single-process run measured in the same run,
and checks that the two networks are identical.
"""
import json
import sys
import time

import numpy as np
from dask.distributed import Client, LocalCluster

import septa
from septa import _septa
from septa import distributed as sd
from septa.network import Network


def main():
    spec = sys.argv[1] if len(sys.argv) > 1 else "data/specs/ia18.json"
    mode = sys.argv[2] if len(sys.argv) > 2 else "ia"
    n = int(sys.argv[3]) if len(sys.argv) > 3 else 60
    block = int(sys.argv[4]) if len(sys.argv) > 4 else 16
    workers = int(sys.argv[5]) if len(sys.argv) > 5 else 2
    job = sd.job_spec(spec, mode=mode, grid=n, block=block)
    text = json.dumps(job)
    run = sd.arrangement if mode == "ia" else sd.material_interface

    t = time.perf_counter()
    local1 = Network._from_core(_septa.sparse_network(text, threads=1))
    t_local1 = time.perf_counter() - t
    t = time.perf_counter()
    local = Network._from_core(_septa.sparse_network(text))
    t_local = time.perf_counter() - t

    with LocalCluster(n_workers=workers, processes=True, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        sd.arrangement([septa.shapes.sphere([0, 0, 0], 0.5)], client=client, grid=8, block=4)  # warm up workers
        t = time.perf_counter()
        dist = run(spec, client=client, grid=n, block=block)
        t_dist = time.perf_counter() - t
    same = (dist.points.tobytes() == local.points.tobytes() and np.array_equal(dist.indices, local.indices)
            and np.array_equal(dist.face_cells, local.face_cells) and dist.cells == local.cells
            and dist.points.tobytes() == local1.points.tobytes())
    s = dist.summary()
    print(json.dumps({
        "spec": spec, "mode": mode, "resolution": n, "block": block, "workers": workers,
        "faces": s["faces"], "cells": s["cells"], "blocks": s["blocks"],
        "seconds": {"local_1_thread": round(t_local1, 3), "local_all_threads": round(t_local, 3),
                    "dask_local_cluster": round(t_dist, 3)},
        "dask_steps": {k: round(dist.seconds[k], 3) for k in ("plan", "blocks", "finish")},
        "local_stages": {k: round(v, 3) for k, v in local1.seconds.items()},
        "ratio_dask_over_local_1_thread": round(t_dist / t_local1, 3),
        "identical": bool(same),
    }, indent=1))


if __name__ == "__main__":
    main()
