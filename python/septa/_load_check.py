"""Validation of a result read back by :func:`septa.load`.

A result folder may be corrupted, truncated or written by someone else:
every array is checked for its shape, dtype and range before a
:class:`~septa.Network` is built from it, and any problem is an
:class:`septa.InputError` naming the file and the array (before: bare
``JSONDecodeError``, ``KeyError`` or ``RecursionError``; 2-column points,
1-column labels and float face indices were accepted, float indices
truncated; a shell offset of 1e12 was taken as is).

Files are read through the library's input layer (``_septa.read_input``:
regular files only, a size cap) and ``.npz`` members are inflated no
further than their ``.npy`` headers declare.
"""
from __future__ import annotations

import json
import zipfile

import numpy as np

from . import _septa
from ._septa import InputError


class _Bad(Exception):
    """An array that fails a check: (array name, what is wrong)."""


def _fail(name: str, what: str):
    raise _Bad(name, what)


def _ints(name: str, a, shape_tail=None, lo=None, hi=None, ndim=None) -> np.ndarray:
    """``a`` as int64: integers only (no float, no bool), the given trailing
    shape / number of axes, every value in ``[lo, hi)``."""
    arr = np.asarray(a)
    if arr.size == 0 and arr.dtype.kind == "f":
        arr = arr.astype(np.int64)  # an empty JSON list reads as float
    if arr.dtype.kind not in "iu":
        _fail(name, f"expected integers, got {arr.dtype}" + (" (a fractional index?)" if arr.dtype.kind == "f" else ""))
    if arr.dtype.kind == "u" and arr.size and arr.max() >= 2**63:
        _fail(name, "values beyond the int64 range")
    arr = arr.astype(np.int64, copy=False)
    if ndim is not None and arr.ndim != ndim:
        _fail(name, f"expected {ndim} axes, got shape {arr.shape}")
    if shape_tail is not None and (arr.ndim != 1 + len(shape_tail) or tuple(arr.shape[1:]) != tuple(shape_tail)):
        _fail(name, f"expected shape (N, {', '.join(map(str, shape_tail))}), got {arr.shape}")
    if arr.size:
        if lo is not None and arr.min() < lo:
            _fail(name, f"value {int(arr.min())} is below {lo}")
        if hi is not None and arr.max() >= hi:
            _fail(name, f"value {int(arr.max())} is not below {hi}")
    return arr


def _points(name: str, a) -> np.ndarray:
    arr = np.asarray(a)
    if arr.size == 0:
        return np.zeros((0, 3))
    if arr.dtype.kind not in "fiu":
        _fail(name, f"expected numbers, got {arr.dtype}")
    if arr.ndim != 2 or arr.shape[1] != 3:
        _fail(name, f"expected shape (N, 3), got {arr.shape}")
    arr = arr.astype(np.float64, copy=False)
    if not np.isfinite(arr).all():
        _fail(name, f"point {int(np.argwhere(~np.isfinite(arr))[0][0])} is not finite")
    return arr


def _csr(name: str, offsets, indices, lo=None, hi=None, min_size=0, names=None):
    """A CSR pair: offsets start at 0, never decrease, end at len(indices)."""
    no, ni = names or (f"{name}_offsets", f"{name}_indices")
    o = _ints(no, offsets, ndim=1)
    i = _ints(ni, indices, ndim=1, lo=lo, hi=hi)
    if len(o) == 0 or o[0] != 0 or o[-1] != len(i) or np.any(np.diff(o) < min_size):
        _fail(no, f"does not describe lists of {len(i)} entries" + (f" of {min_size} or more each" if min_size else ""))
    return o, i


def _json_list(name: str, v, item=None) -> list:
    if not isinstance(v, list):
        _fail(name, f"expected a list, got {type(v).__name__}")
    if item is not None:
        for k, x in enumerate(v):
            if not isinstance(x, item):
                _fail(name, f"entry {k} is {type(x).__name__}, not {item.__name__}")
    return v


