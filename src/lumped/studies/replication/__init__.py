"""The replication article's numbers and verdicts, computed from the package.

``scripts/paper_numbers.py`` writes :func:`compute`'s dictionary to
``paper/build/numbers.json``; the article (``paper/paper.typ``) reads it with
Typst's ``json()``, types no number by hand and decides no verdict: every
"reproduced" or "deviates" it prints is a :class:`Verdict` from here, with the
claim it tested and the differences reported beside it.

The modules, named after what they hold:

* :mod:`~lumped.studies.replication.numbers`: :func:`compute`, the whole
  dictionary, with the configured and the original's parameters
  (:data:`ORIGINAL`) and the provenance (:data:`PACKAGES`);
* :mod:`~lumped.studies.replication.runs`: the original's four runs by the
  exact solution and by Algorithm 1, the release sweep of the large free
  vibration, Siconos' FrictionOscillator's ending, and the convergence study
  (:data:`CONVERGENCE_STEPS`);
* :mod:`~lumped.studies.replication.verdicts`: each claim's :class:`Verdict`
  (:data:`VERDICT_KEYS`);
* :mod:`~lumped.studies.replication.textbook_model`: the ``sgn(0) = 0``
  model and its ``tanh`` regularisation (:data:`TEXTBOOK`).

Layout of the dictionary
------------------------
``parameters``
    The configured values (``m``, ``k``, ``tau``, ``gamma``, ``dt``, ...).
``original``
    The original's values (its section 3), ``changed`` (every parameter whose
    configured value differs from the original's, with both values) and
    ``ours`` (the end times, which the original does not state).
``forced_small``, ``forced_large``, ``free_small``, ``free_large``
    One object per run of the original's section 3 (Figures 5, 6-9, 10,
    11-14): the exact solution (``exact``), Algorithm 1 at the configured step
    (``be``) and their differences (``error``); ``be_original`` and
    ``error_original`` are the same at the original's step ``ORIGINAL_DT``
    (identical to ``be`` and ``error`` when the configured step is the
    original's).  ``free_large.rest_error``: the rest-position error at the
    original's step as fractions of the exact rest position, of the band
    half-width ``mu_s N_f / k`` and of ``x0``.  ``free_large.sweep`` (and
    ``sweep_original``): releases ``x0`` (m), their ``spacing`` (m) and the
    rest positions of the exact solution and of Algorithm 1 (Figure 14's
    existential claim).
``friction_oscillator``
    Siconos' FrictionOscillator (``case``): rest time, rest position and
    reversals of the exact solution, of Algorithm 1 (``backward-euler``) and
    of Moreau-Jean at Siconos' step.
``verdicts``
    ``configured`` and ``original``: one :class:`Verdict` per claim, decided
    from Algorithm 1 at the configured and at the original's step.  A result
    is *reproduced* when the claim the original makes with it, stated as a
    sentence that can be tested, holds in our exact solution and with our
    Algorithm 1: a verification of the published algorithm's claims, not a
    comparison with the original's curves, which are not available to us.
    The differences between the two solutions are reported beside
    (``differences``) and decide nothing.  The :data:`CHECKS` (Figures 1 to 4, Remark 3.1)
    hold by construction; they are listed (``checks``) and judged ``holds``
    or ``fails``, never counted among the results.  ``summary`` groups the
    labels by verdict.
``convergence``, ``convergence_rest``
    The differences for the steps :data:`CONVERGENCE_STEPS`, and how each of
    those runs ends (rest position, reversals, side of zero).
``textbook``
    The ``sgn(0) = 0`` model and its ``tanh`` regularisation, with the
    settings of notebook 02 (:data:`TEXTBOOK`).
``provenance``
    Python, key package versions and the machine; no wall-clock time.

Times in s, displacements in m, velocities in m/s, forces in N. The
dictionary is strict JSON (:func:`lumped.studies.strict_json.clean`): a run
not at rest by its end time has ``"still moving"`` as rest time and
position; a difference or fitted order that cannot be formed is ``None``; an
infinite parameter is ``"inf"``.
"""

from __future__ import annotations

from lumped.studies.replication.numbers import ORIGINAL, PACKAGES, compute
from lumped.studies.replication.runs import CONVERGENCE_STEPS, ORIGINAL_DT
from lumped.studies.replication.textbook_model import TEXTBOOK
from lumped.studies.replication.verdicts import CHECKS, VERDICT_KEYS, Verdict

__all__ = [
    "CHECKS",
    "CONVERGENCE_STEPS",
    "ORIGINAL",
    "ORIGINAL_DT",
    "PACKAGES",
    "TEXTBOOK",
    "VERDICT_KEYS",
    "Verdict",
    "compute",
]
