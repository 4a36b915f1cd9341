"""The ``event-driven`` method on a belt fast against the mass (issue 41): pure slip to its closed form.

One mass ``m`` on a spring ``k`` to the wall, on a friction contact (static ``F_s``, kinetic ``F_k``) with a belt
at ``V``.  From rest the contact slips backwards (``u = v - V < 0`` while ``|v| < |V|``), the kinetic force drags
the mass towards the belt's side, and ``m x'' + k x = sgn(V) F_k``:

    x(t) = sgn(V) (F_k / k) (1 - cos(w t)),    v(t) = sgn(V) (F_k / k) w sin(w t),    w = sqrt(k / m).

The speed never passes ``F_k w / k``, so on a belt faster than that the contact never sticks: pure slip for
ever, whatever ``V``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from cli_run import run_lumped

import lumped as L
from lumped.model.files import parse_system
from lumped.solvers.event_driven import _ATOL_FACTOR, DEFAULT_RTOL
from lumped.solvers.event_driven_network import solve_contact

T_END = 10.0


def belt_system(V: float, static: float, kinetic: float, *, m: float = 1.0, k: float = 1.0, v0: float = 0.0) -> str:
    """The system file of the module docstring, the mass at rest at ``x = 0`` (or moving at ``v0``)."""
    return f"""
[[mass]]
name = "m"
mass = {m!r}
v0 = {v0!r}

[[driver]]
name = "belt"
velocity = {V!r}

[[element]]
name = "spring"
kind = "spring"
between = ["ground", "m"]
stiffness = {k!r}

