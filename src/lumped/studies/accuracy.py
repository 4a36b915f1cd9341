"""The work-precision study: every method against a reference, case by case (issue 10, part 4).

One home for the study that notebook 09, ``benchmarks/bench_accuracy.py``,
the pipeline's ``results/accuracy/study.json`` and the article's accuracy
section share:

* :data:`CASE_NAMES` and :func:`cases`: the five motions, as data;
* :func:`reference`: the reference solution of a case (``exact`` for the
  Bingham and Coulomb laws, ``event-driven`` at its smallest tolerance for
  Herschel-Bulkley laws), with its events;
* :func:`run`: one method on one case at one resolution, a :class:`Result`
  with the four errors and the work;
* :func:`grid_events` and :func:`match_events`: the events of a grid
  trajectory and their pairing with the reference's;
* :func:`observed_orders` and :func:`order_table`: fitted orders per event
  type;
* :func:`study` and :func:`to_json`: the whole table, strict JSON.

The errors
----------
For a case whose mass comes to rest (``final = "rest"``), the *position
error* is the distance between the rest positions and the *rest-time
error* that between the rest times (``Trajectory.final_rest``, or
``ExactSolution.rest_through(t_end)``).  For a Herschel-Bulkley law with
``n < 1`` the mass may creep towards the band edge without stopping
(:mod:`lumped.solvers.event_driven`), so there ``final = "end"``: the position
error is that of ``x(t_end)`` and the rest time is not compared.  The
*largest displacement error* is ``max |x - x_ref|`` over the method's grid
(a grid of :data:`SAMPLE_DT` for the event-driven method, the accepted steps
for ``solve_ivp``).  The *event errors* are, per kind, the largest distance
in time between matched events (in displacement for ``forcing-off``, whose
time is given).  The ``tanh`` model never sticks: its "rest position" is
``x(t_end)`` compared with the reference's rest position, which is what a
user of that model would report.

Work
----
``work`` is a deterministic count of steps: grid steps for the fixed-step
schemes, integrator steps for the event-driven method (each 12 stages of
DOP853) and for ``solve_ivp`` (LSODA's accepted steps), and ``0`` for
``exact``.  ``wall_time`` is a measurement (best of ``repeats`` runs) and is
left out of :func:`to_json` unless asked, so that the pipeline's files do not
change between builds.
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import asdict, dataclass, field
from typing import Any, NamedTuple

import numpy as np

from lumped.drivers.simulation import METHODS
from lumped.laws import HerschelBulkleyDashpot, LinearSpring
from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.model.trajectory import Trajectory
from lumped.numerics import validate
from lumped.solvers import textbook
from lumped.solvers.event_capturing import event_capturing
from lumped.solvers.event_driven import RTOL_RANGE, solve_event_driven
from lumped.solvers.events import Event
from lumped.solvers.exact import ExactSolution, solve_exact
from lumped.studies import config, examples
from lumped.studies.replication import clean

__all__ = [
    "CASE_NAMES",
    "KINDS",
    "SCHEMES",
    "STUDY_METHODS",
    "Case",
    "Reference",
    "Result",
    "Study",
    "cases",
    "grid_events",
    "headline",
    "match_events",
    "observed_orders",
    "order_table",
    "reference",
    "run",
    "study",
    "to_json",
]

#: The event kinds compared, with the issue's names: stick to slip, slip to
#: stick, reversal, forcing switched off (``"rest"`` repeats a ``"stop"``).
KINDS: Mapping[str, str] = {
    "breakaway": "stick to slip",
    "stop": "slip to stick",
    "reversal": "reversal",
    "forcing-off": "forcing switched off",
}
#: The fixed-step schemes, whose errors are fitted against ``dt``.
SCHEMES = ("backward-euler", "event-capturing", "theta")
#: Every method of the study: the registry's, and ``solve_ivp`` (LSODA) on the ``tanh`` model.
STUDY_METHODS = (*SCHEMES, "event-driven", "exact", "tanh")
#: Grid (s) on which the event-driven method and its reference are compared.
SAMPLE_DT = 1e-3
#: Absolute over relative tolerance of ``solve_ivp`` on the tanh model (m, m/s per unit rtol).
TANH_ATOL_FACTOR = 1e-3
#: Step budget of one ``solve_ivp`` run on the tanh model (right-hand-side evaluations).
TANH_MAX_NFEV = 2_000_000
CASE_NAMES = ("free-decay", "forced-17b", "coulomb-17b", "hb-n0.5", "hb-n2")


@dataclass(frozen=True)
class Case:
    """One motion of the study.

    Attributes
    ----------
    name, title : str
        Key of :func:`cases` and a label for figures.
    oscillator : Oscillator
    t_end : float, s
    x0 : float, m
        Release position (released at rest).
    force : SwitchedSine or None
    final : {"rest", "end"}
        Which final position is compared (module docstring).
    """

    name: str
    title: str
    oscillator: Oscillator
    t_end: float
    x0: float = 0.0
    force: SwitchedSine | None = None
    final: str = "rest"

    @property
    def closed_form(self) -> bool:
        """Whether ``exact`` applies (a Bingham or Coulomb law)."""
        return self.oscillator.dashpot.bingham_form() is not None  # the law's contract, point 6

    def kwargs(self) -> dict[str, Any]:
        """``x0`` and ``force`` as the solvers take them."""
        return {"x0": self.x0, "force": self.force}


def _herschel_bulkley(n: float, x0: float) -> Oscillator:
    """m = 1 kg, k = 100 N/m, tau = 1 N, K = 1 N (s/m)^n."""
    return Oscillator(1.0, LinearSpring(100.0), HerschelBulkleyDashpot(1.0, 1.0, n))


def cases(cfg: dict[str, Any] | None = None) -> dict[str, Case]:
    """The five cases, keyed by :data:`CASE_NAMES`, with the paper's values from ``cfg``.

    ``cfg`` defaults to :func:`lumped.studies.config.default`, the repository's
    parameter file *without* ``--config`` overrides or ``$LUMPED_CONFIG``:
    the study compares methods on fixed cases, so what it says (which
    events occur, where each case rests) holds in every build.

    The free decay (Figures 11 to 14) and eq. (17b)'s forced case are
    :func:`lumped.studies.examples.paper`'s; Coulomb is the same system with
    ``gamma = inf`` under eq. (17b) (breakaway, reversals, forcing-off and
    stop in one run); the Herschel-Bulkley cases have ``tau = 1 N``,
    ``K = 1 N (s/m)^n``, ``n = 1/2`` and ``n = 2``, released at
    ``x0 = 0.5 m`` and run for 4 s.
    """
    runs = examples.paper(config.default() if cfg is None else cfg)
    free, forced = runs["free_large"], runs["forced_large"]
    osc = free.oscillator
    coulomb = Oscillator.bingham(osc.mass, osc.stiffness, osc.threshold, math.inf)
    return {
        "free-decay": Case("free-decay", "free decay (Figs 11-14)", osc, free.t_end, x0=free.x0),
        "forced-17b": Case("forced-17b", "forced, eq. (17b)", osc, forced.t_end, force=forced.force),
        "coulomb-17b": Case("coulomb-17b", "Coulomb, eq. (17b)", coulomb, forced.t_end, force=forced.force),
        "hb-n0.5": Case("hb-n0.5", "Herschel-Bulkley, n = 1/2", _herschel_bulkley(0.5, 0.5), 4.0, 0.5, final="end"),
        "hb-n2": Case("hb-n2", "Herschel-Bulkley, n = 2", _herschel_bulkley(2.0, 0.5), 4.0, 0.5),
    }


# ------------------------------------------------------------------ the reference
class Reference(NamedTuple):
    """A case's reference: the ``solution``, the ``method`` that made it, its compared ``events``."""

    solution: ExactSolution
    method: str
    events: tuple[Event, ...]

    def final(self, t: float) -> tuple[float, float]:
        """``(rest time, position)`` of the stick holding at ``t`` (s), or ``(nan, x(t))`` if moving."""
        rest = self.solution.extended(t).rest_through(t)
        if math.isnan(rest[0]):
            return (math.nan, float(self.solution.extended(t).evaluate(np.array([t]))["x"][0]))
        return rest


