"""The forcing's argument ``omega t + phase`` must stay inside the sine's range (issue 19).

One bound, :data:`lumped.numerics.sine.MAX_ARGUMENT` (2e8 rad), checked once by
:func:`lumped.numerics.validate.sine_argument` for every method, the network, the
sweep and the command line: before it, ``--force-phase 1e300`` turned the
forcing into a constant for every method but the exact one, which refused
``omega t`` above 1e15 rad and not the phase.
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import lumped as L
import lumped.solvers.exact
from lumped import Bingham, Load, Mass, Network, Spring, simulate_network
from lumped.drivers import sweep
from lumped.drivers.simulation import METHODS
from lumped.numerics import sine as _sine

BOUND = _sine.MAX_ARGUMENT


def test_a_phase_outside_the_range_is_refused_by_the_switched_sine():
    with pytest.raises(ValueError, match=r"^force_phase must be within \+-2e\+08 rad"):
        L.SwitchedSine(1.0, 1.0, 1e300)
    assert L.SwitchedSine(1.0, 1.0, -BOUND).phase == -BOUND  # the edge is inside


@pytest.mark.parametrize("method", list(METHODS))
def test_every_method_refuses_an_argument_beyond_the_bound(method):
    """omega = 3e8 rad/s for 1 s: omega t_N = 3e8 > 2e8, refused before any step, naming force_omega."""
    force = L.SwitchedSine(1.0, 3e8, 0.0)
    with pytest.raises(ValueError, match=r"^force_omega: .* exceeds 2e\+08 rad"):
        L.simulate(L.Oscillator.bingham(), 1.0, 0.5, force=force, method=method)


def test_the_bound_counts_phase_and_the_grid_end():
    """omega t_N + |phase| at the edge passes; one more radian of phase is refused.

    dt = 0.5 on t_end = 2: t_N = 2 exactly, omega = 1e8 gives omega t_N = 2e8 = BOUND
    (exact in binary arithmetic: 1e8 * 2 is a product by a power of 2).
    """
    osc = L.Oscillator.bingham()
    ok = L.backward_euler(osc, 2.0, 0.5, force=L.SwitchedSine(1.0, 1e8, 0.0))
    assert np.all(np.isfinite(ok.F)) and ok.F[-1] == _sine.sin(2e8)
    with pytest.raises(ValueError, match="^force_omega"):
        L.backward_euler(osc, 2.0, 0.5, force=L.SwitchedSine(1.0, 1e8, 1.0))
    # the grid overshoots t_end = 1.9 to t_N = 2.0: the overshoot counts
    with pytest.raises(ValueError, match="^force_omega"):
        L.backward_euler(osc, 1.9, 0.5, force=L.SwitchedSine(1.0, 1.00000001e8, 0.0))
    # switched off at force_until = 1: only omega * 1 counts
    L.backward_euler(osc, 2.0, 0.5, force=L.SwitchedSine(1.0, 1.5e8, 0.0, 1.0))


def test_the_exact_method_shares_the_bound():
    """The exact method used to accept omega t up to 1e15 rad; now the sine's bound, the same for all."""
    assert lumped.solvers.exact.MAX_PHASE == BOUND
    with pytest.raises(ValueError, match="^force_omega"):
        L.solve_exact(L.Oscillator.bingham(), 1.0, force=L.SwitchedSine(1.0, 1e9, 0.0))


def test_a_network_load_is_checked():
    """Two masses (not the paper's form, so the network step runs, not Algorithm 1)."""
    net = Network(
        [Mass("a", 1.0), Mass("b", 1.0)],
        [Spring("s", ("ground", "a"), 100.0), Spring("t", ("a", "b"), 100.0), Bingham("d", ("ground", "b"), 1.0)],
        [Load("b", L.SwitchedSine(1.0, 3e8, 0.0))],
    )
    with pytest.raises(ValueError, match="^force_omega"):
        simulate_network(net, 1.0, 0.5)


def test_the_sweep_refuses_before_any_work(monkeypatch):
    def no_work(*args, **kwargs):
        raise AssertionError("the kernel ran")

    monkeypatch.setattr("lumped.drivers.sweep.run.batch_backward_euler", no_work)
    with pytest.raises(ValueError, match="^force_omega"):
        sweep.sweep({"force_omega": [1.0, 3e8]}, t_end=1.0, dt=0.5, force_amplitude=1.0, periods=1)
    with pytest.raises(ValueError, match="^force_phase must be within"):
        sweep.sweep({"x0": [0.0, 0.1]}, t_end=1.0, dt=0.5, force_phase=1e300)


def _cli(tmp_path, *args):
    proc = subprocess.run(
        [sys.executable, "-m", "lumped", *args, "--output", str(tmp_path / "o.csv")],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=tmp_path,
    )
    return proc.returncode, proc.stderr.strip().splitlines(), sorted(p.name for p in tmp_path.iterdir())


@pytest.mark.parametrize(
    ("args", "option"),
    [
        (["simulate", "--force-amplitude", "1", "--force-phase", "1e300"], "--force-phase"),
        (["simulate", "--force-amplitude", "1", "--force-omega", "3e8", "--t-end", "1"], "--force-omega"),
        (["simulate", "--method", "exact", "--force-amplitude", "1", "--force-phase", "1e300"], "--force-phase"),
        (["sweep", "--force-amplitude", "1", "--force-phase", "1e300", "--vary", "x0=0:1:2"], "--force-phase"),
        (["sweep", "--vary", "force-phase=0:1e300:2", "--force-amplitude", "1"], "--vary: force_phase"),
        (["sweep", "--vary", "force-omega=1:3e8:2", "--force-amplitude", "1", "--t-end", "1"], "--force-omega"),
    ],
)
def test_the_command_line_refuses_with_one_line_and_status_2(tmp_path, args, option):
    status, lines, files = _cli(tmp_path, *args)
    assert status == 2 and len(lines) == 1 and lines[0].startswith("lumped")
    assert option in lines[0] and "Traceback" not in lines[0]
    assert files == []  # no output, no temporary file left
