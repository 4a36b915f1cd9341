"""Argument checks shared by the API and the command line.

Every helper returns the cleaned value or raises :class:`ValueError` with a
one-line message that *begins with the argument's name* and states the
accepted range.  The command line parses its strings with :func:`parse_float`
and :func:`parse_int`, then calls the same checks, and prints the message with
the argument's name replaced by the option's; so the wording here is the
user-facing wording of both.

The API is strict: a number is an ``int``, a ``float`` or a NumPy real scalar;
strings and booleans are refused, not converted.
"""

from __future__ import annotations

import math
import numbers
import sys
from typing import NamedTuple

import numpy as np

from lumped.numerics.sine import MAX_ARGUMENT

#: Largest number of time steps a single run may take (a bound, so that no run
#: can be made to loop for hours by a typo in ``--dt``).
MAX_STEPS = 2_000_000_000
#: Largest memory, in bytes, that the saved output of one run may occupy.
MAX_OUTPUT_BYTES = 4 * 1024**3
#: Longest estimated run time, in seconds, that a single run may take.
MAX_SECONDS = 600.0
#: Smallest normal double, ``2^-1022`` (about 2.2e-308).  A positive value
#: below it is subnormal and keeps fewer than 16 significant digits (``1e-320``
#: is stored as ``9.99989e-321``): :func:`positive` and :func:`positive_or_inf`
#: refuse it.
TINY = sys.float_info.min


#: The loops of backward Euler (the ``kernel`` of :func:`lumped.backward_euler` and
#: :func:`lumped.kernels.batched.batch_backward_euler`): ``"auto"`` is the compiled one if built.
KERNELS = ("auto", "compiled", "python")


def kernel(value: object, built: str, what: str) -> str:
    """The loop ``value`` names, ``"compiled"`` or ``"python"``; ``built`` is the one ``"auto"`` takes.

    Raises a ``ValueError`` for a name not in :data:`KERNELS`, or for
    ``"compiled"`` when ``what`` (the C kernel) was not built.
    """
    if not isinstance(value, str) or value not in KERNELS:
        names = f"{', '.join(map(repr, KERNELS[:-1]))} or {KERNELS[-1]!r}"
        raise ValueError(f"kernel must be {names}, got {value!r}")
    if value == "compiled" and built != "compiled":
        raise ValueError(f"kernel: 'compiled' requested but {what} was not built")
    return built if value == "auto" else value


def _show(value: object) -> str:
    """``repr`` shortened to one readable line (a 400-digit integer included)."""
    text = repr(value)
    return text if len(text) <= 40 else text[:20] + "..." + text[-8:]


def _as_float(name: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name} must be a real number, got {_show(value)}")
    try:
        out = float(value)
    except OverflowError:
        raise ValueError(f"{name} is beyond double precision (about 1.8e308): {_show(value)}") from None
    if math.isnan(out):
        raise ValueError(f"{name} must be a real number, got nan")
    return out


def finite(name: str, value: object) -> float:
    """Return ``value`` as a finite float."""
    out = _as_float(name, value)
    if not math.isfinite(out):
        raise ValueError(f"{name} must be finite, got {out}")
    return out


def positive(name: str, value: object) -> float:
    """Return ``value`` as a finite float > 0, not subnormal (at least :data:`TINY`)."""
    out = finite(name, value)
    if out <= 0:
        raise ValueError(f"{name} must be > 0 and finite, got {out}")
    return _normal(name, out)


def _normal(name: str, out: float) -> float:
    if out < TINY:
        raise ValueError(
            f"{name}: {out:.3g} is below the smallest normal double, {TINY:.3g}, "
            "where fewer than 16 significant digits remain"
        )
    return out


def non_negative(name: str, value: object) -> float:
    """Return ``value`` as a finite float >= 0."""
    out = finite(name, value)
    if out < 0:
        raise ValueError(f"{name} must be >= 0 and finite, got {out}")
    return out


