"""System files: a network written in TOML (read with :mod:`tomllib`).

The format (book/guide/systems.md, the website's Systems page): ``[[mass]]`` tables with ``name``, ``mass``,
``x0``, ``v0``; ``[[element]]`` tables with ``name``, ``kind``, ``between``
and the kind's parameters; ``[[force]]`` tables with ``on`` and a ``kind``:
``"sine"`` (the default: ``amplitude``, ``omega``, ``phase``, ``until``),
``"constant"`` (``value``, ``from``, ``until``) or ``"table"`` (``file``, a
CSV file ``t,F`` read by :func:`lumped.model.tables.read_table`, relative to
the system file); an optional ``[ground]`` table whose ``acceleration`` is
one of the same kinds (a table's columns ``t,a``), applied as the load
``-m a_g(t)`` on every mass, whose positions and velocities are then
relative to the ground; ``[[driver]]`` tables with ``name`` and
``velocity``, a number (m/s) or one of the same kinds (a table's columns
``t,v``), points whose motion is prescribed (a belt), which elements name in
``between`` as they name the ground or a mass.  Several forces on one mass add.  ``x0``, ``v0``,
``phase`` and ``from`` default to 0 and ``until`` to ``inf``.  Every problem
is a ``ValueError`` of one line naming the file, the entry and the problem
(non-ASCII characters in it escaped).

A ``[[mass]]``, ``[[element]]``, ``[[force]]`` or ``[[driver]]`` table with
``count = N`` stands for N tables, ``i = 1 .. N``: ``{i}``, ``{i+1}``, ``{i-1}``
in its strings, an array of N numbers or a grading ``{ from = a, to = b }``
for a number (:mod:`lumped.model.repeated`), so that a chain of thousands of
blocks is a file of a few lines.

Names of masses, drivers and elements are 1 to 64 ASCII letters, digits, ``_``,
``.`` and ``-``, starting with a letter or ``_``
(:data:`~lumped.laws.element.NAME_PATTERN`): they become column names
of the output.  A file holds at most
:data:`~lumped.model.network.MAX_MASSES` (100,000) masses,
:data:`~lumped.model.network.MAX_ELEMENTS` (300,000) elements and
:data:`~lumped.model.network.MAX_LOADS` (200,000) forces, the ground's
load on every mass included, and at most
:data:`MAX_FILE_BYTES` (16 MiB); a larger file is refused before it is
parsed, one with more entries (``count`` tables counted N times) before any entry is built.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import os
import tomllib
from collections.abc import Collection
from pathlib import Path

from lumped.laws.element import Element
from lumped.laws.kinds import KINDS
from lumped.model.forcing import Constant, SwitchedSine
from lumped.model.network import Driver, Load, Mass, Network, check_count
from lumped.model.repeated import Origin, count_of, expand
from lumped.model.tables import read_table

__all__ = ["MAX_FILE_BYTES", "load_system", "parse_system", "table_files"]

#: Largest system file read (bytes of UTF-8, or characters of ``text``): a
#: network of the largest size written as in book/guide/systems.md takes about 7 MB.
MAX_FILE_BYTES = 16 * 1024**2
_COUNTED = {"mass": "masses", "element": "elements", "force": "loads", "driver": "drivers"}

_TABLES = {"mass", "element", "force", "driver"}
_MASS_KEYS = {"name": None, "mass": None, "x0": 0.0, "v0": 0.0}
#: The keys of a load history by ``kind`` (``None``: required); a ``[[force]]`` adds ``on``.
_HISTORY_KEYS = {
    "sine": {"kind": "sine", "amplitude": None, "omega": None, "phase": 0.0, "until": math.inf},
    "constant": {"kind": None, "value": None, "from": 0.0, "until": math.inf},
    "table": {"kind": None, "file": None},
}


def load_system(path: str | Path) -> Network:
    """Read a system file; ``ValueError`` naming the file, the entry and the problem.

    A table's ``file`` is read relative to the system file's folder.
    """
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
    return parse_system(text, source, folder=path.parent)


def table_files(path: str | Path) -> list[tuple[str, Path]]:
    """The table files that the system file ``path`` names, as ``(entry, file)``: ``("[[force]] 2", folder /
    file)``, ``("[ground] acceleration", ...)`` or ``("[[driver]] 1 velocity", ...)`` (``"[[force]] 2, i =
    7"`` for a ``count`` table's seventh), each resolved as :func:`load_system` reads it.

    What cannot be read is left out (a file that is not TOML names none): :func:`load_system` refuses it.
    """
    path = Path(path)
    try:
        if path.stat().st_size > MAX_FILE_BYTES:
            return []
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        tables = _expanded(data, ("force", "driver"))  # not the masses and elements: they name no files
    except (OSError, UnicodeError, tomllib.TOMLDecodeError, RecursionError, ValueError):
        return []
    ground = data.get("ground", {})
    entries = [(origin.label("force"), raw) for origin, raw in tables["force"]]
    for origin, raw in tables["driver"]:
        entries.append((f"{origin.label('driver')} velocity", raw.get("velocity")))
    if isinstance(ground, dict):
        entries.append(("[ground] acceleration", ground.get("acceleration")))
    return [
        (entry, path.parent / raw["file"])
        for entry, raw in entries
        if isinstance(raw, dict) and raw.get("kind") == "table" and isinstance(raw.get("file"), str)
    ]


def parse_system(text: str, source: str = "<string>", *, folder: str | Path = ".") -> Network:
    """A network from the text of a system file (``source`` names it in messages).

    Every problem is a one-line ``ValueError`` beginning with ``source``;
    non-ASCII characters of the message are escaped (``\\xe9``), so that
    printing it never fails on the encoding of a terminal.  A table's
    ``file`` is read relative to ``folder`` (the current one by default).
    """
    if not isinstance(text, str):
        raise ValueError(f"text must be a str (the TOML text of a system file), got {type(text).__name__}")
    if not isinstance(source, str):
        raise ValueError(f"source must be a str naming the text in messages, got {type(source).__name__}")
    if not isinstance(folder, (str, os.PathLike)):
        raise ValueError(f"folder must be a str or a path, got {type(folder).__name__}")
    try:
        return _parse(text, source, Path(folder))
    except ValueError as err:
        raise ValueError(str(err).encode("ascii", "backslashreplace").decode("ascii")) from None


def _parse(text: str, source: str, folder: Path) -> Network:
    if len(text) > MAX_FILE_BYTES:
        raise ValueError(f"{source}: {len(text)} characters, more than the {MAX_FILE_BYTES} read")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{source}: not valid TOML: {err}") from None
    except RecursionError:
        raise ValueError(f"{source}: not read: its tables or arrays are nested too deeply") from None
    unknown = sorted(set(data) - _TABLES - {"ground"})
    if unknown:
        raise ValueError(
            f"{source}: unknown table {unknown[0]!r:.40}; expected [[mass]], [[element]], [[force]], [[driver]] "
            "and [ground]"
        )
    try:
        tables = _expanded(data)
    except ValueError as err:
        raise ValueError(f"{source}: {err}") from None
    masses = [_entry(source, "mass", o, t, _mass) for o, t in tables["mass"]]
    elements = [_entry(source, "element", o, t, _element) for o, t in tables["element"]]
    loads = [_entry(source, "force", o, t, lambda raw: _force(raw, folder)) for o, t in tables["force"]]
    loads += _ground(source, data.get("ground"), masses, folder)
    drivers = [_entry(source, "driver", o, t, lambda raw: _driver(raw, folder)) for o, t in tables["driver"]]
    try:
        net = Network(masses, elements, loads, drivers)
        _initial_check(net)
    except ValueError as err:
        raise ValueError(f"{source}: {err}") from None
    return net


def _expanded(data: dict, kinds: Collection[str] = _TABLES) -> dict[str, list[tuple[Origin, dict]]]:
    """The file's tables of ``kinds`` (all by default), each ``count`` table expanded
    (:mod:`lumped.model.repeated`), every kind's numbers checked against the network's limits before any
    is expanded."""
    tables = {}
    for key in sorted(_TABLES):
        value = data.get(key, [])
        if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
            raise ValueError(f"{key} must be written as [[{key}]] tables")
        check_count(_COUNTED[key], len(value))
        total = 0
        for number, raw in enumerate(value, 1):
            try:
                total += count_of(raw)
            except ValueError as err:
                raise ValueError(f"[[{key}]] {number}: {err}") from None
        check_count(_COUNTED[key], total)
        if key in kinds:
            tables[key] = expand(value, key)
    return tables


def _entry(source: str, table: str, origin: Origin, raw: dict, build) -> object:  # noqa: ANN001
    label = raw.get("name", raw.get("on")) if isinstance(raw, dict) else None
    where = origin.label(table) + (f" ({label!a:.40})" if isinstance(label, str) else "")
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


#: An optional parameter a file leaves out (the element's dataclass default applies).
_LEFT_OUT = object()


@functools.cache
def _spec(cls: type) -> dict:
    """An element kind's parameters, ``None`` if required, :data:`_LEFT_OUT` if optional (once per kind)."""
    spec = {"name": None, "kind": None, "between": None}
    for f in dataclasses.fields(cls):
        if f.name not in spec:
            spec[f.name] = _LEFT_OUT if f.name in cls.optional else None
    return spec


def _element(raw: dict) -> Element:
    kind = raw.get("kind")
    if not isinstance(kind, str) or kind not in KINDS:  # an array (one per table of a count?) is no key of KINDS
        raise ValueError(f"unknown kind {kind!r:.40}; expected one of {', '.join(KINDS)}")
    cls = KINDS[kind]
    values = {k: v for k, v in _fields(raw, _spec(cls)).items() if v is not _LEFT_OUT}  # left out: the field's default
    del values["kind"]
    if isinstance(values["between"], list):
        values["between"] = tuple(values["between"])
    return cls(**values)


def _force(raw: dict, folder: Path) -> Load:
    keys = _HISTORY_KEYS[_kind(raw)]
    values = _fields(raw, {"on": None} | keys)
    on = values.pop("on")
    return Load(on, _history(values, folder, "F"))


def _driver(raw: dict, folder: Path) -> Driver:
    """A ``[[driver]]``: ``name`` and ``velocity``, a number (m/s) or a history table like a force's
    (``{ kind = "table", file = "belt.csv" }`` with columns ``t,v``, a sine or a constant)."""
    values = _fields(raw, {"name": None, "velocity": None})
    velocity = values["velocity"]
    if isinstance(velocity, dict):
        velocity = _history(_fields(velocity, _HISTORY_KEYS[_kind(velocity)]), folder, "v")
    elif isinstance(velocity, bool) or not isinstance(velocity, (int, float)):
        raise ValueError(
            f'velocity must be a number (m/s) or a table such as {{ kind = "table", file = "belt.csv" }}, '
            f"got {velocity!r:.40}"
        )
    return Driver(values["name"], velocity)


def _kind(raw: dict) -> str:
    kind = raw.get("kind", "sine")
    if not isinstance(kind, str) or kind not in _HISTORY_KEYS:
        raise ValueError(f"unknown kind {kind!r:.40}; expected one of {', '.join(_HISTORY_KEYS)}")
    return kind


def _history(values: dict, folder: Path, column: str) -> object:
    """The load history of an entry's checked ``values``; a table's file is ``folder / file``, column ``column``."""
    kind = values.pop("kind")
    if kind == "table":
        if not isinstance(values["file"], str):
            raise ValueError(f"file must be a string, the path of a CSV file 't,{column}', got {values['file']!r:.40}")
        return read_table(folder / values["file"], column)
    try:
        if kind == "constant":
            return Constant(values["value"], values["from"], values["until"])
        return SwitchedSine(**values)
    except ValueError as err:  # SwitchedSine names its fields force_amplitude, ..., Constant ``start``
        raise ValueError(str(err).removeprefix("force_").replace("start", "from")) from None


def _ground(source: str, raw: object, masses: list[Mass], folder: Path) -> list[Load]:
    """The loads ``-m a_g(t)`` of a ``[ground]`` table on every mass (none without it)."""
    if raw is None:
        return []
    where = f"{source}: [ground]"
    try:
        if not isinstance(raw, dict):
            raise ValueError("must be written as a [ground] table")
        acceleration = _fields(raw, {"acceleration": None})["acceleration"]
        where += " acceleration"
        if not isinstance(acceleration, dict):
            raise ValueError('must be an inline table such as { kind = "table", file = "record.csv" }')
        history = _history(_fields(acceleration, _HISTORY_KEYS[_kind(acceleration)]), folder, "a")
    except (ValueError, TypeError) as err:
        raise ValueError(f"{where}: {err}") from None
    loads = []
    for m in masses:
        try:
            loads.append(Load(m.name, history.scaled(-m.mass)))
        except ValueError:  # the product overflows
            raise ValueError(f"{where}: the load -m a_g on mass {m.name!r} (m = {m.mass:g}) is not finite") from None
    return loads


def _initial_check(net: Network) -> None:
    """Initial elongations the elements refuse (a string beyond its length)."""
    x = {m.name: m.x0 for m in net.masses} | {"ground": 0.0} | {d.name: 0.0 for d in net.drivers}
    v = {m.name: m.v0 for m in net.masses} | {"ground": 0.0} | {d.name: float(d.velocity_at(0.0)) for d in net.drivers}
    for el in net.elements:
        a, b = el.between
        try:
            el.initial_state(x[b] - x[a], v[b] - v[a])
        except ValueError as err:
            raise ValueError(f"element {el.name!r}: {err}") from None
