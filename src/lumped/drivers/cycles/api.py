"""Limit cycles of one mass on a belt and their branches: :func:`cycles`, the API of ``python -m lumped cycles``.

:func:`cycles` takes a :class:`~lumped.model.network.Network` (a system file
read by :func:`lumped.model.files.load_system`) in the scope of
:func:`~lumped.drivers.cycles.equilibria.check_autonomous` and returns a
:class:`CyclesTable`, one row per equilibrium or cycle, in the columns the
issue names: the varied parameter (with ``vary``), ``branch``
(``equilibrium`` or ``cycle``), ``period`` (s), ``max_<mass>`` and
``min_<mass>`` (m; the equilibrium's position for an equilibrium),
``stick_time`` (s per period stuck), ``stable``, ``max_multiplier`` (a cycle's
largest Floquet multiplier in modulus, the trivial one left out),
``max_real_part`` (an equilibrium's largest real part of an eigenvalue, 1/s)
and ``kind`` (``regular``, ``hopf``, ``fold``, ``stick-slip-onset``,
``stick-change``, ``period-doubling``).  A value that does not apply to a row
(an equilibrium's period, stick time and multiplier; a cycle's real part) is
``nan`` in the table and an empty cell in the command's CSV.

Without ``vary``: the equilibrium's row, then one row per cycle found at the
file's parameters: from the file's initial state by a long run (event-driven,
:func:`~lumped.solvers.event_driven_network.solve_contact`) until the
crossings of the section settle (:data:`SETTLE_RTOL`), then Newton on the
return map (:func:`~lumped.drivers.cycles.shooting.find_cycle`); from the
branch born at the nearest Hopf point in the belt's speed within a factor
:data:`HOPF_REACH` of the file's (its cycle nearest the file's speed, then
Newton); and from the belt's speed ``V > 0`` (a cycle stuck as it crosses the
section crosses it at ``V`` exactly: its fixed point, whatever the length of
its stick, which the long run's natural periods may not reach: 5e6 s on
``examples/belt.toml`` at 2e-7 m/s).  With ``vary = (name, start, stop)``: the branches of
:func:`~lumped.drivers.cycles.continuation.continue_branches` over the range and, varying the belt's speed, the
cycles inside it of a branch born at a Hopf point just outside it (:func:`_hopf_branches_into`).

A belt running backwards (``V < 0``) is the mirror image ``x -> -x`` of one running forwards
(:func:`~lumped.drivers.cycles.equilibria.mirrored`) and is computed so: its rows are the forward belt's mirrored,
exactly.  The work is bounded: each branch walks at most
:data:`~lumped.drivers.cycles.continuation.RETURNS_PER_POINT` returns a row (the Hopf branch without ``vary``,
:data:`HOPF_RETURNS`), and a branch cut there, a start that finds no cycle or a Hopf point with no small cycle off
it is said in the summary: no failure becomes a silent "0 cycles".
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np

from lumped.drivers.cycles.equilibria import (
    Equilibrium,
    belt_sign,
    check_autonomous,
    hopf_points,
    mirror_equilibrium,
    mirrored,
    parameter_member,
    steady_sliding,
)
from lumped.drivers.cycles.shooting import Cycle, find_cycle, mirror_cycle
from lumped.model.network import Network
from lumped.model.system_parameters import system_parameters, with_values
from lumped.numerics import validate
from lumped.numerics.roots import brentq
from lumped.solvers.event_driven_network import March, model, solve_contact

__all__ = [
    "COLUMNS",
    "HOPF_REACH",
    "HOPF_RETURNS",
    "MAX_POINTS",
    "SETTLE_RTOL",
    "CyclesTable",
    "belt_parameter",
    "cycles",
    "request",
]

#: The columns after the varied parameter's, with ``max_<mass>``, ``min_<mass>`` in place of ``extremes``.
COLUMNS = ("branch", "period", "extremes", "stick_time", "stable", "max_multiplier", "max_real_part", "kind")
#: The most rows asked of a continuation (as ``lumped response``'s).
MAX_POINTS = 10_000
#: The long run settles when two successive upward crossings of the section differ in speed by this, relative
#: to the belt's speed: Newton on the return map then starts within its basin (it refines to its own tolerance).
SETTLE_RTOL = 1e-6
#: The long run goes on in pieces of :data:`SETTLE_PERIODS` natural periods, at most :data:`SETTLE_PIECES` of them.
SETTLE_PERIODS, SETTLE_PIECES = 20, 50
#: The Hopf points looked for without ``vary``: belt speeds from ``V / HOPF_REACH`` to ``V * HOPF_REACH``.
HOPF_REACH = 10.0
#: The returns the walk along the Hopf branch may take without ``vary``
#: (:func:`~lumped.drivers.cycles.shooting.returns_budget`): ``examples/stribeck_belt.toml``'s takes 215 to its
#: speed; a branch crawling (the same file with ``decay = "gaussian"``: its slip-only cycles' multiplier passes
#: 900 and the steps shrink as the orbits beside them stick) is cut there, some 15 s.
HOPF_RETURNS = 300


class CyclesTable(NamedTuple):
    """The table (column name -> array: ``branch`` and ``kind`` as str, ``stable`` as bool, the rest float with
    ``nan`` where a value does not apply) and a one-line summary."""

    columns: dict[str, np.ndarray]
    summary: str


class Request(NamedTuple):
    """Checked arguments: the network, the varied parameter's name and range (``None``) and the rows."""

    network: Network
    vary: tuple[str, float, float] | None
    points: int