def positive_or_inf(name: str, value: object) -> float:
    """Return ``value`` as a float in [:data:`TINY`, inf]."""
    out = _as_float(name, value)
    if out <= 0:
        raise ValueError(f"{name} must be > 0 (inf allowed), got {out}")
    return _normal(name, out)


def time_or_inf(name: str, value: object) -> float:
    """Return ``value`` as a float in [0, inf]."""
    out = _as_float(name, value)
    if out < 0:
        raise ValueError(f"{name} must be >= 0 (inf allowed), got {out}")
    return out


def positive_int(name: str, value: object) -> int:
    """Return ``value`` as an int >= 1 (a Python or NumPy integer, any size)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise ValueError(f"{name} must be an integer >= 1, got {_show(value)}")
    out = int(value)
    if out < 1:
        raise ValueError(f"{name} must be an integer >= 1, got {out}")
    return out


def stride(name: str, value: object) -> int:
    """Return ``value`` as a stride of saved grid points: an int from 1 to ``MAX_STEPS``.

    No run takes more than ``MAX_STEPS`` steps, so a larger stride could only
    save ``t = 0`` and the last point, which ``MAX_STEPS`` already does: it is
    refused (a typo, like a ``dt`` that would need more steps than that).
    """
    out = positive_int(name, value)
    if out > MAX_STEPS:
        raise ValueError(f"{name} must be an integer from 1 to {MAX_STEPS} (the most steps of a run), got {_show(out)}")
    return out


def parse_float(name: str, text: str) -> float:
    """A command-line number: decimal or ``inf``/``-inf``; ``1e400`` is refused.

    The range checks are left to :func:`finite` and its siblings.
    """
    word = text.strip().lower()
    if not word:
        raise ValueError(f"{name} expects a number, got an empty value")
    if word.lstrip("+-") in ("inf", "infinity"):
        return -math.inf if word.startswith("-") else math.inf
    try:
        out = float(word)
    except ValueError:
        raise ValueError(f"{name} must be a number, got {text!r}") from None
    if math.isinf(out):
        raise ValueError(f"{name}: {text} is beyond double precision (about 1.8e308); write inf for infinity")
    return out


def parse_int(name: str, text: str) -> int:
    """A command-line integer >= 1 (decimal digits, any size)."""
    word = text.strip().lstrip("+")
    if not (word.isascii() and word.isdigit()):  # "²".isdigit() is true, and int("²") fails
        raise ValueError(f"{name} must be an integer >= 1, got {text!r}")
    return positive_int(name, int(word))


def step_count(t_end: float, dt: float, names: str = "t_end/dt") -> int:
    """Number of steps ``N`` of the grid ``t_n = n*dt`` that reaches ``t_end``.

    ``t_end`` that is a multiple of ``dt`` up to round-off gives exactly that
    multiple; otherwise the grid overshoots ``t_end`` by less than one step.
    """
    ratio = t_end / dt
    if ratio > MAX_STEPS:
        raise ValueError(f"{names} must be at most {MAX_STEPS:.0e} steps, got {ratio:.3g}")
    n = round(ratio)
    if abs(ratio - n) > 1e-9 * max(1.0, ratio):
        n = math.ceil(ratio)
    return max(int(n), 1)


class Grid(NamedTuple):
    """The checked time grid ``t_n = n*dt``, ``n = 0 .. n_steps`` (:func:`grid`)."""

    t_end: float
    dt: float
    save_every: int
    n_steps: int


def grid(t_end: object, dt: object, save_every: object = 1) -> Grid:
    """The one check of a run's grid: ``t_end`` and ``dt`` > 0, ``save_every`` a :func:`stride`,
    and the grid's :func:`step_count` (at most :data:`MAX_STEPS`), in that order.

    Every entry point that takes ``t_end``, ``dt`` (and ``save_every``) checks
    them here, once; what it hands on inside the package is already clean.
    """
    t_end, dt = positive("t_end", t_end), positive("dt", dt)
    save_every = stride("save_every", save_every)
    return Grid(t_end, dt, save_every, step_count(t_end, dt))


def output_rows(n_steps: int, save_every: int) -> int:
    """Number of saved rows: ``t = 0``, every ``save_every``-th step, and the last."""
    return n_steps // save_every + 1 + (n_steps % save_every != 0)


def output_size(n_steps: int, save_every: int, n_columns: int = 6) -> int:
    """Number of saved rows; refuses outputs larger than ``MAX_OUTPUT_BYTES``."""
    rows = output_rows(n_steps, save_every)
    need = rows * n_columns * 8
    if need > MAX_OUTPUT_BYTES:
        raise ValueError(
            f"save_every: the output would need {need / 1024**3:.1f} GiB, more than "
            f"the {MAX_OUTPUT_BYTES / 1024**3:.0f} GiB allowed; raise save_every or dt"
        )
    return rows


def run_time(n_steps: int, seconds_per_step: float, what: str, names: str = "t_end/dt") -> float:
    """Estimated run time (s); refuses runs estimated above ``MAX_SECONDS``."""
    estimate = n_steps * seconds_per_step
    if estimate > MAX_SECONDS:
        raise ValueError(
            f"{names}: {n_steps:.3g} steps of {what} would take about {estimate:.3g} s "
            f"(at {seconds_per_step:.2g} s per step), more than the {MAX_SECONDS:.0f} s allowed; "
            "raise dt or shorten t_end"
        )
    return estimate


def sine_phase(name: str, value: object) -> float:
    """Return ``value`` as a finite float inside the sine's range ``|x| <= MAX_ARGUMENT``."""
    out = finite(name, value)
    if not abs(out) <= MAX_ARGUMENT:
        raise ValueError(f"{name} must be within +-{MAX_ARGUMENT:.0e} rad (the forcing's sine), got {out:.6g}")
    return out