def reference(case: Case, rtol: float = RTOL_RANGE[0]) -> Reference:
    """``exact`` where it applies, else ``event-driven`` at ``rtol`` (default: the smallest DOP853 accepts).

    The event-driven reference's own accuracy is measured by
    ``tests/test_accuracy.py``: at this ``rtol`` it agrees with ``exact`` on
    the Bingham free decay, and changes by little from ``rtol = 1e-12``.
    """
    kw = case.kwargs()
    if case.closed_form:
        sol, method = solve_exact(case.oscillator, case.t_end, **kw), "exact"
    else:
        sol, method = solve_event_driven(case.oscillator, case.t_end, rtol=rtol, **kw), "event-driven"
    return Reference(sol, method, tuple(e for e in sol.events if e.kind in KINDS))


# ------------------------------------------------------------------ events of a grid trajectory
def _reversal(t: np.ndarray, x: np.ndarray, v: np.ndarray, i: int, j: int) -> Event:
    """The zero of the line through ``(t_i, v_i)`` and ``(t_j, v_j)`` (opposite signs), ``x`` likewise."""
    a = v[i] / (v[i] - v[j])
    return Event(float(t[i] + a * (t[j] - t[i])), "reversal", float(x[i] + a * (x[j] - x[i])))


def _stick_events(t: np.ndarray, x: np.ndarray, first: int, last: int) -> list[Event]:
    """A stop at the first point of a stick run (none at ``t = 0``), a breakaway at its last (none at the end).

    A run of one point at ``t = 0`` gives nothing: it is the release at rest
    of a mass outside the band, which slips at once (the exact solver records
    no event there either).
    """
    out = [Event(float(t[first]), "stop", float(x[first]))] if first > 0 else []
    if last < t.size - 1 and last > 0:  # v = 0 at t = 0 alone is a release from rest, not a stick
        out.append(Event(float(t[last]), "breakaway", float(x[last])))
    return out