def belt_parameter(network: Network) -> str:
    """The default parameter to vary: the velocity of the friction contact's driven point, ``<driver>.velocity``
    (``belt.velocity``), for a file with one driver; a ``ValueError`` naming the drivers otherwise."""
    names = [d.name for d in network.drivers]
    if len(names) != 1:
        raise ValueError(f"vary: the system has {len(names)} driven points ({', '.join(names)}): name the parameter")
    return f"{names[0]}.velocity"


def request(network: Network, vary: tuple[str, float, float] | None = None, points: int = 50) -> Request:
    """:func:`cycles`'s arguments checked before any work, or a one-line ``ValueError`` naming the argument:
    the system in scope (:func:`check_autonomous`, ``cycles: ...``), ``points`` from 2 to :data:`MAX_POINTS`,
    ``vary`` a parameter of the file with a finite range ``start < stop`` whose ends the file's items accept and
    whose systems are in scope (a belt's speed not reaching 0)."""
    check_autonomous(network)
    points = validate.positive_int("points", points)
    if not 2 <= points <= MAX_POINTS:
        raise ValueError(f"points: between 2 and {MAX_POINTS} rows, got {points}")
    if vary is None:
        return Request(network, None, points)
    if not (isinstance(vary, tuple) and len(vary) == 3 and isinstance(vary[0], str)):
        raise ValueError(f"vary: expected (name, start, stop), got {vary!r:.60}")
    name, start, stop = vary
    if not all(
        isinstance(end, (int, float, np.integer, np.floating)) and not isinstance(end, bool) for end in (start, stop)
    ):
        # no conversion: a string is the command line's to parse (--vary), not the API's to guess at
        raise ValueError(f"vary: START and STOP must be real numbers, got {start!r:.20}:{stop!r:.20}")
    start, stop = float(start), float(stop)
    if not (math.isfinite(start) and math.isfinite(stop) and start < stop):
        raise ValueError(f"vary: START:STOP must be finite with START < STOP, got {start!r}:{stop!r}")
    if np.unique(np.linspace(start, stop, points)).size < points:  # the equilibria's rows would repeat values
        raise ValueError(
            f"vary: {start!r}:{stop!r} holds fewer than {points} distinct values; widen it or give fewer points"
        )
    param, ends = parameter_member(network, name, start, stop)
    if param.table == "mass" and param.key != "mass":
        raise ValueError(f"vary: {name} is the initial state, on which neither steady sliding nor a cycle depends")
    for value, member in zip((start, stop), ends, strict=True):
        try:
            check_autonomous(member)
        except ValueError as err:
            raise ValueError(f"vary: at {name} = {value:g}: {str(err).removeprefix('cycles: ')}") from None
    return Request(network, (name, start, stop), points)


