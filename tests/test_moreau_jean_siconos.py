"""The ``moreau-jean`` method against Siconos itself, on Siconos' FrictionOscillator example (issue 25).

Siconos (INRIA's reference code of nonsmooth mechanics; Debian's
``python3-siconos``) integrates the example with ``EulerMoreauOSI(theta)``:
the smooth part by the θ-rule and the relay's force at the new level, which is
the Moreau-Jean scheme of :mod:`lumped.solvers.moreau_jean`.  Two comparisons:

* with the example's regression reference, ``FrictionOscillator.ref``, kept
  in ``tests/data/siconos`` with its provenance (no Siconos needed);
* with Siconos run here, by ``scripts/siconos_friction_oscillator.py``: in
  this process if Siconos imports, else with the system Python
  (``/usr/bin/python3``, where Debian installs it); skipped, in one line,
  when neither has it.  The test installs nothing (``.ci/run`` does, as root).

Tolerance: both sides solve the same linear equations each step, in a
different order of operations, and the midpoint rule neither damps nor
amplifies round-off, so the states drift apart by at most a few ulps of
``|x| <= 14`` per step: ``4000 * 14 * 2.2e-16 = 1.2e-11`` on [0, 40] s.
Siconos' relay force is a Lemke pivoting solution, one more rounding of the
same size divided by ``h``.  Measured: ``3.5e-13`` in ``x`` and ``v``,
``1.6e-11`` in ``lambda`` (at the stop at ``t = 19.29`` s).  ``1e-10`` is
the bound asserted.
"""

from __future__ import annotations

import gzip
import hashlib
import importlib.util
import math
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from conftest import ROOT

import lumped as L

SCRIPT = ROOT / "scripts" / "siconos_friction_oscillator.py"
REF = ROOT / "tests" / "data" / "siconos" / "FrictionOscillator.ref.gz"
REF_SHA256 = "b7fdbc032f3e160dbb5e61b5a6cf6034ecd1d431c6eebac6c5c202b7b17622d5"
#: The example: m = k = 1, Coulomb bound 1, x0 = 12, v0 = 6, h = 0.01, theta = 1/2.
OSCILLATOR = L.Oscillator.bingham(mass=1.0, stiffness=1.0, threshold=1.0, gamma=math.inf)
H, X0, V0, T_END = 0.01, 12.0, 6.0, 40.0
#: See the module's docstring.
TOLERANCE = 1e-10
SYSTEM_PYTHON = "/usr/bin/python3"


def ours(t_end: float) -> L.Trajectory:
    return L.simulate(OSCILLATOR, t_end, H, x0=X0, v0=V0, method="moreau-jean", theta=0.5)


def differences(rows: np.ndarray, tr: L.Trajectory) -> dict[str, float]:
    """Largest differences, column by column, of Siconos' rows ``(t, x, v, lambda, y, ...)`` from ``tr``."""
    assert rows.shape[0] == tr.t.size
    return {
        "t": float(np.abs(rows[:, 0] - tr.t).max()),
        "x": float(np.abs(rows[:, 1] - tr.x).max()),
        "v": float(np.abs(rows[:, 2] - tr.v).max()),
        # Row 0 holds lambda = y = 0: Siconos computes them in the first step.
        "lambda": float(np.abs(rows[1:, 3] + tr.F_d[1:]).max()),
        "y": float(np.abs(rows[1:, 4] - tr.v[1:]).max()),
    }


def _siconos_rows(tmp_path: Path) -> np.ndarray:
    """The script's rows, by Siconos in this process or in the system Python; skip when neither has it."""
    if importlib.util.find_spec("siconos") is not None:
        spec = importlib.util.spec_from_file_location("siconos_friction_oscillator", SCRIPT)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module.run(T_END)
    python = shutil.which(SYSTEM_PYTHON)
    probe = [python, "-c", "import siconos.kernel"] if python else None
    if probe is None or subprocess.run(probe, check=False, capture_output=True).returncode != 0:
        pytest.skip("Siconos is not installed (Debian: apt-get install python3-siconos); not compared")
    out = tmp_path / "siconos.csv"
    args = [python, str(SCRIPT), "--t-end", str(T_END), "--output", str(out)]
    subprocess.run(args, check=True, capture_output=True, timeout=120)
    return np.loadtxt(out, delimiter=",", skiprows=1)


def test_moreau_jean_runs_as_siconos_row_by_row(tmp_path):
    rows = _siconos_rows(tmp_path)
    diff = differences(rows, ours(T_END))
    print(f"largest difference from Siconos on [0, {T_END:g}] s:", {k: f"{v:.1e}" for k, v in diff.items()})
    assert max(diff.values()) <= TOLERANCE, diff
    assert rows[-1, 2] == pytest.approx(0.0, abs=TOLERANCE)  # at rest, as ours


def test_moreau_jean_runs_as_siconos_regression_reference():
    data = gzip.decompress(REF.read_bytes())
    assert hashlib.sha256(data).hexdigest() == REF_SHA256  # Siconos' file, unchanged
    lines = data.decode().splitlines()
    assert lines[0].split() == ["10000", "10"]
    rows = np.array([[float(v) for v in line.split()] for line in lines[1:]])
    tr = ours(float(rows[-1, 0]))
    diff = differences(rows, tr)
    # Its vector field after the step, (v, -k x + lambda), from our state.
    diff["vdot"] = float(np.abs(rows[1:, 8] - (-tr.x[1:] - tr.F_d[1:])).max())
    diff["xdot"] = float(np.abs(rows[1:, 7] - tr.v[1:]).max())
    print("largest difference from FrictionOscillator.ref on [0, 99.99] s:", {k: f"{v:.1e}" for k, v in diff.items()})
    assert max(diff.values()) <= TOLERANCE, diff
