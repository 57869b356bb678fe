"""One region (or label, or arrangement cell) of a result as a closed,
outward-oriented triangle surface holding only its own vertices: the input
of STL files, volume meshers and trimesh's solid operations.

A polygon is counter-clockwise seen from its positive side (``face_cells[f, 0]``),
so it faces out of the cell on its negative side as it is and out of the cell
on its positive side reversed (the same rule as the ``cells`` block of
``network.vtm``). The triangles are the network's fan triangulation, the one
every writer uses and the certified embedding checks.
"""
from __future__ import annotations

import logging
import os
import re
import tempfile
from pathlib import Path

import numpy as np

from ._septa import InputError

log = logging.getLogger("septa")


def region_index(net, key) -> int:
    """The cell of ``key``: a region's name, or an id (for region and label
    results the region or label id, whose cell is its place among the
    ascending regions; for ``ia``/``mi`` the cell's index)."""
    ids = _region_ids(net)
    if isinstance(key, str):
        named = [i for i, n in net.names["regions"].items() if n == key]
        if not named:
            known = ", ".join(sorted(set(net.names["regions"].values()))) or "none"
            raise InputError(f"region {key!r}: no region of that name (names: {known})")
        key = named[0]
        if key not in ids:
            raise InputError(f"region {named[0]} ({net.names['regions'][key]!r}): not in this result")
    try:
        rid = int(key)
    except (TypeError, ValueError):
        raise InputError(f"region {key!r}: give a region id (int) or name (str)") from None
    if rid not in ids:
        what = "region" if net.mode == "regions" else "region (arrangement or material cell)"
        shown = ", ".join(map(str, ids[:20])) + (", ..." if len(ids) > 20 else "")
        raise InputError(f"region {rid}: no such {what} (the result has {len(ids)}: {shown})")
    return ids.index(rid)


def _region_ids(net) -> list:
    """Per cell its id: the region (label) of a region result, else its index."""
    if net.mode == "regions":
        return [int(c.get("label", [i])[0]) for i, c in enumerate(net.cells)]
    return list(range(len(net.cells)))


def region_surface(net, key, closed: bool = True, dtype=np.float64):
    """``(vertices (n, 3), triangles (m, 3) int64)`` of region ``key`` (id
    or name), outward-oriented. With ``closed`` (the default) a region whose
    surface is not closed (it reaches the domain's box, where the network has
    no polygons) is refused with the number of open edges.

    ``dtype=np.float32`` gives the surface a float32 file (STL) holds: the
    certified embedding keeps every vertex apart in doubles, moving
    coincident ones apart by a few ulps (``embedding`` ``nudged``), and such
    vertices round to one float32 point. They are merged (equal float32
    values, no tolerance) and the triangles that become degenerate dropped,
    as a reader merging an STL's corners would; closedness is checked after."""
    cell = region_index(net, key)
    tri, face = net.triangles, net.triangle_face
    fc = net.face_cells[face]
    # a polygon with the region on both sides is inside it: not boundary
    pos = (fc[:, 0] == cell) & (fc[:, 1] != cell)
    neg = (fc[:, 1] == cell) & (fc[:, 0] != cell)
    t = np.concatenate([tri[pos][:, ::-1], tri[neg]])
    used, inverse = np.unique(t.ravel(), return_inverse=True)
    t = inverse.reshape(-1, 3).astype(np.int64)
    v = net.points[used]
    if np.dtype(dtype) == np.float32:
        v, t = _float32_merged(v, t)
    elif np.dtype(dtype) != np.float64:
        raise InputError(f"region: dtype {np.dtype(dtype)} (use float64 or float32)")
    if closed:
        open_edges = _open_edges(t)
        if open_edges:
            raise InputError(
                f"region {key!r}: its surface is open ({open_edges} edges without their opposite twin); "
                "a region reaching the domain's box is closed only by the box's faces, which the network does "
                "not hold (region(..., closed=False) returns the open surface)")
        # A closed surface bounds the region, or, for the region holding the
        # whole box boundary (the outside of a part that touches no box
        # face), the other regions: its outward side is then their inside
        # and it encloses minus their volume, never a value near 0.
        p = v.astype(np.float64)
        signed = np.einsum("ij,ij->i", p[t[:, 0]], np.cross(p[t[:, 1]], p[t[:, 2]])).sum() / 6.0
        if not signed > 0:
            raise InputError(
                f"region {key!r}: it reaches the domain's box (its closed surface encloses {signed:.6g}: the other "
                "regions, not itself); only regions inside the box are solids (closed=False returns the surface)")
    return v, t


