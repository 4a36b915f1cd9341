"""Self-excited oscillations on a belt (issue 34, notebook 16): the bifurcation diagram in a parameter,
equilibria and limit cycles drawn solid where stable and dashed where not, long runs overlaid."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from lumped.plotting._base import legend_above, new_axes, styled

__all__ = ["bifurcation_diagram"]

#: ``(parameter, position, stable)``: an equilibrium branch (the position of the mass at rest).
EquilibriumBranch = tuple[np.ndarray, np.ndarray, np.ndarray]
#: ``(parameter, x_max, x_min, stable)``: a cycle branch, the extremes of the position over a period.
CycleBranch = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]


def _by_stability(ax: Axes, p: np.ndarray, y: np.ndarray, stable: np.ndarray, colour: str, label: str) -> None:
    """``y(p)`` solid over the runs of stable points and dashed over the others, each run joined to the next
    point so that the line is unbroken; the label goes on the first solid and the first dashed piece."""
    p, y, stable = np.asarray(p, float), np.asarray(y, float), np.asarray(stable, bool)
    edges = np.flatnonzero(np.diff(stable.astype(int))) + 1
    labelled: set[bool] = set()
    for start, end in zip(np.r_[0, edges], np.r_[edges, p.size]):
        kind = bool(stable[start])
        text = f"{label}, {'stable' if kind else 'unstable'}" if label and kind not in labelled else None
        labelled.add(kind)
        stop = min(end + 1, p.size)
        ax.plot(p[start:stop], y[start:stop], "-" if kind else "--", color=colour, lw=1.3, label=text)


@styled
def bifurcation_diagram(
    equilibria: EquilibriumBranch,
    cycles: Mapping[str, CycleBranch],
    runs: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None,
    marks: Mapping[str, tuple[float, float]] | None = None,
    xlabel: str = "belt speed $V$ (m/s)",
    ax: Axes | None = None,
) -> Figure:
    """Equilibria and limit cycles against a parameter: the position of each equilibrium and the extremes of
    each cycle, solid where stable, dashed where not.

    Parameters
    ----------
    equilibria : (p, x, stable)
        The equilibrium branch: parameter values, positions (m) and stability, drawn black.
    cycles : mapping label -> (p, x_max, x_min, stable)
        Each cycle branch, one colour each: its largest and smallest position over a period (m).
    runs : (p, x_max, x_min), optional
        The extremes of long simulated runs after they settle, drawn as open circles.
    marks : mapping label -> (p, x), optional
        Points to mark (a Hopf point, a fold), one marker each.
    xlabel : str
        The parameter's axis label.
    ax : Axes, optional
    """
    fig, ax = new_axes(ax, figsize=(6.0, 4.0))
    _by_stability(ax, *equilibria, "k", "equilibrium")
    for i, (label, (p, high, low, stable)) in enumerate(cycles.items()):
        _by_stability(ax, p, high, stable, f"C{i}", label)
        _by_stability(ax, p, low, stable, f"C{i}", "")
    if runs is not None:
        p, high, low = runs
        ax.plot(np.r_[p, p], np.r_[high, low], "o", mfc="none", mec="0.3", ms=5, label="long runs (event-driven)")
    for j, (label, (p, x)) in enumerate((marks or {}).items()):
        ax.plot([p], [x], "sD^v"[j % 4], color=f"C{len(cycles) + j}", ms=6, label=label)
    ax.set(xlabel=xlabel, ylabel="position $x$ (m)")
    legend_above(ax, ncol=2)
    return fig
