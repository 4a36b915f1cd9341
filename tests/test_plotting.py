"""Plot helpers: one style mechanism, and global matplotlib state left alone."""

from __future__ import annotations

import functools

import matplotlib
import numpy as np

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

import lumped as L  # noqa: E402
from lumped import (  # noqa: E402
    Bingham,
    Mass,
    Network,
    Spring,
    plotting,  # noqa: E402
    simulate_network,
)
from lumped.laws.stribeck import StribeckLaw  # noqa: E402
from lumped.plotting import textbook as textbook_plots  # noqa: E402
from lumped.solvers.textbook import TextbookModel, integrate_adaptive, integrate_fixed  # noqa: E402

#: The style file's own setting (read from the file, not from the package's code).
STYLE_FRAMEON = matplotlib.rc_params_from_file(plotting.STYLE, use_default_template=False)["legend.frameon"]


def _runs():
    osc = L.Oscillator.bingham()
    traj = L.backward_euler(osc, 0.5, 1e-3, x0=0.5)
    exact = L.solve_exact(osc, 0.5, x0=0.5)
    model = TextbookModel(osc)
    fixed = {"Euler": integrate_fixed(model, 0.01, 1e-4, x0=0.005)}
    adaptive = {1e-2: integrate_adaptive(TextbookModel(osc, eps=1e-2), 0.05, x0=0.005)}
    return osc, traj, exact, fixed, adaptive


OSC, TRAJ, EXACT, FIXED, ADAPTIVE = _runs()
#: A network run for the network helpers: the paper's system through the active-set step.
NET = simulate_network(
    Network(
        [Mass("m", 1.0, 0.5)],
        [Spring("k", ("ground", "m"), 100.0), Bingham("d", ("ground", "m"), 1.0, 1.0)],
    ),
    0.5,
    1e-3,
    solver="active-set",
)


@functools.cache
def _fit():
    """A fit of the paper's free decay to its own exact motion (issue 24), for :func:`plotting.fit_record`."""
    from lumped.drivers.fit import fit
    from lumped.model.records import Record

    t = np.linspace(0.0, 1.0, 51)
    record = Record(t, {"m": L.solve_exact(OSC, 1.0, x0=0.5).evaluate(t)["x"]})
    return fit(oscillator_network_with_names(), record, "dashpot.threshold")


def oscillator_network_with_names() -> Network:
    return Network(
        [Mass("m", 1.0, 0.5)],
        [Spring("spring", ("ground", "m"), 100.0), Bingham("dashpot", ("ground", "m"), 1.2, 1.0)],
    )


_T = np.linspace(0.0, 1.0, 11)
#: Made-up arguments of the belt helpers (notebook 15): runs, closed form and stick segment; the creep's.
BELT = ({"run": (_T, 0.2 * np.cos(_T))}, (_T, 0.2 * np.sin(_T)), (0.0, 1.0, 0.2))
CREEP = ((_T, 0.2 * np.cos(_T)), {"eps": (_T, 0.2 + 1e-3 * _T)}, 0.2, [(0.0, 0.3), (0.7, 1.0)])
#: The bifurcation diagram's (notebook 16): equilibria stable from 0.5 on, a cycle branch stable from 0.4 on.
DIAGRAM = ((_T, 0.1 * _T, _T >= 0.5), {"cycle": (_T, 1 + _T, -1 - _T, _T > 0.35)})

