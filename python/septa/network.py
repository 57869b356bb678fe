"""Surface network results: arrays, summary, saving and converters.

A :class:`Network` holds one job's output (the ``network.json`` contract
written by every job): points, polygon faces as CSR, a triangulated view,
patches with their label pairs, chains, corners, shells and cells.
"""
from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

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
    """

    @classmethod
    def _from_core(cls, d: dict) -> "Network":
        """From the arrays that the compiled core returns (no JSON)."""
        net = cls.__new__(cls)
        net._data = None
        net.mode = d["mode"]
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
        return net

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
        return self._data

    def _triangulate(self):
        # Fan triangulation (faces are convex): triangle (v0, vk, vk+1).
        sizes = np.diff(self.offsets)
        ntri = sizes - 2
        self.triangle_face = np.repeat(np.arange(len(sizes), dtype=np.int64), ntri)
        k = np.arange(len(self.triangle_face)) - np.repeat(np.cumsum(ntri) - ntri, ntri)
        first = self.offsets[:-1][self.triangle_face]
        self.triangles = np.stack([self.indices[first], self.indices[first + k + 1], self.indices[first + k + 2]], axis=1)

    def __init__(self, data: dict):
        self._data = data
        self._counts = dict(data.get("counts", {}))
        self.mode = data.get("mode", "ia")
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

    # --- saving -------------------------------------------------------
    def save(self, path) -> Path:
        """Saves by extension: .json (network contract), .ply (binary, per-face
        patch), .obj (a group per patch, chains as polylines), .vtu / .msh
        (through meshio). Written to a temporary file, then renamed."""
        path = Path(path)
        ext = path.suffix.lower()
        tmp = path.with_name(path.name + ".tmp")
        try:
            if ext == ".json":
                tmp.write_text(json.dumps(self.data, separators=(",", ":")))
            elif ext == ".ply":
                tmp.write_bytes(self._ply_bytes())
            elif ext == ".obj":
                tmp.write_text(self._obj_text())
            elif ext in (".vtu", ".msh"):
                meshio = _need("meshio", "meshio")
                fmt = "vtu" if ext == ".vtu" else "gmsh22"
                mesh = self.to_meshio()
                if ext == ".msh":
                    tags = self.face_patch[self.triangle_face].astype(np.int32)
                    mesh.cell_data = {"gmsh:physical": [tags], "gmsh:geometrical": [tags]}
                meshio.write(str(tmp), mesh, file_format=fmt, **({"binary": True} if ext == ".msh" else {}))
            else:
                raise InputError(f"save: unknown extension {ext!r} (use .json .ply .obj .vtu .msh)")
            os.replace(tmp, path)
        finally:
            if tmp.exists():
                tmp.unlink()
        return path

    def _ply_bytes(self) -> bytes:
        # The CLI's network.ply layout: polygons as triangle fans, each with
        # its polygon id, patch and label pair (mesh tools read only face
        # lists of one length with extra properties).
        t = self.triangle_face
        header = (
            "ply\nformat binary_little_endian 1.0\ncomment septa surface network, polygons as triangle fans\n"
            f"element vertex {len(self.points)}\nproperty double x\nproperty double y\nproperty double z\n"
            f"element face {len(t)}\nproperty list uchar int vertex_indices\nproperty int face\nproperty int patch\n"
            "property int label0\nproperty int label1\nend_header\n"
        ).encode()
        rec = np.dtype([("n", "u1"), ("v", "<i4", (3,)), ("face", "<i4"), ("patch", "<i4"), ("l0", "<i4"), ("l1", "<i4")])
        rows = np.empty(len(t), dtype=rec)
        rows["n"] = 3
        rows["v"] = self.triangles
        rows["face"] = t
        rows["patch"] = self.face_patch[t]
        rows["l0"] = self.face_label[t, 0]
        rows["l1"] = self.face_label[t, 1]
        return header + self.points.astype("<f8").tobytes() + rows.tobytes()

    def _obj_text(self) -> str:
        lines = [f"# septa network: {json.dumps({k: v for k, v in self.summary().items() if k != 'seconds'})}"]
        lines += [f"v {x!r} {y!r} {z!r}" for x, y, z in self.points.tolist()]
        for p in range(len(self.patch_labels)):
            lines.append(f"g patch_{p}_label_{self.patch_labels[p, 0]}_{self.patch_labels[p, 1]}")
            for f in np.flatnonzero(self.face_patch == p):
                lines.append("f " + " ".join(str(i + 1) for i in self.indices[self.offsets[f]:self.offsets[f + 1]]))
        for c, chain in enumerate(self.chains):
            lines.append(f"g chain_{c}")
            lines.append("l " + " ".join(str(i + 1) for i in chain))
        return "\n".join(lines) + "\n"

    # --- converters ---------------------------------------------------
    def _triangle_data(self) -> dict:
        pf = self.face_patch[self.triangle_face]
        lab = self.patch_labels[pf] if len(self.patch_labels) else np.full((len(pf), 2), -1)
        return {"patch": pf, "label_a": lab[:, 0], "label_b": lab[:, 1], "face": self.triangle_face}

    def to_meshio(self):
        """A ``meshio.Mesh`` of the triangulated faces with cell data
        ``patch``, ``label_a``, ``label_b``, ``face``."""
        meshio = _need("meshio", "meshio")
        data = self._triangle_data()
        return meshio.Mesh(self.points, [("triangle", self.triangles)], cell_data={k: [v] for k, v in data.items()})

    def to_trimesh(self):
        """A ``trimesh.Trimesh`` (not processed: vertices keep their ids) with
        ``face_attributes`` patch / label_a / label_b / face."""
        trimesh = _need("trimesh", "trimesh")
        return trimesh.Trimesh(vertices=self.points, faces=self.triangles, face_attributes=self._triangle_data(), process=False)

    def to_pyvista(self):
        """A ``pyvista.PolyData`` of the polygons with cell data ``patch``."""
        pv = _need("pyvista", "pyvista")
        sizes = np.diff(self.offsets)
        flat = np.insert(self.indices, self.offsets[:-1], sizes)
        mesh = pv.PolyData(self.points, faces=flat)
        mesh.cell_data["patch"] = self.face_patch
        return mesh


def load(path) -> Network:
    """Loads a job output: a folder holding ``network.json`` or the file itself.

    >>> import septa, pathlib
    >>> net = septa.load(pathlib.Path(septa.__file__).parents[2] / "tests/fixtures/two-planes")  # doctest: +SKIP
    """
    p = Path(path)
    if p.is_dir():
        # A folder written by septa holds manifest.json once complete (io/outdir.rs).
        if (p / ".septa.lock").exists() and not (p / "manifest.json").exists():
            raise InputError(f"{p}: incomplete result: a run was interrupted or is still writing (no manifest.json)")
        p = p / "network.json"
    try:
        text = p.read_bytes().decode("utf-8")
    except OSError as e:
        raise InputError(f"{p}: cannot read ({e.strerror})") from e
    except UnicodeDecodeError as e:
        raise InputError(f"{p}: not a septa network (not UTF-8 text at byte {e.start})") from e
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise InputError(f"{p}:{e.lineno}: invalid JSON: {e.msg}") from e
    if not isinstance(data, dict) or "points" not in data or "faces" not in data:
        raise InputError(f"{p}: not a septa network (needs \"points\" and \"faces\")")
    net = Network(data)
    net.source = p
    return net
