"""With ``--system``, a run's error names the file's entry and key, never a single-mass option (issue 19).

The runs of a one-mass system file go through the single-mass API, whose
messages begin with its parameter (``x0: ...``); the command line used to
print ``--x0``, an option that ``--system`` refuses.
"""

from __future__ import annotations

import pytest

from lumped.cli import main

SYSTEM = """\
[[mass]]
name = "m"
mass = 1.0
x0 = {x0}

[[element]]
name = "k"
kind = "spring"
between = ["ground", "m"]
stiffness = {k}

[[element]]
name = "d"
kind = "bingham"
between = ["ground", "m"]
threshold = 1.0
gamma = 1.0
"""


@pytest.mark.parametrize("method", ["backward-euler", "exact", "event-driven"])
def test_a_size_error_names_the_entry(tmp_path, capsys, method):
    path = tmp_path / "one.toml"
    path.write_text(SYSTEM.format(x0="1e299", k="100.0"))
    out = tmp_path / "run.csv"
    assert main(["simulate", "--system", str(path), "--method", method, "--output", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--x0" not in err, err
    assert err.startswith(f"lumped simulate: error: system file {str(path)!r}: [[mass]] 'm' x0: "), err
    assert not out.exists()


def test_a_stiffness_error_names_the_spring(tmp_path, capsys):
    path = tmp_path / "one.toml"
    path.write_text(SYSTEM.format(x0="1.0", k="1e-300"))
    argv = ["simulate", "--system", str(path), "--dt", "1e-10", "--t-end", "1e-9", "--output", str(tmp_path / "r.csv")]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"lumped simulate: error: system file {str(path)!r}: [[element]] 'k' stiffness: k*dt"), err
