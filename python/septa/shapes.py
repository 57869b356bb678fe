"""Primitive functions, evaluable on numpy arrays of points.

Each primitive is a callable: ``f(points)`` with ``points`` of shape
``(..., 3)`` returns values of shape ``(...)``, ``float64``, **positive
inside** (a sphere is ``r - |x - c|``, as in the reference implementation's
function files). ``f.to_spec()`` gives the primitive as a scene / reference
JSON entry. :func:`sample` evaluates several on a grid into the ``(#V, k)``
array the jobs take.

A primitive *is* its scene entry: values come from the library's one reader
and evaluator of primitives (the compiled core), so ``f(points)`` equals,
bit for bit, what a scene file holding ``f.to_spec()`` samples at those
points, and what the command line and the distributed jobs compute.

>>> import numpy as np
>>> s = sphere([0, 0, 0], 1.0)
>>> s(np.array([[0, 0, 0], [2, 0, 0]])).tolist()
[1.0, -1.0]
>>> float(box([0, 0, 0], [1, 1, 1])(np.array([0.5, 0, 0])))
0.5
"""
from __future__ import annotations

import json

import numpy as np

from . import _septa
from ._septa import InputError

__all__ = ["Primitive", "sphere", "plane", "halfspace", "box", "cylinder", "torus", "capsule", "constant", "sample"]


def _vec(v, name):
    a = np.asarray(v, dtype=np.float64)
    if a.shape != (3,) or not np.all(np.isfinite(a)):
        raise InputError(f"{name}: expected three finite numbers, got {v!r}")
    return a.tolist()


def _positive(x, name):
    x = float(x)
    if not np.isfinite(x) or x <= 0:
        raise InputError(f"{name}: must be a finite positive number, got {x!r}")
    return x


def _direction(v, name):
    # Kept as given: the library normalises it exactly as it does a scene
    # file's (normalising here too could move the last bit).
    a = _vec(v, name)
    if not any(a):
        raise InputError(f"{name}: must not be the zero vector")
    return a


def _points(points, kind):
    p = np.asarray(points, dtype=np.float64)
    if p.shape[-1:] != (3,):
        raise InputError(f"{kind}: points must have shape (..., 3), got {p.shape}")
    return p


def _sample(specs, p):
    """Values of the scene entries ``specs`` at ``p`` ``(..., 3)``: ``(..., k)``."""
    flat = np.ascontiguousarray(p.reshape(-1, 3))
    values = _septa.sample_functions(json.dumps(specs), flat)
    return values.reshape(p.shape[:-1] + (len(specs),))


class Primitive:
    """A function of position; call it on ``(..., 3)`` arrays.

    ``kind`` is the scene ``type`` and ``spec`` the scene entry's other
    fields; the library checks the entry when the primitive is made.
    """

    def __init__(self, kind: str, spec: dict):
        self.kind, self._spec = kind, dict(spec)
        _sample([self.to_spec()], np.zeros((0, 3)))

    def __call__(self, points) -> np.ndarray:
        v = _sample([self.to_spec()], _points(points, self.kind))[..., 0]
        return v[()] if v.ndim == 0 else v

    def to_spec(self) -> dict:
        """The primitive as a scene / reference-format JSON entry."""
        return {"type": self.kind, **self._spec}

    def __repr__(self) -> str:
        return f"septa.shapes.{self.kind}({self.to_spec()})"


def sphere(center, radius) -> Primitive:
    """``r - |x - c|``."""
    return Primitive("sphere", {"center": _vec(center, "sphere.center"), "radius": _positive(radius, "sphere.radius")})


def plane(point, normal) -> Primitive:
    """``(x - point) . normal``, normal normalised: positive on the normal's side."""
    return Primitive("plane", {"point": _vec(point, "plane.point"), "normal": _direction(normal, "plane.normal")})


def halfspace(point, normal) -> Primitive:
    """Inside = behind the plane: ``(point - x) . normal``."""
    return Primitive("halfspace", {"point": _vec(point, "halfspace.point"),
                                   "normal": _direction(normal, "halfspace.normal")})


def box(center, half_size) -> Primitive:
    """Exact signed distance to an axis-aligned box, positive inside."""
    c, h = _vec(center, "box.center"), _vec(half_size, "box.half_size")
    if min(h) <= 0:
        raise InputError(f"box.half_size: must be positive, got {h}")
    return Primitive("box", {"center": c, "half_size": h})


def cylinder(point, axis, radius) -> Primitive:
    """Infinite cylinder: ``r - distance to the axis line``."""
    return Primitive("cylinder", {"axis_point": _vec(point, "cylinder.point"),
                                  "axis_vector": _direction(axis, "cylinder.axis"),
                                  "radius": _positive(radius, "cylinder.radius")})


def torus(center, axis, major, minor) -> Primitive:
    """``minor - distance to the circle of radius major around axis``."""
    return Primitive("torus", {"center": _vec(center, "torus.center"), "axis_vector": _direction(axis, "torus.axis"),
                               "major_radius": _positive(major, "torus.major"),
                               "minor_radius": _positive(minor, "torus.minor")})


def capsule(a, b, radius) -> Primitive:
    """``r - distance to the segment ab``."""
    return Primitive("capsule", {"a": _vec(a, "capsule.a"), "b": _vec(b, "capsule.b"),
                                 "radius": _positive(radius, "capsule.radius")})


def constant(value: float = 0.0) -> Primitive:
    """The constant function (the reference's ``zero`` for value 0)."""
    v = float(value)
    if not np.isfinite(v):
        raise InputError(f"constant.value: must be a finite number, got {v!r}")
    return Primitive("constant", {"value": v})


def sample(functions, grid_or_points) -> np.ndarray:
    """Evaluates functions at the grid vertices: ``(#V, k) float64``.

    Primitives are sampled together in one call of the library (in
    parallel); any other callable ``f(points)`` is called on the points.

    >>> from septa import grid
    >>> sample([sphere([0.5] * 3, 0.3), plane([0.5] * 3, [0, 0, 1])], grid.box(2)).shape
    (27, 2)
    """
    pts = getattr(grid_or_points, "vertices", grid_or_points)
    pts = _points(pts, "sample").reshape(-1, 3)
    functions = list(functions)
    if functions and all(isinstance(f, Primitive) for f in functions):
        return np.ascontiguousarray(_sample([f.to_spec() for f in functions], pts))
    return np.ascontiguousarray(np.stack([np.asarray(f(pts), dtype=np.float64) for f in functions], axis=1))
