"""Every bad or extreme input of the robustness issue, with its clean outcome.

Three sections: the API (a ``ValueError`` with one line that begins with the
argument's name, within a bounded time, never a NaN or infinity it was not
given); the command line (exit status 2, or 130/143 for signals, one stderr
line naming the option or the problem, no traceback, no file left behind, a
bounded time); the pipeline's configuration (in ``test_config_pipeline.py``,
next to the pipeline's own checks).  The exact solver's extreme but valid
physics is in ``test_exact_robust.py``.
"""

from __future__ import annotations

import contextlib
import errno
import importlib
import math
import os
import shutil
import signal
import stat
import subprocess
import sys
import time

import numpy as np
import pytest
from conftest import F17B

import lumped as L
from lumped.cli import main, option_message
from lumped.cli import output as cli_output
from lumped.numerics.validate import MAX_STEPS
from lumped.solvers import backward_euler as timestepping
from lumped.solvers import network_compiled as network_kernel
from lumped.solvers.textbook import TextbookModel, integrate_adaptive, integrate_fixed

# ---------------------------------------------------------------------------
# The API
# ---------------------------------------------------------------------------
OSC = L.Oscillator.bingham()
#: A hang guard, not a speed test: the refused cases below would otherwise run for
#: hours (1e8 to 1e9 steps), and a refusal or the short runs take well under a
#: second, so a case still running after this long cannot have refused up front.
HANG_SECONDS = 120


@contextlib.contextmanager
def no_hang():
    """Fail the test (rather than let it run for hours) if the block outlasts HANG_SECONDS."""

    def stop(signum, frame):  # noqa: ARG001
        raise AssertionError(f"still running after {HANG_SECONDS} s: the input was not refused before the work")

    previous = signal.signal(signal.SIGALRM, stop)
    signal.alarm(HANG_SECONDS)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)


def _run(**kw):
    args = dict(t_end=1.0, dt=1e-3)
    args.update(kw)
    return L.backward_euler(args.pop("oscillator", OSC), args.pop("t_end"), args.pop("dt"), **args)


def _monotone(phi):
    return L.Oscillator(1.0, L.LinearSpring(100.0), L.MonotoneDashpot(phi))


API = {
    # name in the message: call
    "save_every=10**30": ("save_every", lambda: _run(save_every=10**30)),
    "save_every=1e30": ("save_every", lambda: _run(save_every=1e30)),
    "save_every=inf": ("save_every", lambda: _run(save_every=math.inf)),
    "save_every=2.0": ("save_every", lambda: _run(save_every=2.0)),
    "save_every='3'": ("save_every", lambda: _run(save_every="3")),
    "mass=10**400": ("mass", lambda: L.Oscillator.bingham(mass=10**400)),
    "mass=True": ("mass", lambda: L.Oscillator.bingham(mass=True)),
    "x0='0.5'": ("x0", lambda: _run(x0="0.5")),
    "oscillator=None": ("oscillator", lambda: L.backward_euler(None, 1.0, 1e-3)),
    "force=3": ("force", lambda: _run(force=3)),
    "force returns None": ("force", lambda: _run(force=lambda t: None)),
    "force returns a string": ("force", lambda: _run(force=lambda t: "abc")),
    "force of the wrong shape": ("force", lambda: _run(force=lambda t: np.zeros((np.size(t), 2)))),
    "force returns nan": ("force", lambda: _run(force=lambda t: np.full(np.shape(t), np.nan))),
    "force raises": ("force", lambda: _run(force=lambda t: 1 / 0)),
    "law not monotone": ("velocity_of_force", lambda: _run(oscillator=_monotone(lambda f: -f), x0=0.5)),
    "law returns nan": (
        "velocity_of_force",
        lambda: _run(oscillator=_monotone(lambda f: math.nan if f > 0.5 else f), x0=0.5),
    ),
    "law returns an array": ("velocity_of_force", lambda: _monotone(lambda f: np.array([f, f]))),
    "law returns a string": ("velocity_of_force", lambda: _monotone(lambda f: "fast")),
    "x0=1e307": ("x0", lambda: _run(x0=1e307)),
    "v0=1e307": ("v0", lambda: _run(v0=1e307)),
    "force amplitude 1e307": ("force_amplitude", lambda: _run(force=L.SwitchedSine(1e307, 1.0))),
    "stiffness 1e300, x0 1e10": ("x0", lambda: _run(oscillator=L.Oscillator.bingham(stiffness=1e300), x0=1e10)),
    "gamma 1e400 (an overflow, not Coulomb)": ("gamma", lambda: L.BinghamDashpot(1.0, 10**400)),
    "a monotone law for 1e3 s at 1e-5 s": (
        "t_end/dt",
        lambda: _run(oscillator=_monotone(lambda f: f), t_end=1e3, dt=1e-5, save_every=10**6),
    ),
    "rtol nan": ("rtol", lambda: integrate_adaptive(TextbookModel(OSC), 1.0, rtol=math.nan)),
    "rtol inf": ("rtol", lambda: integrate_adaptive(TextbookModel(OSC), 1.0, rtol=math.inf)),
    "rtol 0": ("rtol", lambda: integrate_adaptive(TextbookModel(OSC), 1.0, rtol=0.0)),
    "rtol '1e-6'": ("rtol", lambda: integrate_adaptive(TextbookModel(OSC), 1.0, rtol="1e-6")),
    "atol -1": ("atol", lambda: integrate_adaptive(TextbookModel(OSC), 1.0, atol=-1.0)),
    "atol nan": ("atol", lambda: integrate_adaptive(TextbookModel(OSC), 1.0, atol=math.nan)),
    "textbook Euler for 1.2e8 steps": ("t_end/dt", lambda: integrate_fixed(TextbookModel(OSC), 1.2e4, 1e-4)),
}
API = {key: value for key, value in API.items() if value is not None}


