"""System files: a network written in TOML (read with :mod:`tomllib`).

The format (book/guide/systems.md, the website's Systems page): ``[[mass]]`` tables with ``name``, ``mass``,
``x0``, ``v0``; ``[[element]]`` tables with ``name``, ``kind``, ``between``
and the kind's parameters; ``[[force]]`` tables with ``on``, ``amplitude``,
``omega``, ``phase``, ``until``.  ``x0``, ``v0``, ``phase`` default to 0 and
``until`` to ``inf``.  Every problem is a ``ValueError`` of one line naming
the file, the entry and the problem (non-ASCII characters in it escaped).

Names of masses and elements are 1 to 64 ASCII letters, digits, ``_``,
``.`` and ``-``, starting with a letter or ``_``
(:data:`~lumped.laws.element.NAME_PATTERN`): they become column names
of the output.  A file holds at most
:data:`~lumped.model.network.MAX_MASSES` (10,000) masses,
:data:`~lumped.model.network.MAX_ELEMENTS` (30,000) elements and
:data:`~lumped.model.network.MAX_LOADS` (10,000) forces, and at most
:data:`MAX_FILE_BYTES` (16 MiB); a larger file is refused before it is
parsed, one with more entries before any entry is built.
"""

from __future__ import annotations

import dataclasses
import math
import os
import tomllib
from pathlib import Path

from lumped.laws.element import Element
from lumped.laws.kinds import KINDS
from lumped.model.forcing import SwitchedSine
from lumped.model.network import Load, Mass, Network, check_count

__all__ = ["MAX_FILE_BYTES", "load_system", "parse_system"]

#: Largest system file read (bytes of UTF-8, or characters of ``text``): a
#: network of the largest size written as in book/guide/systems.md takes about 7 MB.
MAX_FILE_BYTES = 16 * 1024**2
_COUNTED = {"mass": "masses", "element": "elements", "force": "loads"}

_TABLES = {"mass", "element", "force"}
_MASS_KEYS = {"name": None, "mass": None, "x0": 0.0, "v0": 0.0}
_FORCE_KEYS = {"on": None, "amplitude": None, "omega": None, "phase": 0.0, "until": math.inf}


def load_system(path: str | Path) -> Network:
    """Read a system file; ``ValueError`` naming the file, the entry and the problem."""
    if not isinstance(path, (str, os.PathLike)):
        raise ValueError(f"path must be a str or a path of a system file, got {type(path).__name__}")
    path = Path(path)
    source = f"system file {str(path)!a}"
    try:
        if path.stat().st_size > MAX_FILE_BYTES:
            raise ValueError(f"{source}: {path.stat().st_size} bytes, more than the {MAX_FILE_BYTES} read")
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        why = getattr(err, "strerror", None) or str(err)
        raise ValueError(f"{source}: cannot read it: {why}") from None
    return parse_system(text, source)


def parse_system(text: str, source: str = "<string>") -> Network:
    """A network from the text of a system file (``source`` names it in messages).

    Every problem is a one-line ``ValueError`` beginning with ``source``;
    non-ASCII characters of the message are escaped (``\\xe9``), so that
    printing it never fails on the encoding of a terminal.
    """
    if not isinstance(text, str):
        raise ValueError(f"text must be a str (the TOML text of a system file), got {type(text).__name__}")
    if not isinstance(source, str):
        raise ValueError(f"source must be a str naming the text in messages, got {type(source).__name__}")
    try:
        return _parse(text, source)
    except ValueError as err:
        raise ValueError(str(err).encode("ascii", "backslashreplace").decode("ascii")) from None


def _parse(text: str, source: str) -> Network:
    if len(text) > MAX_FILE_BYTES:
        raise ValueError(f"{source}: {len(text)} characters, more than the {MAX_FILE_BYTES} read")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{source}: not valid TOML: {err}") from None
    except RecursionError:
        raise ValueError(f"{source}: not read: its tables or arrays are nested too deeply") from None
    unknown = sorted(set(data) - _TABLES)
    if unknown:
        raise ValueError(f"{source}: unknown table {unknown[0]!r:.40}; expected [[mass]], [[element]] and [[force]]")
    tables = {}
    for key in sorted(_TABLES):
        value = data.get(key, [])
        if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
            raise ValueError(f"{source}: {key} must be written as [[{key}]] tables")
        try:
            check_count(_COUNTED[key], len(value))
        except ValueError as err:
            raise ValueError(f"{source}: {err}") from None
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
    where = f"[[{table}]] {number}" + (f" ({label!a:.40})" if isinstance(label, str) else "")
    try:
        return build(raw)
    except ValueError as err:
        raise ValueError(f"{source}: {where}: {err}") from None
    except TypeError as err:  # a value of the wrong TOML type that a check did not catch
        raise ValueError(f"{source}: {where}: {err}") from None


def _fields(raw: dict, spec: dict) -> dict:
    extra = sorted(set(raw) - set(spec))
    if extra:
        raise ValueError(f"unknown parameter {extra[0]!r:.40}; expected {', '.join(spec)}")
    missing = [k for k, default in spec.items() if default is None and k not in raw]
    if missing:
        raise ValueError(f"missing parameter {missing[0]!r:.40}")
    return {k: raw.get(k, default) for k, default in spec.items()}


def _mass(raw: dict) -> Mass:
    return Mass(**_fields(raw, _MASS_KEYS))


def _element(raw: dict) -> Element:
    kind = raw.get("kind")
    if kind not in KINDS:
        raise ValueError(f"unknown kind {kind!r:.40}; expected one of {', '.join(KINDS)}")
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
