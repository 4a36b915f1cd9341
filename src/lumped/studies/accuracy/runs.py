"""One run of the work-precision study: one method on one case at one resolution, and its errors.

* :class:`Result`: the four errors and the work of a run (their definitions
  are in :mod:`lumped.studies.accuracy`);
* :func:`run`: runs a method of :data:`~lumped.studies.accuracy.methods.STUDY_METHODS`
  on a case and measures it against the case's reference.

How a run is measured depends on its method's group
(:mod:`lumped.studies.accuracy.methods`): a fixed-step scheme on its grid, a
toleranced method on :data:`SAMPLE_DT`, a closed form as the reference it is,
the ``tanh`` model on ``solve_ivp``'s accepted steps.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from lumped.drivers.methods import METHODS
from lumped.model.trajectory import Trajectory
from lumped.numerics import validate
from lumped.solvers import textbook
from lumped.solvers.events import Event
from lumped.studies.accuracy.cases import CASE_NAMES, Case, Reference, cases, reference
from lumped.studies.accuracy.events import KINDS, grid_events, match_events
from lumped.studies.accuracy.methods import CLOSED_FORM, SCHEMES, STUDY_METHODS, TANH, TOLERANCED

__all__ = ["SAMPLE_DT", "Result", "compared_final", "run"]

#: Grid (s) on which the event-driven method and its reference are compared.
SAMPLE_DT = 1e-3
#: Absolute over relative tolerance of ``solve_ivp`` on the tanh model (m, m/s per unit rtol).
TANH_ATOL_FACTOR = 1e-3
#: Step budget of one ``solve_ivp`` run on the tanh model (right-hand-side evaluations).
TANH_MAX_NFEV = 2_000_000


@dataclass(frozen=True)
class Result:
    """One method on one case at one resolution (see :mod:`lumped.studies.accuracy` for the errors).

    Attributes
    ----------
    case, method : str
    resolution : float
        ``dt`` (s) for the fixed-step schemes and ``exact``; ``rtol`` for the
        event-driven method and for ``tanh``.
    eps : float
        The ``tanh`` scale (m/s); ``nan`` for the other methods.
    position_error, rest_time_error, max_x_error : float
        m, s, m; ``nan`` where not defined (a run still moving at the end
        of a ``"rest"`` case, or the rest time of an ``"end"`` case).
    event_errors : dict
        :func:`~lumped.studies.accuracy.events.match_events`'s output.
    reference_position : float
        The reference's final position (m), for relative errors.
    work : int
        Steps (:mod:`lumped.studies.accuracy`).
    wall_time : float
        Best of ``repeats`` runs (s); ``nan`` when not timed.
    """

    case: str
    method: str
    resolution: float
    eps: float
    position_error: float
    rest_time_error: float
    max_x_error: float
    event_errors: dict[str, float]
    reference_position: float
    work: int
    wall_time: float = math.nan

    @property
    def relative_position_error(self) -> float:
        """``position_error / |reference position|``."""
        return self.position_error / abs(self.reference_position)


class _Outcome(NamedTuple):
    """What a method run gives the error computation."""

    final: tuple[float, float]  # (rest time or nan, final position)
    max_x: float
    events: tuple[Event, ...] | None  # None: not compared (tanh)
    work: int


def compared_final(case: Case, rest: tuple[float, float], x_end: float) -> tuple[float, float]:
    """``(rest time, position)`` compared for the case: the rest, or ``(nan, x(t_end))`` for ``"end"``."""
    return (math.nan, x_end) if case.final == "end" else rest


def _t_off(case: Case) -> float | None:
    f = case.force
    return None if f is None or f.is_zero or not f.until < case.t_end else f.until


def _scheme(case: Case, ref: Reference, method: str, dt: float) -> _Outcome:
    """A fixed-step scheme on the grid ``n dt``; events located by the scheme or read from the grid.

    A scheme that locates its events (event-locating dates its switches
    between grid points; its trajectory carries them) is compared on those;
    the others' events are read from the grid velocities.
    """
    traj = METHODS[method](case.oscillator, case.t_end, dt, case.x0, 0.0, case.force, 1)
    if traj.events:
        events = tuple(e for e in traj.events if e.kind in KINDS)
    else:
        events = grid_events(traj.t, traj.x, traj.v, _t_off(case))
    exact = ref.solution.sample(dt)
    final = compared_final(case, (traj.rest_time, traj.rest_position), float(traj.x[-1]))
    return _Outcome(final, float(np.max(np.abs(traj.x - exact.x))), events, int(traj.t.size - 1))


def _toleranced(case: Case, ref: Reference, method: str, rtol: float) -> _Outcome:
    """A method integrating to ``rtol`` (its solver in continuous time), compared on :data:`SAMPLE_DT`."""
    sol = METHODS[method].solution(case.oscillator, case.t_end, rtol=rtol, **case.kwargs())  # type: ignore[misc]
    on_grid: Trajectory = sol.sample(SAMPLE_DT)
    x_end = float(sol.evaluate(np.array([case.t_end]))["x"][0])
    max_x = float(np.max(np.abs(on_grid.x - ref.solution.sample(SAMPLE_DT).x)))
    events = tuple(e for e in sol.events if e.kind in KINDS)
    return _Outcome(compared_final(case, sol.rest_through(case.t_end), x_end), max_x, events, sol.steps)


def _closed_form(case: Case, ref: Reference, method: str) -> _Outcome:
    """A closed form: on the cases it runs it is the reference (:func:`reference`), and takes no steps."""
    sol = METHODS[method].solution(case.oscillator, case.t_end, **case.kwargs())  # type: ignore[misc]
    x_end = float(sol.evaluate(np.array([case.t_end]))["x"][0])
    return _Outcome(compared_final(case, sol.rest_through(case.t_end), x_end), 0.0, ref.events, 0)


def _tanh(case: Case, ref: Reference, rtol: float, eps: float) -> _Outcome:
    """LSODA on the ``tanh`` model: it never sticks, so its final position is ``x(t_end)``."""
    model = textbook.TextbookModel(case.oscillator, force=case.force, eps=eps)
    atol, budget = TANH_ATOL_FACTOR * rtol, TANH_MAX_NFEV
    out = textbook.integrate_adaptive(
        model, case.t_end, x0=case.x0, method="LSODA", rtol=rtol, atol=atol, max_nfev=budget, max_seconds=600.0
    )
    if not out.finished:
        raise ValueError(f"eps: the tanh model did not finish ({out.message})")
    max_x = float(np.max(np.abs(out.x - ref.solution.evaluate(out.t)["x"])))
    return _Outcome((math.nan, float(out.x[-1])), max_x, None, int(out.t.size - 1))


def _errors(case: Case, ref: Reference, outcome: _Outcome) -> dict[str, Any]:
    rest = ref.final(case.t_end)
    want = compared_final(case, rest, rest[1])  # at rest at t_end, the rest position is x(t_end)
    return {
        "position_error": abs(outcome.final[1] - want[1]),
        "rest_time_error": abs(outcome.final[0] - want[0]),
        "max_x_error": outcome.max_x,
        "event_errors": {} if outcome.events is None else match_events(outcome.events, ref.events),
        "reference_position": want[1],
    }


def _validated(case: Case | str, method: str, resolution: float, eps: float | None) -> tuple[Case, float, float]:
    """The case, resolution and eps checked against the method (one-line ``ValueError``)."""
    if isinstance(case, str):
        if case not in CASE_NAMES:
            raise ValueError(f"case must be one of {', '.join(CASE_NAMES)} or a Case; got {case!r}")
        case = cases()[case]
    if not isinstance(case, Case):
        raise ValueError(f"case must be a Case or a name, got {type(case).__name__}")
    if method not in STUDY_METHODS:
        raise ValueError(f"method must be one of {', '.join(STUDY_METHODS)}; got {method!r}")
    resolution = validate.positive("resolution", resolution)
    closed_form_only = method == TANH or (method in METHODS and METHODS[method].bingham_only)
    if closed_form_only and not case.closed_form:
        raise ValueError(f"method: {method!r} needs a Bingham or Coulomb law; case {case.name!r} has another")
    if (method == TANH) != (eps is not None):
        raise ValueError("eps: give it for method 'tanh' (the velocity scale, m/s), and only for it")
    return case, resolution, math.nan if eps is None else validate.positive("eps", eps)


def _outcome(case: Case, ref: Reference, method: str, resolution: float, eps: float) -> Callable[[], _Outcome]:
    """The run of ``method`` as a call without arguments (timed by :func:`run`), by its group."""
    if method in SCHEMES:
        return lambda: _scheme(case, ref, method, resolution)
    if method in TOLERANCED:
        return lambda: _toleranced(case, ref, method, resolution)
    if method in CLOSED_FORM:
        return lambda: _closed_form(case, ref, method)
    return lambda: _tanh(case, ref, resolution, eps)


def run(
    case: Case | str,
    method: str,
    resolution: float,
    *,
    eps: float | None = None,
    ref: Reference | None = None,
    repeats: int = 0,
) -> Result:
    """Run ``method`` on ``case`` at ``resolution`` and measure its errors against the reference.

    Parameters
    ----------
    case : Case or str
        A :class:`~lumped.studies.accuracy.cases.Case` or a name of
        :data:`~lumped.studies.accuracy.cases.CASE_NAMES`.
    method : str
        One of :data:`~lumped.studies.accuracy.methods.STUDY_METHODS`;
        ``exact`` and ``tanh`` need a Bingham or Coulomb law.
    resolution : float
        ``dt`` (s) for the fixed-step schemes (and ``exact``, unused);
        ``rtol`` for ``event-driven`` and ``tanh``.
    eps : float, m/s
        The ``tanh`` scale; only for ``tanh``.
    ref : Reference, optional
        The case's :func:`~lumped.studies.accuracy.cases.reference` (computed when not given).
    repeats : int
        Timed runs for ``wall_time`` (best of them); ``0`` times nothing.

    Returns
    -------
    Result
    """
    case, resolution, eps_value = _validated(case, method, resolution, eps)
    repeats = 0 if repeats == 0 else validate.positive_int("repeats", repeats)
    ref = reference(case) if ref is None else ref
    call = _outcome(case, ref, method, resolution, eps_value)
    outcome, best = call(), math.inf
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        best = min(best, time.perf_counter() - start)
    errors = _errors(case, ref, outcome)
    wall = best if repeats else math.nan
    return Result(case.name, method, resolution, eps_value, work=outcome.work, wall_time=wall, **errors)
