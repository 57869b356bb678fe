"""Septa jobs on a Dask cluster (docs/distributed.md).

A sparse job has three steps, the same ones the single-process run
composes (so local and distributed outputs are identical by construction):

1. **plan** (here): the grid's blocks are classified by the functions'
   guaranteed bounds; only blocks that may hold a part of the network are kept;
2. **blocks** (on the workers): each kept block is sampled and turned into
   its part of the network, returned as ``bytes`` (Septa's versioned binary
   layout, checksummed); workers receive the job as JSON text, never Rust
   objects, so they only need ``pip install septa``;
3. **finish** (here): the block results are merged in block order (whatever
   order they arrived in), the topology (patches, chains, shells, cells by
   ray shooting) is found and the :class:`septa.Network` assembled.

Scheduling is Dask's: ``client.map`` over batches of block indices and
``client.gather``. For networks larger than the client's memory,
:func:`stream_ply` feeds results in block order to a streamed PLY and the
topology assembled from block summaries, a bounded number in flight. Without a client (``client=None``) the job runs in this
process with the same core (``compute_sparse``).

>>> import septa.distributed as sd
>>> from septa import shapes
>>> fs = [shapes.sphere([0.1, 0, 0], 0.5), shapes.sphere([-0.2, 0.1, 0], 0.4)]
>>> sd.arrangement(fs, client=None, grid={"resolution": 16}, block=8).summary()["cells"]
4

With a cluster (see docs/distributed.md)::

    from dask.distributed import Client
    client = Client("tcp://scheduler:8786")      # workers: pip install septa
    net = sd.material_interface("data/specs/mi18.json", client=client,
                                grid={"resolution": 400}, block=32)
"""
from __future__ import annotations

import json
import math
import os
import time
from collections import deque

from . import _septa
from .network import Network

__all__ = ["arrangement", "material_interface", "region_surfaces", "stream_ply", "job_spec"]


def _primitive_spec(f):
    if isinstance(f, dict):
        return f
    if hasattr(f, "to_spec"):
        return f.to_spec()
    raise _septa.InputError(f"functions: expected primitive dicts or septa.shapes primitives, got {type(f).__name__}")


def _grid_spec(grid):
    if grid is None:
        return None
    if isinstance(grid, int):
        return {"resolution": grid}
    if not isinstance(grid, dict) or "resolution" not in grid:
        raise _septa.InputError('grid: expected n or {"resolution": n or [nx, ny, nz], "bounds": [[..], [..]], "split": 5}')
    g = dict(grid)
    if "bounds" in g:
        g["bounds"] = [[float(x) for x in c] for c in g["bounds"]]
    return g


def job_spec(scene_or_functions, *, mode=None, grid=None, block=16) -> dict:
    """The JSON-able job a worker receives.

    ``scene_or_functions``: a list of primitives (``septa.shapes`` objects or
    dicts in the reference / scene JSON form), a scene dict, ``"builtin:NAME"``,
    or the path of a reference function file (a JSON list) or scene file
    (JSON, or TOML with a ``.toml`` name; read here, so workers need no access to it; mesh paths inside a scene are
    resolved on the workers). ``grid``: ``n`` or ``{"resolution", "bounds",
    "split"}`` (required for a list of functions; overrides a scene's).
    """
    job = {"block": int(block)}
    src = scene_or_functions
    base = None
    if isinstance(src, (str, os.PathLike)) and not str(src).startswith("builtin:"):
        path = os.fspath(src)
        try:
            if path.endswith(".toml"):
                import tomllib

                with open(path, "rb") as fh:
                    src = tomllib.load(fh)
            else:
                with open(path) as fh:
                    src = json.load(fh)
        except OSError as e:
            raise _septa.InputError(f"{path}: cannot read ({e.strerror})") from e
        except json.JSONDecodeError as e:
            raise _septa.InputError(f"{path}:{e.lineno}: invalid JSON: {e.msg}") from e
        except ValueError as e:  # tomllib.TOMLDecodeError
            raise _septa.InputError(f"{path}: invalid TOML: {e}") from e
        base = os.path.dirname(os.path.abspath(path))
    if isinstance(src, str):
        job["scene"] = src
    elif isinstance(src, dict) and "input" not in src:
        job["scene"] = src
    elif isinstance(src, dict):
        job["functions"] = [_primitive_spec(f) for f in src["input"]]
    else:
        job["functions"] = [_primitive_spec(f) for f in src]
    if base is not None:
        job["base_dir"] = base
    g = _grid_spec(grid)
    if g is not None:
        job["grid"] = g
    elif "functions" in job:
        raise _septa.InputError('grid: a list of functions needs a grid, e.g. grid={"resolution": 64}')
    if mode is not None:
        job["mode"] = mode
    return job