def grid_events(t: np.ndarray, x: np.ndarray, v: np.ndarray, t_off: float | None = None) -> tuple[Event, ...]:
    """Events of a trajectory on a grid, read from its velocities (``v == 0`` exactly is stick).

    Parameters
    ----------
    t, x, v : ndarray, shape (n,)
        Times (s), increasing; displacements (m); velocities (m/s).
    t_off : float or None
        Switch-off time of the forcing (s), if inside the run.

    Returns
    -------
    tuple of Event
        In time order.  A *reversal* is a change of sign of ``v`` with at
        most one grid point of ``v == 0`` between the two signs (a scheme
        stepping across a reversal may land on ``v = 0`` for one step),
        dated at the zero of the line through the last velocity of one sign
        and the first of the other.  Every other run of ``v == 0`` is a
        stick: a *stop* at its first grid time (none for a run from
        ``t = 0``) and a *breakaway* at its last (none for a run to the
        end, or for ``v = 0`` at ``t = 0`` alone, a release from rest).  *forcing-off* is at ``t_off`` with ``x`` interpolated
        linearly (exact on a grid through ``t_off``).
    """
    t, x, v = (np.asarray(a, dtype=float) for a in (t, x, v))
    zero = np.flatnonzero(v == 0)
    runs = np.split(zero, np.flatnonzero(np.diff(zero) != 1) + 1) if zero.size else []
    events, moving = [], np.flatnonzero(v != 0)
    for i, j in itertools.pairwise(moving):
        if j - i <= 2 and v[i] * v[j] < 0:
            events.append(_reversal(t, x, v, i, j))
    for run_ in runs:
        lone = run_.size == 1 and 0 < run_[0] < v.size - 1 and v[run_[0] - 1] * v[run_[0] + 1] < 0
        if not lone:
            events += _stick_events(t, x, int(run_[0]), int(run_[-1]))
    if t_off is not None and t[0] < t_off <= t[-1]:
        events.append(Event(float(t_off), "forcing-off", float(np.interp(t_off, t, x))))
    return tuple(sorted(events, key=lambda e: e.time))


