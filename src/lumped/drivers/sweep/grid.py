"""A sweep's grid: its per-row parameters, its axes, the ``--vary`` text and its chunks.

A grid is the Cartesian product of axes (:class:`Axis`, one per varied
parameter; the first axis varies slowest), built and checked by :func:`axis`
from values or by :func:`parse_vary` from a ``--vary`` text.  Its rows split
into contiguous chunks (:func:`chunk_slice`), one per job.
"""

from __future__ import annotations

import math
import numbers
import sys
from collections.abc import Callable, Sequence
from typing import NamedTuple

import numpy as np

from lumped.drivers.sweep import limits
from lumped.model import parameters
from lumped.numerics import validate

#: The per-row parameters and their defaults (those of ``python -m lumped simulate``),
#: from :data:`lumped.model.parameters.PARAMETERS`.
PARAMETERS = {name: parameters.PARAMETERS[name].default for name in parameters.PER_ROW}


def chunk_slice(rows: int, index: int, count: int) -> slice:
    """Rows of chunk ``index`` (0-based) of ``count`` near-equal contiguous chunks of ``rows`` rows."""
    count = validate.positive_int("count", count)
    if isinstance(index, bool) or not isinstance(index, numbers.Integral) or not 0 <= index < count:
        raise ValueError(f"index must be an integer in [0, {count - 1}], got {index!r}")
    index = int(index)
    return slice(_bound(rows, index, count), _bound(rows, index + 1, count))


def _bound(rows: int, i: int, count: int) -> int:
    """``np.linspace(0, rows, count + 1).round()[i]``, without the ``count + 1`` values (``count`` may be 1e9).

    ``linspace`` forms ``i * (rows / count)`` and sets its last value to ``rows``; rounding is half to even.
    """
    return rows if i == count else int(np.round(np.float64(i) * (rows / count)))


def chunk_pair(chunk: object) -> tuple[int, int] | None:
    """``chunk`` as ``(index, count)``, integers (NumPy's too), or None; checked by :func:`chunk_slice`."""
    if chunk is None:
        return None
    if isinstance(chunk, (str, bytes)) or not isinstance(chunk, Sequence) or len(chunk) != 2:
        raise ValueError(f"chunk must be a pair (index, count), got {chunk!r}")
    return chunk[0], chunk[1]  # type: ignore[return-value]


class Axis(NamedTuple):
    """One varied parameter: its name (a key of :data:`PARAMETERS`) and values."""

    name: str
    values: np.ndarray


def check_value(name: str, value: float) -> float:
    """``value`` through the check of ``name`` in :data:`lumped.model.parameters.PARAMETERS`."""
    return parameters.PARAMETERS[name].check(name, value)  # type: ignore[return-value]


def _check_values(name: str, data: np.ndarray) -> None:
    """Every value of ``data`` through the validator of ``name``, in a few array passes.

    Each validator accepts an interval (``finite``, ``positive``, ...: see
    :mod:`lumped.numerics.validate`) and refuses NaN, so checking a NaN if there is
    one, then the smallest and the largest value, checks them all.
    """
    nan = np.isnan(data)
    if nan.any():
        check_value(name, math.nan)
    for value in (data.min(), data.max()):
        check_value(name, float(value))


def parameter_key(name: object) -> str:
    """The parameter a ``--vary`` NAME or a ``vary`` key names (dashes or underscores)."""
    if not isinstance(name, str):
        raise ValueError(f"vary: a parameter name must be a string, got {name!r}")
    key = name.strip().lstrip("-").replace("-", "_")
    if key in ("t_end", "dt"):
        raise ValueError(f"vary: {key} cannot vary: every row of a sweep shares the time grid; run one sweep per {key}")
    if key not in PARAMETERS:
        raise ValueError(f"vary: unknown or non-numeric option {name!r}; one of {', '.join(PARAMETERS)}")
    return key


def axis_size(key: str, values: object) -> int:
    """The number of values of an axis, read without converting them (a 1-d sequence or array)."""
    shape = getattr(values, "shape", None)
    if shape is not None and len(shape) != 1:
        raise ValueError(f"vary: {key} must be a 1-d sequence of numbers, got an array of shape {tuple(shape)}")
    if shape is None and (isinstance(values, (str, bytes)) or not hasattr(values, "__len__")):
        raise ValueError(f"vary: {key} must be a 1-d sequence of numbers, got {type(values).__name__}")
    return int(shape[0]) if shape is not None else len(values)  # type: ignore[arg-type]


