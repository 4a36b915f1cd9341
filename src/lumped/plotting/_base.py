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
from matplotlib.axes import Axes
from matplotlib.figure import Figure

__all__ = ["STYLE", "style", "styled", "new_axes", "save_figure"]

_P = ParamSpec("_P")
_R = TypeVar("_R")

#: The project's matplotlib style file.
STYLE = Path(__file__).with_name("lumped.mplstyle")

#: Metadata that would change from build to build, blanked for reproducible files.
_PDF_METADATA = {"Creator": None, "Producer": None, "CreationDate": None, "ModDate": None}
_PNG_METADATA = {"Software": None}


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
def save_figure(fig: Figure, stem: str, folder: str | os.PathLike[str] | None = None) -> list[Path]:
    """Write ``stem.pdf`` and ``stem.png`` byte-reproducibly; return the paths.

    ``folder`` defaults to ``$LUMPED_FIGURES_DIR``; when neither is given the
    figure is not written (so running a notebook interactively, or under
    nbval, leaves the working tree alone) and an empty list is returned.
    """
    folder = folder or os.environ.get("LUMPED_FIGURES_DIR")
    if not folder:
        return []
    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / f"{stem}.pdf", out / f"{stem}.png"]
    fig.savefig(paths[0], metadata=_PDF_METADATA)
    fig.savefig(paths[1], metadata=_PNG_METADATA, dpi=200)
    return paths
