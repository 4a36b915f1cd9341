"""The textbook model of the article: ``sgn(0) = 0`` and its ``tanh`` regularisation, run as notebook 02 runs them.

:func:`textbook_runs` gives forward Euler, RK45 and the ``tanh`` model from
rest inside the static band, with the settings of :data:`TEXTBOOK`, so that
the article and notebook 02 print the same numbers.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from lumped.model.oscillator import Oscillator
from lumped.solvers import textbook

__all__ = ["TEXTBOOK", "textbook_runs"]

#: Settings of notebook 02 (notebooks/02_sgn_zero_failure.py), used here so
#: that the article and the notebook print the same numbers: release point
#: (fraction of the static band), forward-Euler step and duration, RK45
#: tolerances and budget, tanh scales, their duration and LSODA tolerances.
TEXTBOOK: dict[str, Any] = {
    "x0_band_fraction": 0.5,
    "t_end": 1.0,
    "euler_dt": 1e-4,
    "rk45_rtol": 1e-8,
    "rk45_atol": 1e-10,
    "rk45_budget": 100_000,
    "tanh_eps": (1e-2, 1e-3, 1e-4, 1e-5),
    "tanh_t_end": 5.0,
    "tanh_rtol": 1e-8,
    "tanh_atol": 1e-12,
}


def _creep(osc: Oscillator, x0: float, eps: float) -> dict[str, float]:
    """The ``tanh`` model released at rest at ``x0``, run as notebook 02 runs it.

    Returns the state at the end, the measured creep rate ``v/x`` (1/s), the
    linear rate ``-k eps/(tau + c eps)`` of the quasi-static law
    ``k x + tau tanh(v/eps) + c v = 0`` linearised at ``x = 0`` (``c = 1/gamma``),
    the same linearisation's slow rate with inertia kept (``inertial_rate``,
    :meth:`~lumped.solvers.textbook.TextbookModel.creep_rates`, the definitions
    notebook 02 prints), and ``k x/tau`` at the end, which the linearisation
    needs small.
    """
    s = TEXTBOOK
    model = textbook.TextbookModel(osc, eps=eps)
    linear, inertial = model.creep_rates()
    run = textbook.integrate_adaptive(
        model,
        s["tanh_t_end"],
        x0=x0,
        method="LSODA",
        rtol=s["tanh_rtol"],
        atol=s["tanh_atol"],
        max_seconds=600.0,
    )
    if not run.finished:
        raise RuntimeError(run.message)
    x, v = float(run.x[-1]), float(run.v[-1])
    return {
        "eps": eps,
        "x_end": x,
        "v_end": v,
        "rate": v / x,
        "linear_rate": linear,
        "inertial_rate": inertial,
        "load_end": osc.stiffness * x / osc.threshold,
    }


def textbook_runs(osc: Oscillator) -> dict[str, Any]:
    """Forward Euler, RK45 and the ``tanh`` regularisation from rest inside the band."""
    s = TEXTBOOK
    x0 = s["x0_band_fraction"] * osc.static_band
    model = textbook.TextbookModel(osc)
    euler = textbook.integrate_fixed(model, s["t_end"], s["euler_dt"], x0=x0, scheme="euler")
    rk45 = textbook.integrate_adaptive(
        model,
        s["t_end"],
        x0=x0,
        method="RK45",
        rtol=s["rk45_rtol"],
        atol=s["rk45_atol"],
        max_nfev=s["rk45_budget"],
        max_seconds=600.0,
    )
    tanh = [_creep(osc, x0, eps) for eps in s["tanh_eps"]]
    ratios = [r["rate"] / r["linear_rate"] for r in tanh]
    return {key: s[key] for key in ("t_end", "euler_dt", "rk45_rtol", "rk45_atol", "rk45_budget", "tanh_t_end")} | {
        "x0": x0,
        "load_0": osc.stiffness * x0 / osc.threshold,
        "euler_steps": int(euler.t.size - 1),
        "euler_sign_changes": euler.sign_changes,
        "euler_max_v": float(np.max(np.abs(euler.v))),
        "euler_x_end": float(euler.x[-1]),
        "rk45_finished": rk45.finished,
        "rk45_nfev": rk45.nfev,
        "rk45_t_reached": rk45.t_reached,
        "rk45_median_step": rk45.median_step,
        "tanh": tanh,
        "linear_ratio_min": min(ratios),
        "linear_ratio_max": max(ratios),
    }
