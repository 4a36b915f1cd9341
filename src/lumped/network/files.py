"""System files: a network written in TOML (read with :mod:`tomllib`).

The format (README, "Networks"): ``[[mass]]`` tables with ``name``, ``mass``,
``x0``, ``v0``; ``[[element]]`` tables with ``name``, ``kind``, ``between``
and the kind's parameters; ``[[force]]`` tables with ``on``, ``amplitude``,
``omega``, ``phase``, ``until``.  ``x0``, ``v0``, ``phase`` default to 0 and
``until`` to ``inf``.  Every problem is a ``ValueError`` of one line naming
the file, the entry and the problem.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path

from lumped.forcing import SwitchedSine
from lumped.network.elements import KINDS, Element
from lumped.network.model import Load, Mass, Network

__all__ = ["load_system", "parse_system"]

_TABLES = {"mass", "element", "force"}
_MASS_KEYS = {"name": None, "mass": None, "x0": 0.0, "v0": 0.0}
_FORCE_KEYS = {"on": None, "amplitude": None, "omega": None, "phase": 0.0, "until": math.inf}


def load_system(path: str | Path) -> Network:
    """Read a system file; ``ValueError`` naming the file, the entry and the problem."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        why = getattr(err, "strerror", None) or str(err)
        raise ValueError(f"system file {str(path)!r}: cannot read it: {why}") from None
    return parse_system(text, f"system file {str(path)!r}")


def parse_system(text: str, source: str = "<string>") -> Network:
    """A network from the text of a system file (``source`` names it in messages)."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{source}: not valid TOML: {err}") from None
    unknown = sorted(set(data) - _TABLES)
    if unknown:
        raise ValueError(f"{source}: unknown table {unknown[0]!r}; expected [[mass]], [[element]] and [[force]]")
    tables = {}
    for key in sorted(_TABLES):
        value = data.get(key, [])
        if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
            raise ValueError(f"{source}: {key} must be written as [[{key}]] tables")
        tables[key] = value
    masses = [_entry(source, "mass", i, t, _mass) for i, t in enumerate(tables["mass"], 1)]
    elements = [_entry(source, "element", i, t, _element) for i, t in enumerate(tables["element"], 1)]
    loads = [_entry(source, "force", i, t, _force) for i, t in enumerate(tables["force"], 1)]
    try:
        net = Network(masses, elements, loads)
        _initial_check(net)
    except ValueError as err:
        raise ValueError(f"{source}: {err}") from None
    return net


def _entry(source: str, table: str, number: int, raw: dict, build) -> object:  # noqa: ANN001
    label = raw.get("name", raw.get("on")) if isinstance(raw, dict) else None
    where = f"[[{table}]] {number}" + (f" ({label!r:.40})" if isinstance(label, str) else "")
    try:
        return build(raw)
    except ValueError as err:
        raise ValueError(f"{source}: {where}: {err}") from None
    except TypeError as err:  # a value of the wrong TOML type that a check did not catch
        raise ValueError(f"{source}: {where}: {err}") from None


def _fields(raw: dict, spec: dict) -> dict:
    extra = sorted(set(raw) - set(spec))
    if extra:
        raise ValueError(f"unknown parameter {extra[0]!r}; expected {', '.join(spec)}")
    missing = [k for k, default in spec.items() if default is None and k not in raw]
    if missing:
        raise ValueError(f"missing parameter {missing[0]!r}")
    return {k: raw.get(k, default) for k, default in spec.items()}


def _mass(raw: dict) -> Mass:
    return Mass(**_fields(raw, _MASS_KEYS))


def _element(raw: dict) -> Element:
    kind = raw.get("kind")
    if kind not in KINDS:
        raise ValueError(f"unknown kind {kind!r}; expected one of {', '.join(KINDS)}")
    cls = KINDS[kind]
    spec = {"name": None, "kind": None, "between": None}
    for f in dataclasses.fields(cls):
        if f.name not in spec:
            spec[f.name] = f.default if f.name in ("force0",) else None
    values = _fields(raw, spec)
    del values["kind"]
    if isinstance(values["between"], list):
        values["between"] = tuple(values["between"])
    return cls(**values)


def _force(raw: dict) -> Load:
    values = _fields(raw, _FORCE_KEYS)
    on = values.pop("on")
    try:
        return Load(on, SwitchedSine(**values))
    except ValueError as err:  # SwitchedSine names its fields force_amplitude, ...
        raise ValueError(str(err).removeprefix("force_")) from None


def _initial_check(net: Network) -> None:
    """Initial elongations the elements refuse (a string beyond its length)."""
    x = {m.name: m.x0 for m in net.masses} | {"ground": 0.0}
    v = {m.name: m.v0 for m in net.masses} | {"ground": 0.0}
    for el in net.elements:
        a, b = el.between
        try:
            el.initial_state(x[b] - x[a], v[b] - v[a])
        except ValueError as err:
            raise ValueError(f"element {el.name!r}: {err}") from None
