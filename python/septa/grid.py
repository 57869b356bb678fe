"""Built-in tetrahedral grids.

A box of ``nx x ny x nz`` cubes; vertex ``(i, j, k)`` (i along x) has index
``i*(ny+1)*(nz+1) + j*(nz+1) + k``, as in the reference implementation's
grids (``shared/data/isn/README.md``). ``split=5`` cuts each cube into 5
tets, mirrored with the parity of ``i+j+k`` so neighbouring cubes' face
diagonals match; ``split=6`` cuts each cube into the 6 tets around its
main diagonal. Every tet is positively oriented.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._septa import InputError

__all__ = ["Grid", "box"]

# Cube corners as (di, dj, dk) bits: corner c = 4*di + 2*dj + dk.
# Five-tet split of the odd cube (i+j+k odd): the central tet on corners
# 0,3,5,6 and the four corner tets cut off around corners 1, 2, 4, 7. The
# even cube uses the mirror image (x -> 1 - x: central tet on 1,2,4,7, as the
# reference's cube (0,0,0)) so face diagonals of neighbours meet.
_FIVE_ODD = np.array([[0, 3, 5, 6], [1, 0, 3, 5], [2, 0, 6, 3], [4, 0, 5, 6], [7, 3, 6, 5]])
_MIRROR_X = np.array([4, 5, 6, 7, 0, 1, 2, 3])
_FIVE_EVEN = _MIRROR_X[_FIVE_ODD]
# Six tets around the diagonal 0-7: one per path 0 -> 7 along cube edges.
_SIX = np.array([[0, 4, 6, 7], [0, 4, 5, 7], [0, 1, 5, 7], [0, 1, 3, 7], [0, 2, 3, 7], [0, 2, 6, 7]])


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


def _orient(vertices: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """Swaps two vertices of every negatively oriented tet."""
    p = vertices[tets]
    vol = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), p[:, 3] - p[:, 0])
    tets = tets.copy()
    neg = vol < 0
    tets[neg, 2], tets[neg, 3] = tets[neg, 3], tets[neg, 2].copy()
    return tets


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

    i, j, k = np.meshgrid(np.arange(nx + 1), np.arange(ny + 1), np.arange(nz + 1), indexing="ij")
    ijk = np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1).astype(np.float64)
    # lo + (hi - lo) * i / n, and exactly hi at i = n: the same numbers as the
    # Rust box grid, so values sampled here equal the command line's.
    n = np.array([nx, ny, nz], dtype=np.float64)
    vertices = b[0] + (b[1] - b[0]) * ijk / n
    vertices = np.where(ijk == n, b[1], vertices)

    ci, cj, ck = (a.ravel() for a in np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij"))
    sy, sx = nz + 1, (ny + 1) * (nz + 1)
    base = ci * sx + cj * sy + ck
    offsets = np.array([(c >> 2) * sx + ((c >> 1) & 1) * sy + (c & 1) for c in range(8)], dtype=np.int64)
    corners = base[:, None].astype(np.int64) + offsets[None, :]  # (#cubes, 8)
    if split == 6:
        tets = corners[:, _SIX].reshape(-1, 4)
    else:
        odd = ((ci + cj + ck) % 2).astype(bool)
        tets = np.where(odd[:, None, None], corners[:, _FIVE_ODD], corners[:, _FIVE_EVEN]).reshape(-1, 4)
    tets = _orient(vertices, tets)
    return Grid(vertices=vertices, tets=np.ascontiguousarray(tets, dtype=np.int64), resolution=(nx, ny, nz), bounds=b, split=split)
