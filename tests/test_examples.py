"""The system files of examples/: each runs as its comment says, and moves as an independent reference says.

* Every ``examples/*.toml`` says in its header comment what it is, how to run
  it (``Run it with`` and the command) and what to look at; the command runs,
  here, in a copy of ``examples/``, and writes the columns of its network
  (``simulate``), or of its response curve (``response``).
* Every example has a test of its motion (:data:`TESTS`):
  ``figure3.toml`` gives Algorithm 1's numbers bit for bit
  (``tests/test_readme.py``); ``maxwell_creep.toml`` follows the closed form
  of a spring in series with a slipping Bingham dashpot; in ``chain.toml``
  each block starts at the pull the quasi-steady creep of the blocks before it
  predicts; ``building.toml`` with its dampers locked is the linear shear
  frame (``scipy.signal.lsim``, exact for the piecewise-linear record), its
  braces never pass their slip loads, and the dampers lower the peak storey
  drift below the exact peaks of the bare and of the locked frame;
  ``figure2_beside_dashpot.toml`` moves as the Figure 3 system until its
  string goes taut, then rests at the string's length with the intervals of
  the hand calculation; ``friction_pads.toml`` moves as Algorithm 1 with one
  pad of the summed threshold, rests where the closed form says, and its pads'
  intervals are what each one's threshold leaves the other;
  ``s_curve.toml`` jumps between its branches at the steps backward Euler's
  closed form gives (``tests/test_curve_element.py``);
  ``two_mass_response.toml`` without friction has the linear two-degree-of-
  freedom response (``tests/test_response_network.py``); ``belt.toml`` meets
  the closed-form stick-slip cycle and ``stribeck_belt.toml`` the linearised
  motion about steady sliding (``tests/test_friction_cli.py``);
  ``block_chain.toml``'s identical blocks move as one block, that block on a
  belt seen from the plate, and its ``count`` tables are the tables written one
  by one (``tests/test_repeated_tables.py``); ``two_blocks.toml``'s sweep in the
  pipeline's chunks is the whole sweep's file (``tests/test_sweep_system.py``).
* ``scripts/ground_record.py`` writes the committed record, byte for byte.
"""

from __future__ import annotations

import contextlib
import dataclasses
import importlib.util
import math
import shlex
import shutil
from pathlib import Path

import numpy as np
import pytest
from conftest import EPS, ROOT
from scipy import signal

import lumped as L
from lumped.cli import main

FOLDER = ROOT / "examples"
#: Each example and the test of its motion.
TESTS = {
    "figure3": "test_readme.py::test_the_example_system_file_is_the_papers_figure_3",
    "maxwell_creep": "test_examples.py::test_the_creep_follows_the_closed_form",
    "chain": "test_examples.py::test_each_block_of_the_chain_starts_at_its_quasi_steady_pull",
    "building": "test_examples.py::test_the_building_with_locked_dampers_is_the_linear_shear_frame",
    "figure2_beside_dashpot": "test_examples.py::test_figure2_beside_the_dashpot_holds_at_the_strings_length",
    "friction_pads": "test_examples.py::test_two_pads_move_as_one_and_share_the_held_force",
    "belt": "test_friction_cli.py::test_the_belt_example_meets_the_closed_form_cycle",
    "block_chain": "test_repeated_tables.py::test_the_block_chain_moves_as_one_block_on_a_belt",
    "stribeck_belt": "test_friction_cli.py::test_the_stribeck_example_is_the_linearised_motion",
    "s_curve": "test_curve_element.py::test_the_s_curve_example_prints_its_jumps",
    "two_mass_response": (
        "test_response_network.py::test_without_friction_the_example_is_the_linear_two_degree_of_freedom_response"
    ),
    "two_blocks": "test_sweep_system.py::test_the_pipelines_chunked_sweep_is_the_whole_sweep_byte_for_byte",
}
#: The examples whose elements close a loop that is rigid at some saved point: their non-unique forces.
INTERVALS = {"figure2_beside_dashpot": ["string", "dashpot"], "friction_pads": ["pad1", "pad2"]}
FILES = sorted(FOLDER.glob("*.toml"))
#: The columns of ``python -m lumped response`` after ``omega`` and the amplitudes.
RESPONSE_COLUMNS = ["stops_per_period", "stable", "max_multiplier", "kind"]


