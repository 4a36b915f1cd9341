"""One-sided derivatives of an exact one-mass solution where its event sequence changes with a parameter.

Where a parameter ``p`` moves the solution across a change of its event
sequence (a stop at the band's edge that turns into a reversal, a breakaway
where the force only touches the band, a half-cycle gained or lost after
the load goes off: :attr:`~lumped.solvers.sensitivities.EventSensitivity.margin`
near 0), the motion at a time, the stop times, the rest time and the rest
position are not differentiable in ``p``: they have a kink, or they jump.
:func:`one_sided` solves the problem again at ``p - delta`` and ``p +
delta`` (``delta`` tiny: :data:`STEP` of the parameter's scale),
differentiates each side by the chain
(:func:`~lumped.solvers.sensitivities.sensitivities`) and reports both
sides' derivatives, their event sequences, and the jumps between them.
:func:`moved` (one parameter of a one-mass problem moved) is shared with the
steady amplitude's one-sided values (:mod:`lumped.drivers.steady_sensitivity`).

Notes
-----
On each side of the change, the event sequence holds over an interval of
``p`` that ends at the change, and there the summaries are smooth: their
derivatives are continuous up to the change.  So a side's derivative at
``p +- delta`` is the one-sided derivative at ``p`` to first order in
``delta`` (``delta |S''|``) when the change lies within ``delta`` of ``p``.
When it does not, both sides have the same event sequence
(:attr:`OneSided.same_events`) and agree to that order: the summary is
differentiable at ``p``.  The jump of a summary ``S`` is
``S(p + delta) - S(p - delta) - delta (S'_+ + S'_-)``, exact to second
order in ``delta``, plus the solver's round-off.  For the free decay's rest,
:class:`~lumped.solvers.sensitivities.RestSwitch` gives the other side in
closed form instead.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.solvers.exact import ExactSolution, solve_exact
from lumped.solvers.sensitivities import PARAMETER_NAMES, Sensitivities, sensitivities

__all__ = ["STEP", "OneSided", "Problem", "moved", "one_sided"]

#: ``delta`` relative to the parameter's scale: far above the solver's round-off (1e-15 of the scales, so
#: each side's event sequence is the one of its side), far below any scale of the motion (so each side's
#: derivative is the one-sided one to 1e-9 of it).
STEP = 1e-9


class Problem(NamedTuple):
    """A one-mass problem: a Bingham or Coulomb oscillator, the sine, the initial state."""

    oscillator: Oscillator
    force: SwitchedSine
    x0: float
    v0: float

    @classmethod
    def of(cls, solution: ExactSolution) -> Problem:
        return cls(solution.oscillator, solution.force, solution.x0, solution.v0)

    def value(self, name: str) -> float:
        """The parameter ``name`` (a name of :data:`~lumped.solvers.sensitivities.PARAMETER_NAMES`)."""
        osc, force = self.oscillator, self.force
        form = osc.dashpot.bingham_form()
        gamma = math.inf if form.viscosity == 0 else 1.0 / form.viscosity
        values = {"mass": osc.mass, "stiffness": osc.stiffness, "threshold": form.threshold, "gamma": gamma}
        values |= {"viscosity": form.viscosity, "x0": self.x0, "v0": self.v0}
        values |= {f"force_{key}": getattr(force, key) for key in ("amplitude", "omega", "phase", "until")}
        return float(values[name])

    def scale(self, name: str) -> float:
        """The parameter's own size, or where it is 0 a scale of the motion for it (what ``delta`` is relative to)."""
        if (value := abs(self.value(name))) > 0:
            return value
        osc = self.oscillator
        length = max(osc.dashpot.bingham_form().threshold, abs(self.force.amplitude), osc.stiffness * abs(self.x0))
        length = length / osc.stiffness if length > 0 else 1.0
        return {"v0": length * math.sqrt(osc.stiffness / osc.mass), "x0": length}.get(name, 1.0)