@pytest.mark.parametrize("case", list(API))
def test_api_refuses_with_one_line_naming_the_argument(case):
    name, call = API[case]
    with no_hang(), pytest.raises(ValueError) as err:
        call()
    message = str(err.value)
    assert "\n" not in message
    assert message.startswith(name), message


def test_forcing_that_overflows_stops_at_the_step_naming_the_quantity():
    # 1e308 N is finite; its first step gives v ~ 1e304 m/s, the second overflows.
    with pytest.raises(ValueError, match=r"^the run overflowed at t = 0\.002 s \(step 2\): the velocity v"):
        _run(force=lambda t: np.full(np.shape(t), 1e308))


def test_numpy_integers_and_the_largest_stride_are_valid():
    every = _run(x0=0.5, save_every=np.int64(7))
    assert np.array_equal(every.t, _run(x0=0.5, save_every=7).t)
    ends = _run(x0=0.5, save_every=MAX_STEPS)  # only t = 0 and the last point
    assert ends.t.tolist() == [0.0, 1.0]
    assert ends.x[-1] == _run(x0=0.5).x[-1]


def _network(solver: str):  # noqa: ANN202
    from lumped import Bingham, Mass, Network, Spring, simulate_network

    net = Network([Mass("m", 1.0, 0.5)], [Spring("k", ("ground", "m"), 100.0), Bingham("d", ("ground", "m"), 1.0, 1.0)])
    return lambda s: simulate_network(net, 1.0, 1e-3, save_every=s, solver=solver)


def _one_mass(s: int):  # noqa: ANN202
    from lumped import Bingham, Mass, Network, Problem, Spring, solve

    net = Network([Mass("m", 1.0, 0.5)], [Spring("k", ("ground", "m"), 100.0), Bingham("d", ("ground", "m"), 1.0, 1.0)])
    return solve(Problem(net, 1.0), 1e-3, method="event-driven", save_every=s)


#: Every driver that takes save_every: (what it is called with a stride).
STRIDED = {
    "backward_euler": lambda s: L.backward_euler(OSC, 1.0, 1e-3, x0=0.5, save_every=s),
    "theta_method": lambda s: L.theta_method(OSC, 1.0, 1e-3, x0=0.5, save_every=s),
    "event_capturing": lambda s: L.event_capturing(OSC, 1.0, 1e-3, x0=0.5, save_every=s).trajectory,
    "ExactSolution.sample": lambda s: L.solve_exact(OSC, 1.0, x0=0.5).sample(1e-3, s),
    **{
        f"simulate-{m}": (lambda m: lambda s: L.simulate(OSC, 1.0, 1e-3, x0=0.5, method=m, save_every=s))(m)
        for m in L.METHODS
    },
    **{f"simulate_network-{solver}": _network(solver) for solver in ("auto", "python", "compiled")},
    "solve-event-driven": _one_mass,
}
#: Drivers that need the compiled network kernel (absent with LUMPED_PURE_PYTHON=1).
NEEDS_NETWORK_KERNEL = {"simulate_network-compiled"}


