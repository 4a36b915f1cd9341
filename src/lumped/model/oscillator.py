"""The mass-spring-dashpot system of Figure 3 and its consistent initial state."""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field

import numpy as np

from lumped.laws import BinghamDashpot, Dashpot, LinearSpring
from lumped.model.parameters import PARAMETERS
from lumped.numerics import validate

__all__ = ["Oscillator", "initial_dashpot_force", "check_magnitudes", "magnitude_failures", "MAGNITUDE_LIMIT", "TINY"]

#: Largest magnitude (N) any force computed in a step may reach.  Sums of a
#: few such terms stay below the largest double, about 1.8e308.
MAGNITUDE_LIMIT = 1e300
#: Smallest normal double, ``2^-1022`` (about 2.2e-308): below it a number keeps
#: fewer than the 53 bits of a double (:func:`check_magnitudes`).
TINY = sys.float_info.min


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

    mass: float = PARAMETERS["mass"].default
    spring: LinearSpring = field(default_factory=lambda: LinearSpring(PARAMETERS["stiffness"].default))
    dashpot: Dashpot = field(
        default_factory=lambda: BinghamDashpot(PARAMETERS["threshold"].default, PARAMETERS["gamma"].default)
    )

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass", validate.positive("mass", self.mass))
        LinearSpring.check(self.spring, "spring")
        Dashpot.check(self.dashpot, "dashpot")

    @classmethod
    def bingham(
        cls,
        mass: float = PARAMETERS["mass"].default,
        stiffness: float = PARAMETERS["stiffness"].default,
        threshold: float = PARAMETERS["threshold"].default,
        gamma: float = PARAMETERS["gamma"].default,
    ) -> Oscillator:
        """The system of the paper with its parameter names; the defaults are the table's
        (:data:`lumped.model.parameters.PARAMETERS`, the paper's section 3 values)."""
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


def check_magnitudes(
    osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, amplitude: float, *, carries_force: bool = True
) -> None:
    """Refuse a run whose forces could overflow double precision, or whose products lose their digits.

    Notes
    -----
    *Overflow.*  The dashpot dissipates, so the energy ``E = m v^2/2 + k x^2/2`` can only
    grow by the work of the external force, ``dE/dt <= P |v| <= P sqrt(2E/m)``.
    Hence ``sqrt(E(t)) <= sqrt(E(0)) + P t sqrt(2/m)``; the factor is twice
    the continuous one so that the bound also holds for backward Euler, whose
    step satisfies ``E_{n+1} <= E_n + dt P |v_{n+1}|``.  From it, ``|F_s| <=
    sqrt(2 k E)`` and ``|v| <= sqrt(2 E/m)``, which bound the predictor
    ``(m/dt) v + F - F_s`` of eq. (15b) and every product the step forms.
    Each must stay below :data:`MAGNITUDE_LIMIT`.

    *Underflow* (:data:`TINY`, the smallest normal double, ``2^-1022``).  A
    product ``p`` of normal numbers is rounded to within ``2^-53 |p|`` while
    ``|p| >= 2^-1022``; below, the spacing of doubles is fixed at ``2^-1074``,
    so ``p`` keeps only ``log2(|p|/2^-1074) < 52`` bits and none at all below
    ``2^-1075``.  Mass, stiffness and ``gamma`` are refused below ``TINY`` by
    their validators (:mod:`lumped.numerics.validate`); here, the coefficients of the
    step, ``m/dt`` and ``k dt`` (eqs. 14, 15b), must be normal too.  Algorithm 1
    carries the displacement as ``x = F_s/k`` and adds ``(k dt) v`` to ``F_s``
    each step: with ``k = 1e-322`` (subnormal) or ``k dt`` subnormal, ``x``
    keeps few or no digits (``k = 1e-322``, ``v0 = 1`` gave ``x = 0`` on every
    row).  States are not refused: a subnormal ``x0`` or ``v0`` is as good as
    zero beside the other terms, and the exact solvers, which call this check
    too, carry ``x`` itself.

    *Subnormal forces.*  When the bounds on the spring force and the load are
    both below ``TINY`` (and not zero), every force of the run is subnormal and
    ``F_s`` keeps only its leading bits, whatever the threshold; such a run is
    refused too, unless ``carries_force`` is false (the exact solver carries
    ``x`` and no ``F_s``).

    Raises
    ------
    ValueError
        Naming the argument at fault: the factor of ``m/dt`` or ``k dt``
        farthest below 1 when that coefficient is subnormal, or the argument
        whose contribution dominates the energy bound.
    """
    m, k = osc.mass, osc.spring.stiffness
    for product, value, factors in (
        ("m/dt", m / dt, {"mass": m, "dt": 1 / dt}),
        ("k*dt", k * dt, {"stiffness": k, "dt": dt}),
    ):
        if not value >= TINY:
            name = min(factors, key=factors.get)  # type: ignore[arg-type]  # the factor farthest below 1
            raise ValueError(
                f"{name}: {product} = {value:.3g} is below the smallest normal double, {TINY:.3g}, "
                "where fewer than 16 significant digits remain; choose units in which the parameters are nearer 1"
            )
    parts, quantities = _energy_bound(m, k, 0.0, t_end, dt, x0, v0, amplitude)
    del quantities[_VISCOUS]
    speed = math.sqrt(2 / m) * (parts["x0"] + parts["v0"] + parts["force_amplitude"])
    bound = osc.dashpot.step_bound(sum(quantities.values()), speed, m / dt + k * dt)  # contract point 9
    quantities[bound.term] = bound.value
    scale = _force_scale(quantities)
    if carries_force and 0 < scale < TINY:
        raise ValueError(
            f"{max(parts, key=parts.get)}: every spring and external force of the run stays below {scale:.3g} N "
            f"(bound from the energy and the load), under the smallest normal double, {TINY:.3g}, where "
            "F_s = k x keeps fewer than 16 significant digits; choose units in which the forces are nearer 1"
        )
    for quantity, value in quantities.items():
        if not value <= MAGNITUDE_LIMIT:
            raise ValueError(
                f"{_blamed(quantity, parts, quantities, m / dt, bound.parameter)}: the run could reach {quantity} = "
                f"{f'{value:.3g}' if math.isfinite(value) else 'more than 1.8e308'} (bound from the energy), "
                f"above the {MAGNITUDE_LIMIT:.0e} that double precision carries through a step"
            )


