"""Repeated tables in system files (``count = N``, ``{i}``, arrays, gradings) and the summary of many masses.

* A ``count`` table is the N tables written one by one: the same network, the same run bit for bit
  (``examples/block_chain.toml`` against the text this module writes table by table).
* Its values: a number for all, an array of N, a grading exact at both ends; ``{i+c}`` in every string.
* Every mistake is one line naming the file, the table and the key (status 2 from the command line).
* ``b17.mass`` is a parameter; the pattern's name ``b{i}.mass`` is refused.
* ``examples/block_chain.toml``: identical blocks move as one, the block on a belt seen from the plate.
* The summary of thousands of masses: how many rest (the last since when), the largest displacement, where.
"""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from conftest import EPS, ROOT

import lumped as L
from lumped.cli import main
from lumped.model.files import table_files
from lumped.model.repeated import expand
from lumped.model.system_parameters import system_parameters, with_values

CHAIN = ROOT / "examples" / "block_chain.toml"
SOURCE = "system file 'chain.toml'"


def chain_text(blocks: int) -> str:
    """examples/block_chain.toml with ``blocks`` blocks (its counts replaced)."""
    text = CHAIN.read_text(encoding="utf-8")
    assert text.count("count = 50\n") == 3 and text.count("count = 49\n") == 1
    return text.replace("count = 50\n", f"count = {blocks}\n").replace("count = 49\n", f"count = {blocks - 1}\n")


def written_out(blocks: int) -> str:
    """The network of examples/block_chain.toml written table by table, as a file without ``count`` is."""
    parts = [f'[[mass]]\nname = "b{i}"\nmass = 1.0\n' for i in range(1, blocks + 1)]
    parts.append('[[driver]]\nname = "plate"\nvelocity = 0.3\n')
    parts += [
        f'[[element]]\nname = "leaf{i}"\nkind = "spring"\nbetween = ["plate", "b{i}"]\nstiffness = 1.0\n'
        for i in range(1, blocks + 1)
    ]
    parts += [
        f'[[element]]\nname = "coupling{i}"\nkind = "spring"\nbetween = ["b{i}", "b{i + 1}"]\nstiffness = 100.0\n'
        for i in range(1, blocks)
    ]
    parts += [
        f'[[element]]\nname = "floor{i}"\nkind = "friction"\nbetween = ["ground", "b{i}"]\n'
        "static = 1.0\nkinetic = 0.5\n"
        for i in range(1, blocks + 1)
    ]
    return "\n".join(parts)


def test_a_count_table_is_its_tables_written_one_by_one() -> None:
    """The example's 50 blocks against 50 tables of each kind: equal masses, elements and driven points."""
    a, b = L.load_system(CHAIN), L.parse_system(written_out(50))
    assert (a.masses, a.elements, a.drivers, a.loads) == (b.masses, b.elements, b.drivers, b.loads)
    assert len(a.masses) == 50 and len(a.elements) == 149


