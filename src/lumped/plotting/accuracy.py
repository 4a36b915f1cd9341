"""The work-precision study's figures: convergence with reference slopes, and error against work.

Both helpers read the dictionary of :func:`lumped.studies.accuracy.to_json` (the
content of ``results/accuracy/study.json``): its ``results`` rows, one per
run, with ``case``, ``method``, ``resolution`` (``dt`` or ``rtol``),
``eps``, the errors and ``work`` (steps; deterministic, so the figures are
byte-identical from build to build).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from lumped.plotting._base import sci_tex, styled
from lumped.plotting.convergence import error_points
from lumped.plotting.figures import _axes_row

__all__ = ["METHOD_STYLE", "accuracy_convergence", "legend_entries", "work_precision"]

#: method -> (legend label, marker, colour) shared by both figures.
METHOD_STYLE = {
    "backward-euler": ("Algorithm 1 (backward Euler)", "o", "C0"),
    "theta": (r"$\theta$-method, $\theta = 1/2$", "s", "C1"),
    "event-locating": ("event-locating", "^", "C2"),
    "moreau-jean": (r"Moreau-Jean, $\theta = 1/2$", "P", "C5"),
    "event-driven": ("event-driven (rtol)", "D", "C3"),
    "tanh": (r"$\tanh$ model, LSODA", "v", "C4"),
}
#: Error of the convergence panels: key of a result -> axis label.
ERROR_LABELS = {
    "max_x_error": r"$\max|x - x_\mathrm{ref}|$ (m)",
    "relative_position_error": "relative error of the final position",
}


def _rows(data: Mapping[str, Any], case: str, method: str) -> list[Mapping[str, Any]]:
    """The results of one method on one case, coarsest first."""
    rows = [r for r in data["results"] if r["case"] == case and r["method"] == method]
    return sorted(rows, key=lambda r: (-r["resolution"], -(r["eps"] if isinstance(r["eps"], float) else 0.0)))


def _reference_slope(ax: Axes, h: np.ndarray, e: np.ndarray, p: int, ls: str) -> None:
    """A line of slope ``p`` through a point a factor 3 below the finest ``(h, e)``."""
    if h.size == 0:
        return
    span = np.array([h.min(), h.max()])
    c = e[np.argmin(h)] / h.min() ** p / 3.0
    ax.plot(span, c * span**p, color="0.45", lw=1.0, ls=ls, label=f"slope {p}")


def _convergence_panel(ax: Axes, data: Mapping[str, Any], case: str, error: str) -> None:
    """Each fixed-step scheme's ``error`` against ``dt``, with slopes 1 and 2."""
    for method in ("backward-euler", "theta", "event-locating", "moreau-jean"):
        rows = _rows(data, case, method)
        h, e = error_points([r["resolution"] for r in rows], [r[error] for r in rows])
        label, marker, colour = METHOD_STYLE[method]
        ax.plot(h, e, marker=marker, color=colour, ms=4, lw=1.0, label=label)
    for method, p, ls in (("backward-euler", 1, "--"), ("event-locating", 2, ":")):
        rows = _rows(data, case, method)
        _reference_slope(ax, *error_points([r["resolution"] for r in rows], [r[error] for r in rows]), p, ls)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"step $\Delta t$ (s)")


