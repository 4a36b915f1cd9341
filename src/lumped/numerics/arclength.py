"""The predictor of pseudo-arclength continuation, shared by every branch the package follows.

A branch is a curve ``G(u) = 0`` in ``n + 1`` unknowns (a state and a
parameter, scaled).  :func:`unit_tangent` is the null vector of ``dG/du``
(``n x (n + 1)``) at a point, oriented along the previous tangent, and
:func:`predict` the point ``ds`` along it from which the corrector (Newton on
``G = 0`` and ``tangent . (u - u_pred) = 0``, each user's own) starts.  The
forced orbits of :mod:`lumped.drivers.response.continuation` and the limit
cycles of :mod:`lumped.drivers.cycles.continuation` both step with these.
"""

from __future__ import annotations

import numpy as np

__all__ = ["predict", "unit_tangent"]


def unit_tangent(matrix: np.ndarray, previous: np.ndarray | None) -> np.ndarray:
    """The unit null vector of ``matrix`` (``n x (n + 1)``), oriented along ``previous`` (or towards a larger
    last component, the parameter, when there is none).

    In closed form for ``1 x 2`` (``(-b, a)`` of the row ``(a, b)``) and ``2 x 3`` (the cross product of the
    rows), else the last right singular vector.
    """
    if matrix.shape == (1, 2):
        t = np.array([-matrix[0, 1], matrix[0, 0]], dtype=float)
    elif matrix.shape == (2, 3):
        t = np.cross(matrix[0], matrix[1])
    else:
        t = np.linalg.svd(matrix)[2][-1]
    t /= np.linalg.norm(t)
    ref = t[-1] if previous is None else t @ previous
    return -t if ref < 0 else t


def predict(u: np.ndarray, tangent: np.ndarray, ds: float, back: tuple[np.ndarray, np.ndarray] | None) -> np.ndarray:
    """The predictor ``ds`` along ``tangent`` from ``u``: where the branch, parametrised by ``sigma = tangent .
    (w - u)``, crosses ``sigma = ds``, by the cubic that matches the previous point ``back = (u_back,
    tangent_back)`` and ``u`` and their slopes ``dw/dsigma = t/(tangent . t)`` (Hermite), extrapolated.

    Its error is ``O(ds^4)`` where the branch is smooth (the tangent line's is ``O(ds^2)``), so that one
    corrector iterate mostly suffices; the tangent line where there is no previous point (the first, and
    after a kink of the branch: a change of the stops or of the stick phases).
    """
    if back is None:
        return u + ds * tangent
    h = float(tangent @ (u - back[0]))  # the previous point at sigma = -h
    if not h > 0:
        return u + ds * tangent
    d_back = back[1] / float(tangent @ back[1])
    s = 1.0 + ds / h  # sigma + h in units of h
    h00, h10, h01, h11 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, 3 * s**2 - 2 * s**3, s**3 - s**2
    return h00 * back[0] + h10 * h * d_back + h01 * u + h11 * h * tangent
