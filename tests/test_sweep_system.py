"""``python -m lumped sweep --system FILE``: a system file's parameters swept (:mod:`lumped.drivers.sweep.system`).

Every row is checked against the single run ``simulate --system`` makes of the file written with the row's
values (the file's text formatted here, not :func:`~lumped.model.system_parameters.with_values`), its summaries
formed here from that run's CSV columns: equal with ``==``, since both are the same arithmetic on the same
numbers and ``%.17g`` round-trips a double.
"""

from __future__ import annotations

import csv
import itertools
import math

import numpy as np
import pytest

from lumped.cli import main
from lumped.drivers.sweep import system as by_file
from lumped.model.files import load_system

#: Two blocks on springs in a chain, a dry-friction contact (static above kinetic) under the second and a
#: Bingham contact under the first, released from x1 = X1; both come to rest within T_END for most rows.
TWO_BLOCKS = """
[[mass]]
name = "m1"
mass = 1.0
x0 = {x1!r}

[[mass]]
name = "m2"
mass = 2.0
x0 = -0.1

[[element]]
name = "k1"
kind = "spring"
between = ["ground", "m1"]
stiffness = 100.0

[[element]]
name = "k12"
kind = "spring"
between = ["m1", "m2"]
stiffness = 50.0

[[element]]
name = "floor1"
kind = "bingham"
between = ["ground", "m1"]
threshold = 1.0
gamma = 1.0

[[element]]
name = "fric"
kind = "friction"
between = ["ground", "m2"]
static = {static!r}
kinetic = 1.5
"""
#: The paper's system with a sine on the mass (a file of the paper's form: the batched kernel).
ONE_MASS = """
[[mass]]
name = "m"
mass = 1.0
x0 = {x0!r}

[[element]]
name = "spring"
kind = "spring"
between = ["ground", "m"]
stiffness = 100.0

[[element]]
name = "dashpot"
kind = "bingham"
between = ["ground", "m"]
threshold = {threshold!r}
gamma = 1.0

[[force]]
on = "m"
kind = "sine"
amplitude = 3.0
omega = 7.0
until = 1.5
"""
CASES = {
    "network": (TWO_BLOCKS, {"fric.static": ("static", 1.5, 4.5, 3), "m1.x0": ("x1", 0.1, 0.6, 2)}, "1", "2e-3"),
    "one-mass": (
        ONE_MASS,
        {"dashpot.threshold": ("threshold", 0.5, 2.0, 4), "m.x0": ("x0", -0.5, 0.5, 3)},
        "3",
        "1e-3",
    ),
}


def _read(path) -> dict[str, list[str]]:
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    return {name: [r[i] for r in rows[1:]] for i, name in enumerate(rows[0])}


def _summaries(run: dict[str, list[str]], mass: str) -> dict[str, str | float | int]:
    """The four summaries of ``mass`` from a single run's CSV, written out independently of lumped."""
    t = [float(v) for v in run["t"]]
    x = [float(v) for v in run[f"x_{mass}"]]
    v = [float(u) for u in run[f"v_{mass}"]]
    stops = sum(1 for n in range(1, len(v)) if v[n] == 0.0 and v[n - 1] != 0.0)
    if v[-1] != 0.0:
        rest_time, rest_position = "", ""
    else:
        last_moving = max((n for n in range(len(v)) if v[n] != 0.0), default=-1)
        rest_time, rest_position = t[last_moving + 1], x[-1]
    return {
        f"rest_time_{mass}": rest_time,
        f"rest_position_{mass}": rest_position,
        f"max_abs_x_{mass}": max(abs(u) for u in x),
        f"stops_{mass}": stops,
    }


def _as_values(cells: dict[str, str]) -> dict[str, str | float | int]:
    return {k: ("" if c == "" else int(c) if k.startswith("stops_") else float(c)) for k, c in cells.items()}


@pytest.mark.parametrize("case", CASES)
def test_every_row_equals_the_single_run_of_the_file_with_its_values_bit_for_bit(case, tmp_path):
    template, axes, t_end, dt = CASES[case]
    base = tmp_path / "system.toml"
    first = {field: start for field, start, _, _ in axes.values()}
    base.write_text(template.format(**first))
    varies = [f"--vary={name}={a}:{b}:{n}" for name, (_, a, b, n) in axes.items()]
    out = tmp_path / "sweep.csv"
    grid = ["--system", str(base), *varies, "--t-end", t_end, "--dt", dt]
    assert main(["sweep", *grid, "--output", str(out)]) == 0
    got = _read(out)
    masses = load_system(str(base)).mass_names
    values = [np.linspace(a, b, n) for _, a, b, n in axes.values()]
    assert len(got["stops_" + masses[0]]) == math.prod(len(v) for v in values)
    resting = 0
    for j, row in enumerate(itertools.product(*values)):  # the first --vary slowest
        assert [float(got[name][j]) for name in axes] == [float(v) for v in row]
        path = tmp_path / f"row{j}.toml"
        path.write_text(template.format(**{field: float(v) for (field, *_), v in zip(axes.values(), row)}))
        assert (
            main(["simulate", "--system", str(path), "--t-end", t_end, "--dt", dt, "--output", str(tmp_path / "r.csv")])
            == 0
        )
        run = _read(tmp_path / "r.csv")
        for mass in masses:
            want = _summaries(run, mass)
            assert _as_values({k: got[k][j] for k in want}) == want, (j, mass)
            resting += want[f"rest_time_{mass}"] != ""
    assert 0 < resting < len(masses) * len(got["stops_" + masses[0]])  # some rows rest at the end, some move


