"""The paper's runs (its section 3), defined once, from the configuration.

Section 3 of Darbha, Nakshatrala and Rajagopal shows four runs of the system
of its Figure 3: forced from rest by eq. (17a) (Figure 5) and by eq. (17b)
(Figures 6 to 9), and released from rest at a small and at a large
displacement (Figures 10 and 11 to 14). Each is an :class:`Example` here,
built from the shared configuration (``config/config.yaml``, read by
:func:`lumped.studies.config.load`), so the notebooks, the article's numbers and the
tests run the same four runs with the same parameters; a ``--config``
override of the pipeline changes them all at once.  The runs are built in
:mod:`lumped.studies.paper_runs` from values already read (so that
:func:`lumped.studies.config.problems` can check them without importing this module);
:func:`paper` adds the default configuration.

The original fixes m, k, mu_s N_f, gamma, eq. (17) and the step; the end
times and the two release positions of the free runs are the configuration's
(the original states neither end times nor, for Figure 10, whether x0 lies
inside the band other than by its figure).

Example
-------
>>> from lumped.studies import examples
>>> run = examples.paper()["free_large"]
>>> trajectory, exact = run.algorithm1(), run.exact()
"""

from __future__ import annotations

from typing import Any

from lumped.studies import config
from lumped.studies.paper_runs import Example, forcing, oscillator, runs

__all__ = ["ORIGINAL_DT", "Example", "oscillator", "forcing", "paper"]

#: The time step of the original's section 3 (s); the configuration's ``dt``
#: may differ (``snakemake --config dt=1e-3``).
ORIGINAL_DT = 1e-4


def paper(cfg: dict[str, Any] | None = None) -> dict[str, Example]:
    """The four runs of section 3, keyed by name, from ``cfg`` (default: :func:`lumped.studies.config.load`)."""
    return runs(config.load() if cfg is None else cfg)
