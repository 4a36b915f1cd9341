"""The orders of the fixed-step schemes, fitted per case and per quantity, and their range over the cases.

* :func:`observed_orders`: the slope of ``log(error)`` against ``log(dt)``
  for every case, scheme and quantity (the final position, rest time, largest
  displacement error and each event kind);
* :func:`order_table`: per scheme and event kind, the smallest and largest
  fitted order over the cases.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence

import numpy as np

from lumped.studies.accuracy.events import KINDS
from lumped.studies.accuracy.methods import SCHEMES
from lumped.studies.accuracy.runs import Result

__all__ = ["MIN_FIT_POINTS", "ROUND_OFF", "fitted_slope", "observed_orders", "order_table"]

#: Fewest steps an order is fitted over.
MIN_FIT_POINTS = 3
#: Errors at or below this (s or m; the cases' times and amplitudes are of
#: order one) are round-off: the scheme is exact there and no order is fitted.
ROUND_OFF = 1e-13


def fitted_slope(steps: Sequence[float], errors: Sequence[float]) -> float:
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
    if len(set(errors[-usable:])) == 1:  # the same error at every step: slope 0, not a round-off of either sign
        return 0.0
    h, e = np.log(steps[-usable:]), np.log(errors[-usable:])
    return float(np.polyfit(h, e, 1)[0])


def observed_orders(results: Iterable[Result]) -> dict[str, dict[str, dict[str, float]]]:
    """Fitted orders ``[case][scheme][quantity]`` over the steps of each fixed-step scheme.

    The quantities are ``position``, ``rest_time``, ``max_x`` and each event
    kind; see :func:`fitted_slope` for the steps used (an error is ``nan`` where
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
        out.setdefault(name, {})[method] = {q: fitted_slope(steps, e) for q, e in quantities.items()}
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
