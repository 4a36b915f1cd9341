"""The convergence figure of the article: Algorithm 1's error against its step, log-log.

Reads the ``convergence`` object of ``paper/build/numbers.json``
(``scripts/paper_numbers.py``): ``steps`` (s) and, per example, lists of
errors against the exact solution, one entry per step.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from lumped.plotting._base import styled

__all__ = ["ERRORS", "EXAMPLES", "UNITS", "convergence", "error_points"]

#: The errors drawn: key of numbers.json -> (legend label, marker, line style).
ERRORS = {
    "max_x": (r"$\max|\Delta x|$", "o", "-"),
    "rest_position": (r"$|\Delta x_\mathrm{rest}|$", "D", ":"),
    "max_v": (r"$\max|\Delta v|$", "s", "-"),
    "int_F_d": (r"$\int|\Delta F_d|\,\mathrm{d}t$", "^", "-"),
}

#: One row of panels per unit: unit -> the errors of :data:`ERRORS` measured in it.
UNITS = {"m": ("max_x", "rest_position"), "m/s": ("max_v",), "N s": ("int_F_d",)}

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


def _panel(ax: Axes, steps: np.ndarray, errors: Mapping[str, Any], keys: Sequence[str]) -> None:
    """The errors ``keys`` of one example (all in one unit) against the step, and slope 1."""
    for key in keys:
        label, marker, ls = ERRORS[key]
        h, e = error_points(steps, errors.get(key, []))
        ax.plot(h, e, marker=marker, ls=ls, ms=4, lw=1.0, color=f"C{list(ERRORS).index(key)}", label=label)
    _slope_one(ax, steps, error_points(steps, errors.get(keys[0], [])))
    ax.set_xscale("log")
    ax.set_yscale("log")


@styled
def convergence(numbers: Mapping[str, Any], axes: Sequence[Axes] | None = None) -> Figure:
    """Errors of Algorithm 1 against the exact solution, against ``dt``, log-log.

    Parameters
    ----------
    numbers : mapping
        The content of ``numbers.json``; its ``convergence`` object is read
        (``steps`` and one mapping of error lists per key of :data:`EXAMPLES`).
    axes : sequence of Axes, optional
        Where to draw: one per unit of :data:`UNITS` and example of
        :data:`EXAMPLES`, row by row (a unit a row, an example a column);
        ``None`` makes a new figure 6.3 in wide (the article's text width:
        printed at the size it is drawn).

    Notes
    -----
    Every available point is drawn with a marker and none is fitted: the rest
    position's error is not monotone in ``dt`` (coarse steps stop the motion a
    half-cycle early, or on the other side of zero), and the dotted line
    through its markers shows that as it is.  The dashed reference line has
    slope 1, the order of backward Euler.  Errors in different units never
    share an axis: each row holds one unit.
    """
    table = numbers["convergence"]
    steps = np.asarray(table["steps"], dtype=float)
    if axes is None:
        fig, grid = plt.subplots(len(UNITS), len(EXAMPLES), figsize=(6.3, 6.0), sharex=True, squeeze=False)
        axes = list(grid.flat)
    fig = axes[0].figure
    x0 = numbers.get("parameters", {}).get("x0_large", "x_0")
    cells = [(unit, example) for unit in UNITS for example in EXAMPLES]
    for ax, (unit, example) in zip(axes, cells):
        _panel(ax, steps, table[example], UNITS[unit])
        if example == next(iter(EXAMPLES)):
            ax.set_ylabel(f"error ({unit})")
        if unit == next(iter(UNITS)):
            ax.set_title(EXAMPLES[example].format(x0=x0), fontsize=10)
        if unit == list(UNITS)[-1]:
            ax.set_xlabel(r"step $\Delta t$ (s)")
    handles, labels = [], []
    for ax in axes[:: len(EXAMPLES)]:  # the first column holds every error once
        for h, label in zip(*ax.get_legend_handles_labels()):
            if label not in labels:
                handles.append(h)
                labels.append(label)
    fig.legend(handles, labels, loc="outside upper center", ncol=5, fontsize=8)
    return fig  # type: ignore[return-value]
