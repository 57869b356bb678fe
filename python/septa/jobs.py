"""The jobs, with the command line's names. Inputs are coerced once to
contiguous float64 / int64 arrays and validated in Rust (without the GIL);
errors are :class:`septa.InputError` (a ``ValueError``) naming what and where.

The exact core is being wired to Python (crates/septa-py); until it is, the
jobs validate their input and then raise ``NotImplementedError``. Meanwhile
``septa ia|mi|regions|cut -o OUTDIR`` on the command line and
:func:`septa.load` give the same results.
"""
from __future__ import annotations

import numpy as np

from . import _septa
from .grid import Grid

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


def arrangement(grid_or_vertices, tets, values=None, *, threads=None, lookup=True, cells="raytrace"):
    """Implicit arrangement of the zero sets of k functions sampled on a tet grid.

    ``arrangement(grid, values)`` or ``arrangement(vertices, tets, values)``
    with ``values`` ``(#V, k) float64``. Returns a :class:`septa.Network`.
    """
    _grid_inputs(grid_or_vertices, tets, values)
    raise NotImplementedError(_PENDING.format(job="arrangement", cli="ia"))


def material_interface(grid_or_vertices, tets, values=None, *, threads=None, lookup=True, cells="raytrace"):
    """Material interface (argmax partition) of k functions on a tet grid."""
    _grid_inputs(grid_or_vertices, tets, values)
    raise NotImplementedError(_PENDING.format(job="material_interface", cli="mi"))


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
