"""Study "where the mass comes to rest" (notebook 10, ``results/studies/rest.csv``): free vibration (``v0 = 0``, no
force) from every ``x0`` of an even grid over [-1, 1] m, run twice, by
Algorithm 1 (``backward-euler``, at the configured ``dt``) and by the
``exact`` solver, summarised by :func:`lumped.drivers.sweep.sweep`.  The file's
columns (:data:`COLUMNS`): ``x0`` (m), then ``rest_time`` (s),
``rest_position`` (m) and ``stops`` of each method, prefixed ``alg1_`` and
``exact_`` (definitions in :mod:`lumped.drivers.sweep`).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from lumped.drivers.methods import METHODS, Method
from lumped.drivers.sweep import sweep

__all__ = ["GRID", "CHUNKS", "T_END", "COMPARED", "COLUMNS", "rows", "chunk_table"]

#: ``studies`` (the configuration key) -> (number of x0 values over [-1, 1] m, chunks).
#: default: about 1 s per chunk on one core; full: a 0.1 mm grid.  An even
#: count keeps x0 = 0 and the band edges x0 = +-tau/k (paper's values) off the
#: grid: there Algorithm 1 creeps at a velocity of order 1e-16 m/s that never
#: moves x and never reaches rest (notebook 10 shows it).
GRID = {"default": (400, 4), "full": (20000, 16)}
CHUNKS = {resolution: chunks for resolution, (_, chunks) in GRID.items()}
#: End of every run (s): our choice; from x0 = 1 m the exact solution rests at 4.40 s.
T_END = 6.0
#: The x0 interval (m), the issue's.
X0_RANGE = (-1.0, 1.0)
#: The two methods compared, from the registry (:data:`lumped.drivers.methods.METHODS`), by the
#: prefix of their columns: the paper's Algorithm 1 and the exact solution.  The choice is the
#: study's question, so it names them; a method the registry lost or renamed fails here, at import.
COMPARED: Mapping[str, Method] = {"alg1": METHODS["backward-euler"], "exact": METHODS["exact"]}
SUMMARIES = ("rest_time", "rest_position", "stops")
COLUMNS = ("x0",) + tuple(f"{p}_{s}" for p in COMPARED for s in SUMMARIES)


def rows(cfg: Mapping[str, float], points: int, chunk: tuple[int, int] | None = None) -> dict[str, np.ndarray]:
    """The rest study's columns (:data:`COLUMNS`) for the rows of ``chunk`` of the x0 grid (all without it).

    Parameters
    ----------
    cfg : mapping
        ``mass`` (kg), ``stiffness`` (N/m), ``threshold`` (N), ``gamma``
        (m/(N s)) and ``dt`` (s), as :func:`lumped.studies.config.load` gives them.
    points : int
        Number of x0 values, ``np.linspace(-1, 1, points)`` (m).
    chunk : (int, int), optional
        ``(index, count)``, :meth:`lumped.drivers.sweep.SweepSpec.chunk`.

    Raises
    ------
    ValueError
        If some run has not come to rest by :data:`T_END` (no NaN is written).
    """
    fixed = {k: cfg[k] for k in ("mass", "stiffness", "threshold", "gamma")}
    grid = np.linspace(*X0_RANGE, points)
    out: dict[str, np.ndarray] = {}
    for prefix, method in COMPARED.items():
        r = sweep({"x0": grid}, t_end=T_END, dt=cfg["dt"], method=method.name, chunk=chunk, **fixed)
        out["x0"] = r["x0"]
        if np.isnan(r["rest_time"]).any():
            x0 = r["x0"][np.isnan(r["rest_time"])][0]
            raise ValueError(f"study rest: {method.name} from x0 = {float(x0)!r} m is still moving at t = {T_END:g} s")
        out.update({f"{prefix}_{s}": r[s] for s in SUMMARIES})
    return out


def chunk_table(cfg: Mapping[str, float], resolution: str, chunk: tuple[int, int]) -> dict[str, np.ndarray]:
    """:func:`rows` of ``chunk`` on the grid of ``resolution`` (a key of :data:`GRID`)."""
    return rows(cfg, GRID[resolution][0], chunk)
