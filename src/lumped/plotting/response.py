"""The response curves of notebook 13 (issue 23): amplitude against frequency along branches of periodic motion,
of one mass (rc01) and of each mass of a network (rc02)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from lumped.plotting._base import styled
from lumped.plotting.studies import amplitude_axes

__all__ = ["network_response", "response_curves"]


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
    return amplitude_axes(axes, len(ratios))


def _panel(ax: Axes, branch: Mapping[str, np.ndarray], fp: float, colour: str) -> None:
    """One branch: stable solid, unstable dashed, the points where the stops per period change as squares."""
    r, ratio, stable = (np.asarray(branch[k]) for k in ("r", "ratio", "stable"))
    ax.plot(r, np.where(stable, ratio, np.nan), "-", color=colour, lw=1.2, label=rf"$F/P = {fp:g}$")
    if not stable.all():
        ax.plot(r, np.where(stable, np.nan, ratio), "--", color=colour, lw=1.2)
    change = np.asarray(branch["kind"]) == "stops-change"
    ax.plot(r[change], ratio[change], "s", color=colour, ms=4)


@styled
def network_response(
    omega: np.ndarray,
    amplitudes: Mapping[str, np.ndarray],
    stable: np.ndarray,
    kind: np.ndarray,
    linear: tuple[np.ndarray, Mapping[str, np.ndarray]] | None = None,
    natural: Sequence[float] = (),
    ax: Axes | None = None,
) -> Figure:
    """The amplitude of each mass (mm) against ``omega`` (rad/s) along one branch of a network's periodic motions.

    Parameters
    ----------
    omega : array (k,)
        The branch's frequencies in order.
    amplitudes : mapping of str to array (k,)
        Mass name -> half of max x minus min x over the period (m): one colour per mass, solid where
        ``stable``, dashed where not; the points where ``kind`` is ``stops-change`` marked with a square.
    stable, kind : array (k,)
    linear : (array, mapping), optional
        ``(omega, {mass: amplitude})`` of a reference curve (the network without friction), thin dotted.
    natural : sequence of float
        Natural frequencies (rad/s), thin vertical lines.
    ax : Axes, optional
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 3.4))
    stable, change = np.asarray(stable, dtype=bool), np.asarray(kind) == "stops-change"
    for i, (name, amp) in enumerate(amplitudes.items()):
        mm = 1e3 * np.asarray(amp)
        ax.plot(omega, np.where(stable, mm, np.nan), "-", color=f"C{i}", lw=1.2, label=name)
        if not stable.all():
            ax.plot(omega, np.where(stable, np.nan, mm), "--", color=f"C{i}", lw=1.2)
        ax.plot(omega[change], mm[change], "s", color=f"C{i}", ms=4)
        if linear is not None:
            ax.plot(linear[0], 1e3 * np.asarray(linear[1][name]), ":", color=f"C{i}", lw=0.9)
    for w in natural:
        ax.axvline(w, color="0.6", lw=0.6)
    ax.plot([], [], "s", color="0.4", ms=4, label="stops change")
    if linear is not None:
        ax.plot([], [], ":", color="0.4", lw=0.9, label="without friction")
    ax.set_xlabel(r"forcing frequency $\omega$ (rad/s)")
    ax.set_ylabel("amplitude (mm)")
    ax.legend(loc="upper right", fontsize=8)
    return ax.figure  # type: ignore[return-value]
