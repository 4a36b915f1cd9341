"""The studies' figures (issue 12, ``results/studies/``): where the mass comes to rest; Den Hartog's amplitudes; stops per cycle.

The helpers take columns of ``results/studies/rest.csv`` (notebook 10
documents them) and ``results/studies/stops.csv`` (notebook 12) as arrays, so
they draw any grid.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.figure import Figure

from lumped.plotting._base import legend_above, new_axes, styled

__all__ = [
    "intervals",
    "rest_discrepancies",
    "rest_positions",
    "den_hartog_amplitudes",
    "den_hartog_history",
    "stop_histories",
    "stops_map",
]

MM = 1e3  # m -> mm


def intervals(x: np.ndarray, mask: np.ndarray) -> list[tuple[float, float]]:
    """The ``(first, last)`` values of ``x`` of every run of consecutive true entries of ``mask``."""
    m = np.concatenate(([False], np.asarray(mask, dtype=bool), [False]))
    edges = np.flatnonzero(np.diff(m.astype(np.int8)))
    return [(float(x[a]), float(x[b - 1])) for a, b in zip(edges[::2], edges[1::2])]


@styled
def rest_positions(
    x0: np.ndarray, exact: np.ndarray, alg1: np.ndarray, band: float, dt: float, ax: Axes | None = None
) -> Figure:
    """Rest position (mm) against the initial displacement ``x0`` (m): exact and Algorithm 1.

    Parameters
    ----------
    x0, exact, alg1 : ndarray, m
        The grid and the rest positions of the exact solver and of Algorithm 1.
    band : float, m
        ``tau/k``, the half-width of the static band ``|x| <= tau/k``, drawn dashed.
    dt : float, s
        Algorithm 1's step, for the legend.
    """
    fig, ax = new_axes(ax, figsize=(6.4, 3.2))
    ax.axhspan(-band * MM, band * MM, color="0.92", lw=0, label=r"static band $|x| \leq \tau/k$")
    ax.plot(x0, exact * MM, "-", color="k", lw=1.0, label="exact")
    ax.plot(x0, alg1 * MM, ".", color="C0", ms=2.0, label=rf"Algorithm 1, $\Delta t = {dt:g}$ s")
    ax.set_xlabel(r"initial displacement $x_0$ (m)")
    ax.set_ylabel("rest position (mm)")
    legend_above(ax, ncol=3)
    return fig


@styled
def rest_discrepancies(
    x0: np.ndarray, error: np.ndarray, wrong_side: np.ndarray, early: np.ndarray, ax: Axes | None = None
) -> Figure:
    """Algorithm 1's rest-position error (mm) against ``x0`` (m), the x0 intervals of its failures shaded.

    Parameters
    ----------
    x0, error : ndarray, m
        The grid and Algorithm 1's rest position minus the exact one.
    wrong_side, early : ndarray of bool
        Rows where Algorithm 1 rests on the other side of zero, and where it
        stops a half-cycle early; each run of rows is shaded over its x0 span.
    """
    fig, ax = new_axes(ax, figsize=(6.4, 3.2))
    half = 0.5 * float(np.min(np.diff(x0))) if x0.size > 1 else 0.0  # a lone row gets its grid cell
    for mask, colour, label in ((wrong_side, "C3", "wrong side of zero"), (early, "C1", "half-cycle early")):
        for i, (a, b) in enumerate(intervals(x0, mask)):
            ax.axvspan(a - half, b + half, color=colour, alpha=0.35, lw=0, label=label if i == 0 else None)
    ax.plot(x0, error * MM, ".", color="C0", ms=2.0, label="Algorithm 1 minus exact")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel(r"initial displacement $x_0$ (m)")
    ax.set_ylabel("rest-position error (mm)")
    legend_above(ax, ncol=3)
    return fig


@styled
def den_hartog_amplitudes(
    table: Mapping[str, np.ndarray],
    curves: Mapping[tuple[float, float], tuple[np.ndarray, np.ndarray, np.ndarray]],
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Amplitude ratio ``X k/P`` against ``r = omega/omega_n``: one panel per damping ratio, one colour per ``F/P``.

    Parameters
    ----------
    table : mapping of str to ndarray
        Columns ``damping``, ``friction_ratio``, ``frequency_ratio``,
        ``amplitude_ratio`` and ``stops_per_period`` of ``results/studies/den_hartog.csv``:
        simulated points, filled without stops in the window, hollow with stops.
    curves : mapping
        ``(damping, F/P)`` -> ``(r, X k/P, nonstop)`` of the closed form:
        solid where the motion without stops is admissible, dotted where the
        formula has a root but the mass would stop.
    axes : sequence of two Axes, optional
    """
    dampings = sorted({d for d, _ in curves})
    if axes is None:
        _, made = plt.subplots(1, len(dampings), figsize=(6.4, 3.4), sharey=True)
        axes = list(np.atleast_1d(made))
    ratios = sorted({f for _, f in curves})
    for ax, zeta in zip(axes, dampings):
        for i, fp in enumerate(ratios):
            _den_hartog_panel(ax, table, curves[(zeta, fp)], zeta, fp, f"C{i}")
        ax.set_title("Coulomb" if zeta == 0 else rf"Coulomb + viscous, $\zeta = {zeta:g}$", fontsize=9)
    return amplitude_axes(axes, len(ratios))