@pytest.mark.parametrize("stride", [MAX_STEPS + 1, 10**23])
@pytest.mark.parametrize("driver", list(STRIDED))
def test_every_driver_bounds_save_every(driver, stride):
    """A stride beyond the most steps of any run is refused up front, naming save_every;
    the largest one keeps t = 0 and the last point."""
    with pytest.raises(ValueError, match=rf"^save_every must be an integer from 1 to {MAX_STEPS} "):
        STRIDED[driver](stride)  # 1000 steps at most: a refusal after the run would still be quick
    if driver in NEEDS_NETWORK_KERNEL and network_kernel.KERNEL != "compiled":
        pytest.skip("the compiled network kernel is not built (or LUMPED_PURE_PYTHON=1): the refusal above is checked")
    ends = STRIDED[driver](MAX_STEPS)
    assert ends.t.tolist() == [0.0, 1.0]


@pytest.mark.parametrize("method", ["exact", "event-driven"])
def test_simulate_refuses_the_stride_before_solving(monkeypatch, method):
    """The methods that solve first and sample after are refused at the boundary, not after the solve."""
    for solver in ("solve_exact", "solve_event_driven"):
        monkeypatch.setattr(
            METHODS_MODULE, solver, lambda *args, **kw: pytest.fail("solved before save_every was checked")
        )
    with pytest.raises(ValueError, match="^save_every must be an integer from 1 to"):
        L.simulate(OSC, 1.0, 1e-3, x0=0.5, method=method, save_every=MAX_STEPS + 1)


@pytest.mark.parametrize("save_every", [1, 7, 1000, 10**6])
def test_rest_time_does_not_depend_on_save_every(save_every):
    # The free decay from x0 = 0.5 at the paper's step stops at t = 3.1458 s
    # (a grid point), which a stride of 1000 does not sample.
    full = L.backward_euler(OSC, 4.0, 1e-4, x0=0.5)
    runs = full.stick_intervals()
    strided = L.backward_euler(OSC, 4.0, 1e-4, x0=0.5, save_every=save_every)
    assert strided.rest_time == runs[-1][0] == full.rest_time
    assert strided.rest_position == full.x[-1]


def test_rest_time_is_nan_while_moving_and_zero_for_a_mass_that_never_moves():
    assert math.isnan(_run(x0=0.5, t_end=0.1).rest_time)
    assert _run(x0=0.005, save_every=100).rest_time == 0.0


@pytest.mark.parametrize("force", [None, F17B, lambda t: 10 * np.sin(5 * np.pi * t)])
def test_blocks_do_not_change_a_single_bit(monkeypatch, force):
    whole = L.backward_euler(OSC, 4.0, 1e-4, x0=0.5, force=force, save_every=3)
    monkeypatch.setattr(timestepping, "BLOCK_SINE", 997)
    monkeypatch.setattr(timestepping, "BLOCK_TABLE", 1009)
    blocks = L.backward_euler(OSC, 4.0, 1e-4, x0=0.5, force=force, save_every=3)
    assert np.array_equal(whole.as_array(), blocks.as_array())
    assert np.array_equal(whole.final_rest, blocks.final_rest, equal_nan=True)


def test_a_callable_forcing_is_never_tabulated_whole(monkeypatch):
    # Memory: the forcing table is one block, whatever the number of steps.
    monkeypatch.setattr(timestepping, "BLOCK_TABLE", 1000)
    sizes = []

    def force(t):
        sizes.append(np.size(t))
        return np.sin(t)

    L.backward_euler(OSC, 1.0, 1e-4, force=force, save_every=10**6)
    assert max(sizes) <= 1000 and sum(sizes[1:]) >= 10_000


# ---------------------------------------------------------------------------
# The command line
# ---------------------------------------------------------------------------