def header(path: Path) -> list[str]:
    """The comment lines at the top of a system file, without their ``#``."""
    lines = path.read_text(encoding="utf-8").splitlines()
    return [line.removeprefix("#").strip() for line in lines[: next(i for i, s in enumerate(lines) if s[:1] != "#")]]


def command(path: Path) -> list[str]:
    """The arguments of the ``python -m lumped`` command under ``Run it with``."""
    lines = header(path)
    line = lines[next(i for i, s in enumerate(lines) if s.endswith("Run it with")) + 1]
    assert line.startswith(
        ("python -m lumped simulate --system examples/", "python -m lumped response --system examples/")
    )
    return shlex.split(line)[3:]


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> dict[str, np.ndarray]:
    """Each example run by its own command in a copy of examples/: the CSV file's columns by name."""
    folder = tmp_path_factory.mktemp("examples")
    shutil.copytree(FOLDER, folder / "examples")
    out = {}
    with contextlib.chdir(folder):
        for path in FILES:
            args = command(path)
            assert main(args) == 0, args
            out[path.stem] = np.genfromtxt(args[args.index("--output") + 1], delimiter=",", names=True)
    return out


def test_every_example_is_tested() -> None:
    assert [p.stem for p in FILES] == sorted(TESTS)
    for test in TESTS.values():
        module, name = test.split("::")
        assert f"\ndef {name}(" in (ROOT / "tests" / module).read_text(encoding="utf-8"), test


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_an_example_says_what_it_is_and_runs_as_it_says(path: Path, runs: dict[str, np.ndarray]) -> None:
    """What it is, where it comes from, how to run it, what to look at; its command writes its network's columns."""
    text = " ".join(header(path))
    for words in ("Run it with", "What to look at", "book/guide/systems.md", TESTS[path.stem].split("::")[0]):
        assert words in text, f"{path.name}: the header comment does not say {words!r}"
    network = L.load_system(path)
    names = network.mass_names
    args = command(path)
    if args[0] == "response":  # the curve from START to STOP, an amplitude per mass
        start, stop = (float(w) for w in args[args.index("--omega") + 1].split(":"))
        run = runs[path.stem]
        assert list(run.dtype.names) == ["omega", *(f"amplitude_{n}" for n in names), *RESPONSE_COLUMNS]
        assert run["omega"][0] == start and run["omega"][-1] == stop
        return
    columns = ["t"] + [f"{q}_{n}" for q in ("x", "v") for n in names]
    columns += [f"{q}_{d.name}" for q in ("x", "v") for d in network.drivers]  # the driven points' motion
    for n in network.element_names:
        shared = n in INTERVALS.get(path.stem, [])
        columns += [f"F_{n}", f"force_min_{n}", f"force_max_{n}"] if shared else [f"F_{n}"]
    columns += [f"load_{n}" for n in names]
    value = {key: float(args[args.index(key) + 1]) for key in ("--t-end", "--dt")}
    every = int(args[args.index("--save-every") + 1]) if "--save-every" in args else 1
    run = runs[path.stem]
    assert list(run.dtype.names) == columns
    assert run.size == round(value["--t-end"] / value["--dt"]) // every + 1
    assert all(np.isfinite(run[c]).all() for c in columns)


# -- maxwell_creep.toml: a spring in series with a Bingham dashpot, pulled by a constant force ---------------