def amplitude_axes(axes: Sequence[Axes], columns: int) -> Figure:
    """Finish panels of amplitude ratio against frequency ratio (Den Hartog's and the response curves'): log
    amplitude from 1e-2 to 50, the axes' labels, one legend of ``columns`` entries above; their figure."""
    for ax in axes:
        ax.set_xlabel(r"frequency ratio $\omega/\omega_n$")
        ax.set_yscale("log")
    axes[0].set_ylabel(r"amplitude ratio $Xk/P$")
    axes[0].set_ylim(1e-2, 50.0)
    fig = axes[0].figure
    fig.legend(*axes[0].get_legend_handles_labels(), loc="outside upper center", ncol=columns, fontsize=8)
    return fig  # type: ignore[return-value]


def _den_hartog_panel(
    ax: Axes, table: Mapping[str, np.ndarray], line: tuple, zeta: float, fp: float, colour: str
) -> None:
    """One ``F/P`` on one panel: the closed form (solid/dotted) and the simulated points (filled/hollow)."""
    r, ratio, nonstop = (np.asarray(a) for a in line)
    ax.plot(r, np.where(nonstop, ratio, np.nan), "-", color=colour, lw=1.0, label=rf"$F/P = {fp:g}$")
    ax.plot(r, np.where(nonstop, np.nan, ratio), ":", color=colour, lw=1.0)
    rows = (table["damping"] == zeta) & (table["friction_ratio"] == fp)
    still = rows & (table["stops_per_period"] == 0)
    ax.plot(table["frequency_ratio"][still], table["amplitude_ratio"][still], "o", color=colour, ms=3.0)
    stopped = rows & (table["stops_per_period"] > 0)
    ax.plot(table["frequency_ratio"][stopped], table["amplitude_ratio"][stopped], "o", mfc="none", mec=colour, ms=3.5)


@styled
def den_hartog_history(
    t: np.ndarray, x: np.ndarray, amplitude: float, window: tuple[float, float], ax: Axes | None = None
) -> Figure:
    """Displacement (mm) of one long run from rest against time (s), with the closed-form steady amplitude.

    Parameters
    ----------
    t, x : ndarray, s and m
        The run, sampled.
    amplitude : float, m
        The closed form's ``X``, drawn dashed at ``+-X``.
    window : (float, float), s
        The last window of the summary, shaded.
    """
    fig, ax = new_axes(ax, figsize=(6.4, 2.8))
    ax.axvspan(*window, color="0.92", lw=0, label="last window")
    ax.plot(t, x * MM, "-", color="C0", lw=0.6, label="exact solver, from rest")
    for sign in (1, -1):
        ax.axhline(
            sign * amplitude * MM, color="k", ls="--", lw=0.8, label=r"closed form $\pm X$" if sign > 0 else None
        )
    ax.set_xlabel(r"time $t$ (s)")
    ax.set_ylabel(r"displacement $x$ (mm)")
    legend_above(ax, ncol=3)
    return fig


def _cells(values: np.ndarray, log: bool) -> np.ndarray:
    """Edges of the cells centred on the sorted grid ``values`` (geometric midpoints when ``log``)."""
    v = np.log(values) if log else values
    mid = 0.5 * (v[1:] + v[:-1])
    first, last = (2 * v[0] - mid[0], 2 * v[-1] - mid[-1]) if v.size > 1 else (v[0] - 0.5, v[0] + 0.5)
    edges = np.concatenate(([first], mid, [last]))
    return np.exp(edges) if log else edges


