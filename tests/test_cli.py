"""Command line: ``python -m lumped simulate``."""

from __future__ import annotations

import importlib.metadata
import os
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest
from conftest import F17B

import lumped as L
from lumped.cli import build_parser, main

HEADER = "t,x,v,F_s,F_d,F"


def _files(folder) -> list[str]:
    return sorted(os.listdir(folder))


def _status(argv) -> int:
    """``main``'s status: it must return it (argparse's usage errors included), not exit."""
    return main(argv)


def test_csv_matches_the_api_and_keeps_first_and_last_rows(tmp_path, capsys):
    out = tmp_path / "run.csv"
    argv = ["simulate", "--x0", "0.5", "--t-end", "0.1003", "--dt", "1e-4", "--save-every", "7", "--output", str(out)]
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert "wrote" in err and len(err.strip().splitlines()) == 1
    with open(out) as fh:
        assert fh.readline().strip() == HEADER
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    ref = L.backward_euler(L.Oscillator.bingham(), 0.1003, 1e-4, x0=0.5, save_every=7)
    # %.17g round-trips doubles exactly
    assert np.array_equal(data, ref.as_array())
    assert data[0, 0] == 0.0 and data[-1, 0] == pytest.approx(0.1003, abs=1e-15)
    assert _files(tmp_path) == ["run.csv"]  # no temporary file left


def test_npz_has_the_named_arrays(tmp_path):
    out = tmp_path / "run.npz"
    argv = [
        "simulate",
        "--force-amplitude",
        "10",
        "--force-omega",
        str(5 * np.pi),
        "--force-until",
        "1",
        "--t-end",
        "2",
        "--dt",
        "1e-3",
        "--save-every",
        "3",
        "--output",
        str(out),
    ]
    assert main(argv) == 0
    with np.load(out) as z:
        assert sorted(z.files) == sorted(HEADER.split(","))
        ref = L.backward_euler(L.Oscillator.bingham(), 2.0, 1e-3, force=F17B, save_every=3)
        for name, column in ref.columns().items():
            assert np.array_equal(z[name], column)
        assert z["t"][0] == 0.0 and z["t"][-1] == 2.0


def test_exact_method(tmp_path):
    out = tmp_path / "exact.npz"
    assert (
        main(["simulate", "--method", "exact", "--x0", "0.5", "--t-end", "5", "--dt", "1e-3", "--output", str(out)])
        == 0
    )
    sol = L.solve_exact(L.Oscillator.bingham(), 5.0, x0=0.5)
    with np.load(out) as z:
        assert np.array_equal(z["x"], sol.sample(1e-3).x)
        assert z["x"][-1] == sol.rest_position


def test_coulomb_from_the_command_line(tmp_path):
    out = tmp_path / "c.csv"
    assert (
        main(["simulate", "--gamma", "inf", "--x0", "0.5", "--t-end", "0.5", "--dt", "1e-3", "--output", str(out)]) == 0
    )
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    ref = L.backward_euler(L.Oscillator.bingham(gamma=np.inf), 0.5, 1e-3, x0=0.5)
    assert np.array_equal(data, ref.as_array())


BAD = [
    (["--mass", "0"], "--mass"),
    (["--mass", "-1"], "--mass"),
    (["--mass", "nan"], "--mass"),
    (["--mass", "inf"], "--mass"),
    (["--mass", "abc"], "--mass"),
    (["--stiffness", "0"], "--stiffness"),
    (["--stiffness", "-3"], "--stiffness"),
    (["--dt", "0"], "--dt"),
    (["--dt=-1e-4"], "--dt"),
    # argparse takes "-1e-4" and "-inf" for options: it refuses them itself,
    # still with one line, status 2 and the option named
    (["--dt", "-1e-4"], "--dt"),
    (["--dt", "inf"], "--dt"),
    (["--t-end", "0"], "--t-end"),
    (["--t-end", "-2"], "--t-end"),
    (["--t-end", "nan"], "--t-end"),
    (["--threshold", "-1"], "--threshold"),
    (["--threshold", "inf"], "--threshold"),
    (["--gamma", "0"], "--gamma"),
    (["--gamma", "-1"], "--gamma"),
    (["--gamma", "nan"], "--gamma"),
    (["--x0", "inf"], "--x0"),
    (["--v0", "nan"], "--v0"),
    (["--force-amplitude", "inf"], "--force-amplitude"),
    (["--force-omega", "-inf"], "--force-omega"),
    (["--force-omega=-inf"], "--force-omega"),
    (["--force-phase", "nan"], "--force-phase"),
    (["--force-until", "-1"], "--force-until"),
    (["--save-every", "0"], "--save-every"),
    (["--save-every", "1.5"], "--save-every"),
    (["--save-every", "2000000001"], "--save-every"),  # beyond the most steps of any run
    (["--save-every", "100000000000000000000000"], "--save-every"),
    (["--method", "rk4"], "--method"),
    (["--t-end", "1e9", "--dt", "1e-9"], "--t-end"),
    (["--t-end", "1e5", "--dt", "1e-4"], "--save-every"),
]


