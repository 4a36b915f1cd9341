"""Plots for the tutorial on the textbook model (notebook 02).

Each helper takes ``ax=`` (draw into an existing Axes, or ``None`` for a new
styled figure), returns the :class:`~matplotlib.figure.Figure`, never calls
``plt.show()`` and leaves global matplotlib state alone (the project style is
applied by the decorator :func:`lumped.plotting._base.styled`, to the helper only).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from lumped.model.oscillator import Oscillator
from lumped.model.trajectory import Trajectory
from lumped.plotting._base import new_axes, sci_tex, styled
from lumped.solvers.textbook import AdaptiveOutcome, FixedStepResult

__all__ = ["acceleration_graph", "chatter", "creep"]


@styled
def acceleration_graph(
    oscillator: Oscillator,
    x: float,
    force: float = 0.0,
    v_max: float = 1e-2,
    ax: Axes | None = None,
) -> Figure:
    """Acceleration against velocity at displacement ``x`` (m), eqs. (11).

    For ``v != 0`` the acceleration is single-valued (eqs. 11a, 11b); at
    ``v = 0`` it is the segment of eq. (11c), ``(F - k x - F_d)/m`` for
    ``|F_d| <= mu_s N_f``.  The point of that segment with zero acceleration,
    if any, is marked: it is the dashpot force that keeps the mass at rest.
    """
    law, m = oscillator.dashpot, oscillator.mass
    net = force - oscillator.stiffness * x
    v = np.linspace(0.0, v_max, 201)[1:]
    fig, ax = new_axes(ax)
    for side, label in ((1, "eq. (11a), $v > 0$"), (-1, "eq. (11b), $v < 0$")):
        ax.plot(side * v, (net - law.slip_force(side * v)) / m, label=label)
    ends = (net - law.threshold) / m, (net + law.threshold) / m
    ax.plot([0.0, 0.0], ends, color="C3", lw=4, alpha=0.6, label="eq. (11c), $v = 0$")
    if abs(net) <= law.threshold:
        ax.plot([0.0], [0.0], "o", color="k", label=rf"$F_d = {net:.3g}$ N: rest")
    ax.axhline(0.0, color="0.5", lw=0.8)
    ax.set_xlabel(r"velocity $v$ (m/s)")
    ax.set_ylabel(r"acceleration $\dot v$ (m/s$^2$)")
    ax.legend(loc="best")
    return fig


@styled
def chatter(
    runs: Mapping[str, FixedStepResult],
    reference: Trajectory | None = None,
    t_max: float | None = None,
    ax: Axes | None = None,
) -> Figure:
    """Dashpot force (N) against time (ms) of fixed-step runs, with the DAE's.

    ``runs`` maps a label to a :class:`~lumped.solvers.textbook.FixedStepResult`;
    ``reference`` is a trajectory of the DAE (Algorithm 1 or the exact
    solution); ``t_max`` (s) crops the time axis.

    The runs often share values (every scheme sits at ``-mu_s N_f`` for long
    stretches), so each is drawn wider and lighter than the one after it and
    below it: where two coincide the earlier shows as a band around the later.
    """
    fig, ax = new_axes(ax)
    if reference is not None:
        keep = slice(None) if t_max is None else reference.t <= t_max
        ax.plot(1e3 * reference.t[keep], reference.F_d[keep], color="k", lw=1.5, ls="--", zorder=3, label="DAE")
    n = len(runs)
    for i, (label, run) in enumerate(runs.items()):
        keep = slice(None) if t_max is None else run.t <= t_max
        ax.step(
            1e3 * run.t[keep],
            run.F_d[keep],
            where="post",
            lw=1.0 + 3.0 * (n - 1 - i),
            alpha=0.45 if i < n - 1 else 1.0,
            color=f"C{i}",
            zorder=2 + i / n,
            label=label,
        )
    ax.set_xlabel(r"time $t$ (ms)")
    ax.set_ylabel(r"dashpot force $F_d$ (N)")
    ax.legend(loc="center right")
    return fig


@styled
def creep(runs: Mapping[float, AdaptiveOutcome], rest: float | None = None, ax: Axes | None = None) -> Figure:
    """Displacement (m) against time (s) of regularised runs, one per ``eps``.

    ``runs`` maps ``eps`` (m/s) to an :class:`~lumped.solvers.textbook.AdaptiveOutcome`;
    ``rest`` (m) is the DAE's rest position, drawn as a thin dashed line under
    the runs; a run that creeps very little stays visible above it, and a dot
    marks where each run ends.
    """
    fig, ax = new_axes(ax)
    if rest is not None:
        ax.axhline(rest, color="k", lw=1.0, ls=(0, (4, 3)), zorder=1.5, label="DAE (Algorithm 1, exact)")
    for i, (eps, run) in enumerate(runs.items()):
        ax.plot(
            run.t,
            run.x,
            color=f"C{i}",
            lw=1.5,
            marker="o",
            markevery=[-1],
            zorder=2,
            label=rf"$\tanh(v/\varepsilon)$, $\varepsilon = {sci_tex(eps, digits=1, show_one=False)}$ m/s",
        )
    ax.set_xlabel(r"time $t$ (s)")
    ax.set_ylabel(r"displacement $x$ (m)")
    ax.legend(loc="best")
    return fig
