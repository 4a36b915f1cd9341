"""A fit to a record (issue 24): data, fitted motion and residuals; and a summary against a parameter with its kinks."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from lumped.plotting._base import styled

__all__ = ["fit_record", "summary_kinks"]


@styled
def fit_record(result: object, axes: Sequence[Axes] | None = None, label: str = "fit") -> Figure:
    """The record's displacements (dots), the fitted motion (line) and the residuals (lower panel), per mass.

    Parameters
    ----------
    result : FitResult
        Of :func:`lumped.drivers.fit.fit`.
    axes : two Axes, optional
        The upper (data and fit) and lower (residuals, mm) panels.
    label : str
        The fitted line's legend entry.
    """
    if axes is None:
        _, made = plt.subplots(2, 1, figsize=(6.4, 4.2), sharex=True, height_ratios=(2.2, 1.0))
        axes = list(made)
    top, bottom = axes
    record, residuals = result.record, result.residuals()  # type: ignore[attr-defined]
    for i, (name, x) in enumerate(record.x.items()):
        colour = f"C{i}"
        top.plot(record.t, 1e3 * x, ".", color="0.55", ms=2.0, label=f"data $x_{{{name}}}$")
        top.plot(record.t, 1e3 * result.model[name], "-", color=colour, lw=1.0, label=label)  # type: ignore[attr-defined]
        bottom.plot(record.t, 1e3 * residuals[name], ".", color=colour, ms=2.0)
    bottom.axhline(0.0, color="k", lw=0.6)
    top.set_ylabel("x (mm)")
    bottom.set(xlabel="t (s)", ylabel="data - fit (mm)")
    top.legend(loc="upper right", fontsize=8)
    return top.figure  # type: ignore[return-value]


@styled
def summary_kinks(
    values: np.ndarray,
    summary: np.ndarray,
    slope: np.ndarray,
    kinks: Sequence[tuple[float, float, float]] = (),
    axes: Sequence[Axes] | None = None,
    labels: tuple[str, str, str] = (r"$\tau$ (N)", "rest position (mm)", "derivative (mm/N)"),
) -> Figure:
    """A summary against a parameter (upper panel) and its exact derivative (lower), with the kinks marked.

    Parameters
    ----------
    values, summary, slope : ndarray, (n,)
        The parameter, the summary (m) and its derivative (m per unit) at each value.
    kinks : sequence of (value, slope_left, slope_right)
        Where the derivative jumps: a vertical line in both panels and the two one-sided derivatives as
        open (left) and filled (right) circles.
    axes : two Axes, optional
    labels : three str
        The parameter's axis label and the two panels' labels.
    """
    if axes is None:
        _, made = plt.subplots(2, 1, figsize=(6.4, 4.4), sharex=True)
        axes = list(made)
    top, bottom = axes
    top.plot(values, 1e3 * np.asarray(summary), "-", color="C0", lw=1.2)
    bottom.plot(values, 1e3 * np.asarray(slope), ".", color="C0", ms=1.5)
    for value, left, right in kinks:
        for ax in (top, bottom):
            ax.axvline(value, color="0.7", lw=0.6, zorder=0)
        bottom.plot([value], [1e3 * left], "o", mfc="none", mec="C3", ms=4)
        bottom.plot([value], [1e3 * right], "o", color="C3", ms=3)
    bottom.axhline(0.0, color="k", lw=0.6)
    top.set_ylabel(labels[1])
    bottom.set(xlabel=labels[0], ylabel=labels[2])
    return top.figure  # type: ignore[return-value]
