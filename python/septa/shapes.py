"""Primitive functions, evaluable on numpy arrays of points.

Each primitive is a callable: ``f(points)`` with ``points`` of shape
``(..., 3)`` returns values of shape ``(...)``, ``float64``, **positive
inside** (a sphere is ``r - |x - c|``, as in the reference implementation's
function files). ``f.to_spec()`` gives the primitive as a scene / reference
JSON entry. :func:`sample` evaluates several on a grid into the ``(#V, k)``
array the jobs take.

>>> import numpy as np
>>> s = sphere([0, 0, 0], 1.0)
>>> s(np.array([[0, 0, 0], [2, 0, 0]])).tolist()
[1.0, -1.0]
>>> float(box([0, 0, 0], [1, 1, 1])(np.array([0.5, 0, 0])))
0.5
"""
from __future__ import annotations

import numpy as np

from ._septa import InputError

__all__ = ["Primitive", "sphere", "plane", "halfspace", "box", "cylinder", "torus", "capsule", "constant", "sample"]


def _vec(v, name):
    a = np.asarray(v, dtype=np.float64)
    if a.shape != (3,) or not np.all(np.isfinite(a)):
        raise InputError(f"{name}: expected three finite numbers, got {v!r}")
    return a


def _positive(x, name):
    x = float(x)
    if not np.isfinite(x) or x <= 0:
        raise InputError(f"{name}: must be a finite positive number, got {x!r}")
    return x


def _unit(v, name):
    a = _vec(v, name)
    n = np.linalg.norm(a)
    if n == 0:
        raise InputError(f"{name}: must not be the zero vector")
    return a / n


class Primitive:
    """A function of position; call it on ``(..., 3)`` arrays."""

    def __init__(self, kind: str, fn, spec: dict):
        self.kind, self._fn, self._spec = kind, fn, spec

    def __call__(self, points) -> np.ndarray:
        p = np.asarray(points, dtype=np.float64)
        if p.shape[-1:] != (3,):
            raise InputError(f"{self.kind}: points must have shape (..., 3), got {p.shape}")
        return self._fn(p)

    def to_spec(self) -> dict:
        """The primitive as a scene / reference-format JSON entry."""
        return {"type": self.kind, **{k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in self._spec.items()}}

    def __repr__(self) -> str:
        return f"septa.shapes.{self.kind}({self.to_spec()})"


def sphere(center, radius) -> Primitive:
    """``r - |x - c|``."""
    c, r = _vec(center, "sphere.center"), _positive(radius, "sphere.radius")
    return Primitive("sphere", lambda p: r - np.linalg.norm(p - c, axis=-1), {"center": c, "radius": r})


def plane(point, normal) -> Primitive:
    """``(x - point) . normal``, normal normalised: positive on the normal's side."""
    q, n = _vec(point, "plane.point"), _unit(normal, "plane.normal")
    return Primitive("plane", lambda p: (p - q) @ n, {"point": q, "normal": n})


def halfspace(point, normal) -> Primitive:
    """Inside = behind the plane: ``(point - x) . normal``."""
    q, n = _vec(point, "halfspace.point"), _unit(normal, "halfspace.normal")
    return Primitive("halfspace", lambda p: (q - p) @ n, {"point": q, "normal": n})


def box(center, half_size) -> Primitive:
    """Exact signed distance to an axis-aligned box, positive inside."""
    c, h = _vec(center, "box.center"), _vec(half_size, "box.half_size")
    if np.any(h <= 0):
        raise InputError(f"box.half_size: must be positive, got {h.tolist()}")

    def f(p):
        d = np.abs(p - c) - h
        outside = np.linalg.norm(np.maximum(d, 0.0), axis=-1)
        inside = np.minimum(np.max(d, axis=-1), 0.0)
        return -(outside + inside)

    return Primitive("box", f, {"center": c, "half_size": h})


def cylinder(point, axis, radius) -> Primitive:
    """Infinite cylinder: ``r - distance to the axis line``."""
    q, a, r = _vec(point, "cylinder.point"), _unit(axis, "cylinder.axis"), _positive(radius, "cylinder.radius")

    def f(p):
        d = p - q
        return r - np.linalg.norm(d - np.multiply.outer(d @ a, a), axis=-1)

    return Primitive("cylinder", f, {"point": q, "axis": a, "radius": r})


def torus(center, axis, major, minor) -> Primitive:
    """``minor - distance to the circle of radius major around axis``."""
    c, a = _vec(center, "torus.center"), _unit(axis, "torus.axis")
    R, r = _positive(major, "torus.major"), _positive(minor, "torus.minor")

    def f(p):
        d = p - c
        h = d @ a
        radial = np.linalg.norm(d - np.multiply.outer(h, a), axis=-1)
        return r - np.hypot(radial - R, h)

    return Primitive("torus", f, {"center": c, "axis": a, "major": R, "minor": r})


def capsule(a, b, radius) -> Primitive:
    """``r - distance to the segment ab``."""
    p0, p1, r = _vec(a, "capsule.a"), _vec(b, "capsule.b"), _positive(radius, "capsule.radius")
    ab = p1 - p0
    L2 = float(ab @ ab)

    def f(p):
        t = np.clip(((p - p0) @ ab) / L2, 0.0, 1.0) if L2 > 0 else np.zeros(p.shape[:-1])
        return r - np.linalg.norm(p - p0 - np.multiply.outer(t, ab), axis=-1)

    return Primitive("capsule", f, {"a": p0, "b": p1, "radius": r})


def constant(value: float = 0.0) -> Primitive:
    """The constant function (the reference's ``zero`` for value 0)."""
    v = float(value)
    return Primitive("constant", lambda p: np.full(p.shape[:-1], v), {"value": v})


def sample(functions, grid_or_points) -> np.ndarray:
    """Evaluates functions at the grid vertices: ``(#V, k) float64``.

    >>> from septa import grid
    >>> sample([sphere([0.5] * 3, 0.3), plane([0.5] * 3, [0, 0, 1])], grid.box(2)).shape
    (27, 2)
    """
    pts = getattr(grid_or_points, "vertices", grid_or_points)
    pts = np.asarray(pts, dtype=np.float64)
    return np.ascontiguousarray(np.stack([np.asarray(f(pts), dtype=np.float64) for f in functions], axis=1))