#: The Bingham law's bound on its step's viscous product (:meth:`lumped.laws.BinghamDashpot.step_bound`).
_VISCOUS = "viscous term |c F~|"


def _energy_bound(m, k, c, t_end, dt, x0, v0, amplitude):  # floats or arrays alike
    """The square roots of the initial energy and work (``parts``) and the bounded quantities."""
    sqrt = np.sqrt
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        parts = {  # square roots of energy, each term kept finite
            "x0": sqrt(k / 2) * abs(x0),
            "v0": sqrt(m / 2) * abs(v0),
            "force_amplitude": abs(amplitude) * (t_end + dt) * sqrt(2 / m),
        }
        root_energy = parts["x0"] + parts["v0"] + parts["force_amplitude"]
        v_max = sqrt(2 / m) * root_energy
        quantities = {
            "spring force |F_s|": sqrt(2 * k) * root_energy,
            "momentum term |m v/dt|": m / dt * v_max,
            "external force |F|": abs(amplitude) + 0 * root_energy,
        }
        quantities[_VISCOUS] = c * sum(quantities.values())
    return parts, quantities


def _force_scale(quantities: dict):  # floats or arrays alike
    """The largest spring or external force of the run: the energy's bound on ``|F_s|``, and the load.

    When it is below ``TINY`` they are all subnormal and Algorithm 1's ``F_s``
    (hence ``x = F_s/k``) keeps only its leading bits, whatever the threshold
    (a mass held in the band keeps ``x = F_s/k``, not ``x0``): with ``m = k = 2^-996``,
    ``x0 = 1e-10``, the displacements differed from the same run in units
    ``2^996`` times larger by 3.4e-13 of ``x0``, where an exact rescaling gives
    the same bits.  A force scale of 0 (nothing loaded, nothing moves) is exact.
    """
    return np.maximum(quantities["spring force |F_s|"], quantities["external force |F|"])


def _blamed(quantity: str, parts: dict, quantities: dict, m_over_dt: float, law_parameter: str) -> str:
    """The argument named for an overflowing ``quantity`` (``law_parameter`` for the law's own bound)."""
    if quantity.startswith("momentum") and m_over_dt > 1e150:
        return "dt"
    if quantity.startswith("viscous") and all(v <= MAGNITUDE_LIMIT for q, v in quantities.items() if q != quantity):
        return law_parameter
    return max(parts, key=parts.get)  # type: ignore[arg-type]


def magnitude_failures(
    mass: np.ndarray,
    stiffness: np.ndarray,
    gamma: np.ndarray,
    t_end: float,
    dt: float,
    x0: np.ndarray,
    v0: np.ndarray,
    amplitude: np.ndarray,
    *,
    carries_force: bool = True,
) -> np.ndarray:
    """Elementwise: where :func:`check_magnitudes` would refuse the Bingham run with these parameters.

    The same bounds on arrays (a sweep's rows, whose parameters have passed
    their validators), in a few array operations; call
    :func:`check_magnitudes` on a failing row for its message.
    """
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (mass, stiffness, gamma, x0, v0, amplitude)))
    m, k, g, x, v, p = arrays
    with np.errstate(under="ignore", over="ignore", divide="ignore"):
        bad = ~(m / dt >= TINY) | ~(k * dt >= TINY)
        c = np.where(np.isinf(g), 0.0, 1 / g)
    _, quantities = _energy_bound(m, k, c, t_end, dt, x, v, p)
    if carries_force:
        scale = _force_scale(quantities)
        bad |= (scale > 0) & (scale < TINY)
    for value in quantities.values():
        bad |= ~(value <= MAGNITUDE_LIMIT)
    return bad