def sine_argument(omega: object, phase: object, t_on: object) -> None:
    """Refuse a switched sine whose argument ``omega t + phase`` can leave the sine's range.

    The one bound of every method on the forcing's argument: ``|phase| +
    |omega| t_on <= MAX_ARGUMENT`` (:data:`lumped.numerics.sine.MAX_ARGUMENT`), where
    ``t_on`` is the last time the sine is evaluated (``min(t_N, force_until)``,
    ``t_N`` the grid's last time).  Arrays (one value per row of a sweep) are
    checked elementwise and the first offending row is reported.  The sum is
    formed as the kernels form ``omega t + phase``, with rounding monotone, so
    an accepted argument is within the range there too.
    """
    if type(omega) is float and type(phase) is float and type(t_on) is float:  # one run: the same test in floats
        if not abs(phase) <= MAX_ARGUMENT:
            sine_phase("force_phase", phase)
        if not abs(omega) * t_on + abs(phase) <= MAX_ARGUMENT:
            _span_refused(abs(omega) * t_on + abs(phase))
        return
    omega, phase, t_on = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (omega, phase, t_on)))
    for value in np.ravel(phase)[~(np.abs(np.ravel(phase)) <= MAX_ARGUMENT)][:1]:
        sine_phase("force_phase", float(value))
    span = np.abs(omega) * t_on + np.abs(phase)
    bad = np.ravel(~(span <= MAX_ARGUMENT))
    if np.any(bad):
        _span_refused(float(np.ravel(span)[int(np.argmax(bad))]))


def _span_refused(worst: float) -> None:
    """Raise the one line of :func:`sine_argument` for the argument ``worst`` (rad)."""
    raise ValueError(
        f"force_omega: |force_omega| * min(t_end, force_until) + |force_phase| = {worst:.3g} rad exceeds "
        f"{MAX_ARGUMENT:.0e} rad, the range of the forcing's sine; lower force_omega or shorten t_end"
    )