@styled
def stops_map(
    frequency_ratio: np.ndarray,
    friction_ratio: np.ndarray,
    stops_per_period: np.ndarray,
    settled: np.ndarray,
    boundary: tuple[np.ndarray, np.ndarray] | None = None,
    boundary_label: str = "nonstop boundary",
    ax: Axes | None = None,
    marked_label: str = "count not settled",
    split: tuple[float, str] | None = None,
) -> Figure:
    """Stops per forcing period over the plane (r = omega/omega_n, F/P): one colour per integer count.

    Parameters
    ----------
    frequency_ratio, friction_ratio, stops_per_period, settled : ndarray
        Columns of ``results/studies/stops.csv`` (one row per grid point, any order of a full grid).
        Points whose count is not settled or not an integer are marked with a cross.
    boundary : (ndarray, ndarray), optional
        A curve ``(r, F/P)`` drawn over the map, e.g. the analytic boundary of nonstop motion
        (the hook for :mod:`lumped.studies.den_hartog`); ``boundary_label`` names it in the legend.
    marked_label : str
        The legend's name for the crosses (points with ``settled == 0``).
    split : (float, str), optional
        ``(r, label)``: a vertical line at ``r`` with its legend entry, e.g. where the map's data change method.
    """
    fig, ax = new_axes(ax, figsize=(6.4, 4.0))
    r, q = np.unique(frequency_ratio), np.unique(friction_ratio)
    grid = np.full((q.size, r.size), np.nan)
    grid[np.searchsorted(q, friction_ratio), np.searchsorted(r, frequency_ratio)] = stops_per_period
    top = int(np.ceil(np.nanmax(grid))) if np.isfinite(grid).any() else 0
    levels = np.arange(top + 2) - 0.5
    cmap = ListedColormap(plt.get_cmap("viridis", top + 1)(np.arange(top + 1)))
    mesh = ax.pcolormesh(_cells(r, True), _cells(q, False), grid, cmap=cmap, norm=BoundaryNorm(levels, top + 1))
    bar = fig.colorbar(mesh, ax=ax, ticks=np.arange(top + 1), label="stops per forcing period")
    bar.ax.minorticks_off()
    odd = (np.asarray(settled) == 0) | (stops_per_period != np.round(stops_per_period))
    if odd.any():
        ax.plot(frequency_ratio[odd], friction_ratio[odd], "x", color="C3", ms=4, label=marked_label)
    if split is not None:
        ax.axvline(split[0], color="0.3", lw=1.0, ls=":", label=split[1])
    ax.axhspan(1.0, 1.1, color="0.85", lw=0, label=r"$F/P \geq 1$: never moves from rest")
    if boundary is not None:
        ax.plot(*boundary, "--", color="C1", lw=1.5, label=boundary_label)
    ax.set_xscale("log")
    ax.set_ylim(0.0, 1.1)
    ax.set_xlabel(r"frequency ratio $r = \omega/\omega_n$")
    ax.set_ylabel(r"friction ratio $F/P$")
    legend_above(ax, ncol=2)
    return fig


@styled
def stop_histories(
    runs: Sequence[tuple[str, np.ndarray, np.ndarray, Sequence[tuple[float, float]]]],
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Displacement against time, one panel per run, stick intervals shaded.

    Parameters
    ----------
    runs : sequence of (str, ndarray, ndarray, sequence of (float, float))
        ``(title, t, x, sticks)``: time in forcing periods, displacement scaled by ``k/P``, and the
        stick intervals in forcing periods.
    """
    if axes is None:
        fig, grid = plt.subplots(len(runs), 1, figsize=(6.4, 1.6 * len(runs) + 0.4), sharex=True)
        axes = list(np.atleast_1d(grid))
    fig = axes[0].figure
    for (title, t, x, sticks), ax in zip(runs, axes):
        for i, (a, b) in enumerate(sticks):
            ax.axvspan(a, b, color="C1", alpha=0.35, lw=0, label="sticking" if i == 0 else None)
        ax.plot(t, x, "-", color="k", lw=1.0)
        ax.set_title(title, fontsize=9)
        ax.set_ylabel(r"$k x / P$")
    axes[-1].set_xlabel(r"time $t / T$ (forcing periods)")
    return fig  # type: ignore[return-value]
