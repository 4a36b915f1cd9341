"""Branches of steady sliding and of its limit cycles in a parameter (issue 34, :mod:`lumped.drivers.cycles.continuation`).

References: the closed-form stick-slip cycle of the static/kinetic belt (:func:`belt_cycle`) at every point of
the branch in belt speed; the Hopf speed of a falling law with viscous damping in closed form (Veraszto and
Stepan's ``V_H = ln((C0 - C) c_v/(b0 + b_s))/c_v``; Leine's law ``F_s/(1 + delta s)`` with a dashpot ``c``:
``V_H = (sqrt(F_s delta/c) - 1)/delta``); the stick-slip onset against an independent computation of the
sliding cycle whose largest speed is the belt's (SciPy's event-located DOP853 and Brent's method).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from lumped.drivers.cycles import continuation
from lumped.drivers.cycles.continuation import BranchPoint, continue_branches
from lumped.drivers.cycles.shooting import Cycle
from lumped.laws import Spring
from lumped.laws.stribeck import Friction
from lumped.model.network import Driver, Mass, Network
from lumped.solvers.closed_form_belt import belt_cycle
from lumped.solvers.event_driven_network import model

# -- the static/kinetic belt ----------------------------------------------------------------------------------

S_K = dict(mass=1.0, stiffness=1.0, static=1.0, kinetic=0.5)


def static_kinetic_belt(V: float = 0.2) -> Network:
    friction = Friction("f", ("belt", "m"), static=S_K["static"], kinetic=S_K["kinetic"])
    return Network([Mass("m", S_K["mass"])], [Spring("k", ("ground", "m"), S_K["stiffness"]), friction],
                   drivers=[Driver("belt", V)])


def cycles_of(rows: list[BranchPoint]) -> list[BranchPoint]:
    return [r for r in rows if r.branch == "cycle"]


class ClosedFormShooting:
    """A test double of the shooting (:mod:`lumped.drivers.cycles.shooting`) on the static/kinetic belt, from
    :func:`belt_cycle`: on the section ``x = kinetic/k`` a speed ``v >= V`` sticks (or slips forward and
    sticks) before it returns, so ``P(v) = V``, ``P' = 0`` and ``dP/dV = 1``; a speed ``v < V`` is a harmonic
    slip about the section that never reaches the belt's speed, ``P(v) = v``, ``P' = 1``: sliding is a centre."""

    @staticmethod
    def parts(net: Network) -> tuple[float, float, float]:
        mdl = model(net)
        return mdl.V, math.sqrt(mdl.K / mdl.m), mdl.contact.slip_limit / mdl.K

    def return_map(self, net: Network, v: float) -> tuple[float, float, float]:
        V, omega, _ = self.parts(net)
        if v >= V:
            return V, 0.0, belt_cycle(**S_K, velocity=V).period
        return v, 1.0, 2 * math.pi / omega

    def find_cycle(self, net: Network, v0: float, *, tol: float = 1e-12) -> Cycle:
        V, omega, centre = self.parts(net)
        if v0 >= V:
            c = belt_cycle(**S_K, velocity=V)
            return Cycle(c.period, V, np.array([c.x_max]), np.array([c.x_min]), c.stick_time, 1, 0.0,
                         np.array([0.0]), 0.0, True)
        a = v0 / omega
        return Cycle(2 * math.pi / omega, v0, np.array([centre + a]), np.array([centre - a]), 0.0, 0, V - v0,
                     np.array([1.0]), 1.0, False)

    def cycle_derivative_in(self, net: Network, v: float, parameter: str) -> float:
        assert parameter == "belt.velocity"
        return 1.0 if v >= model(net).V else 0.0


def test_the_static_kinetic_branch_in_belt_speed_is_the_closed_form_cycle_at_every_point(monkeypatch):
    """With the closed form for the shooting (a double), every point of the branch from 0.1 to 0.5 m/s is the
    stick-slip cycle at its own speed (not one of the harmonic cycles below it, which solve ``F = 0`` as well:
    the module's Notes), the first at 0.1 and the last at 0.5 exactly, at most 0.4/(points - 1) apart."""
    double = ClosedFormShooting()
    for name in ("return_map", "find_cycle", "cycle_derivative_in"):
        monkeypatch.setattr(continuation, name, getattr(double, name))
    rows = continue_branches(static_kinetic_belt(), "belt.velocity", 0.1, 0.5, points=21)
    cycles = cycles_of(rows)
    values = np.array([r.value for r in cycles])
    assert values[0] == 0.1 and values[-1] == 0.5
    assert np.all(np.diff(values) > 0) and np.all(np.diff(values) <= 0.02 * (1 + 1e-9))
    assert {r.kind for r in cycles} == {"regular"}
    for r in cycles:
        ref = belt_cycle(**S_K, velocity=r.value)
        assert (r.cycle.period, r.cycle.stick_time) == (ref.period, ref.stick_time)
        assert r.cycle.section == r.value
