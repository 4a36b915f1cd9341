"""``python -m lumped simulate --system FILE.toml``: a network read from a system file, run and written.

A one-mass file may be run by any method through the single-mass API; its
errors then name the file's entry and key, not an option (:func:`_system_message`).
"""

from __future__ import annotations

import argparse
import os

from lumped.cli.messages import LEADING_NAME
from lumped.cli.options import check_method, method_options
from lumped.cli.output import Output, check_output
from lumped.cli.sensitivity import refuse_ground_mass, sensitivity_columns
from lumped.drivers.methods import METHODS
from lumped.model.parameters import PARAMETERS
from lumped.numerics import validate


def run(args: argparse.Namespace, output: Output) -> str:
    """``--system``: read the file, reserve the output, run the network, write; returns the summary."""
    from lumped.drivers.simulation import solve
    from lumped.model.files import load_system
    from lumped.model.problem import Problem

    values = _grid(args)
    check_method(args.method)
    options = method_options(args)
    check_output(args.output)
    network = load_system(args.system)
    if not METHODS[args.method].runs_networks and not _piecewise(network, args.method, args.system):
        _one_mass(network, args)
    if args.sensitivities is not None:
        from lumped.drivers.sensitivity import plan  # the sensitivities' code, only when asked for

        params = plan(network, args.sensitivities, "--sensitivities")[0]  # before the output is created
        refuse_ground_mass(args.system, params, "--sensitivities")
    output.create()
    try:
        problem = Problem(network, values["t_end"])
        traj = solve(problem, values["dt"], method=args.method, save_every=values["save_every"], **options)
    except ValueError as err:
        raise ValueError(_system_message(str(err), args.system, network)) from None
    columns = traj.system_columns(os.path.splitext(args.output)[1].lower())
    if args.sensitivities is not None:
        columns |= sensitivity_columns(network, traj.t, args.sensitivities)
    output.commit(columns)
    clause = step_clause(traj.solver)
    return traj.summary() + (f"; {clause}" if clause else "")


#: What the trajectory's ``solver`` says of the step that ran (backward Euler's paths).
_STEPS = {
    "algorithm1": "Algorithm 1's compiled loop",
    "resolvent": "the law's resolvent step",
    "compiled": "compiled step (forest)",
    "compiled-banded": "compiled step (banded)",
    "one-mass-friction": "compiled step (one-mass friction loop)",
    "python": "Python step",
}


def step_clause(solver: str) -> str:
    """The summary's clause naming the step solver that ran (``""`` for a method's own stepper), e.g.
    ``"compiled step (banded)"``, or with the steps a rigid loop left to Python: ``"compiled step
    (banded; 3 of 2000 steps in the Python step)"``."""
    path, _, rest = solver.partition("+python (")
    if path not in _STEPS:
        return ""
    if not rest:
        return _STEPS[path]
    return f"{_STEPS[path][:-1]}; {rest.rstrip(')')} in the Python step)"


def _grid(args: argparse.Namespace) -> dict[str, float]:
    """``--t-end``, ``--dt`` and ``--save-every``, the options that go with ``--system``, checked."""
    return {
        name: PARAMETERS[name].check(name, parse(name, getattr(args, name)))
        for name, parse in (
            ("t_end", validate.parse_float),
            ("dt", validate.parse_float),
            ("save_every", validate.parse_int),
        )
    }


#: The single-mass API's parameter names -> (table, key) of a one-mass system file.
_SYSTEM_ENTRIES = {
    "mass": ("mass", "mass"),
    "x0": ("mass", "x0"),
    "v0": ("mass", "v0"),
    "stiffness": ("element", "stiffness"),
    "threshold": ("element", "threshold"),
    "gamma": ("element", "gamma"),
    "consistency": ("element", "consistency"),
    "exponent": ("element", "exponent"),
    "force_amplitude": ("force", "amplitude"),
    "force_omega": ("force", "omega"),
    "force_phase": ("force", "phase"),
    "force_until": ("force", "until"),
}


def _system_message(message: str, path: str, network: object) -> str:
    """A run's error in the words of the system file: the entry and key for a single-mass parameter.

    The runs of a one-mass file go through the single-mass API, whose messages
    begin with its parameter's name (``x0: ...``); ``--x0`` is not an option
    here, so the file, the entry and its key are named instead; a load the
    method does not run (``force: ...``) is named by its mass.
    """
    if message.startswith("force: "):  # Method.force_refusal: the loads of [[force]] and [ground]
        masses = ", ".join(dict.fromkeys(repr(load.on) for load in network.loads))  # type: ignore[attr-defined]
        return f"system file {path!r}: the loads on {masses}{message[len('force') :]}"
    lead = LEADING_NAME.match(message)
    if lead is None or lead.group(1) not in _SYSTEM_ENTRIES:
        return message
    table, key = _SYSTEM_ENTRIES[lead.group(1)]
    entries = {
        "mass": [repr(m.name) for m in network.masses],  # type: ignore[attr-defined]
        "element": [repr(e.name) for e in network.elements if hasattr(e, key)],  # type: ignore[attr-defined]
        "force": [f"on {f.on!r}" for f in network.loads],  # type: ignore[attr-defined]
    }[table]
    where = " ".join([f"[[{table}]]", ", ".join(entries), key]).replace("  ", " ")
    return f"system file {path!r}: {where}{message[lead.end() :]}"


def _piecewise(network: object, method: str, path: str) -> bool:
    """True if ``method`` runs ``network`` by its solver of piecewise-linear networks; its refusal there
    (an element or load with no linear phases) names the file."""
    from lumped.model.problem import one_mass_form

    if METHODS[method].piecewise_networks is None:
        return False
    try:
        one_mass_form(network)  # type: ignore[arg-type]
    except ValueError:
        if (reason := METHODS[method].network_refusal(network)) is not None:  # type: ignore[arg-type]
            raise ValueError(f"{reason} ({path})") from None
        return True
    return False


def _one_mass(network: object, args: argparse.Namespace) -> None:
    """Refuse a network that the single-mass ``--method`` cannot run (driven points, a graph that is not
    monotone, not one mass, or a law the method does not take), naming the file."""
    from lumped.model.problem import one_mass_form

    try:  # a driven point or a falling graph, named as such (not as "not one mass")
        network.refuse_drivers(f"method {args.method!r}")  # type: ignore[attr-defined]
        network.refuse_non_monotone(f"method {args.method!r}")  # type: ignore[attr-defined]
    except ValueError as err:
        raise ValueError(f"{err} ({args.system})") from None
    try:
        form = one_mass_form(network)  # type: ignore[arg-type]
    except ValueError as err:
        where = f"{args.system} {err}" if str(err).startswith("has ") else f"{args.system}: {err}"
        raise ValueError(f"--method {args.method} needs a one-mass system; {where}") from None
    reason = METHODS[args.method].refusal(form.oscillator)
    if reason is not None:
        raise ValueError(f"{reason} ({args.system})")
