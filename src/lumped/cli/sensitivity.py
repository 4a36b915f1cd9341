"""``simulate --sensitivities``: the derivatives of the exact motion as extra columns ``dx_<mass>/d<name>``."""

from __future__ import annotations

import argparse

__all__ = ["check_sensitivities", "sensitivity_columns"]


def check_sensitivities(args: argparse.Namespace) -> None:
    """Refuse ``--sensitivities`` with a method other than ``exact``, whose solution they differentiate."""
    if args.sensitivities is not None and args.method != "exact":
        raise ValueError(
            f"--sensitivities needs --method exact (the derivatives of the exact solution), not {args.method!r}"
        )


def sensitivity_columns(network: object, t: object, names: str) -> dict[str, object]:
    """The columns ``dx_<mass>/d<name>`` of the exact motion's derivatives at the times ``t``."""
    from lumped.drivers.sensitivity import system_sensitivities

    _, sens = system_sensitivities(network, t, names, "--sensitivities")  # type: ignore[arg-type]
    mass = network.masses[0].name  # type: ignore[attr-defined]
    return {f"dx_{mass}/d{name}": sens.x[:, j] for j, name in enumerate(sens.parameters)}
