"""The replication article's numbers and verdicts, computed from the package.

``scripts/paper_numbers.py`` writes :func:`compute`'s dictionary to
``paper/build/numbers.json``; the article (``paper/paper.typ``) reads it with
Typst's ``json()``, types no number by hand and decides no verdict: every
"reproduced" or "deviates" it prints is a :class:`Verdict` from here, with the
tolerance it was decided by.

The modules, named after what they hold:

* :mod:`~lumped.studies.replication.numbers`: :func:`compute`, the whole
  dictionary, with the configured and the original's parameters
  (:data:`ORIGINAL`) and the provenance (:data:`PACKAGES`);
* :mod:`~lumped.studies.replication.runs`: the original's four runs by the
  exact solution and by Algorithm 1, and the convergence study
  (:data:`CONVERGENCE_STEPS`);
* :mod:`~lumped.studies.replication.verdicts`: each claim's :class:`Verdict`
  (:data:`VERDICT_KEYS`, :data:`CURVE_TOL`, :data:`STRETCH_TOL`);
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
    half-width ``mu_s N_f / k`` and of ``x0``.
``verdicts``
    ``configured`` and ``original``: one :class:`Verdict` per claim, decided
    from Algorithm 1 at the configured and at the original's step.  A result
    is *reproduced* when our Algorithm 1 agrees with our exact solution of the
    same equations within the stated tolerance: a verification of the
    published algorithm, not a comparison with the original's curves, which
    are not available to us.  The :data:`CHECKS` (Figures 1 to 4, Remark 3.1)
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
