"""The orders of the fixed-step schemes, fitted per case and per quantity, and pooled per event kind with their spread.

* :func:`fit_order` and :func:`fitted_slope`: the least-squares slope of
  ``log(error)`` against ``log(dt)`` over the finest steps of one series, with
  its standard error;
* :func:`pooled_order`: one slope over several series (one per case), each
  with its own constant, with its standard error;
* :func:`observed_orders`: :func:`fit_order` for every case, scheme and
  quantity (the final position, rest time, largest displacement error and
  each event kind);
* :func:`order_table`: per scheme and event kind, :func:`pooled_order` over
  the cases that have the event.

Why a spread, and why steps that are not nested
-----------------------------------------------
A scheme that dates a switch at a grid point (Algorithm 1, the Moreau-Jean
scheme, the θ-method) makes an event error ``c dt`` whose factor ``c`` in
``[0, 1)`` depends on where the switch falls between two grid points: the
error is ``O(dt)`` but not smooth in ``dt``.  On nested steps
(``dt_0 / 2^j``) every grid holds the grid points of the coarser ones, so a
switch just after a common grid point is missed by the same few microseconds
at every step, and the fitted slope is ``0``: an artefact of the grids, not an
order (issue 32).  The study's steps
(:data:`~lumped.studies.accuracy.work_precision.STEPS`) are therefore in the
ratio 1.37, which puts each switch at a different place in its step on every
grid, and a slope fitted on such irregular errors is reported with its
standard error (the scatter of ``log(error)`` about the fitted line,
``s / sqrt(sum (log dt - mean)^2)``): a slope without its spread says nothing
about an irregular error.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import NamedTuple

import numpy as np

from lumped.studies.accuracy.events import KINDS
from lumped.studies.accuracy.methods import SCHEMES
from lumped.studies.accuracy.runs import Result

__all__ = [
    "MIN_FIT_POINTS",
    "ROUND_OFF",
    "Fit",
    "fit_order",
    "fitted_slope",
    "observed_orders",
    "order_table",
    "pooled_order",
]

#: Fewest steps an order is fitted over.
MIN_FIT_POINTS = 3
#: Errors at or below this (s or m; the cases' times and amplitudes are of
#: order one) are round-off: the scheme is exact there and no order is fitted.
ROUND_OFF = 1e-13


class Fit(NamedTuple):
    """A fitted order: the ``slope`` of ``log(error)`` against ``log(dt)``, its ``stderr``, the ``points`` and ``series``.

    ``nan`` slope and standard error, and no points, where no order is fitted.
    """

    slope: float
    stderr: float
    points: int = 0
    series: int = 0


NO_FIT = Fit(math.nan, math.nan)


def _finest_run(errors: Sequence[float]) -> int:
    """How many of the finest errors are finite and above :data:`ROUND_OFF`, counted from the finest."""
    usable = 0
    for e in reversed(errors):
        if not (e > ROUND_OFF and math.isfinite(e)):
            break
        usable += 1
    return usable


def _series(steps: Sequence[float], errors: Sequence[float]) -> tuple[np.ndarray, np.ndarray] | None:
    """``(log dt, log error)`` over :func:`_finest_run`, or ``None`` if shorter than :data:`MIN_FIT_POINTS`."""
    usable = _finest_run(errors)
    if usable < MIN_FIT_POINTS:
        return None
    return np.log(np.asarray(steps[-usable:], dtype=float)), np.log(np.asarray(errors[-usable:], dtype=float))


def pooled_order(series: Iterable[tuple[np.ndarray, np.ndarray]]) -> Fit:
    """One slope over several ``(log dt, log error)`` series, each with its own constant, and its standard error.

    The least-squares fit of ``log e_ij = a_i + p log dt_ij``: ``p`` is
    ``sum_ij (h_ij - mean_i h)(e_ij - mean_i e) / S``, with
    ``S = sum_ij (h_ij - mean_i h)^2``, and its standard error is
    ``sqrt(RSS / (N - C - 1) / S)`` for ``N`` points in ``C`` series.  An error
    that is the same at every point of every series gives slope ``0`` and
    standard error ``0`` exactly (not a round-off of either sign).
    """
    series = list(series)
    if not series:
        return NO_FIT
    points = sum(h.size for h, _ in series)
    if all(np.all(e == e[0]) for _, e in series):
        return Fit(0.0, 0.0, points, len(series))
    centred = [(h - h.mean(), e - e.mean()) for h, e in series]
    sxx = sum(float(h @ h) for h, _ in centred)
    slope = sum(float(h @ e) for h, e in centred) / sxx
    rss = sum(float((e - slope * h) @ (e - slope * h)) for h, e in centred)
    return Fit(slope, math.sqrt(rss / (points - len(series) - 1) / sxx), points, len(series))


def fit_order(steps: Sequence[float], errors: Sequence[float]) -> Fit:
    """The order of one series: :func:`pooled_order` of its finest run of finite errors above round-off.

    ``steps`` decrease.  The fit takes the longest run of finite errors
    above :data:`ROUND_OFF` that ends at the finest step (a coarse step at
    which the events cannot be paired is left out, a fine one is not); no fit
    (``nan``) if that run is shorter than :data:`MIN_FIT_POINTS`.
    """
    found = _series(steps, errors)
    return NO_FIT if found is None else pooled_order([found])


def fitted_slope(steps: Sequence[float], errors: Sequence[float]) -> float:
    """:func:`fit_order`'s slope alone."""
    return fit_order(steps, errors).slope


