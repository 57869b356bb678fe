"""The jobs, with the command line's names. Inputs are coerced once to
contiguous float64 / int64 arrays and validated in Rust (without the GIL);
errors are :class:`septa.InputError` (a ``ValueError``) naming what and where.

``arrangement`` and ``material_interface`` run the exact core in Rust with
the GIL released. ``region_surfaces`` and ``cut_mesh`` are not wired yet:
they raise ``NotImplementedError``; ``septa regions|cut -o OUTDIR`` and
:func:`septa.load` give their results meanwhile.
"""
from __future__ import annotations

import numpy as np

from . import _septa
from .grid import Grid
from .network import Network

__all__ = ["arrangement", "material_interface", "region_surfaces", "cut_mesh"]

_PENDING = (
    "{job}: the exact core is not wired to Python in this build yet; "
    "run `septa {cli} ... -o OUTDIR` and load the result with septa.load(OUTDIR)"
)


def _grid_inputs(grid_or_vertices, tets, values):
    if isinstance(grid_or_vertices, Grid):
        if values is None:
            values, tets = tets, None
        vertices, tets = grid_or_vertices.vertices, grid_or_vertices.tets if tets is None else tets
    else:
        vertices = grid_or_vertices
    v = np.ascontiguousarray(vertices, dtype=np.float64)
    if v.ndim != 2 or v.shape[1] != 3:
        raise _septa.InputError(f"vertices: expected shape (#V, 3), got {v.shape}")
    _septa.check_values(v, "vertices")
    t = np.ascontiguousarray(tets, dtype=np.int64)
    if t.ndim != 2:
        raise _septa.InputError(f"tets: expected shape (#T, 4), got {t.shape}")
    _septa.check_tets(t, len(v))
    f = np.asarray(values, dtype=np.float64)
    if f.ndim == 1:
        f = f[:, None]
    f = np.ascontiguousarray(f)
    if f.ndim != 2 or f.shape[0] != len(v):
        raise _septa.InputError(f"values: expected shape ({len(v)}, k), got {f.shape}")
    _septa.check_values(f, "values")
    return v, t, f


def _network(mode, grid_or_vertices, tets, values, threads, lookup, cells):
    v, t, f = _grid_inputs(grid_or_vertices, tets, values)
    if cells not in ("raytrace", "grouping"):
        raise _septa.InputError(f'cells must be "raytrace" or "grouping", not {cells!r}')
    box = None
    g = grid_or_vertices
    if isinstance(g, Grid) and g.resolution is not None and (tets is None or values is None or tets is g.tets):
        box = (tuple(g.resolution), g.bounds.tolist(), g.split)
    d = _septa.network(mode, v, t, f, box, lookup=lookup, raytrace=(cells == "raytrace"), threads=threads)
    return Network._from_core(d)


def arrangement(grid_or_vertices, tets, values=None, *, threads=None, lookup=True, cells="raytrace"):
    """Implicit arrangement of the zero sets of k functions sampled on a tet grid.

    ``arrangement(grid, values)`` or ``arrangement(vertices, tets, values)``
    with ``values`` ``(#V, k) float64`` (a 1-D array is one function).
    ``threads``: worker threads (default all cores); ``lookup``: use the
    look-up tables; ``cells``: ``"raytrace"`` or ``"grouping"``.
    Returns a :class:`septa.Network`; the same as ``septa ia``.

    >>> import septa
    >>> from septa import shapes
    >>> g = septa.grid.box(4)
    >>> f = shapes.sample([shapes.plane([.5] * 3, [1, 0, 0]), shapes.plane([.5] * 3, [0, 1, 0])], g)
    >>> s = septa.arrangement(g, f).summary()
    >>> s["patches"], s["chains"], s["cells"]
    (4, 1, 4)
    """
    return _network("ia", grid_or_vertices, tets, values, threads, lookup, cells)


def material_interface(grid_or_vertices, tets, values=None, *, threads=None, lookup=True, cells="raytrace"):
    """Material interface (argmax partition) of k functions on a tet grid;
    the same arguments as :func:`arrangement`, the same result as ``septa mi``."""
    return _network("mi", grid_or_vertices, tets, values, threads, lookup, cells)


def region_surfaces(scene_or_functions, rule=None, *, surfaces=None, curves=None):
    """Non-manifold implicit shape: surfaces and curves of interest of a region rule."""
    raise NotImplementedError(_PENDING.format(job="region_surfaces", cli="regions"))


def cut_mesh(vertices, triangles, planes):
    """Planar cut-cell mesh of a closed triangle mesh by planes."""
    v = np.ascontiguousarray(vertices, dtype=np.float64)
    _septa.check_values(v.reshape(-1, 3), "vertices")
    t = np.ascontiguousarray(triangles, dtype=np.int64)
    if t.ndim != 2 or t.shape[1] != 3 or (len(t) and (t.min() < 0 or t.max() >= len(v))):
        raise _septa.InputError("triangles: expected (#T, 3) indices into vertices")
    raise NotImplementedError(_PENDING.format(job="cut_mesh", cli="cut"))