def _run_blocks(job_text: str, indices: list) -> list:
    """Worker task: block results as bytes (the GIL is released inside)."""
    from septa import _septa as core

    return core.sparse_blocks(job_text, list(indices))


def _distributed(job: dict, client, batch, regions=False, normals=False):
    text = json.dumps(job, separators=(",", ":"))
    t0 = time.perf_counter()
    plan = _septa.sparse_plan(text)
    t1 = time.perf_counter()
    blocks, kept, dense = plan
    results = []
    if kept and not dense:
        if client is None:
            results = _septa.sparse_blocks(text, kept)
        else:
            if batch is None:
                # About four tasks per worker thread: balance without per-task overhead.
                threads = sum(client.nthreads().values()) or 1
                batch = max(1, math.ceil(len(kept) / (4 * threads)))
            batches = [kept[i:i + batch] for i in range(0, len(kept), batch)]
            # A key of its own (hash=False): a job scattered by content shares its
            # key with an earlier run of the same job, which the scheduler may be
            # releasing ("lost dependencies").
            [job_future] = client.scatter([text], broadcast=True, hash=False)
            futures = client.map(_run_blocks, [job_future] * len(batches), batches, pure=False)
            results = [b for part in client.gather(futures) for b in part]
    t2 = time.perf_counter()
    if regions:
        from .jobs import _region_network

        net = _region_network(_septa.sparse_finish_regions(text, plan, results, normals))
    else:
        net = Network._from_core(_septa.sparse_finish(text, plan, results))
    if "blocks" in net._counts and isinstance(net._counts["blocks"], dict):
        net._counts["blocks"]["bytes"] = sum(len(b) for b in results)  # block results received
    # Wall seconds of the three steps as seen here (the core's own stages stay in net.seconds).
    net.seconds.update({"plan": t1 - t0, "blocks": t2 - t1, "finish": time.perf_counter() - t2})
    return net


def arrangement(scene_or_functions, *, client, grid=None, block=16, batch=None) -> Network:
    """Implicit arrangement of analytic functions, blocks run on a Dask cluster.

    ``client``: a ``dask.distributed.Client`` (``None``: run in this process).
    ``scene_or_functions`` and ``grid``: see :func:`job_spec`. ``block``: block
    edge in cubes; ``batch``: blocks per Dask task (default: about four tasks
    per worker thread). Returns the same :class:`septa.Network` as a local run,
    array for array; ``net.summary()["blocks"]`` says how many blocks were
    skipped, sampled and active and how many ``bytes`` of block results came
    back; ``net.seconds`` has the ``plan``, ``blocks`` and ``finish`` steps.

    >>> from septa import shapes, distributed
    >>> fs = [shapes.plane([0, 0, 0], [1, 0, 0]), shapes.plane([0, 0, 0], [0, 1, 0])]
    >>> s = distributed.arrangement(fs, client=None, grid=8, block=4).summary()
    >>> s["patches"], s["cells"]
    (4, 4)
    """
    return _distributed(job_spec(scene_or_functions, mode="ia", grid=grid, block=block), client, batch)