#: A run of 1e9 Algorithm 1 steps (about 24 s with the C kernel, hours in Python):
#: the cases that use it must be refused before it starts.
LONG_RUN = ["--t-end", "1000", "--dt", "1e-6", "--save-every", "1000000"]
BIG = str(2**63)
#: The largest --save-every: the most steps of a run (lumped.numerics.validate.MAX_STEPS).
LARGEST = str(MAX_STEPS)
#: The driver's module, where the command line looks ``simulate`` up at run time.
DRIVER = importlib.import_module("lumped.drivers.simulation")
#: The registry's module, where the one-mass solvers are called.
METHODS_MODULE = importlib.import_module("lumped.drivers.methods")


def _one_line(err: str) -> str:
    assert "Traceback" not in err, err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    return lines[0]


def _main(argv, capsys) -> tuple[int, str]:
    """``main`` in this process: its status and its one stderr line (guarded against a hang)."""
    with no_hang():
        status = main(argv)
    return status, _one_line(capsys.readouterr().err)


# --- bad command lines: status 2, one line naming the real problem -----------------

BAD = [  # (arguments after "simulate", folders to create first, words the line must hold)
    (["--output", "d.csv", *LONG_RUN], ["d.csv"], ["--output", "'d.csv' is a directory"]),
    (["--output", "sub/", *LONG_RUN], ["sub"], ["--output", "is a directory"]),
    (["--output", "nope/o.csv", *LONG_RUN], [], ["--output", "does not exist"]),
    (["--output", ".csv"], [], ["--output", "no file name"]),
    (["--output", "sub/.NPZ"], ["sub"], ["--output", "no file name"]),
    (["--output", ""], [], ["--output", "empty"]),
    (["--output", "o.txt"], [], ["--output", ".csv or .npz"]),
    (["--mass", "--output", "o.csv"], [], ["--mass", "expected one argument"]),
    (["--output", "o.csv", "--dt"], [], ["--dt", "expected one argument"]),
    (["--dt", "1e-3", "--output"], [], ["--output", "expected one argument"]),
    (["--dt", "1e-3", "--dt=1e-4", "--output", "o.csv"], [], ["--dt", "more than once"]),
    (["--output", "a.csv", "--output", "b.csv"], [], ["--output", "more than once"]),
    (["--x00", "1", "--output", "o.csv"], [], ["--x00"]),
    (["--mas", "2", "--output", "o.csv"], [], ["--mas"]),  # no abbreviations
    (["--gamma", "1e400", "--output", "o.csv"], [], ["--gamma", "double precision"]),
    (["--save-every", "-1", "--output", "o.csv"], [], ["--save-every", "integer >= 1"]),
    (["--t-end", "1e5", "--dt", "1e-4", "--output", "o.csv"], [], ["--save-every", "GiB"]),
    (["--t-end", "1e9", "--dt", "1e-9", "--output", "o.csv"], [], ["--t-end/--dt"]),
    (
        ["--method", "exact", "--force-amplitude", "10", "--force-omega", "1e300", "--output", "o.csv"],
        [],
        ["exact"],
    ),  # (API: will name --force-omega instead)
]


@pytest.mark.parametrize(("args", "folders", "words"), BAD, ids=[" ".join(a[:4]) for a, _, _ in BAD])
def test_bad_command_line(tmp_path, monkeypatch, capsys, args, folders, words):
    monkeypatch.chdir(tmp_path)
    for folder in folders:
        os.mkdir(folder)
    status, line = _main(["simulate", *args], capsys)
    assert status == 2
    assert line.startswith("lumped")
    if words == ["exact"]:  # either the API's refusal or the CLI's belt and braces
        assert "--force-omega" in line or "the exact run failed" in line
    else:
        assert all(word in line for word in words), line
    assert sorted(os.listdir(tmp_path)) == sorted(folders)


def test_gamma_inf_is_coulomb_and_writes(tmp_path, capsys):
    status, line = _main(
        ["simulate", "--gamma", "inf", "--x0", "0.5", "--t-end", "0.2", "--output", str(tmp_path / "c.csv")], capsys
    )
    assert status == 0 and "wrote" in line
    assert os.listdir(tmp_path) == ["c.csv"]


