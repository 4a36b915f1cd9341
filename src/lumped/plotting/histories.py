"""Time histories (Figures 5 to 14): Algorithm 1, the exact solution, their difference.

Each figure shows Algorithm 1 on its grid (solid, its step in the legend) and
the exact event-driven solution on a fine grid (dashed) with its events
marked; below it, a panel of the difference between the two on Algorithm 1's
grid (:func:`difference`).  Legends sit above the axes, outside them, so that
they hide no curve.  The helpers take ``ax=`` (or ``axes=``), return the
:class:`~matplotlib.figure.Figure` and leave global matplotlib state alone.
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from lumped.model.trajectory import Trajectory
from lumped.plotting._base import legend_above, new_axes, sci_tex, styled
from lumped.solvers.exact import ExactSolution

__all__ = [
    "LABELS",
    "EVENT_MARKERS",
    "exact_fine",
    "step_label",
    "exact_on_grid",
    "settled",
    "difference",
    "time_history",
    "time_history_panels",
    "rest_inset",
]

#: Axis labels of the trajectory columns (with units).
LABELS = {
    "x": r"displacement $x$ (m)",
    "v": r"velocity $v$ (m/s)",
    "F_s": r"spring force $F_s$ (N)",
    "F_d": r"dashpot force $F_d$ (N)",
    "F": r"external force $F$ (N)",
}

#: Symbol and unit of each column, for the difference panel.
SYMBOLS = {"x": ("x", "m"), "v": ("v", "m/s"), "F_s": ("F_s", "N"), "F_d": ("F_d", "N"), "F": ("F", "N")}

#: Marker of each event kind of the exact solution.
EVENT_MARKERS = {"stop": "o", "reversal": "D", "breakaway": "^", "switch": "x", "rest": "s"}
#: The legend's name of a kind, where it is not the kind itself: the one switch of the paper's figures is
#: its sine going off.
EVENT_LABELS = {"switch": "forcing-off"}

#: Size (inches) of a time history with its difference panel, and without one.
#: The article prints figures at the size they are drawn (``fig()`` in paper.typ).
SIZE_WITH_DIFFERENCE, SIZE_ALONE = (5.4, 3.5), (5.4, 2.8)

#: The points next to a switch "dominate" the difference when the rest of it
#: would fill less than 1/DOMINATED of the panel's height on a common scale.
DOMINATED = 5.0

_NUMERIC = dict(color="C0", lw=1.6)
_EXACT = dict(color="C3", lw=1.0, ls="--", label="exact (event-driven)")


def exact_fine(solution: ExactSolution, points: int = 20001) -> dict[str, np.ndarray]:
    """The exact solution on a uniform grid of ``points`` times, plus every event time."""
    t = np.linspace(0.0, solution.t_end, points)
    events = [e.time for e in solution.events if 0.0 <= e.time <= solution.t_end]
    return solution.evaluate(np.unique(np.r_[t, events]))


def step_label(trajectory: Trajectory, name: str = "Algorithm 1") -> str:
    r"""Legend label with the step, e.g. ``Algorithm 1, $\Delta t = 1\times10^{-4}$ s``."""
    return rf"{name}, $\Delta t = {sci_tex(trajectory.dt)}$ s"


def exact_on_grid(trajectory: Trajectory, solution: ExactSolution) -> Trajectory:
    """The exact solution at the saved times of ``trajectory`` (its ``dt`` and stride).

    Raises ``ValueError`` when the two grids differ (another end time, say).
    """
    sampled = solution.sample(trajectory.dt, trajectory.save_every)
    if not np.array_equal(sampled.t, trajectory.t):
        raise ValueError(
            f"solution: sampled on {sampled.t.size} times, not on the "
            f"trajectory's {trajectory.t.size} (same t_end and dt needed)"
        )
    return sampled


def settled(trajectory: Trajectory, exact: Trajectory) -> np.ndarray:
    """Grid points where both solutions are on the same branch of eq. (6) and were one step before.

    The branch is the sign of ``v`` (slipping either way, or at rest); ``False``
    marks the points within a step of a switch (breakaway, reversal, stop) of
    either solution.
    """
    a, b = np.sign(trajectory.v), np.sign(exact.v)
    same = a == b
    same[1:] &= (a[1:] == a[:-1]) & (b[1:] == b[:-1])
    return same


def _panel_limit(gap: np.ndarray, calm: np.ndarray) -> float | None:
    """Half-height of the difference panel, or ``None`` to show every point.

    The scale is that of the ``calm`` points (:func:`settled`), unless the
    others stay within :data:`DOMINATED` times it.
    """
    inside = float(np.abs(gap[calm]).max(initial=0.0))
    if inside == 0.0 or np.abs(gap).max() <= DOMINATED * inside:
        return None
    return 1.25 * inside


def _mark_off_scale(ax: Axes, t: np.ndarray, gap: np.ndarray, limit: float, unit: str) -> str:
    """Triangles at the panel's edge where ``|gap| > limit``; return a note for the title."""
    off = np.abs(gap) > limit
    for sign, marker, y in ((1, "^", 0.92), (-1, "v", 0.08)):
        where = off & (np.sign(gap) == sign)
        ax.plot(
            t[where],
            np.full(where.sum(), y),
            ls="none",
            marker=marker,
            ms=4,
            color="C3",
            transform=ax.get_xaxis_transform(),
            clip_on=False,
        )
    largest = np.abs(gap[off]).max()
    return (
        f"\n\u25b2\u25bc {off.sum()} points off scale (up to {largest:#.3g} {unit}),"
        " each within a step of a reversal or stop"
    )