@styled
def accuracy_convergence(
    data: Mapping[str, Any],
    cases: Sequence[str] = ("free-decay", "hb-n2"),
    *,
    error: str = "max_x_error",
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Errors of the fixed-step schemes against ``dt``, one panel per case, with slopes 1 and 2.

    Parameters
    ----------
    data : mapping
        :func:`lumped.studies.accuracy.to_json`'s dictionary.
    cases : sequence of str
        Cases drawn, one panel each (titles from ``data["references"]``).
    error : str
        A key of :data:`ERROR_LABELS`.
    axes : sequence of Axes, optional
        One per case; ``None`` makes a new figure.

    Notes
    -----
    The reference lines pass a factor 3 below the finest point of
    Algorithm 1 (slope 1, dashed, its order) and of the event-locating
    scheme (slope 2, dotted).  With ``axes`` given, no legend is drawn (the
    caller places one); otherwise one above the panels.  Points that cannot be drawn on log axes (zero, or ``None``
    in the JSON) are left out.
    """
    if error not in ERROR_LABELS:
        raise ValueError(f"error must be one of {', '.join(ERROR_LABELS)}, got {error!r}")
    fig, row = _axes_row(len(cases), axes, width=3.15, height=2.8)
    for ax, case in zip(row, cases):
        _convergence_panel(ax, data, case, error)
        ax.set_title(data["references"][case]["title"], fontsize=10)
    row[0].set_ylabel(ERROR_LABELS[error])
    if axes is None:
        fig.legend(*row[0].get_legend_handles_labels(), loc="outside upper center", ncol=3, fontsize=8)
    return fig


def _label_eps(ax: Axes, rows: Sequence[Mapping[str, Any]], colour: str) -> None:
    """Write each point's ``eps`` of the tanh model to its left."""
    for r in rows:
        if r["relative_position_error"] > 0:
            ax.annotate(
                rf"$\varepsilon = {sci_tex(r['eps'], show_one=False)}$",
                (r["work"], r["relative_position_error"]),
                xytext=(-4, 0),
                textcoords="offset points",
                ha="right",
                va="center",
                fontsize=5.5,
                color=colour,
            )


def _work_panel(ax: Axes, data: Mapping[str, Any], case: str) -> None:
    """Relative final-position error against steps, every method with results on ``case``."""
    for method, (label, marker, colour) in METHOD_STYLE.items():
        rows = [r for r in _rows(data, case, method) if r["work"] > 0]
        if method == "tanh":  # one line per tolerance: eps falls along it
            for rtol, ls in zip(sorted({r["resolution"] for r in rows}, reverse=True), ("-", "--")):
                sub = [r for r in rows if r["resolution"] == rtol]
                w, e = error_points([r["work"] for r in sub], [r["relative_position_error"] for r in sub])
                rtol_tex = sci_tex(rtol, show_one=False)
                ax.plot(w, e, marker=marker, color=colour, ms=4, lw=1.0, ls=ls, label=f"{label}, rtol ${rtol_tex}$")
                if ls == "-":  # the other tolerance's line has the same eps, in the same order
                    _label_eps(ax, sub, colour)
            continue
        w, e = error_points([r["work"] for r in rows], [r["relative_position_error"] for r in rows])
        if w.size:
            ax.plot(w, e, marker=marker, color=colour, ms=4, lw=1.0, label=label)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("work (steps)")


@styled
def work_precision(
    data: Mapping[str, Any], cases: Sequence[str] = ("free-decay", "hb-n2"), *, axes: Sequence[Axes] | None = None
) -> Figure:
    """Relative error of the final position against the work (steps), one panel per case.

    Parameters
    ----------
    data : mapping
        :func:`lumped.studies.accuracy.to_json`'s dictionary.
    cases : sequence of str
        Cases drawn, one panel each.
    axes : sequence of Axes, optional
        One per case; ``None`` makes a new figure.

    Notes
    -----
    The work is a count of steps, deterministic: grid steps for the
    fixed-step schemes, DOP853 steps (12 stages each) for the event-driven
    method, LSODA's steps for the ``tanh`` model (one line per tolerance, the
    points along it are the values of ``eps``).  A step of each costs a
    different amount; wall times are printed by
    ``benchmarks/bench_accuracy.py --table``.  With ``axes`` given, no legend
    is drawn (:func:`legend_entries` gives the caller its entries).
    """
    fig, row = _axes_row(len(cases), axes, width=3.15, height=2.8)
    for ax, case in zip(row, cases):
        _work_panel(ax, data, case)
        ax.set_title(data["references"][case]["title"], fontsize=10)
    row[0].set_ylabel("relative error of the final position")
    if axes is None:
        fig.legend(*legend_entries(row), loc="outside upper center", ncol=3, fontsize=8)
    return fig


def legend_entries(axes: Sequence[Axes]) -> tuple[list, list[str]]:
    """Handles and labels of every Axes, each label once, in order of appearance."""
    handles: dict[str, Any] = {}
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    return list(handles.values()), list(handles)
