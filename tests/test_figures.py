"""What the article's figures show: the difference panels, legends clear of the data,
the step in the legend, the convergence figure's reference slope, legible text.

Fast (runs at dt = 1e-3); the figures themselves are built by the notebooks.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.text import Text  # noqa: E402

import lumped as L  # noqa: E402
from lumped import (  # noqa: E402
    Bingham,
    LockingBingham,
    Mass,
    Network,
    Spring,
    plotting,  # noqa: E402
    simulate_network,
)
from lumped.plotting import histories  # noqa: E402
from lumped.plotting.convergence import ERRORS as CONVERGENCE_ERRORS  # noqa: E402
from lumped.plotting.convergence import UNITS as CONVERGENCE_UNITS  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
OSC = L.Oscillator.bingham()
DT = 1e-3
#: Eq. (17b), the forcing of Figures 6 to 9 (m = 1 kg, k = 100 N/m, mu_s N_f = 1 N).
FORCE = L.SwitchedSine(amplitude=10.0, omega=5.0 * math.pi, phase=0.0, until=1.0)
FORCED = L.backward_euler(OSC, 2.5, DT, force=FORCE)
FORCED_EXACT = L.solve_exact(OSC, 2.5, force=FORCE)
_V = np.linspace(0.1, 0.3, 5)
#: Made-up arguments of the bifurcation diagram (cy01, cy02): equilibria, two cycle branches, runs, marks.
DIAGRAM = (
    (_V, 1e-3 * _V, _V > 0.2),
    {"stick-slip cycle": (_V, 1e-2 * _V, -1e-2 * _V, _V > 0), "slip-only cycle": (_V, 5e-3 * _V, -5e-3 * _V, _V < 0)},
    (_V[::2], 1e-2 * _V[::2], -1e-2 * _V[::2]),
    {"Hopf, (3): 0.2000 m/s": (0.2, 2e-4), "fold (grazing): 0.3000 m/s": (0.3, 3e-3)},
)


def _text_width_inches() -> float:
    """The article's text width: A4 (21 cm) less the two side margins of paper.typ."""
    typ = (ROOT / "paper" / "paper.typ").read_text(encoding="utf-8")
    assert 'paper: "a4"' in typ
    margin = float(re.search(r"margin: \(x: ([\d.]+)cm", typ).group(1))
    return (21.0 - 2 * margin) / 2.54


@pytest.fixture
def close():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def figure_9():
    """Figure 9 (F_d under eq. 17b) at dt = 1e-3, drawn once for the tests that read it."""
    fig = plotting.time_history(FORCED, FORCED_EXACT, "F_d")
    fig.canvas.draw()
    yield fig
    plt.close(fig)


@pytest.fixture(scope="module")
def figure_6():
    """Figure 6 (x under eq. 17b) at dt = 1e-3."""
    fig = plotting.time_history(FORCED, FORCED_EXACT, "x")
    yield fig
    plt.close(fig)


@pytest.mark.parametrize("column", ["x", "F_d"])
def test_difference_panel_is_algorithm1_minus_exact_on_its_grid(column, figure_6, figure_9):
    fig = {"x": figure_6, "F_d": figure_9}[column]
    main, below = fig.axes
    assert below.get_shared_x_axes().joined(main, below)
    line = below.lines[0]
    exact = FORCED_EXACT.sample(FORCED.dt)
    np.testing.assert_array_equal(line.get_xdata(), FORCED.t)
    np.testing.assert_array_equal(line.get_ydata(), getattr(FORCED, column) - getattr(exact, column))


def test_difference_of_F_d_is_scaled_to_the_points_away_from_switches(figure_9):
    # The 2 mu_s N_f jumps at reversals leave the panel; every point that does
    # is within a step of a switch, is marked by a triangle, and the title counts them.
    below = figure_9.axes[1]
    gap = below.lines[0].get_ydata()
    limit = below.get_ylim()[1]
    off = np.abs(gap) > limit
    calm = histories.settled(FORCED, FORCED_EXACT.sample(DT))
    assert off.any() and not (off & calm).any()
    assert np.abs(gap).max() > 1.9 * OSC.threshold  # the jump is in the data, not hidden
    marked = sum(len(l.get_xdata()) for l in below.lines if l.get_marker() in ("^", "v"))
    assert marked == off.sum()
    assert f"{off.sum()} points off scale" in below.get_title(loc="right")


def test_difference_of_x_shows_every_point(figure_6):
    below = figure_6.axes[1]
    lo, hi = below.get_ylim()
    gap = below.lines[0].get_ydata()
    assert lo <= gap.min() and gap.max() <= hi
    assert "off scale" not in below.get_title(loc="right")


