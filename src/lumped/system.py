"""The mass-spring-dashpot system of Figure 3 and its consistent initial state."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from lumped import _validate
from lumped.laws import BinghamDashpot, Dashpot, LinearSpring

__all__ = ["Oscillator", "initial_dashpot_force", "check_magnitudes", "MAGNITUDE_LIMIT"]

#: Largest magnitude (N) any force computed in a step may reach.  Sums of a
#: few such terms stay below the largest double, about 1.8e308.
MAGNITUDE_LIMIT = 1e300


@dataclass(frozen=True)
class Oscillator:
    """A mass on a spring and a dashpot in parallel (Figure 3, eqs. 4).

    Parameters
    ----------
    mass : float, kg
        ``m > 0``.
    spring : LinearSpring
        Eq. (5); the paper's ``k = 100`` N/m by default.
    dashpot : Dashpot
        Eq. (6) or any other law; the paper's Bingham law with
        ``mu_s N_f = 1`` N and ``gamma = 1`` m/(N s) by default.
    """

    mass: float = 1.0
    spring: LinearSpring = field(default_factory=lambda: LinearSpring(100.0))
    dashpot: Dashpot = field(default_factory=lambda: BinghamDashpot(1.0, 1.0))

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass", _validate.positive("mass", self.mass))
        if not isinstance(self.spring, LinearSpring):
            raise ValueError("spring must be a LinearSpring")
        if not isinstance(self.dashpot, Dashpot):
            raise ValueError("dashpot must be a Dashpot")

    @classmethod
    def bingham(
        cls,
        mass: float = 1.0,
        stiffness: float = 100.0,
        threshold: float = 1.0,
        gamma: float = 1.0,
    ) -> Oscillator:
        """The system of the paper with its parameter names (section 3 defaults)."""
        return cls(mass, LinearSpring(stiffness), BinghamDashpot(threshold, gamma))

    @property
    def stiffness(self) -> float:
        """Spring constant ``k`` (N/m)."""
        return self.spring.stiffness

    @property
    def threshold(self) -> float:
        """Static band half-width ``mu_s N_f`` (N)."""
        return self.dashpot.threshold

    @property
    def static_band(self) -> float:
        """Largest ``|x|`` at which the unforced mass can rest, ``mu_s N_f / k`` (m)."""
        return self.dashpot.threshold / self.spring.stiffness


def initial_dashpot_force(osc: Oscillator, force0: float, x0: float, v0: float) -> float:
    """Dashpot force at ``t = 0`` consistent with eq. (6).

    A moving mass has the force of its velocity (eq. 7).  A mass at rest takes
    the force that keeps it at rest, ``F(0) - k x0``, if that lies in the
    static band (eq. 11c), and the band edge towards which it is pushed
    otherwise.  (The paper sets ``F_d(0) = 0`` in its examples; that value
    only differs from this one at ``t = 0`` and plays no part in the step.)
    """
    law = osc.dashpot
    if v0 != 0:
        lo, hi = law.force_interval(v0)
        return lo
    net = force0 - osc.spring.force(x0)
    return math.copysign(min(abs(net), law.threshold), net)


def check_magnitudes(osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, amplitude: float) -> None:
    """Refuse a run whose forces could overflow double precision.

    Notes
    -----
    The dashpot dissipates, so the energy ``E = m v^2/2 + k x^2/2`` can only
    grow by the work of the external force, ``dE/dt <= P |v| <= P sqrt(2E/m)``.
    Hence ``sqrt(E(t)) <= sqrt(E(0)) + P t sqrt(2/m)``; the factor is twice
    the continuous one so that the bound also holds for backward Euler, whose
    step satisfies ``E_{n+1} <= E_n + dt P |v_{n+1}|``.  From it, ``|F_s| <=
    sqrt(2 k E)`` and ``|v| <= sqrt(2 E/m)``, which bound the predictor
    ``(m/dt) v + F - F_s`` of eq. (15b) and every product the step forms.
    Each must stay below :data:`MAGNITUDE_LIMIT`.

    Raises
    ------
    ValueError
        Naming the argument whose contribution dominates the bound.
    """
    m, k = osc.mass, osc.spring.stiffness
    parts = {  # square roots of energy, each term kept finite
        "x0": math.sqrt(k / 2) * abs(x0),
        "v0": math.sqrt(m / 2) * abs(v0),
        "force_amplitude": abs(amplitude) * (t_end + dt) * math.sqrt(2 / m),
    }
    root_energy = sum(parts.values())
    v_max = math.sqrt(2 / m) * root_energy
    c = getattr(osc.dashpot, "viscosity", 0.0)
    quantities = {
        "spring force |F_s|": math.sqrt(2 * k) * root_energy,
        "momentum term |m v/dt|": m / dt * v_max,
        "external force |F|": abs(amplitude),
    }
    quantities["viscous term |c F~|"] = c * sum(quantities.values())
    for quantity, value in quantities.items():
        if not value <= MAGNITUDE_LIMIT:
            name = (
                "dt"
                if quantity.startswith("momentum") and m / dt > 1e150
                else max(
                    parts,
                    key=parts.get,  # type: ignore[arg-type]
                )
            )
            shown = f"{value:.3g}" if math.isfinite(value) else "more than 1.8e308"
            raise ValueError(
                f"{name}: the run could reach {quantity} = {shown} (bound from the energy), "
                f"above the {MAGNITUDE_LIMIT:.0e} that double precision carries through a step"
            )
