"""The one registry of methods (lumped.drivers.methods, issue 20 item 2): every reader reads it, and a method
asked to run what it cannot says so in one line naming the method and the reason."""

from __future__ import annotations

import argparse

import pytest

import lumped as L
from lumped import simulate_network
from lumped.cli import build_parser, main, messages
from lumped.drivers import methods, simulation
from lumped.drivers import network as network_integrate
from lumped.drivers import sweep as sweep_module
from lumped.drivers.network import SOLVERS
from lumped.model.files import load_system

ONE_MASS = """\
[[mass]]
name = "m1"
mass = 1.0
x0 = 0.5
[[element]]
name = "spring"
kind = "spring"
between = ["ground", "m1"]
stiffness = 100.0
[[element]]
name = "d"
{dashpot}
"""
BINGHAM = 'kind = "bingham"\nbetween = ["ground", "m1"]\nthreshold = 1.0\ngamma = 1.0'
HERSCHEL_BULKLEY = (
    'kind = "herschel-bulkley"\nbetween = ["ground", "m1"]\nthreshold = 1.0\nconsistency = 1.0\nexponent = 2.0'
)
TWO_MASSES = ONE_MASS.format(dashpot=BINGHAM) + '[[mass]]\nname = "m2"\nmass = 1.0\n'
TWO_MASSES_HB = ONE_MASS.format(dashpot=HERSCHEL_BULKLEY) + '[[mass]]\nname = "m2"\nmass = 1.0\n'


def _actions(command: str) -> dict[str, argparse.Action]:
    """The options of a subcommand of the command line's parser, by flag."""
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return {flag: a for a in sub.choices[command]._actions for flag in a.option_strings}


def _choices(command: str) -> tuple[str, ...]:
    """The names ``--method`` of a subcommand lists."""
    return tuple(_actions(command)["--method"].metavar.strip("{}").split(","))


# --------------------------------------------------------------------------- one home


def test_every_public_name_is_the_registry_or_a_view_of_it():
    assert L.METHODS is simulation.METHODS is methods.METHODS
    assert all(name == m.name for name, m in methods.METHODS.items())
    assert sweep_module.SWEEP_METHODS == tuple(n for n, m in methods.METHODS.items() if m.batch)
    network_methods = [m for m in methods.METHODS.values() if m.runs_networks]
    assert [m.name for m in network_methods] == ["backward-euler"]
    assert SOLVERS is network_integrate.SOLVERS == network_methods[0].network_solvers


def test_the_command_line_reads_the_registry():
    assert _choices("simulate") == tuple(methods.METHODS)
    assert _choices("sweep") == methods.SWEEP_METHODS
    flags = {o.flag for m in methods.METHODS.values() for o in m.options}
    assert flags == {"--rtol", "--theta"}
    assert flags <= set(_actions("simulate"))
    sweep_flags = {o.flag for n in methods.SWEEP_METHODS for o in methods.METHODS[n].options}
    assert sweep_flags == {"--rtol"} and flags & set(_actions("sweep")) == sweep_flags  # not --theta
    assert {messages.API_TO_OPTION[o.name] for m in methods.METHODS.values() for o in m.options} == flags