def _int_lists(name: str, v, lo=None, hi=None, min_size=0) -> list:
    out = []
    for k, x in enumerate(_json_list(name, v)):
        if not isinstance(x, list) or any(isinstance(y, bool) or not isinstance(y, int) for y in x):
            _fail(name, f"entry {k} is not a list of whole numbers: {str(x)[:60]}")
        if len(x) < min_size:
            _fail(name, f"entry {k} has {len(x)} entries, at least {min_size} are needed")
        arr = np.asarray(x, dtype=np.int64)
        if arr.size and ((lo is not None and arr.min() < lo) or (hi is not None and arr.max() >= hi)):
            _fail(name, f"entry {k} has a value outside {lo}..{hi}: {str(x)[:60]}")
        out.append(arr)
    return out


def check_json(data, path) -> dict:
    """Checks a ``network.json`` document; returns it. Raises InputError."""
    try:
        if not isinstance(data, dict) or "points" not in data or "faces" not in data:
            raise InputError(f'{path}: not a septa network (needs "points" and "faces")')
        n = len(_points("points", data["points"]))
        faces = _int_lists("faces", data["faces"], lo=0, hi=n, min_size=3)
        nf = len(faces)
        patches = _json_list("patches", data.get("patches", []), dict)
        npatch = len(patches)
        for k, p in enumerate(patches):
            lab = p.get("label", [])
            if not isinstance(lab, list) or any(isinstance(x, bool) or not isinstance(x, int) for x in lab):
                _fail("patches", f"entry {k}: label is not a list of whole numbers")
            if isinstance(p.get("faces", 0), bool) or not isinstance(p.get("faces", 0), int):
                _fail("patches", f"entry {k}: faces is not a whole number")
        shells = _int_lists("shells", data.get("shells", []), lo=0, hi=2 * max(npatch, 1))
        cells = _json_list("cells", data.get("cells", []), dict)
        for k, c in enumerate(cells):
            _int_lists("cells", [c.get("shells", [])], lo=0, hi=len(shells))
            if not isinstance(c.get("label", []), list):
                _fail("cells", f"entry {k}: label is not a list")
        for key, width in (("face_label", 2), ("face_cells", 2)):
            if key in data:
                raw = np.asarray(data[key])
                a = _ints(key, raw if raw.size else np.zeros((0, width), np.int64), shape_tail=(width,))
                if len(a) != nf:
                    _fail(key, f"{len(a)} rows for {nf} faces")
                if key == "face_cells" and a.size and (a.min() < -1 or a.max() >= max(len(cells), 1)):
                    _fail(key, f"a cell id outside -1..{len(cells)}")
        if "face_patch" in data:
            fp = _ints("face_patch", data["face_patch"], ndim=1, lo=0, hi=max(npatch, 1) if npatch else None)
            if len(fp) != nf:
                _fail("face_patch", f"{len(fp)} entries for {nf} faces")
        _int_lists("chains", data.get("chains", []), lo=0, hi=n)
        _ints("corners", data.get("corners", []), ndim=1, lo=0, hi=n)
        for key in ("counts", "seconds"):
            if not isinstance(data.get(key, {}), dict):
                _fail(key, "expected an object")
    except _Bad as e:
        raise InputError(f"{path}: array '{e.args[0]}': {e.args[1]}") from None
    except (ValueError, TypeError, AttributeError, KeyError, IndexError) as e:
        raise InputError(f"{path}: not a septa network ({type(e).__name__}: {e})") from None
    return data


def read_json(path) -> dict:
    """A ``network.json`` read through the input layer, parsed and checked."""
    raw = _septa.read_input(str(path))
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise InputError(f"{path}: not a septa network (not UTF-8 text at byte {e.start})") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise InputError(f"{path}:{e.lineno}: invalid JSON: {e.msg}") from None
    except RecursionError:
        raise InputError(f"{path}: invalid JSON: nested too deeply") from None
    return check_json(data, path)


