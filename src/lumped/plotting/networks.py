"""Pictures of networks (:func:`lumped.simulate_network`): histories, a lock's graph, a chain's stick map.

Each helper draws into ``ax`` (or ``axes``), makes a new styled figure when
none is given, returns the :class:`~matplotlib.figure.Figure` and leaves
global matplotlib state alone, like the rest of :mod:`lumped.plotting`.
The tutorial notebooks 06 to 08 use them for the figures ``ext01`` to ``ext05``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.colors import ListedColormap
from matplotlib.figure import Figure

from lumped.laws import BinghamDashpot, LockingBingham
from lumped.model.trajectory import Trajectory
from lumped.plotting._base import legend_above, new_axes, styled

__all__ = ["chain_positions", "locking_graph", "network_history", "network_panels", "stick_map"]

#: Axis labels of the quantities a trajectory holds.
QUANTITY_LABELS = {"x": "position (m)", "v": "velocity (m/s)", "force": "force (N)"}
#: A reference curve (closed form, exact solution): dashed red, as the paper's figures draw the exact solution.
_REFERENCE = {"color": "C3", "ls": "--", "lw": 1.2}


def _series(tr: Trajectory, quantity: str, name: str) -> np.ndarray:
    """Column ``name`` (a mass for ``x``/``v``, an element for ``force``) of ``tr``."""
    names = tr.network.element_names if quantity == "force" else tr.network.mass_names
    if quantity not in QUANTITY_LABELS:
        raise ValueError(f"quantity must be one of {', '.join(QUANTITY_LABELS)}; got {quantity!r}")
    if name not in names:
        raise ValueError(f"{quantity}: no column {name!r}; expected one of {', '.join(names)}")
    arrays = {"x": tr.positions, "v": tr.velocities, "force": tr.forces}
    return arrays[quantity][:, names.index(name)]


@styled
def network_history(
    runs: Mapping[str, Trajectory],
    quantity: str,
    name: str,
    references: Mapping[str, tuple[np.ndarray, np.ndarray]] | None = None,
    levels: Mapping[str, float] | None = None,
    ax: Axes | None = None,
    legend: bool = True,
) -> Figure:
    """One quantity of one mass or element against time, for several runs.

    Parameters
    ----------
    runs : mapping of label to Trajectory
        Drawn solid, in the colour cycle, in order.
    quantity : {"x", "v", "force"}
        Position (m) or velocity (m/s) of the mass ``name``, or the tension
        (N) of the element ``name``.
    references : mapping of label to (t, y), optional
        Independent solutions (s, and the quantity's unit), drawn dashed red.
    levels : mapping of label to value, optional
        Horizontal dotted lines (a string's length, a lock's speed).
    ax : Axes, optional
    legend : bool
        Draw the legend above the axes, where it hides no data.
    """
    fig, ax = new_axes(ax)
    for label, tr in runs.items():
        ax.plot(tr.t, _series(tr, quantity, name), label=label)
    for label, (t, y) in (references or {}).items():
        ax.plot(t, y, label=label, **_REFERENCE)
    for label, value in (levels or {}).items():
        ax.axhline(value, color="0.4", lw=0.8, ls=":")
        ax.annotate(label, (1.0, value), xycoords=("axes fraction", "data"), ha="right", va="bottom", fontsize=9)
    ax.set_ylabel(QUANTITY_LABELS[quantity])
    ax.set_xlabel("time $t$ (s)")
    if legend:
        legend_above(ax, ncol=3)
    return fig


@styled
def network_panels(
    runs: Mapping[str, Trajectory],
    panels: Sequence[tuple[str, str]],
    references: Mapping[tuple[str, str], Mapping[str, tuple[np.ndarray, np.ndarray]]] | None = None,
    levels: Mapping[tuple[str, str], Mapping[str, float]] | None = None,
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """:func:`network_history` panels stacked on a shared time axis, one legend above.

    ``panels`` lists ``(quantity, name)`` pairs; ``references`` and ``levels``
    are keyed by the same pairs.
    """
    if axes is None:
        _, made = plt.subplots(len(panels), 1, figsize=(6.0, 1.2 + 1.9 * len(panels)), sharex=True)
        axes = list(np.atleast_1d(made))
    for ax, key in zip(axes, panels):
        refs = (references or {}).get(key)
        network_history(runs, key[0], key[1], references=refs, levels=(levels or {}).get(key), ax=ax, legend=False)
    for ax in axes[:-1]:
        ax.set_xlabel("")
    handles = {}
    for ax in axes:
        for line in ax.lines:
            if not line.get_label().startswith("_"):
                handles.setdefault(line.get_label(), line)
    axes[0].legend(handles.values(), handles.keys(), loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=3, fontsize=8)
    return axes[0].figure  # type: ignore[return-value]


def _lock_branches(law: LockingBingham, f_max: float) -> list[tuple[list[float], list[float]]]:
    """The graph of a locking dashpot as polylines ``(w, f)``: the stick and both locks."""
    tau, lock = law.threshold, law.v_lock
    edge = law.threshold + BinghamDashpot(law.threshold, law.gamma).viscosity * lock
    right = ([0.0, 0.0, lock, lock], [-tau, tau, edge, f_max])
    left = ([-lock, -lock, 0.0], [-f_max, -edge, -tau])
    return [left, right]


@styled
def locking_graph(law: LockingBingham, ax: Axes | None = None, f_max: float | None = None) -> Figure:
    """The graph of a locking Bingham dashpot: force ``f`` (N) against rate ``w`` (m/s).

    Vertical at ``w = 0`` (stick, ``|f| <= threshold``) and at ``w = +-v_lock``
    (locked, any ``|f|`` beyond ``threshold + v_lock/gamma``); between them
    the Bingham line of slope ``1/gamma`` (flat for ``gamma = inf``).  Where
    the graph is vertical ``f`` is not a function of ``w``; where it is flat
    ``w`` is not a function of ``f``.
    """
    fig, ax = new_axes(ax)
    edge = law.threshold + BinghamDashpot(law.threshold, law.gamma).viscosity * law.v_lock
    top = max(f_max, edge) if f_max is not None else 2.0 * edge  # never below the lock's corner
    for w, f in _lock_branches(law, top):
        ax.plot(w, f, color="C0", lw=2.0)
    for sign in (-1.0, 1.0):
        ax.axvline(sign * law.v_lock, color="0.5", lw=0.8, ls=":")
    ax.axhline(0.0, color="0.3", lw=0.6)
    ax.axvline(0.0, color="0.3", lw=0.6)
    ax.set_xlim(-1.5 * law.v_lock, 1.5 * law.v_lock)
    ax.set_xlabel("rate $w$ (m/s)")
    ax.set_ylabel("force $f$ (N)")
    return fig


@styled
def stick_map(tr: Trajectory, ax: Axes | None = None) -> Figure:
    """Space-time picture of a chain: which masses are still (``v == 0``) at each saved time.

    Rows are the masses in the network's order (the first at the bottom),
    columns the saved times; still masses are drawn light, moving ones dark.
    """
    fig, ax = new_axes(ax)
    moving = (tr.velocities != 0).T.astype(float)
    dt_saved = tr.t[1] - tr.t[0] if tr.t.size > 1 else 1.0
    extent = (tr.t[0] - dt_saved / 2, tr.t[-1] + dt_saved / 2, -0.5, moving.shape[0] - 0.5)
    cmap = ListedColormap(["#e8eef5", "#1f4e79"])
    ax.imshow(moving, aspect="auto", origin="lower", extent=extent, cmap=cmap, vmin=0, vmax=1, interpolation="nearest")
    ax.grid(False)
    ax.set_xlabel("time $t$ (s)")
    ax.set_ylabel("mass index $i$")
    ax.set_title("dark: moving ($v_i \\neq 0$); light: still", loc="left", fontsize=9)
    return fig


@styled
def chain_positions(tr: Trajectory, spacing: float | None = None, ax: Axes | None = None) -> Figure:
    """Each mass's position against time, mass ``i`` drawn shifted up by ``i * spacing`` (m).

    ``spacing`` defaults to the largest displacement of any mass, so the curves
    do not cross.
    """
    fig, ax = new_axes(ax)
    gap = spacing if spacing is not None else float(np.max(np.abs(tr.positions))) or 1.0
    for i in range(tr.positions.shape[1]):
        ax.plot(tr.t, tr.positions[:, i] + i * gap, color=plt.cm.viridis(i / max(1, tr.positions.shape[1] - 1)), lw=1.0)
    ax.set_xlabel("time $t$ (s)")
    ax.set_ylabel(f"$x_i + {gap:.3g}\\,i$ (m)")
    return fig