def creep_closed_form(t: np.ndarray, m: float, k: float, tau: float, gamma: float, P: float) -> np.ndarray:
    """Position (m), velocity (m/s) and force (N) of the creep example at the times ``t``, as rows.

    Until ``t1 = arccos(1 - tau/P)/omega`` the dashpot holds: a mass on a
    spring under a step load.  From ``t1`` it slips (the force stays above
    ``tau``, checked by the test): ``y = (v, F)`` obeys the linear
    ``y' = B y + b`` (``m v' = P - F``, ``F' = k v - k gamma (F - tau)``),
    whose solution is the steady creep ``y* = (gamma (P - tau), P)`` plus
    ``sum_i c_i u_i exp(lambda_i s)`` over the eigenpairs of ``B``,
    ``s = t - t1``; ``x`` is its integral.
    """
    omega = math.sqrt(k / m)
    t1 = math.acos(1.0 - tau / P) / omega
    holds = t <= t1
    x = P / k * (1.0 - np.cos(omega * t[holds]))
    out = np.empty((t.size, 3))
    out[holds] = np.column_stack([x, P / k * omega * np.sin(omega * t[holds]), k * x])
    steady = np.array([gamma * (P - tau), P])
    lam, u = np.linalg.eig(np.array([[0.0, -1.0 / m], [k, -k * gamma]]))
    c = np.linalg.solve(u, np.array([P / k * omega * math.sin(omega * t1), tau]) - steady)
    s = t[~holds, None] - t1
    y = steady + (np.exp(lam * s) * c) @ u.T
    x = tau / k + steady[0] * s[:, 0] + (np.expm1(lam * s) / lam * c) @ u[0]
    out[~holds] = np.column_stack([x, y]).real
    return out


def creep_values() -> dict[str, float]:
    net = L.load_system(FOLDER / "maxwell_creep.toml")
    (element,) = net.elements
    (load,) = net.loads
    return {
        "m": net.masses[0].mass,
        "k": element.stiffness,
        "tau": element.threshold,
        "gamma": element.gamma,
        "P": load.force(0.0),
    }


def test_the_creep_follows_the_closed_form(runs: dict[str, np.ndarray]) -> None:
    """The file's run against the closed form; its error is first order in dt; the creep tends to gamma (P - tau).

    The error at dt is ``C dt + O(dt^2)``: halving dt from 1e-3 halves it
    to within 1 % (measured to 2.5e-4), so the fitted order is 1 within 0.02.
    """
    values = creep_values()
    run = runs["maxwell_creep"]
    exact = creep_closed_form(run["t"], **values)
    slipping = run["t"] > math.acos(1.0 - values["tau"] / values["P"]) * math.sqrt(values["m"] / values["k"])
    assert (exact[slipping, 2] > values["tau"]).all()  # the closed form's second phase holds throughout
    errors = []
    network = L.load_system(FOLDER / "maxwell_creep.toml")
    for dt in (1e-3, 5e-4):
        tr = L.solve(L.Problem(network, 5.0), dt)
        errors.append(np.abs(tr.positions[:, 0] - creep_closed_form(tr.t, **values)[:, 0]).max())
    assert np.abs(run["x_m"] - exact[:, 0]).max() == errors[0]  # the file's command is the first of these runs
    assert abs(math.log2(errors[0] / errors[1]) - 1.0) < 0.02
    assert errors[0] < 1e-3 * abs(exact[-1, 0])
    # the steady creep: the slow root s = -2.09/s leaves exp(-2.09 * 5) = 3e-5 of the transient at t = 5 s
    steady = values["gamma"] * (values["P"] - values["tau"])
    assert abs(exact[-1, 1] - steady) < 1e-4 * steady and abs(run["v_m"][-1] - steady) < 1e-4 * steady
    assert abs(run["F_creep"][-1] - values["P"]) < 1e-4 * values["P"]


# -- chain.toml: five blocks on a Bingham floor, pulled by a ramp --------------------------------------------