@styled
def difference(trajectory: Trajectory, solution: ExactSolution, column: str, ax: Axes | None = None) -> Figure:
    """Algorithm 1 minus the exact solution, at Algorithm 1's grid points.

    Parameters
    ----------
    trajectory : Trajectory
        Algorithm 1; the exact solution is sampled on its grid
        (:func:`exact_on_grid`), so no interpolation enters the difference.
    solution : ExactSolution
    column : {"x", "v", "F_s", "F_d", "F"}
    ax : Axes, optional

    Notes
    -----
    The whole difference is drawn, as a line through every grid point.  For
    ``x``, ``v`` and ``F_s`` it is smooth and the panel shows all of it.  The
    dashpot force is not: at a reversal it jumps from one edge of the band to
    the other (by ``2 mu_s N_f``), so at the grid points between the exact and
    the discrete reversal the two solutions sit on opposite branches of
    eq. (6) and differ by about ``2 mu_s N_f`` whatever ``dt`` (a shift in
    time, not an error in value); at its stop step Algorithm 1's ``F_d`` also
    absorbs the last momentum, ``m v / dt``.  On a scale that shows those
    points the rest of the difference, tens to hundreds of times smaller,
    would be a flat line.  So when the points within a step of a switch
    (:func:`settled` is ``False``) exceed :data:`DOMINATED` times the largest
    difference elsewhere, the panel is scaled to the latter: the line leaves
    the panel at those points, a triangle at the edge marks each one, and the
    title gives their number and largest value.  Nothing is dropped and the
    scale is stated; Figures 5 and 10 (:func:`time_history_panels`) need no
    such panel, Algorithm 1 being exact there.
    """
    fig, ax = new_axes(ax)
    exact = exact_on_grid(trajectory, solution)
    gap = getattr(trajectory, column) - getattr(exact, column)
    ax.plot(trajectory.t, gap, color="C0", lw=1.0)
    ax.axhline(0.0, color="0.5", lw=0.6)
    symbol, unit = SYMBOLS[column]
    ax.set_ylabel(rf"$\Delta {symbol}$ ({unit})")
    note = ""
    limit = _panel_limit(gap, settled(trajectory, exact))
    if limit is not None:
        ax.set_ylim(-limit, limit)
        note = _mark_off_scale(ax, trajectory.t, gap, limit, unit)
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-2, 3), useMathText=True)
    ax.set_title(f"Algorithm 1 \u2212 exact, on Algorithm 1's grid{note}", fontsize=8, loc="right")
    return fig