@pytest.mark.parametrize(("args", "option"), BAD, ids=[" ".join(a) for a, _ in BAD])
def test_bad_option_one_line_status_2_no_file(tmp_path, capsys, args, option):
    out = tmp_path / "out.csv"
    assert _status(["simulate", *args, "--output", str(out)]) == 2
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and option in lines[0]
    assert "Traceback" not in err
    assert _files(tmp_path) == []


@pytest.mark.parametrize("name", ["out.txt", "out", "out.csv.gz"])
def test_bad_output_suffix(tmp_path, capsys, name):
    assert main(["simulate", "--output", str(tmp_path / name)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--output" in err[0]
    assert _files(tmp_path) == []


def test_missing_output_directory(tmp_path, capsys):
    assert main(["simulate", "--output", str(tmp_path / "nope" / "out.csv")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--output" in err[0] and "does not exist" in err[0]
    assert _files(tmp_path) == []


def _run(*args, cwd):
    return subprocess.run([sys.executable, "-m", "lumped", *args], cwd=cwd, capture_output=True, text=True, timeout=60)


def test_subprocess_success(tmp_path):
    proc = _run("simulate", "--t-end", "0.2", "--dt", "1e-3", "--x0", "0.005", "--output", "o.csv", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "at rest from t = 0 s" in proc.stderr
    data = np.loadtxt(tmp_path / "o.csv", delimiter=",", skiprows=1)
    assert np.all(data[:, 1] == 0.005) and np.all(data[:, 2] == 0.0)


@pytest.mark.parametrize(
    ("args", "option"),
    [
        (["--gamma", "-1"], "--gamma"),
        (["--t-end", "1e9", "--dt", "1e-9"], "--t-end"),
        ([], "--output"),
    ],
)
def test_subprocess_errors(tmp_path, args, option):
    extra = [] if option == "--output" else ["--output", "o.csv"]
    proc = _run("simulate", *args, *extra, cwd=tmp_path)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and option in lines[0] and "Traceback" not in proc.stderr
    assert proc.stdout == ""
    assert _files(tmp_path) == []


# --- help and version ---------------------------------------------------------------

ROOT = Path(__file__).resolve().parent.parent


def _help(argv, capsys) -> str:
    assert main(argv) == 0
    return capsys.readouterr().out


def test_top_help_is_plain_text_with_an_example(capsys):
    text = _help(["--help"], capsys)
    assert not re.search(r"``|:(mod|func|class|data):`", text), text  # no reStructuredText
    assert "Bingham" in text and "simulate" in text
    example = re.search(r"^example.*:\n\s+(python -m lumped simulate .*)$", text, re.M)
    assert example, text
    # the example is a command line the parser accepts
    args = build_parser().parse_args(example.group(1).split()[3:])
    assert args.command == "simulate" and args.output == "run.csv"


def test_simulate_help_lists_the_registered_methods_and_requires_output(capsys):
    text = " ".join(_help(["simulate", "--help"], capsys).split())  # unwrap the lines
    assert "--method {" + ",".join(L.METHODS) + "}" in text
    for name, method in L.METHODS.items():  # the table under the options (tests/test_cli_reference.py: all of it)
        assert f"{name} {method.description}." in text
    usage = text[: text.index("options:")]
    assert "--output OUTPUT" in usage and "[--output" not in usage  # not optional
    assert "required arguments: --output OUTPUT" in text


def test_version_is_the_distribution_version(tmp_path):
    # pyproject.toml is the one source: the installed metadata, the package's
    # __version__ and the command line all say the same.
    declared = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    version = declared["project"]["version"]
    assert L.__version__ == importlib.metadata.version("lumped") == version
    proc = _run("--version", cwd=tmp_path)
    assert proc.returncode == 0 and proc.stdout == f"lumped {version}\n" and proc.stderr == ""
