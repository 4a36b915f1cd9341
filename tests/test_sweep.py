"""Sweeps: ``python -m lumped sweep``, :mod:`lumped.drivers.sweep` and the batched kernel :mod:`lumped.kernels.batched`."""

from __future__ import annotations

import io
import math
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import lumped as L
from lumped.cli import main
from lumped.drivers.sweep import Progress, SweepSpec, axis, parse_vary, run_sweep, sweep
from lumped.kernels import batched

DT = 1e-3  # a coarse grid keeps the default run fast; the arithmetic is the same at any dt
KERNELS = ["python"] + (["compiled"] if batched.BATCH_KERNEL == "compiled" else [])


def _stops(v: np.ndarray, mask: np.ndarray | None = None) -> int:
    """Steps entering stick from motion, written out independently of lumped.drivers.sweep."""
    hits = [n for n in range(1, v.size) if v[n] == 0.0 and v[n - 1] != 0.0 and (mask is None or mask[n])]
    return len(hits)


# ---- grid parsing -------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["force-omega", "force_omega", "--force-omega"])
def test_dash_and_underscore_names(name):
    assert parse_vary(f"{name}=1:3:3").name == "force_omega"


def test_linear_and_log_spacing():
    assert np.array_equal(parse_vary("x0=-1:1:5").values, [-1.0, -0.5, 0.0, 0.5, 1.0])
    log = parse_vary("force_omega=log:1:100:3").values
    assert log == pytest.approx([1.0, 10.0, 100.0], rel=4 * np.finfo(float).eps)


def test_repeated_vary_is_a_grid_with_the_first_slowest():
    spec = SweepSpec.build([parse_vary("x0=0:1:2"), parse_vary("v0=0:2:3")], t_end=0.01, dt=DT)
    p = spec.parameters()
    assert spec.rows == 6
    assert list(p["x0"]) == [0, 0, 0, 1, 1, 1] and list(p["v0"]) == [0, 1, 2, 0, 1, 2]


def test_chunks_concatenate_to_the_whole():
    vary = {"x0": np.linspace(-1, 1, 7), "v0": [0.0, 0.5]}
    whole = sweep(vary, t_end=0.3, dt=DT)
    parts = [sweep(vary, t_end=0.3, dt=DT, chunk=(i, 3)) for i in range(3)]
    for name, values in whole.items():
        assert np.array_equal(np.concatenate([p[name] for p in parts]), values, equal_nan=True)


