"""The convergence figure of the article: Algorithm 1's error against its step, log-log.

Reads the ``convergence`` object of ``paper/build/numbers.json``
(``scripts/paper_numbers.py``): ``steps`` (s) and, per example, lists of
errors against the exact solution, one entry per step.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from lumped.plotting._base import styled
from lumped.plotting.figures import _axes_row

__all__ = ["ERRORS", "EXAMPLES", "convergence", "error_points"]

#: The errors drawn: key of numbers.json -> (legend label, marker, line style).
ERRORS = {
    "max_x": (r"$\max|\Delta x|$ (m)", "o", "-"),
    "max_v": (r"$\max|\Delta v|$ (m/s)", "s", "-"),
    "int_F_d": (r"$\int|\Delta F_d|\,\mathrm{d}t$ (N s)", "^", "-"),
    "rest_position": (r"$|\Delta x_\mathrm{rest}|$ (m)", "D", ":"),
}

#: The examples drawn, one panel each: key of numbers.json -> panel title, in
#: which ``{x0}`` is the ``parameters.x0_large`` of numbers.json.
EXAMPLES = {"forced_large": "(a) forced vibration, eq. (17b)", "free_large": "(b) free vibration from $x_0 = {x0}$ m"}


def error_points(steps: Sequence[float], errors: Sequence[Any]) -> tuple[np.ndarray, np.ndarray]:
    """The ``(step, error)`` pairs that a log-log plot can show.

    Entries that are not positive numbers are skipped: ``None`` or a string
    (a run still moving at its end, so no rest position) and zero (exact).
    """
    pairs = [
        (float(h), float(e))
        for h, e in zip(steps, errors)
        if isinstance(e, (int, float)) and not isinstance(e, bool) and e > 0 and np.isfinite(e)
    ]
    if not pairs:
        return np.empty(0), np.empty(0)
    return tuple(np.array(c) for c in zip(*pairs))  # type: ignore[return-value]


def _slope_one(ax: Axes, steps: np.ndarray, anchor: tuple[np.ndarray, np.ndarray]) -> None:
    """A reference line ``error = C * dt`` a factor 3 below the anchor series' smallest step."""
    h, e = anchor
    if h.size == 0:
        return
    c = e[np.argmin(h)] / h.min() / 3.0
    span = np.array([steps.min(), steps.max()])
    ax.plot(span, c * span, color="0.45", lw=1.0, ls="--", label="slope 1 (first order)")


def _panel(ax: Axes, steps: np.ndarray, errors: Mapping[str, Any], title: str) -> None:
    """One example: each error of :data:`ERRORS` against the step, and slope 1."""
    for key, (label, marker, ls) in ERRORS.items():
        h, e = error_points(steps, errors.get(key, []))
        ax.plot(h, e, marker=marker, ls=ls, ms=4, lw=1.0, label=label)
    _slope_one(ax, steps, error_points(steps, errors.get("max_x", [])))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"step $\Delta t$ (s)")
    ax.set_title(title, fontsize=10)


@styled
def convergence(numbers: Mapping[str, Any], axes: Sequence[Axes] | None = None) -> Figure:
    """Errors of Algorithm 1 against the exact solution, against ``dt``, log-log.

    Parameters
    ----------
    numbers : mapping
        The content of ``numbers.json``; its ``convergence`` object is read
        (``steps`` and one mapping of error lists per key of :data:`EXAMPLES`).
    axes : sequence of two Axes, optional
        Where to draw the two examples; ``None`` makes a new figure 6.3 in
        wide (the article's text width: printed at the size it is drawn).

    Notes
    -----
    Every available point is drawn with a marker and none is fitted: the rest
    position's error is not monotone in ``dt`` (coarse steps stop the motion a
    half-cycle early, or on the other side of zero), and the dotted line
    through its markers shows that as it is.  The dashed reference line has
    slope 1, the order of backward Euler.
    """
    table = numbers["convergence"]
    steps = np.asarray(table["steps"], dtype=float)
    fig, row = _axes_row(len(EXAMPLES), axes, width=3.15, height=2.9)
    x0 = numbers.get("parameters", {}).get("x0_large", "x_0")
    for ax, (key, title) in zip(row, EXAMPLES.items()):
        _panel(ax, steps, table[key], title.format(x0=x0))
    row[0].set_ylabel("error (SI units)")
    handles, labels = row[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside upper center", ncol=3, fontsize=8)
    return fig
