"""The jobs, with the command line's names. Inputs are coerced once to
contiguous float64 / int64 arrays and validated in Rust (without the GIL);
errors are :class:`septa.InputError` (a ``ValueError``) naming what and where.

``arrangement`` and ``material_interface`` run the exact core in Rust with
the GIL released; so do ``region_surfaces`` (Bloomenthal's non-manifold
shapes on the exact network) and ``cut_mesh`` (TopoCut planar cut-cells).
"""
from __future__ import annotations

import json
import logging
import os
import time

import numpy as np

from . import _septa
from . import _inputs
from .grid import Grid
from .network import Network
from .cut import CutCells, cut_mesh

__all__ = ["arrangement", "material_interface", "region_surfaces", "cut_mesh", "CutCells"]

# Messages of every job: its counts and stage seconds at INFO
# (logging.getLogger("septa").setLevel(logging.INFO) to see them).
log = logging.getLogger("septa")



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
    t = _inputs.integer_array(tets, "tets")
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


def _check_progress(progress):
    if progress is not None and not callable(progress):
        raise _septa.InputError("progress: expected a function progress(done, total)")


def _network(mode, grid_or_vertices, tets, values, threads, lookup, cells, progress=None, certify=True):
    v, t, f = _grid_inputs(grid_or_vertices, tets, values)
    if cells not in ("raytrace", "grouping"):
        raise _septa.InputError(f'cells must be "raytrace" or "grouping", not {cells!r}')
    box = None
    g = grid_or_vertices
    if isinstance(g, Grid) and g.resolution is not None and (tets is None or values is None or tets is g.tets):
        box = (tuple(g.resolution), g.bounds.tolist(), g.split)
    _check_progress(progress)
    t0 = time.perf_counter()
    d = _septa.network(mode, v, t, f, box, lookup=lookup, raytrace=(cells == "raytrace"),
                       threads=_inputs.threads(threads), progress=progress, certify=bool(certify))
    net = Network._from_core(d)
    _log_done(mode, net, t0)
    return net


def _log_done(what, net, t0):
    if log.isEnabledFor(logging.INFO):
        s = net.summary()
        log.info("%s: %d faces, %d patches, %d chains, %d cells in %.3f s (%s)", what, s["faces"], s["patches"],
                 s["chains"], s["cells"], time.perf_counter() - t0,
                 ", ".join(f"{k} {v:.3f}" for k, v in net.seconds.items()))


def arrangement(grid_or_vertices, tets, values=None, *, threads=None, lookup=True, cells="raytrace", progress=None,
                certify=True):
    """Implicit arrangement of the zero sets of k functions sampled on a tet grid.

    ``arrangement(grid, values)`` or ``arrangement(vertices, tets, values)``
    with ``values`` ``(#V, k) float64`` (a 1-D array is one function).
    ``threads``: worker threads (default all cores); ``lookup``: use the
    look-up tables; ``cells``: ``"raytrace"`` or ``"grouping"``;
    ``progress``: a function ``progress(done, total)`` called as blocks of
    the grid finish (e.g. to drive a tqdm bar). Counts and stage seconds are
    logged at INFO on the ``septa`` logger. ``certify``: check the written
    doubles exactly (no two vertices at one point, no degenerate triangle,
    no two triangles crossing) and repair them without changing any count;
    ``net.embedding`` says what was found and changed (``False``: the
    doubles as computed, ``net.embedding`` is None).
    Returns a :class:`septa.Network`; the same as ``septa ia``.

    >>> import septa
    >>> from septa import shapes
    >>> g = septa.grid.box(4)
    >>> f = shapes.sample([shapes.plane([.5] * 3, [1, 0, 0]), shapes.plane([.5] * 3, [0, 1, 0])], g)
    >>> s = septa.arrangement(g, f).summary()
    >>> s["patches"], s["chains"], s["cells"]
    (4, 1, 4)
    """
    return _network("ia", grid_or_vertices, tets, values, threads, lookup, cells, progress, certify)


