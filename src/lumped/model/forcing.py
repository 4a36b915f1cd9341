"""External forcing ``F(t)``: the load contract (:class:`Forcing`) and the load types, each a small frozen dataclass.

* :class:`SwitchedSine`: ``P sin(omega t + phi)`` for ``t <= t_off`` and ``0``
  afterwards, which covers both forcings of the paper, eqs. (17a) and (17b);
* :class:`Constant`: a step load ``P`` switched on at ``start`` and off after ``until``;
* :class:`Table`: a sampled history (a measured load, a ground-acceleration
  record), linearly interpolated, zero outside its samples;
* :class:`LoadSum`: several loads on one mass, added, as one callable.

Any other forcing may be passed to the API as a Python callable of time
(:func:`evaluate` calls it).  A ground acceleration ``a_g(t)`` is written as
the loads ``-m a_g(t)`` on every mass (``scaled(-m)`` of its type): positions
and velocities are then relative to the ground.

Solvers and drivers ask a load what it provides through :class:`Forcing`'s
contract, or through this module's functions that also answer for a plain
callable (:func:`closed_form`, :func:`as_sine`, :func:`jumps`,
:func:`check_span`, :func:`parameters`, :func:`kind_of`); no code outside this
module asks a load for its class.  The methods whose closed forms need the
forcing's formula take its :class:`SineForm`; the one-mass ones take it as a
:class:`SwitchedSine` on from ``t = 0`` (:func:`as_sine`), which writes a
:class:`Constant` on from ``t = 0`` as one (``P sin(pi/2) = P`` exactly).
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from lumped.numerics import validate
from lumped.numerics.sine import sin, sin_array

__all__ = [
    "Constant",
    "Forcing",
    "LoadSum",
    "SineForm",
    "SwitchedSine",
    "Table",
    "as_sine",
    "check_span",
    "check_spans",
    "closed_form",
    "evaluate",
    "first_bad_sample",
    "history",
    "jumps",
    "kind_of",
    "one_force",
    "parameters",
    "sine_form",
    "validate_force",
]


class SineForm(NamedTuple):
    """A load's closed form (:class:`Forcing`, point 3): ``amplitude * sin(omega t + phase)`` for
    ``start <= t <= until``, else ``0``.

    ``amplitude`` (N), ``omega`` (rad/s), ``phase`` (rad), ``start`` and ``until`` (s, ``until = inf`` for
    never).  A step load is the form with ``omega = 0`` and ``phase = pi/2`` (``sin(pi/2)`` is exactly 1
    in :mod:`math` and in :mod:`lumped.numerics.sine`, tested).
    """

    amplitude: float
    omega: float
    phase: float
    start: float
    until: float

    @property
    def switch_times(self) -> tuple[float, ...]:
        """``start`` and ``until`` where finite, sorted."""
        return _finite_sorted({self.start, self.until})

    def on_after(self, t: float) -> bool:
        """True if the load is on just after ``t`` (s): a phase beginning at ``t`` feels it."""
        return self.start <= t < self.until


class Forcing:
    """A prescribed function of time: the force of a load (N).

    Written for a load, the contract speaks only of a quantity given as a function of time, so that a
    driven point's velocity (m/s) can later be given by the same types, asked the same questions.  A new
    kind of load is one frozen dataclass in this module deriving from this class; solvers and drivers
    ask it through the points below (or this module's functions of the same names, which also answer
    for a plain callable of time), never by its class.  A load must provide:

    1. ``__call__(t)``: its value at the times ``t``, vectorised: an array of the shape of ``t`` for an
       array, a ``float`` for a number; finite for every finite ``t >= 0``.  Every method evaluates a
       load through this (:func:`evaluate`), so one that has a closed form (point 3) must give the
       form's values here bit for bit.
    2. ``scaled(factor)``: ``factor`` times the load, of the same kind, for a kind a system file may
       give as a ground acceleration ``a_g`` (run as the loads ``-m a_g``); :class:`LoadSum`, which only
       the API builds, has none.

    What a method may ask beyond the values is a member here, with a default that says "nothing
    more": a load overrides one only where it can say more.

    3. ``closed_form()``: the :class:`SineForm` the load equals at every ``t >= 0``, or ``None`` (the
       default).  The exact methods run only loads that have one: the piecewise-linear network
       solvers take any form; the one-mass exact, event-driven and event-locating solvers and
       Algorithm 1's compiled sine loop take a form on from ``t = 0`` as a :class:`SwitchedSine`
       (:meth:`sine`).
    4. ``sine()``: the load as one :class:`SwitchedSine` at every ``t >= 0``, or ``None``.  The default
       builds it from :meth:`closed_form` when the form starts at ``t = 0``; a sine returns itself.
    5. ``switch_times``: the finite times, sorted, at which the value may jump (a stepper or an exact
       solver breaks its phases there); ``()`` (the default) for a load continuous in time.
    6. ``check_span(t_last)``: refuse, in one ``ValueError``, a run to ``t_last`` (s) over which the
       load cannot be evaluated exactly (a sine's argument beyond the range of
       :mod:`lumped.numerics.sine`).  The default accepts every span.
    7. ``parameters``: the names of the numeric fields the sensitivities and the fit may vary, as a
       system file names them after ``force.`` (``amplitude``, ``omega``, ``phase``, ``until`` for a
       sine), ``()`` (the default) for none.  Each is a dataclass field that
       :func:`dataclasses.replace` sets and ``__post_init__`` checks again; the exact sensitivities
       differentiate the closed form (point 3) in them.
    8. ``description``: the load in a few words for messages (``a sine``, ``a table``).
    9. ``integral(t)``: the integral of the value from ``0`` to the times ``t``, vectorised, in closed
       form; ``None`` (the default) if the kind has none.  A driven point's velocity must have one: its
       position is this integral (:class:`lumped.model.network.Driver`).
    10. ``initial_slope()``: the value's rate of change just after ``t = 0`` (a driven point's
        acceleration there, for the consistent initial forces); ``None`` (the default) if unknown.
    """

    __slots__ = ()

    def closed_form(self) -> SineForm | None:
        """The :class:`SineForm` this load equals at every ``t >= 0``, or ``None`` (point 3)."""
        return None

    def sine(self) -> SwitchedSine | None:
        """This load as one :class:`SwitchedSine` at every ``t >= 0``, or ``None`` (point 4)."""
        form = self.closed_form()
        if form is None or form.start != 0:
            return None
        return SwitchedSine(form.amplitude, form.omega, form.phase, form.until)

    @property
    def switch_times(self) -> tuple[float, ...]:
        """The finite times (s), sorted, at which the value may jump (point 5)."""
        return ()

    def check_span(self, t_last: float) -> None:
        """Refuse a run to ``t_last`` (s) over which the load cannot be evaluated exactly (point 6)."""

    @property
    def parameters(self) -> tuple[str, ...]:
        """The numeric fields the sensitivities and the fit may vary (point 7)."""
        return ()

    @property
    def description(self) -> str:
        """The load in words, for messages (point 8)."""
        return "a load"

    def integral(self, t: np.ndarray | float) -> np.ndarray | float | None:
        """The integral of the value from 0 to ``t`` (point 9), or ``None``."""
        return None

    def initial_slope(self) -> float | None:
        """The value's rate of change just after ``t = 0`` (point 10), or ``None``."""
        return None


