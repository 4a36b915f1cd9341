"""The orders of the network methods per event type, against the ``exact`` network solver (issue 21).

The one-mass study (:mod:`lumped.studies.accuracy`) has a network
counterpart here: the two fixed-step methods that run networks, backward
Euler (:func:`lumped.simulate_network`) and ``event-locating``
(:mod:`lumped.solvers.event_capturing_network`), on three networks
(:data:`NETWORK_CASES`), at the steps :data:`NETWORK_STEPS`, against the
``exact`` network solver (closed forms per phase, which agree with the
independent stick-slip reference of ``tests/references.py`` to about
1e-12 m; its trapezoidal rival shares its modes and switching rule but not
its integration, and backward Euler shares nothing with it).

The events of a run, per friction element, are of four kinds
(:data:`NETWORK_KINDS`): ``slip to stick`` (a stop after which the element
sticks), ``reversal`` (a stop after which it slips back), ``stick to slip``
(a breakaway) and ``switch`` (a load going off, at a given time).  A method
that locates its events reports them (``Trajectory.events``); for backward
Euler they are read off the grid as the one-mass study reads them
(:func:`grid_events`).  The error of a kind is the largest time error of the
events paired in order, element by element (``nan`` if an element has not
as many events of the kind as the reference), except for ``switch``, whose
time is given: there it is the largest displacement error at that time.  ``max_x`` is the largest displacement
error over the grid.  The order of each is the slope of its logarithm
against ``log(dt)`` (:func:`~lumped.studies.accuracy.orders.fitted_slope`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from lumped.drivers.simulation import solve
from lumped.laws.dashpot_elements import Bingham
from lumped.laws.spring_elements import Spring
from lumped.model.forcing import SwitchedSine
from lumped.model.network import Load, Mass, Network
from lumped.model.problem import Problem
from lumped.model.trajectory import Trajectory
from lumped.studies.accuracy.events import grid_events as mass_grid_events
from lumped.studies.accuracy.orders import fitted_slope

__all__ = [
    "NETWORK_CASES",
    "NETWORK_KINDS",
    "NETWORK_METHODS",
    "NETWORK_STEPS",
    "grid_events",
    "located_events",
    "network_orders",
    "network_study",
]

#: The steps (s), coarse to fine.
NETWORK_STEPS = (2e-3, 1e-3, 5e-4, 2.5e-4)
#: The fixed-step methods that run networks.
NETWORK_METHODS = ("backward-euler", "event-locating")
#: The event kinds, then the displacement error over the grid.
NETWORK_KINDS = ("slip to stick", "reversal", "stick to slip", "switch")
#: The one-mass study's event names (:data:`lumped.studies.accuracy.events.KINDS`) as named here.
_NAMES = {"stop": "slip to stick", "breakaway": "stick to slip", "reversal": "reversal"}
#: The sine on the last mass: 10 N at 5 pi rad/s, off after 1 s (as in tests/test_network_references.py).
_SINE = SwitchedSine(10.0, 5 * math.pi, 0.0, 1.0)


def _chain(n: int, gamma: float, load: SwitchedSine | None) -> Network:
    """Masses 1, 1.5, 2 kg at 0.1, 0.2, 0.3 m; to the previous (the first: the ground) a spring of
    100, 120, 140 N/m and a Bingham element of threshold 1, 1.3, 1.6 N; the load on the last mass."""
    masses = [Mass(f"m{i}", 1.0 + 0.5 * i, 0.1 * (i + 1)) for i in range(n)]
    elements = []
    for i in range(n):
        a = "ground" if i == 0 else f"m{i - 1}"
        elements += [
            Spring(f"k{i}", (a, f"m{i}"), 100.0 + 20 * i),
            Bingham(f"b{i}", (a, f"m{i}"), 1.0 + 0.3 * i, gamma),
        ]
    return Network(masses, elements, [Load(f"m{n - 1}", load)] if load else [])


def _tree() -> Network:
    """m1 and m2 hang from m0, m0 from the ground; Coulomb and Bingham elements, released from rest."""
    masses = [Mass("m0", 1.0, 0.1), Mass("m1", 1.5, 0.25), Mass("m2", 0.8, -0.05)]
    elements = [
        Spring("k0", ("ground", "m0"), 100.0),
        Bingham("b0", ("ground", "m0"), 3.0, math.inf),
        Spring("k1", ("m0", "m1"), 120.0),
        Bingham("b1", ("m0", "m1"), 2.0, 2.0),
        Spring("k2", ("m2", "m0"), 80.0),
        Bingham("b2", ("m2", "m0"), 1.5, math.inf),
    ]
    return Network(masses, elements, [])


#: name -> (network, t_end): a Coulomb chain and a Bingham chain under the sine, a tree released from rest.
NETWORK_CASES: Mapping[str, tuple[Network, float]] = {
    "coulomb chain, sine": (_chain(3, math.inf, _SINE), 1.6),
    "bingham chain, sine": (_chain(2, 1.0, _SINE), 1.6),
    "tree, free": (_tree(), 1.2),
}


def located_events(tr: Trajectory) -> list[tuple[int, str, float]]:
    """``(element, kind, time)`` of the events a method located (its ``events``)."""
    names = tr.network.element_names
    out = []
    for ev in tr.events:
        if ev.kind == "switch":
            out.append((-1, "switch", ev.time))
        for name in ev.elements:
            e = names.index(name)
            kind = "stick to slip" if ev.kind == "breakaway" else "slip to stick" if ev.mode[e] == 0 else "reversal"
            out.append((e, kind, ev.time))
    return out


def grid_events(tr: Trajectory) -> list[tuple[int, str, float]]:
    """``(element, kind, time)`` read off the grid, element by element, as the one-mass study reads a
    mass's (:func:`lumped.studies.accuracy.events.grid_events`) from the element's rate, taken as 0
    where the element is flagged rigid: a reversal is a change of sign with at most one grid point
    at rest between, any other run at rest a stick (``slip to stick`` at its first point,
    ``stick to slip`` at its last)."""
    first, second = tr.network.incidence()
    v = np.column_stack([tr.velocities, np.zeros(tr.t.size)])  # the ground's column last, as incidence() counts
    x = np.column_stack([tr.positions, np.zeros(tr.t.size)])
    out = []
    for e, el in enumerate(tr.network.elements):
        if not el.rigid_capable:
            continue
        w = np.where(tr.rigid[:, e], 0.0, v[:, second[e]] - v[:, first[e]])
        for ev in mass_grid_events(tr.t, x[:, second[e]] - x[:, first[e]], w):
            out.append((e, _NAMES[ev.kind], ev.time))
    return out


def _errors(tr: Trajectory, ref: Trajectory, dt: float) -> dict[str, float]:
    """Per kind, the largest time error of the events paired in order, element by element (``nan`` if an
    element has not as many of a kind as the reference: the motion took another course); ``switch``:
    the displacement error at its time; ``max_x``: the largest displacement error over the grid."""
    mine, theirs = (located_events(tr) if tr.events else grid_events(tr)), located_events(ref)
    out = {"max_x": float(np.max(np.abs(tr.positions - ref.positions)))}
    for kind in NETWORK_KINDS:
        wanted = [(e, t) for e, k, t in theirs if k == kind]
        if not wanted:
            continue
        if kind == "switch":
            rows = [int(round(t / dt)) for _, t in wanted]
            out[kind] = max(float(np.max(np.abs(tr.positions[r] - ref.positions[r]))) for r in rows)
            continue
        errors = []
        for e in sorted({e for e, _ in wanted}):
            want = [t for f, t in wanted if f == e]
            got = [t for f, k, t in mine if f == e and k == kind]
            errors += [abs(a - b) for a, b in zip(got, want)] if len(got) == len(want) else [math.nan]
        out[kind] = max(errors)
    return out


def network_study(steps: tuple[float, ...] = NETWORK_STEPS) -> dict[str, dict[str, dict[str, list[float]]]]:
    """``[case][method][quantity]``: the errors at each of ``steps``, as :func:`_errors` defines them."""
    out: dict[str, dict[str, dict[str, list[float]]]] = {}
    for name, (net, t_end) in NETWORK_CASES.items():
        problem = Problem(net, t_end)
        for dt in steps:
            ref = solve(problem, dt, method="exact")
            for method in NETWORK_METHODS:
                errors = _errors(solve(problem, dt, method=method), ref, dt)
                table = out.setdefault(name, {}).setdefault(method, {})
                for quantity, value in errors.items():
                    table.setdefault(quantity, []).append(value)
    return out


def network_orders(
    study: Mapping[str, Mapping[str, Mapping[str, list[float]]]], steps: tuple[float, ...] = NETWORK_STEPS
) -> dict[str, dict[str, list[float]]]:
    """``[method][quantity]``: the smallest and largest fitted order over the cases (``[]`` if none)."""
    out: dict[str, dict[str, list[float]]] = {}
    for method in NETWORK_METHODS:
        for quantity in (*NETWORK_KINDS, "max_x"):
            found = [fitted_slope(steps, c[method][quantity]) for c in study.values() if quantity in c[method]]
            finite = [o for o in found if math.isfinite(o)]
            out.setdefault(method, {})[quantity] = [min(finite), max(finite)] if finite else []
    return out