@pytest.mark.parametrize(("case", "batched"), [("network", False), ("one-mass", True)])
def test_a_file_of_the_papers_form_runs_in_the_batched_kernel_and_another_row_by_row(case, batched, tmp_path):
    """So that the test above compares the batched kernel, not only the single run with itself."""
    template, axes, *_ = CASES[case]
    path = tmp_path / "s.toml"
    path.write_text(template.format(**{field: start for field, start, _, _ in axes.values()}))
    ready = by_file.prepare(
        load_system(str(path)), {name: [a] for name, (_, a, _, _) in axes.items()}, t_end=1.0, dt=1e-3
    )
    assert (ready.batch is not None) is batched


def test_rows_in_worker_processes_equal_the_rows_in_this_one(tmp_path, monkeypatch):
    path = tmp_path / "s.toml"
    path.write_text(TWO_BLOCKS.format(x1=0.3, static=2.0))
    net = load_system(str(path))
    vary = {"fric.static": np.linspace(1.5, 4.0, 4)}
    here = by_file.sweep_system(net, vary, t_end=1.0, dt=2e-3)
    monkeypatch.setattr(by_file, "PROCESS_SECONDS", 0.0)
    monkeypatch.setattr(by_file, "workers", lambda rows: 2)
    ready = by_file.prepare(net, vary, t_end=1.0, dt=2e-3)
    assert ready.workers == 2
    there = by_file.run(ready)
    assert list(there) == list(here)
    for name in here:
        assert np.array_equal(there[name], here[name], equal_nan=True), name


@pytest.mark.parametrize("case", CASES)
def test_the_chunks_concatenate_to_the_whole_grid(case, tmp_path):
    template, axes, t_end, dt = CASES[case]
    base = tmp_path / "system.toml"
    base.write_text(template.format(**{field: start for field, start, _, _ in axes.values()}))
    grid = ["--system", str(base), *(f"--vary={n}={a}:{b}:{k}" for n, (_, a, b, k) in axes.items()), "--t-end", t_end]
    assert main(["sweep", *grid, "--dt", dt, "--output", str(tmp_path / "all.csv")]) == 0
    lines = []
    for i in range(4):  # 6 or 12 rows in 4 chunks: 1 to 3 rows each
        out = tmp_path / f"chunk{i}.csv"
        assert main(["sweep", *grid, "--dt", dt, "--chunk", f"{i}/4", "--output", str(out)]) == 0
        text = out.read_text().splitlines()
        lines += text[1:] if lines else text
    assert lines == (tmp_path / "all.csv").read_text().splitlines()


BAD = {
    "unknown entry": (["--vary", "nope.static=1:2:2"], "--vary: unknown parameter 'nope.static'; this system's are"),
    "unknown key": (["--vary", "fric.friction=1:2:2"], "--vary: unknown parameter 'fric.friction'"),
    "non-numeric key": (["--vary", "fric.kind=1:2:2"], "--vary: 'fric.kind' is not a numeric parameter"),
    "no dot": (["--vary", "static=1:2:2"], "--vary: 'static' is not a parameter's name"),
    "out of the key's domain": (["--vary", "m1.mass=-1:1:3"], "--vary: m1.mass = -1: mass must be > 0"),
    "a domain of two keys": (["--vary", "fric.static=1:2:3"], "--vary: fric.static = 1: kinetic = 1.5 N must not"),
    "a grid value past the domain": (["--vary", "floor1.threshold=1:-1:3"], "--vary: floor1.threshold = -1: "),
    "bad count": (["--vary", "fric.static=2:3:two"], "--vary: COUNT must be an integer"),
    "twice": (["--vary", "fric.static=2:3:2", "--vary", "fric.static=2:3:2"], "--vary: fric.static is varied more"),
    "no vary": ([], "--vary: a --system sweep needs at least one --vary"),
    "single-mass option": (["--vary", "fric.static=2:3:2", "--x0", "1"], "--x0 describes the single mass"),
    "periods": (["--vary", "fric.static=2:3:2", "--periods", "3"], "--periods sets the single mass's forced"),
    "chunk past the end": (["--vary", "fric.static=2:3:2", "--chunk", "3/3"], "--chunk: I must be 0 to N-1"),
    "chunk text": (["--vary", "fric.static=2:3:2", "--chunk", "1of3"], "--chunk expects I/N"),
    "method": (["--vary", "fric.static=2:3:2", "--method", "theta"], "--method: 'theta' cannot run a sweep"),
    "too long": (
        ["--vary", "fric.static=2:3:1000000"],
        "--vary: 1000000 rows of backward-euler (10000 steps each) would",
    ),
}


