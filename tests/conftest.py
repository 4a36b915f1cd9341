"""Shared fixtures: the paper's parameters (section 3) and its time step; a repository copy."""

from __future__ import annotations

import os

# pyproject.toml runs one pytest-xdist worker per core (-n auto): OpenBLAS's own threads would only
# spin against the other workers (the fit coverage test took 27.8 s of CPU for 16.7 s, 15.5 s with one
# thread).  Set before NumPy loads OpenBLAS, and inherited by the workers, the notebooks' kernels and
# the pipelines the tests run; a value the caller gives is kept.
for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

import dataclasses
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from hypothesis import settings

import lumped as L
from lumped.solvers import backward_euler
from lumped.studies import examples

# In CI the property tests draw the same examples on every run (a red CI then
# means a change broke something, never that a new random draw was unlucky);
# locally they explore new examples each time.
settings.register_profile("ci", derandomize=True)
if os.environ.get("CI"):
    settings.load_profile("ci")

#: Machine epsilon of float64; tolerances below are written in units of it.
EPS = float(np.finfo(float).eps)
#: The paper's time step (section 3).
PAPER_DT = examples.ORIGINAL_DT
#: The forcings of eqs. (17a) and (17b), as lumped.studies.examples defines them.
F17A = examples.paper()["forced_small"].force
F17B = examples.paper()["forced_large"].force
#: The kernels of Algorithm 1 to test: the Python loop always, the C kernel too when built.
KERNELS = ["python"] + (["compiled"] if backward_euler.KERNEL == "compiled" else [])


def assert_same_trajectory(a: L.Trajectory, b: L.Trajectory) -> None:
    """``a`` and ``b`` are the same run bit for bit: every field of the trajectory (the saved arrays, the
    final rest found at full resolution, the events, the system, the method, the path), and what is derived
    from them (rest time and position, stick intervals).  ``as_array()`` alone would miss a rest step off
    by one, which lives in ``final_rest``, not in the saved rows."""
    for f in dataclasses.fields(a):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if f.name == "final_rest" and x is not None and y is not None:
            x, y = np.concatenate(x), np.concatenate(y)
        if isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
            assert isinstance(x, np.ndarray) and isinstance(y, np.ndarray) and x.dtype == y.dtype, f.name
            assert np.array_equal(x, y, equal_nan=True), f.name
        else:
            assert x == y, f.name
    assert np.array_equal(a.rest_times, b.rest_times, equal_nan=True), "rest_times"
    assert np.array_equal(a.rest_positions, b.rest_positions, equal_nan=True), "rest_positions"
    assert a.stick_intervals() == b.stick_intervals(), "stick_intervals"


#: The test files (or classes) that take longest, longest first (seconds of one run under pytest-xdist on
#: 2 cores, 2026-11-27): the network fit's 100 trials 96 to 158, the website 51, the articles of other
#: configurations 40 each, the folds 75 in all; the notebooks 16 (22) and 13 (14).  They are handed out first
#: (``--no-loadscope-reorder`` keeps this order), so that none starts last and runs alone.
LONGEST_FIRST = (
    "tests/test_network_fit.py",
    "tests/test_site.py",
    "tests/test_paper_variants.py",
    "tests/test_cycles_continuation.py",
    "notebooks/16_self_excited_cycles.ipynb",
    "notebooks/13_response_curves.ipynb",
)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """LONGEST_FIRST's files first, in its order; every other test as collected."""

    def rank(item: pytest.Item) -> int:
        return next((i for i, p in enumerate(LONGEST_FIRST) if item.nodeid.startswith(p + "::")), len(LONGEST_FIRST))

    items.sort(key=rank)


def energy_scale(eb: L.EnergyBalance) -> float:
    """The energy scale of a run: stored + dissipated + numerical + |external work|.

    Each step's residual of the discrete energy balance is a few roundings of
    ``eps`` times this.
    """
    return float(
        np.max(eb.kinetic + eb.potential) + eb.dissipated[-1] + eb.numerical[-1] + np.abs(eb.external_work).max()
    )


@pytest.fixture
def paper_oscillator() -> L.Oscillator:
    """gamma = 1, mu_s N_f = 1, m = 1, k = 100 (section 3)."""
    return L.Oscillator.bingham(mass=1.0, stiffness=100.0, threshold=1.0, gamma=1.0)


#: The repository's root folder.
ROOT = Path(__file__).resolve().parent.parent


def copy_tracked_files(target: Path) -> Path:
    """Copy the repository's tracked files (as in the work tree) to ``target``.

    Pipeline tests run Snakemake there, so that they neither read nor write
    this checkout's ``results/`` and ``figures/``.
    """
    listed = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout.decode()
    for name in filter(None, listed.split("\0")):
        if (ROOT / name).is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, target / name)
    return target


def case_kwargs(case) -> dict:
    """Keyword arguments of the solvers for a :class:`references.Case` (x0, v0, force)."""
    force = None if case.force is None else L.SwitchedSine(*case.force)
    return dict(x0=case.x0, v0=case.v0, force=force)


def case_table(*names: str) -> dict[str, tuple[float, dict]]:
    """``name -> (gamma, solver keyword arguments)`` for cases of ``references.CASES``."""
    from references import CASES

    return {name: (CASES[name].gamma, case_kwargs(CASES[name])) for name in names}