@pytest.mark.parametrize(
    ("spec", "words"),
    [
        ("x0=0:1:0", "COUNT"),
        ("x0=a:1:3", "START and STOP"),
        ("x0=0:1:2.5", "COUNT"),
        ("speed=0:1:3", "unknown or non-numeric"),
        ("method=0:1:3", "unknown or non-numeric"),
        ("force_omega=log:0:10:3", "log spacing"),
        ("force_omega=log:-1:10:3", "log spacing"),
        ("dt=1e-4:1e-3:3", "shares the time grid"),
        ("x0", "NAME=START:STOP:COUNT"),
        ("mass=-1:1:3", "mass must be > 0"),
        ("x0=0:1:1", "COUNT = 1 needs START == STOP"),
        ("x0=-1.7e308:1.7e308:3", "STOP - START overflows"),  # was blamed on the NaN linspace made
    ],
)
def test_bad_vary_one_line_status_2_no_file(tmp_path, capsys, spec, words):
    out = tmp_path / "s.csv"
    assert main(["sweep", "--vary", spec, "--output", str(out)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "--vary" in err and words in err
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize(
    ("argv", "option"),
    [
        (["--vary", "x0=0:1:2", "--vary", "x-0=0:1:2"], "--vary"),  # dashes dropped: the same name
        (["--vary", "x0=0:1:2", "--x0", "1"], "--x0"),
        (["--vary", "x0=0:1:2", "--periods", "0"], "--periods"),
        (["--vary", "x0=0:1:2", "--method", "theta"], "--method"),
        (["--vary", "x0=-1:1:100001", "--t-end", "1000"], "--vary"),  # too long: refused with the estimate
        (["--vary", "force_omega=1:2:2", "--force-amplitude", "1", "--t-end", "1"], "--periods"),
        (["--mass", "0"], "--mass"),
    ],
)
def test_bad_sweep_options_one_line_status_2(tmp_path, capsys, argv, option):
    assert main(["sweep", *argv, "--output", str(tmp_path / "s.npz")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("lumped sweep: error: " + option), err
    assert not list(tmp_path.iterdir())


def test_a_too_long_sweep_states_the_estimate(tmp_path, capsys):
    main(["sweep", "--vary", "x0=-1:1:100001", "--t-end", "1000", "--output", str(tmp_path / "s.csv")])
    assert "would take about" in capsys.readouterr().err


@pytest.mark.parametrize(("forced", "kind"), [({}, "free"), ({"force_amplitude": 1.0, "force_omega": 10.0}, "forced")])
def test_the_estimate_costs_forced_grids_as_forced(forced, kind):
    """A forced grid's steps cost several times a free one's (a sine per step): the estimate says so."""
    from lumped.drivers.sweep import SECONDS_PER_TRAJECTORY_STEP
    from lumped.kernels.batched import BATCH_KERNEL

    spec = SweepSpec.build([axis("x0", [0.0, 0.5])], t_end=1.0, periods=1, **forced)
    assert spec.seconds_per_step() == SECONDS_PER_TRAJECTORY_STEP[BATCH_KERNEL][kind]


def test_duplicate_names_through_the_api():
    with pytest.raises(ValueError, match="^vary: x0 is varied more than once"):
        SweepSpec.build([axis("x0", [0.0]), axis("x0", [1.0])])


# ---- rows against single runs -------------------------------------------------------------------------


#: Call sizes: the defaults (one call here), and small ones that cut the 23 rows into blocks of 5 (the
#: last one of 3, not a divisor) and the 2000 steps into spans of 37 // 5 = 7 and 37 // 3 = 12 steps
#: (which divide neither 2000 nor the save stride 7 nor the window's first step), resumed call after call.
CALLS = {"default": None, "small": (5, 37)}


@pytest.mark.parametrize("calls", CALLS)
@pytest.mark.parametrize("kernel", KERNELS)
def test_batched_equals_single_runs_bit_for_bit(kernel, calls, monkeypatch):
    """Free and forced, Bingham and Coulomb, moving and resting at the end: every summary with ``==``.

    Every row and every saved step is compared, so a block of rows or a span of steps that a call
    leaves out (``np.empty`` memory) or takes twice is caught.
    """
    made = []
    if CALLS[calls] is not None:
        monkeypatch.setattr("lumped.kernels.batched.CALL_SIZE", CALLS[calls][0])
        monkeypatch.setattr("lumped.kernels.batched.CALL_WORK", CALLS[calls][1])
        real = batched._call
        monkeypatch.setattr("lumped.kernels.batched._call", lambda *a: made.append(a[2]) or real(*a))
    rng = np.random.default_rng(12)
    n = 23
    rows = {
        "mass": rng.uniform(0.5, 2, n),
        "stiffness": rng.uniform(50, 150, n),
        "threshold": rng.uniform(0, 2, n),
        "gamma": np.where(np.arange(n) % 3 == 0, np.inf, rng.uniform(0.5, 5, n)),
        "x0": rng.uniform(-1, 1, n),
        "v0": np.where(np.arange(n) % 4 == 0, 0.0, rng.uniform(-1, 1, n)),
        "force_amplitude": np.where(np.arange(n) % 2 == 0, 0.0, rng.uniform(-5, 5, n)),
        "force_omega": rng.uniform(2, 20, n),
        "force_phase": rng.uniform(-1, 1, n),
        "force_until": np.where(np.arange(n) % 5 == 0, 0.7, np.inf),
    }
    t_end, window = 2.0, 0.9  # the window of the kernel's window counts: steps with t_n >= 0.9
    c = np.where(np.isinf(rows["gamma"]), 0.0, 1 / rows["gamma"])
    params = batched.BatchParameters(*(rows[k] if k != "gamma" else c for k in _BATCH_ORDER))
    first = np.full(n, int(np.searchsorted(np.arange(2001) * DT, window)))
    got = batched.batch_backward_euler(params, t_end, DT, window=first, save_every=7, kernel=kernel)
    for j in range(n):
        osc = L.Oscillator.bingham(rows["mass"][j], rows["stiffness"][j], rows["threshold"][j], rows["gamma"][j])
        force = L.SwitchedSine(*(rows[k][j] for k in _BATCH_ORDER[6:]))
        ref = L.backward_euler(osc, t_end, DT, x0=rows["x0"][j], v0=rows["v0"][j], force=force)
        inside = ref.t >= window
        assert got.v_end[j] == ref.v[-1] and got.x_end[j] == ref.x[-1]
        assert got.max_abs_x[j] == np.max(np.abs(ref.x))
        assert got.window_max_abs_x[j] == np.max(np.abs(ref.x[inside]))
        assert got.stops[j] == _stops(ref.v) and got.window_stops[j] == _stops(ref.v, inside)
        if ref.v[-1] == 0:
            assert got.rest_step[j] * DT == ref.rest_time
        assert np.array_equal(
            got.x[:, j],
            L.backward_euler(osc, t_end, DT, x0=rows["x0"][j], v0=rows["v0"][j], force=force, save_every=7).x,
        )
    if CALLS[calls] is not None:  # the calls did split rows and steps: 4 blocks of 5 in spans of 7, 1 of 3 in 12
        assert len(made) == 4 * math.ceil(2000 / 7) + math.ceil(2000 / 12)


_BATCH_ORDER = (
    "mass",
    "stiffness",
    "threshold",
    "gamma",
    "x0",
    "v0",
    "force_amplitude",
    "force_omega",
    "force_phase",
    "force_until",
)


def test_sweep_rows_equal_single_run_summaries_free_decay():
    x0 = np.linspace(-1, 1, 9)
    rows = sweep({"x0": x0}, t_end=4.0, dt=DT)
    assert list(rows) == ["x0", "rest_time", "rest_position", "max_abs_x", "stops"]
    for j, x in enumerate(x0):
        ref = L.backward_euler(L.Oscillator.bingham(), 4.0, DT, x0=x)
        assert np.array_equal(rows["rest_time"][j], ref.rest_time, equal_nan=True)
        assert np.array_equal(rows["rest_position"][j], ref.rest_position, equal_nan=True)
        assert rows["max_abs_x"][j] == np.max(np.abs(ref.x)) and rows["stops"][j] == _stops(ref.v)


def test_forced_summaries_against_a_direct_computation():
    """steady_amplitude and stops_per_period from the last K periods of a single run, computed here."""
    omega = np.array([4.0, 10.0, 25.0])
    rows = sweep({"force_omega": omega}, t_end=6.0, dt=DT, periods=3, force_amplitude=3.0, threshold=1.0)
    for j, w in enumerate(omega):
        ref = L.backward_euler(L.Oscillator.bingham(), 6.0, DT, force=L.SwitchedSine(3.0, w))
        inside = ref.t >= ref.t[-1] - 3 * 2 * math.pi / w
        assert rows["steady_amplitude"][j] == np.max(np.abs(ref.x[inside]))
        assert rows["stops_per_period"][j] == _stops(ref.v, inside) / 3
    assert rows["stops_per_period"].max() > 0  # the case sticks somewhere: the count is exercised


def test_forced_columns_are_nan_where_the_forcing_ends_or_is_absent():
    rows = sweep({"force_amplitude": [0.0, 3.0]}, t_end=2.0, dt=DT, force_omega=20.0, periods=2)
    assert np.isnan(rows["steady_amplitude"][0]) and np.isfinite(rows["steady_amplitude"][1])
    ended = sweep({"force_until": [1.0, math.inf]}, t_end=2.0, dt=DT, force_omega=20.0, force_amplitude=3.0, periods=2)
    assert np.isnan(ended["stops_per_period"][0]) and np.isfinite(ended["stops_per_period"][1])


def test_exact_rows_against_solve_exact():
    """Rest time and position from the exact event times; stops = the solver's stop events (here every
    stick lasts longer than dt, so each stop event is one grid step entering stick)."""
    x0 = np.array([-0.9, -0.3, 0.005, 0.5, 0.8])
    rows = sweep({"x0": x0}, t_end=4.0, dt=DT, method="exact")
    for j, x in enumerate(x0):
        sol = L.solve_exact(L.Oscillator.bingham(), 4.0, x0=x)
        start, where = sol.rest_through(4.0)
        assert np.array_equal([rows["rest_time"][j], rows["rest_position"][j]], [start, where], equal_nan=True)
        assert rows["stops"][j] == len(sol.event_times("stop"))  # a "rest" event repeats its stop
        extrema = [abs(e.x[0]) for e in sol.events if e.kind in ("stop", "reversal", "rest")]
        assert rows["max_abs_x"][j] == pytest.approx(max([abs(x), *extrema]), abs=1e-9)


# ---- the output files -----------------------------------------------------------------------------------


def test_csv_and_npz_columns(tmp_path):
    argv = ["sweep", "--vary", "x0=-1:1:3", "--vary", "force-omega=log:5:20:2", "--force-amplitude", "2"]
    argv += ["--t-end", "3", "--dt", "1e-3", "--periods", "2"]
    assert main([*argv, "--output", str(tmp_path / "s.csv")]) == 0
    assert main([*argv, "--output", str(tmp_path / "s.npz")]) == 0
    header = "x0,force_omega,rest_time,rest_position,max_abs_x,stops,steady_amplitude,stops_per_period"
    assert (tmp_path / "s.csv").read_text().splitlines()[0] == header
    csv = np.genfromtxt(tmp_path / "s.csv", delimiter=",", names=True)
    with np.load(tmp_path / "s.npz") as npz:
        assert list(npz.files) == header.split(",")
        assert npz["stops"].dtype == np.int64 and npz["x0"].size == 6
        for name in npz.files:
            assert np.array_equal(csv[name], npz[name], equal_nan=True)  # %.17g round-trips


def test_progress_goes_to_stderr_only(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr("lumped.kernels.batched.CALL_SIZE", 2)
    # an estimate long enough to show progress (50 s), not so long as to be refused
    monkeypatch.setattr("lumped.drivers.sweep.limits.SECONDS_PER_BATCHED_ROW", 10.0)
    out = tmp_path / "s.csv"
    assert main(["sweep", "--vary", "x0=0:1:5", "--t-end", "0.1", "--output", str(out)]) == 0
    assert "sweep: 5/5 rows" in capsys.readouterr().err
    lines = out.read_text().splitlines()
    assert lines[0] == "x0,rest_time,rest_position,max_abs_x,stops" and len(lines) == 6


def test_progress_on_a_terminal_rewrites_one_line():
    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    stream = Tty()
    bar = Progress(stream, True)
    bar(1, 2)
    bar(2, 2)
    assert stream.getvalue().startswith("\rsweep: 1/2") and stream.getvalue().count("\n") == 1


# ---- the fallback -------------------------------------------------------------------------------------


@pytest.mark.skipif(batched.BATCH_KERNEL != "compiled", reason="batched C kernel not built")
def test_numpy_fallback_is_bit_identical_to_the_compiled_kernel():
    spec = SweepSpec.build(
        [parse_vary("x0=-1:1:11"), parse_vary("force_omega=log:5:30:4")],
        t_end=3.0,
        dt=DT,
        periods=2,
        force_amplitude=2.0,
        gamma=math.inf,
    )
    compiled = run_sweep(spec)
    try:
        batched.BATCH_KERNEL = "python"
        fallback = run_sweep(spec)
    finally:
        batched.BATCH_KERNEL = "compiled"
    for name in compiled:
        assert np.array_equal(compiled[name], fallback[name], equal_nan=True)


def _vector_paths() -> list[str]:
    if batched.BATCH_KERNEL != "compiled":
        return []
    from lumped.kernels import _batch_kernel

    return list(_batch_kernel.paths())


def test_this_machine_runs_every_vector_path():
    """The project's machine has AVX-512 and AVX2: the path tests below run every loop, none skipped."""
    if batched.BATCH_KERNEL != "compiled":
        pytest.skip("batched C kernel not built")
    from lumped.kernels import _batch_kernel

    flags = open("/proc/cpuinfo").read().split() if os.path.exists("/proc/cpuinfo") else []
    expected = ["default"] + (["avx2"] if "avx2" in flags else []) + (["avx512"] if "avx512f" in flags else [])
    assert list(_batch_kernel.paths()) == expected


@pytest.mark.parametrize("path", _vector_paths())
def test_each_vector_path_equals_the_numpy_twin_bit_for_bit(path):
    """AVX-512, AVX2 and baseline loops against the NumPy loop, every bit of every sum and saved x.

    301 trajectories: three blocks of the kernel (the last one partial and not a
    whole number of vector lanes); windows differing within a block (from step
    0, mid-run, none); free and forced lanes, some forcing switched off; a
    save stride that cuts the kernel's chunks of steps.
    """
    rng = np.random.default_rng(7)
    n, dt, n_steps, save_every = 301, DT, 1500, 7
    par = np.array(
        [
            rng.uniform(0.5, 2, n),
            rng.uniform(50, 150, n),
            rng.uniform(0, 2, n),
            np.where(np.arange(n) % 3 == 0, 0.0, rng.uniform(0.2, 2, n)),
            rng.uniform(-1, 1, n),
            np.where(np.arange(n) % 4 == 0, 0.0, rng.uniform(-1, 1, n)),
            np.where(np.arange(n) < 150, 0.0, rng.uniform(-5, 5, n)),
            rng.uniform(2, 20, n),
            rng.uniform(-1, 1, n),
            np.where(np.arange(n) % 5 == 0, 0.7, np.inf),
        ]
    )
    nw = rng.choice([0.0, 1.0, 333.0, 901.0, n_steps + 1.0], n)
    rows = batched.validate.output_rows(n_steps, save_every) - 1
    out = {}
    for name, loop in (("twin", batched._numpy_batch), ("c", batched._compiled_batch)):
        sums, xs = np.empty((7, n)), np.empty((rows, n))
        loop(dt, 1, n_steps, n_steps, save_every, par, nw, sums, xs, *(() if name == "twin" else (path,)))
        out[name] = (sums, xs)
    for twin, c in zip(out["twin"], out["c"]):
        assert np.array_equal(twin.view(np.uint64), c.view(np.uint64))


def _good_arguments(n: int = 3, n_steps: int = 10, save_every: int = 4) -> list:
    """A valid call of the batched kernel: 3 trajectories, steps 1..10 saved at 4, 8 and 10."""
    par = np.ones((10, n))
    return [DT, 1, n_steps, n_steps, save_every, par, np.full(n, 11.0), np.empty((7, n)), np.empty((3, n))]


#: (argument index, bad value, words of the message): every argument the binding checks.
BAD_BATCH = {
    "dt zero": (0, 0.0, "dt must be > 0"),
    "dt nan": (0, math.nan, "dt must be > 0"),
    "first 0": (1, 0, "1 <= first"),
    "last past n_steps": (2, 11, "1 <= first"),
    "first past last + 1": (1, 12, "1 <= first"),
    "n_steps negative": (3, -1, "n_steps must be >= 0"),
    "save_every negative": (4, -1, "save_every must be >= 0"),
    "save_every 0 with rows": (4, 0, "xs must be empty"),
    "save_every changes the rows": (4, 3, "xs must hold exactly"),
    "par short": (5, np.ones((9, 3)), "par must hold 10 rows"),
    "par of ints": (5, np.ones((10, 3), dtype=np.int64), "par must hold doubles"),
    "par of float32": (5, np.ones((10, 3), dtype=np.float32), "par must hold doubles"),
    "par strided": (5, np.ones((10, 6))[:, ::2], "par must be a C-contiguous"),
    "par not a buffer": (5, [1.0] * 30, "par must be a C-contiguous"),
    "nw of ints": (6, np.full(3, 11), "nw must hold doubles"),
    "nw longer": (6, np.full(4, 11.0), "par must hold 10 rows"),
    "sums read-only": (7, bytes(7 * 3 * 8), "sums must be a C-contiguous writable"),
    "sums short": (7, np.empty((6, 3)), "sums must hold 7 rows"),
    "xs short": (8, np.empty((2, 3)), "xs must hold exactly"),
    "xs long": (8, np.empty((4, 3)), "xs must hold exactly"),
    "xs of bytes": (8, bytearray(9 * 8), "xs must hold doubles"),
    "xs read-only": (8, None, "xs must be a C-contiguous writable"),  # made in the test
}


@pytest.mark.skipif(batched.BATCH_KERNEL != "compiled", reason="batched C kernel not built")
@pytest.mark.parametrize("case", BAD_BATCH)
def test_the_batched_binding_refuses_each_bad_argument(case):
    """One line, a ValueError naming the argument; the good call beside it runs (so the refusal is the argument's)."""
    index, value, words = BAD_BATCH[case]
    good = _good_arguments()
    batched._compiled_batch(*good)
    if case == "xs read-only":
        value = np.empty((3, 3))
        value.setflags(write=False)
    bad = good[:index] + [value] + good[index + 1 :]
    with pytest.raises(ValueError, match="^bingham_batch: ") as err:
        batched._compiled_batch(*bad)
    assert words in str(err.value) and "\n" not in str(err.value)


@pytest.mark.skipif(batched.BATCH_KERNEL != "compiled", reason="batched C kernel not built")
def test_the_batched_binding_accepts_the_edges():
    """No steps (n_steps = 0 or first = last + 1), no trajectories, nothing saved: no error, and the
    summaries are what no step leaves.

    From step 0 (``first = 1``) a call with no step writes the initial state: ``v = v0``, ``F_s = k x0``,
    ``rest`` the first step of the current run of ``v == 0`` (0 if ``v0 == 0``, else 1) and every count
    and maximum 0 (``_batch_kernel.c``'s layout).  With ``m = k = x0 = 1`` these are exact: ``(v0, 1,
    rest, 0, 0, 0, 0)``.  Resuming (``first > 1``) with no step leaves the summaries as they were.
    """
    par = np.ones((10, 3))
    par[5] = (1.0, 0.0, -2.0)  # v0: moving, at rest, moving the other way
    sums = np.full((7, 3), np.nan)
    batched._compiled_batch(DT, 1, 0, 0, 0, par, np.full(3, 1.0), sums, np.empty(0))
    expected = np.array([[1.0, 0.0, -2.0], [1.0] * 3, [1.0, 0.0, 1.0], *([[0.0] * 3] * 4)])
    assert np.array_equal(sums, expected)
    resumed = np.arange(21.0).reshape(7, 3)
    batched._compiled_batch(DT, 5, 4, 10, 4, par, np.full(3, 1.0), resumed, np.empty((0, 3)))
    assert np.array_equal(resumed, np.arange(21.0).reshape(7, 3))
    sums, xs = np.empty((7, 0)), np.empty((3, 0))
    batched._compiled_batch(DT, 1, 10, 10, 4, np.ones((10, 0)), np.empty(0), sums, xs)
    assert sums.shape == (7, 0) and xs.shape == (3, 0)


@pytest.mark.skipif(batched.BATCH_KERNEL != "compiled", reason="batched C kernel not built")
def test_an_unknown_vector_path_is_refused():
    sums, x = np.empty((7, 1)), np.empty(0)
    with pytest.raises(ValueError, match="path must be"):
        batched._compiled_batch(DT, 1, 10, 10, 0, np.ones((10, 1)), np.ones(1), sums, x, "neon")


def test_the_estimate_is_for_the_chunk_that_runs():
    """200000 exact rows of 6 s at 1e-4 (ten times the full rest study) are too long as one run, fine as 16 chunks."""
    axes = [axis("x0", np.linspace(-1, 1, 200_000))]
    with pytest.raises(ValueError, match=r"^vary: 200000 rows of exact \(60000 steps each\) would take about"):
        SweepSpec.build(axes, t_end=6.0, method="exact")
    spec = SweepSpec.build(axes, t_end=6.0, method="exact", chunk=(15, 16))
    assert spec.rows == 200_000 and len(range(spec.rows)[spec.chunk(15, 16)]) == 12500
    with pytest.raises(ValueError, match=r"^vary: 200000 rows of exact"):  # a chunk too long is still refused
        SweepSpec.build(axes, t_end=6.0, method="exact", chunk=(0, 1))


# ---- signals between bounded calls ----------------------------------------------------------------------


@pytest.mark.skipif(batched.BATCH_KERNEL != "compiled", reason="batched C kernel not built")
@pytest.mark.parametrize(("sig", "status"), [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_stops_a_long_sweep_within_one_call(tmp_path, sig, status):
    """A sweep of 20001 rows x 4e6 steps (estimated 200 s) stops within a bounded time of the signal.

    Python's handlers run between kernel calls, and a call is bounded by CALL_WORK trajectory-steps:
    at the estimated (pessimistic) cost of a forced trajectory-step, 2^24 * 1.3e-8 s = 0.22 s.  The bound
    allows four such calls (a loaded machine) plus 1 s for the handler, the cleanup and the exit.  One
    call for all the steps of 8192 rows, as before, takes 8192 * 4e6 * 0.45e-9 s = 15 s at least.
    """
    from lumped.drivers.sweep import SECONDS_PER_TRAJECTORY_STEP

    bound = 1.0 + 4 * batched.CALL_WORK * SECONDS_PER_TRAJECTORY_STEP["compiled"]["forced"]
    argv = ["sweep", "--vary", "x0=-1:1:20001", "--t-end", "400", "--dt", "1e-4", "--output", "o.csv"]
    proc = subprocess.Popen(
        [sys.executable, "-m", "lumped", *argv],
        cwd=tmp_path,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    try:
        deadline = time.monotonic() + 20
        while not list(tmp_path.glob("*.part")):  # the output is reserved just before the run
            assert proc.poll() is None and time.monotonic() < deadline, "the sweep did not start"
            time.sleep(0.02)
        time.sleep(2.0)  # past the row checks, inside the kernel's calls
        assert proc.poll() is None
        proc.send_signal(sig)
        sent = time.monotonic()
        _, err = proc.communicate(timeout=bound + 30)
        waited = time.monotonic() - sent
    finally:
        proc.kill()
    assert proc.returncode == status and waited < bound, (waited, bound)
    assert err.strip() == "lumped sweep: interrupted; no output written"
    assert os.listdir(tmp_path) == []  # neither the output nor its temporary file
