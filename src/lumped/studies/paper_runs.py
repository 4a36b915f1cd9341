"""The paper's four runs (its section 3) built from a configuration mapping.

:mod:`lumped.studies.examples` is the public face: its :func:`~lumped.studies.examples.paper`
reads the configuration (:func:`lumped.studies.config.load`) when given none.  This
module builds the runs from values already read, and imports no
configuration, so that :func:`lumped.studies.config.problems` can check the runs a
configuration makes (the checks each run makes before it starts) without
an import circle between the configuration and the examples.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.model.trajectory import Trajectory
from lumped.solvers.backward_euler import backward_euler
from lumped.solvers.exact import ExactSolution, solve_exact

__all__ = ["Example", "oscillator", "forcing", "runs"]


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


def runs(cfg: dict[str, Any]) -> dict[str, Example]:
    """The four runs of section 3, keyed by name, from the configuration values ``cfg``."""
    osc, dt = oscillator(cfg), float(cfg["dt"])
    forced = dict(oscillator=osc, dt=dt, t_end=cfg["t_end_forced"])
    return {
        "forced_small": Example("forced_small", (5,), force=forcing(cfg, "small"), **forced),
        "forced_large": Example("forced_large", (6, 7, 8, 9), force=forcing(cfg, "large"), **forced),
        "free_small": Example("free_small", (10,), osc, dt, cfg["t_end_small"], x0=cfg["x0_small"]),
        "free_large": Example("free_large", (11, 12, 13, 14), osc, dt, cfg["t_end_large"], x0=cfg["x0_large"]),
    }
