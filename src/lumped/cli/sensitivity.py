"""``simulate --sensitivities``: the derivatives of the exact motion as extra columns ``dx_<mass>/d<name>``
(every mass's, mass by mass)."""

from __future__ import annotations

import argparse

__all__ = ["check_sensitivities", "refuse_ground_mass", "sensitivity_columns"]


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
    masses = network.mass_names  # type: ignore[attr-defined]
    if sens.x.ndim == 2:  # one mass
        return {f"dx_{masses[0]}/d{name}": sens.x[:, j] for j, name in enumerate(sens.parameters)}
    return {
        f"dx_{mass}/d{name}": sens.x[:, i, j] for i, mass in enumerate(masses) for j, name in enumerate(sens.parameters)
    }


def refuse_ground_mass(path: str, parameters: tuple, what: str) -> None:
    """Refuse a mass's ``mass`` among ``parameters`` when the system file ``path`` has a ``[ground]`` table.

    The ground's load on a mass is ``-m a_g(t)``, written into the system when the file is read; a changed
    mass would keep the old load, so its derivative (and its fit) would be wrong.
    """
    import tomllib

    with open(path, "rb") as fh:
        ground = "ground" in tomllib.load(fh)
    masses = [p.name for p in parameters if p.table == "mass" and p.key == "mass"]
    if ground and masses:
        raise ValueError(
            f"{what}: {masses[0]} is not supported with a [ground] table, whose load -m a_g moves with the mass"
        )
