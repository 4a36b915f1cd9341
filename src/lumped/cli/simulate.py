"""``python -m lumped simulate``: one motion of the single mass (or of a ``--system`` file), written to a file."""

from __future__ import annotations

import argparse
import math
from typing import TYPE_CHECKING

from lumped.cli import loads, system
from lumped.cli.options import HelpFormatter, add_method_options, check_method, method_options
from lumped.cli.output import Output, check_output
from lumped.cli.reference import methods_help
from lumped.cli.sensitivity import check_sensitivities, sensitivity_columns
from lumped.drivers.methods import METHODS, OPTIONS
from lumped.model.parameters import PARAMETERS
from lumped.numerics import validate

if TYPE_CHECKING:
    from lumped.model.trajectory import Trajectory


def add_parser(sub: argparse._SubParsersAction) -> None:
    """The ``simulate`` subcommand: the parameters, ``--system``, ``--method`` and its options, ``--output``."""
    sim = sub.add_parser(
        "simulate",
        help="integrate one motion and write it to a file",
        description="Integrate one motion and write it to a .csv or .npz file.",
        epilog=methods_help(),
        allow_abbrev=False,
        formatter_class=HelpFormatter,
    )
    for p in PARAMETERS.values():
        sim.add_argument(p.option, default=p.default_text, help=f"{p.help} [default: {p.default_text}]")
    loads.add_options(sim)
    sim.add_argument(
        "--system",
        default=None,
        metavar="FILE.toml",
        help="a network of masses and elements described in a TOML file (see "
        "book/guide/systems.md; examples in examples/, such as examples/building.toml); only --t-end, --dt, --save-every, --method, "
        f"{', '.join(o.flag for o, _ in OPTIONS.values())}, --output go with it "
        "(the networks each --method runs are listed below)",
    )
    add_method_options(sim)
    sim.add_argument(
        "--sensitivities",
        default=None,
        metavar="NAME[,NAME...]",
        help="with --method exact: add the columns dx_<mass>/d<NAME>, the derivative of each mass's x at each "
        "time with respect to the parameters NAME, written element.key, mass.key or force.key as in the system "
        "file (without --system the mass is m, its elements spring and dashpot: m.x0, dashpot.threshold, "
        "dashpot.gamma, spring.stiffness, force.amplitude, ...); a network's for every mass",
    )
    required = sim.add_argument_group("required arguments")
    required.add_argument("--output", required=True, help="output file, .csv or .npz")


def run(args: argparse.Namespace, output: Output) -> str:
    """Validate, reserve the output file, run, write; returns the summary."""
    check_sensitivities(args)
    if args.system is not None:
        return system.run(args, output)
    values = _clean(args)
    network = _network(values) if args.sensitivities is not None else None
    if network is not None:
        from lumped.drivers.sensitivity import plan  # the sensitivities' code, only when asked for

        plan(network, args.sensitivities, "--sensitivities")  # before the output is created
    output.create()
    traj = _compute(values, args.method)
    columns = traj.columns()
    if network is not None:
        columns |= sensitivity_columns(network, traj.t, args.sensitivities)
    output.commit(columns)
    return _summary(traj)


def _network(values: dict[str, object]) -> object:
    """The single mass of the options as a system: the mass ``m``, the elements ``spring`` and ``dashpot``
    (a Bingham element), its load on ``m``; the names of ``--sensitivities``."""
    from lumped.laws import GROUND, Bingham, Spring
    from lumped.model.network import Load, Mass, Network

    v, between = values, (GROUND, "m")
    elements = [Spring("spring", between, v["stiffness"]), Bingham("dashpot", between, v["threshold"], v["gamma"])]
    loads = [] if v["force"] is None else [Load("m", v["force"])]  # type: ignore[arg-type]
    return Network([Mass("m", v["mass"], v["x0"], v["v0"])], elements, loads)  # type: ignore[arg-type]


def _clean(args: argparse.Namespace) -> dict[str, object]:
    """Parse and validate every option; the messages use the API's names."""
    values: dict[str, object] = {}
    for name, p in PARAMETERS.items():
        parse = validate.parse_int if p.integer else validate.parse_float
        values[name] = p.check(name, parse(name, getattr(args, name)))
    check_method(args.method)
    values["options"] = method_options(args)
    check_output(args.output)
    n = validate.step_count(values["t_end"], values["dt"])  # type: ignore[arg-type]
    validate.output_size(n, values["save_every"])  # type: ignore[arg-type]
    values["force"] = loads.force(args, values)
    return values


def _compute(values: dict[str, object], method: str) -> Trajectory:
    """Run ``method`` through the driver :func:`lumped.drivers.simulation.simulate`."""
    from lumped.drivers.simulation import simulate
    from lumped.model.oscillator import Oscillator

    v = values
    osc = Oscillator.bingham(v["mass"], v["stiffness"], v["threshold"], v["gamma"])  # type: ignore[arg-type]
    return simulate(
        osc,
        v["t_end"],
        v["dt"],
        x0=v["x0"],
        v0=v["v0"],  # type: ignore[arg-type]
        force=v["force"],
        method=method,
        save_every=v["save_every"],
        **v["options"],  # type: ignore[arg-type]
    )  # type: ignore[arg-type]


def _summary(traj: Trajectory) -> str:
    """Rest time and position as the method found them, or the last state."""
    if math.isnan(traj.rest_time):
        return f"still moving at t = {traj.t[-1]:.6g} s (x = {traj.x[-1]:.9g} m)"
    return f"at rest from t = {traj.rest_time:.10g} s at x = {traj.rest_position:.10g} m"
