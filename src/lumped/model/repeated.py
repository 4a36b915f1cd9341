"""Repeated tables of a system file: a table with ``count = N`` stands for N tables, ``i = 1 .. N``.

Any ``[[mass]]``, ``[[element]]``, ``[[force]]`` or ``[[driver]]`` table may
carry ``count = N`` (an integer ``>= 1``); it is then N tables, numbered by
the index ``i``, in the file's order at the place of the one written
(book/guide/systems.md, "Many masses: repeated tables"):

1. in every string value (``name``, the points of ``between``, ``on``,
   ``decay``, a table's ``file``, at any depth) ``{i}`` is the index and
   ``{i+c}``, ``{i-c}`` (``c`` an integer) the index shifted; any other
   ``{...}``, or a brace left unmatched, is refused, and so is a shifted index
   below 0.  No other rule applies to a shifted index: a ``between`` that names
   a mass that does not exist (``b{i+1}`` at ``i = N`` when there are N
   masses) is the file's usual one-line error naming the element;
2. every number is the same for all N; an array of numbers is one number per
   table (N of them, in order); a grading table ``{ from = a, to = b }`` is
   ``a + (b - a)(i - 1)/(N - 1)``, ``a`` at ``i = 1`` and exactly ``b`` at
   ``i = N`` (with ``count = 1`` it needs ``a == b``);
3. arrays that are not all numbers (a ``curve``'s ``points``, ``between``) are
   the same for all N, their strings with the index put in;
4. two tables of one kind that name the same thing after expansion are
   refused, naming both.

Every refusal is a ``ValueError`` of one line naming the table (``[[element]]
3``, its place among the file's ``[[element]]`` tables) and the key.  The
counts are checked against the network's limits before any table is built.
"""

from __future__ import annotations

import math
import re
import sys
from typing import NamedTuple

__all__ = ["Origin", "count_of", "expand"]

_PLACEHOLDER = re.compile(r"\{([^{}]*)\}")
_INDEX = re.compile(r"\s*i\s*(?:([+-])\s*(\d+))?\s*")
_ANY_BRACE = re.compile(r"[{}]")


class Origin(NamedTuple):
    """Where an expanded table comes from: its ``number`` among the file's tables of its kind (from 1) and,
    for a table with ``count``, its index ``i`` (``None`` otherwise)."""

    number: int
    index: int | None = None

    def label(self, table: str) -> str:
        """``[[element]] 3`` or ``[[element]] 3, i = 17``."""
        return f"[[{table}]] {self.number}" + ("" if self.index is None else f", i = {self.index}")


def count_of(raw: dict) -> int:
    """The tables that ``raw`` stands for: its ``count`` (checked), 1 without one."""
    count = raw.get("count", 1)
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise ValueError(f"count must be an integer >= 1 (the number of tables it stands for), got {count!r:.40}")
    return count


def expand(raws: list[dict], table: str) -> list[tuple[Origin, dict]]:
    """The tables of one kind (``raws``, as written) with every ``count`` table expanded, each with its origin.

    Raises
    ------
    ValueError
        One line beginning ``[[table]] n: key:``: see the module's points 1 to 4.
    """
    out: list[tuple[Origin, dict]] = []
    for number, raw in enumerate(raws, 1):
        if "count" not in raw:
            out.append((Origin(number), raw))
            continue
        try:
            n = count_of(raw)
            columns = {key: _column(value, n, key) for key, value in raw.items() if key != "count"}
        except ValueError as err:
            raise ValueError(f"[[{table}]] {number}: {err}") from None
        out += [(Origin(number, i + 1), {key: c[i] for key, c in columns.items()}) for i in range(n)]
    _check_unique(out, table, raws)
    return out


