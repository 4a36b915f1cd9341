"""The law contracts: a law is a graph in (rate, tension); a dashpot is its monotone case.

Every constitutive law of a dissipative element here is a graph between the
element's rate ``u`` (its elongation rate, ``w``) and its tension ``T``:
off zero rate it slips with ``T = sgn(u) g(|u|)`` (the *slip curve*), at zero
rate it holds any tension of its *stick interval* ``[-static, static]``.
:class:`SlipLaw` states what every law provides (the slip curve, the stick
interval and the slip limit ``g(0+)``, the steepest fall of the curve that a
backward-Euler step must outweigh, its linear pieces if it has closed forms
per phase).  A law whose graph falls (static friction above kinetic, a
Stribeck curve) is picked by a rule in each step
(:class:`lumped.laws.step_graph.SlipGraph`).

A *dashpot* (:class:`Dashpot`) is a law whose graph is monotone, written the
way the paper writes eq. (6): the velocity as a function of the force,
``v = phi(F_d)``.  When ``phi`` is flat (the Bingham band ``|F_d| <= mu_s
N_f``) the inverse is set-valued, so ``F_d`` cannot be computed from ``v``
and becomes an unknown of the differential-algebraic system (8).

One backward-Euler step (eqs. 13 to 15) of a dashpot reduces to a scalar
equation for its force.  With ``eta = m/dt + k*dt`` eq. (15a) reads

    F_d + eta * phi(F_d) = F~,          v = (F~ - F_d) / eta,

that is ``F_d = (I + eta*phi)^{-1}(F~)``: the *resolvent* of the monotone graph
``phi`` applied to the predictor ``F~`` of eq. (15b).  Each dashpot provides
that resolvent; Algorithm 1 is its closed form for the Bingham graph
(:mod:`lumped.laws.bingham`).

This module holds the linear spring of eq. (5), the two contracts with their
numbered points (:class:`SlipLaw`, :class:`Dashpot`) and the named values a
law returns (:class:`DashpotState`, :class:`BinghamForm`, :class:`StepBound`,
:class:`SlipPiece`).  The laws themselves are in :mod:`lumped.laws.bingham`,
:mod:`lumped.laws.monotone`, :mod:`lumped.laws.regularised`,
:mod:`lumped.laws.stribeck` and :mod:`lumped.laws.slip`.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from lumped.laws import monotone_graph
from lumped.numerics import validate
from lumped.numerics.roots import brentq

__all__ = ["LinearSpring", "SlipLaw", "SlipPiece", "Slope", "Dashpot", "DashpotState", "BinghamForm", "StepBound"]


@dataclass(frozen=True)
class LinearSpring:
    """Linear spring, eq. (5): ``x = F_s / k``.

    Parameters
    ----------
    stiffness : float, N/m
        Spring constant ``k > 0``.
    """

    stiffness: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", validate.positive("stiffness", self.stiffness))

    def force(self, x: np.ndarray | float) -> np.ndarray | float:
        """Spring force ``F_s = k x`` (N) for displacement ``x`` (m)."""
        return self.stiffness * x

    def displacement(self, force: np.ndarray | float) -> np.ndarray | float:
        """Displacement ``x = F_s / k`` (m), eq. (5)."""
        return force / self.stiffness

    def energy(self, force: np.ndarray | float) -> np.ndarray | float:
        """Stored energy ``F_s**2 / (2k)`` (J)."""
        return 0.5 * force * force / self.stiffness

    @staticmethod
    def check(value: object, name: str) -> LinearSpring:
        """``value`` if it is a :class:`LinearSpring`, else a ``ValueError`` naming ``name``."""
        if not isinstance(value, LinearSpring):
            raise ValueError(f"{name} must be a LinearSpring")
        return value


class DashpotState(NamedTuple):
    """Solution of one implicit dashpot step: ``force`` (N), ``velocity`` (m/s)."""

    force: float
    velocity: float


class BinghamForm(NamedTuple):
    """A law that *is* the Bingham graph of eq. (6): ``tau`` (N) and ``c = 1/gamma`` (N s/m, ``0`` for Coulomb)."""

    threshold: float
    viscosity: float


class StepBound(NamedTuple):
    """A bound on what a law's step forms (contract point 9).

    ``value`` (``inf`` if it may overflow) is compared with
    :data:`lumped.model.oscillator.MAGNITUDE_LIMIT`; ``term`` names it in the message
    and ``parameter`` is the law's argument blamed when it alone is too large.
    """

    value: float
    term: str
    parameter: str


class SlipPiece(NamedTuple):
    """A linear piece of a slip curve: ``g(s) = a + b s`` for ``lo <= s <= hi`` (speeds, m/s)."""

    lo: float
    hi: float
    a: float
    b: float


class Slope(NamedTuple):
    """The slope ``g'(s)`` of a slip curve (N s/m) and a bound on its error (N s/m, ``0`` where exact)."""

    value: float
    error: float


