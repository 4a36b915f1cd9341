"""A sweep's limits and its API's refusals (issue 19): one line, before any work, never a traceback.

The size of a grid (rows, memory, file, time) is checked from the sizes of
its axes before any value is built or checked: the tests replace the value
check by one that fails the test if called, rather than timing the refusal.
The time estimate of the single-run methods is checked to count every event of
the runs (benchmarks/bench_sweep_estimate.py compares it with measured time).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import lumped as L
from lumped.cli import main
from lumped.drivers.sweep import MAX_ROWS, SweepSpec, axis, chunk_slice, grid, limits, parse_vary, summaries, sweep


@pytest.fixture
def no_value_check(monkeypatch):
    """Building or checking any value of an axis fails the test."""

    def called(*args, **kwargs):
        raise AssertionError("a value was built or checked before the size was")

    monkeypatch.setattr(grid, "_check_values", called)
    monkeypatch.setattr(grid, "axis", called)  # read from grid by sweep() and by VaryText.axis
    monkeypatch.setattr(np, "linspace", called)


def _one_line(capsys, status: int, start: str) -> str:
    err = capsys.readouterr().err.strip()
    assert status == 2 and len(err.splitlines()) == 1, err
    assert err.startswith(start), err
    return err


# ---- sizes, before any value ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("vary", "words"),
    [
        (["x0=-1:1:10000", "v0=-1:1:10000"], "the grid has 1e+08 rows (10000 x 10000), more than 1e+07"),
        (["x0=-1:1:6000", "v0=-1:1:5000"], "the grid has 3e+07 rows (6000 x 5000), more than 1e+07"),
    ],
)
def test_a_huge_grid_is_refused_from_its_counts(tmp_path, capsys, no_value_check, vary, words):
    argv = [item for v in vary for item in ("--vary", v)]
    status = main(["sweep", *argv, "--output", str(tmp_path / "s.csv")])
    assert words in _one_line(capsys, status, "lumped sweep: error: --vary: ")
    assert not list(tmp_path.iterdir())


def test_a_huge_grid_is_refused_from_its_sizes_through_the_api(no_value_check):
    with pytest.raises(ValueError, match=r"^vary: the grid has 1e\+08 rows \(10000 x 10000\)"):
        sweep({"x0": range(10_000), "v0": np.zeros(10_000)})


def test_memory_is_estimated_per_row_and_column(tmp_path, capsys, no_value_check):
    """1e7 rows of 9 columns: about 5 GiB by the estimate (the row limit alone would let them through)."""
    argv = ["x0=0:1:10", "v0=0:1:10", "mass=1:2:10", "stiffness=1:2:100", "threshold=0:1:100"]
    status = main(["sweep", *[i for v in argv for i in ("--vary", v)], "--output", str(tmp_path / "s.npz")])
    err = _one_line(capsys, status, "lumped sweep: error: --vary: 10000000 rows of 9 columns would need about")
    assert "GiB of memory, more than the 4 GiB allowed" in err


def test_the_file_is_bounded_by_25_bytes_a_value_in_csv(monkeypatch):
    """The file's bound (25 bytes a value in .csv, 8 in .npz) is checked apart from the memory's."""
    monkeypatch.setattr(limits, "MAX_MEMORY_BYTES", math.inf)
    monkeypatch.setattr(limits.validate, "MAX_SECONDS", math.inf)
    counts = [10, 10, 10, 100, 100]  # 1e7 rows of 9 columns: 2.1 GiB in .csv, 0.7 in .npz
    assert limits.check_size(counts, n_steps=1, method="backward-euler", forced=False, output=".csv") == 10**7
    monkeypatch.setattr(limits.validate, "MAX_OUTPUT_BYTES", 2 * 1024**3)
    with pytest.raises(ValueError, match=r"^vary: the \.csv file could reach 2\.1 GiB \(10000000 rows of 9 values"):
        limits.check_size(counts, n_steps=1, method="backward-euler", forced=False, output=".csv")
    assert limits.check_size(counts, n_steps=1, method="backward-euler", forced=False, output=".npz") == 10**7


def test_a_long_exact_sweep_is_refused_before_its_values(tmp_path, capsys, no_value_check):
    """The issue's case: 2e6 exact rows at dt = 0.5 were estimated at 10 s and took some 20 minutes."""
    status = main(["sweep", "--vary", "x0=-1:1:2000000", "--method", "exact", "--dt", "0.5", "--output", "s.csv"])
    err = _one_line(capsys, status, "lumped sweep: error: --vary: 2000000 rows of exact (4 steps each) would take")
    assert "more than the 600 s allowed" in err