def test_figure_9_legend_hides_no_data_of_the_last_slip(figure_9):
    ax = figure_9.axes[0]
    box = ax.get_legend().get_window_extent()
    assert not box.overlaps(ax.get_window_extent())  # outside the axes altogether
    curves = ax.lines[:2]  # Algorithm 1 and the exact solution, then event markers
    assert [c.get_label().split(",")[0] for c in curves] == ["Algorithm 1", "exact (event-driven)"]
    for line in curves:
        t, y = (np.asarray(a, dtype=float) for a in line.get_data())
        keep = (t >= 1.70) & (t <= 1.78)
        px, py = ax.transData.transform(np.c_[t[keep], y[keep]]).T
        inside = (px >= box.x0) & (px <= box.x1) & (py >= box.y0) & (py <= box.y1)
        assert keep.sum() > 50 and not inside.any(), line.get_label()


@pytest.mark.parametrize(
    ("dt", "tex"),
    [
        (1e-4, r"1\times10^{-4}"),
        (2.5e-4, r"2.5\times10^{-4}"),
        (1e-3, r"1\times10^{-3}"),
        (1.25e-5, r"1.25\times10^{-5}"),
        (0.5, "0.5"),
        (0.01, r"1\times10^{-2}"),
    ],
)
def test_step_is_written_in_scientific_notation(dt, tex):
    assert plotting.sci_tex(dt) == tex


def test_time_history_legend_gives_the_step(figure_6):
    labels = [t.get_text() for t in figure_6.axes[0].get_legend().get_texts()]
    assert labels[0] == r"Algorithm 1, $\Delta t = 1\times10^{-3}$ s"


NUMBERS = {
    "parameters": {"x0_large": 0.5},
    "convergence": {
        "steps": [1e-2, 1e-3, 1e-4],
        "forced_large": {
            "max_x": [1e-2, 1e-3, 1e-4],
            "max_v": [0.1, 0.01, 0.001],
            "int_F_d": [1.0, 0.1, 0.01],
            "rest_position": [None, 2e-4, 3e-5],
        },
        "free_large": {
            "max_x": [2e-2, 2e-3, 2e-4],
            "max_v": [0.2, 0.02, 0.002],
            "int_F_d": [2.0, 0.2, 0.02],
            "rest_position": ["still moving", 1e-3, 0.0],
        },
    },
}


def test_convergence_figure_has_a_slope_one_reference_in_each_panel(close):
    fig = plotting.convergence(NUMBERS)
    for ax in fig.axes:
        assert ax.get_xscale() == ax.get_yscale() == "log"
        (ref,) = [line for line in ax.lines if line.get_label().startswith("slope 1")]
        x, y = (np.log10(np.asarray(a, dtype=float)) for a in ref.get_data())
        assert np.polyfit(x, y, 1)[0] == pytest.approx(1.0, rel=1e-12)