def material_interface(grid_or_vertices, tets, values=None, *, threads=None, lookup=True, cells="raytrace",
                       progress=None, certify=True):
    """Material interface (argmax partition) of k functions on a tet grid;
    the same arguments as :func:`arrangement`, the same result as ``septa mi``."""
    return _network("mi", grid_or_vertices, tets, values, threads, lookup, cells, progress, certify)


def region_surfaces(scene_or_functions, rule=None, *, surfaces=None, curves=None, grid=None, mode="ia", normals=False,
                    clean=None, progress=None, certify=True, project=False):
    """Non-manifold implicit shape: the surfaces and curves of interest of a region rule.

    ``scene_or_functions`` is a scene (a dict in the scene-file form, a path,
    or ``"builtin:NAME"``), or a list of primitive dicts (``{"type": "sphere",
    "center": [..], "radius": r, "name": ..}``) used with ``rule`` (the
    scene's ``regions``: a list of ``{"when": EXPR, "region": R}`` or a CSG
    string for a solid), ``surfaces`` (region pairs of interest, default all),
    ``curves`` (region triples of interest), ``grid`` (``{"resolution": n,
    "bounds": [[..], [..]]}``) and ``mode``.
    Returns a :class:`septa.Network` whose patches are the surfaces (labels are
    region pairs, polygons counter-clockwise seen from the lesser region) and
    whose chains are the curves; ``net.surfaces`` and ``net.curves`` list
    each one's regions and topology (Euler characteristic, boundary loops).
    With ``normals=True`` (Bloomenthal 4.5.3.2: one vertex copy per region
    pair), ``net.normals`` holds one row per copy: ``"vertex"`` (point id),
    ``"regions"`` (the pair) and ``"normal"`` (unit gradient normal pointing
    into the lesser region), and ``net.indices_normal``, aligned with
    ``net.indices``, the copy of each polygon corner (else both are None).
    ``clean``: a factor (e.g. 0.2) to clean up small and thin triangles
    (Bloomenthal 4.5.3.1): edges shorter than it times the smallest cube
    edge are collapsed where the surfaces' topology, curves and corners
    stay; the polygons become triangles; ``net.summary()["clean"]`` says
    how many edges were collapsed and refused.
    ``progress``: a function ``progress(done, total)`` called as blocks of
    the network finish (as in :func:`arrangement`); the ``septa`` logger
    says what was computed, at INFO. ``certify``: as in :func:`arrangement`.
    ``project``: first move every vertex onto the true zero sets of the
    functions, inside its grid element, moves the exact check refuses left
    undone (``net.embedding["projection"]``); the same as
    ``septa regions --project``.

    >>> import septa
    >>> net = septa.region_surfaces("builtin:sphere-with-hole")
    >>> [(s["regions"], s["euler"], s["boundary_loops"]) for s in net.surfaces]
    [([0, 2], 1, 1)]
    >>> net = septa.region_surfaces("builtin:sphere-with-hole", normals=True)
    >>> len(net.indices_normal) == len(net.indices), net.normals["normal"].shape[1]
    (True, 3)
    """
    scene = scene_or_functions
    if isinstance(scene, (list, tuple)):
        scene = {"grid": grid or {"resolution": 32, "bounds": [[-1, -1, -1], [1, 1, 1]]}, "mode": mode,
                 "functions": [f.to_spec() if hasattr(f, "to_spec") else f for f in scene]}
        if rule is not None:
            scene["solid" if isinstance(rule, str) else "regions"] = rule
        if surfaces is not None:
            scene["surfaces"] = surfaces
        if curves is not None:
            scene["curves"] = curves
    elif rule is not None or surfaces is not None or curves is not None:
        raise _septa.InputError("rule, surfaces and curves go with a list of functions; a scene carries its own")
    text = json.dumps(scene) if isinstance(scene, dict) else str(scene)
    _check_progress(progress)
    t0 = time.perf_counter()
    net = _region_network(_septa.regions(text, normals=normals, clean=clean, progress=progress, certify=bool(certify),
                                          project=bool(project)))
    _log_done("region_surfaces", net, t0)
    return net


