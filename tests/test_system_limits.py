"""What a system file may hold (issue 19): names, sizes, nesting, argument types.

Every refusal is one line: a ``ValueError`` from the API, exit status 2 and
no output file from the command line.
"""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

import lumped as L
from lumped import Bingham, Mass, MaxwellBingham, Network, Spring, simulate_network
from lumped.cli import main
from lumped.laws.element import MAX_NAME_LENGTH
from lumped.model.files import MAX_FILE_BYTES, load_system, parse_system
from lumped.model.network import MAX_ELEMENTS, MAX_MASSES

ONE = """\
[[mass]]
name = "{mass}"
mass = 1.0
x0 = 0.5

[[element]]
name = "{element}"
kind = "spring"
between = ["ground", "{mass}"]
stiffness = 100.0

[[element]]
name = "d"
kind = "bingham"
between = ["ground", "{mass}"]
threshold = 1.0
gamma = 1.0
"""


def simulate(tmp_path, text: str, output: str = "out.csv") -> int:
    path = tmp_path / "sys.toml"
    path.write_text(text, encoding="utf-8")
    out = str(tmp_path / output)
    return main(["simulate", "--system", str(path), "--t-end", "0.01", "--dt", "1e-3", "--output", out])


def assert_refused(tmp_path, capsys, text: str, expected: str) -> str:
    status = simulate(tmp_path, text)
    err = capsys.readouterr().err
    assert status == 2, err
    assert err.count("\n") == 1 and err.isascii() and len(err) < 400 and expected in err
    assert not any(tmp_path.glob("out.csv*"))
    return err


BAD_NAMES = {
    "comma": "a,b",
    "newline": "a\\nb",  # TOML escape: a newline in the name
    "non-ascii": "d\u00e9",
    "empty": "",
    "too-long": "k" * (MAX_NAME_LENGTH + 1),
    "leading-digit": "1k",
    "quote": 'a\\"b',
}


@pytest.mark.parametrize("where", ["mass", "element"])
@pytest.mark.parametrize("case", list(BAD_NAMES))
def test_bad_name_refused_when_the_file_is_read(tmp_path, capsys, where: str, case: str) -> None:
    names = {"mass": "m1", "element": "k"} | {where: BAD_NAMES[case]}
    assert_refused(tmp_path, capsys, ONE.format(**names), "must be 1 to 64 ASCII letters")


@pytest.mark.parametrize("case", list(BAD_NAMES))
def test_bad_name_refused_by_the_api(case: str) -> None:
    name = BAD_NAMES[case].replace("\\n", "\n").replace('\\"', '"')
    with pytest.raises(ValueError, match="^name must be 1 to 64 ASCII"):
        Spring(name, ("ground", "m"), stiffness=1.0)
    with pytest.raises(ValueError, match="^name must be 1 to 64 ASCII"):
        Mass(name, 1.0)


#: Names that system files, notebooks, tests and benchmarks use, and the extremes of the rule.
GOOD_NAMES = ["m1", "k", "spring", "dashpot", "lock_cd", "mx_ac", "k01", "s_ab", "_x", "a.b-c", "K" * MAX_NAME_LENGTH]


@pytest.mark.parametrize("name", GOOD_NAMES)
def test_good_names_make_a_header_that_matches_the_columns(tmp_path, name: str) -> None:
    assert simulate(tmp_path, ONE.format(mass="m1", element=name)) == 0
    lines = (tmp_path / "out.csv").read_text(encoding="ascii").splitlines()
    header = lines[0].split(",")
    assert header == ["t", "x_m1", "v_m1", f"F_{name}", "F_d", "load_m1"]
    assert all(len(line.split(",")) == len(header) for line in lines[1:])


def chain(n: int) -> str:
    masses = "".join(f'[[mass]]\nname = "m{i}"\nmass = 1.0\n' for i in range(n))
    return masses + '[[element]]\nname = "k"\nkind = "spring"\nbetween = ["ground", "m0"]\nstiffness = 1.0\n'


def test_too_many_masses_refused_at_once(tmp_path, capsys) -> None:
    start = time.perf_counter()
    assert_refused(tmp_path, capsys, chain(MAX_MASSES + 1), f"masses: {MAX_MASSES + 1} given, more than")
    assert time.perf_counter() - start < 30  # the file is parsed, nothing is built or run


def test_too_many_elements_refused_by_the_api() -> None:
    elements = [Spring(f"k{i}", ("ground", "m"), stiffness=1.0) for i in range(MAX_ELEMENTS + 1)]
    with pytest.raises(ValueError, match=f"^elements: {MAX_ELEMENTS + 1} given"):
        Network([Mass("m", 1.0)], elements)


def test_file_too_large_refused_before_parsing(tmp_path, capsys) -> None:
    text = ONE.format(mass="m1", element="k") + "#" * MAX_FILE_BYTES + "\n"
    assert_refused(tmp_path, capsys, text, f"more than the {MAX_FILE_BYTES} read")
    with pytest.raises(ValueError, match="characters, more than"):
        parse_system(text)


