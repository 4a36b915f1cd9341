"""The paper's Figures 1 to 4: constitutive graphs and the schematic of the system.

Each helper draws one picture into ``ax`` (or a new figure when ``ax=None``),
in the project style (:func:`~lumped.plotting._base.styled`), and returns the
:class:`~matplotlib.figure.Figure`; the multi-panel
helpers take ``axes=`` likewise.  Nothing here changes global matplotlib state
or calls ``plt.show()``; the notebooks decide what to save (with
:func:`~lumped.plotting.save_figure`).

The time histories (Figures 5 to 14) are in :mod:`lumped.plotting.histories`.
Every figure is drawn at the size the article prints it (``fig()`` in
``paper/paper.typ`` uses the natural size of the PDF), so the style's 10 pt
text is 10 pt on paper.
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib import patches
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from lumped.laws import BinghamDashpot
from lumped.plotting._base import new_axes, styled

__all__ = [
    "bingham_force_of_velocity",
    "bingham_velocity_of_force",
    "bingham_pictorial",
    "bingham_pair",
    "string_spring_schematic",
    "string_force_of_displacement",
    "string_displacement_of_force",
    "string_spring_triptych",
    "oscillator_schematic",
]

_GRAPH = dict(color="C0", lw=2.0)


def _axes_row(n: int, axes: Sequence[Axes] | None, width: float = 3.2, height: float = 3.0) -> tuple[Figure, list]:
    """``n`` axes side by side (new, styled, ``width`` inches each) or the given ones."""
    if axes is not None:
        return axes[0].figure, list(axes)
    fig, row = plt.subplots(1, n, figsize=(width * n, height))  # inside the caller's style
    return fig, list(np.atleast_1d(row))


def _centre_spines(ax: Axes, xlabel: str, ylabel: str) -> None:
    """Axes through the origin, no ticks: the look of a constitutive sketch."""
    ax.grid(False)
    for side in ("left", "bottom"):
        ax.spines[side].set_position("zero")
    ax.spines["top"].set_visible(False)
    ax.spines["right"].set_visible(False)
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_xlabel(xlabel, loc="right")
    ax.annotate(ylabel, (0, 1), xycoords=("data", "axes fraction"), xytext=(6, 0), textcoords="offset points", va="top")


# --- Figure 1 and Figure 4: the Bingham dashpot, eq. (6) ---------------------


@styled
def bingham_force_of_velocity(law: BinghamDashpot, ax: Axes | None = None, v_max: float = 2.0) -> Figure:
    """Figure 1(a): the force as a *set* of values of the velocity.

    For ``v != 0`` the force is ``sgn(v) mu_s N_f + v/gamma`` (eq. 7); at
    ``v = 0`` it is the whole interval ``[-mu_s N_f, mu_s N_f]``
    (:meth:`~lumped.laws.BinghamDashpot.force_interval`), drawn as a vertical
    segment, so the graph is not that of a function of ``v``.
    """
    fig, ax = new_axes(ax)
    v = np.linspace(0.0, v_max, 50)[1:]
    for s in (1.0, -1.0):
        ax.plot(s * v, law.slip_force(s * v), **_GRAPH)
    lo, hi = law.force_interval(0.0)
    ax.plot([0.0, 0.0], [lo, hi], **_GRAPH)
    ax.plot([0.0, 0.0], [lo, hi], "o", color="C0", ms=4)
    _centre_spines(ax, r"$v$", r"$F_d$")
    ax.annotate(r"$\mu_s N_f$", (0, hi), xytext=(8, 0), textcoords="offset points", va="center")
    ax.annotate(r"$-\mu_s N_f$", (0, lo), xytext=(-8, 0), textcoords="offset points", va="center", ha="right")
    ax.set_title("(a) force against velocity")
    return fig


@styled
def bingham_velocity_of_force(law: BinghamDashpot, ax: Axes | None = None, f_max: float = 3.0) -> Figure:
    """Figure 1(b): the velocity as a *function* of the force, eq. (6)."""
    fig, ax = new_axes(ax)
    force = np.linspace(-f_max, f_max, 601)
    ax.plot(force, law.velocity(force), **_GRAPH)
    _centre_spines(ax, r"$F_d$", r"$v$")
    ax.set_title("(b) velocity against force")
    return fig


@styled
def bingham_pair(law: BinghamDashpot, axes: Sequence[Axes] | None = None) -> Figure:
    """Figure 1: panels (a) and (b) side by side."""
    fig, (left, right) = _axes_row(2, axes)
    bingham_force_of_velocity(law, ax=left)
    bingham_velocity_of_force(law, ax=right)
    return fig


@styled
def bingham_pictorial(law: BinghamDashpot, ax: Axes | None = None, f_max: float = 3.0) -> Figure:
    """Figure 4: eq. (6) with its two constants marked.

    The static band ``|F_d| <= mu_s N_f`` lies on the force axis (shaded) and
    the slope of the two branches outside it is ``gamma``.
    """
    fig, ax = new_axes(ax, figsize=(4.5, 3.4))
    bingham_velocity_of_force(law, ax=ax, f_max=f_max)
    tau, g = law.threshold, law.gamma
    ax.axvspan(-tau, tau, color="C1", alpha=0.15, lw=0)
    # The label sits right of the band (where the graph has no points, v < 0)
    # and points into it, so that the v-axis at F_d = 0 does not cross it.
    ax.annotate(
        "stick band:\n$v = 0$",
        (0.5 * tau, -0.3 * g * (f_max - tau)),
        xytext=(tau + 0.25 * (f_max - tau), -0.6 * g * (f_max - tau)),
        va="center",
        arrowprops=dict(arrowstyle="->", color="0.3", lw=0.8),
    )
    for s in (1, -1):
        ax.annotate(
            f"${'-' if s < 0 else ''}\\mu_s N_f$",
            (s * tau, 0.0),
            xytext=(-4 * s, 6),
            textcoords="offset points",
            ha="right" if s > 0 else "left",
        )
    a, b = tau + 0.35 * (f_max - tau), tau + 0.75 * (f_max - tau)
    ax.plot([a, b, b], [g * (a - tau), g * (a - tau), g * (b - tau)], color="0.3", lw=0.8)
    ax.text(b + 0.05, g * (0.5 * (a + b) - tau), r"slope $\gamma$", va="center")
    ax.set_title("Bingham dashpot, eq. (6)")
    return fig


# --- Figure 2: a spring with an inextensible string in parallel --------------


def _zigzag(ax: Axes, x0: float, x1: float, y: float, turns: int = 6, amp: float = 0.08, **kw: object) -> None:
    """A spring drawn as a zigzag from ``(x0, y)`` to ``(x1, y)``."""
    lead = 0.12 * (x1 - x0)
    xs = np.linspace(x0 + lead, x1 - lead, 2 * turns + 1)
    ys = y + amp * np.array([0] + [(-1) ** i for i in range(2 * turns - 1)] + [0])
    ax.plot(np.r_[x0, xs, x1], np.r_[y, ys, y], color="k", lw=1.2, **kw)


def _wall(ax: Axes, x: float, y0: float, y1: float) -> None:
    """A hatched wall whose face is the line ``x`` from ``y0`` to ``y1``."""
    ax.add_patch(patches.Rectangle((x - 0.12, y0), 0.12, y1 - y0, hatch="///", fill=False, lw=0, color="0.4"))
    ax.plot([x, x], [y0, y1], color="k", lw=1.5)


def _blank(ax: Axes) -> None:
    ax.set_aspect("equal")
    ax.axis("off")


@styled
def string_spring_schematic(ax: Axes | None = None) -> Figure:
    """Figure 2(a): a spring and a slack, inextensible string between a wall and a plate."""
    fig, ax = new_axes(ax)
    _wall(ax, 0.0, -0.6, 0.6)
    _zigzag(ax, 0.0, 2.0, 0.3)
    sag = np.linspace(0.0, 2.0, 60)
    ax.plot(sag, -0.3 - 0.18 * np.sin(np.pi * sag / 2.0), color="C1", lw=1.2)
    ax.add_patch(patches.Rectangle((2.0, -0.55), 0.08, 1.1, color="0.3"))
    ax.annotate("", (2.7, 0.0), (2.08, 0.0), arrowprops=dict(arrowstyle="-|>", color="k"))
    ax.text(2.75, 0.0, "$F$", va="center")
    ax.text(1.0, 0.5, "spring $k$", ha="center")
    ax.text(1.0, -0.62, "inextensible\nstring (slack)", ha="center", va="top", color="C1")
    ax.set_xlim(-0.3, 3.0)
    ax.set_ylim(-1.25, 0.8)
    _blank(ax)
    ax.set_title("(a) spring and string\nin parallel")
    return fig


@styled
def string_force_of_displacement(ax: Axes | None = None, stiffness: float = 1.0, length: float = 1.0) -> Figure:
    """Figure 2(b): force against displacement.

    The spring alone carries ``F = k x`` while the string is slack
    (``x < L``); at ``x = L`` the taut string takes any further tension, so
    every ``F >= k L`` belongs to the graph (a vertical half-line) and the
    displacement cannot exceed ``L``.
    """
    fig, ax = new_axes(ax)
    x = np.linspace(-0.6 * length, length, 50)
    ax.plot(x, stiffness * x, **_GRAPH)
    ax.plot([length, length], [stiffness * length, 2.2 * stiffness * length], **_GRAPH)
    ax.plot([length], [stiffness * length], "o", color="C0", ms=4)
    ax.axvline(length, color="0.5", lw=0.8, ls=":")
    ax.annotate("$L$", (length, 0), xytext=(4, -12), textcoords="offset points")
    ax.annotate("$kL$", (0, stiffness * length), xytext=(-6, 0), textcoords="offset points", ha="right", va="center")
    ax.plot([0, length], [stiffness * length] * 2, color="0.5", lw=0.8, ls=":")
    _centre_spines(ax, "$x$", "$F$")
    ax.set_xlim(-0.7 * length, 1.4 * length)
    ax.set_title("(b) force against\ndisplacement")
    return fig


@styled
def string_displacement_of_force(ax: Axes | None = None, stiffness: float = 1.0, length: float = 1.0) -> Figure:
    """Figure 2(c): the displacement as a *function* of the force, ``x = min(F/k, L)``."""
    fig, ax = new_axes(ax)
    force = np.linspace(-0.6 * stiffness * length, 2.2 * stiffness * length, 300)
    ax.plot(force, np.minimum(force / stiffness, length), **_GRAPH)
    ax.annotate("$kL$", (stiffness * length, 0), xytext=(0, -12), textcoords="offset points", ha="center")
    ax.annotate("$L$", (0, length), xytext=(-6, 0), textcoords="offset points", ha="right", va="center")
    ax.plot([stiffness * length] * 2, [0, length], color="0.5", lw=0.8, ls=":")
    _centre_spines(ax, "$F$", "$x$")
    ax.set_ylim(-0.7 * length, 1.4 * length)
    ax.set_title("(c) displacement\nagainst force")
    return fig


@styled
def string_spring_triptych(axes: Sequence[Axes] | None = None, stiffness: float = 1.0, length: float = 1.0) -> Figure:
    """Figure 2: panels (a), (b) and (c) side by side.

    A new figure is 6.3 in wide, the width of the article's text, so that it
    is printed at the size it is drawn (no text below the style's 10 pt).
    """
    fig, (a, b, c) = _axes_row(3, axes, width=2.1, height=2.6)
    string_spring_schematic(ax=a)
    string_force_of_displacement(ax=b, stiffness=stiffness, length=length)
    string_displacement_of_force(ax=c, stiffness=stiffness, length=length)
    return fig


# --- Figure 3: the mass-spring-dashpot system ---------------------------------


def _dashpot(ax: Axes, x0: float, x1: float, y: float) -> None:
    """A dashpot from ``(x0, y)`` to ``(x1, y)``: an open cylinder and a piston."""
    c0, c1, h = x0 + 0.3 * (x1 - x0), x0 + 0.7 * (x1 - x0), 0.12
    ax.plot([x0, c0], [y, y], color="k", lw=1.2)
    ax.plot([c1, c0, c0, c1], [y + h, y + h, y - h, y - h], color="k", lw=1.2)
    piston = c0 + 0.6 * (c1 - c0)
    ax.plot([piston, piston], [y - 0.8 * h, y + 0.8 * h], color="k", lw=2.0)
    ax.plot([piston, x1], [y, y], color="k", lw=1.2)


@styled
def oscillator_schematic(ax: Axes | None = None) -> Figure:
    """Figure 3: a mass tied to a wall by a spring and a (Bingham) dashpot in parallel."""
    fig, ax = new_axes(ax, figsize=(5.0, 2.8))
    _wall(ax, 0.0, -0.2, 1.2)
    ax.plot([0.0, 3.6], [-0.2, -0.2], color="k", lw=1.2)
    _zigzag(ax, 0.0, 2.0, 0.8)
    _dashpot(ax, 0.0, 2.0, 0.2)
    ax.add_patch(patches.Rectangle((2.0, -0.1), 0.8, 1.2, fc="0.85", ec="k", lw=1.2))
    for cx in (2.2, 2.6):
        ax.add_patch(patches.Circle((cx, -0.15), 0.05, fc="w", ec="k", lw=0.8))
    ax.text(2.4, 0.5, "$m$", ha="center", va="center", fontsize=13)
    ax.text(1.0, 1.0, "$k$", ha="center")
    ax.text(1.0, -0.05, r"$\mu_s N_f,\ \gamma$", ha="center", va="top")
    ax.annotate("", (3.5, 0.5), (2.8, 0.5), arrowprops=dict(arrowstyle="-|>", color="k"))
    ax.text(3.55, 0.5, "$F(t)$", va="center")
    ax.annotate("", (2.9, 1.35), (2.4, 1.35), arrowprops=dict(arrowstyle="-|>", color="k"))
    ax.plot([2.4, 2.4], [1.2, 1.45], color="k", lw=0.8)
    ax.text(2.95, 1.35, "$x(t)$", va="center")
    ax.set_xlim(-0.3, 4.1)
    ax.set_ylim(-0.4, 1.6)
    _blank(ax)
    return fig