@dataclass(frozen=True)
class SwitchedSine(Forcing):
    """``F(t) = amplitude * sin(omega*t + phase)`` for ``t <= until``, else 0.

    Parameters
    ----------
    amplitude : float, N
    omega : float, rad/s
    phase : float, rad
        Within ``+-MAX_ARGUMENT = 2e8`` (:mod:`lumped.numerics.sine`); a run also
        needs ``|omega| t + |phase|`` in that range (:meth:`check_span`).
    until : float, s
        Time ``t_off >= 0`` after which the force is zero; ``inf`` for never.
    """

    amplitude: float = 0.0
    omega: float = 0.0
    phase: float = 0.0
    until: float = math.inf

    def __post_init__(self) -> None:
        for name, check in (
            ("amplitude", validate.finite),
            ("omega", validate.finite),
            ("phase", validate.sine_phase),
            ("until", validate.time_or_inf),
        ):
            object.__setattr__(self, name, check("force_" + name, getattr(self, name)))

    def __call__(self, t: np.ndarray | float) -> np.ndarray | float:
        """The force at the times ``t`` (N), with the kernels' sine (:func:`lumped.numerics.sine.sin_array`), bit for bit."""
        on = self.amplitude * sin_array(self.omega * np.asarray(t, dtype=float) + self.phase)
        out = np.where(np.asarray(t) <= self.until, on, 0.0)
        return float(out) if np.ndim(out) == 0 else out

    def check_span(self, t_last: float) -> None:
        """Refuse a run to ``t_last`` (s) whose argument ``omega t + phase`` leaves the sine's range.

        See :func:`lumped.numerics.validate.sine_argument`, the one bound every method shares.
        """
        validate.sine_argument(self.omega, self.phase, min(t_last, self.until))

    def closed_form(self) -> SineForm:
        """Its own formula, on from ``t = 0`` (:class:`Forcing`, point 3)."""
        return SineForm(self.amplitude, self.omega, self.phase, 0.0, self.until)

    def sine(self) -> SwitchedSine:
        """Itself (:class:`Forcing`, point 4)."""
        return self

    @property
    def switch_times(self) -> tuple[float, ...]:
        """``until`` where finite: the force goes off there."""
        return _finite_sorted({self.until})

    @property
    def parameters(self) -> tuple[str, ...]:
        """``amplitude``, ``omega``, ``phase``, ``until``."""
        return ("amplitude", "omega", "phase", "until")

    @property
    def description(self) -> str:
        """``a sine``."""
        return "a sine"

    def integral(self, t: np.ndarray | float) -> np.ndarray | float:
        """``P (cos(phase) - cos(omega t + phase)) / omega`` up to ``until`` (``P sin(phase) t`` at ``omega = 0``)."""
        end = np.minimum(np.asarray(t, dtype=float), self.until)
        if self.omega == 0:
            out = self.amplitude * math.sin(self.phase) * end
        else:
            out = self.amplitude * (math.cos(self.phase) - np.cos(self.omega * end + self.phase)) / self.omega
        return float(out) if np.ndim(out) == 0 else out

    def initial_slope(self) -> float:
        """``P omega cos(phase)`` (0 if the sine is off from the start)."""
        return 0.0 if self.until == 0 else self.amplitude * self.omega * math.cos(self.phase)

    @property
    def is_zero(self) -> bool:
        """True when the force vanishes at all times."""
        return self.amplitude == 0 or (self.omega == 0 and sin(self.phase) == 0)

    def canonical(self) -> tuple[float, float, float]:
        """``(P, omega, phase)`` with ``P >= 0`` and ``omega >= 0``, same function."""
        p, w, ph = self.amplitude, self.omega, self.phase
        if w < 0:  # sin(-|w| t + ph) = sin(|w| t - ph + pi)
            w, ph = -w, math.pi - ph
        if p < 0:
            p, ph = -p, ph + math.pi
        return p, w, math.remainder(ph, 2 * math.pi)

    def scaled(self, factor: float) -> SwitchedSine:
        """``factor`` times this force (``-m a_g`` from a ground acceleration ``a_g``)."""
        return SwitchedSine(factor * self.amplitude, self.omega, self.phase, self.until)


