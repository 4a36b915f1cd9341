"""Property-based checks of Algorithm 1's invariants over random valid parameters."""

from __future__ import annotations

import math

import numpy as np
import pytest
import references
from conftest import EPS, KERNELS, energy_scale
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import lumped as L
from lumped.solvers import backward_euler

SETTINGS = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])

masses = st.floats(0.1, 10.0)
stiffnesses = st.floats(1.0, 1000.0)
thresholds = st.floats(0.0, 5.0)
gammas = st.one_of(st.just(math.inf), st.floats(0.01, 100.0))
# no subnormal states: a run whose every force is subnormal is refused by design
# (check_magnitudes; tests/test_magnitudes.py), and one beside normal terms adds nothing
#: States in the package's domain: a run whose every force stays below the smallest normal
#: double (x0 = 0, v0 = 2.2e-308, no load) is refused by design (the magnitudes check), so a
#: nonzero state is drawn at least 1e-300 in size.
positions = st.floats(-1.0, 1.0, allow_subnormal=False).filter(lambda x: x == 0.0 or abs(x) >= 1e-300)
velocities = st.floats(-5.0, 5.0, allow_subnormal=False).filter(lambda v: v == 0.0 or abs(v) >= 1e-300)
forcings = st.one_of(
    st.none(),
    st.builds(
        L.SwitchedSine,
        amplitude=st.floats(-20.0, 20.0, allow_subnormal=False),
        omega=st.floats(0.0, 50.0),
        phase=st.floats(-math.pi, math.pi),
        until=st.floats(0.0, 2.0),
    ),
)
steps = st.sampled_from([1e-3, 5e-4, 2e-4])


@st.composite
def runs(draw):
    osc = L.Oscillator.bingham(draw(masses), draw(stiffnesses), draw(thresholds), draw(gammas))
    kwargs = dict(x0=draw(positions), v0=draw(velocities), force=draw(forcings))
    return osc, draw(steps), kwargs


@pytest.mark.parametrize("kernel", KERNELS)
@SETTINGS
@given(runs())
def test_stick_band_and_sign_relation(kernel, run):
    osc, dt, kwargs = run
    tr = L.backward_euler(osc, 1.0, dt, kernel=kernel, **kwargs)
    tau = osc.threshold
    stuck = tr.v[1:] == 0.0
    assert np.all(np.abs(tr.F_d[1:][stuck]) <= tau)  # lines 5-6: F_d = F~, |F~| <= tau
    f_tilde = references.line3(osc.mass, dt, tr.v[:-1], tr.F[1:], tr.F_s[:-1])  # eq. (15b)
    if tau == 0 and math.isinf(osc.dashpot.gamma):
        # tau = 0 with c = 0: the dashpot exerts no force at all, and eq. (16)
        # degenerates (its derivation needs F_d = s tau + c v != 0 off stick).
        assert np.all(tr.F_d[1:] == 0.0)
    else:
        assert np.array_equal(np.sign(tr.F_d[1:]), np.sign(f_tilde))  # eq. (16)
        # off the band v = phi(F_d): same sign as F_d (eq. 7a)
        moving = ~stuck
        assert np.array_equal(np.sign(tr.v[1:][moving]), np.sign(tr.F_d[1:][moving]))
    # and eq. (15a) itself, F_d + eta v = F~, to round-off of |F~| + tau
    # (plus an absolute 1e-290 for states near the subnormal range, where
    # rounding is no longer relative; hypothesis does draw v0 = 2.2e-308)
    eta = osc.mass / dt + osc.stiffness * dt
    gap = np.abs(tr.F_d[1:] + eta * tr.v[1:] - f_tilde)
    assert np.all(gap <= 8 * EPS * (np.abs(f_tilde) + tau) + 1e-290)


@pytest.mark.parametrize("kernel", KERNELS)
@SETTINGS
@given(runs())
def test_discrete_energy_balance_closes(kernel, run):
    # Round-off only: a few roundings of eps*E per step over N steps (see
    # test_algorithm1.test_discrete_energy_balance_closes_to_round_off).
    osc, dt, kwargs = run
    tr = L.backward_euler(osc, 1.0, dt, kernel=kernel, **kwargs)
    eb = tr.energy_balance()
    assert np.abs(eb.residual).max() <= 4 * EPS * energy_scale(eb) * len(tr.t) + 1e-300


@pytest.mark.skipif(backward_euler.KERNEL != "compiled", reason="C kernel not built: nothing to compare")
@SETTINGS
@given(runs())
def test_kernels_bit_identical(run):
    osc, dt, kwargs = run
    a = L.backward_euler(osc, 0.5, dt, kernel="compiled", **kwargs)
    b = L.backward_euler(osc, 0.5, dt, kernel="python", **kwargs)
    assert np.array_equal(a.as_array(), b.as_array())


@SETTINGS
@given(masses, stiffnesses, thresholds, positions, velocities, forcings, steps)
def test_coulomb_limit_of_huge_gamma(m, k, tau, x0, v0, force, dt):
    # Bound derived in test_algorithm1.test_coulomb_and_huge_gamma_agree:
    # N (c/eta + 2 eps) relative to the scale of v and x, c = 1e-12.
    kwargs = dict(x0=x0, v0=v0, force=force)
    a = L.backward_euler(L.Oscillator.bingham(m, k, tau, math.inf), 1.0, dt, **kwargs)
    b = L.backward_euler(L.Oscillator.bingham(m, k, tau, 1e12), 1.0, dt, **kwargs)
    n, eta = len(a.t), m / dt + k * dt
    rel = n * (1e-12 / eta + 2 * EPS)
    assert np.abs(a.v - b.v).max() <= rel * np.abs(a.v).max()
    assert np.abs(a.x - b.x).max() <= rel * np.abs(a.x).max()


@settings(max_examples=30, deadline=None)
@given(
    st.floats(0.2, 5.0),
    st.floats(5.0, 500.0),
    st.floats(0.1, 3.0),
    st.one_of(st.just(math.inf), st.floats(0.0, 0.9)),
    st.floats(-1.0, 1.0),
)
def test_exact_free_decay_follows_recurrence(m, k, tau, zeta, x0):
    # gamma from a damping ratio zeta < 1 (zeta = inf stands for Coulomb).
    gamma = math.inf if math.isinf(zeta) or zeta == 0 else 1.0 / (2 * zeta * math.sqrt(k * m))
    band = tau / k
    ref = references.free_decay(m, k, tau, gamma, x0)
    ref_t, ref_x = ref.times, ref.positions
    # a turning point within round-off of the band edge makes the count ill-posed
    assume(abs(abs(x0) - band) > 1e-9 * abs(x0))
    assume(np.all(np.abs(np.abs(ref_x) - band) > 1e-9 * abs(x0)))
    assume(len(ref_t) <= 200)
    osc = L.Oscillator.bingham(m, k, tau, gamma)
    sol = L.solve_exact(osc, (ref_t[-1] if len(ref_t) else 0.0) + 1.0, x0=x0)
    turning = [e for e in sol.events if e.kind in ("reversal", "stop")]
    assert len(turning) == len(ref_t)
    if len(ref_t):
        # 1e-12 relative on times, per test_exact's reasoning (<= 200 events)
        np.testing.assert_allclose([e.time for e in turning], ref_t, rtol=1e-12, atol=0)
        np.testing.assert_allclose([e.x[0] for e in turning], ref_x, rtol=0, atol=1e-12 * abs(x0))
    else:
        assert sol.rest_time == 0.0 and sol.rest_position == x0