#: The step of the central difference of :meth:`SlipLaw.slope`, relative to the speed: ``eps^(1/3)``, which
#: balances its truncation (``h^2 g^(3)/6``) against the rounding of ``g`` over ``h``.
SLOPE_STEP = float(np.finfo(float).eps) ** (1 / 3)


def central_slope(g: Callable[[float], float], speed: float) -> Slope:
    """``g'(speed)`` by a central difference of step ``h = SLOPE_STEP * speed``, with its error bound.

    With ``D(h) = (g(s+h) - g(s-h))/(2h) = g' + h^2 g^(3)/6 + O(h^4)``, ``|D(h) - D(2h)|`` is three times the
    leading truncation term of ``D(h)`` (a margin for the ``O(h^4)`` rest); each value of ``g``, computed to a
    few ulps (``4 eps |g|`` taken), adds ``4 eps max|g| / h`` to ``D(h)`` and as much to that estimate.  The
    steps are made exact in floating point (``(s + h) - s``), so only ``g``'s rounding enters.
    """
    s = float(speed)
    h = (s + SLOPE_STEP * s) - s
    values = [float(g(s + j * h)) for j in (-2, -1, 1, 2)]
    d1 = (values[2] - values[1]) / (2 * h)
    d2 = (values[3] - values[0]) / (4 * h)
    rounding = 8 * float(np.finfo(float).eps) * max(abs(v) for v in values) / h
    return Slope(d1, abs(d1 - d2) + rounding)