@dataclass(frozen=True)
class Constant(Forcing):
    """``F(t) = value`` for ``start <= t <= until``, else 0: a step load, switched off after ``until``.

    Parameters
    ----------
    value : float, N
    start : float, s
        Time ``>= 0`` at which the load comes on (a system file's ``from``).
    until : float, s
        Time after which it is zero, later than ``start``; ``inf`` for never.
    """

    value: float
    start: float = 0.0
    until: float = math.inf

    def __post_init__(self) -> None:
        object.__setattr__(self, "value", validate.finite("value", self.value))
        object.__setattr__(self, "start", validate.non_negative("start", self.start))
        object.__setattr__(self, "until", validate.time_or_inf("until", self.until))
        if not self.until > self.start:
            raise ValueError(f"until must be later than start ({self.start:g} s), got {self.until:g}")

    def __call__(self, t: np.ndarray | float) -> np.ndarray | float:
        """The force at the times ``t`` (N)."""
        t = np.asarray(t, dtype=float)
        out = np.where((t >= self.start) & (t <= self.until), self.value, 0.0)
        return float(out) if out.ndim == 0 else out

    def integral(self, t: np.ndarray | float) -> np.ndarray | float:
        """``value`` times the time spent on, from 0 to ``t``."""
        on = np.clip(np.asarray(t, dtype=float) - self.start, 0.0, self.until - self.start)
        out = self.value * on
        return float(out) if np.ndim(out) == 0 else out

    def initial_slope(self) -> float:
        """0: the value is constant while on."""
        return 0.0

    def scaled(self, factor: float) -> Constant:
        """``factor`` times this force."""
        return Constant(factor * self.value, self.start, self.until)

    def closed_form(self) -> SineForm:
        """``value sin(0 t + pi/2)`` on ``[start, until]``: ``sin(pi/2)`` is exactly 1, so the form's values
        are the load's bit for bit (:class:`Forcing`, point 3)."""
        return SineForm(self.value, 0.0, math.pi / 2, self.start, self.until)

    @property
    def switch_times(self) -> tuple[float, ...]:
        """``start`` and ``until`` where finite."""
        return _finite_sorted({self.start, self.until})

    @property
    def parameters(self) -> tuple[str, ...]:
        """``value`` and ``until`` (``start`` is a system file's ``from``, not varied)."""
        return ("value", "until")

    @property
    def description(self) -> str:
        """``a constant``, with the time it comes on if later than 0."""
        return "a constant" + (f" switched on at t = {self.start:g} s" if self.start else "")


