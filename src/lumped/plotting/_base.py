"""Shared plotting machinery: one style file, deterministic saving.

Plot helpers in this package take ``ax=`` (an existing Axes, or ``None`` to make
a new figure), return the :class:`~matplotlib.figure.Figure`, and never change
global matplotlib state.  The style is applied one way only: every public
helper is decorated with :func:`styled`, so it both creates *and draws* inside
:func:`style` (legends, lines and text take their defaults from the style
file whether or not the Axes were made by the package).
"""

from __future__ import annotations

import functools
import os
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import ParamSpec, TypeVar

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.legend import Legend

__all__ = ["STYLE", "style", "styled", "new_axes", "save_figure", "sci_tex", "legend_above"]

_P = ParamSpec("_P")
_R = TypeVar("_R")

#: The project's matplotlib style file.
STYLE = Path(__file__).with_name("lumped.mplstyle")

#: Metadata that would change from build to build, blanked for reproducible files.
_METADATA: dict[str, dict[str, None]] = {
    "pdf": {"Creator": None, "Producer": None, "CreationDate": None, "ModDate": None},
    "png": {"Software": None},
}


@contextmanager
def style() -> Iterator[None]:
    """Apply the project style inside a ``with`` block only.

    The one setting kept on leaving is matplotlib's interactive flag: Jupyter
    switches it on when the first figure is made, and restoring it would hide
    every later inline figure.
    """
    with plt.style.context(STYLE):
        yield
        interactive = matplotlib.is_interactive()
    matplotlib.interactive(interactive)


def styled(helper: Callable[_P, _R]) -> Callable[_P, _R]:
    """Decorator: run a plot helper inside :func:`style` (creation and drawing)."""

    @functools.wraps(helper)
    def wrapper(*args: _P.args, **kwargs: _P.kwargs) -> _R:
        with style():
            return helper(*args, **kwargs)

    return wrapper


@styled
def new_axes(ax: Axes | None = None, **subplot_kw: object) -> tuple[Figure, Axes]:
    """Return ``(figure, ax)``: the given Axes and its figure, or a new styled pair."""
    if ax is not None:
        return ax.figure, ax  # type: ignore[return-value]
    return plt.subplots(**subplot_kw)  # type: ignore[arg-type,return-value]


@styled
def save_figure(
    fig: Figure, stem: str, folder: str | os.PathLike[str] | None = None, formats: tuple[str, ...] = ("pdf", "png")
) -> list[Path]:
    """Write ``stem.pdf`` and ``stem.png`` byte-reproducibly; return the paths.

    ``folder`` defaults to ``$LUMPED_FIGURES_DIR``; when neither is given the
    figure is not written (so running a notebook interactively, or under
    nbval, leaves the working tree alone) and an empty list is returned.
    ``formats`` selects the files (a subset of ``("pdf", "png")``); the PDF is
    drawn at the figure's size in inches, which is the size the article prints
    it at (``fig()`` in ``paper/paper.typ``), so a 10 pt label stays 10 pt.
    """
    folder = folder or os.environ.get("LUMPED_FIGURES_DIR")
    if not folder:
        return []
    unknown = set(formats) - set(_METADATA)
    if unknown:
        raise ValueError(f"formats: {sorted(unknown)} not among {sorted(_METADATA)}")
    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / f"{stem}.{ext}" for ext in formats]
    for path, ext in zip(paths, formats):
        fig.savefig(path, metadata=_METADATA[ext], dpi=200 if ext == "png" else "figure")
    return paths


def sci_tex(value: float, digits: int = 3, show_one: bool = True) -> str:
    """``value`` as mathtext: ``1\\times10^{-4}``, ``2.5\\times10^{-4}``, or ``0.5``.

    Plain decimals for ``0.1 <= |value| < 1000``, scientific notation with at
    most ``digits`` significant digits (trailing zeros dropped) otherwise;
    ``show_one=False`` writes a mantissa of 1 as the bare power, ``10^{-2}``.
    """
    if value == 0 or not np.isfinite(value):
        return f"{value:g}"
    if 0.1 <= abs(value) < 1000:
        return f"{value:.{digits}g}"
    mantissa, exponent = f"{value:.{digits - 1}e}".split("e")
    mantissa = mantissa.rstrip("0").rstrip(".")
    power = rf"10^{{{int(exponent)}}}"
    return power if mantissa == "1" and not show_one else rf"{mantissa}\times{power}"


def legend_above(ax: Axes, ncol: int = 4, **kw: object) -> Legend:
    """A legend outside the axes, above them, so that it hides no data.

    Under constrained layout (the style's) the axes shrink to make room.
    """
    return ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.02), ncol=ncol, borderaxespad=0.0, fontsize=8, **kw)  # type: ignore[arg-type]
