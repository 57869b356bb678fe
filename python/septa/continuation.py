"""Networks of your own Python function, by continuation (docs/sparse.md;
Bloomenthal, *Non-Manifold Surfaces*, 4.5.1).

A function without bounds (any callable ``f(points) -> values`` with
``points`` ``(n, 3) float64`` and values ``(n, k)``) cannot be skipped block
by block by interval arithmetic; instead the search starts from seed blocks
and grows across the block faces the network touches (exactly decided on the
samples). Only the blocks the network meets are sampled, so ``f`` is called
about once per such block (plus once for the coarse scan).

Seeds: ``seeds=[(x, y, z), ...]`` (the blocks holding these points), or by
default a coarse scan of the block corners (a block whose 8 corners show a
sign change, IA, or a change of the largest function, MI). Every connected
piece of the network that meets a seed block is found completely; a piece
that meets none (e.g. a small separate sphere inside one block, invisible at
the corners) is **missed by design** -- give a seed point in it.

>>> import numpy as np
>>> from septa import continuation
>>> def f(p):
...     r = np.sqrt((p[:, 0] - 0.01) ** 2 + (p[:, 1] + 0.02) ** 2 + (p[:, 2] - 0.03) ** 2)
...     return np.stack([0.55 - r, p[:, 0] - 0.013], axis=1)
>>> net = continuation.arrangement(f, 2, grid=16, seeds=[(0.56, -0.02, 0.03)], block=4)
>>> net.summary()["cells"], net.summary()["blocks"]["seeds"]
(4, 1)
"""
from __future__ import annotations

import numpy as np

from . import _septa
from .network import Network

__all__ = ["arrangement", "material_interface"]


def _grid(grid):
    if isinstance(grid, (int, np.integer)):
        grid = {"resolution": int(grid)}
    if not isinstance(grid, dict) or "resolution" not in grid:
        raise _septa.InputError('grid: expected n or {"resolution": n or [nx, ny, nz], "bounds": [[..], [..]], "split": 5}')
    res = grid["resolution"]
    res = [int(res)] * 3 if np.ndim(res) == 0 else [int(x) for x in res]
    bounds = grid.get("bounds", [[-1.0] * 3, [1.0] * 3])
    bounds = [[float(x) for x in c] for c in bounds]
    return res, bounds, int(grid.get("split", 5))


def _blocks(f, k, job, indices):
    """Worker task: one round's blocks as ``(bytes, next blocks)``."""
    from septa import _septa as core

    return core.continuation_blocks(f, k, tuple(job), list(indices))


def _on_cluster(client, mode, f, k, res, bounds, split, block, seeds, batch):
    """The search with each round's blocks on a Dask cluster (``client.map``);
    seeds and the finish here. ``f`` travels to the workers pickled by Dask
    (cloudpickle: closures and lambdas work)."""
    job = (mode, res, bounds, split, int(block))
    frontier = _septa.continuation_seeds(f, int(k), job, seeds)
    n_seeds = len(frontier)
    visited = set(frontier)
    results, rounds = [], 0
    threads = sum(client.nthreads().values()) or 1
    while frontier:
        rounds += 1
        size = batch or max(1, -(-len(frontier) // (4 * threads)))
        parts = [frontier[i:i + size] for i in range(0, len(frontier), size)]
        futures = client.map(_blocks, [f] * len(parts), [int(k)] * len(parts), [job] * len(parts), parts, pure=False)
        nxt = set()
        for part in client.gather(futures):
            for data, neighbours in part:
                results.append(data)
                nxt.update(n for n in neighbours if n not in visited)
        visited |= nxt
        frontier = sorted(nxt)
    net = Network._from_core(_septa.continuation_finish(f, int(k), job, results))
    net._counts["blocks"].update({"seeds": n_seeds, "rounds": rounds})
    return net


def _run(mode, f, k, grid, seeds, block, threads, dense, client=None, batch=None):
    if not callable(f):
        raise _septa.InputError(f"f: expected a callable f(points (n, 3)) -> (n, k), got {type(f).__name__}")
    res, bounds, split = _grid(grid)
    if seeds is not None:
        seeds = [tuple(float(x) for x in p) for p in np.asarray(seeds, dtype=np.float64).reshape(-1, 3)]
    if client is not None and not dense:
        return _on_cluster(client, mode, f, k, res, bounds, split, block, seeds, batch)
    d = _septa.continuation(f, int(k), mode, res, bounds, split=split, block=int(block), seeds=seeds, dense=dense,
                            threads=threads)
    return Network._from_core(d)


def arrangement(f, k, *, grid=32, seeds=None, block=8, threads=None, dense=False, client=None, batch=None) -> Network:
    """Implicit arrangement of the ``k`` functions computed by ``f``.

    ``grid``: ``n`` or ``{"resolution": n or [nx, ny, nz], "bounds": [[..], [..]],
    "split": 5}`` (default bounds ``[-1, 1]^3``); ``seeds``: points, or ``None``
    for the coarse scan; ``block``: block edge in cubes; ``dense=True`` samples
    every vertex instead (the reference result). ``net.summary()["blocks"]``
    reports blocks visited (``sampled``), never visited (``skipped``), ``seeds``
    and search ``rounds``. Exceptions raised by ``f`` become
    :class:`septa.InputError` naming them.

    ``client``: a ``dask.distributed.Client``: each round of the search runs
    its blocks on the cluster (``client.map`` over batches of ``batch`` blocks,
    ``f`` pickled to the workers by Dask); the seeds and the finish run here.
    The result is the same network as without a client.
    """
    return _run("ia", f, k, grid, seeds, block, threads, dense, client, batch)


def material_interface(f, k, *, grid=32, seeds=None, block=8, threads=None, dense=False, client=None,
                       batch=None) -> Network:
    """Material interface (argmax partition) of the ``k`` functions computed
    by ``f``; the same arguments as :func:`arrangement`."""
    return _run("mi", f, k, grid, seeds, block, threads, dense, client, batch)