def test_count_with_a_non_ascii_digit_names_vary(tmp_path, capsys):
    status = main(["sweep", "--vary", "x0=0:1:²", "--output", str(tmp_path / "s.csv")])
    err = _one_line(capsys, status, "lumped sweep: error: --vary: COUNT must be an integer >= 1")
    assert "'²'" in err


def test_periods_with_a_non_ascii_digit_names_periods(tmp_path, capsys):
    status = main(["sweep", "--vary", "x0=0:1:2", "--periods", "²", "--output", str(tmp_path / "s.csv")])
    _one_line(capsys, status, "lumped sweep: error: --periods must be an integer >= 1, got '²'")


def test_the_help_states_the_limits_and_what_stops_counts(capsys):
    assert main(["sweep", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert f"more than {MAX_ROWS:.0e} rows" in text and "more than 600 s" in text and "4 GiB" in text
    assert "not the exact solution's stops" in text and "3 stops, --method exact: 1" in text


# ---- the time estimate of the single-run methods --------------------------------------------------------

#: (method, sweep arguments): few grid points (the cost per run and per event dominates), many grid points,
#: and forced runs (many events).  benchmarks/bench_sweep_estimate.py times the same runs against the
#: estimate (within a factor 4 of it on this project's machine): timing is a benchmark's job, not a test's.
RUNS = [
    ("exact", dict(vary={"x0": np.linspace(-1, 1, 40)}, dt=0.5)),
    ("exact", dict(vary={"x0": np.linspace(-1, 1, 20)}, dt=1e-4)),
    ("exact", dict(vary={"x0": np.linspace(-1, 1, 5)}, t_end=10.0, dt=0.01, force_amplitude=10.0, force_omega=15.7)),
    ("exact", dict(vary={"x0": np.linspace(-1, 1, 4)}, t_end=25.0, dt=0.01, force_amplitude=10.0, force_omega=15.7)),
    ("event-driven", dict(vary={"x0": np.linspace(-1, 1, 10)}, dt=0.5)),
]


def spec_of(method: str, kw: dict) -> SweepSpec:
    kw = dict(kw)
    axes = [axis(name, values) for name, values in kw.pop("vary").items()]
    return SweepSpec.build(axes, method=method, periods=1, **kw)


@pytest.mark.parametrize(("method", "kw"), RUNS, ids=[f"{m}-{i}" for i, (m, _) in enumerate(RUNS)])
def test_the_estimate_counts_every_event_the_runs_have(method, kw):
    """The estimate's event term is an upper bound: no row has more events than the estimate gives it.

    The old estimate (1 us per grid point, no events) was 100 times too low at dt = 0.5, where the
    cost is the events'.  Each row is solved exactly and its events counted; the estimate, with
    every row in its sample (these grids have at most EVENT_SAMPLE rows), must cover each, and the
    row cost is the model's: SECONDS_PER_RUN's row, sample and event terms, nothing else.
    """
    spec = spec_of(method, kw)
    rows = np.arange(spec.rows)
    assert rows.size <= limits.EVENT_SAMPLE
    estimated = spec._events(rows)
    p = spec.parameters()
    for j in rows:
        row = {n: float(v[j]) for n, v in p.items()}
        force = L.SwitchedSine(row["force_amplitude"], row["force_omega"], row["force_phase"], row["force_until"])
        osc = L.Oscillator.bingham(row["mass"], row["stiffness"], row["threshold"], row["gamma"])
        counted = len(L.solve_exact(osc, spec.n_steps * spec.dt, x0=row["x0"], v0=row["v0"], force=force).events)
        assert counted <= estimated[j], (j, counted, estimated[j])
    cost = limits.SECONDS_PER_RUN[method]
    event = cost["forced event" if spec.forced else "free event"]
    row = cost["row"] + (spec.n_steps + 1) * cost["sample"] + event * float(np.mean(estimated))
    assert spec.seconds() == pytest.approx(spec.rows * row, rel=1e-12)  # no output file: no writing term


# ---- the API's refusals -------------------------------------------------------------------------------

BAD_API = [
    ("complex values", lambda: sweep({"x0": [1 + 2j]}), "vary: x0 must hold real numbers (int or float), got complex"),
    ("pairs, not a mapping", lambda: sweep([("x0", [0.1])]), "vary must be a mapping of parameter names"),
    ("a 2-d array", lambda: sweep({"x0": np.zeros((2, 2))}), r"vary: x0 must be a 1-d sequence of numbers, got an"),
    ("nested lists", lambda: sweep({"x0": [[0.1, 0.2]]}), "vary: x0 must be a 1-d sequence of numbers"),
    ("a scalar", lambda: sweep({"x0": 0.5}), "vary: x0 must be a 1-d sequence of numbers, got float"),
    ("boolean array", lambda: sweep({"x0": np.array([True, False])}), "vary: x0 must hold real numbers"),
    ("boolean in a list", lambda: sweep({"x0": [True, 0.5]}), "vary: x0 must hold real numbers .* got booleans"),
    ("strings", lambda: sweep({"x0": ["0.1"]}), "vary: x0 must hold real numbers .* got strings"),
    ("a name not a string", lambda: sweep({1: [0.1]}), "vary: a parameter name must be a string"),
    ("a chunk not a pair", lambda: sweep({"x0": [0.1]}, chunk=(0,)), "chunk must be a pair"),
    ("a boolean chunk index", lambda: sweep({"x0": [0.1]}, chunk=(True, 2)), "index must be an integer"),
]


@pytest.mark.parametrize(("call", "message"), [(c, m) for _, c, m in BAD_API], ids=[i for i, _, _ in BAD_API])
def test_bad_api_input_is_one_value_error(call, message):
    with pytest.raises(ValueError, match="^" + message.replace("(", r"\(").replace(")", r"\)")) as info:
        call()
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("index", [np.int64(1), np.int32(1), 1])
def test_numpy_integers_are_chunk_indices(index):
    vary = {"x0": np.linspace(-1, 1, 4)}
    assert np.array_equal(sweep(vary, t_end=0.01, dt=1e-3, chunk=(index, np.int64(2)))["x0"], vary["x0"][2:])
    assert chunk_slice(4, index, 2) == slice(2, 4)


def test_values_are_checked_in_full_by_their_extremes():
    """The array check sees a bad value anywhere, NaN included, and names it as the validator does."""
    with pytest.raises(ValueError, match=r"^vary: mass must be > 0 and finite, got -1\.0"):
        axis("mass", [1.0, 2.0, -1.0, 3.0])
    with pytest.raises(ValueError, match=r"^vary: x0 must be a real number, got nan"):
        axis("x0", [0.0, math.nan, 1.0])
    with pytest.raises(ValueError, match=r"^vary: force_until must be >= 0"):
        axis("force_until", [math.inf, -1.0])
    assert parse_vary("gamma=1:2:3").values.tolist() == [1.0, 1.5, 2.0]


def test_a_row_error_names_vary_and_the_row(tmp_path, capsys):
    status = main(["sweep", "--vary", "x0=0:1e299:3", "--output", str(tmp_path / "s.csv")])
    err = _one_line(capsys, status, "lumped sweep: error: --vary: x0: the run could reach")
    assert err.endswith("(row 1: x0 = 5e+298)")


# ---- what the stops column counts -----------------------------------------------------------------------


def test_stops_counts_the_samples_stops_as_documented():
    """From x0 = 0.5 backward Euler's one-step sticks at reversals count: 3, where the exact solution stops once."""
    import lumped as L

    be = sweep({"x0": [0.5]}, t_end=4.0)["stops"]
    exact = sweep({"x0": [0.5]}, t_end=4.0, method="exact")["stops"]
    solution = L.solve_exact(L.Oscillator.bingham(), 4.0, x0=0.5)
    stops = [e for e in solution.events if e.kind == "stop"]
    assert be.tolist() == [3] and exact.tolist() == [len(stops)] == [1]
    assert "the exact solution's stop events" in summaries.__doc__