@dataclass(frozen=True, eq=False)
class Table(Forcing):
    """Samples ``(t_i, F_i)``, linearly interpolated, zero before ``t_0`` and after the last ``t_i``.

    Parameters
    ----------
    t : array_like, (n,), s
        At least two finite times, strictly increasing.
    values : array_like, (n,), N
        Finite values at those times.

    Between two samples the force is ``np.interp``'s straight line, so a
    table of equal values gives that value itself, bit for bit.
    """

    t: np.ndarray
    values: np.ndarray

    def __post_init__(self) -> None:
        t, values = _samples("t", self.t), _samples("values", self.values)
        if t.shape != values.shape:
            raise ValueError(f"values must have one value per time: {values.size} values for {t.size} times")
        if t.size < 2:
            raise ValueError(f"t must hold at least two times, got {t.size}")
        bad = first_bad_sample(t, values)
        if bad is not None:
            raise ValueError(f"{bad[1]} at index {bad[0]}")
        for name, array in (("t", t), ("values", values)):
            array.setflags(write=False)
            object.__setattr__(self, name, array)

    def __call__(self, t: np.ndarray | float) -> np.ndarray | float:
        """The force at the times ``t`` (N)."""
        out = np.interp(np.asarray(t, dtype=float), self.t, self.values, left=0.0, right=0.0)
        return float(out) if np.ndim(out) == 0 else out

    def integral(self, t: np.ndarray | float) -> np.ndarray | float:
        """The exact integral of the straight lines between samples (the trapezoids), from 0 to ``t``."""
        tt, ff = self.t, self.values
        if tt[0] > 0:  # zero before the first sample; the integral counts from t = 0
            tt, ff = np.concatenate(([0.0], tt)), np.concatenate(([0.0], ff))
        cumulative = np.concatenate(([0.0], np.cumsum(np.diff(tt) * (ff[1:] + ff[:-1]) / 2)))
        x = np.clip(np.asarray(t, dtype=float), tt[0], tt[-1])
        k = np.clip(np.searchsorted(tt, x, side="right") - 1, 0, tt.size - 2)
        here = np.interp(x, tt, ff)
        out = cumulative[k] + (x - tt[k]) * (ff[k] + here) / 2
        if tt[0] < 0:  # samples before t = 0: count from 0
            out = out - self._from_start(tt, ff, cumulative)
        return float(out) if np.ndim(out) == 0 else out

    @staticmethod
    def _from_start(tt: np.ndarray, ff: np.ndarray, cumulative: np.ndarray) -> float:
        """The integral from the first sample to ``t = 0``."""
        k = int(np.clip(np.searchsorted(tt, 0.0, side="right") - 1, 0, tt.size - 2))
        here = float(np.interp(0.0, tt, ff))
        return float(cumulative[k] + (0.0 - tt[k]) * (ff[k] + here) / 2)

    def initial_slope(self) -> float:
        """The slope of the straight line holding ``t = 0`` (0 before the first sample)."""
        if not self.t[0] <= 0 < self.t[-1]:
            return 0.0
        k = int(np.searchsorted(self.t, 0.0, side="right") - 1)
        return float((self.values[k + 1] - self.values[k]) / (self.t[k + 1] - self.t[k]))

    def scaled(self, factor: float) -> Table:
        """``factor`` times this force (the values scaled, the times kept)."""
        return Table(self.t, factor * self.values)

    @property
    def switch_times(self) -> tuple[float, ...]:
        """The first and last sample times: the force is zero outside them."""
        return _finite_sorted({float(self.t[0]), float(self.t[-1])})

    @property
    def description(self) -> str:
        """``a table``."""
        return "a table"