def material_interface(scene_or_functions, *, client, grid=None, block=16, batch=None) -> Network:
    """Material interface (argmax partition), blocks run on a Dask cluster;
    the same arguments and guarantees as :func:`arrangement`."""
    return _distributed(job_spec(scene_or_functions, mode="mi", grid=grid, block=block), client, batch)


def region_surfaces(scene, *, client, grid=None, block=16, batch=None, normals=False) -> Network:
    """Surfaces and curves of interest of a scene's region rule (as
    :func:`septa.region_surfaces`, with the same ``normals``), blocks on a
    Dask cluster. ``scene``: a scene dict, a scene file path or ``"builtin:NAME"``."""
    if isinstance(scene, (list, tuple)):
        raise _septa.InputError("region_surfaces: needs a scene (with its region rule), not a list of functions")
    return _distributed(job_spec(scene, grid=grid, block=block), client, batch, regions=True, normals=normals)


def stream_ply(scene_or_functions, path, *, client, mode=None, grid=None, block=16, batch=None, in_flight=None,
               triangles=False, topology=True, progress=None) -> dict:
    """Streams a network larger than memory to the PLY ``path``, blocks run
    on a Dask cluster: the distributed form of :func:`septa.stream.stream_ply`.

    Workers return block results as bytes; here they are fed in block order
    to Septa's stream (vertex numbering, the PLY, the topology assembled from
    block summaries) and dropped, so this process holds a bounded number of
    results however large the grid: at most ``in_flight`` batches (default
    two per worker thread) of ``batch`` blocks are submitted at a time.
    ``mode``: ``"ia"`` or ``"mi"`` (default: the scene's, else IA). Returns
    the same dict as :func:`septa.stream.stream_ply`, and writes the same
    bytes: the PLY and ``<path>.topology.json`` do not depend on where the
    blocks ran. On an error or Ctrl-C no PLY is left and pending tasks are cancelled.
    ``progress``: a function ``progress(done, total)`` called here as block
    results are written (``total``: the blocks that are not skipped).

    >>> import septa, tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "s.ply"
    >>> fs = [septa.shapes.sphere([0.1, 0, 0], 0.5), septa.shapes.sphere([-0.2, 0.1, 0], 0.4)]
    >>> s = stream_ply(fs, out, client=None, grid=16, block=8)
    >>> s["counts"]["cells"], out.exists()
    (4, True)
    """
    job = job_spec(scene_or_functions, mode=mode, grid=grid, block=block)
    text = json.dumps(job, separators=(",", ":"))
    plan = _septa.sparse_plan(text)
    kept = plan[1]
    if progress is not None and not callable(progress):
        raise _septa.InputError("progress: expected a function progress(done, total)")
    writer = _septa.StreamWriter(text, os.fspath(path), plan, bool(triangles), bool(topology))
    done = 0

    def feed(results):
        nonlocal done
        writer.feed(results)
        done += len(results)
        if progress is not None:
            progress(done, len(kept))

    if client is None:
        step = batch or 64
        for i in range(0, len(kept), step):
            feed(_septa.sparse_blocks(text, kept[i:i + step]))
        return writer.finish()
    threads = sum(client.nthreads().values()) or 1
    if batch is None:
        # Small tasks: each result waits here until the blocks before it are in.
        batch = max(1, math.ceil(len(kept) / (16 * threads)))
    in_flight = in_flight or 2 * threads
    batches = iter([kept[i:i + batch] for i in range(0, len(kept), batch)])
    [job_future] = client.scatter([text], broadcast=True, hash=False)  # a key of its own, as above
    pending = deque()

    def submit():
        b = next(batches, None)
        if b is not None:
            pending.append(client.submit(_run_blocks, job_future, b, pure=False))

    try:
        for _ in range(in_flight):
            submit()
        while pending:
            fut = pending.popleft()
            results = fut.result()
            fut.release()
            submit()
            feed(results)
            del results
        return writer.finish()
    except BaseException:
        for fut in pending:
            fut.cancel()
        del writer  # an unfinished stream removes its files
        raise
