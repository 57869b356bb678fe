"""Input coercion shared by the jobs: each array is converted once to the
dtype the Rust core reads, and a value that the conversion would change
(a fractional index, a label 2.5, NaN) is an :class:`septa.InputError`
naming the array and the element instead of being truncated silently
(before: ``septa.arrangement(V, T + 0.7, F)`` ran on ``T``)."""
from __future__ import annotations

import numpy as np

from . import _septa

#: Most worker threads accepted (the command line's ``--threads`` limit).
MAX_THREADS = 1024


def _first_bad(mask: np.ndarray) -> tuple:
    return tuple(int(i) for i in np.argwhere(mask)[0])


def integer_array(a, name: str) -> np.ndarray:
    """``a`` as a C-contiguous int64 array; floats must hold whole numbers,
    booleans become 0/1. Raises InputError naming the first bad element."""
    arr = np.asarray(a)
    if arr.dtype == object or arr.dtype.kind in "USVcmM":
        raise _septa.InputError(f"{name}: expected integers, got an array of {arr.dtype}")
    if arr.dtype.kind == "f":
        bad = ~np.isfinite(arr) | (arr != np.round(arr)) if arr.size else np.zeros(arr.shape, bool)
        if bad.any():
            at = _first_bad(bad)
            raise _septa.InputError(f"{name}: element {at} is {arr[at].item()!r}, not a whole number")
        if arr.size and (np.abs(arr).max() >= 2.0**63):
            raise _septa.InputError(f"{name}: values beyond the int64 range")
    elif arr.dtype.kind == "u" and arr.dtype.itemsize == 8 and arr.size and arr.max() >= 2**63:
        raise _septa.InputError(f"{name}: values beyond the int64 range")
    return np.ascontiguousarray(arr, dtype=np.int64)


def threads(t):
    """``None`` (all cores) or a whole number of worker threads in 1..=1024."""
    if t is None:
        return None
    if isinstance(t, bool) or not isinstance(t, (int, np.integer)):
        raise _septa.InputError(f"threads: expected a whole number or None, not {t!r}")
    if not 1 <= int(t) <= MAX_THREADS:
        raise _septa.InputError(f"threads: {t} is out of range 1..={MAX_THREADS}")
    return int(t)