def test_a_long_loop_runs_and_writes_the_intervals(tmp_path, capsys) -> None:
    """A ring of 12 Coulomb elements through 11 masses (once refused, issue 21): it runs, at
    rest, and the CSV holds each element's admissible interval beside its force."""
    n = 11
    text = "".join(f'[[mass]]\nname = "m{i}"\nmass = 1.0\n' for i in range(n))
    points = ["ground", *(f"m{i}" for i in range(n)), "ground"]
    for i, (a, b) in enumerate(zip(points, points[1:])):
        text += f'[[element]]\nname = "b{i}"\nkind = "bingham"\nbetween = ["{a}", "{b}"]\n'
        text += "threshold = 1.0\ngamma = inf\n"
    assert simulate(tmp_path, text) == 0, capsys.readouterr().err
    header = (tmp_path / "out.csv").read_text().splitlines()[0].split(",")
    loads = [f"load_m{i}" for i in range(n)]
    assert header[-3 - n :] == ["F_b11", "force_min_b11", "force_max_b11", *loads]
    data = np.loadtxt(tmp_path / "out.csv", delimiter=",", skiprows=1)
    assert np.all(data[:, header.index("force_min_b0")] == -1.0) and np.all(data[:, header.index("F_b0")] == 0.0)


@pytest.mark.parametrize("depth", [100, 100_000])
def test_deep_nesting_is_one_line(tmp_path, capsys, depth: int) -> None:
    text = ONE.format(mass="m1", element="k") + "[[force]]\non = " + "[" * depth + "]" * depth + "\n"
    expected = "nested too deeply" if depth > 1000 else "[[force]] 1"
    assert_refused(tmp_path, capsys, text, expected)


@pytest.mark.parametrize(
    ("call", "expected"),
    [
        (lambda: parse_system(123), "^text must be a str"),
        (lambda: parse_system(b"[[mass]]"), "^text must be a str"),
        (lambda: load_system(123), "^path must be a str or a path"),
        (lambda: L.solve_exact("osc", 1.0), "^oscillator must be an Oscillator, got str"),
        (lambda: L.solve_event_driven("osc", 1.0), "^oscillator must be an Oscillator, got str"),
    ],
    ids=["parse-int", "parse-bytes", "load-int", "exact-str", "event-driven-str"],
)
def test_wrong_argument_types_are_value_errors(call, expected: str) -> None:
    with pytest.raises(ValueError, match=expected):
        call()


def test_existing_example_still_loads() -> None:
    net = parse_system(ONE.format(mass="m1", element="k"))
    assert net.mass_names == ["m1"] and net.element_names == ["k", "d"]
    assert isinstance(net.elements[1], Bingham) and np.isfinite(net.masses[0].x0)


LONG = "y" * 100_000
LONG_WORDS = {
    "parameter": ONE.replace("stiffness = 100.0", f"stiffness = 100.0\n{LONG} = 1"),
    "table": ONE + f"[{LONG}]\n",
    "kind": ONE.replace('kind = "spring"', f'kind = "{LONG}"'),
}


@pytest.mark.parametrize("case", list(LONG_WORDS))
def test_a_long_unknown_word_is_cut_in_the_message(tmp_path, capsys, case: str) -> None:
    assert_refused(tmp_path, capsys, LONG_WORDS[case].format(mass="m1", element="k"), f"unknown {case} 'yyy")


MAXWELL = ONE.format(mass="m1", element="k") + (
    '[[element]]\nname = "mx"\nkind = "maxwell-bingham"\nbetween = ["ground", "m1"]\n'
    "stiffness = 80.0\nthreshold = 0.5\ngamma = {gamma}\nforce0 = {force0}\n"
)


@pytest.mark.parametrize("force0", ["0.6", "-0.6", "1e300"])
def test_coulomb_maxwell_force0_outside_its_band_is_refused(tmp_path, capsys, force0: str) -> None:
    """With ``gamma = inf`` the dashpot carries at most its threshold: the step would drop the force at once."""
    text = MAXWELL.format(gamma="inf", force0=force0)
    assert_refused(tmp_path, capsys, text, "[[element]] 3 ('mx'): force0 = ")
    with pytest.raises(ValueError, match="^force0 = .* outside the band"):
        MaxwellBingham("mx", ("ground", "m"), 80.0, 0.5, math.inf, force0=float(force0))


@pytest.mark.parametrize(("gamma", "force0"), [("inf", "0.5"), ("inf", "-0.5"), ("1.0", "5.0"), ("inf", "0.0")])
def test_maxwell_force0_that_is_a_state_is_accepted(tmp_path, gamma: str, force0: str) -> None:
    """On the band's edge, or beyond it with a finite gamma (the dashpot creeps: notebook 07)."""
    assert simulate(tmp_path, MAXWELL.format(gamma=gamma, force0=force0)) == 0


def test_the_summary_of_many_masses_is_one_short_line() -> None:
    """Twelve free masses on springs, released from 0.1 m: more than ten masses are counted, not listed one by
    one; the largest displacement is the release (a spring pulls each one back), the first mass's at t = 0."""
    masses = [Mass(f"m{i}", 1.0, x0=0.1) for i in range(12)]
    springs = [Spring(f"k{i}", ("ground", f"m{i}"), stiffness=1.0) for i in range(12)]
    text = simulate_network(Network(masses, springs), 0.01, 0.01).summary()
    assert text == "12 masses: all still moving at t = 0.01 s; largest |x| 0.1 m ('m0' at t = 0 s)"