def _as_values(key: str, values: object) -> np.ndarray:
    """``values`` as a 1-d float array: real numbers only (no booleans, strings or complex numbers)."""
    axis_size(key, values)
    try:
        data = np.asarray(values)
    except (ValueError, TypeError):  # ragged nesting
        raise ValueError(f"vary: {key} must be a 1-d sequence of numbers") from None
    if data.ndim != 1:
        raise ValueError(f"vary: {key} must be a 1-d sequence of numbers, got an array of shape {data.shape}")
    if data.dtype.kind not in "iuf" or (
        not isinstance(values, np.ndarray) and any(isinstance(v, (bool, np.bool_)) for v in values)  # type: ignore[attr-defined]
    ):
        what = {"b": "booleans", "c": "complex numbers", "U": "strings", "S": "bytes"}.get(
            data.dtype.kind, "non-numbers"
        )
        what = "booleans" if data.dtype.kind in "iuf" else what
        raise ValueError(f"vary: {key} must hold real numbers (int or float), got {what}")
    return data.astype(float)


def axis(name: str, values: Sequence[float] | np.ndarray) -> Axis:
    """An :class:`Axis`, checked: a known, per-row parameter; valid values in a 1-d sequence.

    Raises
    ------
    ValueError
        Beginning with ``vary:``.
    """
    key = parameter_key(name)
    data = _as_values(key, values)
    if data.size == 0:
        raise ValueError(f"vary: {key} has no values")
    try:
        _check_values(key, data)
    except ValueError as err:
        raise ValueError(f"vary: {err}") from None
    return Axis(key, data)


class VaryText(NamedTuple):
    """A parsed ``--vary`` text, its values not built yet (:meth:`axis` builds them)."""

    name: str
    start: float
    stop: float
    count: int
    log: bool

    def values(self) -> np.ndarray:
        """The ``COUNT`` values, evenly (``np.linspace``) or geometrically (``np.geomspace``) spaced, unchecked."""
        space = np.geomspace if self.log else np.linspace
        return space(self.start, self.stop, self.count)

    def axis(self) -> Axis:
        """The :class:`Axis` of the single mass's parameter of :meth:`values`, checked."""
        return axis(self.name, self.values())

    @property
    def all_zero(self) -> bool:
        """Whether every value is zero (``START == STOP == 0``)."""
        return self.start == 0 and self.stop == 0


def vary_text(spec: str, key: Callable[[str], str] | None = None) -> VaryText:
    """Parse ``NAME=START:STOP:COUNT`` or ``NAME=log:START:STOP:COUNT`` without building the values.

    ``NAME`` is an option's name without the leading dashes, with dashes or
    underscores (``force-omega`` or ``force_omega``), checked and cleaned by
    ``key`` (:func:`parameter_key`; a system file's sweep passes its own, which
    takes ``entry.key``).  ``COUNT`` points from
    ``START`` to ``STOP`` inclusive, evenly spaced (``np.linspace``) or, with
    ``log:``, evenly spaced in the logarithm (``np.geomspace``; both bounds
    must be > 0).  ``COUNT = 1`` needs ``START == STOP``.
    """
    name, eq, rest = spec.partition("=")
    if not eq or not name.strip():
        raise ValueError(f"vary: expected NAME=START:STOP:COUNT, got {spec!r}")
    name = (parameter_key if key is None else key)(name)
    parts = rest.split(":")
    log = parts[0].strip().lower() == "log"
    parts = parts[1:] if log else parts
    if len(parts) != 3:
        raise ValueError(f"vary: expected NAME=[log:]START:STOP:COUNT, got {spec!r}")
    start, stop = (_number(spec, p) for p in parts[:2])
    count = parts[2].strip()
    if not (count.isascii() and count.isdigit()) or int(count) < 1:  # "²".isdigit() is true
        raise ValueError(f"vary: COUNT must be an integer >= 1 (decimal digits), got {count!r} in {spec!r}")
    n = int(count)
    if n == 1 and start != stop:
        raise ValueError(f"vary: COUNT = 1 needs START == STOP in {spec!r}")
    if not log and not math.isfinite(stop - start):  # linspace's step would be inf, its values NaN
        raise ValueError(
            f"vary: STOP - START overflows (beyond the largest double, {sys.float_info.max:.4g}) in {spec!r}; "
            "take START and STOP nearer each other"
        )
    if log and not (start > 0 and stop > 0):
        raise ValueError(f"vary: log spacing needs START > 0 and STOP > 0 in {spec!r}")
    if n > limits.MAX_ROWS:
        raise ValueError(f"vary: COUNT {n} is above {limits.MAX_ROWS:.0e}, the most rows a sweep may have, in {spec!r}")
    return VaryText(name, start, stop, n, log)


def parse_vary(spec: str) -> Axis:
    """The :class:`Axis` of a ``--vary`` text (:func:`vary_text`), its values checked."""
    return vary_text(spec).axis()


def _number(spec: str, text: str) -> float:
    try:
        value = validate.finite("START/STOP", validate.parse_float("START/STOP", text))
    except ValueError:
        raise ValueError(f"vary: START and STOP must be finite numbers, got {text.strip()!r} in {spec!r}") from None
    return value