def read_npz(path) -> dict:
    """Every array of ``network.npz``: each member inflated no further than
    its ``.npy`` header declares (and never beyond the input limit), no
    object arrays. Raises InputError naming the file and the array."""
    limit = _septa.check_input_file(str(path))
    out = {}
    fmt = np.lib.format
    try:
        with zipfile.ZipFile(path) as z:
            for info in z.infolist():
                name = info.filename[:-4] if info.filename.endswith(".npy") else info.filename
                with z.open(info) as fh:
                    try:
                        major, _ = fmt.read_magic(fh)
                        read = fmt.read_array_header_1_0 if major == 1 else fmt.read_array_header_2_0
                        shape, _, dtype = read(fh)
                    except ValueError as e:
                        raise InputError(f"{path}: array '{name}': not a readable .npy ({e})") from None
                    if dtype.hasobject:
                        raise InputError(f"{path}: array '{name}': object arrays are not read")
                    size = int(np.prod(shape, dtype=object)) * dtype.itemsize
                    if size > limit:
                        raise InputError(f"{path}: array '{name}': shape {shape} declares {size} bytes, "
                                         f"more than the input limit of {limit}")
                with z.open(info) as fh:
                    try:
                        out[name] = fmt.read_array(fh, allow_pickle=False)
                    except ValueError as e:
                        raise InputError(f"{path}: array '{name}': {e}") from None
    except (zipfile.BadZipFile, OSError, EOFError) as e:
        raise InputError(f"{path}: not a readable .npz ({e})") from None
    return out


def check_npz(a: dict, path) -> tuple:
    """Checks the arrays of ``network.npz``; returns (arrays, meta)."""
    need = ("meta", "points", "offsets", "indices", "patch", "labels", "cells")
    missing = [k for k in need if k not in a]
    if missing:
        raise InputError(f"{path}: not a septa result (no {', '.join(missing)})")
    try:
        try:
            meta = json.loads(str(a["meta"]))
        except (json.JSONDecodeError, RecursionError) as e:
            _fail("meta", f"not a JSON document ({e})")
        if not isinstance(meta, dict):
            _fail("meta", "not a JSON object")
        for key in ("counts", "seconds"):
            if not isinstance(meta.get(key, {}), dict):
                _fail("meta", f"{key} is not an object")
        pts = _points("points", a["points"])
        offsets, indices = _csr("faces", a["offsets"], a["indices"], lo=0, hi=len(pts), min_size=3,
                                names=("offsets", "indices"))
        nf = len(offsets) - 1
        plab = _ints("patch_labels", a.get("patch_labels", np.zeros((0, 2), np.int64)), shape_tail=(2,))
        npatch = len(plab)
        patch = _ints("patch", a["patch"], ndim=1, lo=0, hi=npatch if npatch else None)
        labels = _ints("labels", a["labels"], shape_tail=(2,))
        cell_labels = _ints("cell_labels", a.get("cell_labels", np.zeros((0, 0), np.int64)), ndim=2)
        ncells = len(cell_labels)
        cells = _ints("cells", a["cells"], shape_tail=(2,), lo=-1, hi=max(ncells, 1))
        for name, arr in (("patch", patch), ("labels", labels), ("cells", cells)):
            if len(arr) != nf:
                _fail(name, f"{len(arr)} rows for {nf} faces")
        checked = dict(a)
        for name, lo, hi in (("chain", 0, len(pts)), ("chain_patch", 0, npatch), ("shell", 0, 2 * npatch)):
            o, i = (a.get(f"{name}_offsets", np.zeros(1, np.int64)), a.get(f"{name}_indices", np.zeros(0, np.int64)))
            checked[f"{name}_offsets"], checked[f"{name}_indices"] = _csr(name, o, i, lo=lo, hi=hi)
        nshells = len(checked["shell_offsets"]) - 1
        o, i = a.get("cell_shell_offsets", np.zeros(1, np.int64)), a.get("cell_shell_indices", np.zeros(0, np.int64))
        checked["cell_shell_offsets"], checked["cell_shell_indices"] = _csr("cell_shell", o, i, lo=0, hi=nshells)
        if len(checked["cell_shell_offsets"]) - 1 != ncells:
            _fail("cell_shell_offsets", f"{len(checked['cell_shell_offsets']) - 1} cells, cell_labels has {ncells}")
        checked["corners"] = _ints("corners", a.get("corners", np.zeros(0, np.int64)), ndim=1, lo=0, hi=len(pts))
        checked.update(points=pts, offsets=offsets, indices=indices, patch=patch, labels=labels, cells=cells,
                       patch_labels=plab, cell_labels=cell_labels)
    except _Bad as e:
        raise InputError(f"{path}: array '{e.args[0]}': {e.args[1]}") from None
    except (ValueError, TypeError, AttributeError, KeyError, IndexError) as e:
        raise InputError(f"{path}: not a septa result ({type(e).__name__}: {e})") from None
    return checked, meta
