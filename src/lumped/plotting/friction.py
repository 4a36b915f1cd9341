"""Friction on a belt (issue 33, notebook 15): a contact's graph, the phase portrait with its stick
segment, what ``tanh`` smoothing does to the stick (creep), and the stability of steady sliding on a
Stribeck belt about its Hopf speed."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from lumped.plotting._base import legend_above, new_axes, styled

__all__ = ["belt_phase_portrait", "friction_graph", "smoothing_creep", "stribeck_stability"]

Curve = tuple[np.ndarray, np.ndarray]


@styled
def friction_graph(laws: Mapping[str, object], speed: float, ax: Axes | None = None) -> Figure:
    """Each law's graph in (rate, tension): ``T = sgn(u) g(|u|)`` off zero rate, ``[-static, static]`` at it.

    Parameters
    ----------
    laws : mapping label -> SlipLaw
        Laws of :class:`lumped.laws.SlipLaw` (``static`` and ``slip(speed)``).
    speed : float, m/s
        The rates drawn are ``[-speed, speed]``.
    ax : Axes, optional
    """
    fig, ax = new_axes(ax, figsize=(5.0, 3.4))
    u = np.linspace(0.0, speed, 801)[1:]
    for i, (label, law) in enumerate(laws.items()):
        g = np.asarray(law.slip(u), dtype=float)  # type: ignore[attr-defined]
        s = law.static  # type: ignore[attr-defined]
        colour = f"C{i}"
        ax.plot(
            np.concatenate((-u[::-1], [0.0, 0.0], u)),
            np.concatenate((-g[::-1], [-s, s], g)),
            color=colour,
            lw=1.3,
            label=label,
        )
    ax.axhline(0.0, color="k", lw=0.5)
    ax.axvline(0.0, color="k", lw=0.5)
    ax.set(xlabel="rate $u$ (m/s)", ylabel="tension $T$ (N)")
    legend_above(ax, ncol=2)
    return fig


@styled
def belt_phase_portrait(
    runs: Mapping[str, Curve],
    cycle: Curve,
    stick: tuple[float, float, float],
    ax: Axes | None = None,
) -> Figure:
    """Phase portraits ``(x, v)`` of simulated runs over the closed-form limit cycle, its stick segment marked.

    Parameters
    ----------
    runs : mapping label -> (x, v)
        Positions (m) and velocities (m/s) of each run, drawn as thin lines.
    cycle : (x, v)
        The closed-form cycle, sampled (drawn dashed, black).
    stick : (x_start, x_end, V)
        The stick segment ``v = V`` from ``x_start`` to ``x_end`` (drawn thick).
    ax : Axes, optional
    """
    fig, ax = new_axes(ax, figsize=(5.6, 3.8))
    for i, (label, (x, v)) in enumerate(runs.items()):
        ax.plot(x, v, color=f"C{i}", lw=0.9, label=label)
    ax.plot(*cycle, "--", color="k", lw=1.0, label="closed form")
    start, end, belt = stick
    ax.plot([start, end], [belt, belt], color="C3", lw=4.0, alpha=0.5, solid_capstyle="butt", label="stick, $v = V$")
    ax.set(xlabel="$x$ (m)", ylabel="$v$ (m/s)")
    legend_above(ax, ncol=2)
    return fig


@styled
def smoothing_creep(
    reference: Curve,
    runs: Mapping[str, Curve],
    belt: float,
    stick: Sequence[tuple[float, float]],
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Velocity over one cycle of smoothed models against the exact one (upper), and the creep (lower).

    Parameters
    ----------
    reference : (t, v)
        The exact cycle's velocity (s, m/s), drawn dashed, black.
    runs : mapping label -> (t, v)
        Each smoothed run, on the same time axis (aligned by the caller).
    belt : float, m/s
        The belt's speed ``V``: the lower panel draws ``|v - V|`` on a log scale.
    stick : sequence of (t_start, t_end)
        The exact stick intervals, shaded in both panels.
    axes : two Axes, optional
    """
    if axes is None:
        _, made = plt.subplots(2, 1, figsize=(6.2, 4.6), sharex=True, height_ratios=(1.3, 1.0))
        axes = list(made)
    top, bottom = axes
    for i, (label, (t, v)) in enumerate(runs.items()):
        top.plot(t, v, color=f"C{i}", lw=1.0, label=label)
        bottom.semilogy(t, np.maximum(np.abs(np.asarray(v) - belt), 1e-12), color=f"C{i}", lw=1.0)
    top.plot(*reference, "--", color="k", lw=1.0, label="exact")
    for ax in (top, bottom):
        for start, end in stick:
            ax.axvspan(start, end, color="0.9", zorder=0)
    top.set_ylabel("$v$ (m/s)")
    bottom.set(xlabel="$t$ (s)", ylabel="$|v - V|$ (m/s)", ylim=(1e-7, 1.0))
    legend_above(top, ncol=4)
    return top.figure  # type: ignore[return-value]


@styled
def stribeck_stability(
    swings: Mapping[str, tuple[Curve, Curve]],
    measured: Curve,
    linear: Curve,
    hopf: float,
    axes: Sequence[Axes] | None = None,
) -> Figure:
    """Steady sliding on a Stribeck belt: swings growing or decaying (left), growth rate against belt speed (right).

    Parameters
    ----------
    swings : mapping label -> ((t, swing), (t, predicted))
        For each belt speed, the oscillation's swings (s, m) and the linearised motion's prediction, drawn
        on a log scale (solid and dashed, one colour each).
    measured : (speeds, rates)
        Growth rates measured from simulated runs (m/s, 1/s), drawn as markers.
    linear : (speeds, rates)
        The linearised motion's growth rate (m/s, 1/s), drawn as a line.
    hopf : float, m/s
        The Hopf speed, where the linear rate vanishes: marked in the right panel.
    axes : two Axes, optional
    """
    if axes is None:
        _, made = plt.subplots(1, 2, figsize=(6.4, 3.3))
        axes = list(made)
    left, right = axes
    for i, (label, ((t, swing), (tp, predicted))) in enumerate(swings.items()):
        left.semilogy(t, swing, color=f"C{i}", lw=1.0, label=label)
        left.semilogy(tp, predicted, "--", color=f"C{i}", lw=0.9)
    left.set(xlabel="$t$ (s)", ylabel="swing (m)")
    legend_above(left, ncol=1)
    right.plot(*linear, color="k", lw=1.0, label="linearised")
    right.plot(*measured, "o", color="C3", ms=4, label="event-driven")
    right.axhline(0.0, color="k", lw=0.5)
    right.axvline(hopf, color="0.5", lw=0.8, ls=":", label=f"Hopf speed {hopf:.4f} m/s")
    right.set(xlabel="belt speed $V$ (m/s)", ylabel="growth rate (1/s)")
    legend_above(right, ncol=1)
    return left.figure  # type: ignore[return-value]
