"""Surface network results: arrays, summary, saving and converters.

A :class:`Network` holds one job's output (the ``network.json`` contract
written by every job): points, polygon faces as CSR, a triangulated view,
patches with their label pairs, chains, corners, shells and cells.
"""
from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

import numpy as np

from . import _septa
from ._septa import InputError

__all__ = ["Network", "load"]

_COUNT_KEYS = ("vertices", "faces", "patches", "chains", "corners", "shells", "cells")


def _need(module: str, extra: str):
    """Imports an optional package or says how to install it."""
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as e:
        raise ImportError(f"this needs the `{extra}` package: pip install {extra}") from e


class Network:
    """A surface network (patches, chains, corners, shells, cells).

    Attributes (numpy arrays):
        points: ``(#V, 3) float64``.
        offsets, indices: polygon faces as CSR; face f is
            ``indices[offsets[f]:offsets[f+1]]``, CCW seen from its positive side.
        triangles: ``(#tri, 3) int64`` fan triangulation; ``triangle_face``
            ``(#tri,) int64`` the face of each.
        face_patch: ``(#F,) int64``; face_cells: ``(#F, 2) int64`` [positive, negative] side cell, -1 for none.
        patch_labels: ``(#P, 2) int64``.
        chains: list of ``int64`` point-id arrays; corners: ``int64`` point ids.
        shells: list of half-patch id arrays (2p / 2p+1 = positive / negative side of p).
        cells: list of dicts ``{"shells", "label"}``.
        cell_volume: ``(#C,) float64`` each cell's volume (regions: each
            region's; NaN for a cell a tet mesh's boundary leaves open);
            patch_area ``(#P,)``; chain_length ``(#chains,)``. Empty when
            the result carries no measures.
        names: ``{"functions": [...], "regions": {region: name}}``.
        embedding: what the exact check of the written doubles found and
            what its repairs changed (``{"before", "after", "snapped",
            "rotated", "nudged", ...}``; ``after`` counts ``coincident_points``,
            ``degenerate_triangles``, ``intersecting_pairs``), or None when
            not certified.
    """

    @classmethod
    def _from_core(cls, d: dict) -> "Network":
        """From the arrays that the compiled core returns (no JSON)."""
        net = cls.__new__(cls)
        net._data = None
        net.mode = d["mode"]
        net.functions = int(d.get("functions", 0) or 0)
        net.points = d["points"]
        net.offsets, net.indices = d["offsets"], d["indices"]
        net._triangulate()
        net.face_patch, net.face_cells, net.face_label = d["face_patch"], d["face_cells"], d["face_label"]
        net.patch_labels, net._patch_faces = d["patch_labels"], d["patch_faces"]
        net.chains, net.corners, net.shells, net.cells = d["chains"], d["corners"], d["shells"], d["cells"]
        net.chain_patches = d.get("chain_patches", [])
        net.seconds = dict(d["seconds"])
        net._counts = dict(d["counts"])
        net._counts["cells_method"] = d.get("cells_method")
        net._set_notes(d.get("names"), d.get("cell_volume"), d.get("patch_area"), d.get("chain_length"))
        net.embedding = json.loads(d["embedding"]) if d.get("embedding") else None
        return net

    def _set_notes(self, names, cell_volume, patch_area, chain_length):
        """Names and measures (missing or of the wrong length: none)."""
        names = names if isinstance(names, dict) else {}
        regions = names.get("regions") or {}
        self.names = {"functions": [str(f) for f in names.get("functions") or []],
                      "regions": {int(k): str(v) for k, v in dict(regions).items()}}

        def floats(xs, n):
            a = np.asarray([np.nan if x is None else x for x in xs] if isinstance(xs, list) else
                           (np.zeros(0) if xs is None else xs), dtype=np.float64).ravel()
            return a if len(a) == n else np.zeros(0)

        self.cell_volume = floats(cell_volume, len(self.cells))
        self.patch_area = floats(patch_area, len(self.patch_labels))
        self.chain_length = floats(chain_length, len(self.chains))

    @property
    def data(self) -> dict:
        """The network as the ``network.json`` contract (built on demand)."""
        if self._data is None:
            faces = [self.indices[a:b].tolist() for a, b in zip(self.offsets[:-1], self.offsets[1:])]
            self._data = {
                "mode": self.mode,
                "points": self.points.tolist(),
                "faces": faces,
                "face_label": self.face_label.tolist(),
                "face_patch": self.face_patch.tolist(),
                "face_cells": self.face_cells.tolist(),
                "patches": [{"label": l, "faces": int(n)} for l, n in zip(self.patch_labels.tolist(), self._patch_faces)],
                "chains": [c.tolist() for c in self.chains],
                "corners": self.corners.tolist(),
                "shells": [s.tolist() for s in self.shells],
                "cells": [{"shells": list(c["shells"]), "label": list(c["label"])} for c in self.cells],
                "counts": {k: v for k, v in self._counts.items() if k != "cells_method"},
                "seconds": self.seconds,
            }
            if self.names["functions"] or self.names["regions"]:
                self._data["names"] = {"functions": self.names["functions"],
                                       "regions": {str(k): v for k, v in self.names["regions"].items()}}
            if len(self.cell_volume) or len(self.patch_area) or len(self.chain_length):
                nulls = lambda a: [None if not np.isfinite(x) else float(x) for x in a]
                self._data["measures"] = {"cell_volume": nulls(self.cell_volume), "patch_area": nulls(self.patch_area),
                                          "chain_length": nulls(self.chain_length)}
        return self._data

    def _triangulate(self):
        # Built on first use (loading stays fast): see `triangles`.
        self._tri = None

    def _fan(self):
        # Fan triangulation (faces are convex): triangle (v0, vk, vk+1).
        if getattr(self, "_tri", None) is None:
            sizes = np.diff(self.offsets)
            ntri = sizes - 2
            face = np.repeat(np.arange(len(sizes), dtype=np.int64), ntri)
            k = np.arange(len(face)) - np.repeat(np.cumsum(ntri) - ntri, ntri)
            first = self.offsets[:-1][face]
            tri = np.stack([self.indices[first], self.indices[first + k + 1], self.indices[first + k + 2]], axis=1)
            self._tri = (tri, face)
        return self._tri

    @property
    def triangles(self) -> np.ndarray:
        """``(#tri, 3) int64``: the polygons' fan triangulation (computed on first use)."""
        return self._fan()[0]

    @property
    def triangle_face(self) -> np.ndarray:
        """``(#tri,) int64``: the polygon of each triangle."""
        return self._fan()[1]

    def __init__(self, data: dict):
        self._data = data
        self._counts = dict(data.get("counts", {}))
        self.mode = data.get("mode", "ia")
        self.functions = int(data.get("functions", 0) or 0)
        self.points = np.asarray(data.get("points", []), dtype=np.float64).reshape(-1, 3)
        faces = data.get("faces", [])
        sizes = np.fromiter((len(f) for f in faces), dtype=np.int64, count=len(faces))
        self.offsets = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
        self.indices = np.fromiter((i for f in faces for i in f), dtype=np.int64, count=int(self.offsets[-1]))
        if len(self.indices) and (self.indices.min() < 0 or self.indices.max() >= len(self.points)):
            raise InputError("network: a face refers to a point that does not exist")
        if np.any(sizes < 3):
            raise InputError(f"network: face {int(np.argmax(sizes < 3))} has fewer than 3 points")
        self._triangulate()
        self.face_label = np.asarray(data.get("face_label", np.full((len(faces), 2), -1)), dtype=np.int64).reshape(-1, 2)
        self.face_patch = np.asarray(data.get("face_patch", np.zeros(len(faces))), dtype=np.int64)
        self.face_cells = np.asarray(data.get("face_cells", np.full((len(faces), 2), -1)), dtype=np.int64).reshape(-1, 2)
        self.patch_labels = np.asarray([p.get("label", [-1, -1])[:2] + [-1] * (2 - len(p.get("label", [])[:2])) for p in data.get("patches", [])], dtype=np.int64).reshape(-1, 2)
        self._patch_faces = [p.get("faces", 0) for p in data.get("patches", [])]
        self.chain_patches = data.get("chain_patches", [])
        self.chains = [np.asarray(c, dtype=np.int64) for c in data.get("chains", [])]
        self.corners = np.asarray(data.get("corners", []), dtype=np.int64)
        self.shells = [np.asarray(s, dtype=np.int64) for s in data.get("shells", [])]
        self.cells = list(data.get("cells", []))
        self.seconds = dict(data.get("seconds", {}))
        m = data.get("measures") or {}
        self._set_notes(data.get("names"), m.get("cell_volume"), m.get("patch_area"), m.get("chain_length"))
        self.embedding = data.get("embedding", self._counts.get("embedding"))

    def __len__(self) -> int:
        return len(self.offsets) - 1

    def __repr__(self) -> str:
        s = self.summary()
        return "Network(" + ", ".join(f"{k}={s[k]}" for k in _COUNT_KEYS) + f", mode={self.mode!r})"

    def summary(self) -> dict:
        """Counts and timings, the same dict as the command line's ``--json``."""
        out = dict(self._counts)
        out.update({
            "vertices": len(self.points),
            "faces": len(self),
            "patches": len(self.patch_labels),
            "chains": len(self.chains),
            "corners": len(self.corners),
            "shells": len(self.shells),
            "cells": len(self.cells),
        })
        out["seconds"] = self.seconds
        return out

    # --- remeshing ----------------------------------------------------
    def remesh(self, length: float, iterations: int = 8) -> "Network":
        """A new network whose patches are remeshed to triangles of edge
        length about ``length`` (isotropic remeshing, as ``--remesh L`` and
        ``septa remesh OUT L``): the chains and corners are constraints
        shared by every patch around them, vertices stay on this network's
        patches (closest point on their triangles), and the result is
        certified by the exact check. The same patches, chains, corners,
        shells and cells (their labels, ``chain_patches``, names kept);
        ``patch_area`` and ``chain_length`` measured on the triangles,
        ``cell_volume`` moved by the change of each cell's polygons.
        ``remeshing`` holds the report (``before``/``after`` quality,
        ``hausdorff``, ``refused``: when the exact check still finds a
        violation, the polygons are kept as they are). ``embedding`` is the
        certificate of the new triangles."""
        def csr(lists):
            lists = [np.asarray(x, dtype=np.int64).ravel() for x in lists]
            offsets = np.zeros(len(lists) + 1, dtype=np.int64)
            offsets[1:] = np.cumsum([len(x) for x in lists]) if lists else []
            return offsets, (np.concatenate(lists) if lists else np.zeros(0, dtype=np.int64))

        i64 = lambda a, *shape: np.ascontiguousarray(np.asarray(a, dtype=np.int64).reshape(*shape))
        vol = self.cell_volume if len(self.cell_volume) == len(self.cells) else np.zeros(0)
        d = _septa.remesh(
            np.ascontiguousarray(self.points, dtype=np.float64).reshape(-1, 3), i64(self.offsets, -1),
            i64(self.indices, -1), i64(self.face_patch, -1), i64(self.face_cells, -1, 2), i64(self.face_label, -1, 2),
            len(self.patch_labels), len(self.cells), *csr(self.chains), i64(self.corners, -1),
            np.ascontiguousarray(vol, dtype=np.float64), float(length), int(iterations))
        net = Network.__new__(Network)
        net._data = None
        net.mode, net.functions = self.mode, self.functions
        net.points, net.offsets, net.indices = d["points"], d["offsets"], d["indices"]
        net._triangulate()
        net.face_patch, net.face_cells, net.face_label = d["face_patch"], d["face_cells"], d["face_label"]
        net.patch_labels = self.patch_labels.copy()
        net._patch_faces = np.bincount(net.face_patch, minlength=len(net.patch_labels)).tolist()
        net.chains, net.corners = list(d["chains"]), d["corners"]
        net.chain_patches = [np.asarray(c).copy() for c in self.chain_patches]
        net.shells = [np.asarray(s).copy() for s in self.shells]
        net.cells = [dict(c) for c in self.cells]
        net.seconds = dict(self.seconds)
        report = json.loads(d["report"])
        net.seconds["remesh"] = report.get("seconds", 0.0)
        net._counts = dict(self._counts)
        edges = np.sort(np.stack([net.triangles, np.roll(net.triangles, -1, axis=1)], axis=2).reshape(-1, 2), axis=1)
        new = {"vertices": len(net.points), "faces": len(net), "edges": len(np.unique(edges, axis=0))}
        net._counts.update({k: v for k, v in new.items() if k in net._counts})
        net._set_notes(self.names, d["cell_volume"] if len(d["cell_volume"]) else None, d["patch_area"],
                       d["chain_length"])
        net.names = {"functions": list(self.names["functions"]), "regions": dict(self.names["regions"])}
        net.embedding = json.loads(d["embedding"]) if d["embedding"] else self.embedding
        net.remeshing = report
        for attr in ("surfaces", "curves"):
            if hasattr(self, attr):
                setattr(net, attr, getattr(self, attr))
        return net

    # --- saving -------------------------------------------------------
    def save(self, path) -> Path:
        """Saves by extension with the command line's writers (one vocabulary:
        per polygon ``patch``, ``labels`` (2), ``cells`` (2); chains and
        corners as line and vertex cells): ``.npz`` (every array, numpy
        reads it), ``.ply`` (triangles with ``face``, ``patch``,
        ``labels_0/1``, ``cells_0/1``), ``.plain.ply`` (triangles only, for
        meshio), ``.obj``, ``.vtu``, ``.vtm`` (ParaView multiblock of
        patches, chains, corners, cells), ``.json`` (the ``network.json``
        document) and ``.msh`` (through meshio). Written to a temporary
        file, then renamed."""
        path = Path(path)
        name = path.name.lower()
        ext = ".plain.ply" if name.endswith(".plain.ply") else path.suffix.lower()
        # never replace a link, FIFO or device at `path` (septa.InputError
        # naming it, whatever the format); the temporary file is made new
        # (O_EXCL), never opened through a planted link
        _septa.check_output_file(str(path))
        if ext in _RUST_FORMATS:
            self._write_rust(path, _RUST_FORMATS[ext])
            return path
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
        os.close(fd)
        tmp = Path(tmp)
        try:
            if ext == ".json":
                tmp.write_text(json.dumps(self.data, separators=(",", ":")))
            elif ext == ".msh":
                meshio = _need("meshio", "meshio")
                mesh = self.to_meshio()
                # Gmsh numbers physical groups from 1 (tag 0 is "no group"):
                # patch p is physical surface p + 1, named as its OBJ group
                tags = (self.face_patch[self.triangle_face] + 1).astype(np.int32)
                mesh.cell_data = {"gmsh:physical": [tags], "gmsh:geometrical": [tags]}
                mesh.field_data = {name: np.array([p + 1, 2]) for p, name in enumerate(self.patch_names())}
                meshio.write(str(tmp), mesh, file_format="gmsh22", binary=True)
            else:
                raise InputError(f"save: unknown extension {ext!r} (use {' '.join(sorted(_RUST_FORMATS))} .json .msh)")
            _septa.check_output_file(str(path))
            os.replace(tmp, path)
        finally:
            if tmp.exists():
                tmp.unlink()
        return path

    def patch_names(self) -> list:
        """Per patch its name, as its OBJ group and Gmsh physical name:
        ``patch_<p>_<a>_<b>`` with the names of its labels (IA: ``patch_<p>_<f>``
        with its function's name; MI materials and regions by the scene's
        names, a label volume's by its ``--names`` table), or
        ``patch_<p>_labels_<a>_<b>`` when neither label has a name."""
        named = lambda x: self.names["regions"].get(int(x)) or (
            self.names["functions"][x] if self.mode == "mi" and 0 <= x < len(self.names["functions"]) else None)
        fname = lambda f: self.names["functions"][f] if 0 <= f < len(self.names["functions"]) else None
        real = lambda n, x: n is not None and n != str(x)
        out = []
        for p, (a, b) in enumerate(self.patch_labels.tolist()):
            if self.mode == "ia" and (b < 0 or a == b):
                n = fname(a)
                out.append(f"patch_{p}_{_name_token(n)}" if real(n, a) else f"patch_{p}_labels_{a}_{b}")
                continue
            na, nb = named(a), named(b)
            if real(na, a) or real(nb, b):
                out.append(f"patch_{p}_{_name_token(na if real(na, a) else str(a))}_{_name_token(nb if real(nb, b) else str(b))}")
            else:
                out.append(f"patch_{p}_labels_{a}_{b}")
        return out

    def _write_rust(self, path: Path, fmt: str) -> None:
        from . import _septa

        def csr(lists):
            lists = [np.asarray(x, dtype=np.int64).ravel() for x in lists]
            offsets = np.zeros(len(lists) + 1, dtype=np.int64)
            offsets[1:] = np.cumsum([len(x) for x in lists]) if lists else []
            return offsets, (np.concatenate(lists) if lists else np.zeros(0, dtype=np.int64))

        i64 = lambda a, *shape: np.ascontiguousarray(np.asarray(a, dtype=np.int64).reshape(*shape))
        labels = [list(c.get("label", [])) for c in self.cells]
        width = max((len(l) for l in labels), default=0)
        cell_labels = np.full((len(labels), width), -1, dtype=np.int64)
        for i, l in enumerate(labels):
            cell_labels[i, :len(l)] = [int(x) for x in l]
        meta = {"counts": {k: v for k, v in self._counts.items() if k != "cells_method"}, "seconds": self.seconds,
                "cells_method": self._counts.get("cells_method"),
                "names": {"functions": self.names["functions"],
                          "regions": {str(k): v for k, v in self.names["regions"].items()}}}
        f64 = lambda a: np.ascontiguousarray(a, dtype=np.float64) if len(a) else None
        _septa.write_result(
            str(path), fmt, self.mode if self.mode in ("ia", "mi", "regions") else "ia", self.functions,
            np.ascontiguousarray(self.points, dtype=np.float64).reshape(-1, 3), i64(self.offsets, -1), i64(self.indices, -1),
            i64(self.face_patch, -1), i64(self.face_label, -1, 2), i64(self.face_cells, -1, 2), i64(self.patch_labels, -1, 2),
            *csr(self.chains), *csr(self.chain_patches), i64(self.corners, -1), *csr(self.shells),
            *csr([c.get("shells", []) for c in self.cells]), cell_labels, json.dumps(meta, default=str),
            cell_volume=f64(self.cell_volume), patch_area=f64(self.patch_area), chain_length=f64(self.chain_length))

    # --- converters ---------------------------------------------------
    def _triangle_data(self) -> dict:
        t = self.triangle_face
        return {"patch": self.face_patch[t], "labels": self.face_label[t], "cells": self.face_cells[t], "face": t}

    def to_meshio(self):
        """A ``meshio.Mesh`` of the triangulated faces with cell data
        ``patch``, ``labels`` ``(#tri, 2)``, ``cells`` ``(#tri, 2)`` and
        ``face`` (the polygon of each triangle)."""
        meshio = _need("meshio", "meshio")
        data = self._triangle_data()
        return meshio.Mesh(self.points, [("triangle", self.triangles)], cell_data={k: [v] for k, v in data.items()})

    def to_trimesh(self):
        """A ``trimesh.Trimesh`` (not processed: vertices keep their ids) with
        ``face_attributes`` patch / labels / cells / face."""
        trimesh = _need("trimesh", "trimesh")
        return trimesh.Trimesh(vertices=self.points, faces=self.triangles, face_attributes=self._triangle_data(), process=False)

    def region(self, key, to: str | None = None, closed: bool = True, dtype=np.float64):
        """Region (label, arrangement cell) ``key``, an id or a scene's region
        name, as a closed, outward-oriented triangle surface holding only its
        own vertices: ``(vertices (n, 3), triangles (m, 3))``, or with
        ``to="trimesh"`` / ``to="pyvista"`` that mesh. A region reaching the
        domain's box has an open surface: refused unless ``closed=False``.
        ``dtype=np.float32``: the surface an STL file holds (vertices that
        round to one float32 point merged, degenerate triangles dropped)."""
        from ._solids import region_surface

        v, t = region_surface(self, key, closed, dtype)
        if to is None:
            return v, t
        if to == "trimesh":
            return _need("trimesh", "trimesh").Trimesh(vertices=v, faces=t, process=False)
        if to == "pyvista":
            pv = _need("pyvista", "pyvista")
            return pv.PolyData(v, faces=np.hstack([np.full((len(t), 1), 3), t]).ravel())
        raise InputError(f"region: to={to!r} (use None, 'trimesh' or 'pyvista')")

    def save_regions(self, folder, format: str = "stl") -> dict:
        """Writes every region with a closed surface (see :meth:`region`) to
        ``folder/NAME.<format>`` (``stl``, binary float32; ``obj``; ``ply``;
        through trimesh), NAME the scene's region name when it has one and
        is a plain file name, else ``region_<id>``. Regions reaching the
        domain's box are left out (logged). Returns ``{region id: path}``."""
        from ._solids import save_regions

        return save_regions(self, folder, format)

    def to_pyvista(self):
        """A ``pyvista.MultiBlock`` with the blocks and arrays of
        ``network.vtm`` (PolyData where the file has unstructured pieces):
        ``patches`` (the polygons with cell data ``patch``, ``labels`` (2),
        ``cells`` (2), ``area``), ``chains`` (a line per chain edge with
        ``chain``, ``patches`` (how many patches meet there, 0 if unknown),
        ``length`` when measured), ``corners`` (vertex cells with ``corner``)
        and ``cells`` (each polygon once per side, oriented out of that cell,
        with ``cell``, ``patch``, ``label`` (MI material, region, label; IA the
        sign vector as bits, function ``f`` positive in bit ``f < 31``) and
        ``volume`` when measured). ``mb["patches"]`` is the surface."""
        pv = _need("pyvista", "pyvista")
        sizes = np.diff(self.offsets)
        # the file's order: triangles, quads, then larger polygons by size
        # (stable: by face id within a size); `face` names each row's face
        size_class = _size_class(sizes)
        order = np.argsort(size_class, kind="stable")
        loops = np.split(self.indices, self.offsets[1:-1]) if len(order) else []
        polys = np.concatenate([np.concatenate([[len(loops[f])], loops[f]]) for f in order]) if len(order) else np.zeros(0, np.int64)
        patches = pv.PolyData(self.points, faces=polys)
        patches.cell_data["patch"] = self.face_patch[order]
        patches.cell_data["labels"] = self.face_label[order]
        patches.cell_data["cells"] = self.face_cells[order]
        patches.cell_data["area"] = self._face_area()[order]
        patches.cell_data["face"] = order
        mb = pv.MultiBlock()
        mb["patches"] = patches
        edges = [np.stack([c[:-1], c[1:]], axis=1) for c in self.chains if len(c) > 1]
        if edges:
            e = np.concatenate(edges)
            chains = pv.PolyData(self.points, lines=np.hstack([np.full((len(e), 1), 2), e]).ravel())
            edges_per = [max(len(c) - 1, 0) for c in self.chains]
            chain = np.repeat(np.arange(len(self.chains)), edges_per)
            chains.cell_data["chain"] = chain
            around = [len(self.chain_patches[c]) if c < len(self.chain_patches) else 0 for c in range(len(self.chains))]
            chains.cell_data["patches"] = np.asarray(around, dtype=np.int32)[chain]
            if len(self.chain_length):
                chains.cell_data["length"] = self.chain_length[chain]
            mb["chains"] = chains
        if len(self.corners):
            corners = pv.PolyData(self.points, verts=np.stack([np.ones_like(self.corners), self.corners], axis=1).ravel())
            corners.cell_data["corner"] = np.arange(len(self.corners))
            mb["corners"] = corners
        side = []  # (cell, face, reversed): reversed for the positive side, so it faces out of the cell
        for k, rev in ((0, True), (1, False)):
            f = np.flatnonzero(self.face_cells[:, k] >= 0)
            side.append((self.face_cells[f, k], f, np.full(len(f), rev)))
        cell = np.concatenate([s[0] for s in side])
        face = np.concatenate([s[1] for s in side])
        rev = np.concatenate([s[2] for s in side])
        if len(face):
            # the file's order: (size class, cell, face, reversed)
            order = np.lexsort((rev, face, cell, size_class[face]))
            cell, face, rev = cell[order], face[order], rev[order]
            flat = np.concatenate([np.concatenate([[len(loops[f])], loops[f][::-1] if r else loops[f]]) for f, r in zip(face, rev)])
            cells = pv.PolyData(self.points, faces=flat)
            cells.cell_data["cell"] = cell
            cells.cell_data["patch"] = self.face_patch[face]
            cells.cell_data["label"] = self._cell_label_numbers()[cell]
            cells.cell_data["face"] = face
            if len(self.cell_volume):
                cells.cell_data["volume"] = self.cell_volume[cell]
            mb["cells"] = cells
        return mb

    def _face_area(self) -> np.ndarray:
        """Each polygon's area, summed over its fan as the writers do."""
        tri, face = self._fan()
        p = self.points
        c = np.cross(p[tri[:, 1]] - p[tri[:, 0]], p[tri[:, 2]] - p[tri[:, 0]])
        n = np.zeros((len(self), 3))
        np.add.at(n, face, c)
        return np.linalg.norm(n, axis=1) / 2.0

    def _cell_label_numbers(self) -> np.ndarray:
        """One number per cell, as the ``label`` of ``network.vtm``'s cells."""
        out = np.full(len(self.cells), -1, dtype=np.int32)
        for c, cell in enumerate(self.cells):
            lab = list(cell.get("label", []))
            if self.mode == "ia":
                out[c] = sum(int(bool(b)) << f for f, b in enumerate(lab[:31]))
            elif lab:
                out[c] = int(lab[0])
        return out

    def _repr_html_(self) -> str:
        """The viewer inline in a notebook: one self-contained iframe (the
        bundled viewer and the result; nothing loaded from the network)."""
        from .viewer import inline_html

        return inline_html(self)