def _samples(name: str, raw: object) -> np.ndarray:
    """``raw`` as a new one-dimensional float array, or a ``ValueError`` naming ``name``."""
    if not _real_array(raw) or np.ndim(raw) != 1:
        raise ValueError(f"{name} must be a one-dimensional array of real numbers, got {_short(raw)}")
    return np.array(raw, dtype=float)


def first_bad_sample(
    t: np.ndarray, values: np.ndarray, names: tuple[str, str] = ("t", "values")
) -> tuple[int, str] | None:
    """The first sample a :class:`Table` refuses, as ``(index, why)``; ``None`` if every one is good.

    ``why`` names the column (``names``): a time or value that is not finite,
    or a time that does not follow the one before it.
    """
    for i, (ti, vi) in enumerate(zip(t.tolist(), values.tolist())):
        if not math.isfinite(ti):
            return i, f"{names[0]} must be finite, got {ti!r}"
        if not math.isfinite(vi):
            return i, f"{names[1]} must be finite, got {vi!r}"
        if i and not ti > t[i - 1]:
            return i, f"{names[0]} must increase strictly, got {ti!r} after {float(t[i - 1])!r}"
    return None


@dataclass(frozen=True)
class LoadSum(Forcing):
    """Several forces on one mass, added in their order: one callable of time.

    The sum is formed as :meth:`lumped.model.network.Network.load_table`
    forms it (``0 + F_1 + F_2 + ...``), so a one-mass system runs the same
    numbers as a single force or as a network.
    """

    forces: tuple

    def __post_init__(self) -> None:
        forces = tuple(self.forces) if isinstance(self.forces, (list, tuple)) else None
        if not forces or any(validate_force(f) is None for f in forces):
            raise ValueError("forces must be a non-empty sequence of forces (callables of time)")
        object.__setattr__(self, "forces", forces)

    def __call__(self, t: np.ndarray | float) -> np.ndarray | float:
        """The summed force at the times ``t`` (N)."""
        times = np.asarray(t, dtype=float)
        flat = times.reshape(-1)
        out = np.zeros_like(flat)
        for force in self.forces:
            out += evaluate(force, flat)
        return float(out[0]) if times.ndim == 0 else out.reshape(times.shape)

    @property
    def switch_times(self) -> tuple[float, ...]:
        """Its forces' together."""
        return _finite_sorted({t for f in self.forces for t in jumps(f)})

    def check_span(self, t_last: float) -> None:
        """Each of its forces' check."""
        for force in self.forces:
            check_span(force, t_last)

    @property
    def description(self) -> str:
        """``a sum of N loads``."""
        return f"a sum of {len(self.forces)} loads"


def history(value: object) -> Forcing | None:
    """``value`` if it is a prescribed function of time of this module (a :class:`Forcing`), else ``None``."""
    return value if isinstance(value, Forcing) else None


def one_force(forces: Sequence[object]) -> object:
    """The forces on one mass as one: ``None`` for none, the force itself for one, else their :class:`LoadSum`."""
    if not forces:
        return None
    return forces[0] if len(forces) == 1 else LoadSum(tuple(forces))


def _finite_sorted(times: set[float]) -> tuple[float, ...]:
    return tuple(sorted(t for t in times if math.isfinite(t)))


def closed_form(force: object) -> SineForm | None:
    """``force``'s :class:`SineForm` (:class:`Forcing`, point 3); ``None`` for none or a plain callable."""
    return force.closed_form() if isinstance(force, Forcing) else None


def as_sine(force: object) -> SwitchedSine | None:
    """``force`` as one :class:`SwitchedSine` at every ``t >= 0`` (:class:`Forcing`, point 4), else ``None``."""
    return force.sine() if isinstance(force, Forcing) else None


def sine_form(force: object) -> object:
    """``force`` as a :class:`SwitchedSine` where it is one at every ``t >= 0`` (:func:`as_sine`), else ``force``.

    ``Constant(P, 0, t_off)`` is ``SwitchedSine(P, 0, pi/2, t_off)`` at every
    ``t >= 0``, value for value: ``sin(pi/2)`` is exactly 1 in
    :mod:`lumped.numerics.sine` (tested), so the methods that need a sine's
    formula run it.
    """
    sine = as_sine(force)
    return force if sine is None else sine


def jumps(force: object) -> tuple[float, ...]:
    """The finite times, sorted, at which ``force`` may jump (:class:`Forcing`, point 5): a sine's
    ``until``, a constant's ``start`` and ``until``, a table's first and last times (it is zero outside
    them), a sum's together; none for any other callable (taken as continuous)."""
    return force.switch_times if isinstance(force, Forcing) else ()