def cycles(
    network: Network,
    *,
    vary: tuple[str, float, float] | None = None,
    points: int = 50,
    progress: Callable[[int, int], None] | None = None,
) -> CyclesTable:
    """Steady sliding and the limit cycles of ``network`` (module docstring), as a table.

    Parameters
    ----------
    network : Network
        One mass on a friction contact on a belt (:func:`check_autonomous`).
    vary : (str, float, float), optional
        ``(name, start, stop)``: a parameter of the file (``belt.velocity``, ``element.key``, ``mass.key``;
        :func:`belt_parameter` gives the belt's) and its range, ``start < stop``.
    points : int
        2 to :data:`MAX_POINTS`: about the rows of each branch (with ``vary``).
    progress : callable, optional
        Called as ``progress(done, total)``.

    Returns
    -------
    CyclesTable

    Raises
    ------
    ValueError
        One line naming the argument, before any work (:func:`request`).
    """
    req = request(network, vary, points)
    if progress is not None and not callable(progress):
        raise ValueError(f"progress must be callable as progress(done, total), got {type(progress).__name__}")
    if req.vary is None:
        rows, notes = _rows_at_file(req.network, req.points, progress)
        summary = "; ".join([_summary(rows, None), *notes])
        return CyclesTable(_table(rows, network.mass_names, None), summary)
    from lumped.drivers.cycles.continuation import continue_branches

    name, start, stop = req.vary
    notes: list[str] = []  # what ended a branch early or found none: the summary says it
    branch = continue_branches(req.network, name, start, stop, req.points, progress, notes=notes)
    branch += _hopf_branches_into(req.network, name, start, stop, req.points, notes)
    rows = [(p.value, p.branch, p.equilibrium if p.branch == "equilibrium" else p.cycle, p.kind) for p in branch]
    return CyclesTable(_table(rows, network.mass_names, name), "; ".join([_summary(rows, name), *notes]))


Row = tuple[float, str, Any, str]  # (value, branch, Equilibrium or Cycle, kind)


def _hopf_branches_into(network: Network, name: str, start: float, stop: float, points: int, notes: list[str]) -> list:
    """The cycles, inside ``[start, stop]``, of the branch born at the nearest Hopf point in the belt's speed just
    outside the range (within a factor :data:`HOPF_REACH` of its nearer end, on the range's side of 0): a
    subcritical branch (``examples/stribeck_belt.toml``'s slip-only cycles, born at 0.52983 m/s) reaches speeds
    far from its Hopf point, and a range that leaves the point out would otherwise report none of them.  The
    walk starts at that point and takes at most :data:`HOPF_RETURNS` returns outside the range (its rows there are
    not reported); none for another parameter, a range through 0, or no such point."""
    if name != belt_parameter(network) or start * stop <= 0:
        return []
    from lumped.drivers.cycles.continuation import continue_branches

    inside = hopf_points(network, name, start, stop)  # the range's own walk follows these
    near, far = sorted((start, stop), key=abs)
    chosen: list[float] = []
    for end, side, other in ((near, near / HOPF_REACH, far), (far, far * HOPF_REACH, near)):
        # from the reach's end across the range, so that a point on the range's end (which a search that stops
        # there does not see) is found too
        found = hopf_points(network, name, *sorted((side, other)))  # each search locates a point to some ulps
        hopf = [h for h in found if all(abs(h - g) > 1e-9 * abs(g) for g in inside + chosen)]
        if hopf:
            chosen.append(min(hopf, key=lambda g: abs(g - end)))
    out = []
    for h in chosen:
        end = min((start, stop), key=lambda e: abs(e - h))
        margin = 1e-3 * max(stop - start, abs(h - end), 1e-6 * abs(h))  # the point inside the walk's range
        lo, hi = min(h - margin, start), max(h + margin, stop)
        walked = continue_branches(  # the Hopf branch alone, over the range and the way to it
            network, name, lo, hi, points, None, start_branch=False, returns=HOPF_RETURNS, notes=notes
        )
        out += [p for p in walked if p.branch == "cycle" and start <= p.value <= stop]
    return out


