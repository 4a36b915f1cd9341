"""The runs behind the article's numbers: the original's four runs summarised, and the convergence study.

* :func:`paper_run`: one run of the original's section 3, by the exact
  solution and by Algorithm 1 at the configured and at the original's step,
  with their differences;
* :func:`eq19`: Figure 5's run against eq. (19);
* :func:`rest_sweep`: where the large free vibration rests, released from a
  row of positions (:data:`SWEEP_POINTS`, :data:`SWEEP_SPACING`);
* :func:`friction_oscillator_ends`: how Siconos' FrictionOscillator ends, by
  the exact solution, Algorithm 1 and Moreau-Jean at Siconos' step;
* :func:`convergence`: the differences for each step of
  :data:`CONVERGENCE_STEPS`, their fitted orders, and how each run ends.

A run not at rest by its end time has :data:`STILL_MOVING` as rest time and
position.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from lumped.drivers.methods import METHODS
from lumped.model.oscillator import Oscillator
from lumped.model.trajectory import Trajectory, sign_changes
from lumped.solvers.exact import ExactSolution, solve_exact
from lumped.studies import examples
from lumped.studies.accuracy.friction_oscillator import FRICTION_OSCILLATOR

__all__ = [
    "CONVERGENCE_STEPS",
    "CURVES",
    "ORIGINAL_DT",
    "QUANTITIES",
    "STILL_MOVING",
    "SWEEP_POINTS",
    "SWEEP_SPACING",
    "convergence",
    "eq19",
    "friction_oscillator_ends",
    "law_violations",
    "motion_end",
    "paper_run",
    "rest_sweep",
    "same_side",
]

#: The original's step (s).
ORIGINAL_DT = examples.ORIGINAL_DT
#: Steps of the convergence study (s); the original's is 1e-4.
CONVERGENCE_STEPS = (1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5)
#: Rest time and rest position of a run still moving at its end time.
STILL_MOVING = "still moving"
#: The quantity each time-history figure shows, per run.
CURVES = {"forced_large": (6, 7, 8, 9), "free_large": (11, 12, 13, 14)}
QUANTITIES = ("x", "v", "F_s", "F_d")
#: Release positions of :func:`rest_sweep`: ``x0`` and this many more, towards zero.
SWEEP_POINTS = 40
#: Their spacing, as a fraction of the band half-width ``mu_s N_f / k``.  A
#: free motion from rest is non-expansive in the energy norm, so two rests lie
#: no farther apart than their releases: neighbouring rests of the sweep are at
#: most half a band half-width apart, and every value between two of them is
#: the rest of some release in between (the rest is continuous in ``x0``).
SWEEP_SPACING = 0.5


def _rest(value: float) -> float | str:
    """A rest time or position, or STILL_MOVING where the trajectory gives ``nan``."""
    return STILL_MOVING if math.isnan(value) else value


def motion_end(be: Trajectory, ref: Trajectory) -> float:
    """The end of the motion: the later of the two stops (s), or the end of the run if either still moves.

    ``ref`` is the exact solution sampled on the grid, whose rest time is the
    exact stop (not a grid time).

    Every difference measured up to this time is independent of the run's
    end time once both solutions are at rest; after it both hold their rest
    states, whose difference is measured separately (``rest_position``).
    """
    stops = (be.rest_time, ref.rest_time)
    return float(be.t[-1]) if any(math.isnan(s) for s in stops) else float(max(stops))


def _integral(values: np.ndarray, t: np.ndarray, until: float, dt: float) -> float:
    """Right-endpoint rule for the integral of ``values`` over ``(0, until]`` on the grid ``t``.

    ``until`` is a grid time (Algorithm 1's stop) or an exact event time; a
    millionth of a step of slack keeps a grid time from being lost to the
    round-off of ``t``.
    """
    return float(np.sum(values[1:][t[1:] <= until + 1e-6 * dt]) * dt)


def _deviation(be: Trajectory, ref: Trajectory) -> dict[str, float]:
    """Largest absolute differences over the run, column by column, and the rest-state differences.

    The largest differences over the run are those of the motion: after the
    later stop both solutions hold their rest states, whose difference the
    motion's last point already shows.  ``int_F_d`` is the time integral of
    ``|F_d - F_d,exact|`` (N s) up to :func:`motion_end`: the largest
    difference in ``F_d`` is the jump ``2 mu_s N_f`` seen at a grid point
    between a reversal of the exact motion and that of Algorithm 1, so it
    does not shrink with the step, while the integral does; it stops at the
    end of the motion so that the held force of the rest state, which differs
    by ``k |Delta x_rest|``, does not accumulate into it for as long as the
    run happens to last.
    """
    out = {f"max_{c}": float(np.max(np.abs(getattr(be, c) - getattr(ref, c)))) for c in QUANTITIES}
    out["motion_end"] = motion_end(be, ref)
    out["int_F_d"] = _integral(np.abs(be.F_d - ref.F_d), be.t, out["motion_end"], be.dt)
    out["rest_position"] = abs(be.rest_position - ref.rest_position)
    out["rest_time"] = abs(be.rest_time - ref.rest_time)
    return out


def _exact_summary(ex: ExactSolution, sampled: Trajectory) -> dict[str, Any]:
    kinds = [e.kind for e in ex.events]
    moving = [e for e in ex.events if e.kind in ("breakaway", "reversal", "stop")]
    return {
        "rest_time": _rest(ex.rest_time),
        "rest_position": _rest(ex.rest_position),
        "reversals": kinds.count("reversal"),
        "breakaways": kinds.count("breakaway"),
        "first_event_time": moving[0].time if moving else math.nan,
        "reversal_times": [e.time for e in ex.events if e.kind == "reversal"],
        "reversal_positions": [e.x[0] for e in ex.events if e.kind == "reversal"],
        "peak_x": float(np.max(np.abs(sampled.x))),
        "peak_v": float(np.max(np.abs(sampled.v))),
        "peak_F_d": float(np.max(np.abs(sampled.F_d))),
        "int_abs_F_d": _integral(np.abs(sampled.F_d), sampled.t, _motion_of(ex, sampled), sampled.dt),
    } | _end_forces(sampled)


def _end_forces(tr: Trajectory) -> dict[str, Any]:
    """The forces at the last grid point, and the grid points off the graph of eq. (6)."""
    return {
        "end_F_s": float(tr.F_s[-1]),
        "end_F_d": float(tr.F_d[-1]),
        "law_violations": law_violations(tr.v, tr.F_d, tr.oscillator.threshold),
    }


def law_violations(v: np.ndarray, f_d: np.ndarray, tau: float) -> int:
    """Grid points where ``(v, F_d)`` is off the graph of eq. (6): ``|F_d| > tau`` at ``v = 0``, or ``F_d``
    of the other sign than ``v != 0``.

    Neither test involves round-off: a stick step stores a force whose
    magnitude it compared with ``tau``, and a slip force is at least ``tau``
    from zero.
    """
    stuck = v == 0.0
    off_band = np.count_nonzero(stuck & (np.abs(f_d) > tau))
    return int(off_band + np.count_nonzero(~stuck & (np.sign(f_d) != np.sign(v))))


def _turning_positions(x: np.ndarray, v: np.ndarray) -> list[float]:
    """``x`` at the grid point before each change of direction (the first point moving the new way)."""
    moving = np.flatnonzero(v != 0.0)
    turns = np.flatnonzero(np.diff(np.sign(v[moving])) != 0)
    return [float(x[i]) for i in moving[turns + 1] - 1]


def _motion_of(ex: ExactSolution, sampled: Trajectory) -> float:
    """The end of the exact motion (s): its stop, or the end of the run if it still moves."""
    return float(sampled.t[-1]) if math.isnan(ex.rest_time) else float(ex.rest_time)


def _be_summary(be: Trajectory) -> dict[str, Any]:
    return {
        "dt": be.dt,
        "rest_time": _rest(be.rest_time),
        "rest_position": _rest(be.rest_position),
        "peak_x": float(np.max(np.abs(be.x))),
        "peak_v": float(np.max(np.abs(be.v))),
        "min_F_d": float(np.min(be.F_d)),
        "max_F_d": float(np.max(be.F_d)),
        "stick_fraction": float(np.mean(be.v == 0.0)),
        "reversals": sign_changes(be.v),
        "first_move_time": float(be.t[np.argmax(be.v != 0.0)]) if np.any(be.v != 0.0) else math.nan,
        "turning_positions": _turning_positions(be.x, be.v),
        "energy_residual": float(np.max(np.abs(be.energy_balance().residual))),
        "steps": int(be.t.size - 1),
    } | _end_forces(be)


def paper_run(run: examples.Example) -> dict[str, Any]:
    """Exact solution, and Algorithm 1 at the configured and the original's step."""
    exact = run.exact()
    out: dict[str, Any] = {"exact": _exact_summary(exact, exact.sample(run.dt))}
    for suffix, dt in (("", run.dt), ("_original", ORIGINAL_DT)):
        be = run.algorithm1(dt)
        out["be" + suffix], out["error" + suffix] = _be_summary(be), _deviation(be, exact.sample(dt))
    return out


def eq19(run: examples.Example, dt: float) -> dict[str, float]:
    """Figure 5 against eq. (19): F_d = F_1, and x = v = F_s = 0."""
    be = run.algorithm1(dt)
    return {
        "max_F1": float(np.max(np.abs(be.F))),
        "eq19_max_F_d": float(np.max(np.abs(be.F_d - be.F))),
        "eq19_max_x": float(np.max(np.abs(be.x))),
        "eq19_max_v": float(np.max(np.abs(be.v))),
        "eq19_max_F_s": float(np.max(np.abs(be.F_s))),
    }


def rest_sweep(run: examples.Example, dt: float, spacing: float = SWEEP_SPACING) -> dict[str, Any]:
    """Rest positions from releases at rest at ``x0 - j spacing mu_s N_f / k`` (``j = 0 ..`` :data:`SWEEP_POINTS`).

    Only releases outside the band (``|x0| > mu_s N_f / k``, where the mass
    moves) and of the same sign as ``x0`` are kept; each is run by the exact
    solution and by Algorithm 1 at ``dt`` to the run's end time.  A smaller
    release makes no more half-cycles, so each comes to rest no later than the
    run itself.
    """
    band = run.oscillator.static_band
    releases = [run.x0 - math.copysign(j * spacing * band, run.x0) for j in range(SWEEP_POINTS + 1)]
    releases = [x0 for x0 in releases if abs(x0) > band and x0 * run.x0 > 0]
    moved = [dataclasses.replace(run, x0=x0) for x0 in releases]
    return {
        "x0": releases,
        "spacing": spacing * band,
        "exact": [_rest(r.exact().rest_position) for r in moved],
        "algorithm1": [_rest(r.algorithm1(dt).rest_position) for r in moved],
    }


def friction_oscillator_ends() -> dict[str, Any]:
    """Siconos' FrictionOscillator (:data:`~lumped.studies.accuracy.friction_oscillator.FRICTION_OSCILLATOR`):
    rest time (s), rest position (m) and reversals, exact and by Algorithm 1 and Moreau-Jean at Siconos' step."""
    p = FRICTION_OSCILLATOR
    osc = Oscillator.bingham(p["mass"], p["stiffness"], p["bound"], math.inf)
    ex = solve_exact(osc, p["t_end"], x0=p["x0"], v0=p["v0"])
    kinds = [e.kind for e in ex.events]
    out: dict[str, Any] = {"case": dict(p)}
    out["exact"] = {"rest_time": _rest(ex.rest_time), "rest_position": _rest(ex.rest_position)}
    out["exact"]["reversals"] = kinds.count("reversal")
    for name in ("backward-euler", "moreau-jean"):
        tr = METHODS[name](osc, p["t_end"], p["dt"], p["x0"], p["v0"], None, 1)
        out[name] = {"rest_time": _rest(tr.rest_time), "rest_position": _rest(tr.rest_position)}
        out[name]["reversals"] = sign_changes(tr.v)
    return out


# ------------------------------------------------------------------ convergence
def _order(steps: list[float], errors: list[float]) -> float:
    """Least-squares slope of log(error) against log(step); ``nan`` unless every error is > 0."""
    if not all(e > 0 and math.isfinite(e) for e in errors):
        return math.nan  # a zero error (exact at that step) or a run still moving
    return float(np.polyfit(np.log(steps), np.log(errors), 1)[0])


def convergence(runs: dict[str, examples.Example]) -> tuple[dict[str, Any], dict[str, Any]]:
    """Differences from the exact solution for each step, and how each run ends."""
    steps = list(CONVERGENCE_STEPS)
    table: dict[str, Any] = {"steps": steps}
    ends: dict[str, Any] = {"steps": steps}
    for name in CURVES:
        exact = runs[name].exact()
        trajectories = [runs[name].algorithm1(dt) for dt in steps]
        rows = [_deviation(be, exact.sample(be.dt)) for be in trajectories]
        table[name] = {key: [r[key] for r in rows] for key in rows[0]}
        for col, key in (("x", "max_x"), ("v", "max_v"), ("int_F_d", "int_F_d")):
            table[name][f"order_{col}"] = _order(steps, table[name][key])
        ends[name] = _ends(trajectories, exact)
    return table, ends


def _ends(trajectories: list[Trajectory], exact: ExactSolution) -> dict[str, Any]:
    """Rest position and reversals of each run, and the steps at which it ends differently."""
    n_exact = [e.kind for e in exact.events].count("reversal")
    same = [same_side(be.rest_position, exact.rest_position) for be in trajectories]
    reversals = [sign_changes(be.v) for be in trajectories]
    return {
        "rest_position": [_rest(be.rest_position) for be in trajectories],
        "reversals": reversals,
        "same_side": same,
        "fewer_reversals": [be.dt for be, n in zip(trajectories, reversals) if n < n_exact],
        "other_side": [be.dt for be, s in zip(trajectories, same) if s is False],
    }


def same_side(x: float, x_exact: float) -> bool | None:
    """Whether two rest positions lie on the same side of zero; ``None`` if either is missing."""
    if math.isnan(x) or math.isnan(x_exact):
        return None
    return bool(np.sign(x) == np.sign(x_exact))