class SlipLaw(ABC):
    """A friction law: a graph in (rate ``u``, tension ``T``), symmetric (``T(-u) = -T(u)``).

    A new law must provide:

    1. ``static`` (N, >= 0): the stick interval at ``u = 0`` is ``[-static, static]``, the largest
       tension a stuck contact holds.
    2. ``slip(speed)``: the slip curve ``g(s)`` (N) at speeds ``s > 0`` (m/s), vectorised over NumPy
       arrays, finite and ``>= 0``; off zero rate ``T(u) = sgn(u) g(|u|)``.  Its limit at ``0+``
       (``slip_limit``, point 3) must not exceed ``static``.
    3. ``slip_limit``: ``g(0+)`` (N), the tension just after breaking away.
    4. ``fall``: the steepest fall of the slip curve, ``sup_s max(0, -g'(s))`` (N s/m): the bound
       that a backward-Euler step needs for uniqueness (one mass: ``m/dt + k dt > fall``;
       :func:`lumped.solvers.uniqueness.check_step`).  ``0`` for a curve that never falls.
    5. ``pieces()``: the slip curve as :class:`SlipPiece` s, in increasing speed, the last reaching
       ``inf``, if it is piecewise linear (so each phase has a closed form); ``None`` otherwise.

    What a solver may ask beyond points 1 to 5 is a method here with a default that any law meeting
    them satisfies; a law overrides one only to be faster or more exact.  No solver asks a law for
    its class.

    6. ``bingham_form()``: the :class:`~lumped.laws.BinghamForm` ``(tau, c)`` if the graph *is* the
       Bingham graph of eq. (6) (``g(s) = static + c s``), else ``None``.  Such a contact is run as
       the Bingham element it equals, bit for bit.
    7. ``slip_speed(z, sigma)``: the speed ``s > 0`` with ``g(s) + sigma s = z``, for ``z >
       slip_limit`` and ``sigma > fall`` (where it is unique): the slip step of a contact whose
       resolvent variable is ``z``.  The default is the linear pieces' closed form, else Brent's
       method on the bracket ``(0, z/sigma]`` (``g >= 0``), widened to ``2 z/sigma`` where rounding leaves
       ``g + sigma s - z`` below zero at its end.
    8. ``kernel_form()``: ``(code, parameters)`` for the compiled one-mass loop, or ``None`` (the
       default: the Python step runs it).
    9. ``slope(speed)``: the slope ``g'(s)`` at a speed ``s > 0`` as a :class:`Slope` (the value and a bound
       on its error): the linearisation of steady sliding (:mod:`lumped.drivers.cycles.equilibria`).  The
       default is the linear pieces' exact slope (the piece starting at ``s`` where two meet), else a central
       difference with its error bound (:func:`central_slope`); a law with a closed form overrides it.
    """

    static: float

    @abstractmethod
    def slip(self, speed: np.ndarray | float) -> np.ndarray | float:
        """The slip curve ``g(s)`` (N) at speeds ``s > 0`` (point 2)."""

    @property
    @abstractmethod
    def slip_limit(self) -> float:
        """``g(0+)`` (N), point 3."""

    @property
    @abstractmethod
    def fall(self) -> float:
        """The steepest fall of the slip curve (N s/m), point 4."""

    def pieces(self) -> tuple[SlipPiece, ...] | None:
        """The slip curve's linear pieces, or ``None`` (point 5)."""
        return None

    def tension(self, rate: np.ndarray | float) -> np.ndarray | float:
        """``T(u) = sgn(u) g(|u|)`` off zero rate, ``0`` at ``u = 0`` (for plots)."""
        u = np.asarray(rate, dtype=float)
        out = np.where(u != 0, np.sign(u) * self.slip(np.where(u != 0, np.abs(u), 1.0)), 0.0)
        return float(out) if np.ndim(rate) == 0 else out

    def force_interval(self, rate: float) -> tuple[float, float]:
        """The tensions compatible with ``rate``: the stick interval at 0, the slip tension elsewhere."""
        if rate == 0:
            return (-self.static, self.static)
        t = float(self.tension(rate))
        return (t, t)

    def bingham_form(self) -> BinghamForm | None:
        """``(tau, c)`` if the graph is the Bingham graph (point 6), else ``None``."""
        pieces = self.pieces()
        if pieces is None or len(pieces) != 1 or pieces[0].a != self.static:
            return None
        c = pieces[0].b
        return BinghamForm(self.static, c)

    def slip_speed(self, z: float, sigma: float) -> float:
        """The speed ``s > 0`` of ``g(s) + sigma s = z`` (point 7); ``z > slip_limit``, ``sigma > 0``."""
        pieces = self.pieces()
        if pieces is not None:
            for p in pieces:
                s = (z - p.a) / (p.b + sigma)
                if s <= p.hi:
                    return max(s, p.lo)
            return s  # the last piece reaches inf
        g = self.slip

        def h(s: float) -> float:
            return float(g(s)) + sigma * s - z

        # g >= 0 puts the root in (0, z/sigma]; where g(z/sigma) is below an ulp of z (it underflows to 0, say)
        # sigma (z/sigma) may round below z, so h < 0 there: twice that end, h >= z/2 > 0 whatever the rounding.
        hi = z / sigma
        return brentq(h, 0.0, hi if h(hi) >= 0 else 2.0 * hi)

    def kernel_form(self) -> tuple[int, tuple[float, ...]] | None:
        """``(code, parameters)`` of the compiled one-mass loop, or ``None`` (point 8)."""
        return None

    def slope(self, speed: float) -> Slope:
        """``g'(speed)`` (N s/m) and a bound on its error (point 9); ``speed > 0``."""
        pieces = self.pieces()
        if pieces is not None:
            return Slope(next(p.b for p in pieces if speed < p.hi or p.hi == math.inf), 0.0)
        return central_slope(self.slip, speed)

    @staticmethod
    def check(value: object, name: str) -> SlipLaw:
        """``value`` if it is a friction law, else a ``ValueError`` (the one test of "is this a law?")."""
        if not isinstance(value, SlipLaw):
            raise ValueError(f"{name} must be a lumped.laws.SlipLaw, got {type(value).__name__}")
        return value


