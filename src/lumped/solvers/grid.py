"""The time grid ``t_n = n*dt`` that the fixed-step schemes ``theta`` and ``event-capturing`` share.

Both march on Algorithm 1's grid and return a
:class:`~lumped.model.trajectory.Trajectory` there; before they march,
:func:`start_run` checks their common arguments, the size of the output and
a bound on the run time.
"""

from __future__ import annotations

from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.numerics import validate
from lumped.solvers.backward_euler import _seconds_per_step

__all__ = ["start_run"]

#: Cost of one step relative to Algorithm 1's Python loop, for the run-time
#: bound: measured 2.6 (theta) and 3.0 (event-capturing) on the free decay
#: (measured with benchmarks/bench_accuracy.py --table), with a margin.
_COST_OVER_PYTHON_BE = 5.0


def start_run(
    osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, save_every: int, kind: str, force: object
) -> tuple:
    """Validate the common arguments; return ``(t_end, dt, x0, v0, save_every, n_steps)``."""
    if not isinstance(osc, Oscillator):
        raise ValueError(f"oscillator must be an Oscillator, got {type(osc).__name__}")
    t_end, dt = validate.positive("t_end", t_end), validate.positive("dt", dt)
    x0, v0 = validate.finite("x0", x0), validate.finite("v0", v0)
    save_every = validate.stride("save_every", save_every)
    n_steps = validate.step_count(t_end, dt)
    if isinstance(force, SwitchedSine):
        force.check_span(n_steps * dt)  # the sine's range, to the grid's last time
    validate.output_size(n_steps, save_every)
    per_step = _COST_OVER_PYTHON_BE * _seconds_per_step(osc, None, "python", dt)  # law's cost measured there
    validate.run_time(n_steps, per_step, f"the {kind} scheme")
    return t_end, dt, x0, v0, save_every, n_steps
