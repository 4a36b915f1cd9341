"""The time grid ``t_n = n*dt`` that the fixed-step schemes ``theta``, ``moreau-jean`` and ``event-locating`` share.

They march on Algorithm 1's grid and return a
:class:`~lumped.model.trajectory.Trajectory` there; before they march,
:func:`start_run` checks their common arguments, the size of the output and
a bound on the run time.  :func:`march` is the loop of the two one-step
schemes (``theta``, ``moreau-jean``): the load tabulated on the grid, one
step per grid point, the rows saved and the rest's start kept.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from lumped.model.forcing import as_sine, check_span, evaluate
from lumped.model.oscillator import Oscillator, check_magnitudes, initial_dashpot_force
from lumped.model.trajectory import COLUMNS, Trajectory
from lumped.numerics import validate
from lumped.solvers.backward_euler import _seconds_per_step

__all__ = ["Step", "march", "start_run"]

#: One step of a scheme: ``(F_s, v, F_d, F_n, F_{n+1})`` at ``t_n`` -> ``(F_s, v, F_d)`` at ``t_{n+1}``.
Step = Callable[[float, float, float, float, float], tuple[float, float, float]]

#: Cost of one step relative to Algorithm 1's Python loop, for the run-time
#: bound: measured 2.6 (theta) and 3.0 (event-locating) on the free decay
#: (measured with benchmarks/bench_accuracy.py --table), with a margin.
_COST_OVER_PYTHON_BE = 5.0


def start_run(
    osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, save_every: int, kind: str, force: object
) -> tuple:
    """Validate the common arguments; return ``(t_end, dt, x0, v0, save_every, n_steps)``."""
    if not isinstance(osc, Oscillator):
        raise ValueError(f"oscillator must be an Oscillator, got {type(osc).__name__}")
    t_end, dt, save_every, n_steps = validate.grid(t_end, dt, save_every)
    x0, v0 = validate.finite("x0", x0), validate.finite("v0", v0)
    check_span(force, n_steps * dt)  # a sine's range, to the grid's last time
    validate.output_size(n_steps, save_every)
    per_step = _COST_OVER_PYTHON_BE * _seconds_per_step(osc, None, "python", dt)  # law's cost measured there
    validate.run_time(n_steps, per_step, f"the {kind} scheme")
    return t_end, dt, x0, v0, save_every, n_steps


def march(osc: Oscillator, step: Step, run: tuple, force: object, method: str, what: str) -> Trajectory:
    """March ``step`` on the grid of ``run`` (what :func:`start_run` returns) under ``force`` (validated).

    The run's magnitudes are checked first; row 0 is the initial state with the dashpot force the law gives
    there, and a row is kept every ``save_every`` steps and at the end.  The trajectory's ``method`` is
    ``method``, its ``rest_time`` the first grid point of the final run of ``v == 0``; a step that overflows
    raises ``ValueError`` naming ``what`` (``the θ-method``) and the step.
    """
    t_end, dt, x0, v0, save_every, n_steps = run
    sine = as_sine(force)
    check_magnitudes(osc, t_end, dt, x0, v0, sine.amplitude if sine is not None else 0.0)
    stride = min(save_every, n_steps + 1)
    out = np.empty((validate.output_rows(n_steps, stride), len(COLUMNS)))
    f0 = float(evaluate(force, np.zeros(1))[0])  # type: ignore[arg-type]
    k = osc.spring.stiffness
    out[0] = (0.0, x0, v0, k * x0, initial_dashpot_force(osc, f0, x0, v0), f0)
    f_s, v, f_d, f_now = out[0, 3], out[0, 2], out[0, 4], out[0, 5]
    row, rest_start = 1, 0 if v == 0 else 1
    for first in range(1, n_steps + 1, 1 << 16):
        table = evaluate(force, np.arange(first, min(first + (1 << 16), n_steps + 1)) * dt)  # type: ignore[arg-type]
        for n, f_next in enumerate(table.tolist(), start=first):
            f_s, v, f_d = step(f_s, v, f_d, f_now, f_next)
            f_now = f_next
            if not (math.isfinite(f_s) and math.isfinite(v) and math.isfinite(f_d)):
                raise ValueError(f"{what} overflowed at t = {n * dt:.6g} s (step {n})")
            rest_start = n + 1 if v != 0.0 else rest_start
            if n % stride == 0 or n == n_steps:
                out[row] = (n * dt, f_s / k, v, f_s, f_d, f_next)
                row += 1
    final = (rest_start * dt, float(out[-1, 1])) if out[-1, 2] == 0 else (math.nan, math.nan)
    return Trajectory.from_array(out, osc, method=method, dt=dt, save_every=save_every, final_rest=final)
