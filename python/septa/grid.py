"""Built-in tetrahedral grids.

A box of ``nx x ny x nz`` cubes; vertex ``(i, j, k)`` (i along x) has index
``i*(ny+1)*(nz+1) + j*(nz+1) + k``, as in the reference implementation's
grids (``shared/data/isn/README.md``). ``split=5`` cuts each cube into 5
tets, mirrored with the parity of ``i+j+k`` so neighbouring cubes' face
diagonals match; ``split=6`` cuts each cube into the 6 tets around its
main diagonal. Every tet is positively oriented.

The grid is the library's (``septa::grid::BoxGrid``, through the compiled
core): the same vertices, bit for bit, and the same tets as a scene file's
grid or the command line's ``--grid``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _septa
from ._septa import InputError

__all__ = ["Grid", "box"]


@dataclass(frozen=True)
class Grid:
    """A tetrahedral grid.

    Attributes:
        vertices: ``(#V, 3) float64`` positions.
        tets: ``(#T, 4) int64`` vertex ids, positively oriented.
        resolution: cubes along x, y, z (box grids) or None.
        bounds: ``(2, 3) float64`` min and max corner, or None.
        split: 5 or 6 tets per cube (box grids) or None.
    """

    vertices: np.ndarray
    tets: np.ndarray
    resolution: tuple | None = None
    bounds: np.ndarray | None = None
    split: int | None = None

    def __repr__(self) -> str:
        return f"Grid({len(self.vertices)} vertices, {len(self.tets)} tets, resolution={self.resolution}, split={self.split})"


def box(resolution, bounds=((0.0, 0.0, 0.0), (1.0, 1.0, 1.0)), split: int = 5) -> Grid:
    """A box grid of ``resolution`` cubes (an int or ``(nx, ny, nz)``).

    Args:
        resolution: cubes per side, ``R`` or ``(nx, ny, nz)``, each >= 1.
        bounds: ``[[x0, y0, z0], [x1, y1, z1]]`` with ``x0 < x1`` etc.
        split: 5 (alternating, as the reference implementation) or 6.

    Returns:
        A :class:`Grid` with ``(nx+1)(ny+1)(nz+1)`` vertices and
        ``split * nx*ny*nz`` tets.

    >>> g = box(2, [[-1, -1, -1], [1, 1, 1]], split=6)
    >>> len(g.vertices), len(g.tets)
    (27, 48)
    >>> g.vertices[1].tolist()   # vertex (0, 0, 1)
    [-1.0, -1.0, 0.0]
    """
    res = (resolution,) * 3 if np.ndim(resolution) == 0 else tuple(resolution)
    if len(res) != 3 or any(int(r) != r or r < 1 for r in res):
        raise InputError(f"grid.box: resolution must be a positive integer or three of them, got {resolution!r}")
    nx, ny, nz = (int(r) for r in res)
    b = np.asarray(bounds, dtype=np.float64)
    if b.shape != (2, 3) or not np.all(np.isfinite(b)) or np.any(b[1] <= b[0]):
        raise InputError(f"grid.box: bounds must be [[x0,y0,z0],[x1,y1,z1]] with finite min < max, got {bounds!r}")
    if split not in (5, 6):
        raise InputError(f"grid.box: split must be 5 or 6, got {split!r}")

    vertices, tets = _septa.box_grid((nx, ny, nz), b.tolist(), int(split))
    return Grid(vertices=vertices, tets=tets, resolution=(nx, ny, nz), bounds=b, split=split)
