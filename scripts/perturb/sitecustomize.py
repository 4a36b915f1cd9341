"""Move the last bit of the elementary functions: a stand-in for another machine's libm.

``scripts/perturbed_check.py`` puts this folder on ``PYTHONPATH`` for its
``libm-ulp`` environment, so that Python imports this module at start-up, in
pytest and in every notebook kernel alike.  It replaces ``math.sin``, ``cos``,
``tan``, ``exp``, ``expm1``, ``log``, ``tanh``, ``sinh``, ``cosh`` and the
NumPy ufuncs of the same names by wrappers whose results are one ulp away from
the library's: towards zero where the result's last bit is 1, away from zero
where it is 0, so that the change has no bias.  Results that every libm gives
exactly (0, 1, -1, infinities, NaN) are left alone, as are NaN-free integer
powers and the arithmetic itself.  The C kernels call libm directly and are
untouched: run with ``LUMPED_PURE_PYTHON=1`` so that the Python kernels stand
in for them.
"""

from __future__ import annotations

import math
import struct

NAMES = ("sin", "cos", "tan", "exp", "expm1", "log", "tanh", "sinh", "cosh")


def _moved(r: float) -> float:
    """``r`` one ulp up or down in magnitude, by its last bit (``r`` itself if exact everywhere)."""
    if r == 0.0 or abs(r) == 1.0 or not math.isfinite(r):
        return r
    odd = struct.unpack("<q", struct.pack("<d", r))[0] & 1
    return math.nextafter(r, 0.0 if odd else math.copysign(math.inf, r))


def _wrap_math(f):
    def moved(*args):
        return _moved(f(*args))

    moved.__name__ = moved.__qualname__ = f.__name__
    moved.__doc__ = f.__doc__
    return moved


def _patch_math() -> None:
    for name in NAMES:
        setattr(math, name, _wrap_math(getattr(math, name)))


def _patch_numpy() -> None:
    import numpy as np

    def moved(r):
        r = np.asarray(r)
        if r.dtype.kind != "f":
            return r
        odd = (r.view(np.int64 if r.itemsize == 8 else np.int32) & 1).astype(bool)
        towards = np.where(odd, 0.0, np.copysign(np.inf, r)).astype(r.dtype)
        keep = (r == 0) | (np.abs(r) == 1) | ~np.isfinite(r)
        return np.where(keep, r, np.nextafter(r, towards))

    def wrap(uf):
        def call(*args, **kwargs):
            out = uf(*args, **kwargs)
            if isinstance(out, np.ndarray):
                out[...] = moved(out)
                return out
            return out.dtype.type(moved(out)[()]) if isinstance(out, np.generic) else out

        call.__name__ = call.__qualname__ = uf.__name__
        call.__doc__ = uf.__doc__
        return call

    for name in NAMES:
        setattr(np, name, wrap(getattr(np, name)))


_patch_math()
_patch_numpy()