def label_surfaces(volume, *, sigma=0.0, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0), progress=None,
                   certify=True, names=None) -> Network:
    """Exact surfaces between the labels of a segmented volume (``septa labels``).

    ``volume``: a 3-axis integer array (any integer dtype; what nibabel,
    pynrrd or SimpleITK give), or the path of a ``.npy``, ``.nrrd`` or
    ``.nii``/``.nii.gz`` file (the last two need ``pip install pynrrd`` or
    ``nibabel``). One indicator function per label, optionally smoothed by a
    Gaussian of ``sigma`` voxels, then the exact material interface; regions
    are the labels, every pair of labels is a surface and every triple a curve.
    Points are ``origin + index * spacing``, or for a file without explicit
    ``spacing``/``origin`` its full voxel-to-world map (NIfTI affine, NRRD
    space directions and origin: rotations, shears and flips included, as
    ``nibabel.affines.apply_affine``); a mirroring map reverses each polygon
    so it stays counter-clockwise seen from the lesser region. Bool and
    whole-number float volumes are accepted. Returns a
    :class:`septa.Network` with ``surfaces`` and ``curves`` as
    :func:`region_surfaces`. ``progress``: a function ``progress(done,
    total)`` called as blocks of the network finish (as in :func:`arrangement`).
    ``certify``: as in :func:`arrangement`, on the placed points.
    ``names``: a dict label -> name (``septa labels --names``), in
    ``net.names["regions"]``, every saved result and ``net.region(name)``.

    >>> import numpy as np, septa
    >>> v = np.zeros((8, 8, 8), dtype=np.int32)
    >>> v[2:5, 2:6, 2:6] = 1
    >>> v[5:7, 2:6, 2:6] = 2
    >>> net = septa.label_surfaces(v)
    >>> sorted(s["regions"] for s in net.surfaces)
    [[0, 1], [0, 2], [1, 2]]
    """
    spacing_given = tuple(spacing) != (1.0, 1.0, 1.0) or tuple(origin) != (0.0, 0.0, 0.0)
    sp = np.asarray(spacing, dtype=np.float64).reshape(3)
    og = np.asarray(origin, dtype=np.float64).reshape(3)
    if not (np.isfinite(sp).all() and (sp > 0).all() and np.isfinite(og).all()):
        raise _septa.InputError(f"spacing must be 3 positive numbers and origin 3 numbers, got {spacing}, {origin}")
    affine = np.eye(4)
    affine[:3, :3] = np.diag(sp)
    affine[:3, 3] = og
    name = "volume"
    if isinstance(volume, (str, os.PathLike)):
        name = os.fspath(volume)
        volume, file_affine = _read_volume(name)
        if not spacing_given:
            affine = file_affine
    a = np.asarray(volume)
    if a.ndim != 3:
        raise _septa.InputError(f"{name}: expected a 3-axis label array, got {a.ndim} axes of {a.dtype}")
    # bool and whole-number float volumes are labels too; 2.5 is an error naming its voxel.
    a = _inputs.integer_array(a, name)
    m = np.asarray(affine, dtype=np.float64)[:3]
    if not np.isfinite(m).all() or np.linalg.matrix_rank(m[:, :3]) < 3:
        raise _septa.InputError(f"{name}: the voxel-to-world matrix {m[:, :3].tolist()} is not invertible and finite")
    _check_progress(progress)
    names = _label_names(names)
    t0 = time.perf_counter()
    # Placed in the core as the command line places them (the full affine:
    # direction cosines, shears, flips; a mirror reverses each polygon so it
    # stays counter-clockwise seen from the lesser region), then certified.
    data = _septa.labels(np.ascontiguousarray(a, dtype=np.int64), float(sigma), progress=progress,
                         affine=m.tolist(), names=names, certify=bool(certify))
    net = _region_network(data)
    _log_done("label_surfaces", net, t0)
    return net


