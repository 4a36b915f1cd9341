"""A sine history beyond the sine's range (``MAX_ARGUMENT = 2e8`` rad) is refused before any step, wherever it
is: a load (``[[force]]``) or a driven point's velocity (``[[driver]]``), by every method that runs a network.

Before, a driver's sine was never checked (its integral, the point's position, went NaN mid-run: ``force must
return finite values; got nan``), and the network solvers of ``exact``, ``event-driven`` and ``event-locating``
did not check their loads (a 1e8 rad/s sine ran for ever).  :func:`lumped.model.forcing.check_spans` is the one
check; the bound is ``|omega| t_last + |phase| <= 2e8`` (``t_last`` the grid's last time), tested at its edge.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from cli_run import run_lumped
from conftest import ROOT

import lumped
from lumped import Bingham, Driver, Friction, Load, Mass, Network, Spring, SwitchedSine, simulate_network
from lumped.numerics.sine import MAX_ARGUMENT

SPAN = r"\|omega\| \* min\(t_end, until\) \+ \|phase\| = 2\.02e\+08 rad exceeds 2e\+08 rad"


def belt(velocity: object) -> Network:
    """One block on a spring to the wall, on a belt of ``velocity`` (a friction contact)."""
    return Network(
        [Mass("m", 1.0)],
        [Spring("k", ("ground", "m"), 1.0), Friction("f", ("belt", "m"), static=1.0, kinetic=0.5)],
        (),
        [Driver("belt", velocity)],
    )


def test_a_drivers_sine_at_the_edge_runs_and_beyond_it_is_refused_before_the_run() -> None:
    """``omega = 1e8`` rad/s to the grid's last time 2 s is exactly the range: it runs, finite; 2.02 s is refused
    in one line naming the driver (the run would turn NaN at t = 2.01 s)."""
    net = belt(SwitchedSine(0.2, MAX_ARGUMENT / 2.0))
    run = simulate_network(net, 2.0, 0.01)
    assert np.all(np.isfinite(run.positions)) and np.all(np.isfinite(run.driver_motion()[0]))
    with pytest.raises(ValueError, match=rf"^driver 'belt' velocity: {SPAN}, the range of the forcing's sine"):
        simulate_network(net, 2.02, 0.01)


def _loaded(method: str, force: SwitchedSine) -> Network:
    """Two masses, springs and a Bingham dashpot (piecewise linear), a load on ``a``; for ``event-driven``,
    whose network solver runs one mass, the block on a belt with the load."""
    if method == "event-driven":
        net = belt(0.2)
        return Network(net.masses, net.elements, [Load("m", force)], net.drivers)
    elements = [Spring("k", ("ground", "a"), 1.0), Spring("k2", ("a", "b"), 1.0), Bingham("d", ("ground", "b"), 0.1)]
    return Network([Mass("a", 1.0), Mass("b", 1.0)], elements, [Load("a", force)])


@pytest.mark.parametrize("method", ["backward-euler", "exact", "event-driven", "event-locating"])
def test_every_network_method_refuses_a_load_beyond_the_range_before_any_phase(method: str) -> None:
    """A phase that puts the argument 2 rad past the range by the end (omega 1 rad/s: quick to run either way):
    each method's one line, before any step."""
    force = SwitchedSine(1.0, 1.0, MAX_ARGUMENT - 1.0)
    with pytest.raises(ValueError, match=r"^force_omega: .* = 2e\+08 rad exceeds 2e\+08 rad, the range"):
        lumped.solve(lumped.Problem(_loaded(method, force), 3.0), 0.01, method=method)
    lumped.solve(lumped.Problem(_loaded(method, force), 1.0), 0.01, method=method)  # within: runs


def test_the_command_line_refuses_a_drivers_sine_in_one_line(tmp_path: Path) -> None:
    """Exit status 2, one line naming the driver, no output written."""
    text = (ROOT / "examples" / "belt.toml").read_text(encoding="utf-8")
    sine = 'velocity = { kind = "sine", amplitude = 0.2, omega = 1e8 }'
    (tmp_path / "s.toml").write_text(text.replace("velocity = 0.2", sine, 1), encoding="utf-8")
    result = run_lumped(
        "simulate", "--system", "s.toml", "--t-end", "2.02", "--dt", "0.01", "--output", "o.csv", cwd=tmp_path
    )
    assert result.returncode == 2 and result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "driver 'belt' velocity: |omega| * min(t_end, until) + |phase| = 2.02e+08" in lines[0]
    assert not list(tmp_path.glob("o.*"))
