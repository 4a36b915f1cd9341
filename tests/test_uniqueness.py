"""The dt bound of :mod:`lumped.solvers.uniqueness` on chains at the edge of its two branches.

A uniform chain of ``n`` masses ``m`` joined by falling contacts (each falling by ``lambda``) and each held to
the ground by another (falling by ``lambda_g``), no springs: ``A(dt) = m/dt I - lambda P - lambda_g I`` with ``P``
the path's Laplacian, whose largest eigenvalue is ``2 + 2 cos(pi/n)``.  So the exact bound is
``dt* = m / (lambda (2 + 2 cos(pi/n)) + lambda_g)`` (a closed form independent of any factorisation), and the
Gershgorin bound of a larger network, where an inner mass carries ``2 lambda`` from each of its two links, is
``dt_G = m / (4 lambda + lambda_g)``: below ``dt*`` by the relative
``lambda (2 - 2 cos(pi/n)) / (4 lambda + lambda_g)``.
"""

from __future__ import annotations

import math

import pytest

from lumped import Friction, Mass, Network
from lumped.solvers.uniqueness import EXACT_MASSES, check_step, largest_step

LINK = {"static": 2.0, "kinetic": 1.0, "stribeck_velocity": 0.1}
FLOOR = {"static": 3.0, "kinetic": 1.0, "stribeck_velocity": 0.5}
#: The bisection ends within 1e-12 relative of the test's edge; the L D L^T of the tridiagonal A moves that edge
#: by a few ulps of m/dt (its backward error over a band of three), far below: 1e-11 covers both.
REL = 1e-11


def chain(n: int) -> tuple[Network, float, float]:
    """The uniform chain of ``n`` 1 kg masses, and its links' and floor contacts' falls."""
    masses = [Mass(f"m{i}", 1.0) for i in range(n)]
    links = [Friction(f"c{i}", (f"m{i - 1}", f"m{i}"), **LINK) for i in range(1, n)]
    floors = [Friction(f"g{i}", (f"m{i}", "ground"), **FLOOR) for i in range(n)]
    return Network(masses, links + floors), links[0].steepest_fall, floors[0].steepest_fall


def exact_bound(n: int, lam: float, lam_g: float) -> float:
    """``dt*`` of the module's docstring (m = 1 kg)."""
    return 1.0 / (lam * (2.0 + 2.0 * math.cos(math.pi / n)) + lam_g)


def test_the_largest_exact_network_has_the_closed_form_bound():
    """At ``EXACT_MASSES`` masses the bound is the exact test of ``A(dt)``: the chain's closed form (a 2000-mass
    chain, refused in a fraction of a second by the sparse factorisation; ``benchmarks/bench_uniqueness.py``)."""
    net, lam, lam_g = chain(EXACT_MASSES)
    dt_star = exact_bound(EXACT_MASSES, lam, lam_g)
    assert largest_step(net, 1.0) == pytest.approx(dt_star, rel=REL)
    check_step(net, dt_star * (1 - 1e-9))
    with pytest.raises(ValueError, match=r"^dt: .* too long .* take dt <= 0\.0227 s$"):
        check_step(net, dt_star * (1 + 1e-9))


def test_one_mass_more_takes_the_gershgorin_bound_below_the_exact_one():
    """At ``EXACT_MASSES + 1`` masses the bound is Gershgorin's ``dt_G``, safe (below ``dt*``) by the closed
    relative margin of the module's docstring, 5e-7 here: a step between the two is refused."""
    n = EXACT_MASSES + 1
    net, lam, lam_g = chain(n)
    dt_g, dt_star = 1.0 / (4.0 * lam + lam_g), exact_bound(n, lam, lam_g)
    assert largest_step(net, 1.0) == pytest.approx(dt_g, rel=REL)
    margin = lam * (2.0 - 2.0 * math.cos(math.pi / n)) / (4.0 * lam + lam_g)
    # each closed form is exact to a few ulps (1e-15), a 1e-9 part of the 5e-7 margin
    assert dt_star / dt_g - 1.0 == pytest.approx(margin, rel=1e-8)
    check_step(net, dt_g * (1 - 1e-9))
    with pytest.raises(ValueError, match=r"take dt <= 0\.0227 s$"):
        check_step(net, dt_g * (1 + 1e-9))  # admissible by the exact test (dt* is 5e-7 higher), refused