def _row(fit: Fit) -> dict[str, float]:
    """A :class:`Fit` as the study's JSON writes it (``cases``: the series pooled)."""
    return {"slope": fit.slope, "stderr": fit.stderr, "points": fit.points, "cases": fit.series}


def _quantities(rs: Sequence[Result]) -> dict[str, list[float]]:
    """The errors of one scheme on one case, coarsest first: final position, rest time, largest error, events."""
    out = {
        "position": [r.position_error for r in rs],
        "rest_time": [r.rest_time_error for r in rs],
        "max_x": [r.max_x_error for r in rs],
    }
    for kind in rs[0].event_errors:
        out[kind] = [r.event_errors.get(kind, math.nan) for r in rs]
    return out


def _groups(results: Iterable[Result], steps: Sequence[float]) -> dict[tuple[str, str], list[Result]]:
    """``(case, scheme)`` -> its results at ``steps``, coarsest first."""
    wanted = set(steps)
    groups: dict[tuple[str, str], list[Result]] = {}
    for r in results:
        if r.method in SCHEMES and r.resolution in wanted:
            groups.setdefault((r.case, r.method), []).append(r)
    return {key: sorted(rs, key=lambda r: -r.resolution) for key, rs in groups.items()}


def observed_orders(
    results: Iterable[Result], steps: Sequence[float]
) -> dict[str, dict[str, dict[str, dict[str, float]]]]:
    """``[case][scheme][quantity]``: ``{"slope", "stderr", "points", "cases"}`` of :func:`fit_order` over the runs at ``steps``.

    The quantities are ``position``, ``rest_time``, ``max_x`` and each event
    kind; an error is ``nan`` where events cannot be paired or a run is still
    moving, and zero where the scheme is exact (the event-locating scheme's
    closed-form breakaways).  Runs at other steps (the original's step, which
    the headline quotes) are not fitted.
    """
    out: dict[str, dict[str, dict[str, dict[str, float]]]] = {}
    for (name, method), rs in _groups(results, steps).items():
        dts = [r.resolution for r in rs]
        fits = {q: fit_order(dts, e) for q, e in _quantities(rs).items()}
        out.setdefault(name, {})[method] = {q: _row(f) for q, f in fits.items()}
    return out


def order_table(results: Iterable[Result], steps: Sequence[float]) -> dict[str, dict[str, dict[str, float]]]:
    """``[scheme][kind]``: :func:`pooled_order` over the cases with the event, as ``slope``, ``stderr``, ``points``, ``cases``.

    Each case contributes its finest run of pairable errors (:func:`fit_order`)
    with its own constant; ``nan`` slope and standard error, no points, where
    no case gives one.
    """
    groups = _groups(results, steps)
    out: dict[str, dict[str, dict[str, float]]] = {}
    for method in SCHEMES:
        for kind in KINDS:
            found = []
            for (_, m), rs in groups.items():
                if m == method and kind in rs[0].event_errors:
                    found.append(_series([r.resolution for r in rs], _quantities(rs)[kind]))
            out.setdefault(method, {})[kind] = _row(pooled_order(s for s in found if s is not None))
    return out
