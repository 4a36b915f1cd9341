"""The cases of the work-precision study, as data, and the reference each is measured against.

* :data:`CASE_NAMES`, :class:`Case` and :func:`cases`: the five motions;
* :class:`Reference` and :func:`reference`: a case's reference solution (the
  closed form for the Bingham and Coulomb laws, the event-driven method at
  its smallest tolerance for Herschel-Bulkley laws), with its events.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from lumped.drivers.methods import METHODS
from lumped.laws import HerschelBulkleyDashpot, LinearSpring
from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.solvers.event_driven import RTOL_RANGE
from lumped.solvers.events import Event
from lumped.solvers.exact import ExactSolution
from lumped.studies import config, examples
from lumped.studies.accuracy.events import KINDS
from lumped.studies.accuracy.methods import CLOSED_FORM, TOLERANCED

__all__ = ["CASE_NAMES", "Case", "Reference", "cases", "reference"]

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
        Which final position is compared (:mod:`lumped.studies.accuracy`).
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
    ``gamma = inf`` under eq. (17b) (breakaway, reversals, the switch-off and
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

    That is, the first method of :data:`~lumped.studies.accuracy.methods.CLOSED_FORM`
    for a Bingham or Coulomb law, else the first of
    :data:`~lumped.studies.accuracy.methods.TOLERANCED`, each by its
    solver in continuous time (``Method.solution``).  The event-driven
    reference's own accuracy is measured by ``tests/test_accuracy.py``: at
    this ``rtol`` it agrees with ``exact`` on the Bingham free decay, and
    changes by little from ``rtol = 1e-12``.
    """
    kw = case.kwargs()
    if case.closed_form:
        method = CLOSED_FORM[0]
        sol = METHODS[method].solution(case.oscillator, case.t_end, **kw)  # type: ignore[misc]
    else:
        method = TOLERANCED[0]
        sol = METHODS[method].solution(case.oscillator, case.t_end, rtol=rtol, **kw)  # type: ignore[misc]
    return Reference(sol, method, tuple(e for e in sol.events if e.kind in KINDS))