#: Every helper that draws a legend, as a call taking ``ax``.
LEGENDS = {
    "time_history": lambda ax: plotting.time_history(TRAJ, EXACT, "x", ax=ax),
    "time_history_panels": lambda ax: plotting.time_history_panels(TRAJ, EXACT, axes=[ax] * 4),
    "acceleration_graph": lambda ax: textbook_plots.acceleration_graph(OSC, 0.005, ax=ax),
    "chatter": lambda ax: textbook_plots.chatter(FIXED, TRAJ, ax=ax),
    "creep": lambda ax: textbook_plots.creep(ADAPTIVE, rest=0.005, ax=ax),
    "network_history": lambda ax: plotting.network_history({"run": NET}, "x", "m", ax=ax),
    "network_panels": lambda ax: plotting.network_panels({"run": NET}, [("x", "m"), ("v", "m")], axes=[ax] * 2),
    "fit_record": lambda ax: plotting.fit_record(_fit(), axes=[ax] * 2),
    "friction_graph": lambda ax: plotting.friction_graph({"law": StribeckLaw(1.0, 0.5, 0.01)}, 0.05, ax=ax),
    "belt_phase_portrait": lambda ax: plotting.belt_phase_portrait(*BELT, ax=ax),
    "smoothing_creep": lambda ax: plotting.smoothing_creep(*CREEP, axes=[ax] * 2),
    "bifurcation_diagram": lambda ax: plotting.bifurcation_diagram(*DIAGRAM, ax=ax),
}
#: Helpers whose ``ax=None`` call is spelled differently (they take ``axes``).
WHOLE = {
    "time_history_panels": lambda: plotting.time_history_panels(TRAJ, EXACT),
    "network_panels": lambda: plotting.network_panels({"run": NET}, [("x", "m"), ("v", "m")]),
    "fit_record": lambda: plotting.fit_record(_fit()),
    "smoothing_creep": lambda: plotting.smoothing_creep(*CREEP),
}


def test_the_style_file_differs_from_matplotlib_on_legend_frames():
    # Otherwise the next test could not tell styled from unstyled legends.
    assert STYLE_FRAMEON is False and matplotlib.rcParamsDefault["legend.frameon"] is True


@pytest.mark.parametrize("helper", LEGENDS)
def test_legend_drawn_into_an_unstyled_axes_follows_the_style_file(helper):
    # Axes made outside the package (default rcParams, frames on): the helper
    # draws inside the style, so its legend takes the style's legend.frameon.
    # (time_history_panels draws one legend for the figure, above the panels.)
    with matplotlib.rc_context(matplotlib.rcParamsDefault):
        ax = Figure().add_subplot()
        LEGENDS[helper](ax)
    legend = ax.get_legend() or (ax.figure.legends[0] if ax.figure.legends else None)
    assert legend is not None
    assert legend.get_frame_on() is STYLE_FRAMEON


@pytest.mark.parametrize("helper", LEGENDS)
def test_helpers_leave_global_rcparams_alone(helper):
    before = dict(matplotlib.rcParams)
    fig = WHOLE[helper]() if helper in WHOLE else LEGENDS[helper](None)
    assert isinstance(fig, Figure)
    after = dict(matplotlib.rcParams)
    assert {k for k in before if before[k] != after[k]} <= {"interactive"}
    plt.close(fig)


def test_summary_kinks_leaves_global_rcparams_alone_and_marks_each_kink():
    before = dict(matplotlib.rcParams)
    x = np.linspace(0.0, 1.0, 11)
    fig = plotting.summary_kinks(x, x**2, 2 * x, kinks=[(0.5, 0.9, 1.1)])
    assert {k for k in before if before[k] != dict(matplotlib.rcParams)[k]} <= {"interactive"}
    top, bottom = fig.axes
    assert len(bottom.lines) == 5 and len(top.lines) == 2  # the curve, the kink's line, its two circles, the axis
    plt.close(fig)


def test_bifurcation_diagram_draws_stable_solid_and_unstable_dashed_joined_where_stability_changes():
    """Each branch splits into runs of equal stability; a run is joined to the next point (no gap at the change),
    solid where stable, dashed where not, and each kind is labelled once per branch."""
    fig = plotting.bifurcation_diagram(*DIAGRAM)
    (ax,) = fig.axes
    pieces = [(line.get_linestyle(), line.get_xdata()[0], line.get_xdata()[-1], line.get_label()) for line in ax.lines]
    assert pieces[:2] == [("--", 0.0, 0.5, "equilibrium, unstable"), ("-", 0.5, 1.0, "equilibrium, stable")]
    high = pieces[2:4]
    assert [p[:3] for p in high] == [("--", 0.0, 0.4), ("-", 0.4, 1.0)]  # stable from 0.4 on
    assert [p[3] for p in high] == ["cycle, unstable", "cycle, stable"]
    assert all(p[3].startswith("_") for p in pieces[4:6])  # the lower extremes: same styles, no second label
    plt.close(fig)
