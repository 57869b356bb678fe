"""Planar cut-cell meshes (TopoCut, Fang et al. 2022) as a full result:
``septa.cut_mesh`` returns :class:`CutCells`, which saves to the files of
``septa cut`` (binary polyhedral .vtu, .obj, OpenFOAM polyMesh) and converts
to pyvista and meshio."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from . import _septa
from . import _inputs

__all__ = ["CutCells", "cut_mesh"]


def _split(values: np.ndarray, offsets: np.ndarray) -> list:
    return np.split(values, offsets[1:-1]) if len(offsets) > 1 else []


class CutCells:
    """A planar cut-cell mesh, exact in its combinatorics.

    Attributes (numpy arrays unless said):

    - ``points`` ``(#V, 3) float64``: the certified floating-point embedding
      of the cut-vertices (the first ``cut_vertices`` rows), then the face
      centres the embedding added to split faces that no nearby doubles keep
      planar;
    - ``faces``: per cut-face, a list of its loops (``int64`` point ids): the
      outer boundary first, counter-clockwise about the support normal, then
      its holes (clockwise);
    - ``face_cells`` ``(#F, 2) int64``: the cell the face normal points out of,
      then the cell it points into (-1: outside the domain, for faces on the
      input surface);
    - ``face_plane`` / ``face_triangle`` ``(#F,) int64``: the cut plane (row of
      ``planes``) or the input triangle each face lies on, -1 for the other
      kind;
    - ``cells``: per cell, an ``(k, 2) int64`` array of its faces with their
      orientation (+1: the face normal points out of the cell, -1: into it);
    - ``cell_volumes`` ``(#C,) float64``; ``planes`` ``(#P, 4)``: the planes
      used (duplicates dropped);
    - ``face_polygons``: per cut-face, the polygons it is written as
      (itself, or its triangles when it has holes or its rounded vertices are
      not exactly coplanar); ``cell_polygons()`` gives each cell's written
      polygons oriented outwards (what .vtu, .obj, pyvista and meshio get).
    """

    def __init__(self, core):
        self._core = core
        self._summary = json.loads(core.summary())
        a = core.arrays()
        self.points = a["points"]
        self.cut_vertices = int(a["cut_vertices"])
        loops = _split(a["loop_vertices"], a["loop_offsets"])
        flo = a["face_loop_offsets"]
        self.faces = [loops[s:e] for s, e in zip(flo[:-1], flo[1:])]
        polys = _split(a["polygon_vertices"], a["polygon_offsets"])
        fpo = a["face_polygon_offsets"]
        self.face_polygons = [polys[s:e] for s, e in zip(fpo[:-1], fpo[1:])]
        self.face_cells = a["face_cells"]
        self.face_plane, self.face_triangle = a["face_plane"], a["face_triangle"]
        self.cell_volumes, self.planes = a["cell_volumes"], a["planes"]
        nf, nc = len(self.faces), len(self.cell_volumes)
        cell = np.concatenate([self.face_cells[:, 0], self.face_cells[:, 1]])
        face = np.concatenate([np.arange(nf), np.arange(nf)])
        sign = np.concatenate([np.ones(nf, np.int64), -np.ones(nf, np.int64)])
        keep = cell >= 0
        cell, face, sign = cell[keep], face[keep], sign[keep]
        order = np.argsort(cell, kind="stable")
        bounds = np.searchsorted(cell[order], np.arange(nc + 1))
        pairs = np.stack([face[order], sign[order]], axis=1)
        self.cells = [pairs[bounds[c]:bounds[c + 1]] for c in range(nc)]

    def summary(self) -> dict:
        """Counts, checks and what the certified embedding changed (as ``cut.json``)."""
        return dict(self._summary)

    def cell_polygons(self) -> list:
        """Per cell, its written boundary polygons (``int64`` point ids), oriented outwards."""
        return [[p if s > 0 else p[::-1] for f, s in c for p in self.face_polygons[f]] for c in self.cells]

    def save(self, path, format: str | None = None) -> Path:
        """Writes ``path``: ``.vtu`` (binary ``VTK_POLYHEDRON`` cells with
        ``cell_id`` and ``volume``, as ``cells.vtu``), ``.obj`` (a group per
        cell), or OpenFOAM (``format="foam"``, or a path ending in
        ``polyMesh``; see :meth:`save_foam`). Returns the path written."""
        path = Path(path)
        fmt = (format or ("foam" if path.name == "polyMesh" else path.suffix.lstrip("."))).lower()
        if fmt == "vtu":
            self._core.write_vtu(str(path))
        elif fmt == "obj":
            self._core.write_obj(str(path))
        elif fmt == "foam":
            return self.save_foam(path)
        else:
            raise _septa.InputError(f"{path}: cannot tell the format; use .vtu, .obj, a polyMesh folder or format='foam'")
        return path

    def save_foam(self, path) -> Path:
        """Writes an OpenFOAM ``polyMesh`` (points, faces, owner, neighbour,
        boundary with the patch ``surface`` for the input surface and an
        empty patch per plane family, faceZones per plane family) into
        ``path`` if it ends in ``polyMesh``, else into
        ``path/constant/polyMesh`` (a case folder). Returns that folder.

        PolyMesh cell ``i`` is cell ``i`` here, except when the last cell has
        no face on the input surface: it would own no face (OpenFOAM's
        owner < neighbour) and readers that count cells from the owner list
        (fluidfoam) would miss it, so it trades its number with the last
        cell that has one; ``foam_cells_swapped`` then holds the pair (else
        ``None``)."""
        path = Path(path)
        if path.name != "polyMesh":
            path = path / "constant" / "polyMesh"
        self.foam_cells_swapped = self._core.write_foam(str(path))
        return path

    def to_pyvista(self):
        """A ``pyvista.UnstructuredGrid`` of ``VTK_POLYHEDRON`` cells with cell
        data ``cell_id`` and ``volume``."""
        import pyvista as pv

        stream = []
        for c in self.cell_polygons():
            cell = [len(c)]
            for p in c:
                cell.append(len(p))
                cell.extend(p.tolist())
            stream.append(len(cell))
            stream.extend(cell)
        nc = len(self.cells)
        g = pv.UnstructuredGrid(np.asarray(stream, dtype=np.int64), np.full(nc, pv.CellType.POLYHEDRON, np.uint8),
                                self.points.copy())
        g.cell_data["cell_id"] = np.arange(nc, dtype=np.int64)
        g.cell_data["volume"] = self.cell_volumes.copy()
        return g

    def to_meshio(self):
        """A ``meshio.Mesh`` with one ``polyhedron<N>`` block per number of
        cell points N (ascending; cells in id order inside a block, as
        meshio's own .vtu reader groups them) and cell data ``cell_id`` and
        ``volume`` to map rows back to cells."""
        import meshio

        polys = self.cell_polygons()
        npts = np.array([len(np.unique(np.concatenate(c))) for c in polys], dtype=np.int64)
        blocks, ids = [], []
        for n in np.unique(npts):
            sel = np.flatnonzero(npts == n)
            blocks.append((f"polyhedron{n}", [polys[i] for i in sel]))
            ids.append(sel)
        return meshio.Mesh(self.points.copy(), blocks,
                           cell_data={"cell_id": ids, "volume": [self.cell_volumes[i] for i in ids]})

    def _viewer_network(self):
        """The viewer's network contract for these cells (as ``septa view``
        makes from cells.obj): every cell's outward polygons, patch = cell."""
        faces, owner = [], []
        for c, polys in enumerate(self.cell_polygons()):
            faces.extend(p.tolist() for p in polys)
            owner.extend([c] * len(polys))
        nc = len(self.cells)
        counts = np.bincount(np.asarray(owner, dtype=np.int64), minlength=nc)
        data = {
            "mode": "cut", "points": self.points.tolist(), "faces": faces, "face_patch": owner,
            "face_cells": [[c, -1] for c in owner],
            "patches": [{"label": [c], "faces": int(counts[c])} for c in range(nc)],
            "chains": [], "corners": [], "shells": [],
            "cells": [{"shells": [], "label": [c], "name": f"cell_{c}"} for c in range(nc)],
            "counts": {"vertices": len(self.points), "faces": len(faces), "cells": nc},
        }
        return type("CutNetwork", (), {"data": data, "source": None})()


def cut_mesh(vertices, triangles, planes, *, threads=None, progress=None) -> CutCells:
    """Planar cut-cell mesh of a closed, outward triangle mesh by planes (TopoCut).

    ``vertices`` ``(#V, 3)``, ``triangles`` ``(#T, 3)``, ``planes`` ``(#P, 4)``
    rows ``a b c d`` for ``a x + b y + c z + d = 0``. Returns :class:`CutCells`;
    the combinatorics are exact, the same as ``septa cut``. ``progress(done,
    total)``, if given, is called as each stage of the cut ends (from a worker
    thread; an exception in it is printed, not raised).

    >>> import septa, numpy as np
    >>> v = np.array([[0,0,0],[1,0,0],[0,1,0],[0,0,1]], float)
    >>> t = np.array([[0,2,1],[0,1,3],[0,3,2],[1,2,3]])
    >>> septa.cut_mesh(v, t, [[1, 0, 0, -0.25]]).summary()["cut_cells"]
    2
    """
    v = np.ascontiguousarray(vertices, dtype=np.float64)
    _septa.check_values(v.reshape(-1, 3), "vertices")
    t = _inputs.integer_array(triangles, "triangles")
    if t.ndim != 2 or t.shape[1] != 3 or (len(t) and (t.min() < 0 or t.max() >= len(v))):
        raise _septa.InputError("triangles: expected (#T, 3) indices into vertices")
    p = np.ascontiguousarray(planes, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 4:
        raise _septa.InputError(f"planes: expected shape (#P, 4), got {p.shape}")
    _septa.check_values(p, "planes")
    if progress is not None and not callable(progress):
        raise _septa.InputError("progress: expected a callable progress(done, total)")
    return CutCells(_septa.cut(v, t, p, threads=_inputs.threads(threads) or 0, progress=progress))