def _rows_at_file(network: Network, points: int, progress: Callable | None) -> tuple[list[Row], list[str]]:
    """The equilibrium's row, then the cycles found from the initial state and from the Hopf branch; and what
    was not found, in words, for the summary.  A belt running backwards is computed as its mirror image
    (:func:`~lumped.drivers.cycles.equilibria.mirrored`), and its rows mirrored back."""
    if belt_sign(network) < 0:
        rows, notes = _rows_at_file(mirrored(network), points, progress)
        mirror = lambda item: mirror_equilibrium(item) if isinstance(item, Equilibrium) else mirror_cycle(item)
        return [(value, branch, mirror(item), kind) for value, branch, item, kind in rows], notes
    tick = progress or (lambda done, total: None)
    eq = steady_sliding(network)
    rows: list[Row] = [(math.nan, "equilibrium", eq, "regular")]
    notes = []
    starts = []
    tick(0, 3000)
    v0, note = _settled_crossing(network, eq)
    if note:
        notes.append(note)
    starts.append(("the initial state", v0))
    tick(2000, 3000)
    walked = None if progress is None else lambda done, total: progress(2000 + min(done, 999), 3000)
    starts.append(("the Hopf branch", _hopf_branch_crossing(network, points, notes, walked)))
    belt = model(network).V
    starts.append(("the belt's speed", belt if belt > 0 else None))  # a cycle stuck at the section crosses it at V
    for i, (where, v) in enumerate(starts):
        if v is None or any(v == w for _, w in starts[:i]):  # none, or an earlier start's (its cycle is a row)
            continue
        try:
            cycle = find_cycle(network, v)
        except ValueError as err:  # Newton's failure: no cycle vouched for from this start
            # find_cycle names its own argument (``v0: ...``, ``v: ...``); the user gave neither
            notes.append(f"from {where}: {str(err).split(': ', 1)[-1]}")
            continue
        if not any(_same(cycle, row[2]) for row in rows[1:]):
            rows.append((math.nan, "cycle", cycle, "regular"))
    tick(3000, 3000)
    return rows, notes


def _same(a: Cycle, b: Cycle) -> bool:
    """Two cycles found from two starts are one if they stick as often and cross the section at the same speed
    in the same period (each to Newton's 1e-12 relative, with a margin of 1e4 for the two starts).

    The speed alone does not tell them apart: a stick-slip cycle whose stick is short crosses the section at
    the belt's speed ``V`` and a slip-only cycle grazing the stuck state crosses it just below (on the
    static/kinetic belt with ``static - kinetic = 1e-6 K``, stuck 1e-5 s a period, both within 1e-11 of ``V``);
    their stick phases (1 and 0) and their periods (``2 pi + 1e-5`` s and ``2 pi`` s) differ."""
    close = lambda p, q: abs(p - q) <= 1e-8 * max(abs(p), abs(q))
    return a.stick_phases == b.stick_phases and close(a.section, b.section) and close(a.period, b.period)


def _settled_crossing(network: Network, eq: Equilibrium) -> tuple[float | None, str]:
    """The speed at which the long run from the file's initial state crosses the section ``x = x*`` upward, once
    two successive crossings agree to :data:`SETTLE_RTOL` of the belt's speed, and ``""``; ``None`` and what the run
    did instead: it settles on steady sliding (within ``SETTLE_RTOL`` of the scale ``|x*| + static/K`` of ``x*``
    over its last natural period)
    or it does not settle in :data:`SETTLE_PIECES` pieces."""
    mdl = model(network)
    x_star, speed = float(eq.position[0]), abs(mdl.V)
    span = SETTLE_PERIODS * 2 * math.pi * math.sqrt(mdl.m / mdl.K)
    scale = abs(x_star) + mdl.contact.static / mdl.K
    net, last = network, None
    for _ in range(SETTLE_PIECES):
        march = solve_contact(net, span, rtol=1e-10)
        t = np.linspace(0.0, span, 200 * SETTLE_PERIODS + 1)
        x, v = march.state(t)
        tail = x[t > span - span / SETTLE_PERIODS]
        if np.max(np.abs(tail - x_star)) < SETTLE_RTOL * scale:  # at x*, not merely slow (a block riding a slow belt)
            return None, "the run from the initial state settles on steady sliding"
        for v_cross in _crossings(march, t, x, v, x_star):
            if last is not None and abs(v_cross - last) <= SETTLE_RTOL * speed:
                return v_cross, ""
            last = v_cross
        mass = net.masses[0]
        params = system_parameters(net, [f"{mass.name}.x0", f"{mass.name}.v0"])
        net = with_values(net, params, [float(x[-1]), float(v[-1])])
    periods = SETTLE_PERIODS * SETTLE_PIECES
    return None, f"the run from the initial state does not settle on a cycle in {periods} natural periods"


def _crossings(march: March, t: np.ndarray, x: np.ndarray, v: np.ndarray, x_star: float) -> list[float]:
    """The speeds at the upward crossings of ``x = x*`` in a run sampled at ``t``, each located by Brent's
    method on the continuous motion."""
    out = []
    for i in np.flatnonzero((x[:-1] < x_star) & (x[1:] >= x_star) & (v[1:] > 0)):
        f = lambda s: float(march.state(np.array([s]))[0][0]) - x_star
        when = brentq(f, float(t[i]), float(t[i + 1]))
        out.append(float(march.state(np.array([when]))[1][0]))
    return out