def moved(problem: Problem, name: str, delta: float) -> Problem:
    """``problem`` with the parameter ``name`` moved by ``delta``; ``ValueError`` where it cannot move so."""
    value = problem.value(name) + delta
    if not math.isfinite(value):
        raise ValueError(f"{name}: {problem.value(name)!r} has no neighbouring values; it cannot move")
    if name.startswith("force_"):
        force = dataclasses.replace(problem.force, **{name[len("force_") :]: value})
        return problem._replace(force=force)
    if name in ("x0", "v0"):
        return problem._replace(**{name: value})
    osc = problem.oscillator
    form = osc.dashpot.bingham_form()
    p = {"mass": osc.mass, "stiffness": osc.stiffness, "threshold": form.threshold}
    p["gamma"] = math.inf if form.viscosity == 0 else 1.0 / form.viscosity
    if name == "viscosity":
        if value < 0:
            raise ValueError("viscosity: c = 0 is the edge of its range; it has no side below")
        p["gamma"] = math.inf if value == 0 else 1.0 / value
    else:
        p[name] = value
    return problem._replace(oscillator=Oscillator.bingham(p["mass"], p["stiffness"], p["threshold"], p["gamma"]))


@dataclass(frozen=True)
class OneSided:
    """The derivatives in one parameter on each side of its value (module Notes).

    Attributes
    ----------
    parameter : str
    delta : float
        The distance of each side from the value, in the parameter's units.
    below, above : Sensitivities
        The derivatives (one column) of the solutions at ``p - delta`` and ``p + delta``: the one-sided
        derivatives from below and from above; their ``events`` are each side's own.
    same_events : bool
        True when both sides have the same event sequence: the solution is differentiable at ``p``.
    x_jump : ndarray, (n,), m
        Jump of ``x`` at the times ``t``.
    rest_time_jump, rest_position_jump : float, s and m
        Jumps of the rest time and position (``nan`` without a rest on either side).
    """

    parameter: str
    delta: float
    below: Sensitivities
    above: Sensitivities
    same_events: bool
    x_jump: np.ndarray
    rest_time_jump: float
    rest_position_jump: float


def one_sided(
    solution: ExactSolution,
    parameters: Sequence[str],
    t: np.ndarray | Sequence[float] = (),
    step: float = STEP,
) -> tuple[OneSided, ...]:
    """The one-sided derivatives of ``solution`` in each of ``parameters``, and the jumps (module Notes).

    Parameters
    ----------
    solution : ExactSolution
        From :func:`~lumped.solvers.exact.solve_exact`.
    parameters : sequence of str
        Names from :data:`~lumped.solvers.sensitivities.PARAMETER_NAMES`.
    t : array_like, (n,), s
        Times in ``[0, t_end]`` for the motion's derivatives.
    step : float
        ``delta`` relative to each parameter's scale (:meth:`Problem.scale`), in ``(0, 1e-3]``.

    Raises
    ------
    ValueError
        An unknown parameter, one that cannot move (``gamma = inf``, ``force_until = inf``, ``viscosity``
        below 0), a bad step, or what :func:`~lumped.solvers.sensitivities.sensitivities` refuses.
    """
    if not isinstance(solution, ExactSolution):
        raise ValueError(f"solution must be an ExactSolution, got {type(solution).__name__}")  # noqa: TRY004 (the API's one error type)
    if not 0 < step <= 1e-3:
        raise ValueError(f"step must lie in (0, 1e-3], got {step!r}")
    for name in parameters:
        if name not in PARAMETER_NAMES:
            raise ValueError(f"parameters: unknown parameter {name!r}; expected some of {', '.join(PARAMETER_NAMES)}")
    problem = Problem.of(solution)
    return tuple(_sides(solution, problem, name, t, step * problem.scale(name)) for name in parameters)


def _solve(problem: Problem, t_end: float, max_events: int) -> ExactSolution:
    osc, force, x0, v0 = problem
    return solve_exact(osc, t_end, x0=x0, v0=v0, force=force, max_events=max_events)


def _sides(solution: ExactSolution, problem: Problem, name: str, t, delta: float) -> OneSided:
    """:class:`OneSided` of ``name`` from the solutions at ``p -+ delta``."""
    runs = [_solve(moved(problem, name, d), solution.t_end, solution.max_events) for d in (-delta, delta)]
    below, above = (sensitivities(run, t, [name]) for run in runs)
    kinds = [[e.kind for e in run.events] for run in runs]
    x = [run.evaluate(below.t)["x"] if below.t.size else np.zeros(0) for run in runs]
    x_jump = x[1] - x[0] - delta * (below.x[:, 0] + above.x[:, 0])
    rest = [np.array([run.rest_time, run.rest_position]) for run in runs]
    slopes = np.array([below.rest_time[0] + above.rest_time[0], below.rest_position[0] + above.rest_position[0]])
    jumps = rest[1] - rest[0] - delta * slopes
    return OneSided(name, delta, below, above, kinds[0] == kinds[1], x_jump, float(jumps[0]), float(jumps[1]))