def test_a_count_table_runs_as_its_tables_written_one_by_one() -> None:
    """Equal networks give equal runs: every saved array bit for bit (ten blocks, through their first slip)."""
    a, b = (L.solve(L.Problem(L.parse_system(text), 4.0), 1e-2) for text in (chain_text(10), written_out(10)))
    for name in ("t", "positions", "velocities", "forces", "applied", "rigid"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert np.array_equal(a.rest_times, b.rest_times, equal_nan=True) and a.solver == b.solver


BLOCKS = """
[[mass]]
count = 4
name = "b{i}"
mass = [1.0, 2.0, 3.0, 4.0]
x0 = { from = 0.1, to = 0.3 }
v0 = 0.5

[[element]]
count = 4
name = "k{i-1}_{i}"
kind = "spring"
between = ["ground", "b{i}"]
stiffness = { from = 1, to = 4 }
"""


def test_numbers_arrays_and_gradings() -> None:
    """A number for every table, an array one by one, a grading linear in i with both ends exact."""
    net = L.parse_system(BLOCKS)
    assert [m.mass for m in net.masses] == [1.0, 2.0, 3.0, 4.0]
    assert {m.v0 for m in net.masses} == {0.5}
    # 0.1 + k (0.2/3): each value two roundings (the step, then the sum) from the exact one, the ends exact
    x0 = [m.x0 for m in net.masses]
    assert x0[0] == 0.1 and x0[-1] == 0.3
    assert np.allclose(x0, np.linspace(0.1, 0.3, 4), rtol=2 * EPS, atol=0)
    assert [el.stiffness for el in net.elements] == [1.0, 2.0, 3.0, 4.0]  # steps of 1: exact
    assert [el.name for el in net.elements] == ["k0_1", "k1_2", "k2_3", "k3_4"]


def test_strings_at_any_depth_take_the_index(tmp_path: Path) -> None:
    """``{i}`` in a driven point's table file: each driver reads its own file, as ``table_files`` lists them."""
    for i in (1, 2):
        (tmp_path / f"pull{i}.csv").write_text(f"t,v\n0,{i}\n10,{i}\n", encoding="utf-8")
    text = """
[[mass]]
count = 2
name = "b{i}"
mass = 1.0

[[driver]]
count = 2
name = "plate{i}"
velocity = { kind = "table", file = "pull{i}.csv" }

[[element]]
count = 2
name = "leaf{i}"
kind = "spring"
between = ["plate{i}", "b{i}"]
stiffness = 1.0
"""
    path = tmp_path / "sys.toml"
    path.write_text(text, encoding="utf-8")
    net = L.load_system(path)
    assert [float(d.velocity_at(1.0)) for d in net.drivers] == [1.0, 2.0]
    assert table_files(path) == [
        ("[[driver]] 1, i = 1 velocity", tmp_path / "pull1.csv"),
        ("[[driver]] 1, i = 2 velocity", tmp_path / "pull2.csv"),
    ]


REFUSED = {
    "count-not-integer": ("count = 4\nname", "count = 4.5\nname", "[[mass]] 1: count must be an integer >= 1"),
    "count-zero": ("count = 4\nname", "count = 0\nname", "[[mass]] 1: count must be an integer >= 1"),
    "count-bool": ("count = 4\nname", "count = true\nname", "[[mass]] 1: count must be an integer >= 1"),
    "count-beyond-the-limit": (
        "count = 4\nname",
        "count = 1000000000000\nname",
        "masses: 1000000000000 given, more than the",
    ),
    "array-length": ("mass = [1.0, 2.0, 3.0, 4.0]", "mass = [1.0, 2.0]", "[[mass]] 1: mass: an array of 2 numbers"),
    "unknown-placeholder": ('name = "b{i}"', 'name = "b{j}"', "[[mass]] 1: name: unknown placeholder '{j}'"),
    "unmatched-brace": ('"ground", "b{i}"', '"ground", "b{i"', "[[element]] 1: between: 'b{i' has a brace"),
    "negative-index": ('"ground", "b{i}"', '"ground", "b{i-2}"', "[[element]] 1: between: '{i-2}' in 'b{i-2}' is -1"),
    "collision-within": ('name = "k{i-1}_{i}"', 'name = "k"', "[[element]] 1, i = 2: name: 'k' gives 'k', the name"),
    "grading-infinite": ("to = 4 }", "to = inf }", "[[element]] 1: stiffness: a grading { from = a, to = b } takes"),
    "grading-value-refused": ("to = 4 }", "to = -4 }", "[[element]] 1, i = 2 ('k1_2'): stiffness must be > 0"),
    "names-no-mass": ('"ground", "b{i}"', '"b{i}", "b{i+1}"', "element 'k3_4': between names 'b5', which is neither"),
    # to - from overflows (its NaN at i = 1 was blamed on the value: "stiffness must be a real number, got nan")
    "grading-overflow": (
        "stiffness = { from = 1, to = 4 }",
        "stiffness = { from = -1.7e308, to = 1.7e308 }",
        "[[element]] 1: stiffness: a grading { from = -1.7e+308, to = 1.7e+308 } overflows: to - from is beyond",
    ),
    # an array of strings is the same for every table (point 3), no key of a dict ("unhashable type: 'list'")
    "decay-array": (
        'kind = "spring"\nbetween = ["ground", "b{i}"]\nstiffness = { from = 1, to = 4 }',
        (
            'kind = "friction"\nbetween = ["ground", "b{i}"]\nstatic = 1.0\nkinetic = 0.5\nstribeck_velocity = 0.1\n'
            'decay = ["gaussian", "exponential", "gaussian", "rational"]'
        ),
        "[[element]] 1, i = 1 ('k0_1'): decay must be one of 'exponential', 'gaussian', 'rational'; got ['gaussian',",
    ),
    "kind-array": ('kind = "spring"', 'kind = ["spring"]', "[[element]] 1, i = 1 ('k0_1'): unknown kind ['spring']; "),
}


def test_a_grading_at_the_largest_double_is_exact_and_one_beyond_is_refused() -> None:
    """The edge of the overflow: ``to - from = 1.7e308`` is a double, and the grading of 3 its exact
    ``-0.85e308, 0, 0.85e308`` (the step 0.85e308 is exact, and so is each sum); ``1.8e308`` is not."""
    [(_, one), (_, two), (_, three)] = expand([{"count": 3, "x0": {"from": -0.85e308, "to": 0.85e308}}], "mass")
    assert [one["x0"], two["x0"], three["x0"]] == [-0.85e308, 0.0, 0.85e308]
    with pytest.raises(
        ValueError, match=r"^\[\[mass\]\] 1: x0: a grading \{ from = -9e\+307, to = 9e\+307 \} overflows"
    ):
        expand([{"count": 3, "x0": {"from": -0.9e308, "to": 0.9e308}}], "mass")


@pytest.mark.parametrize("case", REFUSED, ids=list(REFUSED))
def test_a_mistake_is_one_line_naming_the_table_and_the_key(tmp_path: Path, capsys, case: str) -> None:
    """From the API a ValueError naming the file, the table and the key; from the command line status 2."""
    old, new, expected = REFUSED[case]
    assert old in BLOCKS
    text = BLOCKS.replace(old, new, 1)  # the first place: [[mass]]'s count
    with pytest.raises(ValueError, match="^system file 'chain.toml': ") as err:
        L.parse_system(text, SOURCE)
    assert expected in str(err.value) and "\n" not in str(err.value)
    path = tmp_path / "chain.toml"
    path.write_text(text, encoding="utf-8")
    out = tmp_path / "out.csv"
    assert main(["simulate", "--system", str(path), "--t-end", "0.1", "--dt", "0.01", "--output", str(out)]) == 2
    message = capsys.readouterr().err
    assert message.count("\n") == 1 and expected in message and not out.exists()


def test_a_name_given_by_a_count_table_and_another_table_is_refused_naming_both() -> None:
    text = BLOCKS + '\n[[mass]]\nname = "b3"\nmass = 1.0\n'
    with pytest.raises(ValueError, match=r"\[\[mass\]\] 2: name: 'b3' gives 'b3', the name of \[\[mass\]\] 1, i = 3"):
        L.parse_system(text, SOURCE)


def test_one_table_of_a_pattern_is_a_parameter_and_the_pattern_is_not() -> None:
    """``b3.mass`` is the third block's and varies it alone; ``b{i}.mass`` is refused, naming what to write."""
    net = L.parse_system(BLOCKS)
    (param,) = system_parameters(net, "b3.mass")
    assert (param.table, param.index, param.value) == ("mass", 2, 3.0)
    changed = with_values(net, [param], [7.0])
    assert [m.mass for m in changed.masses] == [1.0, 2.0, 7.0, 4.0]
    with pytest.raises(ValueError, match=r"^--vary: 'b\{i\}.mass' names a pattern of a count table.*such as b1.mass"):
        system_parameters(net, "b{i}.mass", "--vary")


def test_the_block_chain_moves_as_one_block_on_a_belt() -> None:
    """examples/block_chain.toml (ten blocks, cheaper; the claims hold for any count), as its header says.

    * One block: the coupling springs start relaxed and every block obeys the same equation, so the exact
      motion is one; the runs differ only by the linear solves' rounding, at most ``n eps max|x|`` a step (``n``
      the unknowns and elements summed over), and a step does not expand differences, so they sum over the
      steps.  No stick or slip decision sits on a corner (the first breakaway, at ``t = 1/0.3 s``, is off the
      grid), so none is taken differently.
    * Seen from the plate, ``y = v t - x`` is examples/belt.toml's block on a belt at ``v``: its extremes
      between the first two breakaways lie within ``v dt + A (omega dt)^2/8`` of the closed form damped by
      backward Euler's ``1/sqrt(1 + (omega dt)^2)`` a step (tests/test_friction_cli.py derives it).
    """
    net, dt = L.parse_system(chain_text(10)), 1e-2
    tr = L.solve(L.Problem(net, 12.0), dt)  # two breakaways: at 3.33 s and 10.9 s
    x, u = tr.positions, tr.velocities
    bound = tr.t.size * (len(net.masses) + len(net.elements)) * EPS * np.abs(x).max()
    assert np.abs(x - x[:, :1]).max() <= bound
    m, k, v = net.masses[0].mass, net.elements[0].stiffness, net.drivers[0].velocity
    static, kinetic = net.elements[-1].static, net.elements[-1].kinetic
    omega = math.sqrt(k / m)
    amplitude = math.hypot((static - kinetic) / k, v / omega)
    phi = -math.atan(k * v / (omega * (static - kinetic)))
    y, stuck = v * tr.t - x[:, 0], u[:, 0] == 0.0
    breakaway = tr.t[1:][stuck[:-1] & ~stuck[1:]]
    assert breakaway[0] == pytest.approx(static / (k * v), abs=dt) and breakaway.size >= 2
    cycle = (tr.t > breakaway[0]) & (tr.t < breakaway[1])
    for phase, extreme, sign in ((-phi, y[cycle].max(), 1.0), (math.pi - phi, y[cycle].min(), -1.0)):
        damped = kinetic / k + sign * amplitude * (1.0 + (omega * dt) ** 2) ** (-phase / omega / dt / 2)
        assert abs(extreme - damped) <= v * dt + amplitude * (omega * dt) ** 2 / 8
    assert round(amplitude, 4) == 0.5831  # the header's number


def coulomb_blocks(count: int) -> str:
    """``count`` free blocks on Coulomb contacts (gamma = inf), block i launched at v0 = i/4 - 1/16 m/s."""
    return f"""
[[mass]]
count = {count}
name = "b{{i}}"
mass = 1.0
v0 = {{ from = 0.1875, to = {count / 4 - 0.0625} }}

[[element]]
count = {count}
name = "floor{{i}}"
kind = "bingham"
between = ["ground", "b{{i}}"]
threshold = 1.0
gamma = inf
"""


def test_the_summary_of_thousands_of_masses_counts_them_and_names_the_largest_displacement() -> None:
    """2000 blocks sliding to rest on Coulomb contacts, dt = 1/8 s: backward Euler's closed form.

    A step takes ``tau dt/m = 1/8`` off a sliding block's speed; block i (v0 = i/4 - 1/16) slides 2i - 1 steps
    and sticks at step 2i (the step would reverse it by 1/16: a force of half the threshold holds it, no
    corner), so it rests from t = i/4 s; at t = 50 s blocks 1 to 200 rest, 'b200' the last, and block 2000,
    still sliding, has moved the most: ``dt sum_{j<=400} (v0 - j/8)``.  Every number here is a multiple of
    1/128 below 2^15, so binary arithmetic is exact and the test holds to the last digit.
    """
    net = L.parse_system(coulomb_blocks(2000))
    assert [m.v0 for m in net.masses[:3]] == [0.1875, 0.4375, 0.6875]  # the grading is i/4 - 1/16 exactly
    tr = L.solve(L.Problem(net, 50.0), 0.125)
    far = Fraction(1, 8) * sum(Fraction(2000, 4) - Fraction(1, 16) - Fraction(j, 8) for j in range(1, 401))
    assert tr.summary() == (
        "2000 masses: 200 at rest at the end, the last from t = 50 s ('b200'); 1800 still moving at t = 50 s "
        f"('b201', 'b202', 'b203', 'b204', 'b205' ... and 1795 more); largest |x| {float(far):.6g} m "
        "('b2000' at t = 50 s)"
    )
    assert tr.summary(shown=3000).count(" at rest from t = ") == 200  # shown masses: each one's own clause


def test_the_summary_of_a_few_masses_names_each() -> None:
    """Up to ten masses, each mass's clause as before (the README's commands print them): block i rests at
    (2i - 1)^2/128 m from t = i/4 s (the same closed form)."""
    tr = L.solve(L.Problem(L.parse_system(coulomb_blocks(3)), 1.0), 0.125)
    assert tr.summary() == (
        "b1 at rest from t = 0.25 s at x = 0.0078125 m; b2 at rest from t = 0.5 s at x = 0.0703125 m; "
        "b3 at rest from t = 0.75 s at x = 0.1953125 m"
    )