def _mark_events(ax: Axes, solution: ExactSolution, column: str) -> None:
    """One marker per event kind present, on the exact curve (left limit at jumps)."""
    for kind, marker in EVENT_MARKERS.items():
        times = solution.event_times(kind)
        times = times[(times > 0.0) & (times <= solution.t_end)]
        if kind == "rest" or times.size == 0:
            continue
        values = solution.evaluate(times)[column]
        ax.plot(times, values, ls="none", marker=marker, ms=5, mfc="none", mec="k", label=EVENT_LABELS.get(kind, kind))
    rest = solution.rest_time
    if np.isfinite(rest) and 0.0 < rest <= solution.t_end:
        ax.axvline(rest, color="0.4", lw=0.8, ls=":", label="final rest")


def _history_axes(with_difference: bool) -> tuple[Figure, Axes, Axes | None]:
    """A new figure: the main axes and, if asked, a difference panel below them."""
    if not with_difference:
        fig, ax = plt.subplots(figsize=SIZE_ALONE)
        return fig, ax, None
    fig, (ax, below) = plt.subplots(2, 1, figsize=SIZE_WITH_DIFFERENCE, sharex=True, height_ratios=(3.0, 1.3))
    return fig, ax, below


@styled
def time_history(
    trajectory: Trajectory,
    solution: ExactSolution | None,
    column: str,
    ax: Axes | None = None,
    legend: bool = True,
    diff_ax: Axes | None = None,
    exact_label: str = _EXACT["label"],
) -> Figure:
    """One column of Algorithm 1 against time, with the exact solution and its events.

    Parameters
    ----------
    trajectory : Trajectory
        Algorithm 1 (drawn solid; its step ``trajectory.dt`` in the legend).
    solution : ExactSolution or None
        Drawn dashed on a fine grid (:func:`exact_fine`), its events marked
        with :data:`EVENT_MARKERS`; ``None`` draws Algorithm 1 alone.
    column : {"x", "v", "F_s", "F_d", "F"}
    ax : Axes, optional
        Where to draw.  ``None`` makes a new figure which, when ``solution``
        is given, has the :func:`difference` panel below, sharing the time axis.
    legend : bool
        Draw the legend, above the axes (outside them: it hides no data).
    diff_ax : Axes, optional
        With ``ax`` given: where to draw the difference (nowhere if ``None``).
    exact_label : str
        The exact solution's legend entry (Figure 5 names its closed form, eq. (19)).
    """
    if ax is None:
        fig, ax, diff_ax = _history_axes(solution is not None)
    fig = ax.figure
    ax.plot(trajectory.t, getattr(trajectory, column), label=step_label(trajectory), **_NUMERIC)
    if solution is not None:
        fine = exact_fine(solution)
        ax.plot(fine["t"], fine[column], **{**_EXACT, "label": exact_label})
        _mark_events(ax, solution, column)
        if diff_ax is not None:
            difference(trajectory, solution, column, ax=diff_ax)
    ax.set_ylabel(LABELS[column])
    ax.set_xlim(0.0, trajectory.t[-1])
    bottom = ax if diff_ax is None else diff_ax
    bottom.set_xlabel("time $t$ (s)")
    if legend:
        legend_above(ax, ncol=3)
    return fig  # type: ignore[return-value]