def test_help_lists_every_registered_method(capsys):
    assert main(["simulate", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    for name, m in methods.METHODS.items():  # tests/test_cli_reference.py checks the whole table
        assert f"{name} {m.description}. Runs {m.runs}." in text
    assert "needs one mass" not in text  # exact and event-locating run networks too
    assert main(["sweep", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "--method {" + ",".join(methods.SWEEP_METHODS) + "}" in text


def test_the_options_are_the_registrys_and_checked_by_it():
    with pytest.raises(ValueError, match=r"^rtol: method 'exact' takes no option 'rtol' \(it takes none\)$"):
        L.simulate(L.Oscillator.bingham(), 0.1, 1e-3, method="exact", rtol=1e-8)
    with pytest.raises(ValueError, match=r"^rtol must lie in"):
        simulation.method_options("event-driven", {"rtol": 1.0})
    assert simulation.method_options("event-driven", {"rtol": 1e-8}) == {"rtol": 1e-8}


# --------------------------------------------------------------------------- refusals, one line each


def test_exact_refuses_a_law_without_bingham_form():
    osc = L.Oscillator(1.0, L.LinearSpring(100.0), L.HerschelBulkleyDashpot(1.0, 1.0, 2.0))
    message = "^method: 'exact' cannot run a HerschelBulkleyDashpot: its closed forms need a Bingham or Coulomb law$"
    with pytest.raises(ValueError, match=message):
        L.simulate(osc, 0.1, 1e-3, x0=0.5, method="exact")
    assert methods.METHODS["event-driven"].refusal(osc) is None  # any monotone law


def test_a_single_mass_method_refuses_a_network_of_several_masses(tmp_path):
    path = tmp_path / "two.toml"
    path.write_text(TWO_MASSES)
    message = "^method 'event-driven' needs a one-mass system; the network has 2 masses$"
    with pytest.raises(ValueError, match=message):
        L.solve(L.Problem(load_system(str(path)), 0.1), 1e-3, method="event-driven")
    assert L.solve(L.Problem(load_system(str(path)), 0.1), 1e-3, method="exact").positions.shape == (101, 2)


def test_exact_refuses_a_network_element_without_a_closed_form(tmp_path):
    path = tmp_path / "two.toml"
    path.write_text(TWO_MASSES_HB)
    message = "^method 'exact' cannot run element 'd' of kind 'herschel-bulkley': its closed forms per phase need "
    with pytest.raises(ValueError, match=message):
        L.solve(L.Problem(load_system(str(path)), 0.1), 1e-3, method="exact")


@pytest.mark.parametrize(
    ("system", "message"),
    [
        (
            ONE_MASS.format(dashpot=HERSCHEL_BULKLEY),
            "--method: 'exact' cannot run a HerschelBulkleyDashpot: its closed forms need a Bingham or Coulomb law",
        ),
        (TWO_MASSES_HB, "method 'exact' cannot run element 'd' of kind 'herschel-bulkley': "),
    ],
)
def test_the_command_line_refuses_exact_in_one_line(tmp_path, capsys, system, message):
    path, out = tmp_path / "s.toml", tmp_path / "run.csv"
    path.write_text(system)
    assert main(["simulate", "--system", str(path), "--method", "exact", "--t-end", "0.1", "--output", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("lumped simulate: error: " + message), err
    assert str(path) in err
    assert not out.exists() and not list(tmp_path.glob("*.part"))


def test_exact_runs_a_one_mass_bingham_file(tmp_path, capsys):
    path, out = tmp_path / "s.toml", tmp_path / "run.csv"
    path.write_text(ONE_MASS.format(dashpot=BINGHAM))
    assert main(["simulate", "--system", str(path), "--method", "exact", "--t-end", "0.1", "--output", str(out)]) == 0


@pytest.mark.parametrize("method", [n for n, m in methods.METHODS.items() if not m.batch])
def test_a_sweep_refuses_a_method_it_does_not_run(tmp_path, capsys, method):
    message = f"method: '{method}' cannot run a sweep: a scheme of the accuracy study"
    with pytest.raises(ValueError, match="^" + message):
        sweep_module.sweep({"x0": [0.1, 0.2]}, t_end=0.1, dt=1e-3, method=method)
    out = tmp_path / "s.csv"
    assert main(["sweep", "--vary", "x0=0:1:2", "--method", method, "--output", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("lumped sweep: error: --" + message), err
    assert "(a sweep runs backward-euler, exact, event-driven)" in err
    assert not list(tmp_path.iterdir())


def test_an_unknown_name_is_refused_with_the_registrys_names():
    with pytest.raises(ValueError, match="^method must be one of backward-euler, exact, event-driven, event-"):
        L.simulate(L.Oscillator.bingham(), 0.1, 1e-3, method="rk4")
    with pytest.raises(ValueError, match="^method: a sweep runs backward-euler, exact, event-driven; got 'rk4'$"):
        sweep_module.sweep({"x0": [0.1]}, t_end=0.1, dt=1e-3, method="rk4")
    with pytest.raises(ValueError, match="^solver must be one of auto, active-set, compiled, python; got 'rk4'$"):
        simulate_network(load_system_text(ONE_MASS.format(dashpot=BINGHAM)), 0.1, 1e-3, solver="rk4")


def load_system_text(text: str):
    """A network from the text of a system file."""
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "s.toml"
        path.write_text(text)
        return load_system(str(path))


# --------------------------------------------------------------------------- backward Euler's loops, named once


@pytest.mark.parametrize("name", ["fortran", None, 1])
def test_both_kernel_arguments_are_checked_in_one_place(name):
    from lumped.kernels import batched
    from lumped.numerics import validate

    message = f"^kernel must be 'auto', 'compiled' or 'python', got {name!r}$"
    with pytest.raises(ValueError, match=message):
        L.backward_euler(L.Oscillator.bingham(), 0.1, 1e-3, kernel=name)
    with pytest.raises(ValueError, match=message):
        batched._kernel_name(name)
    assert validate.KERNELS == ("auto", "compiled", "python")
    assert validate.kernel("python", "compiled", "the C kernel") == "python"
    with pytest.raises(ValueError, match="^kernel: 'compiled' requested but the C kernel was not built$"):
        validate.kernel("compiled", "python", "the C kernel")
