"""Plot helpers (matplotlib).  Each takes ``ax=``, returns the Figure and leaves
global matplotlib state alone; :func:`save_figure` writes reproducible files."""

from lumped.plotting._base import STYLE, legend_above, new_axes, save_figure, sci_tex, style, styled
from lumped.plotting.convergence import convergence
from lumped.plotting.figures import (
    bingham_pair,
    bingham_pictorial,
    oscillator_schematic,
    string_spring_triptych,
)
from lumped.plotting.histories import (
    difference,
    exact_fine,
    exact_on_grid,
    step_label,
    time_history,
    time_history_panels,
)

__all__ = [
    "STYLE",
    "bingham_pair",
    "bingham_pictorial",
    "convergence",
    "difference",
    "exact_fine",
    "exact_on_grid",
    "legend_above",
    "new_axes",
    "oscillator_schematic",
    "save_figure",
    "sci_tex",
    "step_label",
    "string_spring_triptych",
    "style",
    "styled",
    "time_history",
    "time_history_panels",
]