def test_huge_save_every_gives_one_line(tmp_path, capsys):
    """Status 2, the bound named, no file, never a traceback."""
    status, line = _main(
        ["simulate", "--t-end", "0.01", "--save-every", BIG, "--output", str(tmp_path / "o.csv")], capsys
    )
    assert status == 2 and line.startswith(
        f"lumped simulate: error: --save-every must be an integer from 1 to {LARGEST}"
    )
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize(
    "method",
    [
        "backward-euler",
        "exact",
    ],
)
def test_the_largest_save_every_keeps_first_and_last(tmp_path, capsys, method):
    out = tmp_path / "o.csv"
    status, _ = _main(
        ["simulate", "--method", method, "--t-end", "0.01", "--save-every", LARGEST, "--output", str(out)], capsys
    )
    assert status == 0
    assert np.loadtxt(out, delimiter=",", skiprows=1)[:, 0].tolist() == [0.0, 0.01]


OVERFLOW = [
    (["--x0", "1e307"], ("--x0",)),
    (["--v0", "1e307"], ("--v0",)),
    (["--force-amplitude", "1e307", "--force-omega", "1"], ("--force-amplitude",)),
    (["--stiffness", "1e300", "--x0", "1e10"], ("--stiffness", "--x0")),
    (["--method", "exact", "--force-amplitude", "10", "--force-omega", "1e300"], ("--force-omega",)),
]


@pytest.mark.parametrize(("args", "options"), OVERFLOW, ids=[" ".join(a) for a, _ in OVERFLOW])
def test_overflow_is_refused_naming_the_option(tmp_path, capsys, args, options):
    status, line = _main(["simulate", *args, "--t-end", "0.01", "--output", str(tmp_path / "o.csv")], capsys)
    assert status == 2 and any(option in line for option in options), line
    assert os.listdir(tmp_path) == []


# --- API errors and failures during the run: one line, the temporary file removed ---


def _raise(exc):
    def run(*args, **kwargs):
        raise exc

    return run


def _sigterm(*args, **kwargs):
    os.kill(os.getpid(), signal.SIGTERM)  # the handler runs on return from kill()
    raise AssertionError("SIGTERM did not unwind the run")


FAILURES = [  # (the driver's behaviour, status, the whole line after "lumped simulate: ")
    (
        _raise(ValueError("x0: the initial state overflows (|x0| k = 1e310 N)")),
        2,
        "error: --x0: the initial state overflows (|x0| k = 1e310 N)",
    ),
    (
        _raise(ValueError("force_amplitude must be finite, got inf")),
        2,
        "error: --force-amplitude must be finite, got inf",
    ),
    (
        _raise(ValueError("t_end/dt: 3e+10 steps would take about 700 s; raise dt or shorten t_end")),
        2,
        "error: --t-end/--dt: 3e+10 steps would take about 700 s; raise dt or shorten t_end",
    ),
    (_raise(ValueError("the run overflowed at t = 1.5: x = inf")), 2, "error: the run overflowed at t = 1.5: x = inf"),
    (_raise(ValueError("two\nlines")), 2, "error: two lines"),
    (
        _raise(OverflowError("math range error")),
        2,
        "error: the backward-euler run failed: OverflowError: math range error",
    ),
    (_raise(FloatingPointError("overflow")), 2, "error: the backward-euler run failed: FloatingPointError: overflow"),
    (_raise(MemoryError()), 2, "error: out of memory; raise --save-every or --dt"),
    (_raise(KeyboardInterrupt()), 130, "interrupted; no output written"),
    (_sigterm, 143, "interrupted; no output written"),
]


@pytest.mark.parametrize(("run", "status", "line"), FAILURES, ids=[f[2][:40] for f in FAILURES])
def test_failure_during_the_run(tmp_path, monkeypatch, capsys, run, status, line):
    monkeypatch.setattr(DRIVER, "simulate", run)
    before = signal.getsignal(signal.SIGTERM)
    assert _main(["simulate", "--output", str(tmp_path / "o.csv")], capsys) == (status, "lumped simulate: " + line)
    assert os.listdir(tmp_path) == []
    assert signal.getsignal(signal.SIGTERM) is before  # handlers restored


