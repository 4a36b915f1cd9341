"""Loads on the command line (issue 21): the system file's kinds and ``simulate``'s load options.

Every refusal is one line with exit status 2 and no output file, naming the
system file, the entry and the key, or the option; the runs agree with the
API (and the closed form of :mod:`test_loads`).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from cli_run import run_lumped
from test_loads import coulomb

import lumped as L
from lumped.cli import main

TABLES = {
    "good.csv": "# a constant 4 N, written as a table\nt,F\n0,4\n1,4\n",
    "repeat.csv": "t,F\n0,1\n1,1\n1,2\n",
    "nan.csv": "t,F\n0,1\n1,nan\n",
    "huge.csv": "t,F\n0,1\n1,1e400\n",
    "three.csv": "t,F\n0,1,2\n1,1\n",
    "word.csv": "t,F\n0,one\n1,1\n",
    "underscore.csv": "t,F\n0,0.0_4\n1,1\n",  # float() reads 0.04; the guide's plain decimals do not
    "blank.csv": "t,F\n0,1\n\n1,1\n",
    "header.csv": "time,F\n0,1\n1,1\n",
    "one-row.csv": "t,F\n0,1\n",
    "empty.csv": "",
    "accel-as-force.csv": "t,F\n0,1\n1,1\n",
    "late.csv": "t,F\n0.6,1\n1,1\n",
    "zeros.csv": "t,F\n0,0\n1,0\n",
    "before.csv": "t,F\n-1,2\n0,0\n",
}


def force(body: str) -> str:
    return '[[force]]\non = "m"\n' + body


def ground(acceleration: str) -> str:
    return f"[ground]\nacceleration = {acceleration}\n"


#: (appended to the Coulomb system, expected after "system file 'PATH': ").
BAD_FILES = {
    "unknown-kind": (force('kind = "ramp"\nvalue = 1.0\n'), "[[force]] 1 ('m'): unknown kind 'ramp'; expected one of"),
    "constant-without-value": (force('kind = "constant"\n'), "[[force]] 1 ('m'): missing parameter 'value'"),
    "constant-with-amplitude": (
        force('kind = "constant"\nvalue = 1.0\namplitude = 2.0\n'),
        "[[force]] 1 ('m'): unknown parameter 'amplitude'; expected on, kind, value, from, until",
    ),
    "until-before-from": (
        force('kind = "constant"\nvalue = 1.0\nfrom = 1.0\nuntil = 0.5\n'),
        "[[force]] 1 ('m'): until must be later than from (1 s), got 0.5",
    ),
    "negative-from": (force('kind = "constant"\nvalue = 1.0\nfrom = -1.0\n'), "[[force]] 1 ('m'): from must be >= 0"),
    "text-value": (force('kind = "constant"\nvalue = "1"\n'), "[[force]] 1 ('m'): value must be a real number"),
    "sine-without-omega": (force("amplitude = 1.0\n"), "[[force]] 1 ('m'): missing parameter 'omega'"),
    "file-not-text": (force('kind = "table"\nfile = 3\n'), "[[force]] 1 ('m'): file must be a string"),
    "file-missing": (
        force('kind = "table"\nfile = "nope.csv"\n'),
        "[[force]] 1 ('m'): file '{dir}/nope.csv': cannot read",
    ),
    "not-increasing": (
        force('kind = "table"\nfile = "repeat.csv"\n'),
        "[[force]] 1 ('m'): file '{dir}/repeat.csv': line 4: t must increase strictly, got 1.0 after 1.0",
    ),
    "nan": (force('kind = "table"\nfile = "nan.csv"\n'), "file '{dir}/nan.csv': line 3: F must be finite, got nan"),
    "overflow": (force('kind = "table"\nfile = "huge.csv"\n'), "'{dir}/huge.csv': line 3: F must be finite, got inf"),
    "three-columns": (force('kind = "table"\nfile = "three.csv"\n'), "line 2: expected two numbers 't,F', got '0,1,2'"),
    "a-word": (force('kind = "table"\nfile = "word.csv"\n'), "line 2: expected two numbers 't,F', got '0,one'"),
    "underscore": (
        force('kind = "table"\nfile = "underscore.csv"\n'),
        "line 2: expected two numbers 't,F', got '0,0.0_4'",
    ),
    "blank-line": (force('kind = "table"\nfile = "blank.csv"\n'), "line 3: expected two numbers 't,F', got ''"),
    "header": (force('kind = "table"\nfile = "header.csv"\n'), "line 1: expected the header 't,F', got 'time,F'"),
    "one-row": (force('kind = "table"\nfile = "one-row.csv"\n'), "needs at least two rows of 't,F', got 1"),
    "empty": (force('kind = "table"\nfile = "empty.csv"\n'), "line 1: expected the header 't,F', got nothing"),
    "ground-key": ("[ground]\nvelocity = 1.0\n", "[ground]: unknown parameter 'velocity'; expected acceleration"),
    "ground-number": (ground("9.81"), "[ground] acceleration: must be an inline table"),
    "ground-kind": (ground('{ kind = "quake" }'), "[ground] acceleration: unknown kind 'quake'"),
    "ground-header": (
        ground('{ kind = "table", file = "accel-as-force.csv" }'),
        "[ground] acceleration: file '{dir}/accel-as-force.csv': line 1: expected the header 't,a', got 't,F'",
    ),
    "ground-overflow": (
        ground('{ kind = "constant", value = 1e308 }'),
        "[ground] acceleration: the load -m a_g on mass 'm' (m = 2) is not finite",
    ),
    "kind-not-text": (ground('{ kind = ["sine"] }'), "[ground] acceleration: unknown kind ['sine']"),
    "ground-array": ("[[ground]]\nacceleration = 1.0\n", "[ground]: must be written as a [ground] table"),
    "unknown-table": (
        "[grund]\n",
        "unknown table 'grund'; expected [[mass]], [[element]], [[force]], [[driver]] and [ground]",
    ),
}


@pytest.fixture
def folder(tmp_path):
    for name, text in TABLES.items():
        (tmp_path / name).write_text(text)
    return tmp_path


def simulate(args: list[str], out) -> int:  # noqa: ANN001
    return main(["simulate", *args, "--t-end", "0.5", "--dt", "1e-3", "--output", str(out)])


@pytest.mark.parametrize("case", list(BAD_FILES))
def test_a_bad_load_in_a_system_file_is_one_line_naming_the_entry(folder, capsys, case):
    text, expected = BAD_FILES[case]
    path = folder / "sys.toml"
    path.write_text(coulomb(text))
    assert simulate(["--system", str(path)], folder / "out.csv") == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    assert err.startswith(f"lumped simulate: error: system file {str(path)!r}: "), err
    assert expected.format(dir=folder) in err, err
    assert not any(folder.glob("out.csv*"))


@pytest.mark.parametrize("method", ["exact", "event-driven"])
def test_a_method_that_needs_a_sine_refuses_a_table_naming_the_entry(folder, capsys, method):
    path = folder / "sys.toml"
    path.write_text(coulomb(force('kind = "table"\nfile = "good.csv"\n')))
    assert simulate(["--system", str(path), "--method", method], folder / "out.csv") == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and not any(folder.glob("out.csv*"))
    assert err.startswith(f"lumped simulate: error: system file {str(path)!r}: the loads on 'm': method {method!r}")
    assert "not a table; backward-euler, event-locating, theta and moreau-jean run any load" in err


def test_a_table_file_is_read_relative_to_the_system_file(folder, monkeypatch):
    (folder / "sub").mkdir()
    (folder / "sub" / "sys.toml").write_text(coulomb(force('kind = "table"\nfile = "../good.csv"\n')))
    monkeypatch.chdir("/")
    net = L.load_system(folder / "sub" / "sys.toml")
    assert net.loads[0].force(0.5) == 4.0


# -- simulate, one mass -----------------------------------------------------

COULOMB = ["--gamma", "inf", "--mass", "2", "--stiffness", "200", "--threshold", "2"]


def test_force_value_runs_the_closed_form(tmp_path, capsys):
    out = tmp_path / "c.npz"
    assert simulate([*COULOMB, "--force-value", "5", "--method", "exact"], out) == 0
    assert "at rest from t = 0.3141592654 s at x = 0.03 m" in capsys.readouterr().err  # 2 (5 - 2) / 200
    with np.load(out) as z:
        osc = L.Oscillator.bingham(2.0, 200.0, 2.0, math.inf)
        ref = L.simulate(osc, 0.5, 1e-3, force=L.Constant(5.0), method="exact")
        assert np.array_equal(z["x"], ref.x) and np.array_equal(z["F"], ref.F) and np.all(z["F"] == 5.0)


def test_force_table_runs_as_the_constant_it_equals(folder):
    table, constant = folder / "t.npz", folder / "c.npz"
    assert simulate([*COULOMB, "--force-table", str(folder / "good.csv")], table) == 0
    assert simulate([*COULOMB, "--force-value", "4"], constant) == 0
    with np.load(table) as a, np.load(constant) as b:
        assert all(np.array_equal(a[name], b[name]) for name in L.COLUMNS)


def test_force_from_and_until_switch_the_constant(tmp_path):
    out = tmp_path / "c.npz"
    assert simulate(["--force-value", "-3", "--force-from", "0.1", "--force-until", "0.3"], out) == 0
    ref = L.simulate(L.Oscillator.bingham(), 0.5, 1e-3, force=L.Constant(-3.0, 0.1, 0.3))
    with np.load(out) as z:
        assert np.array_equal(z["x"], ref.x) and np.array_equal(z["F"], ref.F)
        assert z["F"][100] == -3.0 and z["F"][99] == 0.0 and z["F"][301] == 0.0


#: Options that would do nothing, or that go with another kind: (arguments, the message's start).
BAD_OPTIONS = [
    (["--force-amplitude", "10"], "--force-amplitude 10 applies no force: with --force-omega 0 and --force-phase 0"),
    (["--force-omega", "3"], "--force-omega does nothing: --force-amplitude is 0"),
    (["--force-phase", "1"], "--force-phase does nothing: --force-amplitude is 0"),
    (["--force-until", "2"], "--force-until does nothing: --force-amplitude is 0"),
    (["--force-from", "1"], "--force-from goes with --force-value"),
    (["--force-value", "0", "--force-until", "1"], "--force-until does nothing: --force-value is 0"),
    (["--force-value", "0", "--force-from", "1"], "--force-from does nothing: --force-value is 0"),
    (["--force-value", "2", "--force-amplitude", "3"], "--force-amplitude cannot go with --force-value"),
    (["--force-value", "2", "--force-omega", "3"], "--force-omega cannot go with --force-value"),
    (
        ["--force-value", "2", "--force-from", "1", "--force-until", "1"],
        "--force-until must be later than --force-from",
    ),
    (["--force-value", "2", "--force-from", "-1"], "--force-from must be >= 0"),
    (["--force-value", "inf"], "--force-value must be finite"),
    (["--force-value", "two"], "--force-value must be a number, got 'two'"),
    (["--force-table", "good.csv", "--force-value", "2"], "--force-value cannot go with --force-table"),
    (["--force-table", "good.csv", "--force-until", "2"], "--force-until cannot go with --force-table"),
    (["--force-table", "good.csv", "--force-amplitude", "2"], "--force-amplitude cannot go with --force-table"),
    (["--force-table", "repeat.csv"], "--force-table: file 'repeat.csv': line 4: t must increase strictly"),
    (["--force-table", "nope.csv"], "--force-table: file 'nope.csv': cannot read it"),
    (["--force-table", "good.csv", "--method", "exact"], "force: method 'exact' runs a sine or a constant load"),
    (["--force-value", "2", "--force-from", "0.2", "--method", "exact"], "force: method 'exact' runs a sine"),
    # loads that cannot act between t = 0 and --t-end (0.5 here), which ran at rest with status 0
    (
        ["--force-amplitude", "3", "--force-omega", "5", "--force-until", "0"],
        "--force-until 0 switches the sine off at t = 0, so it never acts",
    ),
    (["--force-amplitude", "3", "--force-phase", "1", "--force-until", "0"], "--force-until 0 switches the sine off"),
    (["--force-value", "3", "--force-from", "5"], "--force-from 5 is not before --t-end 0.5: the constant load"),
    (["--force-value", "3", "--force-from", "0.5"], "--force-from 0.5 is not before --t-end 0.5"),
    (["--force-value", "0"], "--force-value 0 applies no force"),
    (["--force-table", "late.csv"], "--force-table: file 'late.csv' is 0 from t = 0 to --t-end 0.5 s (its times run"),
    (["--force-table", "zeros.csv"], "--force-table: file 'zeros.csv' is 0 from t = 0 to --t-end 0.5 s"),
    (["--force-table", "before.csv"], "--force-table: file 'before.csv' is 0 from t = 0 to --t-end 0.5 s"),
]


@pytest.mark.parametrize(("args", "message"), BAD_OPTIONS, ids=[" ".join(a) for a, _ in BAD_OPTIONS])
def test_a_load_option_that_does_nothing_or_clashes_is_refused_in_one_line(folder, capsys, monkeypatch, args, message):
    monkeypatch.chdir(folder)
    assert simulate(args, folder / "out.csv") == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"lumped simulate: error: {message}"), err
    assert not any(folder.glob("out.csv*"))


@pytest.mark.parametrize("option", ["--force-value=1", "--force-from=1", "--force-table=good.csv"])
def test_load_options_are_refused_with_system(folder, capsys, option):
    path = folder / "sys.toml"
    path.write_text(coulomb(""))
    assert simulate(["--system", str(path), option], folder / "out.csv") == 2
    assert option.split("=")[0] + " describes the single mass" in capsys.readouterr().err


def test_the_paper_sine_and_a_zero_force_still_run(tmp_path):
    # Unchanged: a sine with its frequency, and no forcing option at all.
    assert simulate(["--force-amplitude", "10", "--force-omega", "15.7", "--force-until", "1"], tmp_path / "a.csv") == 0
    assert simulate(["--x0", "0.5", "--force-amplitude", "0"], tmp_path / "b.csv") == 0


def test_loads_that_act_for_part_of_the_run_still_run(folder):
    # The edges of the refusals above: a constant on just before --t-end (0.5), a table that begins inside the run.
    (folder / "inside.csv").write_text("t,F\n0.4,0\n0.45,3\n")
    assert simulate(["--force-value", "3", "--force-from", "0.499"], folder / "a.csv") == 0
    assert simulate(["--force-table", str(folder / "inside.csv")], folder / "b.csv") == 0


def test_a_sweep_whose_every_sine_is_off_before_it_acts_is_refused_in_one_line(tmp_path):
    out = tmp_path / "sweep.csv"
    args = ["--force-amplitude", "3", "--force-omega", "5", "--force-until", "0", "--vary", "x0=0.1:0.2:2"]
    run = run_lumped("sweep", *args, "--output", out)
    assert run.returncode == 2 and run.stderr.count("\n") == 1, run.stderr
    assert run.stderr.startswith("lumped sweep: error: --force-until 0 switches the sine off at t = 0")
    assert not out.exists()


SWEEP_ZERO = [
    (["--force-amplitude", "3", "--vary", "x0=0.1:0.2:2"], "--force-amplitude 3 applies no force"),
    (["--vary", "force_amplitude=1:3:2"], "--vary force_amplitude applies no force"),
]


@pytest.mark.parametrize(("args", "message"), SWEEP_ZERO, ids=[" ".join(a) for a, _ in SWEEP_ZERO])
def test_a_sweep_whose_every_sine_is_zero_is_refused_in_one_line(tmp_path, args, message):
    out = tmp_path / "sweep.csv"
    run = run_lumped("sweep", *args, "--output", out)
    assert run.returncode == 2 and run.stderr.count("\n") == 1, run.stderr
    assert run.stderr.startswith(f"lumped sweep: error: {message}: with --force-omega 0 and --force-phase 0")
    assert not out.exists()


def test_a_sweep_of_a_constant_load_still_runs(tmp_path):
    args = ["--force-amplitude", "3", "--force-phase", "1.5707963267948966", "--vary", "x0=0.1:0.2:2"]
    out = tmp_path / "sweep.csv"
    run = run_lumped("sweep", *args, "--output", out)
    assert run.returncode == 0 and len(out.read_text().splitlines()) == 3