def _hopf_branch_crossing(network: Network, points: int, notes: list[str], progress: Callable | None) -> float | None:
    """The section speed of the cycle nearest the file's belt speed on the branch born at the nearest Hopf point
    in that speed (within :data:`HOPF_REACH`), or ``None`` where there is none: a branch that does not come
    within the range (a subcritical Hopf point's, on the side away from the file's speed) has only its cycle of
    zero amplitude, which is steady sliding, no start.  The walk takes at most :data:`HOPF_RETURNS` returns (a
    branch crawling with its steps is cut there and the notes say so), its progress reported as it goes."""
    name = belt_parameter(network)
    (param,) = system_parameters(network, [name])
    V = param.value
    lo, hi = sorted((V / HOPF_REACH, V * HOPF_REACH))
    hopf = hopf_points(network, name, lo, hi)
    if not hopf:
        return None
    nearest = min(hopf, key=lambda h: abs(h - V))
    if nearest == V:
        return None
    from lumped.drivers.cycles.continuation import continue_branches

    start, stop = sorted((nearest, V))
    rows = continue_branches(  # the Hopf branch alone
        network, name, start, stop, points, progress, start_branch=False, returns=HOPF_RETURNS, notes=notes
    )
    # its cycles strictly inside the range: not those at the Hopf point (its zero amplitude's, steady sliding, and the
    # branch's point at the range's end there), nor beyond it: the first small cycle of a subcritical branch lies on
    # the side away from V, and Newton from any of them at V would come to steady sliding
    branch = [p for p in rows if p.branch == "cycle" and (start < p.value < stop or p.value == V)]
    if not branch:
        return None
    return float(min(branch, key=lambda p: abs(p.value - V)).cycle.section)


def _table(rows: list[Row], masses: list[str], vary: str | None) -> dict[str, np.ndarray]:
    """The columns of :data:`COLUMNS` (``nan`` where a value does not apply)."""
    nan = math.nan
    cols: dict[str, list] = {name: [] for name in ([vary] if vary else [])}
    cols |= {"branch": [], "period": []}
    cols |= {f"{e}_{m}": [] for m in masses for e in ("max", "min")}
    cols |= {"stick_time": [], "stable": [], "max_multiplier": [], "max_real_part": [], "kind": []}
    for value, branch, item, kind in rows:
        if vary:
            cols[vary].append(value)
        equilibrium = branch == "equilibrium"
        cols["branch"].append(branch)
        cols["period"].append(nan if equilibrium else item.period)
        for i, m in enumerate(masses):
            cols[f"max_{m}"].append(float(item.position[i] if equilibrium else item.x_max[i]))
            cols[f"min_{m}"].append(float(item.position[i] if equilibrium else item.x_min[i]))
        cols["stick_time"].append(nan if equilibrium else item.stick_time)
        cols["stable"].append(bool(item.stable) and kind != "hopf")  # a pair on the imaginary axis: marginal
        cols["max_multiplier"].append(nan if equilibrium else item.max_multiplier)
        cols["max_real_part"].append(item.max_real_part if equilibrium else nan)
        cols["kind"].append(kind)
    text = ("branch", "kind")
    return {k: np.array(v, dtype=str if k in text else bool if k == "stable" else float) for k, v in cols.items()}


def _summary(rows: list[Row], vary: str | None) -> str:
    """``1 equilibrium (stable), 2 cycles (1 stable); changes: 1 hopf, 1 fold``."""
    eq = [r for r in rows if r[1] == "equilibrium"]
    cyc = [r for r in rows if r[1] == "cycle"]
    located = dict.fromkeys((r[3], r[0]) for r in rows if r[3] != "regular")  # a Hopf point ends both branches
    kinds = [kind for kind, _ in located]
    changes = ", ".join(f"{kinds.count(k)} {k}" for k in dict.fromkeys(kinds)) or "none"
    if vary is None:
        state = "stable" if eq[0][2].stable else "not stable"
        found = f"{len(cyc)} cycle{'s' * (len(cyc) != 1)} ({sum(r[2].stable for r in cyc)} stable)"
        return f"steady sliding at x = {eq[0][2].position[0]:.6g} m ({state}); {found}"
    return f"{len(eq)} equilibria and {len(cyc)} cycles in {vary}; changes: {changes}"