def test_disk_full_during_the_write(tmp_path, monkeypatch, capsys):
    def full(*args, **kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(np, "savetxt", full)
    out = tmp_path / "o.csv"
    status, line = _main(["simulate", "--t-end", "0.01", "--output", str(out)], capsys)
    assert status == 2
    assert line == (f"lumped simulate: error: --output: cannot write {str(out)!r}: No space left on device")
    assert os.listdir(tmp_path) == []


def test_unwritable_folder_is_refused_before_the_run(tmp_path, monkeypatch, capsys):
    def denied(*args, **kwargs):
        raise PermissionError(errno.EACCES, os.strerror(errno.EACCES))

    monkeypatch.setattr(cli_output.tempfile, "mkstemp", denied)
    monkeypatch.setattr(DRIVER, "simulate", _raise(AssertionError("ran")))
    status, line = _main(["simulate", "--output", str(tmp_path / "o.csv")], capsys)
    assert status == 2
    assert line == (f"lumped simulate: error: --output: cannot create a file in {str(tmp_path)!r}: Permission denied")


def _make_unwritable(folder) -> list[str]:
    """Make ``folder`` unwritable even for root; return the command that undoes it."""
    folder.chmod(0o555)
    if not os.access(folder, os.W_OK):
        return ["chmod", "755", str(folder)]
    # root ignores the mode bits; the immutable attribute (ext4) stops it too
    if shutil.which("chattr") and subprocess.run(["chattr", "+i", str(folder)]).returncode == 0:
        return ["chattr", "-i", str(folder)]
    folder.chmod(0o755)
    pytest.skip("running as root on a file system without chattr +i: cannot make a folder unwritable")


def test_read_only_folder(tmp_path, capsys):
    folder = tmp_path / "ro"
    folder.mkdir()
    undo = _make_unwritable(folder)
    try:
        status, line = _main(["simulate", *LONG_RUN, "--output", str(folder / "o.csv")], capsys)
        assert status == 2 and "--output: cannot create a file in" in line
        assert os.listdir(folder) == []
    finally:
        subprocess.run(undo, check=True)
        folder.chmod(0o755)


@pytest.mark.parametrize(
    ("message", "expected"),
    [
        ("mass must be > 0 and finite, got 0.0", "--mass must be > 0 and finite, got 0.0"),
        ("save_every: the output would need 5 GiB", "--save-every: the output would need 5 GiB"),
        ("x0: |x0| k = 1e310 N overflows", "--x0: |x0| k = 1e310 N overflows"),  # a formula
        ("t_end/dt must be at most 2e+09 steps", "--t-end/--dt must be at most 2e+09 steps"),
        ("force_until must be >= 0", "--force-until must be >= 0"),
        ("gamma: 1e400 is beyond double precision", "--gamma: 1e400 is beyond double precision"),
        ("mass must be a number, got 'dt'", "--mass must be a number, got 'dt'"),  # the user's value
        ("massive failure: dt", "massive failure: dt"),
        ("the run overflowed at t = 2: dt too large", "the run overflowed at t = 2: dt too large"),
        ("t must be sorted", "t must be sorted"),  # an API name with no option
    ],
)
def test_option_message(message, expected):
    assert option_message(message) == expected


# --- the summary comes from the method's full-resolution run -----------------------


def test_summary_independent_of_save_every(tmp_path, capsys):
    lines = []
    for k in ("1", "1000"):
        argv = "simulate --x0 0.5 --t-end 4 --dt 1e-4 --save-every".split() + [
            k,
            "--output",
            str(tmp_path / f"k{k}.npz"),
        ]
        lines.append(_main(argv, capsys)[1].split(";")[0])
    assert lines[0] == lines[1]
    assert "at rest from t = 3.1458 s" in lines[0]


def test_exact_summary_is_the_event_time(tmp_path, capsys):
    argv = "simulate --method exact --x0 0.5 --t-end 4 --dt 1e-4 --save-every 1000 --output".split()
    argv.append(str(tmp_path / "e.npz"))
    assert "at rest from t = 3.145527023 s" in _main(argv, capsys)[1]


def test_still_moving_names_the_grids_last_time(tmp_path, capsys):
    argv = [
        "simulate",
        "--x0",
        "0.5",
        "--t-end",
        "1.00005",
        "--dt",
        "1e-4",
        "--save-every",
        "7",
        "--output",
        str(tmp_path / "m.csv"),
    ]
    assert "still moving at t = 1.0001 s" in _main(argv, capsys)[1]


# --- subprocesses: the interpreter's own behaviour, umask, signals -----------------


def _cli(*args, cwd, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "lumped", *args], cwd=cwd, capture_output=True, text=True, timeout=30, **kwargs
    )


