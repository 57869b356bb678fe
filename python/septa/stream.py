"""Polygons of large networks streamed to disk (docs/sparse.md).

:func:`stream_ply` runs a sparse job block by block and writes each
block's polygons to one binary PLY as soon as it is done, so memory stays
bounded by a few blocks however large the grid: the job the command line
runs as ``septa ia SCENE --grid N --stream OUT.ply``. It gives the polygons
(with their label pair, block index, patch and cells per face, and vertices
shared between blocks written once) and the topology, assembled from
per-block summaries while the polygons stream: patches, chains, corners,
shells and cells in ``OUT.topology.json`` (``network.json``'s names; chain
vertex ids are the PLY's), equal to the in-memory network's up to numbering.

>>> import septa, tempfile, pathlib
>>> out = pathlib.Path(tempfile.mkdtemp()) / "spheres.ply"
>>> spheres = [septa.shapes.sphere([0, 0, 0], 0.45), septa.shapes.sphere([0.31, 0, 0], 0.45)]
>>> s = septa.stream.stream_ply(spheres, out, grid=16, block=4)
>>> s["faces"] > 0 and out.exists(), s["blocks"]["total"]
(True, 64)
>>> s["counts"]["patches"], s["counts"]["cells"]
(4, 4)
"""
import json
import os

from . import _septa
from .distributed import job_spec


def stream_ply(scene_or_functions, path, *, grid=None, mode="ia", block=16, window=0, triangles=False,
               threads=None, topology=True, progress=None) -> dict:
    """Streams the IA or MI polygons of analytic functions to the PLY ``path``
    (or, for a path ending in ``.vtu``, a VTK file with cell data ``patch``,
    ``labels``, ``cells`` and ``block``, which meshio and ParaView read).

    ``scene_or_functions``, ``grid``, ``block``: as :func:`septa.distributed.job_spec`.
    ``window``: blocks computed at a time (0: four per thread). ``triangles``:
    write each polygon as a fan of triangles (what trimesh reads; PLY only). ``topology``:
    assemble patches, chains, shells and cells too (else faces get patch and
    cells -1). Returns ``{"path", "faces" (polygons), "ply_faces", "vertices",
    "active_tets", "blocks": {"total", "skipped", "sampled", "active"}}`` and,
    with topology, ``"counts"`` (as ``network.json``) and ``"topology"`` (the
    JSON's path). Files are written atomically: on an error or Ctrl-C no PLY
    is left. ``progress``: a function ``progress(done, total)`` called as
    blocks finish (``total``: the blocks that are not skipped).
    """
    if progress is not None and not callable(progress):
        raise _septa.InputError("progress: expected a function progress(done, total)")
    job = job_spec(scene_or_functions, mode=mode, grid=grid, block=block)
    return _septa.stream_ply(json.dumps(job), os.fspath(path), int(window), bool(triangles), threads,
                             bool(topology), progress)