def _name_token(s: str) -> str:
    """A name as an OBJ group or Gmsh physical name (io/names.rs
    ``name_token``): letters, digits, ``_ - .`` kept, anything else ``_``."""
    return "".join(c if c.isalnum() or c in "_-." else "_" for c in str(s))


def _size_class(sizes: np.ndarray) -> np.ndarray:
    """The VTK writers' order of polygons by size (io/result_vtk.rs):
    triangles (VTK_TRIANGLE), quads (VTK_QUAD), then each larger size
    (VTK_POLYGON), so that meshio reads one block per size."""
    sizes = np.asarray(sizes, dtype=np.int64)
    return np.where(sizes == 3, 0, np.where(sizes == 4, 1, sizes))


_RUST_FORMATS = {".npz": "npz", ".ply": "ply", ".plain.ply": "plain.ply", ".obj": "obj", ".vtu": "vtu", ".vtm": "vtm"}


def _from_npz(p: Path) -> Network:
    """A :class:`Network` from ``network.npz`` (numpy's ``.npy`` reader on
    each member, inflated no further than its header declares; every array
    checked, ``_load_check.py``)."""
    from . import _load_check

    a, meta = _load_check.check_npz(_load_check.read_npz(p), p)
    split = lambda name: np.split(a[f"{name}_indices"], a[f"{name}_offsets"][1:-1]) if len(a[f"{name}_offsets"]) > 1 else []
    offsets, indices = a["offsets"], a["indices"]
    mode = meta.get("mode", "ia")
    cell_shells = split("cell_shell")
    cells = [{"shells": s.tolist(), "label": [bool(x) for x in l] if mode == "ia" else l.tolist()}
             for s, l in zip(cell_shells, a["cell_labels"])]
    d = {"mode": mode, "points": a["points"], "offsets": offsets, "indices": indices, "face_patch": a["patch"],
         "face_cells": a["cells"], "face_label": a["labels"], "patch_labels": a["patch_labels"],
         "patch_faces": np.bincount(a["patch"], minlength=len(a["patch_labels"])), "chains": split("chain"),
         "chain_patches": split("chain_patch"), "corners": a["corners"], "shells": split("shell"), "cells": cells,
         "functions": meta.get("functions", 0), "counts": meta.get("counts", {}), "seconds": meta.get("seconds", {}), "cells_method": meta.get("cells_method"),
         "names": meta.get("names"), "cell_volume": a.get("cell_volume"), "patch_area": a.get("patch_area"),
         "chain_length": a.get("chain_length")}
    net = Network._from_core(d)
    if mode == "regions":
        net.surfaces, net.curves = meta["counts"].get("surfaces", []), meta["counts"].get("curves", [])
    return net


def load(path) -> Network:
    """Loads a job output: a folder (its ``network.npz`` when there is one,
    else ``network.json``), or a ``.npz`` / ``.json`` file.

    >>> import septa, pathlib
    >>> net = septa.load(pathlib.Path(septa.__file__).parents[2] / "tests/fixtures/two-planes")  # doctest: +SKIP
    """
    p = Path(path)
    if p.is_dir():
        # A folder written by septa holds manifest.json once complete (io/outdir.rs).
        if (p / ".septa.lock").exists() and not (p / "manifest.json").exists():
            raise InputError(f"{p}: incomplete result: a run was interrupted or is still writing (no manifest.json)")
        p = p / "network.npz" if (p / "network.npz").exists() else p / "network.json"
    from . import _load_check

    if p.suffix.lower() == ".npz":
        net = _from_npz(p)
        net.source = p
        return net
    data = _load_check.read_json(p)
    net = Network(data)
    net.source = p
    return net
