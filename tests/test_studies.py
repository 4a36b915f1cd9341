"""The studies' data (lumped.studies, scripts/study.py): chunks, files, bad inputs."""

import importlib.util

import numpy as np
import pytest
from conftest import ROOT

import lumped.studies.config
from lumped import studies
from lumped.drivers.simulation import simulate
from lumped.model.oscillator import Oscillator
from lumped.plotting.studies import intervals
from lumped.studies import rest

CFG = lumped.studies.config.default()
SCRIPT = ROOT / "scripts" / "study.py"
#: A small grid (even: off x0 = 0 and the band edges), cut into uneven chunks.
POINTS, CHUNKS = 14, 3


@pytest.fixture(scope="module")
def whole():
    return rest.rows(CFG, POINTS)


def test_chunks_written_and_merged_equal_one_unchunked_sweep(whole, tmp_path):
    parts = []
    for i in range(CHUNKS):
        parts.append(tmp_path / f"chunk-{i}.csv")
        studies.write_csv(rest.rows(CFG, POINTS, (i, CHUNKS)), parts[-1], rest.COLUMNS)
    studies.merge_csv(parts, tmp_path / "rest.csv", rest.COLUMNS)
    merged = studies.read_csv(tmp_path / "rest.csv", rest.COLUMNS)
    assert list(merged) == list(rest.COLUMNS)
    for name in rest.COLUMNS:  # bit for bit: floats are written by repr
        assert merged[name].dtype == whole[name].dtype and np.array_equal(merged[name], whole[name]), name


@pytest.mark.parametrize("row", [0, 5, 13])
def test_a_row_is_the_single_runs_of_both_methods(whole, row):
    """Against lumped.drivers.simulation.simulate, one run per method (not through the sweep)."""
    osc = Oscillator.bingham(CFG["mass"], CFG["stiffness"], CFG["threshold"], CFG["gamma"])
    x0 = np.linspace(-1, 1, POINTS)[row]
    for prefix, method in (("alg1", "backward-euler"), ("exact", "exact")):
        run = simulate(osc, rest.T_END, CFG["dt"], x0=x0, method=method)
        assert whole[f"{prefix}_rest_position"][row] == run.rest_position
        assert whole[f"{prefix}_rest_time"][row] == run.rest_time
    # every rest position lies in the static band |x| <= tau/k (eq. 6 with v = 0)
    assert abs(whole["exact_rest_position"][row]) <= CFG["threshold"] / CFG["stiffness"]


def test_intervals_are_the_runs_of_true_rows():
    x = np.arange(8.0)
    mask = np.array([1, 1, 0, 0, 1, 0, 1, 1], bool)
    assert intervals(x, mask) == [(0.0, 1.0), (4.0, 4.0), (6.0, 7.0)]
    assert intervals(x, np.zeros(8, bool)) == []


def _script(capsys, *args):
    """The script's main, in this process (its imports are this test's)."""
    spec = importlib.util.spec_from_file_location("study", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    code = module.main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize(
    ("args", "start"),
    [
        (
            ("chunk", "rest", "config/config.yaml", "default", 4, 4, "out.csv"),
            "study: index must be an integer in [0, 3]",
        ),
        (("chunk", "rest", "config/config.yaml", "default", "ten", 4, "out.csv"), "study: invalid literal"),
        (
            ("chunk", "rest", "config/config.yaml", "coarse", 0, 4, "out.csv"),
            "study: resolution must be one of default",
        ),
        (("chunk", "nowhere", "config/config.yaml", "default", 0, 4, "out.csv"), "study: study must be one of rest"),
        (("merge", "rest", "out.csv", "missing.csv"), "study: [Errno 2]"),
        (("nonsense",), "python scripts/study.py chunk STUDY CONFIG"),
        (
            ("chunk", "stops", "config/config.yaml", "default", 2, 2, "out.csv"),
            "study: index must be an integer in [0, 1]",
        ),
    ],
)
def test_bad_arguments_exit_2_with_one_line_and_no_file(tmp_path, capsys, args, start):
    args = [tmp_path / a if str(a).endswith(".csv") else a for a in args]
    args = [ROOT / a if a == "config/config.yaml" else a for a in args]
    code, out, err = _script(capsys, *args)
    assert code == 2 and err.startswith(start), err
    assert len(err.strip().splitlines()) == (2 if args == ["nonsense"] else 1), err  # the usage: its two lines
    assert not (tmp_path / "out.csv").exists()


def test_a_run_still_moving_is_refused_rather_than_written():
    # from the band edge up to round-off, Algorithm 1 creeps at ~1e-16 m/s and never stops (notebook 10)
    with pytest.raises(ValueError, match=r"^study rest: backward-euler from x0 = -0.010000000000000009 m is still"):
        rest.rows(CFG, 401, (0, 2))