@pytest.mark.parametrize("case", BAD)
def test_a_bad_input_is_one_line_and_status_2_before_any_work(case, tmp_path, capsys, monkeypatch):
    args, message = BAD[case]
    path = tmp_path / "s.toml"
    path.write_text(TWO_BLOCKS.format(x1=0.3, static=2.0))
    ran = []
    monkeypatch.setattr(by_file, "_row", lambda *a: ran.append(a))
    status = main(["sweep", "--system", str(path), *args, "--t-end", "1", "--output", str(tmp_path / "o.csv")])
    err = capsys.readouterr().err
    assert status == 2 and len(err.strip().splitlines()) == 1, err
    assert err.startswith("lumped sweep: error: " + message), err
    assert not ran and not (tmp_path / "o.csv").exists()


def test_a_row_whose_step_is_refused_names_its_values(tmp_path, capsys):
    """A falling friction law's step bound (backward Euler's uniqueness) depends on the row's mass: checked for
    every row before the first runs."""
    path = tmp_path / "s.toml"
    path.write_text(
        TWO_BLOCKS.format(x1=0.3, static=2.0).replace("kinetic = 1.5", "kinetic = 1.5\nstribeck_velocity = 1e-2")
    )
    out = tmp_path / "o.csv"
    status = main(
        [
            "sweep",
            "--system",
            str(path),
            "--vary",
            "m2.mass=2:0.01:2",
            "--t-end",
            "1",
            "--dt",
            "1e-3",
            "--output",
            str(out),
        ]
    )
    err = capsys.readouterr().err
    assert status == 2 and len(err.strip().splitlines()) == 1 and "(row 1: m2.mass = 0.01)" in err, err
    assert not out.exists()


# ---- the pipeline: the sweep in chunks (rules/sweeps.smk, profiles/cluster) ------------------------------


def _merge_script():
    import importlib.util

    from conftest import ROOT

    spec = importlib.util.spec_from_file_location("merge_chunks", ROOT / "scripts" / "merge_chunks.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_merge_refuses_chunks_of_different_sweeps_in_one_line(tmp_path, capsys):
    (tmp_path / "a.csv").write_text("x,stops_m\n1,2\n")
    (tmp_path / "b.csv").write_text("y,stops_m\n1,2\n")
    assert _merge_script().main([str(tmp_path / "o.csv"), str(tmp_path / "a.csv"), str(tmp_path / "b.csv")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("merge_chunks: ") and "columns differ" in err
    assert not (tmp_path / "o.csv").exists()


@pytest.mark.slow  # a snakemake run of four chunks (some 20 s): the slow suite (.ci/run runs it)
def test_the_pipelines_chunked_sweep_is_the_whole_sweep_byte_for_byte(tmp_path):
    """rules/sweeps.smk built by Snakemake (one job a chunk, the merge) against one ``sweep --system`` run of the
    whole grid, as scripts/slurm_local.sh compares the build through profiles/cluster with a local one."""
    import re
    import subprocess

    from conftest import copy_tracked_files
    from test_pipeline import SNAKEMAKE

    root = copy_tracked_files(tmp_path / "repo")
    target = "results/sweeps/two_blocks.csv"
    done = subprocess.run(
        [SNAKEMAKE, "--nolock", "--cores", "2", target], cwd=root, capture_output=True, text=True, timeout=600
    )
    assert done.returncode == 0, done.stdout + done.stderr
    rules = (root / "rules" / "sweeps.smk").read_text()
    vary = re.findall(r'"([\w.]+=[^"]+)"', rules.split('"vary": [')[1].split("]")[0])
    t_end, dt = (re.search(rf'"{k}": ([\d.e-]+)', rules).group(1) for k in ("t_end", "dt"))
    args = [f"--vary={v}" for v in vary] + ["--t-end", t_end, "--dt", dt]
    whole = tmp_path / "whole.csv"
    assert main(["sweep", "--system", str(root / "examples" / "two_blocks.toml"), *args, "--output", str(whole)]) == 0
    assert (root / target).read_bytes() == whole.read_bytes()
    assert len(whole.read_text().splitlines()) == 1 + 8 * 4


def test_the_single_mass_sweeps_chunks_concatenate_to_the_whole_grid(tmp_path):
    """``--chunk I/N`` of the sweep without ``--system``: the API's ``chunk`` on the command line."""
    grid = ["--vary", "x0=-1:1:7", "--vary", "threshold=0.5:1:2", "--t-end", "1", "--dt", "1e-3"]
    assert main(["sweep", *grid, "--output", str(tmp_path / "all.csv")]) == 0
    lines = []
    for i in range(3):
        out = tmp_path / f"chunk{i}.csv"
        assert main(["sweep", *grid, "--chunk", f"{i}/3", "--output", str(out)]) == 0
        text = out.read_text().splitlines()
        lines += text[1:] if lines else text
    assert lines == (tmp_path / "all.csv").read_text().splitlines() and len(lines) == 1 + 14
