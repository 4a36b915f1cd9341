"""The response curves of notebook 13 (issue 23): amplitude against frequency along branches of periodic motion."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from lumped.plotting._base import styled

__all__ = ["response_curves"]


@styled
def response_curves(
    branches: Mapping[tuple[float, float], Mapping[str, np.ndarray]],
    closed: Mapping[tuple[float, float], tuple[np.ndarray, np.ndarray, np.ndarray]] | None = None,
    runs: Mapping[str, np.ndarray] | None = None,
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """``X k/P`` against ``r = omega/omega_n`` along branches: one panel per damping ratio, one colour per ``F/P``.

    Parameters
    ----------
    branches : mapping
        ``(damping, F/P)`` -> columns ``r``, ``ratio`` (``X k/P``), ``stable`` (bool) and ``kind`` of a
        branch in order: solid where stable, dashed where not; ``stops-change`` points marked with a square.
    closed : mapping, optional
        ``(damping, F/P)`` -> ``(r, X k/P, nonstop)`` of Den Hartog's closed form: thin black dotted
        where the motion without stops is admissible.
    runs : mapping of str to ndarray, optional
        Columns ``damping``, ``friction_ratio``, ``frequency_ratio``, ``amplitude_ratio`` of
        ``results/studies/den_hartog.csv``: the long runs, hollow circles.
    axes : sequence of Axes, optional
    """
    dampings = sorted({d for d, _ in branches})
    if axes is None:
        _, made = plt.subplots(1, len(dampings), figsize=(6.4, 3.6), sharey=True)
        axes = list(np.atleast_1d(made))
    ratios = sorted({f for _, f in branches})
    for ax, zeta in zip(axes, dampings):
        for i, fp in enumerate(ratios):
            _panel(ax, branches[(zeta, fp)], fp, f"C{i}")
            if closed is not None and (zeta, fp) in closed:
                r, ratio, nonstop = (np.asarray(a) for a in closed[(zeta, fp)])
                ax.plot(r, np.where(nonstop, ratio, np.nan), ":", color="k", lw=0.8)
            if runs is not None:
                rows = (runs["damping"] == zeta) & (runs["friction_ratio"] == fp)
                ax.plot(runs["frequency_ratio"][rows], runs["amplitude_ratio"][rows], "o", mfc="none", mec=f"C{i}")
        ax.set_title("Coulomb" if zeta == 0 else rf"Bingham, $\zeta = {zeta:g}$", fontsize=9)
        ax.set_xlabel(r"frequency ratio $\omega/\omega_n$")
        ax.set_yscale("log")
    axes[0].set_ylabel(r"amplitude ratio $Xk/P$")
    axes[0].set_ylim(1e-2, 50.0)
    fig = axes[0].figure
    fig.legend(*axes[0].get_legend_handles_labels(), loc="outside upper center", ncol=len(ratios), fontsize=8)
    return fig  # type: ignore[return-value]


def _panel(ax: Axes, branch: Mapping[str, np.ndarray], fp: float, colour: str) -> None:
    """One branch: stable solid, unstable dashed, the points where the stops per period change as squares."""
    r, ratio, stable = (np.asarray(branch[k]) for k in ("r", "ratio", "stable"))
    ax.plot(r, np.where(stable, ratio, np.nan), "-", color=colour, lw=1.2, label=rf"$F/P = {fp:g}$")
    if not stable.all():
        ax.plot(r, np.where(stable, np.nan, ratio), "--", color=colour, lw=1.2)
    change = np.asarray(branch["kind"]) == "stops-change"
    ax.plot(r[change], ratio[change], "s", color=colour, ms=4)