def test_no_command(tmp_path):
    proc = _cli(cwd=tmp_path)
    assert proc.returncode == 2 and "COMMAND" in _one_line(proc.stderr)


def test_help(tmp_path):
    proc = _cli("simulate", "--help", cwd=tmp_path)
    assert proc.returncode == 0 and proc.stderr == ""
    assert proc.stdout.startswith("usage: lumped simulate") and "--save-every" in proc.stdout


@pytest.mark.parametrize(
    ("umask", "existing", "mode"),
    [
        (0o022, None, 0o644),
        (0o077, None, 0o600),
        (0o077, 0o644, 0o644),
        (0o022, 0o600, 0o600),
    ],
)
def test_file_mode(tmp_path, umask, existing, mode):
    out = tmp_path / "o.csv"
    if existing is not None:
        out.write_text("old\n")
        out.chmod(existing)
    proc = _cli("simulate", "--t-end", "0.01", "--output", "o.csv", cwd=tmp_path, umask=umask)
    assert proc.returncode == 0, proc.stderr
    assert stat.S_IMODE(out.stat().st_mode) == mode
    assert out.read_text().startswith("t,x,v,F_s,F_d,F\n")


def _interrupt(tmp_path, args, sig, *, started, env=None, wait=3.0):
    """Start a run, wait until ``started(temporary file)``, send ``sig``; returns the
    finished process and the seconds it took after the signal (at most ``wait``)."""
    env = {**os.environ, **(env or {})}
    proc = subprocess.Popen(
        [sys.executable, "-m", "lumped", "simulate", *args, "--output", "o.csv"],
        cwd=tmp_path,
        env=env,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    try:
        deadline = time.monotonic() + 10
        while not any(started(tmp_path / f) for f in os.listdir(tmp_path)):
            assert proc.poll() is None and time.monotonic() < deadline, "the run did not start"
            time.sleep(0.02)
        time.sleep(0.2)
        proc.send_signal(sig)
        sent = time.monotonic()
        _, err = proc.communicate(timeout=wait)
    finally:
        proc.kill()
    return subprocess.CompletedProcess(proc.args, proc.returncode, "", err), time.monotonic() - sent


def _exists(path) -> bool:
    return True


def _has_data(path) -> bool:
    return path.stat().st_size > 0


PHASES = {  # the phase the signal reaches -> (arguments, environment, when to send)
    # Algorithm 1 in the Python loop (1e8 steps, about 30 s): interruptible anywhere
    "run": (["--t-end", "100", "--dt", "1e-6", "--save-every", "100000000"], {"LUMPED_PURE_PYTHON": "1"}, _exists),
    # 2e6 rows: the C kernel takes 0.05 s, writing the 55 MB of CSV about 5 s
    "write": (["--t-end", "20", "--dt", "1e-5"], None, _has_data),
}


@pytest.mark.parametrize("phase", PHASES)
@pytest.mark.parametrize(("sig", "status"), [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_signal_removes_the_temporary_file(tmp_path, phase, sig, status):
    args, env, started = PHASES[phase]
    proc, _ = _interrupt(tmp_path, args, sig, started=started, env=env)
    assert proc.returncode == status
    assert _one_line(proc.stderr) == "lumped simulate: interrupted; no output written"
    assert os.listdir(tmp_path) == []


@pytest.mark.skipif(timestepping.KERNEL != "compiled", reason="C kernel not built (or LUMPED_PURE_PYTHON=1)")
def test_sigint_stops_the_c_kernel_at_once(tmp_path):
    proc, waited = _interrupt(tmp_path, LONG_RUN, signal.SIGINT, started=_exists, wait=1.5)
    assert proc.returncode == 130 and waited < 1.0
    assert os.listdir(tmp_path) == []
