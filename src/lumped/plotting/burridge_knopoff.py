"""The Burridge-Knopoff chain (notebook 17): a slip event in space and time, and the distribution of event sizes."""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure

from lumped.plotting._base import legend_above, new_axes, styled

__all__ = ["event_sizes", "slip_spacetime"]


@styled
def slip_spacetime(t: np.ndarray, v: np.ndarray, floor: float = 1e-6, ax: Axes | None = None) -> Figure:
    """The blocks' speeds ``|v|`` (S, N) over time ``t`` (S,) and block number, log colour scale; stuck cells white.

    ``floor``: speeds below it (and the stuck blocks' zeros) are drawn as stuck.
    """
    fig, ax = new_axes(ax, figsize=(6.0, 3.6))
    speed = np.ma.masked_less(np.abs(np.asarray(v, float)), floor)
    image = ax.pcolormesh(
        np.asarray(t, float),
        np.arange(speed.shape[1]),
        speed.T,
        shading="nearest",
        cmap="viridis",
        norm=LogNorm(vmin=floor, vmax=max(float(speed.max()), 10 * floor)),
        rasterized=True,
    )
    fig.colorbar(image, ax=ax, label=r"speed $|\dot U_j|$ (units $D_0\omega_p$)")
    ax.set(xlabel=r"time $\omega_p t$", ylabel="block $j$")
    return fig


@styled
def event_sizes(
    moments: np.ndarray,
    fit: tuple[float, float, float] | None = None,
    bins_per_decade: int = 5,
    ax=None,  # noqa: ANN001
) -> Figure:
    """The density of event moments on log-log axes (log-spaced bins), with a fitted power law over its range.

    ``fit``: ``(exponent, low, high)``, drawn as ``s^-exponent`` through the histogram's mass in ``[low, high]``.
    """
    fig, ax = new_axes(ax, figsize=(5.5, 4.0))
    m = np.asarray(moments, float)
    m = m[m > 0]
    edges = 10.0 ** np.arange(
        np.floor(np.log10(m.min())), np.log10(m.max()) + 1.0 / bins_per_decade, 1.0 / bins_per_decade
    )
    counts, _ = np.histogram(m, edges)
    density = counts / (m.size * np.diff(edges))
    centres = np.sqrt(edges[1:] * edges[:-1])
    ax.loglog(centres[counts > 0], density[counts > 0], "o", mfc="none", label=f"{m.size} events")
    if fit is not None:
        a, low, high = fit
        s = np.geomspace(low, min(high, m.max()), 50)
        inside = (m >= low) & (m <= high)
        norm = (
            inside.mean() * (1 - a) / (high ** (1 - a) - low ** (1 - a))
            if np.isfinite(high)
            else inside.mean() * (a - 1) / low ** (1 - a)
        )
        ax.loglog(s, norm * s**-a, "-", color="C3", label=f"power law, exponent {a:.2f}")
    ax.set(xlabel=r"moment $M = \sum_j \delta U_j$ (units $D_0$)", ylabel="density (per unit moment)")
    legend_above(ax, ncol=2)
    return fig
