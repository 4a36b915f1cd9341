"""Every number the article quotes, computed from the ``lumped`` package.

Usage::

    python scripts/paper_numbers.py paper/build/numbers.json

The article (``paper/paper.typ``) reads the JSON with Typst's ``json()`` and
types no number by hand.  ``tests/test_paper_numbers.py`` calls
:func:`compute` and checks each value against an independent reference
(eq. 19, the free-decay recurrence of the viscous + Coulomb oscillator, the
quasi-static creep law of the regularised model, or the exact event-driven
solution against backward Euler).

Layout of the JSON: one object per example of section 3 of the paper
(``forced_small`` = Figure 5, ``forced_large`` = Figures 6-9, ``free_small`` =
Figure 10, ``free_large`` = Figures 11-14), each with the exact solution
(``exact``), Algorithm 1 at the paper's step (``be``) and their differences
(``error``); ``convergence`` holds the same differences for a range of steps;
``textbook`` the numbers of the ``sgn(0) = 0`` model and its regularisation.
Times in s, displacements in m, velocities in m/s, forces in N.

The JSON is strict (no ``NaN`` or ``Infinity``, which JSON lacks): a run that
has not come to rest by its end time has ``"still moving"`` as its rest time
and rest position; a difference or fitted order that cannot be formed (one of
the runs still moving, or a zero error on a logarithmic fit) is ``null``, as is
``first_event_time`` of a mass that never moves; an
infinite parameter (``gamma`` for Coulomb friction, ``force_until`` for a
forcing never switched off) is the string ``"inf"``.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

import lumped as L
import lumped.config
from lumped import examples
from lumped import textbook
from lumped.results import sign_changes

#: Steps of the convergence study (s); the paper's is 1e-4.
CONVERGENCE_STEPS = (1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5)
#: Forward Euler on the textbook model: step (s) and duration (s).
TEXTBOOK_DT, TEXTBOOK_T_END = 1e-4, 1.0
#: Budget of right-hand-side evaluations given to RK45 on the textbook model.
RK45_BUDGET = 50_000
RK45_RTOL, RK45_ATOL = 1e-8, 1e-10
#: Regularisation scales (m/s) of sgn(v) -> tanh(v/eps).
TANH_EPS = (1e-3, 1e-4, 1e-5, 1e-6)
#: Rest time and rest position of a run still moving at its end time.
STILL_MOVING = "still moving"


def _rest(value: float) -> float | str:
    """A rest time or position, or STILL_MOVING where the trajectory gives ``nan``."""
    return STILL_MOVING if math.isnan(value) else value


def _deviation(be: L.Trajectory, ref: L.Trajectory) -> dict[str, float]:
    """Largest absolute differences over the run, column by column.

    ``int_F_d`` is the time integral of ``|F_d - F_d,exact|`` (N s): the
    largest difference in ``F_d`` is the jump ``2 mu_s N_f`` seen at a grid
    point between a reversal of the exact motion and that of Algorithm 1, so
    it does not shrink with the step, while the integral does.
    """
    out = {f"max_{c}": float(np.max(np.abs(getattr(be, c) - getattr(ref, c)))) for c in ("x", "v", "F_s", "F_d")}
    out["int_F_d"] = float(np.sum(np.abs(be.F_d - ref.F_d)[1:]) * be.dt)
    return out


def _compare(osc: L.Oscillator, dt: float, run: dict[str, Any], exact: L.ExactSolution) -> dict[str, float]:
    """Algorithm 1 at step ``dt`` against the exact solution sampled on its grid."""
    be = L.backward_euler(osc, run["t_end"], dt, x0=run["x0"], force=run["force"])
    out = _deviation(be, exact.sample(dt))
    out["rest_position"] = abs(be.rest_position - exact.rest_position)
    out["rest_time"] = abs(be.rest_time - exact.rest_time)
    return out


def _exact_summary(ex: L.ExactSolution) -> dict[str, Any]:
    kinds = [e.kind for e in ex.events]
    moving = [e for e in ex.events if e.kind in ("breakaway", "reversal", "stop")]
    return {
        "rest_time": _rest(ex.rest_time),
        "rest_position": _rest(ex.rest_position),
        "reversals": kinds.count("reversal"),
        "breakaways": kinds.count("breakaway"),
        "first_event_time": moving[0].time if moving else math.nan,
        "reversal_times": [e.time for e in ex.events if e.kind == "reversal"],
        "reversal_positions": [e.x for e in ex.events if e.kind == "reversal"],
    }


def _example(osc: L.Oscillator, dt: float, run: dict[str, Any]) -> dict[str, Any]:
    exact = L.solve_exact(osc, run["t_end"], x0=run["x0"], force=run["force"])
    be = L.backward_euler(osc, run["t_end"], dt, x0=run["x0"], force=run["force"])
    sampled = exact.sample(dt)
    error = _deviation(be, sampled)
    error["rest_position"] = abs(be.rest_position - exact.rest_position)
    error["rest_time"] = abs(be.rest_time - exact.rest_time)
    return {
        "exact": _exact_summary(exact)
        | {"peak_x": float(np.max(np.abs(sampled.x))), "peak_v": float(np.max(np.abs(sampled.v)))},
        "be": {
            "rest_time": _rest(be.rest_time),
            "rest_position": _rest(be.rest_position),
            "peak_x": float(np.max(np.abs(be.x))),
            "peak_v": float(np.max(np.abs(be.v))),
            "min_F_d": float(np.min(be.F_d)),
            "max_F_d": float(np.max(be.F_d)),
            "stick_fraction": float(np.mean(be.v == 0.0)),
            "reversals": sign_changes(be.v),
            "energy_residual": float(np.max(np.abs(be.energy_balance().residual))),
            "steps": int(be.t.size - 1),
        },
        "error": error,
    }


def _forced_small_extra(osc: L.Oscillator, dt: float, run: dict[str, Any]) -> dict[str, float]:
    """Figure 5 against eq. (19): F_d = F_1, and x = v = F_s = 0."""
    be = L.backward_euler(osc, run["t_end"], dt, x0=run["x0"], force=run["force"])
    return {
        "max_F1": float(np.max(np.abs(be.F))),
        "eq19_max_F_d": float(np.max(np.abs(be.F_d - be.F))),
        "eq19_max_x": float(np.max(np.abs(be.x))),
        "eq19_max_v": float(np.max(np.abs(be.v))),
        "eq19_max_F_s": float(np.max(np.abs(be.F_s))),
    }


def _order(steps: list[float], errors: list[float]) -> float:
    """Least-squares slope of log(error) against log(step); ``nan`` unless every error is > 0."""
    if not all(e > 0 and math.isfinite(e) for e in errors):
        return math.nan  # a zero error (exact at that step) or a run still moving
    return float(np.polyfit(np.log(steps), np.log(errors), 1)[0])


def _convergence(osc: L.Oscillator, runs: dict[str, dict[str, Any]]) -> dict[str, Any]:
    out: dict[str, Any] = {"steps": list(CONVERGENCE_STEPS)}
    for name in ("forced_large", "free_large"):
        run = runs[name]
        exact = L.solve_exact(osc, run["t_end"], x0=run["x0"], force=run["force"])
        rows = [_compare(osc, dt, run, exact) for dt in CONVERGENCE_STEPS]
        table = {key: [r[key] for r in rows] for key in rows[0]}
        table["order_x"] = _order(list(CONVERGENCE_STEPS), table["max_x"])
        table["order_v"] = _order(list(CONVERGENCE_STEPS), table["max_v"])
        table["order_int_F_d"] = _order(list(CONVERGENCE_STEPS), table["int_F_d"])
        out[name] = table
    return out


def _creep(osc: L.Oscillator, x0: float, eps: float) -> dict[str, float]:
    """Regularised model released at rest inside the band, run to ``TEXTBOOK_T_END``.

    Returns the state at the end (the creep velocity ``v_end`` at ``x_end``),
    the distance crept, and the small-displacement creep rate ``-k eps/tau``
    (1/s) of the linearised law ``v = -k x eps / mu_s N_f``.
    """
    model = textbook.TextbookModel(osc, eps=eps)
    run = textbook.integrate_adaptive(
        model, TEXTBOOK_T_END, x0=x0, method="Radau", rtol=1e-10, atol=1e-14,
        max_nfev=1_000_000, max_seconds=1e9,
    )  # fmt: skip
    if not run.finished:
        raise RuntimeError(run.message)
    return {
        "eps": eps,
        "x_end": float(run.x[-1]),
        "v_end": float(run.v[-1]),
        "drift": float(x0 - run.x[-1]),
        "linear_rate": -osc.stiffness * eps / osc.threshold if osc.threshold > 0 else -math.inf,
    }


def _textbook(osc: L.Oscillator, x0: float) -> dict[str, Any]:
    model = textbook.TextbookModel(osc)
    euler = textbook.integrate_fixed(model, TEXTBOOK_T_END, TEXTBOOK_DT, x0=x0, scheme="euler")
    rk45 = textbook.integrate_adaptive(
        model, TEXTBOOK_T_END, x0=x0, method="RK45", rtol=RK45_RTOL, atol=RK45_ATOL,
        max_nfev=RK45_BUDGET, max_seconds=1e9,
    )  # fmt: skip
    return {
        "x0": x0,
        "t_end": TEXTBOOK_T_END,
        "euler_dt": TEXTBOOK_DT,
        "euler_steps": int(euler.t.size - 1),
        "euler_sign_changes": euler.sign_changes,
        "euler_max_v": float(np.max(np.abs(euler.v))),
        "euler_x_end": float(euler.x[-1]),
        "rk45_rtol": RK45_RTOL,
        "rk45_atol": RK45_ATOL,
        "rk45_budget": RK45_BUDGET,
        "rk45_finished": rk45.finished,
        "rk45_nfev": rk45.nfev,
        "rk45_t_reached": rk45.t_reached,
        "rk45_median_step": rk45.median_step,
        "tanh": [_creep(osc, x0, eps) for eps in TANH_EPS],
    }


def compute(cfg: dict[str, Any] | None = None) -> dict[str, Any]:
    """All numbers of the article, as a JSON-ready dictionary."""
    cfg = cfg if cfg is not None else lumped.config.load()
    osc, dt = examples.oscillator(cfg), float(cfg["dt"])
    runs = {name: dict(t_end=e.t_end, x0=e.x0, force=e.force) for name, e in examples.paper(cfg).items()}
    out: dict[str, Any] = {
        "parameters": {
            "m": osc.mass,
            "k": osc.stiffness,
            "tau": osc.threshold,
            "gamma": float(cfg["gamma"]),
            "dt": dt,
            "band": osc.static_band,
            "omega_over_pi": cfg["force_omega_over_pi"],
            "force_until": cfg["force_until"],
            "P_small": cfg["force_amplitude_small"],
            "P_large": cfg["force_amplitude_large"],
            "t_end_forced": cfg["t_end_forced"],
            "t_end_small": cfg["t_end_small"],
            "t_end_large": cfg["t_end_large"],
            "x0_small": cfg["x0_small"],
            "x0_large": cfg["x0_large"],
        }
    }
    for name, run in runs.items():
        out[name] = _example(osc, dt, run)
    out["forced_small"]["eq19"] = _forced_small_extra(osc, dt, runs["forced_small"])
    out["convergence"] = _convergence(osc, runs)
    out["textbook"] = _textbook(osc, cfg["x0_small"])
    return _clean(out)


def _clean(value: Any) -> Any:
    """NaN to None and infinities to "inf"/"-inf" (strict JSON); numpy scalars to Python numbers."""
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        if math.isnan(value):
            return None
        return float(value) if math.isfinite(value) else ("inf" if value > 0 else "-inf")
    return value


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 1:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    target = Path(args[0])
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(compute(), indent=1, sort_keys=True, allow_nan=False) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
