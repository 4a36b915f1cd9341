"""The work-precision study: every method against a reference, case by case (issue 10, part 4).

One home for the study that notebook 09, ``benchmarks/bench_accuracy.py``,
the pipeline's ``results/accuracy/study.json`` and the article's accuracy
section share, in modules named after what they hold:

* :mod:`~lumped.studies.accuracy.methods`: the methods compared, read from
  the registry :data:`lumped.drivers.methods.METHODS` and grouped by what
  their resolution is (:data:`SCHEMES`, the fixed-step schemes; the
  toleranced and the closed-form methods; and the ``tanh`` model);
* :mod:`~lumped.studies.accuracy.cases`: :data:`CASE_NAMES` and
  :func:`cases`, the five motions, as data, and :func:`reference`, the
  reference solution of a case (``exact`` for the Bingham and Coulomb laws,
  ``event-driven`` at its smallest tolerance for Herschel-Bulkley laws),
  with its events;
* :mod:`~lumped.studies.accuracy.events`: :func:`grid_events` and
  :func:`match_events`, the events of a grid trajectory and their pairing
  with the reference's;
* :mod:`~lumped.studies.accuracy.runs`: :func:`run`, one method on one case
  at one resolution, a :class:`Result` with the four errors and the work;
* :mod:`~lumped.studies.accuracy.orders`: :func:`observed_orders` and
  :func:`order_table`, orders per event type fitted on steps that are not
  nested, each slope with its standard error (:func:`fit_order`, :func:`pooled_order`);
* :mod:`~lumped.studies.accuracy.work_precision`: :func:`study`,
  :func:`to_json` and :func:`from_json`, the whole table as strict JSON, and
  :func:`headline`, the numbers the article quotes.

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
(a grid of :data:`~lumped.studies.accuracy.runs.SAMPLE_DT` for the
event-driven method, the accepted steps for ``solve_ivp``).  The *event
errors* are, per kind, the largest distance in time between matched events
(in displacement for the ``switch``, the forcing going off, whose time is given).  The ``tanh``
model never sticks: its "rest position" is ``x(t_end)`` compared with the
reference's rest position, which is what a user of that model would report.

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

from lumped.studies.accuracy.cases import CASE_NAMES, Case, Reference, cases, reference
from lumped.studies.accuracy.events import KINDS, grid_events, match_events
from lumped.studies.accuracy.methods import SCHEMES, STUDY_METHODS
from lumped.studies.accuracy.orders import Fit, fit_order, observed_orders, order_table, pooled_order
from lumped.studies.accuracy.runs import Result, run
from lumped.studies.accuracy.work_precision import (
    RTOLS,
    STEPS,
    TANH_EPS,
    TANH_RTOLS,
    Study,
    from_json,
    headline,
    study,
    to_json,
)

__all__ = [
    "CASE_NAMES",
    "KINDS",
    "RTOLS",
    "SCHEMES",
    "STEPS",
    "STUDY_METHODS",
    "TANH_EPS",
    "TANH_RTOLS",
    "Case",
    "Fit",
    "Reference",
    "Result",
    "Study",
    "cases",
    "fit_order",
    "from_json",
    "grid_events",
    "headline",
    "match_events",
    "observed_orders",
    "order_table",
    "pooled_order",
    "reference",
    "run",
    "study",
    "to_json",
]