def check_span(force: object, t_last: float) -> None:
    """Refuse a run to ``t_last`` (s) over which ``force`` cannot be evaluated exactly (:class:`Forcing`,
    point 6); a plain callable is not checked."""
    if isinstance(force, Forcing):
        force.check_span(t_last)


def check_spans(loads: Sequence[object], drivers: Sequence[object], t_last: float) -> None:
    """Refuse a run to ``t_last`` (s) over which a network's load or a driven point's velocity cannot be
    evaluated exactly (:func:`check_span` of each): the one check of a network's histories before any step.

    A driver's velocity is refused in the words of a load's, naming the driver: a sine beyond the range
    would give NaN positions mid-run (its integral is a cosine of the same argument).
    """
    for load in loads:
        check_span(load.force, t_last)  # type: ignore[attr-defined]
    for driver in drivers:
        try:
            check_span(driver.history, t_last)  # type: ignore[attr-defined]
        except ValueError as err:
            reason = str(err).split(": ", 1)[-1].replace("force_", "")
            raise ValueError(f"driver {driver.name!r} velocity: {reason}") from None  # type: ignore[attr-defined]


def parameters(force: object) -> tuple[str, ...]:
    """The numeric fields of ``force`` that the sensitivities and the fit may vary (:class:`Forcing`, point 7)."""
    return force.parameters if isinstance(force, Forcing) else ()


def kind_of(force: object) -> str:
    """A force in words, for messages (:class:`Forcing`, point 8): ``a sine``, ``a table``, ``a sum of 2
    loads``, ...; ``a callable of time`` for a plain callable."""
    return force.description if isinstance(force, Forcing) else "a callable of time"


def validate_force(force: object) -> SwitchedSine | Callable[[np.ndarray], np.ndarray] | None:
    """Return ``force`` if it is ``None``, a :class:`SwitchedSine` or a callable."""
    if force is None or callable(force):
        return force  # type: ignore[return-value]
    raise ValueError(f"force must be a SwitchedSine, a callable of time or None, got {type(force).__name__}")


def _numbers(raw: object, shape: tuple[int, ...]) -> np.ndarray | None:
    """``raw`` as a float array of ``shape`` (a number is broadcast), else ``None``."""
    try:
        values = np.asarray(raw, dtype=float)
    except (TypeError, ValueError, OverflowError):
        return None
    if values.ndim == 0 and isinstance(raw, (numbers.Real, np.ndarray)) and not isinstance(raw, bool):
        return np.full(shape, float(values))
    return values if values.shape == shape and _real_array(raw) else None


def _real_array(raw: object) -> bool:
    """True for a real numeric array (not strings, booleans or objects)."""
    kind = np.asarray(raw).dtype.kind
    return kind in "iuf"


def _at(force: Callable[[float], object], t: float) -> float:
    """``force(t)`` as a float, or a ``ValueError`` that says what went wrong."""
    try:
        raw = force(t)
    except Exception as err:  # a user's callable: report its failure, named
        raise ValueError(f"force raised {type(err).__name__} at t = {t:.6g} s: {err}") from None
    if isinstance(raw, bool) or not isinstance(raw, (numbers.Real, np.ndarray)):
        raise ValueError(f"force must return a real number, got {_short(raw)} at t = {t:.6g} s")
    values = np.asarray(raw)
    if values.size != 1 or values.dtype.kind not in "iuf":
        raise ValueError(f"force must return one real number per time, got {_short(raw)} at t = {t:.6g} s")
    return float(values.reshape(()))


def _short(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def evaluate(force: Callable[[np.ndarray], np.ndarray] | None, t: np.ndarray) -> np.ndarray:
    """Values of a forcing callable on the times ``t`` (zeros for ``None``).

    A callable that accepts an array and returns an array of the same shape
    (or one number, taken as constant) is called once; any other is called
    point by point.  The values must be real and finite.

    Raises
    ------
    ValueError
        Naming ``force``: not callable, an exception inside it, a value that
        is not a real number, or a non-finite value (with the time).
    """
    if force is None:
        return np.zeros_like(t)
    force = validate_force(force)
    try:
        values = _numbers(force(t), t.shape)
    except Exception:  # a scalar-only callable: call it point by point below
        values = None
    if values is None:
        values = np.array([_at(force, float(s)) for s in t])
    bad = ~np.isfinite(values)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"force must return finite values; got {values[i]} at t = {t[i]:.6g} s")
    return values