[[element]]
name = "fric"
kind = "friction"
between = ["belt", "m"]
static = {static!r}
kinetic = {kinetic!r}
"""


def pure_slip(t: np.ndarray, V: float, kinetic: float, m: float, k: float, v0: float = 0.0):
    """The closed form (module docstring), from ``x = 0`` with ``v0``: ``x``, ``v``."""
    w, c = math.sqrt(k / m), math.copysign(kinetic / k, V)
    return c * (1 - np.cos(w * t)) + v0 / w * np.sin(w * t), c * w * np.sin(w * t) + v0 * np.cos(w * t)


def global_bound(motion, static: float, kinetic: float, m: float, k: float, amplitude: float, speed: float):
    """Bounds on the errors of ``x`` and ``v`` at ``rtol = DEFAULT_RTOL``, derived from DOP853's error control.

    An accepted step's error estimate has RMS below 1 in units of ``sc = atol + rtol |y|`` (dop853's Notes), so
    each component errs locally by less than ``sqrt(2) sc`` (the estimate, of the embedded lower-order pair,
    bounds the order-8 step's true error: the premise of every such control).  The error obeys the
    homogeneous oscillator ``m e'' + k e = 0``, whose flow keeps the energy norm ``sqrt(k ex^2 + m ev^2)``: the
    global error in that norm is at most the sum of the local ones over the ``N`` steps, and ``|ex| <= norm /
    sqrt(k)``, ``|ev| <= norm / sqrt(m)``.  ``atol`` is the method's: ``1e-3 rtol`` times the band
    ``static / k`` (velocities: over ``sqrt(k m)``).
    """
    rtol = DEFAULT_RTOL
    (phase,) = motion.phases  # pure slip: one phase, no event
    steps = len(phase.motion.steps) - 1
    sc_x = _ATOL_FACTOR * rtol * static / k + rtol * amplitude
    sc_v = _ATOL_FACTOR * rtol * static / math.sqrt(k * m) + rtol * speed
    norm = steps * math.sqrt(2) * math.hypot(math.sqrt(k) * sc_x, math.sqrt(m) * sc_v)
    return norm / math.sqrt(k), norm / math.sqrt(m)


# (static, kinetic, m, k): metre-scaled; the scaled-down contact (1e-15 N); micrometre and kilometre
# systems (a band of 1e-6 m and 1e3 m; the kilometre one with m = 4, k = 1e-3 so that w = 1/63 rad/s).
SCALES = {
    "metre": (1.0, 0.5, 1.0, 1.0),
    "femto-newton": (1e-15, 0.5e-15, 1.0, 1.0),
    "micrometre": (2e-6, 1e-6, 1.0, 1.0),
    "kilometre": (2.0, 1.0, 4.0, 1e-3),
}
SPEEDS = (0.2, 10.0, 1e3, 1e6, 2e8, 1e9, 1e12, 1e15, -1e12)


def _pure(scale: str, V: float) -> bool:
    """Whether the belt outruns the mass: ``|V|`` above the peak speed ``(F_k / k) w`` (twice, for room)."""
    _, kinetic, m, k = SCALES[scale]
    return abs(V) > 2 * kinetic / math.sqrt(k * m)


@pytest.mark.parametrize(("scale", "V"), [(s, V) for s in SCALES for V in SPEEDS if _pure(s, V)])
def test_pure_slip_meets_its_closed_form_at_every_belt_speed(scale: str, V: float) -> None:
    static, kinetic, m, k = SCALES[scale]
    motion = solve_contact(parse_system(belt_system(V, static, kinetic, m=m, k=k)), T_END)
    t = np.linspace(0.0, T_END, 101)
    x, v = motion.state(t)
    x_ref, v_ref = pure_slip(t, V, kinetic, m, k)
    amplitude, speed = 2 * kinetic / k, kinetic / math.sqrt(k * m)
    bound_x, bound_v = global_bound(motion, static, kinetic, m, k, amplitude, speed)
    assert np.max(np.abs(x - x_ref)) <= bound_x
    assert np.max(np.abs(v - v_ref)) <= bound_v
    assert not motion.events


@pytest.mark.parametrize("V", [1e12, -2e8])
def test_pure_slip_keeps_a_start_velocity_small_against_the_belt(V: float) -> None:
    """``v0 = 0.3`` m/s on a belt at ``|V| >= 2e8``: ``u0 = v0 - V`` keeps ``v0`` only to ``eps |V|`` (1e-4 m/s at
    1e12); the start must take ``v0`` itself.  The bound is :func:`global_bound`'s plus nothing: the start is exact."""
    v0 = 0.3
    motion = solve_contact(parse_system(belt_system(V, 1.0, 0.5, v0=v0)), T_END)
    t = np.linspace(0.0, T_END, 101)
    x, v = motion.state(t)
    x_ref, v_ref = pure_slip(t, V, 0.5, 1.0, 1.0, v0)
    amplitude, speed = 0.5 + 0.5 + v0, 0.5 + v0
    bound_x, bound_v = global_bound(motion, 1.0, 0.5, 1.0, 1.0, amplitude, speed)
    assert np.max(np.abs(x - x_ref)) <= bound_x
    assert np.max(np.abs(v - v_ref)) <= bound_v


# A driven point beyond double precision (issue 41: a belt at 1e308 m/s wrote inf into the CSV).
ALL_METHODS = ("backward-euler", "exact", "event-driven", "event-locating", "theta", "moreau-jean")


@pytest.mark.parametrize("method", ALL_METHODS)
def test_a_belt_whose_position_overflows_is_refused_by_every_method(method: str) -> None:
    """At 1e308 m/s the belt's position ``1e308 t`` passes the largest double (1.8e308) at ``t = 1.8 s``: a run to
    3 s is refused before any method runs; to 1 s (position 1e308) it runs, finite, where the method takes belts."""
    net = parse_system(belt_system(1e308, 1.0, 0.5))
    with pytest.raises(ValueError, match=r"^driver 'belt': moving at 1e\+308 m/s, its position passes the largest"):
        L.solve(L.Problem(net, 3.0), 0.5, method=method)
    if method in ("backward-euler", "exact", "event-driven"):
        traj = L.solve(L.Problem(net, 1.0), 0.5, method=method)
        assert np.all(np.isfinite(traj.positions)) and np.all(np.isfinite(traj.forces))


def test_a_spring_pulled_beyond_double_precision_is_refused() -> None:
    """A spring of 10 N/m to the belt at 1e308 m/s would carry 1e309 N by 1 s: refused, naming the spring."""
    text = belt_system(1e308, 1.0, 0.5).replace('between = ["ground", "m"]', 'between = ["belt", "m"]')
    net = parse_system(text.replace("stiffness = 1.0", "stiffness = 10.0"))
    for method in ("backward-euler", "exact", "event-driven"):
        with pytest.raises(ValueError, match=r"^element 'spring': its stiffness 10 N/m times the travel of driver"):
            L.solve(L.Problem(net, 1.0), 0.5, method=method)
    with pytest.raises(ValueError, match=r"^element 'spring'"):
        solve_contact(net, 1.0)  # the method's own entry point refuses too


def test_the_command_line_refuses_the_overflowing_belt_in_one_line(tmp_path) -> None:
    (tmp_path / "s.toml").write_text(belt_system(1e308, 1.0, 0.5), encoding="utf-8")
    for method in ("backward-euler", "exact", "event-driven"):
        args = ("--system", "s.toml", "--t-end", "3", "--dt", "0.5", "--method", method, "--output", "o.csv")
        result = run_lumped("simulate", *args, cwd=tmp_path)
        assert result.returncode == 2 and result.stdout == ""
        assert result.stderr.count("\n") == 1 and "driver 'belt'" in result.stderr
        assert not (tmp_path / "o.csv").exists()


# The one-mass route (solvers/event_driven.py), the twin: a Coulomb contact to the ground, the mass thrown at
# ``v0`` fast against the band ``tau / k``.  Until its first stop, ``m x'' + k x = -tau``:
# ``x = -(tau / k)(1 - cos w t) + (v0 / w) sin w t``, ``v = -(tau / k) w sin w t + v0 cos w t``, which stops at
# ``tan(w t) = k v0 / (w tau)``; the test samples the slip up to 0.9 of that time.
ONE_MASS = [(1.0, 1.0), (1.0, 1e6), (1.0, 1e12), (1e-15, 0.2), (1e-6, 1e-6), (1e3, 1e4)]


@pytest.mark.parametrize(("tau", "v0"), ONE_MASS)
def test_the_one_mass_route_meets_the_first_slip_of_a_thrown_mass(tau: float, v0: float) -> None:
    from lumped.laws import BinghamDashpot, LinearSpring
    from lumped.model.oscillator import Oscillator
    from lumped.solvers.event_driven import solve_event_driven

    m, k = 1.0, 1.0
    w = math.sqrt(k / m)
    t_stop = math.atan2(k * v0, w * tau) / w
    sol = solve_event_driven(Oscillator(m, LinearSpring(k), BinghamDashpot(tau, math.inf)), t_stop, v0=v0)
    t = np.linspace(0.0, 0.9 * t_stop, 61)  # the first slip
    out = sol.evaluate(t)
    x_ref = -(tau / k) * (1 - np.cos(w * t)) + v0 / w * np.sin(w * t)
    v_ref = -(tau / k) * w * np.sin(w * t) + v0 * np.cos(w * t)
    # global_bound's derivation, with the one-mass route's atol (1e-3 rtol times the smaller of the energy
    # bound |v0| / w and the band tau / k, _motion_scale) and the same oscillator isometry
    steps = len(sol.phases[0].motion.steps) - 1
    scale = min(v0 / w, tau / k)
    sc_x = _ATOL_FACTOR * DEFAULT_RTOL * scale + DEFAULT_RTOL * (v0 / w + 2 * tau / k)
    sc_v = _ATOL_FACTOR * DEFAULT_RTOL * scale * w + DEFAULT_RTOL * (v0 + tau / math.sqrt(k * m))
    norm = steps * math.sqrt(2) * math.hypot(math.sqrt(k) * sc_x, math.sqrt(m) * sc_v)
    assert np.max(np.abs(out["x"] - x_ref)) <= norm / math.sqrt(k)
    assert np.max(np.abs(out["v"] - v_ref)) <= norm / math.sqrt(m)


def pulled_block(V: float) -> str:
    """The pulled block: the spring to the driven point ``belt`` at ``V``, the contact (static 1, kinetic 0.5) to
    the ground: the mass follows the point, ``x`` grows as ``V t``."""
    text = belt_system(V, 1.0, 0.5).replace('between = ["ground", "m"]', 'between = ["belt", "m"]', 1)
    return text.replace('between = ["belt", "m"]\nstatic', 'between = ["ground", "m"]\nstatic')


@pytest.mark.parametrize("V", [1.0, 100.0, 1e4, 1e6])
def test_a_block_pulled_fast_keeps_the_springs_elongation(V: float) -> None:
    """The block starts with the point's speed ``v0 = V`` at ``x = 0``; in the spring's frame ``y = x - V t``,
    ``m y'' + k y = -kinetic`` from rest: ``y = -(kinetic / k)(1 - cos w t)``, and ``v = V + y'`` stays above
    ``V - kinetic / sqrt(k m) > 0``: pure slip.  Carried as ``(x, v)``, the error control's ``rtol |x|``,
    ``rtol |v|`` (``rtol V t``, ``rtol V``) swamped ``y``: 6.0e-6 m off at 1e4 m/s over 100 s (1.1e-7 at 100 m/s).
    The bound is :func:`global_bound`'s on the frame's motion (the forces' scale)."""
    T = 100.0
    net = parse_system(pulled_block(V).replace("v0 = 0.0", f"v0 = {V!r}"))
    motion = solve_contact(net, T)
    t = np.linspace(0.0, T, 401)
    x, v = motion.state(t)
    bound_y, bound_w = global_bound(motion, 1.0, 0.5, 1.0, 1.0, 1.0, 0.5)
    # x - V t and v - V are formed here, in doubles: their own round-off is below eps (|x| + V t), eps (|v| + V)
    eps = np.finfo(float).eps
    assert np.max(np.abs((x - V * t) + 0.5 * (1 - np.cos(t)))) <= bound_y + 4 * eps * V * T
    assert np.max(np.abs((v - V) + 0.5 * np.sin(t))) <= bound_w + 4 * eps * V


@pytest.mark.parametrize("V", [1e3, 1e12])
def test_pure_slip_keeps_its_velocity_through_the_loads_switch_off(V: float) -> None:
    """A load ``0.1 sin(2 t)`` on until ``t_off = 3 s`` ends a slip phase; the next starts from the last one's
    state.  Passed on as ``u = v - V``, the mass's velocity kept only ``eps |V|`` (1e-4 m/s at 1e12).  With
    ``c = F_k / k = 0.5`` and ``P = 0.1``: ``x = c (1 - cos t) + P (sin 2t - 2 sin t) / (1 - 4)`` before ``t_off``,
    the free oscillation about ``c`` from ``x(t_off), v(t_off)`` after; the bound is :func:`global_bound`'s."""
    text = (
        belt_system(V, 1.0, 0.5) + '\n[[force]]\non = "m"\nkind = "sine"\namplitude = 0.1\nomega = 2.0\nuntil = 3.0\n'
    )
    motion = solve_contact(parse_system(text), T_END)
    c, P, t_off = 0.5, 0.1, 3.0
    on = lambda t: c * (1 - np.cos(t)) + P * (np.sin(2 * t) - 2 * np.sin(t)) / -3.0
    on_v = lambda t: c * np.sin(t) + P * (2 * np.cos(2 * t) - 2 * np.cos(t)) / -3.0
    t = np.linspace(t_off, T_END, 71)
    x_ref = c + (on(t_off) - c) * np.cos(t - t_off) + on_v(t_off) * np.sin(t - t_off)
    x, _ = motion.state(t)
    steps = sum(len(ph.motion.steps) - 1 for ph in motion.phases)
    # atol: 1e-3 rtol times the forces' band (static + P) / k = 1.1 m (velocities: over sqrt(k m)); |x| <= 1.2 m,
    # |v| <= 0.7 m/s; the error's flow is the free oscillator's isometry through the switch (m = k = 1)
    atol = _ATOL_FACTOR * DEFAULT_RTOL * 1.1
    norm = steps * math.sqrt(2) * math.hypot(atol + DEFAULT_RTOL * 1.2, atol + DEFAULT_RTOL * 0.7)
    assert [e.kind for e in motion.events] == ["switch"]
    assert np.max(np.abs(x - x_ref)) <= norm