def _label_names(names):
    """``{label (int): name (non-empty str)}`` or None; a clear error naming the bad entry."""
    if names is None:
        return None
    if not isinstance(names, dict):
        raise _septa.InputError(f"names: expected a dict label -> name, got {type(names).__name__}")
    out = {}
    for k, v in names.items():
        if isinstance(k, bool) or not isinstance(k, (int, np.integer)):
            raise _septa.InputError(f"names: key {k!r} is not an integer label")
        if not isinstance(v, str) or not v.strip() or any(ord(c) < 32 for c in v):
            raise _septa.InputError(f"names: label {k}: the name must be a non-empty text without control characters")
        out[int(k)] = v
    return out


def _read_volume(path: str):
    """(labels, 4x4 voxel-to-world affine) of a .npy, .nrrd or .nii(.gz) file."""
    low = path.lower()
    try:
        if low.endswith(".npy"):
            return np.load(path, allow_pickle=False), np.eye(4)
        if low.endswith(".nrrd"):
            try:
                import nrrd
            except ImportError as e:
                raise ImportError("reading .nrrd needs pynrrd: pip install pynrrd") from e
            data, header = nrrd.read(path)
            affine = np.eye(4)
            directions = header.get("space directions")
            if directions is not None:
                # One row per axis: the world step of one voxel along it.
                d = np.asarray(directions, dtype=np.float64)
                if d.shape != (3, 3):
                    raise _septa.InputError(f"{path}: space directions of shape {d.shape}, expected 3 rows of 3")
                affine[:3, :3] = d.T
            affine[:3, 3] = np.asarray(header.get("space origin", (0.0, 0.0, 0.0)), dtype=np.float64)
            return data, affine
        if low.endswith(".nii") or low.endswith(".nii.gz"):
            try:
                import nibabel
            except ImportError as e:
                raise ImportError("reading .nii needs nibabel: pip install nibabel") from e
            img = nibabel.load(path)
            return np.asanyarray(img.dataobj), np.asarray(img.affine, dtype=np.float64)
    except (OSError, ValueError) as e:
        if isinstance(e, _septa.InputError):
            raise
        raise _septa.InputError(f"{path}: cannot read ({e})") from e
    raise _septa.InputError(f"{path}: expected a .npy, .nrrd or .nii/.nii.gz label volume")


def _region_network(data: dict) -> Network:
    """Region surfaces as a :class:`Network` with ``surfaces``, ``curves``
    and, when computed, ``normals``: from the core's arrays (with
    ``"summary"``) or from a ``network.json`` document."""
    if "summary" in data:
        summary = json.loads(data["summary"])
        data["counts"], data["seconds"] = summary, summary.get("seconds", {})
        net = Network._from_core(data)
        net.surfaces, net.curves = summary["surfaces"], summary["curves"]
        net.embedding = summary.get("embedding")
        net.normals = net.indices_normal = None
        if "normal_vertex" in data:
            net.normals = {"vertex": data["normal_vertex"], "regions": data["normal_regions"],
                           "normal": data["normal_vectors"]}
            net.indices_normal = data["indices_normal"]
        return net
    net = Network(data)
    net.surfaces = data["counts"]["surfaces"]
    net.curves = data["counts"]["curves"]
    net.normals = None
    net.indices_normal = None
    if "normals" in data:
        n = data["normals"]
        net.normals = {
            "vertex": np.asarray(n["vertex"], dtype=np.int64),
            "regions": np.asarray(n["regions"], dtype=np.int64).reshape(-1, 2),
            "normal": np.asarray(n["normal"], dtype=np.float64).reshape(-1, 3),
        }
        net.indices_normal = np.asarray([c for f in data["face_normals"] for c in f], dtype=np.int64)
    return net
