"""An ``--output`` that names a file the command reads is refused before any work (issue 31).

``simulate --force-table T.csv --output T.csv`` replaced the load table with
its own output, status 0; so did an output equal to a table that the system
file names, the system file itself, or fit's record.  Every command that
writes an output compares it with its inputs as the file system sees them
(links and other spellings of a path included) and refuses in one line,
status 2, leaving the input as it was.
"""

from __future__ import annotations

import os

import pytest
from cli_run import run_lumped

SYSTEM = """[[mass]]
name = "m1"
mass = 1.0
x0 = 0.5
[[element]]
name = "spring"
kind = "spring"
between = ["ground", "m1"]
stiffness = 100.0
[[element]]
name = "dashpot"
kind = "bingham"
between = ["ground", "m1"]
threshold = 1.0
gamma = 1.0
[[force]]
on = "m1"
kind = "table"
file = "load.csv"
[ground]
acceleration = { kind = "table", file = "ground/a.csv" }
"""

RECORD = "t,x_m1\n0,0.5\n0.1,0.4\n0.2,0.2\n"


@pytest.fixture
def folder(tmp_path):
    (tmp_path / "ground").mkdir()
    (tmp_path / "load.csv").write_text("t,F\n0,1\n1,1\n")
    (tmp_path / "ground" / "a.csv").write_text("t,a\n0,0.5\n1,0.5\n")
    (tmp_path / "sys.toml").write_text(SYSTEM)
    (tmp_path / "sys.csv").write_text(SYSTEM)  # a system file whose name an output may take
    (tmp_path / "rec.csv").write_text(RECORD)
    (tmp_path / "rec.json").write_text(RECORD)
    os.symlink("load.csv", tmp_path / "link.csv")
    return tmp_path


SIMULATE = ["simulate", "--t-end", "0.2", "--dt", "0.01"]
RESPONSE = ["response", "--force-on", "m1", "--amplitude", "1", "--omega", "5:6"]
FIT = ["fit", "--free", "dashpot.threshold"]

#: (arguments, the output, the input it names, the message after "--output '<output>' is ").
CASES = {
    "force-table": ([*SIMULATE, "--force-table", "load.csv"], "load.csv", "the --force-table file"),
    "force-table by a link": ([*SIMULATE, "--force-table", "load.csv"], "link.csv", "the --force-table file"),
    "force-table by another path": (
        [*SIMULATE, "--force-table", "load.csv"],
        "ground/../load.csv",
        "the --force-table",
    ),
    "system's force table": ([*SIMULATE, "--system", "sys.toml"], "load.csv", "the file of [[force]] 1 in --system"),
    "system's ground table": ([*SIMULATE, "--system", "sys.toml"], "ground/a.csv", "the file of [ground] acceleration"),
    "system file": ([*SIMULATE, "--system", "sys.csv"], "sys.csv", "the --system file"),
    "response, system's table": ([*RESPONSE, "--system", "sys.toml"], "load.csv", "the file of [[force]] 1"),
    "fit, record": ([*FIT, "--system", "sys.toml", "--data", "rec.json"], "rec.json", "the --data file"),
}


@pytest.mark.parametrize(("args", "output", "what"), CASES.values(), ids=list(CASES))
def test_an_output_that_is_an_input_is_refused_in_one_line_before_any_work(folder, args, output, what):
    before = {p: p.read_bytes() for p in folder.rglob("*") if p.is_file()}
    run = run_lumped(*args, "--output", output, cwd=folder)
    command = args[0]
    assert run.returncode == 2 and run.stderr.count("\n") == 1, run.stderr
    assert run.stderr.startswith(f"lumped {command}: error: --output {output!r} is {what}"), run.stderr
    assert {p: p.read_bytes() for p in folder.rglob("*") if p.is_file()} == before  # nothing written, nothing left


def test_an_output_beside_the_inputs_is_written(folder):
    run = run_lumped(*SIMULATE, "--force-table", "load.csv", "--output", "out.csv", cwd=folder)
    assert run.returncode == 0, run.stderr
    assert (folder / "out.csv").exists() and (folder / "load.csv").read_text() == "t,F\n0,1\n1,1\n"
