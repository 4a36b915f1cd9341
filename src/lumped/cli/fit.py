"""``python -m lumped fit``: estimate a system file's parameters from a measured record (:mod:`lumped.drivers.fit`)."""

from __future__ import annotations

import argparse
import math

from lumped.cli.options import HelpFormatter
from lumped.cli.output import Output, check_output
from lumped.cli.sensitivity import refuse_ground_mass

_DESCRIPTION = """\
Estimate parameters of a system file from a measured record by least squares
(SciPy's least_squares), with the exact Jacobian from the sensitivities of the
exact solution.  The record is a CSV file with the columns t (s, from 0,
increasing) and x_<mass> (m) for the measured masses, plain decimal numbers;
other columns are not read.  --free names the parameters to estimate,
element.key or mass.key as in the file: an element's threshold, gamma,
stiffness, damping, a mass's mass, x0, v0 (and force.amplitude, force.omega,
force.phase of a single sine load).  The system: what the exact solver runs
(one mass, or a network of springs, Bingham, Coulomb and linear dashpots under
sine and constant loads); the record may measure any subset of its masses.

How it searches: in units-free variables (the residuals over the record's
largest |x|, a positive parameter by its logarithm, another by its start), so
the result does not depend on the record's units.  Each local fit starts on
the record's first eighth and doubles the part fitted until it is all fitted,
from the file's values and from --starts - 1 further starts spread over a
factor 1/2 to 2 of each positive parameter and 2 starts' sizes either way of
the others (a phase over every angle).  The lowest end is the estimate.

What it guarantees: the estimate is a local minimum of the sum of squares,
the lowest the starts reached; a parameter is marked not identified (no
standard error) when the record cannot tell it within a factor e, when it is
in a combination the record does not determine, when another end fits the
record as well (a sum of squares within the 95 % confidence region of the
estimate's), when it runs toward its bound 0 (a threshold the record cannot
tell from 0) or a factor 1000 from its start, and then every parameter that
depends on it.  What it does not: a minimum that none of the starts reaches,
nor standard errors beyond the linearised model with independent errors of
equal variance.

The summary gives each estimate with its standard error; --output writes them
to a JSON file with the reasons for any not identified, the residual standard
deviation, the correlation matrix and the combinations of the parameters that
the data identify or do not."""


def add_parser(sub: argparse._SubParsersAction) -> None:
    """The ``fit`` subcommand."""
    fp = sub.add_parser(
        "fit",
        help="estimate a system file's parameters from a measured record",
        description=_DESCRIPTION,
        allow_abbrev=False,
        formatter_class=HelpFormatter,
    )
    required = fp.add_argument_group("required arguments")
    required.add_argument("--system", required=True, metavar="FILE.toml", help="the system file, with the start values")
    required.add_argument("--data", required=True, metavar="RECORD.csv", help="the record: columns t and x_<mass>")
    required.add_argument(
        "--free", required=True, metavar="NAME[,NAME...]", help="the parameters to estimate (dashpot.threshold,m.x0)"
    )
    fp.add_argument(
        "--output", default=None, metavar="FIT.json", help="write the estimates and statistics to a .json file"
    )
    fp.add_argument(
        "--starts",
        default="4",
        metavar="N",
        help="local fits from the file's values and N - 1 spread starts (1 to 64; the cost grows with N)",
    )


def run(args: argparse.Namespace, output: Output | None) -> str:
    """Validate, read the system and the record, reserve the output, fit, write; returns the summary."""
    from lumped.drivers.fit import fit
    from lumped.model.files import load_system
    from lumped.model.records import read_record
    from lumped.model.system_parameters import system_parameters
    from lumped.numerics import validate

    if args.output is not None:
        check_output(args.output, (".json",))
    starts = validate.parse_int("--starts", args.starts)
    network = load_system(args.system)
    refuse_ground_mass(args.system, system_parameters(network, args.free, "--free"), "--free")
    record = read_record(args.data, network.mass_names)
    if output is not None:
        output.create()
    try:
        result = fit(network, record, args.free, starts=starts)
    except ValueError as err:
        raise ValueError(_blamed(str(err), args)) from None
    if output is not None:
        output.commit(as_json(result))
    return result.summary()


def _blamed(message: str, args: argparse.Namespace) -> str:
    """The API's message with the argument it begins with replaced by what the user gave: ``free`` by
    ``--free``, ``starts`` by ``--starts``, ``record`` by the record's file, ``system`` by the system file."""
    where = {"free": "--free", "starts": "--starts", "record": f"file {args.data!a}"}
    where["system"] = f"system file {args.system!a}"
    head, space, rest = message.replace(":", " :", 1).partition(" ")
    return f"{where[head]}{space}{rest}".replace(" :", ":", 1) if head in where else message


def as_json(result: object) -> dict:
    """The fit as strict JSON (no NaN: a missing standard error or correlation is ``null``)."""
    from lumped.studies.strict_json import clean

    r = result
    names = list(r.parameters)  # type: ignore[attr-defined]
    return clean(
        {
            "parameters": {
                name: {
                    "start": r.start[j],  # type: ignore[attr-defined]
                    "estimate": r.estimate[j],  # type: ignore[attr-defined]
                    "standard_error": r.standard_error[j],  # type: ignore[attr-defined]
                    "identified": bool(r.identified[j]),  # type: ignore[attr-defined]
                    "reason": r.reasons[j] or None,  # type: ignore[attr-defined]
                }
                for j, name in enumerate(names)
            },
            "residual_std": r.residual_std,  # type: ignore[attr-defined]
            "points": int(sum(x.size for x in r.record.x.values())),  # type: ignore[attr-defined]
            "correlation": r.correlation.tolist(),  # type: ignore[attr-defined]
            "combinations": [
                {
                    "coefficients": dict(zip(names, c.coefficients.tolist())),
                    "text": c.text(names),
                    "singular_value_ratio": c.ratio,
                    "standard_error": c.standard_error if math.isfinite(c.standard_error) else None,
                    "identified": c.identified,
                }
                for c in r.combinations  # type: ignore[attr-defined]
            ],
            "evaluations": r.evaluations,  # type: ignore[attr-defined]
            "message": r.message,  # type: ignore[attr-defined]
        }
    )
