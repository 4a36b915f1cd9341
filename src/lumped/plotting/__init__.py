"""Plot helpers (matplotlib).  Each takes ``ax=``, returns the Figure and leaves
global matplotlib state alone; :func:`save_figure` writes reproducible files."""

from lumped.plotting._base import STYLE, new_axes, save_figure, style

__all__ = ["STYLE", "new_axes", "save_figure", "style"]
