"""The work-precision study as a whole: every method at every resolution on the cases, its JSON, its headline.

* :data:`STEPS`, :data:`RTOLS`, :data:`TANH_EPS`, :data:`TANH_RTOLS`: the
  pipeline's resolutions;
* :class:`Study` and :func:`study`: every run's :class:`~lumped.studies.accuracy.runs.Result`,
  the references and the fitted orders;
* :func:`to_json` and :func:`from_json`: the study as strict JSON
  (``results/accuracy/study.json``) and back;
* :func:`headline`: the numbers the article quotes.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field
from typing import Any

from lumped.drivers.methods import METHODS
from lumped.numerics import validate
from lumped.studies import examples
from lumped.studies.accuracy.cases import CASE_NAMES, Case, Reference, cases, reference
from lumped.studies.accuracy.events import KINDS
from lumped.studies.accuracy.friction_oscillator import friction_oscillator
from lumped.studies.accuracy.methods import CLOSED_FORM, SCHEMES, TANH, TOLERANCED
from lumped.studies.accuracy.orders import observed_orders, order_table
from lumped.studies.accuracy.runs import Result, compared_final, run
from lumped.studies.strict_json import clean

__all__ = [
    "HB_TARGET",
    "RTOLS",
    "STEPS",
    "TANH_CASES",
    "TANH_EPS",
    "TANH_RTOLS",
    "TANH_TARGET",
    "Study",
    "from_json",
    "headline",
    "study",
    "to_json",
]

#: Resolutions of the pipeline's study: steps (s) of the fixed-step schemes,
#: ``rtol`` of the event-driven method, ``(eps, rtol)`` of the tanh model.
#: The steps are ``1.6e-3 / 1.37^j``, ``j = 1 ... 10`` (1.2e-3 down to 6.9e-5 s), not
#: nested: halving ``1.6e-3`` puts ``t = 0.0064 s``, 23 us after the (17b) cases'
#: breakaway, on every grid, and a scheme dating it at a grid point then makes the
#: same error at every step (slope 0, an artefact; :mod:`~lumped.studies.accuracy.orders`).
#: Ten steps over a factor 17 give each fitted slope a standard error.
STEPS = tuple(1.6e-3 / 1.37**j for j in range(1, 11))
RTOLS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
TANH_EPS = (1e-2, 1e-3, 1e-4, 1e-5)
TANH_RTOLS = (1e-6, 1e-9)
#: Cases on which the tanh model is run (the issue's target is the free decay's rest position).
TANH_CASES = ("free-decay",)


@dataclass(frozen=True)
class Study:
    """Every :class:`Result` of :func:`study`, the references' finals, the fitted orders, and
    :func:`~lumped.studies.accuracy.friction_oscillator.friction_oscillator` (Siconos' example)."""

    results: tuple[Result, ...]
    references: dict[str, dict[str, Any]]
    orders: dict[str, dict[str, dict[str, dict[str, float]]]] = field(default_factory=dict)
    friction_oscillator: dict[str, Any] = field(default_factory=dict)
    #: The steps the orders are fitted over (the fixed-step schemes also run at the original's step, not fitted).
    steps: tuple[float, ...] = ()

    def select(self, case: str, method: str) -> list[Result]:
        """The results of one method on one case, coarsest first."""
        return sorted((r for r in self.results if (r.case, r.method) == (case, method)), key=lambda r: -r.resolution)


def _runs(case: Case, steps: Sequence[float], rtols: Sequence[float], tanh: Sequence[tuple[float, float]]) -> list:
    """``(method, resolution, eps)`` of every run on ``case``, method group by group.

    A scheme that needs the law's Bingham form (``moreau-jean``) runs on the Bingham and Coulomb cases only.
    ``steps`` may hold one step twice (the original's, when it is also a fitted one): it runs once.
    """
    steps = sorted(set(steps), reverse=True)
    out = [(m, dt, None) for m in SCHEMES if case.closed_form or not METHODS[m].bingham_only for dt in steps]
    out += [(m, r, None) for m in TOLERANCED for r in rtols]
    if case.closed_form:
        out += [(m, steps[-1], None) for m in CLOSED_FORM]
        out += [(TANH, rtol, eps) for eps, rtol in tanh if case.name in TANH_CASES]
    return out


def _reference_summary(case: Case, ref: Reference) -> dict[str, Any]:
    """The reference's method, final position and rest time, the case's title and the reference's event counts."""
    rest_time, position = compared_final(case, ref.final(case.t_end), ref.final(case.t_end)[1])
    out = {"method": ref.method, "position": position, "rest_time": rest_time, "final": case.final}
    return out | {"title": case.title, "events": {k: sum(e.kind == k for e in ref.events) for k in KINDS}}


def study(
    names: Sequence[str] = CASE_NAMES,
    *,
    steps: Sequence[float] = STEPS,
    rtols: Sequence[float] = RTOLS,
    tanh: Sequence[tuple[float, float]] | None = None,
    repeats: int = 0,
    cfg: dict[str, Any] | None = None,
    original_step: float | None = examples.ORIGINAL_DT,
) -> Study:
    """Run every method at every resolution on the named cases.

    Parameters
    ----------
    names : sequence of str
        Cases of :data:`~lumped.studies.accuracy.cases.CASE_NAMES`.
    steps, rtols : sequence of float
        Steps (s) of the fixed-step schemes, from coarse to fine, over which
        their orders are fitted (:func:`~lumped.studies.accuracy.orders.observed_orders`;
        not nested, as :data:`STEPS`, for the orders to mean anything); tolerances
        of the event-driven method.
    original_step : float, s, optional
        One more step at which the fixed-step schemes run, for :func:`headline`,
        and not fitted (the original's, :data:`ORIGINAL_DT`, by default; ``None``: none).
    tanh : sequence of (eps, rtol), optional
        Settings of the tanh model on :data:`TANH_CASES`; by default every
        pair of :data:`TANH_EPS` and :data:`TANH_RTOLS`.
    repeats : int
        Timed repeats per run (:func:`~lumped.studies.accuracy.runs.run`); ``0`` times nothing.
    cfg : dict, optional
        Configuration for :func:`~lumped.studies.accuracy.cases.cases` (by
        default the repository's, without overrides).
    """
    tanh = [(e, r) for e in TANH_EPS for r in TANH_RTOLS] if tanh is None else list(tanh)
    if not steps or list(steps) != sorted(steps, reverse=True):
        raise ValueError(f"steps must be a non-empty sequence from coarse to fine, got {list(steps)}")
    runs_at = (*steps, *(() if original_step is None else (validate.positive("original_step", original_step),)))
    table = cases(cfg)
    unknown = [n for n in names if n not in table]
    if unknown or not names:
        raise ValueError(f"names must be cases of {', '.join(CASE_NAMES)}; got {list(names)}")
    results, refs = [], {}
    for name in names:
        case = table[name]
        ref = reference(case)
        refs[name] = _reference_summary(case, ref)
        for method, res, eps in _runs(case, runs_at, rtols, tanh):
            results.append(run(case, method, res, eps=eps, ref=ref, repeats=repeats))
    orders = observed_orders(results, steps)
    return Study(tuple(results), refs, orders, friction_oscillator(), tuple(float(dt) for dt in steps))


def to_json(result: Study, *, wall_time: bool = False) -> dict[str, Any]:
    """The study as a strict-JSON dictionary (:func:`lumped.studies.strict_json.clean`).

    Layout: ``references`` (per case: the reference method, final position
    and rest time, event counts), ``results`` (one object per run, the
    fields of :class:`Result`; ``wall_time`` only when asked, since it
    changes from run to run), ``steps`` (those the orders are fitted over),
    ``orders`` (:func:`observed_orders`) and ``order_table``
    (:func:`order_table`, a slope and its standard error per scheme and event kind), ``kinds`` (:data:`KINDS`),
    ``headline`` (:func:`headline`) and ``friction_oscillator`` (Siconos'
    example, :mod:`~lumped.studies.accuracy.friction_oscillator`).
    """
    rows = []
    for r in result.results:
        row = asdict(r) | {"relative_position_error": r.relative_position_error}
        if not wall_time:
            del row["wall_time"]
        rows.append(row)
    out = {"references": result.references, "results": rows, "orders": result.orders, "steps": list(result.steps)}
    table = order_table(result.results, result.steps)
    out |= {"order_table": table, "kinds": dict(KINDS), "headline": headline(result)}
    out["friction_oscillator"] = result.friction_oscillator
    return clean(out)


def _float(value: Any) -> float:
    """A float of :func:`to_json`'s output back: ``None`` is NaN, ``"inf"``/``"-inf"`` the infinities."""
    return math.nan if value is None else float(value)


def _floats(tree: Any) -> Any:
    """:func:`_float` on every leaf of nested dictionaries of numbers but the integers (counts), kept."""
    if isinstance(tree, dict):
        return {k: _floats(v) for k, v in tree.items()}
    return tree if isinstance(tree, int) else _float(tree)


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
    orders, steps = _floats(data["orders"]), tuple(float(dt) for dt in data["steps"])
    return Study(tuple(results), refs, orders, _floats(data["friction_oscillator"]), steps)


# ------------------------------------------------------------------ the article's numbers
#: The original's step (s), at which the headline compares the schemes.
ORIGINAL_DT = examples.ORIGINAL_DT
#: Relative error the issue asks of the event-driven method on Herschel-Bulkley, and of the tanh model.
HB_TARGET, TANH_TARGET = 1e-8, 1e-3


def _at(rows: Sequence[Result], resolution: float) -> Result | None:
    return next((r for r in rows if r.resolution == resolution), None)


def _herschel_bulkley(result: Study, name: str) -> dict[str, Any]:
    """On case ``name``: the largest ``rtol`` meeting :data:`HB_TARGET`, and backward Euler at the
    original's step (at its finest step if it did not run there)."""
    good = [r for r in result.select(name, "event-driven") if r.relative_position_error <= HB_TARGET]
    rows = result.select(name, "backward-euler")
    be = _at(rows, ORIGINAL_DT) or (rows[-1] if rows else None)
    return {
        "rtol": good[0].resolution if good else math.nan,
        "steps": good[0].work if good else 0,
        "error": good[0].relative_position_error if good else math.nan,
        "be_dt": be.resolution if be else math.nan,
        "be_steps": be.work if be else 0,
        "be_error": be.relative_position_error if be else math.nan,
    }


def headline(result: Study) -> dict[str, Any]:
    """The numbers the article quotes, from the study's results (``nan`` where a run is missing).

    ``original_step``: on the free decay at :data:`ORIGINAL_DT`, each
    fixed-step scheme's relative rest-position error; ``event_driven``: on
    the free decay at the smallest ``rtol`` of the study, its relative
    rest-position and absolute rest-time difference from ``exact``;
    ``herschel_bulkley``: per case, the largest ``rtol`` whose relative error
    is at most :data:`HB_TARGET`, its steps, and backward Euler's steps and
    relative error at the original's step (:data:`ORIGINAL_DT`); ``tanh``: the cheapest setting (fewest
    steps) with relative error at most :data:`TANH_TARGET`, or ``None``.
    """
    free = {m: result.select("free-decay", m) for m in (*SCHEMES, "event-driven", TANH)}
    original = {m: _at(free[m], ORIGINAL_DT) for m in SCHEMES}
    out: dict[str, Any] = {"dt": ORIGINAL_DT, "hb_target": HB_TARGET, "tanh_target": TANH_TARGET}
    out["original_step"] = {m: r.relative_position_error if r else math.nan for m, r in original.items()}
    ed = free["event-driven"][-1] if free["event-driven"] else None
    out["event_driven"] = {
        "rtol": ed.resolution if ed else math.nan,
        "position": ed.relative_position_error if ed else math.nan,
        "rest_time": ed.rest_time_error if ed else math.nan,
    }
    out["herschel_bulkley"] = {name: _herschel_bulkley(result, name) for name in ("hb-n0.5", "hb-n2")}
    tanh = [r for r in free[TANH] if r.relative_position_error <= TANH_TARGET]
    best = min(tanh, key=lambda r: r.work) if tanh else None
    out["tanh"] = None if best is None else {"eps": best.eps, "rtol": best.resolution, "steps": best.work}
    out["tanh_errors"] = [{"eps": r.eps, "rtol": r.resolution, "error": r.relative_position_error} for r in free[TANH]]
    return out