def test_convergence_figure_puts_one_unit_on_each_axis(close):
    # Figure 15 of the article once drew m, m/s and N s on one axis "error (SI units)".
    fig = plotting.convergence(NUMBERS)
    units = {ax.get_ylabel() for ax in fig.axes if ax.get_ylabel()}
    assert units == {"error (m)", "error (m/s)", "error (N s)"}
    rows = [tuple(CONVERGENCE_ERRORS[k][0] for k in keys) for keys in CONVERGENCE_UNITS.values()]
    for i, ax in enumerate(fig.axes):
        drawn = tuple(line.get_label() for line in ax.lines if not line.get_label().startswith("slope"))
        assert drawn == rows[i // 2]  # a row per unit, holding only that unit's errors


def test_convergence_figure_skips_points_without_a_value(close):
    # None / "still moving" (no rest) and 0 (no log) are left out, nothing else.
    fig = plotting.convergence(NUMBERS)
    rest = [line for ax in fig.axes for line in ax.lines if "rest" in line.get_label()]
    assert len(rest) == 2  # the first row (m) of each example
    np.testing.assert_array_equal(rest[0].get_xdata(), [1e-3, 1e-4])
    np.testing.assert_array_equal(rest[1].get_xdata(), [1e-3])


#: A small chain for the tutorial's network figures (ext01 to ext06 are drawn by these helpers).
CHAIN = simulate_network(
    Network(
        [Mass("a", 1.0, 0.3), Mass("b", 1.0)],
        [
            Spring("k", ("a", "b"), 100.0),
            Bingham("fa", ("ground", "a"), 1.0, 1.0),
            Bingham("fb", ("ground", "b"), 1.0, 1.0),
        ],
    ),
    0.5,
    1e-3,
)
#: A grid of x0 for the studies' helpers (st01, st02), with made-up rest positions.
REST_X0 = np.linspace(-1.0, 1.0, 9)
#: Made-up rows and curves for the Den Hartog helpers (dh01): two dampings, two F/P.
DH_TABLE = {
    "damping": np.repeat([0.0, 0.05], 4),
    "friction_ratio": np.tile(np.repeat([0.2, 0.6], 2), 2),
    "frequency_ratio": np.tile([0.5, 2.0], 4),
    "amplitude_ratio": np.linspace(0.1, 2.0, 8),
    "stops_per_period": np.tile([0.0, 2.0], 4),
}
DH_CURVES = {
    (z, f): (np.linspace(0.2, 2.5, 5), np.linspace(2.0, 0.1, 5), np.array([0, 1, 1, 1, 0], bool))
    for z in (0.0, 0.05)
    for f in (0.2, 0.6)
}
#: A 4 x 3 grid of (r, F/P) for the stops map (sp01), flattened as the study's columns.
SPC_R = np.geomspace(0.1, 3.0, 4)
SPC_GRID = tuple(a.ravel() for a in np.meshgrid(SPC_R, [0.2, 0.5, 0.8], indexing="ij"))
FIGURES = {
    "fig01": lambda: plotting.bingham_pair(OSC.dashpot),
    "fig02": plotting.string_spring_triptych,
    "fig03": plotting.oscillator_schematic,
    "fig04": lambda: plotting.bingham_pictorial(OSC.dashpot),
    "fig05": lambda: plotting.time_history_panels(FORCED, FORCED_EXACT),
    "fig09": None,  # the module's figure_9
    "convergence": lambda: plotting.convergence(NUMBERS),
    "ext-panels": lambda: plotting.network_panels(
        {"run": CHAIN}, [("x", "a"), ("v", "a")], levels={("x", "a"): {"$L$": 0.2}}
    ),
    "ext-history": lambda: plotting.network_history({"run": CHAIN}, "force", "k", levels={"level": 1.0}),
    "ext-locking": lambda: plotting.locking_graph(LockingBingham("l", ("ground", "a"), 1.0, math.inf, 2.0)),
    "ext-stick-map": lambda: plotting.stick_map(CHAIN),
    "ext-positions": lambda: plotting.chain_positions(CHAIN),
    "st01": lambda: plotting.rest_positions(REST_X0, 0.01 * np.sin(REST_X0), 0.01 * np.cos(REST_X0), 0.01, 1e-4),
    "st02": lambda: plotting.rest_discrepancies(REST_X0, 1e-3 * REST_X0, REST_X0 > 0.5, REST_X0 < -0.5),
    "dh01": lambda: plotting.den_hartog_amplitudes(DH_TABLE, DH_CURVES),
    "dh02": lambda: plotting.den_hartog_history(REST_X0, 1e-3 * np.sin(REST_X0), 1e-3, (0.5, 1.0)),
    "sp01": lambda: plotting.stops_map(*SPC_GRID, 2.0 * (SPC_GRID[0] < 1), np.ones(12), boundary=(SPC_R, 0.5 / SPC_R)),
    "rc01": lambda: plotting.response_curves(
        {
            (z, f): {
                "r": np.array([0.5, 1.0, 2.0]),
                "ratio": np.array([1.0, 5.0, 0.3]),
                "stable": np.array([True, False, True]),
                "kind": np.array(["regular", "stops-change", "regular"]),
            }
            for z in (0.0, 0.05)
            for f in (0.2, 0.6)
        },
        DH_CURVES,
        DH_TABLE,
    ),
    "rc02": lambda: plotting.network_response(
        np.array([1.0, 2.0, 3.0]),
        {"m1": np.array([0.01, 0.02, 0.01]), "m2": np.array([0.02, 0.01, 0.005])},
        np.array([True, False, True]),
        np.array(["regular", "stops-change", "regular"]),
        (np.array([1.0, 3.0]), {"m1": np.array([0.01, 0.01]), "m2": np.array([0.02, 0.005])}),
        (1.5, 2.5),
    ),
    "sp02": lambda: plotting.stop_histories([("a", REST_X0, REST_X0, [(0.0, 0.5)]), ("b", REST_X0, -REST_X0, [])]),
    "fit01": lambda: plotting.summary_kinks(REST_X0, 0.01 * REST_X0, 0.01 * np.sign(REST_X0), [(0.0, -0.01, 0.01)]),
    "fit02": lambda: plotting.fit_record(_fit()),
    "fr01": lambda: plotting.belt_phase_portrait(
        {"backward Euler": (REST_X0, 0.2 * np.cos(REST_X0))}, (REST_X0, 0.2 * np.sin(REST_X0)), (0.0, 1.0, 0.2)
    ),
    "fr02": lambda: plotting.smoothing_creep(
        (REST_X0, 0.2 * np.cos(REST_X0)), {r"$\varepsilon$": (REST_X0, 0.2 + 1e-3 * REST_X0)}, 0.2, [(0.0, 0.5)]
    ),
    "fr03": lambda: plotting.stribeck_stability(
        {"V": ((REST_X0, 1e-5 * np.exp(REST_X0)), (REST_X0, 1e-5 * np.exp(REST_X0)))},
        (np.array([0.15, 0.25]), np.array([1.0, -1.0])),
        (np.array([0.1, 0.3]), np.array([2.0, -2.0])),
        0.2,
    ),
    "cy01": lambda: plotting.bifurcation_diagram(*DIAGRAM[:3]),
    "cy02": lambda: plotting.bifurcation_diagram(*DIAGRAM),
    "bk01": lambda: plotting.slip_spacetime(REST_X0, np.outer(np.abs(np.sin(REST_X0)), np.ones(5))),
    "bk02": lambda: plotting.event_sizes(np.exp(REST_X0), (2.0, 1.0, 2.0)),
}


def _fit():
    """A fit of the threshold to the paper's free decay over 1 s (fit02's helper)."""
    from lumped.drivers.fit import fit
    from lumped.model.records import Record

    t = np.linspace(0.0, 1.0, 51)
    record = Record(t, {"m": L.solve_exact(OSC, 1.0, x0=0.5).evaluate(t)["x"]})
    start = Network(
        [Mass("m", 1.0, 0.5)], [Spring("spring", ("ground", "m"), 100.0), Bingham("dashpot", ("ground", "m"), 1.2, 1.0)]
    )
    return fit(start, record, "dashpot.threshold")


@pytest.mark.parametrize("name", FIGURES)
def test_text_is_at_least_8_pt_as_printed(name, figure_9, close):
    # The article prints a figure at its drawn size, scaled down only if wider
    # than the text (fig() in paper.typ), so the printed size of a label is its
    # font size times min(1, text width / figure width).
    fig = FIGURES[name]() if FIGURES[name] else figure_9
    fig.canvas.draw()
    scale = min(1.0, _text_width_inches() / fig.get_figwidth())
    texts = [t for t in fig.findobj(Text) if t.get_visible() and t.get_text().strip()]
    assert texts
    smallest = min(t.get_fontsize() for t in texts) * scale
    assert smallest >= 8.0, f"{name}: {smallest:.1f} pt"
    assert fig.get_figwidth() <= _text_width_inches()


def test_stick_band_label_is_clear_of_the_velocity_axis(close):
    fig = plotting.bingham_pictorial(OSC.dashpot)
    ax = fig.axes[0]
    fig.canvas.draw()
    (label,) = [t for t in ax.texts if t.get_text().startswith("stick band")]
    axis = ax.spines["left"].get_window_extent()
    assert not label.get_window_extent().overlaps(axis)


def test_work_precision_labels_each_tanh_point_with_its_eps(close):
    # Figure 16 of the article: the tanh model's points carried no eps, the legend read "rtol 1e-06".
    rows = [
        {"case": "c", "method": "tanh", "resolution": rtol, "eps": eps, "work": work, "relative_position_error": err}
        for rtol, works in ((1e-6, (1000, 950)), (1e-9, (1900, 1800)))
        for eps, work, err in zip((1e-2, 1e-3), works, (0.5, 0.01))
    ]
    fig = plotting.work_precision({"results": rows, "references": {"c": {"title": "case"}}}, ("c",))
    (ax,) = fig.axes
    labels = [t.get_text() for t in ax.texts]
    assert labels == [r"$\varepsilon = 10^{-2}$", r"$\varepsilon = 10^{-3}$"]  # on the first line, in order
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    assert any(text.endswith(r"rtol $10^{-6}$") for text in legend), legend
    assert not any("e-0" in text for text in legend), legend


@pytest.mark.parametrize(("gamma", "inset"), [(1.0, True), (math.inf, False)])
def test_rest_inset_only_where_the_mass_comes_to_rest(close, gamma, inset):
    # Figure 11's inset magnifies the stretched rest; a Coulomb run still moving at 4 s has none to show
    # (the gamma=inf variant of the pipeline once failed here).
    osc = L.Oscillator.bingham(mass=1.0, stiffness=100.0, threshold=1.0, gamma=gamma)
    tr = L.backward_euler(osc, 4.0, 1e-3, x0=0.5)
    exact = L.solve_exact(osc, 4.0, x0=0.5)
    fig = plotting.time_history(tr, exact, "x")
    made = plotting.rest_inset(fig.axes[0], tr, exact, osc.static_band)
    assert (made is not None) == inset
    if inset:
        low, high = made.get_ylim()
        assert low <= -osc.static_band and high >= osc.static_band  # the band is in view
        assert made.get_xlim()[0] <= exact.rest_time <= made.get_xlim()[1]
