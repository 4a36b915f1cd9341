"""System files (TOML) and ``lumped simulate --system``: the contract of issue 9."""

from __future__ import annotations

import numpy as np
import pytest

from lumped.cli import main
from lumped.model.files import parse_system

GOOD = """\
[[mass]]
name = "m1"
mass = 1.0
x0 = 0.5
v0 = 0.0

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
amplitude = 10.0
omega = 15.707963267948966
phase = 0.0
until = 1.0
"""

CHAIN = """\
[[mass]]
name = "a"
mass = 1.0
x0 = 0.1
[[mass]]
name = "b"
mass = 2.0
[[element]]
name = "s"
kind = "spring-string"
between = ["ground", "a"]
stiffness = 50.0
length = 0.2
[[element]]
name = "mx"
kind = "maxwell-bingham"
between = ["a", "b"]
stiffness = 80.0
threshold = 0.5
gamma = inf
[[element]]
name = "lock"
kind = "locking-bingham"
between = ["ground", "b"]
threshold = 0.2
gamma = 1.0
v_lock = 0.5
"""


def run(tmp_path, text: str, output: str = "out.npz", *extra: str) -> tuple[int, str]:
    path = tmp_path / "sys.toml"
    path.write_text(text)
    status = main(
        [
            "simulate",
            "--system",
            str(path),
            "--t-end",
            "0.2",
            "--dt",
            "1e-3",
            "--output",
            str(tmp_path / output),
            *extra,
        ]
    )
    return status, str(path)


def test_npz_has_the_arrays_of_the_contract(tmp_path, capsys) -> None:
    status, _ = run(tmp_path, CHAIN, "out.npz", "--save-every", "10")
    assert status == 0
    data = np.load(tmp_path / "out.npz")
    assert data["t"].shape == (21,) and data["x"].shape == (21, 2) and data["v"].shape == (21, 2)
    assert data["force"].shape == (21, 3)
    assert list(data["mass_names"]) == ["a", "b"] and list(data["element_names"]) == ["s", "mx", "lock"]
    err = capsys.readouterr().err
    assert "a " in err and "b " in err


def test_csv_columns(tmp_path) -> None:
    assert run(tmp_path, CHAIN, "out.csv")[0] == 0
    header = (tmp_path / "out.csv").read_text().splitlines()[0]
    assert header == "t,x_a,x_b,v_a,v_b,F_s,F_mx,F_lock,load_a,load_b"


def test_paper_file_is_algorithm1(tmp_path) -> None:
    import lumped as L

    assert run(tmp_path, GOOD, "out.npz")[0] == 0
    data = np.load(tmp_path / "out.npz")
    tr = L.backward_euler(
        L.Oscillator.bingham(), 0.2, 1e-3, x0=0.5, force=L.SwitchedSine(10.0, 15.707963267948966, 0.0, 1.0)
    )
    assert np.array_equal(data["x"][:, 0], tr.x) and np.array_equal(data["force"][:, 1], tr.F_d)


def test_defaults_of_the_format() -> None:
    net = parse_system(GOOD.replace("x0 = 0.5\nv0 = 0.0\n", "").replace("phase = 0.0\nuntil = 1.0\n", ""))
    assert net.masses[0].x0 == 0.0 and net.loads[0].force.until == float("inf")


BAD = {
    "not-toml": ("[[mass]\nname=1", "not valid TOML"),
    "unknown-kind": (GOOD.replace('kind = "bingham"', 'kind = "bingam"'), "unknown kind 'bingam'"),
    "missing-parameter": (GOOD.replace("stiffness = 100.0\n", ""), "missing parameter 'stiffness'"),
    "unknown-parameter": (
        GOOD.replace("stiffness = 100.0", "stiffness = 100.0\nstiff = 1"),
        "unknown parameter 'stiff'",
    ),
    "negative-mass": (GOOD.replace("mass = 1.0", "mass = -1.0"), "mass must be > 0"),
    "zero-stiffness": (GOOD.replace("stiffness = 100.0", "stiffness = 0.0"), "stiffness must be > 0"),
    "negative-threshold": (GOOD.replace("threshold = 1.0", "threshold = -1.0"), "threshold must be >= 0"),
    "zero-length": (CHAIN.replace("length = 0.2", "length = 0.0"), "length must be > 0"),
    "self-loop": (
        GOOD.replace('between = ["ground", "m1"]\nstiffness', 'between = ["m1", "m1"]\nstiffness'),
        "joins 'm1' to itself",
    ),
    "no-such-mass": (
        GOOD.replace('between = ["ground", "m1"]\nthreshold', 'between = ["ground", "m2"]\nthreshold'),
        "'m2', which is neither a mass",
    ),
    "duplicate-name": (GOOD.replace('name = "dashpot"', 'name = "spring"'), "element 'spring': the name is used twice"),
    "string-beyond-length": (CHAIN.replace("x0 = 0.1", "x0 = 0.3"), "beyond the string's length"),
    "string-value": (GOOD.replace("stiffness = 100.0", 'stiffness = "100"'), "stiffness must be a real number"),
    "force-on-nobody": (GOOD.replace('on = "m1"', 'on = "m9"'), "no mass of that name"),
}


@pytest.mark.parametrize("case", list(BAD))
def test_bad_file_one_line_status_2_no_output(tmp_path, capsys, case: str) -> None:
    text, expected = BAD[case]
    status, path = run(tmp_path, text)
    err = capsys.readouterr().err
    assert status == 2
    assert err.count("\n") == 1 and expected in err and path in err
    assert not any(tmp_path.glob("out.npz*"))


@pytest.mark.parametrize("option", ["--x0=0.1", "--mass=2", "--force-amplitude=1"])
def test_single_mass_options_refused_with_system(tmp_path, capsys, option: str) -> None:
    status, _ = run(tmp_path, GOOD, "out.npz", option)
    assert status == 2 and option.split("=")[0] in capsys.readouterr().err
    assert not any(tmp_path.glob("out.npz*"))


@pytest.mark.parametrize("stride", ["2000000001", "100000000000000000000000"])
def test_save_every_beyond_the_most_steps_is_refused_with_system(tmp_path, capsys, stride: str) -> None:
    status, _ = run(tmp_path, CHAIN, "out.npz", "--save-every", stride)
    err = capsys.readouterr().err
    assert status == 2 and err.count("\n") == 1 and "--save-every must be an integer from 1 to 2000000000" in err
    assert not any(tmp_path.glob("out.npz*"))