def _column(value: object, n: int, key: str) -> list:
    """The N values of ``key`` (point 2): one for each ``i``."""
    if isinstance(value, str):
        return [_put_index(value, i, key) for i in range(1, n + 1)] if _ANY_BRACE.search(value) else [value] * n
    if isinstance(value, dict):
        if set(value) == {"from", "to"}:
            return _graded(value["from"], value["to"], n, key)
        columns = {k: _column(v, n, f"{key}.{k}") for k, v in value.items()}
        return [{k: c[i] for k, c in columns.items()} for i in range(n)]
    if isinstance(value, list):
        if value and all(_is_number(v) for v in value):
            if len(value) != n:
                raise ValueError(f"{key}: an array of {len(value)} numbers, but count = {n} needs one per table, {n}")
            return list(value)
        return [_nested(value, i, key) for i in range(1, n + 1)]
    return [value] * n


def _nested(value: object, i: int, key: str) -> object:
    """``value`` with the index ``i`` put into its strings at any depth (point 3)."""
    if isinstance(value, str):
        return _put_index(value, i, key)
    if isinstance(value, list):
        return [_nested(v, i, key) for v in value]
    if isinstance(value, dict):
        return {k: _nested(v, i, f"{key}.{k}") for k, v in value.items()}
    return value


def _put_index(text: str, i: int, key: str) -> str:
    """``text`` with ``{i}``, ``{i+c}``, ``{i-c}`` replaced by the index (point 1)."""

    def one(match: re.Match) -> str:
        form = _INDEX.fullmatch(match.group(1))
        if form is None:
            raise ValueError(
                f"{key}: unknown placeholder {match.group(0)!r:.40} in {text!r:.60}; "
                "expected {i}, {i+c} or {i-c} with c an integer"
            )
        sign, shift = form.groups()
        value = i + (int(shift) if sign == "+" else -int(shift) if sign else 0)
        if value < 0:
            raise ValueError(f"{key}: {match.group(0)!r} in {text!r:.60} is {value} at i = {i}; an index is >= 0")
        return str(value)

    out = _PLACEHOLDER.sub(one, text)
    if _ANY_BRACE.search(out):
        raise ValueError(f"{key}: {text!r:.60} has a brace that opens or closes no placeholder such as {{i}}")
    return out


def _graded(start: object, stop: object, n: int, key: str) -> list[float]:
    """A grading table's N values, linear in ``i``: ``start`` at ``i = 1``, ``stop`` exactly at ``i = n``."""
    if not (_is_number(start) and _is_number(stop) and math.isfinite(start) and math.isfinite(stop)):  # type: ignore[arg-type]
        raise ValueError(
            f"{key}: a grading {{ from = a, to = b }} takes two finite numbers, got {start!r:.20}, {stop!r:.20}"
        )
    a, b = float(start), float(stop)  # type: ignore[arg-type]
    if n == 1:
        if a != b:
            raise ValueError(f"{key}: a grading from {a:g} to {b:g} needs count >= 2 (a at i = 1, b at i = count)")
        return [a]
    step = (b - a) / (n - 1)
    values = [a + k * step for k in range(n - 1)] + [b]
    if not (math.isfinite(b - a) and all(map(math.isfinite, values))):  # b - a beyond the largest double: NaN at i = 1
        raise ValueError(
            f"{key}: a grading {{ from = {a:g}, to = {b:g} }} overflows: to - from is beyond the largest double "
            f"({sys.float_info.max:.4g}); take from and to nearer each other"
        )
    return values


def _is_number(value: object) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _check_unique(tables: list[tuple[Origin, dict]], table: str, raws: list[dict]) -> None:
    """Point 4: a name (``on`` for a force: not a name, several forces on a mass add) given twice, where at
    least one of the two comes from a ``count`` table; other repeats are the network's to refuse."""
    if table == "force":
        return
    seen: dict[object, Origin] = {}
    for origin, raw in tables:
        name = raw.get("name")
        if not isinstance(name, str):
            continue
        first = seen.setdefault(name, origin)
        if first is not origin and (first.index is not None or origin.index is not None):
            written = raws[origin.number - 1].get("name")
            raise ValueError(
                f"{origin.label(table)}: name: {written!r:.40} gives {name!r:.40}, "
                f"the name of {first.label(table)} too; names must differ after expansion"
            )
