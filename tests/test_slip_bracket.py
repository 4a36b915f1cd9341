"""The slip step of a curve that underflows: ``SlipLaw.slip_speed``'s bracket when ``g(z/sigma)`` is below an ulp.

A contact of kinetic 0 and viscous 0 whose Stribeck fall has decayed past the smallest double (a Gaussian at
``s/v_s > 27``, an exponential past 745) has ``g(s) = 0`` exactly, so the step's equation ``g(s) + sigma s = z``
is ``sigma s = z``: ``s = z/sigma`` (a closed form).  Computed, ``sigma (z/sigma)`` may round an ulp below ``z``,
so the end ``z/sigma`` of the bracket ``(0, z/sigma]`` had the sign of its start and Brent's method refused
(``brentq: f(a) and f(b) must have opposite signs``, reaching the user from a run).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from lumped import Friction, Mass, Network, simulate_network
from lumped.laws.stribeck import StribeckLaw

#: A predictor and slope met by the run below (its first step): 1000 (z/1000) = z - 1 ulp.
Z, SIGMA = 1012.6205128205131, 1000.0


@pytest.mark.parametrize(("decay", "v_s"), [("gaussian", 0.01), ("exponential", 1e-3)])
def test_the_slip_speed_where_the_curve_underflows_is_z_over_sigma(decay: str, v_s: float) -> None:
    """Brent's root, on the widened bracket, is ``z/sigma`` to its tolerance (4 eps relative: roots.RTOL)."""
    law = StribeckLaw(1.0, 0.0, v_s, decay, 0.0)
    end = Z / SIGMA
    assert float(law.slip(end)) == 0.0 and SIGMA * end - Z < 0  # the edge: the old bracket's end is negative
    assert law.slip_speed(Z, SIGMA) == pytest.approx(end, rel=4 * np.finfo(float).eps, abs=0)


def test_a_gaussian_contact_beside_a_coulomb_pad_slows_by_the_pad_alone() -> None:
    """One 1 kg block at about 1 m/s on a Gaussian contact (kinetic 0, viscous 0: no force at that speed) and a
    Coulomb pad of 0.1 N: backward Euler gives ``v_n = v0 - 0.1 n dt`` (the Python step; the compiled ones
    refuse two contacts in parallel).  Each step rounds ``v`` to a few ulps (its root to 4 eps, the update to
    one): 10 steps, 64 eps of 1 m/s covers them."""
    v0 = 1.0128205128205128
    contacts = [
        Friction("g", ("m", "ground"), static=1.0, kinetic=0.0, stribeck_velocity=0.01, decay="gaussian"),
        Friction("pad", ("m", "ground"), static=0.1, kinetic=0.1),
    ]
    run = simulate_network(Network([Mass("m", 1.0, 0.0, v0)], contacts), 0.01, 1e-3, solver="python")
    assert math.isclose(run.t[-1], 0.01)
    np.testing.assert_allclose(run.velocities[:, 0], v0 - 0.1 * run.t, rtol=0, atol=64 * np.finfo(float).eps)