@styled
def rest_inset(
    ax: Axes,
    trajectory: Trajectory,
    solution: ExactSolution,
    band: float,
    bounds: Sequence[float] = (0.62, 0.56, 0.37, 0.36),
) -> Axes | None:
    """An inset of ``ax`` magnifying where the mass comes to rest, the static band shaded.

    On a displacement axis scaled to the first swing, a rest a few millimetres
    from ``x = 0`` cannot be told from the unstretched position; the inset shows
    the last swing and the rest against the band ``|x| <= band`` (``tau / k``).
    A mass still moving at the end has no rest to show: no inset, ``None``.

    Parameters
    ----------
    ax : Axes
        The displacement axes of :func:`time_history` (``column="x"``).
    trajectory, solution
        As drawn in ``ax``.
    band : float, m
        Half-width of the static band, ``mu_s N_f / k``.
    bounds : (x0, y0, width, height)
        Where the inset sits, in fractions of ``ax``.

    Returns
    -------
    Axes or None
        The inset, or ``None`` when the exact solution does not come to rest by its end.
    """
    if not np.isfinite(solution.rest_time):  # still moving at the end: no rest to show
        return None
    inset = ax.inset_axes(list(bounds))
    turns = solution.event_times("reversal")
    turns = turns[turns <= solution.rest_time]
    start = turns[-1] if turns.size else 0.0
    inset.axhspan(-band, band, color="0.85", lw=0, label=r"static band $|x| \leq \mu_s N_f/k$")
    inset.axhline(0.0, color="0.4", lw=0.6)
    fine = exact_fine(solution)
    inset.plot(trajectory.t, trajectory.x, **_NUMERIC)
    inset.plot(fine["t"], fine["x"], **_EXACT)
    shown = trajectory.x[trajectory.t >= start]
    half = max(2.0 * band, 1.2 * float(np.abs(shown).max(initial=0.0)))  # the band, or all of a last swing
    inset.set(xlim=(start, trajectory.t[-1]), ylim=(-half, half))
    inset.tick_params(labelsize=7)
    inset.yaxis.set_major_formatter(lambda y, _: f"{1e3 * y:g}")
    inset.set_ylabel("x (mm)", fontsize=7)
    inset.set_title("the rest, magnified; band shaded", fontsize=7)
    return inset


def _zero_throughout(trajectory: Trajectory, solution: ExactSolution | None, column: str) -> bool:
    """Whether ``column`` is exactly 0 at every grid point and, if given, in the exact solution."""
    if np.any(getattr(trajectory, column) != 0.0):
        return False
    return solution is None or not np.any(exact_fine(solution)[column] != 0.0)


@styled
def time_history_panels(
    trajectory: Trajectory,
    solution: ExactSolution | None,
    columns: Sequence[str] = ("x", "v", "F_s", "F_d"),
    axes: Sequence[Axes] | None = None,
    exact_label: str = _EXACT["label"],
) -> Figure:
    """Several columns in a grid of two columns (Figures 5 and 10), one legend above.

    No difference panels: these are the runs in which the mass never moves
    and Algorithm 1 equals the exact solution (the notebooks print the
    largest difference).  A column that is exactly zero throughout, in
    Algorithm 1 and in the exact solution, is said to be so in its panel, so
    that a flat line reads as the result it is.  ``exact_label`` as in
    :func:`time_history`.
    """
    if axes is None:
        rows = (len(columns) + 1) // 2
        fig, grid = plt.subplots(rows, 2, figsize=(6.2, 0.5 + 1.75 * rows), sharex=True)
        axes = list(np.ravel(grid))
    fig = axes[0].figure
    for i, (name, ax) in enumerate(zip(columns, axes)):
        time_history(trajectory, solution, name, ax=ax, legend=False, exact_label=exact_label)
        if _zero_throughout(trajectory, solution, name):
            ax.text(
                0.5,
                0.62,
                f"${SYMBOLS[name][0]} = 0$ throughout: the mass never moves",
                transform=ax.transAxes,
                ha="center",
                fontsize=7,
                color="0.3",
            )
        if i < len(columns) - 2:  # a shared time axis is labelled on the bottom row only
            ax.set_xlabel("")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside upper center", ncol=4, fontsize=8)
    return fig  # type: ignore[return-value]
