"""Shared plotting machinery: one style file, deterministic saving.

Plot helpers in this package take ``ax=`` (an existing Axes, or ``None`` to make
a new figure), return the :class:`~matplotlib.figure.Figure`, and never change
global matplotlib state: the style is applied with a context manager.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import matplotlib
import matplotlib.pyplot as plt
from matplotlib.axes import Axes
from matplotlib.figure import Figure

__all__ = ["STYLE", "style", "new_axes", "save_figure"]

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


def new_axes(ax: Axes | None = None, **subplot_kw: object) -> tuple[Figure, Axes]:
    """Return ``(figure, ax)``: the given Axes and its figure, or a new styled pair."""
    if ax is not None:
        return ax.figure, ax  # type: ignore[return-value]
    with style():
        fig, ax = plt.subplots(**subplot_kw)  # type: ignore[arg-type]
    return fig, ax


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
    with style():
        fig.savefig(paths[0], metadata=_PDF_METADATA)
        fig.savefig(paths[1], metadata=_PNG_METADATA, dpi=200)
    return paths