def test_each_block_of_the_chain_starts_at_its_quasi_steady_pull(runs: dict[str, np.ndarray]) -> None:
    """Block j is exactly still until the pull reaches ``j tau + r j (j-1)/(2 k gamma)``, then creeps for good.

    While blocks 1 to j-1 creep and block j holds, the ramp ``F = r t`` has
    the particular solution of constant speeds ``(j - i) r/k`` (every spring's
    force rising at ``r``, no inertia force), which backward Euler reproduces
    exactly; block j starts when the spring before it reaches ``tau``.  The
    run departs from it by (a) the grid: a block's first nonzero velocity
    comes at the first step past the start, a pull at most ``r dt`` later, and
    (b) what is left of the start-up swings of the block before: a start
    changes the creeping speeds by ``r/k`` each, kinetic energy at most
    ``n m (r/k)^2 / 2``, a spring force of at most ``sqrt(n) r/omega``; every
    mode of the blocks on the floor decays at ``1/(2 m gamma)`` (the floor's
    viscosity is proportional to the mass; all modes are underdamped, the
    slowest, 3.47 rad/s, with damping ratio 0.72, hence the factor
    ``1/sqrt(1 - 0.72^2) < 1.5``) over the ``tau/r`` seconds between starts.
    """
    net = L.load_system(FOLDER / "chain.toml")
    m, n = net.masses[0].mass, len(net.masses)
    k = next(e for e in net.elements if e.kind == "spring").stiffness
    floor = [e for e in net.elements if e.kind == "bingham"]
    tau, gamma = floor[0].threshold, floor[0].gamma
    assert {(e.threshold, e.gamma) for e in floor} == {(tau, gamma)} and all(b.mass == m for b in net.masses)
    pull = net.loads[0].force
    r = float(np.diff(pull.values)[0] / np.diff(pull.t)[0])
    run = runs["chain"]
    dt = run["t"][1]
    j = np.arange(1, n + 1)
    predicted = j * tau + r * j * (j - 1) / (2 * k * gamma)
    swing = 1.5 * math.sqrt(n) * r / math.sqrt(k / m) * math.exp(-tau / r / (2 * m * gamma))
    assert swing < 2e-3 and r * dt == pytest.approx(1e-3)
    for block in range(n):
        x, v = run[f"x_m{block + 1}"], run[f"v_m{block + 1}"]
        start = int(np.argmax(v != 0))
        assert (x[:start] == 0).all() and (v[start:] > 0).all()  # still, then creeping for good
        departure = pull(run["t"][start]) - predicted[block]
        assert -swing <= departure <= r * dt + swing, (block + 1, departure)
    # the far block: the pull has passed the sum of the thresholds by the drag of the four before it, 0.25 N
    assert predicted[-1] - n * tau == pytest.approx(0.25)


# -- building.toml: a shear frame with friction-damped braces under the synthetic record -----------------------


