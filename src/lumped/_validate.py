"""Argument checks shared by the API and the command line.

Every helper returns the cleaned value or raises :class:`ValueError` with a
one-line message that names the argument and the accepted range.  The command
line prints that message and exits with status 2, so the wording here is the
user-facing wording of both.
"""

from __future__ import annotations

import math

#: Largest number of time steps a single run may take (a bound, so that no run
#: can be made to loop for hours by a typo in ``--dt``).
MAX_STEPS = 2_000_000_000
#: Largest memory, in bytes, that the saved output of one run may occupy.
MAX_OUTPUT_BYTES = 4 * 1024**3


def _as_float(name: str, value: object) -> float:
    try:
        out = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
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
    """Return ``value`` as a finite float > 0."""
    out = finite(name, value)
    if out <= 0:
        raise ValueError(f"{name} must be > 0 and finite, got {out}")
    return out


def non_negative(name: str, value: object) -> float:
    """Return ``value`` as a finite float >= 0."""
    out = finite(name, value)
    if out < 0:
        raise ValueError(f"{name} must be >= 0 and finite, got {out}")
    return out


def positive_or_inf(name: str, value: object) -> float:
    """Return ``value`` as a float in (0, inf]."""
    out = _as_float(name, value)
    if out <= 0:
        raise ValueError(f"{name} must be > 0 (inf allowed), got {out}")
    return out


def time_or_inf(name: str, value: object) -> float:
    """Return ``value`` as a float in [0, inf]."""
    out = _as_float(name, value)
    if out < 0:
        raise ValueError(f"{name} must be >= 0 (inf allowed), got {out}")
    return out


def positive_int(name: str, value: object) -> int:
    """Return ``value`` as an int >= 1."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ValueError(f"{name} must be an integer >= 1, got {value!r}")
    try:
        out = int(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an integer >= 1, got {value!r}") from None
    if out < 1 or (isinstance(value, float) and value != out):
        raise ValueError(f"{name} must be an integer >= 1, got {value!r}")
    return out


def step_count(t_end: float, dt: float, names: str = "t_end/dt") -> int:
    """Number of steps ``N`` of the grid ``t_n = n*dt`` that reaches ``t_end``.

    ``t_end`` that is a multiple of ``dt`` up to round-off gives exactly that
    multiple; otherwise the grid overshoots ``t_end`` by less than one step.
    """
    ratio = t_end / dt
    n = round(ratio)
    if abs(ratio - n) > 1e-9 * max(1.0, ratio):
        n = math.ceil(ratio)
    if n > MAX_STEPS:
        raise ValueError(
            f"{names} must be at most {MAX_STEPS:.0e} steps, got {ratio:.3g}"
        )
    return max(int(n), 1)


def output_size(n_steps: int, save_every: int, n_columns: int = 6) -> int:
    """Number of saved rows; refuses outputs larger than ``MAX_OUTPUT_BYTES``."""
    rows = n_steps // save_every + 1 + (n_steps % save_every != 0)
    need = rows * n_columns * 8
    if need > MAX_OUTPUT_BYTES:
        raise ValueError(
            f"save_every: the output would need {need / 1024**3:.1f} GiB, more than "
            f"the {MAX_OUTPUT_BYTES / 1024**3:.0f} GiB allowed; raise save_every or dt"
        )
    return rows
