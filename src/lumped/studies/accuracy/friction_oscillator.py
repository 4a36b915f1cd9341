"""Siconos' FrictionOscillator beside the study: where each fixed-step scheme rests at Siconos' step.

Siconos' example (``tests/data/siconos/README.md``): a unit mass on a unit
spring with Coulomb friction of bound 1, released from ``x0 = 12`` m with
``v0 = 6`` m/s and integrated at ``dt = 0.01`` s.  It slides through eight
half-cycles whose amplitude about the friction's centre falls by ``2 tau/k``
each, and rests at ``15 - sqrt(205)`` m (``exact``).  :func:`friction_oscillator`
runs every fixed-step scheme of the registry at that step and measures

* ``error``: the distance of its rest position from the exact one (m);
* ``stick_swing``: ``max |F_d + F_s|`` over the final stick after its first
  step (N): with no load the reaction is ``-F_s``, so this is how far the
  dashpot force strays from it (``0`` if it settles on it; the ``theta``
  method's alternates, :mod:`lumped.solvers.theta`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from lumped.drivers.methods import METHODS
from lumped.model.oscillator import Oscillator
from lumped.solvers.exact import solve_exact
from lumped.studies.accuracy.methods import SCHEMES

__all__ = ["FRICTION_OSCILLATOR", "friction_oscillator"]

#: The example's values (m in kg, k in N/m, the Coulomb bound in N, x0 in m, v0 in m/s, dt and t_end in s).
FRICTION_OSCILLATOR = {"mass": 1.0, "stiffness": 1.0, "bound": 1.0, "x0": 12.0, "v0": 6.0, "dt": 0.01, "t_end": 40.0}


def _stick_swing(t: np.ndarray, f_d: np.ndarray, f_s: np.ndarray, rest_time: float) -> float:
    """``max |F_d + F_s|`` over the grid points after the first of the final stick (N); nan if moving."""
    after = t > rest_time
    return float(np.max(np.abs(f_d[after] + f_s[after]))) if after.any() else math.nan


def friction_oscillator() -> dict[str, Any]:
    """The example's exact rest and, per fixed-step scheme, its rest position, error and stick swing."""
    p = FRICTION_OSCILLATOR
    osc = Oscillator.bingham(p["mass"], p["stiffness"], p["bound"], math.inf)
    exact = solve_exact(osc, p["t_end"], x0=p["x0"], v0=p["v0"]).rest_through(p["t_end"])[1]
    out: dict[str, Any] = {"case": dict(p), "exact": exact, "schemes": {}}
    for name in SCHEMES:
        tr = METHODS[name](osc, p["t_end"], p["dt"], p["x0"], p["v0"], None, 1)
        out["schemes"][name] = {
            "position": tr.rest_position,
            "error": abs(tr.rest_position - exact),
            "stick_swing": _stick_swing(tr.t, tr.F_d, tr.F_s, tr.rest_time),
        }
    return out
