"""The single-mass system's parameters, in one table.

Each :class:`Parameter` holds a name (the API's argument, and the command
line's option with ``--`` and dashes), its default (the paper's section 3),
its unit, the check of :mod:`lumped.numerics.validate` that accepts it (so the
messages are the API's), the command line's help text, and the range a
configuration file states for it (:class:`Range`).

The readers of :data:`PARAMETERS`:

* the command line (:mod:`lumped.cli`): the options of ``simulate`` and
  ``sweep``, their defaults and help, and their checks;
* the sweep (:mod:`lumped.drivers.sweep`): the per-row parameters
  (:data:`PER_ROW`), their defaults and checks;
* the configuration (:func:`lumped.studies.config.schema`): the rule and the words of
  every key that is one of these parameters (``mass``, ``x0_small``, ...);
* the tests, which hold ``Oscillator.bingham``'s and ``BinghamDashpot``'s
  defaults to the table's.

This module imports only :mod:`lumped.numerics.validate` and :mod:`lumped.numerics.sine`: every
layer may read it.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from types import MappingProxyType

from lumped.numerics import validate
from lumped.numerics.sine import MAX_ARGUMENT

__all__ = ["Range", "Parameter", "PARAMETERS", "PER_ROW", "shown"]

#: The largest double: a JSON-schema bound that excludes infinity.
_LARGEST = sys.float_info.max


@dataclass(frozen=True)
class Range:
    """An interval of floats, as a configuration file states it.

    Attributes
    ----------
    low : float or None
        Lower bound; ``None`` for ``-high``.
    open : bool
        Whether ``low`` itself is refused.
    high : float
        Upper bound (included); the largest double excludes infinity only.
    inf : str or None
        What ``inf`` means where it is accepted (``"Coulomb friction"``); then
        there is no upper bound.
    """

    low: float | None = None
    open: bool = False
    high: float = _LARGEST
    inf: str | None = None

    def rule(self) -> dict[str, object]:
        """The JSON-schema (draft 2020-12) rule of the interval."""
        out: dict[str, object] = {"type": "number"}
        low = -self.high if self.low is None else self.low
        out["exclusiveMinimum" if self.open else "minimum"] = low
        if self.inf is None:
            out["maximum"] = self.high
        return out

    def words(self) -> str:
        """The interval as a configuration message states it (``a finite number > 0``)."""
        bound = "" if self.low is None else f" {'>' if self.open else '>='} {shown(self.low)}"
        if self.inf is not None:
            return f"a number{bound}, or inf for {self.inf}"
        if self.high != _LARGEST:
            return f"a number from {shown(-self.high)} to {shown(self.high)}"
        return f"a finite number{bound}"

    def accepts(self, value: float) -> bool:
        """Whether ``value`` lies in the interval (NaN never does)."""
        if math.isnan(value) or (self.inf is None and not value <= self.high):
            return False
        low = -self.high if self.low is None else self.low
        return value > low if self.open else value >= low


@dataclass(frozen=True)
class Parameter:
    """One parameter of the single-mass system.

    Attributes
    ----------
    name : str
        The API's argument; the option is ``--`` + name with ``-`` for ``_``.
    default : float or int
        The paper's value (section 3), or none (zero forcing).
    unit : str
        SI unit; ``""`` for a count.
    check : callable
        ``check(name, value)`` of :mod:`lumped.numerics.validate`: the cleaned value,
        or a ``ValueError`` that begins with ``name``.
    help : str
        The command line's help, without the default.
    range : Range or None
        What a configuration file accepts; ``None`` for an integer (the
        configuration has no such key).
    """

    name: str
    default: float | int
    unit: str
    check: Callable[[str, object], float | int]
    help: str
    range: Range | None

    @property
    def option(self) -> str:
        """The command line's option (``--force-amplitude``)."""
        return "--" + self.name.replace("_", "-")

    @property
    def integer(self) -> bool:
        """Whether the value is a count (parsed as an integer)."""
        return isinstance(self.default, int)

    @property
    def default_text(self) -> str:
        """The default as the command line shows and parses it (``1e-4``, ``inf``)."""
        return shown(self.default)

    def describe(self) -> str:
        """What a configuration file accepts, with the unit: ``a finite number > 0 (kg)``."""
        assert self.range is not None, f"{self.name} has no range for a configuration"
        return f"{self.range.words()} ({self.unit})"


def shown(value: float) -> str:
    """A number as short as it is written by hand: ``1``, ``100``, ``1e-4``, ``inf``."""
    plain = f"{value:g}"
    mantissa, _, exponent = f"{value:.0e}".partition("e")
    short = f"{mantissa}e{int(exponent)}" if exponent else plain
    return short if float(short) == value and len(short) < len(plain) else plain


_POSITIVE = Range(0.0, open=True)
_FINITE = Range()

PARAMETERS: Mapping[str, Parameter] = MappingProxyType(
    {
        p.name: p
        for p in (
            Parameter("mass", 1.0, "kg", validate.positive, "mass m > 0 (kg)", _POSITIVE),
            Parameter("stiffness", 100.0, "N/m", validate.positive, "spring constant k > 0 (N/m)", _POSITIVE),
            Parameter(
                "gamma",
                1.0,
                "m/(N s)",
                validate.positive_or_inf,
                "Bingham slope gamma > 0 (m/(N s)); inf for Coulomb",
                Range(0.0, open=True, inf="Coulomb friction"),
            ),
            Parameter("threshold", 1.0, "N", validate.non_negative, "static threshold mu_s N_f >= 0 (N)", Range(0.0)),
            Parameter("x0", 0.0, "m", validate.finite, "initial displacement (m)", _FINITE),
            Parameter("v0", 0.0, "m/s", validate.finite, "initial velocity (m/s)", _FINITE),
            Parameter("force_amplitude", 0.0, "N", validate.finite, "forcing amplitude P (N)", _FINITE),
            Parameter("force_omega", 0.0, "rad/s", validate.finite, "forcing angular frequency (rad/s)", _FINITE),
            Parameter("force_phase", 0.0, "rad", validate.sine_phase, "forcing phase (rad)", Range(high=MAX_ARGUMENT)),
            Parameter(
                "force_until",
                math.inf,
                "s",
                validate.time_or_inf,
                "time after which the force is zero (s)",
                Range(0.0, inf="a forcing never switched off"),
            ),
            Parameter("t_end", 2.0, "s", validate.positive, "final time > 0 (s)", _POSITIVE),
            Parameter("dt", 1e-4, "s", validate.positive, "time step > 0 (s)", _POSITIVE),
            Parameter(
                "save_every",
                1,
                "",
                validate.stride,
                f"keep every K-th grid point (1 to {shown(validate.MAX_STEPS)})",
                None,
            ),
        )
    }
)
"""Every parameter of ``python -m lumped simulate``, in the order of its help."""

#: The parameters that describe one run of the system (what a sweep may vary,
#: one value per row); the rest set the time grid and what is kept of it.
PER_ROW = tuple(name for name in PARAMETERS if name not in ("t_end", "dt", "save_every"))
