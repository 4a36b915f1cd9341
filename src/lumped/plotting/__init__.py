"""Plot helpers (matplotlib).  Each takes ``ax=``, returns the Figure and leaves
global matplotlib state alone; :func:`save_figure` writes reproducible files.

matplotlib is the optional extra ``plot``: ``pip install "lumped[plot]"`` (from
the checkout, ``pip install ".[plot]"``); the solver itself does not need it.
"""

try:
    import matplotlib  # noqa: F401  (only to say which extra is missing)
except ModuleNotFoundError as err:
    if err.name != "matplotlib":  # installed but broken: its own message says why
        raise
    raise ImportError(
        "lumped.plotting needs matplotlib, which is not installed:"
        ' pip install "lumped[plot]" (in the checkout: pip install ".[plot]")'
    ) from None

from lumped.plotting._base import STYLE, legend_above, new_axes, save_figure, sci_tex, style, styled
from lumped.plotting.accuracy import accuracy_convergence, work_precision
from lumped.plotting.burridge_knopoff import event_sizes, slip_spacetime
from lumped.plotting.convergence import convergence
from lumped.plotting.cycles import bifurcation_diagram
from lumped.plotting.figures import (
    bingham_pair,
    bingham_pictorial,
    oscillator_schematic,
    string_spring_triptych,
)
from lumped.plotting.fit import fit_record, summary_kinks
from lumped.plotting.friction import belt_phase_portrait, friction_graph, smoothing_creep, stribeck_stability
from lumped.plotting.histories import (
    difference,
    exact_fine,
    exact_on_grid,
    rest_inset,
    step_label,
    time_history,
    time_history_panels,
)
from lumped.plotting.networks import chain_positions, locking_graph, network_history, network_panels, stick_map
from lumped.plotting.response import network_response, response_curves
from lumped.plotting.studies import (
    den_hartog_amplitudes,
    den_hartog_history,
    rest_discrepancies,
    rest_positions,
    stop_histories,
    stops_map,
)

__all__ = [
    "STYLE",
    "accuracy_convergence",
    "belt_phase_portrait",
    "bifurcation_diagram",
    "bingham_pair",
    "bingham_pictorial",
    "chain_positions",
    "convergence",
    "den_hartog_amplitudes",
    "den_hartog_history",
    "difference",
    "event_sizes",
    "exact_fine",
    "exact_on_grid",
    "fit_record",
    "friction_graph",
    "legend_above",
    "locking_graph",
    "network_history",
    "network_response",
    "network_panels",
    "new_axes",
    "oscillator_schematic",
    "response_curves",
    "rest_discrepancies",
    "rest_inset",
    "rest_positions",
    "save_figure",
    "sci_tex",
    "slip_spacetime",
    "smoothing_creep",
    "step_label",
    "stick_map",
    "stop_histories",
    "stops_map",
    "string_spring_triptych",
    "stribeck_stability",
    "style",
    "styled",
    "summary_kinks",
    "time_history",
    "time_history_panels",
    "work_precision",
]
