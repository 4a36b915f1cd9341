"""The public API at its edges (issue 31): a wrong argument is one ``ValueError`` naming it, at the boundary.

Before: ``response_curve(None, ...)`` raised ``AttributeError``; ``find_orbit``,
``continue_orbits``, ``sensitivities``, ``system_sensitivities``,
``read_table`` and ``read_record`` raised ``AttributeError`` or ``TypeError``
on ``None``, a number or a string where a system, a name list or a path
goes; ``sweep(..., chunk=(0, 10**9))`` on 3 rows allocated the bounds of
all 10**9 chunks (7.45 GiB); derivatives that overflow were written as
``nan`` with status 0.
"""

from __future__ import annotations

import math
import tracemalloc
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_lumped

import lumped as L
from lumped.drivers.sweep import chunk_slice, sweep

OSC = L.Oscillator.bingham()
EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
TWO = L.load_system(EXAMPLES / "two_mass_response.toml")
FIGURE3 = L.load_system(EXAMPLES / "figure3.toml")

#: (call, the message's start); each is refused before any work.
BAD_CALLS = {
    "response_curve network None": (lambda: L.response_curve(None, "m2", 1.0, 5.0, 6.0), "network must be a Network"),
    "response_curve network str": (lambda: L.response_curve("s.toml", "m2", 1.0, 5.0, 6.0), "network must be"),
    "response_curve mass": (lambda: L.response_curve(TWO, 2, 1.0, 5.0, 6.0), "mass must be the name of a mass"),
    "find_orbit system": (lambda: L.find_orbit(None, 10.0, 5.0), "system must be an Oscillator or a LoadedNetwork"),
    "find_orbit amplitude": (lambda: L.find_orbit(OSC, "10", 5.0), "force_amplitude must be"),
    "find_orbit omega": (lambda: L.find_orbit(OSC, 10.0, None), "force_omega must be"),
    "continue_orbits points None": (lambda: L.continue_orbits(OSC, 10.0, 5.0, 5.5, None), "points must be"),
    "continue_orbits points bool": (lambda: L.continue_orbits(OSC, 10.0, 5.0, 5.5, True), "points must be"),
    "continue_orbits points 1": (lambda: L.continue_orbits(OSC, 10.0, 5.0, 5.5, 1), "points must be at least 2"),
    "continue_orbits stop nan": (lambda: L.continue_orbits(OSC, 10.0, 5.0, math.nan), "stop must be"),
    "sensitivities parameters": (
        lambda: L.sensitivities(L.solve_exact(OSC, 1.0, x0=0.5), [0.5], 5),
        "parameters must be a sequence of names",
    ),
    "system_sensitivities network": (lambda: L.system_sensitivities(None, [0, 1.0], "m.x0"), "network must be"),
    "system_sensitivities names": (lambda: L.system_sensitivities(FIGURE3, [0, 1.0], 5), "parameters: expected names"),
    "one_sided_sensitivities network": (
        lambda: L.one_sided_sensitivities((1, 2), [0, 1.0], "m.x0"),
        "network must be a Network, got tuple",
    ),
    "read_table path": (lambda: L.read_table(None, "F"), "path must be a str or a path of a file, got NoneType"),
    "read_record path": (lambda: L.read_record(5, ["m"]), "path must be a str or a path of a file, got int"),
    "read_record masses": (lambda: L.read_record("r.csv", None), "masses must be a sequence of the system's mass"),
    "read_record masses str": (lambda: L.read_record("r.csv", "m"), "masses must be a sequence"),
}


@pytest.mark.parametrize("call,message", BAD_CALLS.values(), ids=list(BAD_CALLS))
def test_a_wrong_argument_is_one_value_error_naming_it(call, message):
    with pytest.raises(ValueError, match="^" + message) as err:
        call()
    assert "\n" not in str(err.value)


def test_a_chunk_of_a_billion_computes_its_own_two_bounds_only():
    # The bounds are linspace(0, rows, count + 1).round() (the chunks' definition): computed for the two
    # ends of the chunk asked for, not for all count + 1.  10**7 chunks held 80 MB before; now a few bytes.
    tracemalloc.start()
    try:
        assert chunk_slice(3, 0, 10**7) == slice(0, 0)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 100_000
    out = sweep({"x0": [0.1, 0.2, 0.3]}, t_end=0.01, dt=1e-3, chunk=(0, 10**9))
    assert all(column.size == 0 for column in out.values())


@pytest.mark.parametrize("rows", [0, 1, 3, 7, 100, 1001])
@pytest.mark.parametrize("count", [1, 2, 3, 7, 64, 1000])
def test_chunk_bounds_are_the_rounded_linspace(rows, count):
    bounds = np.linspace(0, rows, count + 1).round().astype(int)
    for i in range(count):
        assert chunk_slice(rows, i, count) == slice(int(bounds[i]), int(bounds[i + 1]))


OVERFLOW = {
    # c = 1/gamma = 1e300: dx/dgamma = -c^2 dx/dc is inf * 0 at t = 0
    "gamma 1e-300": (
        ["--gamma", "1e-300", "--x0", "0.5"],
        "dashpot.gamma,m.x0",
        "'dashpot.gamma' is not finite at t = 0",
    ),
    # a forcing of 1e150 N at 10 rad/s: x is finite (3e148 m), the exponential of the mass's derivative overflows
    "amplitude 1e150": (["--force-amplitude", "1e150", "--force-omega", "10"], "m.mass", "'m.mass' is not finite"),
}


@pytest.mark.parametrize(("args", "names", "message"), OVERFLOW.values(), ids=list(OVERFLOW))
def test_sensitivities_that_overflow_are_refused_not_written_as_nan(tmp_path, args, names, message):
    common = ["--method", "exact", "--t-end", "1", "--dt", "0.1", "--sensitivities", names]
    run = run_lumped("simulate", *args, *common, "--output", "s.csv", cwd=tmp_path)
    assert run.returncode == 2 and run.stderr.count("\n") == 1, run.stderr
    assert run.stderr.startswith(f"lumped simulate: error: --sensitivities: the derivative by {message}"), run.stderr
    assert not list(tmp_path.iterdir())