def shear_frame(network: L.Network, braces: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mass, damping and stiffness matrices of the building, the braces ``"locked"`` (springs) or ``"removed"``."""
    names = network.mass_names
    M = np.diag([m.mass for m in network.masses])
    C, K = np.zeros_like(M), np.zeros_like(M)
    for el in network.elements:
        matrix, value = {
            "spring": (K, getattr(el, "stiffness", 0.0)),
            "dashpot": (C, getattr(el, "damping", 0.0)),
            "maxwell-bingham": (K, getattr(el, "stiffness", 0.0) if braces == "locked" else 0.0),
        }[el.kind]
        ends = [names.index(p) for p in el.between if p != "ground"]
        for a in ends:
            for b in ends:
                matrix[a, b] += value if a == b else -value
    return M, C, K


def linear_response(network: L.Network, braces: str, record: L.Table) -> np.ndarray:
    """Floor positions (m) relative to the ground at the record's times: the exact response of the linear frame.

    ``M x'' + C x' + K x = -M 1 a_g(t)``; ``scipy.signal.lsim`` with its
    default first-order hold is exact for an input linear between samples,
    as the table load is (and it is 0 at both ends of the record).
    """
    M, C, K = shear_frame(network, braces)
    n = len(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    B = np.concatenate([np.zeros(n), -np.ones(n)])[:, None]
    system = (A, B, np.eye(2 * n)[:n], np.zeros((n, 1)))
    return signal.lsim(system, record.values, record.t)[1]


def building() -> tuple[L.Network, L.Table]:
    return L.load_system(FOLDER / "building.toml"), L.read_table(FOLDER / "ground_record.csv", "a")


def locked(network: L.Network) -> L.Network:
    """The building with slip loads out of reach: each brace a spring."""
    elements = [dataclasses.replace(e, threshold=1e12) if e.kind == "maxwell-bingham" else e for e in network.elements]
    return L.Network(network.masses, elements, network.loads)


def drifts(x: np.ndarray) -> np.ndarray:
    """Storey drifts (m): each floor's position less the one below (the ground's is 0)."""
    return np.diff(x, axis=1, prepend=0.0)


def test_the_building_with_locked_dampers_is_the_linear_shear_frame() -> None:
    """Backward Euler on the locked building converges at order 1 to the linear frame's exact response.

    The error, measured against the peak, at the record's times: the order
    fitted over dt = 2e-4, 1e-4, 5e-5 is 1 within 0.1 (at these steps the
    highest mode, 65 rad/s, has omega dt below 0.013, so the error is in its
    first-order regime: the ratios measured from 1e-3 down are 1.8 to 1.95).
    """
    network, record = building()
    exact = linear_response(network, "locked", record)
    frame = locked(network)
    steps, errors = (2e-4, 1e-4, 5e-5), []
    for dt in steps:
        every = round(0.01 / dt)
        tr = L.solve(L.Problem(frame, 20.0), dt, save_every=every)
        assert tr.t.size == record.t.size and np.abs(tr.forces).max() < 1e-3 * 1e12  # the braces never slip
        errors.append(np.abs(tr.positions - exact).max() / np.abs(exact).max())
    order = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert abs(order - 1.0) < 0.1, (order, errors)
    assert errors[1] < 0.03


def test_the_braces_never_pass_their_slip_loads_and_every_damper_slips(runs: dict[str, np.ndarray]) -> None:
    """``|F_brace| <= slip load``: the bound a Coulomb slip device guarantees, reached when it slips.

    The slipping force is ``(dt k tau)/(dt k)``, two roundings of ``tau``.
    """
    network, _ = building()
    run = runs["building"]
    for brace in (e for e in network.elements if e.kind == "maxwell-bingham"):
        peak = np.abs(run[f"F_{brace.name}"]).max()
        assert brace.threshold * (1 - 2 * EPS) <= peak <= brace.threshold * (1 + 2 * EPS), brace.name


def test_the_dampers_lower_the_peak_drift(runs: dict[str, np.ndarray]) -> None:
    """The file's run (dt = 1e-4) against the exact peaks of the bare frame and of the locked one.

    Backward Euler at 1e-4 is within 3 % of the exact linear response (the
    test above); the damped building's peak drift is below half the locked
    frame's and a third of the bare frame's, margins far beyond that.
    """
    network, record = building()
    run = runs["building"]
    x = np.column_stack([run[f"x_{n}"] for n in network.mass_names])
    damped = np.abs(drifts(x)).max()
    bare = np.abs(drifts(linear_response(network, "removed", record))).max()
    stiff = np.abs(drifts(linear_response(network, "locked", record))).max()
    assert damped < 0.55 * stiff and damped < 0.33 * bare, (damped, stiff, bare)
    assert 0.010 < damped < 0.012 and 0.038 < bare < 0.042 and 0.020 < stiff < 0.023  # the file's comment


def test_the_ground_record_is_what_its_script_writes() -> None:
    """scripts/ground_record.py regenerates examples/ground_record.csv to its printed digits; its header says it is synthetic.

    The script sums NumPy sines, whose last bit may differ between CPUs (NumPy's
    vectorised ``sin`` and ``exp`` take another path on another instruction set),
    so a value within round-off of a rounding boundary of its 6 printed digits
    may print one unit apart: each value is held to one unit of its 6th
    significant digit, the times and the header exactly.
    """
    spec = importlib.util.spec_from_file_location("ground_record", ROOT / "scripts" / "ground_record.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    committed = (FOLDER / "ground_record.csv").read_text(encoding="utf-8")
    ours, theirs = script.text().splitlines(), committed.splitlines()
    assert [r for r in ours if r.startswith(("#", "t,"))] == [r for r in theirs if r.startswith(("#", "t,"))]
    rows = np.array([[float(v) for v in r.split(",")] for r in ours if r[0].isdigit() or r[0] == "-"])
    kept = np.array([[float(v) for v in r.split(",")] for r in theirs if r[0].isdigit() or r[0] == "-"])
    assert np.array_equal(rows[:, 0], kept[:, 0])
    a = np.abs(kept[:, 1])
    unit = np.where(a > 0, 10.0 ** (np.floor(np.log10(np.where(a > 0, a, 1.0))) - 5), 0.0)
    assert np.all(np.abs(rows[:, 1] - kept[:, 1]) <= unit * (1 + 1e-9))
    assert committed.startswith("# SYNTHETIC ground acceleration, not a measured earthquake")
    record = L.read_table(FOLDER / "ground_record.csv", "a")
    assert record.values[0] == record.values[-1] == 0.0 and np.abs(record.values).max() == script.PEAK
    assert record.t.size == 2001 and record.t[-1] == 20.0


# -- figure2_beside_dashpot.toml: a spring with a string beside a Bingham dashpot, under a constant pull -------


def test_figure2_beside_the_dashpot_holds_at_the_strings_length(runs: dict[str, np.ndarray]) -> None:
    """Before the string is taut, the Figure 3 system's velocities bit for bit; then at rest at ``x = L``
    exactly, each force in the interval of the hand calculation.

    Slack, the ``spring-string`` steps as the spring (the same arithmetic,
    ``k e + dt k w``), so the velocities equal Algorithm 1's for spring and
    dashpot; the positions are sums of the same increments in another order,
    within ``n eps max|x|`` after ``n`` steps.  At rest the step's held force
    is ``R = m v_prev/dt + P`` (the momentum balance with ``v = 0``): the
    string carries ``>= k L``, the dashpot ``|F_d| <= tau``, their sum ``R``,
    so ``F_s`` is in ``[max(kL, R - tau), R + tau]`` and ``F_d`` in
    ``[-tau, min(tau, R - kL)]``; the bound is the rounding of ``R`` (two
    operations, against the step's own) relative to ``R``.
    """
    net = L.load_system(FOLDER / "figure2_beside_dashpot.toml")
    string, dashpot = net.elements
    m, P, tau, kL = net.masses[0].mass, net.loads[0].force(0.0), dashpot.threshold, string.stiffness * string.length
    run = runs["figure2_beside_dashpot"]
    dt = run["t"][1]
    bare = L.Network(net.masses, [L.Spring("spring", string.between, string.stiffness), dashpot], net.loads)
    ref = L.simulate_network(bare, run["t"][-1], dt)
    assert ref.solver == "algorithm1"
    taut = int(np.argmax(run["x_m"] == string.length))
    assert taut > 0 and 0.131 < run["t"][taut] < 0.133 and (ref.positions[:, 0] > string.length).any()
    assert np.array_equal(run["v_m"][:taut], ref.velocities[:taut, 0])
    assert np.abs(run["x_m"][:taut] - ref.positions[:taut, 0]).max() <= taut * EPS * string.length
    assert (run["x_m"][taut:] == string.length).all() and (run["v_m"][taut + 1 :] == 0).all()
    rest = np.arange(taut + 1, run.size)
    held = m * run["v_m"][rest - 1] / dt + P
    bound = 4 * EPS * held
    expected = {
        "string": (np.maximum(kL, held - tau), held + tau),
        "dashpot": (np.full(held.size, -tau), np.minimum(tau, held - kL)),
    }
    for name, (low, high) in expected.items():
        assert np.all(np.abs(run[f"force_min_{name}"][rest] - low) <= bound), name
        assert np.all(np.abs(run[f"force_max_{name}"][rest] - high) <= bound), name
    assert np.all(np.abs(run["F_string"][rest] + run["F_dashpot"][rest] - held) <= bound)
    # at rest for good: R = P, the string in [14, 16] N, the least-norm split 14 N and 1 N (the file's comment)
    assert held[-1] == P and [run[c][-1] for c in ("force_min_string", "force_max_string")] == [P - tau, P + tau]
    assert run["F_string"][-1] == P - tau and run["F_dashpot"][-1] == tau


# -- friction_pads.toml: a block on two Coulomb pads, pushed by a constant force ---------------------------------


def test_two_pads_move_as_one_and_share_the_held_force(runs: dict[str, np.ndarray]) -> None:
    """Algorithm 1 with one pad of ``tau1 + tau2`` gives the same velocities; the block stops after half a
    period near ``2 (P - tau)/k``; at rest each pad's interval is what the other's threshold leaves.

    Sliding, both pads carry their thresholds, whose sum is the one pad's
    threshold: the same step (measured bit for bit; the positions, sums of
    the same increments in another order, within ``n eps max|x|``).  The closed form (the
    issue's Coulomb oscillator, ``tau < P < 3 tau``) stops at ``t = pi/omega``
    at ``2 (P - tau)/k``; backward Euler shrinks the swing ``A = (P - tau)/k``
    by ``(1 + (omega dt)^2)^(-1/2)`` per step, over ``pi/(omega dt)`` steps,
    and stops at the first step past the turn, where ``x`` is within
    ``A (omega dt)^2`` of it.  At rest the pads hold ``R = P - k x`` (the
    spring's force is ``k x`` to one rounding).
    """
    net = L.load_system(FOLDER / "friction_pads.toml")
    spring, pad1, pad2 = net.elements
    m, k, P = net.masses[0].mass, spring.stiffness, net.loads[0].force(0.0)
    tau1, tau2 = pad1.threshold, pad2.threshold
    run = runs["friction_pads"]
    dt, t_end = run["t"][1], run["t"][-1]
    ref = L.backward_euler(L.Oscillator.bingham(m, k, tau1 + tau2, math.inf), t_end, dt, force=net.loads[0].force)
    assert np.array_equal(run["v_m"], ref.v)
    assert np.abs(run["x_m"] - ref.x).max() <= run.size * EPS * np.abs(ref.x).max()  # sums in another order
    omega, swing = math.sqrt(k / m), (P - (tau1 + tau2)) / k
    stop = int(np.argmax((run["v_m"] == 0) & (run["t"] > 0)))
    assert (run["v_m"][1:stop] > 0).all() and (run["v_m"][stop:] == 0).all()
    assert math.pi / omega <= run["t"][stop] < math.pi / omega + dt
    damped = swing * (1 - (1 + (omega * dt) ** 2) ** (-math.pi / (omega * dt) / 2))
    assert abs(2 * swing - run["x_m"][stop] - damped) <= swing * (omega * dt) ** 2
    slides = slice(1, stop)
    assert (run["F_pad1"][slides] == tau1).all() and (run["F_pad2"][slides] == tau2).all()
    rest = slice(stop + 1, None)  # the step after the stop: no inertia left
    held = P - run["F_spring"][rest]
    bound = 4 * EPS * (abs(held) + tau1 + tau2)
    for name, mine, other in (("pad1", tau1, tau2), ("pad2", tau2, tau1)):
        assert np.all(np.abs(run[f"force_min_{name}"][rest] - np.maximum(-mine, held - other)) <= bound), name
        assert np.all(np.abs(run[f"force_max_{name}"][rest] - np.minimum(mine, held + other)) <= bound), name
        assert np.all(np.abs(run[f"F_{name}"][rest] - held / 2) <= bound), name  # least norm: R/2 each
    # the file's comment: 0.13 mm short of 0.08 m, R = 2.013 N
    assert round(2 * swing - run["x_m"][-1], 5) == 0.00013 and round(held[-1], 3) == 2.013
