"""The numeric parameters of a system, named as in its file: ``mass.key``, ``element.key`` and ``force.key``.

A system file (:mod:`lumped.model.files`) names its masses and elements;
each number in it is then ``<name>.<key>``: a mass's ``mass``, ``x0`` or
``v0`` (``m.x0``), an element's parameter (``dashpot.threshold``,
``spring.stiffness``, ``damper.damping``), and, for a system with a single
load, that load's ``force.amplitude``, ``force.omega``, ``force.phase``,
``force.until`` (a sine) or ``force.value``, ``force.until`` (a constant),
and a driven point's ``velocity`` where it is one number (``belt.velocity``).
A table with ``count`` (:mod:`lumped.model.repeated`) gives its tables' own
names, so ``b17.mass`` is the 17th block's mass and varies that block alone;
the pattern's name (``b{i}.mass``) is refused in one line: the tables of a
pattern are independent entries once read, and a value that changes them
all is changed in the file.
The sensitivities (``simulate --sensitivities``) and the fit (``lumped
fit``) name their parameters so; :func:`system_parameters` reads such
names and :func:`with_values` writes new values into a system.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Sequence
from typing import NamedTuple

from lumped.model.forcing import parameters
from lumped.model.network import Driver, Load, Network, listed

__all__ = ["DRIVER_KEYS", "MASS_KEYS", "ONE_MASS_NAMES", "SystemParameter", "system_parameters", "with_values"]

#: A mass's numeric keys.
MASS_KEYS = ("mass", "x0", "v0")
#: A driven point's numeric keys (its velocity where it is one number, m/s).
DRIVER_KEYS = ("velocity",)
#: The loads' table in a system file, which is the first part of their names.
LOAD = "force"


#: ``(table, key)`` of a parameter of a file of the paper's form (one mass, a spring and a Bingham dashpot, a
#: sine or constant load) -> the one-mass API's name for it (``lumped.Oscillator``'s and the one-mass sweep's);
#: a constant load is the sine ``value sin(0 t + pi/2)`` it equals, so its ``value`` is the amplitude.
ONE_MASS_NAMES = {
    ("mass", "mass"): "mass",
    ("mass", "x0"): "x0",
    ("mass", "v0"): "v0",
    ("element", "stiffness"): "stiffness",
    ("element", "threshold"): "threshold",
    ("element", "gamma"): "gamma",
    ("force", "amplitude"): "force_amplitude",
    ("force", "value"): "force_amplitude",
    ("force", "omega"): "force_omega",
    ("force", "phase"): "force_phase",
    ("force", "until"): "force_until",
}


class SystemParameter(NamedTuple):
    """A numeric parameter of a system: its ``name`` (``element.key``), the ``table`` holding it
    (``"mass"``, ``"element"``, ``"driver"`` or ``"force"``), the item's ``index`` in it, the ``key`` and its
    ``value``."""

    name: str
    table: str
    index: int
    key: str
    value: float


def _element_keys(el: object) -> tuple[str, ...]:
    """The numeric parameters of an element: its dataclass fields after ``name`` and ``between`` that hold floats."""
    return tuple(
        f.name
        for f in dataclasses.fields(el)  # type: ignore[arg-type]
        if f.name not in ("name", "between") and isinstance(getattr(el, f.name), float)
    )


def _choices(network: Network) -> list[str]:
    """Every parameter name of ``network``, masses first."""
    names = [f"{m.name}.{key}" for m in network.masses for key in MASS_KEYS]
    names += [f"{el.name}.{key}" for el in network.elements for key in _element_keys(el)]
    names += [f"{d.name}.{key}" for d in network.drivers if d.constant_velocity is not None for key in DRIVER_KEYS]
    if len(network.loads) == 1:
        names += [f"{LOAD}.{key}" for key in parameters(network.loads[0].force)]
    return names


def _one(network: Network, name: str, what: str) -> SystemParameter:
    """The parameter called ``name``, or a ``ValueError`` that begins with ``what``."""
    item, dot, key = name.rpartition(".")
    if not dot or not item or not key:
        raise ValueError(f"{what}: {name!r} is not a parameter's name; write it element.key or mass.key (m.x0)")
    if "{" in item:
        raise ValueError(
            f"{what}: {name!r} names a pattern of a count table, not one parameter; name one of its tables "
            f"(such as {re.sub(r'[{][^{}]*[}]', '1', item)[:40]}.{key}), or change the value in the file to change them all"
        )
    for i, m in enumerate(network.masses):
        if m.name == item and key in MASS_KEYS:
            return SystemParameter(name, "mass", i, key, float(getattr(m, key)))
    for i, el in enumerate(network.elements):
        if el.name == item and key in _element_keys(el):
            return SystemParameter(name, "element", i, key, float(getattr(el, key)))
    for i, d in enumerate(network.drivers):
        if d.name == item and key in DRIVER_KEYS:
            if d.constant_velocity is None:
                raise ValueError(f"{what}: {name!r}: driver {d.name!r} follows a history, not one velocity")
            return SystemParameter(name, "driver", i, key, float(d.constant_velocity))
    if item == LOAD and network.loads:
        force = network.loads[0].force
        if len(network.loads) > 1 or not parameters(force):
            raise ValueError(f"{what}: {name!r}: only a system with one sine or constant load names it {LOAD}.<key>")
        if key in parameters(force):
            return SystemParameter(name, "force", 0, key, float(getattr(force, key)))
    raise ValueError(f"{what}: unknown parameter {name!r}; this system's are {listed(_choices(network), 12)}")


def system_parameters(
    network: Network, names: str | Sequence[str], what: str = "parameters"
) -> tuple[SystemParameter, ...]:
    """The parameters of ``network`` called ``names`` (a sequence, or one string separated by commas).

    Raises
    ------
    ValueError
        One line beginning with ``what``: not a string or a sequence, no name, a name given twice, or one
        that is not a parameter of ``network`` (the message lists those it has).
    """
    if not isinstance(network, Network):
        raise ValueError(f"network must be a Network, got {type(network).__name__}")
    if isinstance(names, str):
        names = [n.strip() for n in names.split(",")]
    if not isinstance(names, Sequence):  # a number, a set, a generator: no names in an order
        got = type(names).__name__
        raise ValueError(f"{what}: expected names such as dashpot.threshold,m.x0, got {got}")  # noqa: TRY004 (the API's one error type)
    names = list(names)
    if not names or any(not isinstance(n, str) or not n for n in names):
        raise ValueError(f"{what}: expected names such as dashpot.threshold,m.x0 separated by commas, got {names!r}")
    twice = [n for i, n in enumerate(names) if n in names[:i]]
    if twice:
        raise ValueError(f"{what}: {twice[0]!r} is named twice")
    return tuple(_one(network, n, what) for n in names)


def with_values(network: Network, parameters: Sequence[SystemParameter], values: Sequence[float]) -> Network:
    """``network`` with each of ``parameters`` set to the matching number of ``values`` (checked by the items).

    Raises
    ------
    ValueError
        A value the mass, element or load refuses (its own message).
    """
    if not all(math.isfinite(float(v)) for v in values):
        raise ValueError(f"values must be finite numbers, got {list(values)!r}")
    masses, elements, loads = list(network.masses), list(network.elements), list(network.loads)
    drivers = list(network.drivers)
    for p, value in zip(parameters, values, strict=True):
        value = float(value)
        if p.table == "mass":
            masses[p.index] = dataclasses.replace(masses[p.index], **{p.key: value})
        elif p.table == "element":
            elements[p.index] = dataclasses.replace(elements[p.index], **{p.key: value})
        elif p.table == "driver":
            drivers[p.index] = Driver(drivers[p.index].name, value)
        else:
            load = loads[p.index]
            loads[p.index] = Load(load.on, dataclasses.replace(load.force, **{p.key: value}))  # type: ignore[type-var]
    return Network(masses, elements, loads, drivers)