def _float32_merged(v: np.ndarray, t: np.ndarray):
    """Vertices rounded to float32, equal ones merged, degenerate triangles
    and pairs of opposite coincident triangles (a fin of no volume) dropped."""
    v32 = v.astype(np.float32)
    u, first, inv = np.unique(v32, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first)  # keep the double surface's vertex order
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    t = rank[inv.reshape(-1)][t]
    t = t[(t[:, 0] != t[:, 1]) & (t[:, 1] != t[:, 2]) & (t[:, 0] != t[:, 2])]
    key = np.sort(t, axis=1)
    if len(key):
        _, idx, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
        t = t[counts[idx.reshape(-1)] == 1]
    used, inv2 = np.unique(t.ravel(), return_inverse=True)
    return u[order][used], inv2.reshape(-1, 3).astype(np.int64)


def _open_edges(t: np.ndarray) -> int:
    """Directed edges whose reverse is not used as often (0 for a closed,
    consistently oriented surface)."""
    if not len(t):
        return 0
    a = t.ravel()
    b = t[:, [1, 2, 0]].ravel()
    n = int(t.max()) + 1
    fwd = np.sort(a * n + b)
    rev = np.sort(b * n + a)
    if len(fwd) == len(rev) and np.array_equal(fwd, rev):
        return 0
    f_keys, f_counts = np.unique(fwd, return_counts=True)
    r_keys, r_counts = np.unique(rev, return_counts=True)
    common, fi, ri = np.intersect1d(f_keys, r_keys, return_indices=True)
    matched = np.minimum(f_counts[fi], r_counts[ri]).sum()
    return int(len(fwd) - matched)


def _file_names(net) -> list:
    """One file stem per cell, as the command line's ``--format stl``
    (io/solids_out.rs): for a region result the region's name if it is a
    plain, unique file name, else ``region_<id>``; for ``ia``/``mi`` ``cell_<c>``."""
    names = net.names["regions"]
    taken = list(names.values())
    out = []
    for c, rid in enumerate(_region_ids(net)):
        if net.mode != "regions":
            out.append(f"cell_{c}")
            continue
        n = names.get(rid)
        plain = n and taken.count(n) == 1 and re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9_.-]{0,99}", n)
        out.append(n if plain else f"region_{rid}")
    return out


def save_regions(net, folder, fmt: str = "stl") -> dict:
    """See :meth:`septa.Network.save_regions`."""
    from . import _septa
    from .network import _need

    fmt = fmt.lower().lstrip(".")
    if fmt not in ("stl", "obj", "ply"):
        raise InputError(f"save_regions: format {fmt!r} (use stl, obj or ply)")
    trimesh = _need("trimesh", "trimesh")
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    written = {}
    for rid, stem in zip(_region_ids(net), _file_names(net)):
        try:
            v, t = region_surface(net, rid, dtype=np.float32 if fmt == "stl" else np.float64)
        except InputError as e:
            log.info("save_regions: %s: not written (%s)", stem, e)
            continue
        path = folder / f"{stem}.{fmt}"
        _septa.check_output_file(str(path))
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=folder)
        os.close(fd)
        try:
            trimesh.Trimesh(vertices=v, faces=t, process=False).export(tmp, file_type=fmt)
            os.replace(tmp, path)
        finally:
            if os.path.exists(tmp):
                os.unlink(tmp)
        written[rid] = path
    return written
