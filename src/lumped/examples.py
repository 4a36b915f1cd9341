"""The paper's runs (its section 3), defined once, from the configuration.

Section 3 of Darbha, Nakshatrala and Rajagopal shows four runs of the system
of its Figure 3: forced from rest by eq. (17a) (Figure 5) and by eq. (17b)
(Figures 6 to 9), and released from rest at a small and at a large
displacement (Figures 10 and 11 to 14). Each is an :class:`Example` here,
built from the shared configuration (``config/config.yaml``, read by
:func:`lumped.config.load`), so the notebooks, the article's numbers and the
tests run the same four runs with the same parameters; a ``--config``
override of the pipeline changes them all at once.

The original fixes m, k, mu_s N_f, gamma, eq. (17) and the step; the end
times and the two release positions of the free runs are the configuration's
(the original states neither end times nor, for Figure 10, whether x0 lies
inside the band other than by its figure).

Example
-------
>>> from lumped import examples
>>> run = examples.paper()["free_large"]
>>> trajectory, exact = run.algorithm1(), run.exact()
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from lumped.event_driven import ExactSolution, solve_exact
from lumped.forcing import SwitchedSine
from lumped.results import Trajectory
from lumped.system import Oscillator
from lumped.timestepping import backward_euler

__all__ = ["ORIGINAL_DT", "Example", "oscillator", "forcing", "paper"]

#: The time step of the original's section 3 (s); the configuration's ``dt``
#: may differ (``snakemake --config dt=1e-3``).
ORIGINAL_DT = 1e-4


@dataclass(frozen=True)
class Example:
    """One run of the paper's section 3.

    Attributes
    ----------
    name : str
        ``forced_small``, ``forced_large``, ``free_small`` or ``free_large``.
    figures : tuple of int
        The original's figures that show this run.
    oscillator : Oscillator
    dt : float
        Step of Algorithm 1 (s): the configuration's ``dt``.
    t_end : float
        End time (s).
    x0, v0 : float
        Initial displacement (m) and velocity (m/s).
    force : SwitchedSine or None
        Eq. (17a) or (17b), or ``None`` for a free vibration.
    """

    name: str
    figures: tuple[int, ...]
    oscillator: Oscillator
    dt: float
    t_end: float
    x0: float = 0.0
    v0: float = 0.0
    force: SwitchedSine | None = None

    def algorithm1(self, dt: float | None = None) -> Trajectory:
        """Algorithm 1 (backward Euler) at step ``dt`` (s), by default the configured one."""
        return backward_euler(
            self.oscillator, self.t_end, self.dt if dt is None else dt, x0=self.x0, v0=self.v0, force=self.force
        )

    def exact(self) -> ExactSolution:
        """The exact solution over ``[0, t_end]`` (:func:`lumped.solve_exact`)."""
        return solve_exact(self.oscillator, self.t_end, x0=self.x0, v0=self.v0, force=self.force)


def oscillator(cfg: dict[str, Any]) -> Oscillator:
    """The system of the original's Figure 3 with the configured m, k, mu_s N_f and gamma."""
    return Oscillator.bingham(cfg["mass"], cfg["stiffness"], cfg["threshold"], float(cfg["gamma"]))


def forcing(cfg: dict[str, Any], which: str) -> SwitchedSine:
    """Eq. (17a) for ``which="small"``, eq. (17b) for ``"large"``, with the configured values.

    The original: F(t) = P sin(5 pi t) for t <= 1 s and 0 afterwards, with
    P = 0.5 N (17a) and P = 10 N (17b).
    """
    if which not in ("small", "large"):
        raise ValueError(f"which must be 'small' or 'large', got {which!r}")
    return SwitchedSine(
        amplitude=cfg[f"force_amplitude_{which}"],
        omega=cfg["force_omega_over_pi"] * math.pi,
        phase=0.0,
        until=cfg["force_until"],
    )


def paper(cfg: dict[str, Any] | None = None) -> dict[str, Example]:
    """The four runs of section 3, keyed by name, from ``cfg`` (default: :func:`lumped.config.load`)."""
    if cfg is None:
        from lumped.config import load

        cfg = load()
    osc, dt = oscillator(cfg), float(cfg["dt"])
    forced = dict(oscillator=osc, dt=dt, t_end=cfg["t_end_forced"])
    return {
        "forced_small": Example("forced_small", (5,), force=forcing(cfg, "small"), **forced),
        "forced_large": Example("forced_large", (6, 7, 8, 9), force=forcing(cfg, "large"), **forced),
        "free_small": Example("free_small", (10,), osc, dt, cfg["t_end_small"], x0=cfg["x0_small"]),
        "free_large": Example("free_large", (11, 12, 13, 14), osc, dt, cfg["t_end_large"], x0=cfg["x0_large"]),
    }
