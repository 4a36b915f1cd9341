"""Plot helpers (matplotlib).  Each takes ``ax=``, returns the Figure and leaves
global matplotlib state alone; :func:`save_figure` writes reproducible files."""

from lumped.plotting._base import STYLE, new_axes, save_figure, style, styled
from lumped.plotting.figures import (
    bingham_pair,
    bingham_pictorial,
    exact_fine,
    oscillator_schematic,
    string_spring_triptych,
    time_history,
    time_history_panels,
)

__all__ = [
    "STYLE",
    "bingham_pair",
    "bingham_pictorial",
    "exact_fine",
    "new_axes",
    "oscillator_schematic",
    "save_figure",
    "string_spring_triptych",
    "style",
    "styled",
    "time_history",
    "time_history_panels",
]