class Dashpot(SlipLaw):
    """A dashpot given by its velocity-force graph ``v = phi(F_d)``.

    A new dashpot law must provide:

    1. ``velocity(force)``: the graph ``phi``, vectorised over NumPy arrays.
       It must be monotone non-decreasing with ``phi(0) = 0`` (a dashpot
       dissipates: ``F_d * v >= 0``).  It may be flat on an interval, where the
       force is not a function of the velocity.
    2. ``force_interval(velocity)``: the inverse graph, the closed interval
       ``(lo, hi)`` of forces compatible with a velocity (``lo == hi`` off the
       flat parts).  Used for plots and for the Filippov set of eq. (11).
    3. ``_resolvent_impl(predictor, eta)``: the solution ``F_d`` of
       ``F_d + eta*phi(F_d) = predictor`` together with ``v = phi(F_d)``,
       returned as a :class:`DashpotState`.  ``eta > 0`` is finite.
    4. ``threshold``: the largest ``|F_d|`` for which ``phi(F_d) = 0`` (the
       static band), ``0`` if there is none.
    5. Optionally ``slip_force(velocity)``: the force carried while slipping,
       vectorised, ``0`` at ``v = 0``.  The default inverts the graph point by
       point through ``force_interval``; a law with a closed form should
       override it (the event-driven integrator calls it at every stage).

    What a solver may ask of a law beyond its graph is a method here, with a
    generic default that any law meeting points 1 to 4 satisfies; a law
    overrides one only to be faster or more exact.  No solver asks a law for
    its class.

    6. ``bingham_form()``: the :class:`BinghamForm` ``(tau, c)`` if the law is
       the Bingham graph of eq. (6), else ``None`` (the default).  Only such a
       law has the closed forms: Algorithm 1's compiled loop
       (:mod:`lumped.solvers.backward_euler`), the exact solution
       (:mod:`lumped.solvers.exact`) and the textbook ODE
       (:mod:`lumped.solvers.textbook`).  Every other method needs only points 1 to 5.
    7. ``viscous_part()``: ``v -> F_d(v) - sgn(v) tau``, the slip force
       without its static part, as a scalar function continuous through
       ``v = 0`` (the event-driven integrator's right-hand side).  The default
       subtracts from :meth:`slip_force`.
    8. ``band_free_resolvent()``: the resolvent ``(u, v)`` of the graph with
       its band cut out, ``psi(u) = phi(u + sgn(u) tau)``, as a function of
       ``(predictor, eta)`` (the event-locating scheme's slip step).  The
       default is the bracketed root of :class:`~lumped.laws.MonotoneDashpot` on ``psi``.
    9. ``step_bound(force, speed, eta)``: a :class:`StepBound` on the
       magnitudes the law's resolvent forms for predictors ``|F~| <= force``
       and its slip force at speeds up to ``speed``, beyond those forces
       themselves (:func:`lumped.model.oscillator.check_magnitudes` refuses a run whose
       bound passes :data:`lumped.model.oscillator.MAGNITUDE_LIMIT`).  The default,
       ``0``, says it forms none: true of a resolvent whose root lies between
       ``0`` and ``F~`` and whose law is checked finite where it is called
       (:class:`~lumped.laws.MonotoneDashpot`); a law that multiplies (``c F~``, ``K
       |v|^n``) overrides it.

    The public :meth:`resolvent` checks its arguments and calls the hook.

    A dashpot is the monotone case of the law contract :class:`SlipLaw`,
    whose points it answers from the ones above: its stick interval and its
    slip limit are both the threshold, its slip curve is :meth:`slip_force`,
    it never falls, and it is piecewise linear where it has a Bingham form.
    """

    threshold: float

    # -- SlipLaw's points 1 to 5, from the dashpot's own -----------------------------------------
    @property
    def static(self) -> float:  # type: ignore[override]
        """The stick interval's half-width, the threshold (point 1 of :class:`SlipLaw`)."""
        return self.threshold

    def slip(self, speed: np.ndarray | float) -> np.ndarray | float:
        """``g(s) = slip_force(s)`` (point 2 of :class:`SlipLaw`; the law is odd)."""
        return self.slip_force(speed)

    @property
    def slip_limit(self) -> float:
        """The threshold: a monotone law slips on from the edge of its band (point 3)."""
        return self.threshold

    @property
    def fall(self) -> float:
        """``0``: a monotone law never falls (point 4)."""
        return 0.0

    def pieces(self) -> tuple[SlipPiece, ...] | None:
        """One piece ``tau + c s`` where the law has a Bingham form, else ``None`` (point 5)."""
        form = self.bingham_form()
        return None if form is None else (SlipPiece(0.0, math.inf, form.threshold, form.viscosity),)

    @abstractmethod
    def velocity(self, force: np.ndarray | float) -> np.ndarray | float:
        """Velocity ``phi(F_d)`` (m/s) carried by a dashpot force (N)."""

    @abstractmethod
    def force_interval(self, velocity: float) -> tuple[float, float]:
        """Interval of dashpot forces (N) compatible with ``velocity`` (m/s)."""

    @abstractmethod
    def _resolvent_impl(self, predictor: float, eta: float) -> DashpotState:
        """Solve ``F_d + eta*phi(F_d) = predictor`` (see the class docstring)."""

    def slip_force(self, velocity: np.ndarray | float) -> np.ndarray | float:
        """Force (N) while slipping at ``velocity`` (m/s), 0 at ``v = 0`` (point 5)."""

        def one(v: float) -> float:
            return 0.0 if v == 0 else self.force_interval(v)[0]

        if np.ndim(velocity) == 0:
            return one(float(velocity))
        return np.array([one(float(v)) for v in np.ravel(velocity)]).reshape(np.shape(velocity))

    def bingham_form(self) -> BinghamForm | None:
        """``(tau, c)`` if this law is the Bingham graph of eq. (6), else ``None`` (point 6)."""
        return None

    def viscous_part(self) -> Callable[[float], float]:
        """``v -> F_d(v) - sgn(v) tau`` (N) as a scalar function, ``0`` at ``v = 0`` (point 7)."""
        tau, slip = self.threshold, self.slip_force
        return lambda v: float(slip(v)) - math.copysign(tau, v) if v != 0 else 0.0

    def band_free_resolvent(self) -> Callable[[float, float], DashpotState]:
        """Resolvent ``(u, v)`` of ``u + eta psi(u) = predictor``, ``psi`` the law without its band (point 8).

        Notes
        -----
        In slip with direction ``s`` the dashpot force is ``F_d = s tau + u``
        with ``v = psi(u) = phi(u + sgn(u) tau)`` (``psi(0) = 0``): the graph
        with the band ``[-tau, tau]`` cut out.  ``psi`` is single valued,
        continuous and monotone, and it continues the slip branch through
        ``v = 0`` (the root search of a stop in :func:`lumped.solvers.event_capturing.event_capturing`
        evaluates the step past it).  The default is the bracketed root of
        :class:`lumped.laws.MonotoneDashpot` on ``psi``: ``psi`` checked as
        that class checks its law (:func:`lumped.laws.monotone_graph.check_monotone`
        with no threshold) and solved by the same
        :func:`lumped.laws.monotone_graph.resolvent`.
        """
        tau, phi = self.threshold, self.velocity

        def psi(u: float) -> float:
            return float(phi(u + math.copysign(tau, u))) if u != 0 else 0.0

        def checked(u: float) -> float:
            return monotone_graph.checked(psi, u)

        monotone_graph.check_monotone(checked, 0.0)
        return lambda predictor, eta: DashpotState(*monotone_graph.resolvent(checked, predictor, eta))

    def step_bound(self, force: float, speed: float, eta: float) -> StepBound:
        """Bound on the magnitudes the law's step forms for ``|F~| <= force`` (N), ``|v| <= speed`` (m/s) (point 9)."""
        return StepBound(0.0, "viscous term of the dashpot law", "dashpot")

    def resolvent(self, predictor: float, eta: float) -> DashpotState:
        """Implicit dashpot step: ``F_d = (I + eta*phi)^{-1}(predictor)``.

        Parameters
        ----------
        predictor : float, N
            ``F~`` of eq. (15b).
        eta : float, kg/s
            ``m/dt + k*dt``, the factor of eq. (15a) divided by ``dt/m``.

        Returns
        -------
        DashpotState
            Dashpot force and velocity at the new time level.
        """
        predictor = validate.finite("predictor", predictor)
        eta = validate.positive("eta", eta)
        return self._resolvent_impl(predictor, eta)

    @staticmethod
    def check(value: object, name: str, message: str = "{name} must be a Dashpot") -> Dashpot:
        """``value`` if it is a dashpot law, else a ``ValueError``.

        The one test of "is this a law?", so that no other module asks for a
        law's class: ``message`` is formatted with ``name`` and ``got``, the
        name of ``value``'s type.
        """
        if not isinstance(value, Dashpot):
            raise ValueError(message.format(name=name, got=type(value).__name__))
        return value
