"""``import lumped`` and the command line's modules stay light: no SciPy solver at import time.

SciPy's ``integrate`` and ``optimize`` cost about half a second to import,
more than a whole event-driven run; the package imports them (and
``scipy.linalg``) inside the functions that need them.  A fresh interpreter
per check, since this test session has SciPy loaded already.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

HEAVY = ("scipy.integrate", "scipy.optimize", "scipy.linalg")


@pytest.mark.parametrize(
    "modules",
    [
        "lumped",
        "lumped.cli, lumped.drivers.simulation, lumped.model.files, lumped.drivers.network, lumped.solvers.event_driven",
    ],
)
def test_importing_loads_no_scipy_solver(modules):
    code = f"import sys, {modules}; print(' '.join(m for m in {HEAVY!r} if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)
    assert out.stdout.strip() == ""


def test_an_event_driven_run_loads_no_scipy_solver():
    """The event-driven method's whole run (integrator and stop search) is SciPy-free."""
    code = (
        "import sys, lumped as L\n"
        "osc = L.Oscillator(1.0, L.LinearSpring(100.0), L.HerschelBulkleyDashpot(1.0, 1.0, 0.5))\n"
        "L.simulate(osc, 1.0, 1e-3, x0=0.5, method='event-driven', rtol=1e-8)\n"
        f"print(' '.join(m for m in {HEAVY!r} if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)
    assert out.stdout.strip() == ""