def match_events(found: Sequence[Event], wanted: Sequence[Event]) -> dict[str, float]:
    """Per kind of :data:`KINDS` present in ``wanted``: the largest error of the pairs matched in order.

    The ``i``-th event of a kind in ``found`` is paired with the ``i``-th of
    that kind in ``wanted``; the error is in time (s), in displacement (m)
    for ``forcing-off``.  If the count of any kind differs, every kind is
    ``nan``: the motion took another course (a half-cycle more or less, a
    spurious stick), and pairing its events in order would compare
    different switches.  A kind absent from ``wanted`` is left out.
    """
    out: dict[str, float] = {}
    counts = [(sum(e.kind == k for e in found), sum(e.kind == k for e in wanted)) for k in KINDS]
    paired = all(a == b for a, b in counts)
    for kind in KINDS:
        want = [e for e in wanted if e.kind == kind]
        got = [e for e in found if e.kind == kind]
        if not want:
            continue
        if not paired:
            out[kind] = math.nan
            continue
        values = [(a.x, b.x) if kind == "forcing-off" else (a.time, b.time) for a, b in zip(got, want)]
        out[kind] = max(abs(a - b) for a, b in values)
    return out


# ------------------------------------------------------------------ one run
@dataclass(frozen=True)
class Result:
    """One method on one case at one resolution (see the module docstring for the errors).

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
        :func:`match_events`'s output.
    reference_position : float
        The reference's final position (m), for relative errors.
    work : int
        Steps (module docstring).
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


def _final(case: Case, rest: tuple[float, float], x_end: float) -> tuple[float, float]:
    """``(rest time, position)`` compared for the case: the rest, or ``(nan, x(t_end))`` for ``"end"``."""
    return (math.nan, x_end) if case.final == "end" else rest


def _t_off(case: Case) -> float | None:
    f = case.force
    return None if f is None or f.is_zero or not f.until < case.t_end else f.until


def _scheme(case: Case, ref: Reference, method: str, dt: float) -> _Outcome:
    """A fixed-step scheme on the grid ``n dt``; events located by the scheme or read from the grid."""
    if method == "event-capturing":
        captured = event_capturing(case.oscillator, case.t_end, dt, **case.kwargs())
        traj, events = captured.trajectory, tuple(e for e in captured.events if e.kind in KINDS)
    else:
        traj = METHODS[method](case.oscillator, case.t_end, dt, case.x0, 0.0, case.force, 1)
        events = grid_events(traj.t, traj.x, traj.v, _t_off(case))
    exact = ref.solution.sample(dt)
    final = _final(case, (traj.rest_time, traj.rest_position), float(traj.x[-1]))
    return _Outcome(final, float(np.max(np.abs(traj.x - exact.x))), events, int(traj.t.size - 1))


def _event_driven(case: Case, ref: Reference, rtol: float) -> _Outcome:
    sol = solve_event_driven(case.oscillator, case.t_end, rtol=rtol, **case.kwargs())
    on_grid: Trajectory = sol.sample(SAMPLE_DT)
    x_end = float(sol.evaluate(np.array([case.t_end]))["x"][0])
    max_x = float(np.max(np.abs(on_grid.x - ref.solution.sample(SAMPLE_DT).x)))
    events = tuple(e for e in sol.events if e.kind in KINDS)
    return _Outcome(_final(case, sol.rest_through(case.t_end), x_end), max_x, events, sol.steps)


def _exact(case: Case, ref: Reference, dt: float) -> _Outcome:
    sol = solve_exact(case.oscillator, case.t_end, **case.kwargs())
    x_end = float(sol.evaluate(np.array([case.t_end]))["x"][0])
    return _Outcome(_final(case, sol.rest_through(case.t_end), x_end), 0.0, ref.events, 0)


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
    want = _final(case, rest, rest[1])  # at rest at t_end, the rest position is x(t_end)
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
    closed_form_only = method == "tanh" or (method in METHODS and METHODS[method].bingham_only)
    if closed_form_only and not case.closed_form:
        raise ValueError(f"method: {method!r} needs a Bingham or Coulomb law; case {case.name!r} has another")
    if (method == "tanh") != (eps is not None):
        raise ValueError("eps: give it for method 'tanh' (the velocity scale, m/s), and only for it")
    return case, resolution, math.nan if eps is None else validate.positive("eps", eps)


def _outcome(case: Case, ref: Reference, method: str, resolution: float, eps: float) -> Callable[[], _Outcome]:
    """The run of ``method`` as a call without arguments (timed by :func:`run`)."""
    if method in SCHEMES:
        return lambda: _scheme(case, ref, method, resolution)
    if method == "event-driven":
        return lambda: _event_driven(case, ref, resolution)
    if method == "exact":
        return lambda: _exact(case, ref, resolution)
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
        A :class:`Case` or a name of :data:`CASE_NAMES`.
    method : str
        One of :data:`STUDY_METHODS`; ``exact`` and ``tanh`` need a Bingham
        or Coulomb law.
    resolution : float
        ``dt`` (s) for the fixed-step schemes (and ``exact``, unused);
        ``rtol`` for ``event-driven`` and ``tanh``.
    eps : float, m/s
        The ``tanh`` scale; only for ``tanh``.
    ref : Reference, optional
        The case's :func:`reference` (computed when not given).
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


# ------------------------------------------------------------------ orders
#: Fewest steps an order is fitted over.
MIN_FIT_POINTS = 3


def _slope(steps: Sequence[float], errors: Sequence[float]) -> float:
    """Least-squares slope of ``log(error)`` against ``log(step)`` over the finest steps whose errors are > 0.

    ``steps`` decrease.  The fit takes the longest run of finite, positive
    errors that ends at the finest step (a coarse step at which the events
    cannot be paired is left out, a fine one is not); ``nan`` if that run is
    shorter than :data:`MIN_FIT_POINTS`.
    """
    usable = 0
    for e in reversed(errors):
        if not (e > ROUND_OFF and math.isfinite(e)):
            break
        usable += 1
    if usable < MIN_FIT_POINTS:
        return math.nan
    h, e = np.log(steps[-usable:]), np.log(errors[-usable:])
    return float(np.polyfit(h, e, 1)[0])


#: Errors at or below this (s or m; the cases' times and amplitudes are of
#: order one) are round-off: the scheme is exact there and no order is fitted.
ROUND_OFF = 1e-13


def observed_orders(results: Iterable[Result]) -> dict[str, dict[str, dict[str, float]]]:
    """Fitted orders ``[case][scheme][quantity]`` over the steps of each fixed-step scheme.

    The quantities are ``position``, ``rest_time``, ``max_x`` and each event
    kind; see :func:`_slope` for the steps used (an error is ``nan`` where
    events cannot be paired or a run is still moving, and zero where the
    scheme is exact, as the event-capturing scheme's closed-form breakaways).
    """
    groups: dict[tuple[str, str], list[Result]] = {}
    for r in results:
        if r.method in SCHEMES:
            groups.setdefault((r.case, r.method), []).append(r)
    out: dict[str, dict[str, dict[str, float]]] = {}
    for (name, method), rs in groups.items():
        rs = sorted(rs, key=lambda r: -r.resolution)
        steps = [r.resolution for r in rs]
        quantities = {
            "position": [r.position_error for r in rs],
            "rest_time": [r.rest_time_error for r in rs],
            "max_x": [r.max_x_error for r in rs],
        }
        for kind in rs[0].event_errors:
            quantities[kind] = [r.event_errors.get(kind, math.nan) for r in rs]
        out.setdefault(name, {})[method] = {q: _slope(steps, e) for q, e in quantities.items()}
    return out


def order_table(orders: Mapping[str, Mapping[str, Mapping[str, float]]]) -> dict[str, dict[str, list[float]]]:
    """``[scheme][kind]``: the smallest and largest fitted order over the cases (``[]`` if none is finite)."""
    out: dict[str, dict[str, list[float]]] = {}
    for method in SCHEMES:
        for kind in KINDS:
            found = [o[method][kind] for o in orders.values() if method in o and kind in o[method]]
            finite = [v for v in found if math.isfinite(v)]
            out.setdefault(method, {})[kind] = [min(finite), max(finite)] if finite else []
    return out


# ------------------------------------------------------------------ the study
#: Resolutions of the pipeline's study: steps (s) of the fixed-step schemes,
#: ``rtol`` of the event-driven method, ``(eps, rtol)`` of the tanh model.
STEPS = (1.6e-3, 8e-4, 4e-4, 2e-4, 1e-4)
RTOLS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
TANH_EPS = (1e-2, 1e-3, 1e-4, 1e-5)
TANH_RTOLS = (1e-6, 1e-9)
#: Cases on which the tanh model is run (the issue's target is the free decay's rest position).
TANH_CASES = ("free-decay",)


@dataclass(frozen=True)
class Study:
    """Every :class:`Result` of :func:`study`, the references' finals, and the fitted orders."""

    results: tuple[Result, ...]
    references: dict[str, dict[str, Any]]
    orders: dict[str, dict[str, dict[str, float]]] = field(default_factory=dict)

    def select(self, case: str, method: str) -> list[Result]:
        """The results of one method on one case, coarsest first."""
        return sorted((r for r in self.results if (r.case, r.method) == (case, method)), key=lambda r: -r.resolution)


def _runs(case: Case, steps: Sequence[float], rtols: Sequence[float], tanh: Sequence[tuple[float, float]]) -> list:
    """``(method, resolution, eps)`` of every run on ``case``."""
    out = [(m, dt, None) for m in SCHEMES for dt in steps]
    out += [("event-driven", r, None) for r in rtols]
    if case.closed_form:
        out.append(("exact", steps[-1], None))
        out += [("tanh", rtol, eps) for eps, rtol in tanh if case.name in TANH_CASES]
    return out


def study(
    names: Sequence[str] = CASE_NAMES,
    *,
    steps: Sequence[float] = STEPS,
    rtols: Sequence[float] = RTOLS,
    tanh: Sequence[tuple[float, float]] | None = None,
    repeats: int = 0,
    cfg: dict[str, Any] | None = None,
) -> Study:
    """Run every method at every resolution on the named cases.

    Parameters
    ----------
    names : sequence of str
        Cases of :data:`CASE_NAMES`.
    steps, rtols : sequence of float
        Steps (s) of the fixed-step schemes, from coarse to fine; tolerances
        of the event-driven method.
    tanh : sequence of (eps, rtol), optional
        Settings of the tanh model on :data:`TANH_CASES`; by default every
        pair of :data:`TANH_EPS` and :data:`TANH_RTOLS`.
    repeats : int
        Timed repeats per run (:func:`run`); ``0`` times nothing.
    cfg : dict, optional
        Configuration for :func:`cases` (by default the repository's, without overrides).
    """
    tanh = [(e, r) for e in TANH_EPS for r in TANH_RTOLS] if tanh is None else list(tanh)
    if not steps or list(steps) != sorted(steps, reverse=True):
        raise ValueError(f"steps must be a non-empty sequence from coarse to fine, got {list(steps)}")
    table = cases(cfg)
    unknown = [n for n in names if n not in table]
    if unknown or not names:
        raise ValueError(f"names must be cases of {', '.join(CASE_NAMES)}; got {list(names)}")
    results, refs = [], {}
    for name in names:
        case = table[name]
        ref = reference(case)
        rest_time, position = _final(case, ref.final(case.t_end), ref.final(case.t_end)[1])
        refs[name] = {"method": ref.method, "position": position, "rest_time": rest_time, "final": case.final}
        refs[name] |= {"title": case.title, "events": {k: sum(e.kind == k for e in ref.events) for k in KINDS}}
        for method, res, eps in _runs(case, steps, rtols, tanh):
            results.append(run(case, method, res, eps=eps, ref=ref, repeats=repeats))
    return Study(tuple(results), refs, observed_orders(results))


def to_json(result: Study, *, wall_time: bool = False) -> dict[str, Any]:
    """The study as a strict-JSON dictionary (:func:`lumped.studies.replication.clean`).

    Layout: ``references`` (per case: the reference method, final position
    and rest time, event counts), ``results`` (one object per run, the
    fields of :class:`Result`; ``wall_time`` only when asked, since it
    changes from run to run), ``orders`` (:func:`observed_orders`) and
    ``order_table`` (:func:`order_table`), ``kinds`` (:data:`KINDS`) and
    ``headline`` (:func:`headline`).
    """
    rows = []
    for r in result.results:
        row = asdict(r) | {"relative_position_error": r.relative_position_error}
        if not wall_time:
            del row["wall_time"]
        rows.append(row)
    out = {"references": result.references, "results": rows, "orders": result.orders}
    out |= {"order_table": order_table(result.orders), "kinds": dict(KINDS), "headline": headline(result)}
    return clean(out)


def _float(value: Any) -> float:
    """A float of :func:`to_json`'s output back: ``None`` is NaN, ``"inf"``/``"-inf"`` the infinities."""
    return math.nan if value is None else float(value)


def _floats(tree: Any) -> Any:
    """:func:`_float` on every leaf of nested dictionaries of numbers."""
    return {k: _floats(v) for k, v in tree.items()} if isinstance(tree, dict) else _float(tree)


def from_json(data: Mapping[str, Any]) -> Study:
    """The :class:`Study` that :func:`to_json` wrote (without wall times), e.g. ``results/accuracy/study.json``.

    ``to_json(from_json(d)) == d`` for every ``d`` that :func:`to_json` returned without wall times.
    """
    results = []
    for row in data["results"]:
        floats = {f: _float(row[f]) for f in ("resolution", "eps", "position_error", "rest_time_error")}
        floats |= {f: _float(row[f]) for f in ("max_x_error", "reference_position")}
        errors = {k: _float(v) for k, v in row["event_errors"].items()}
        results.append(Result(row["case"], row["method"], event_errors=errors, work=int(row["work"]), **floats))
    refs = {}
    for name, ref in data["references"].items():
        refs[name] = dict(ref) | {"position": _float(ref["position"]), "rest_time": _float(ref["rest_time"])}
    return Study(tuple(results), refs, _floats(data["orders"]))


#: The original's step (s), at which the headline compares the schemes.
ORIGINAL_DT = examples.ORIGINAL_DT
#: Relative error the issue asks of the event-driven method on Herschel-Bulkley, and of the tanh model.
HB_TARGET, TANH_TARGET = 1e-8, 1e-3


def _at(rows: Sequence[Result], resolution: float) -> Result | None:
    return next((r for r in rows if r.resolution == resolution), None)


def headline(result: Study) -> dict[str, Any]:
    """The numbers the article quotes, from the study's results (``nan`` where a run is missing).

    ``original_step``: on the free decay at :data:`ORIGINAL_DT`, each
    fixed-step scheme's relative rest-position error; ``event_driven``: on
    the free decay at the smallest ``rtol`` of the study, its relative
    rest-position and absolute rest-time difference from ``exact``;
    ``herschel_bulkley``: per case, the largest ``rtol`` whose relative error
    is at most :data:`HB_TARGET`, its steps, and backward Euler's steps and
    relative error at the finest step; ``tanh``: the cheapest setting (fewest
    steps) with relative error at most :data:`TANH_TARGET`, or ``None``.
    """
    free = {m: result.select("free-decay", m) for m in (*SCHEMES, "event-driven", "tanh")}
    original = {m: _at(free[m], ORIGINAL_DT) for m in SCHEMES}
    out: dict[str, Any] = {"dt": ORIGINAL_DT, "hb_target": HB_TARGET, "tanh_target": TANH_TARGET}
    out["original_step"] = {m: r.relative_position_error if r else math.nan for m, r in original.items()}
    ed = free["event-driven"][-1] if free["event-driven"] else None
    out["event_driven"] = {
        "rtol": ed.resolution if ed else math.nan,
        "position": ed.relative_position_error if ed else math.nan,
        "rest_time": ed.rest_time_error if ed else math.nan,
    }
    out["herschel_bulkley"] = {}
    for name in ("hb-n0.5", "hb-n2"):
        good = [r for r in result.select(name, "event-driven") if r.relative_position_error <= HB_TARGET]
        be = result.select(name, "backward-euler")
        out["herschel_bulkley"][name] = {
            "rtol": good[0].resolution if good else math.nan,
            "steps": good[0].work if good else 0,
            "error": good[0].relative_position_error if good else math.nan,
            "be_dt": be[-1].resolution if be else math.nan,
            "be_steps": be[-1].work if be else 0,
            "be_error": be[-1].relative_position_error if be else math.nan,
        }
    tanh = [r for r in free["tanh"] if r.relative_position_error <= TANH_TARGET]
    best = min(tanh, key=lambda r: r.work) if tanh else None
    out["tanh"] = None if best is None else {"eps": best.eps, "rtol": best.resolution, "steps": best.work}
    out["tanh_errors"] = [
        {"eps": r.eps, "rtol": r.resolution, "error": r.relative_position_error} for r in free["tanh"]
    ]
    return out
