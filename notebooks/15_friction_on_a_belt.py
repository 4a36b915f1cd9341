# ---
# jupyter:
#   jupytext:
#     formats: ipynb,py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 15. Friction on a belt: static above kinetic, Stribeck, and what smoothing hides
#
# **What you will learn.**
#
# * how a block on a spring, dragged by a moving belt through a friction
#   contact, becomes the same kind of differential-algebraic system as the
#   paper's oscillator (notebook 1), now with a graph that *falls*: the
#   contact holds up to `static` when stuck and slides with less;
# * why a backward-Euler step of such a law may have several solutions, the
#   rule the package uses to pick one, and the step-size bound
#   $m/\Delta t + k\,\Delta t > \lambda$ under which the step is unique (and
#   the package's refusal of a longer step);
# * the closed-form stick-slip limit cycle, derived with SymPy and checked
#   against the package's `belt_cycle`, beside `exact` (to $10^{-12}$ s) and
#   backward Euler (first order, with the constant of its error derived), and
#   the phase portrait with its stick segment;
# * what the `tanh` smoothing of the tools engineers use does to it: the
#   stick becomes creep, the period is off, and an explicit integrator pays
#   for the stiffness in steps;
# * a falling curve given as any function (Leine's benchmark), run by the
#   `event-driven` method beside backward Euler;
# * steady sliding on a Stribeck belt: stable above the Hopf speed, growing
#   into stick-slip below it, at the rates of its linearisation;
# * a curve invertible neither way, and the jumps at its folds (the delay
#   convention, and what Maxwell's would give).
#
# Every statement below is backed by a printed number or an `assert`.

# %%
# %matplotlib inline
import math

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import lumped as L
import lumped.plotting as P
from lumped.laws.step_graph import SLIP_BACK, SLIP_FORWARD, STICK, _slip_rule
from lumped.model.files import parse_system
from lumped.solvers.closed_form_belt import belt_cycle
from lumped.solvers.event_driven_network import solve_contact

m, k, S, K, V = 1.0, 1.0, 1.0, 0.5, 0.2  # kg, N/m, N (static), N (kinetic), m/s (the belt)


def belt(contact: str = "", x0: float = 0.0, v0: float = 0.0) -> L.Network:
    """The block on a spring, riding a belt at V through a friction contact (extra keys in ``contact``)."""
    return parse_system(f"""
        [[mass]]
        name = "m"
        mass = {m}
        x0 = {x0!r}
        v0 = {v0!r}
        [[driver]]
        name = "belt"
        velocity = {V}
        [[element]]
        name = "spring"
        kind = "spring"
        between = ["ground", "m"]
        stiffness = {k}
        [[element]]
        name = "contact"
        kind = "friction"
        between = ["belt", "m"]
        static = {S}
        kinetic = {K}
        {contact}
    """)


print(f"m = {m} kg, k = {k} N/m, static S = {S} N, kinetic K = {K} N, belt V = {V} m/s")

# %% [markdown]
# ## Step 1: the governing equations
#
# The block's position $x$ is the spring's elongation; the belt's point under
# it moves at $V$. The contact joins the belt to the block, so its *rate* is
# the block's speed relative to the belt, $u = v - V$, and its *tension* $T$
# pulls the block back as the spring's does. Newton's second law and the two
# constitutive relations give, as in notebook 1's system (8),
#
# $$\dot v = \frac{1}{m}\bigl(-k x - T\bigr), \qquad \dot x = v, \qquad
#   0 = \beta\bigl(v - V,\ T\bigr), \tag{1}$$
#
# where the contact's graph $\beta$ is
#
# $$T = \operatorname{sgn}(u)\,g(|u|)\ \ (u \ne 0), \qquad T \in [-S, S]\ \ (u = 0), \tag{2}$$
#
# with the *slip curve* $g$. For static above kinetic (the `friction` kind
# without a Stribeck velocity) $g \equiv K < S$: the tension drops from $S$ to
# $K$ as soon as the contact slips. With a Stribeck velocity $v_s$ it falls
# smoothly, $g(s) = K + (S - K)\,e^{-s/v_s}$. Either way the graph is no longer
# monotone: unlike the Bingham dashpot, *neither* $T$ as a function of $u$ nor
# $u$ as a function of $T$ describes it, and a step needs a rule.

# %%
coulomb_like = belt().elements[1].law
stribeck = belt("stribeck_velocity = 0.01").elements[1].law
for name, law in (("static/kinetic", coulomb_like), ("Stribeck, v_s = 0.01 m/s", stribeck)):
    print(f"{name:25s}: stick interval [-{law.static:g}, {law.static:g}] N, g(0+) = {law.slip_limit:g} N, "
          f"g(0.01) = {law.slip(0.01):.4f} N, g(1) = {law.slip(1.0):.4f} N, steepest fall {law.fall:g} N s/m")
fig = P.friction_graph({"static/kinetic": coulomb_like, "Stribeck, $v_s = 0.01$ m/s": stribeck}, 0.05)

# %% [markdown]
# The static/kinetic law's fall is a jump (at $u = 0$, from $S$ to $K$) and
# its slip curve is flat, so its steepest fall *off* zero rate is 0. The
# Stribeck curve's steepest fall is its slope at $0^+$, $(S - K)/v_s = 50$ N s/m.

# %% [markdown]
# ## Step 2: one backward-Euler step, and which solution
#
# Evaluate (1) at $t_{n+1}$ as in notebook 1's (13): $x^{(n+1)} = x^{(n)} +
# \Delta t\, v^{(n+1)}$ and $m (v^{(n+1)} - v^{(n)})/\Delta t = -k x^{(n+1)} -
# T^{(n+1)}$. In the contact's rate $u = v^{(n+1)} - V$ the step is one scalar
# equation,
#
# $$T + \eta\,u = z, \qquad \eta = \frac{m}{\Delta t} + k\,\Delta t, \qquad
#   z = \frac{m}{\Delta t} v^{(n)} - k x^{(n)} - \eta V, \tag{3}$$
#
# with $(u, T)$ on the graph (2); SymPy checks the algebra:

# %%
m_, k_, dt_, V_ = sp.symbols("m k Delta_t V", positive=True)
x0_, v0_, v1_, T_ = sp.symbols("x_n v_n v_n1 T", real=True)
x1 = x0_ + dt_ * v1_
momentum = m_ * (v1_ - v0_) / dt_ + k_ * x1 + T_  # = 0
eta_ = m_ / dt_ + k_ * dt_
z_ = m_ / dt_ * v0_ - k_ * x0_ - eta_ * V_
assert sp.simplify(momentum - (T_ + eta_ * (v1_ - V_) - z_)) == 0
print("(3):", sp.Eq(T_ + eta_ * sp.Symbol("u"), z_))

# %% [markdown]
# *Stuck* ($u = 0$) solves (3) when $|z| \le S$, with $T = z$. *Slipping
# forward* ($u > 0$) solves it where $h(u) = g(u) + \eta u = z$. For
# static/kinetic, $h(u) = K + \eta u$, so every $z \in (K, S]$ has **two**
# solutions: stuck, and slipping at $u = (z - K)/\eta$. The package picks one
# by the contact's state at the step's start
# (`lumped.laws.step_graph._slip_rule`): a stuck contact stays stuck while its
# tension is within $[-S, S]$; a slipping one keeps slipping while its rate
# keeps its sign, and sticks when the rate would change sign. The step starts
# from the mode the contact was in, solves (3) on that piece and asks the rule;
# it is done when the rule keeps the mode. For $\Delta t = 0.01$ s:

# %%
mode = {STICK: "stick", SLIP_FORWARD: "slip forward", SLIP_BACK: "slip back"}
eta = m / 0.01 + k * 0.01


def one_step(before, z):
    """The mode, rate and tension of (3) for z > 0 (stick, or forward slip on g = K), by the rule."""
    current = before
    while True:
        u, T = (0.0, z) if current == STICK else ((z - K) / eta, K)
        new = _slip_rule(current, u, T, S)
        if new == current:
            return current, u, T
        current = new


for before, z in ((STICK, 0.8), (SLIP_FORWARD, 0.8), (SLIP_FORWARD, 0.3), (STICK, 1.2)):
    after, u, T = one_step(before, z)
    print(f"was {mode[before]:12s}, z = {z} N -> {mode[after]:12s} (u = {u:+.2e} m/s, T = {T} N)")

# %% [markdown]
# At $z = 0.8$ N a contact that was stuck keeps the stuck solution (its
# tension is within $S$) and one that was slipping forward keeps slipping (its
# rate keeps its sign). Both answers solve (3): the rule is what makes static
# friction *static*, a hysteresis between $K$ and $S$. Below $K$ the slipping
# contact's rate would turn negative, so it sticks; above $S$ the stuck one
# breaks away.
#
# ### The step-size bound for a falling curve
#
# On a Stribeck curve a second problem appears *within* the slip branch. If
# $g$ falls with slope down to $-\lambda$, then $h'(u) = g'(u) + \eta \ge \eta -
# \lambda$: when $\eta > \lambda$, $h$ is strictly increasing and each $z$ has
# at most one slip root. When $\eta < \lambda$, $h$ has a minimum at
# $u^* = v_s \ln(\lambda/\eta)$ (where $h' = -\lambda e^{-u/v_s} + \eta = 0$), and
# every $z$ between $h(u^*)$ and $h(0) = S$ has **two** slip roots, besides the
# stuck solution. So for one mass the step is unique when
#
# $$\frac{m}{\Delta t} + k\,\Delta t > \lambda, \tag{4}$$
#
# i.e. $\Delta t < \Delta t^* = \bigl(\lambda - \sqrt{\lambda^2 - 4km}\bigr)/(2k)$
# (the smaller root of $k\Delta t^2 - \lambda\Delta t + m = 0$). With
# $v_s = 0.01$ m/s, $\lambda = 50$ N s/m:

# %%
lam = stribeck.fall
dt_star = (lam - math.sqrt(lam**2 - 4 * k * m)) / (2 * k)
print(f"lambda = {lam:g} N s/m, dt* = {dt_star:.6f} s")
h = lambda u, eta: stribeck.slip(u) + eta * u
for dt in (0.05, 0.01):
    eta = m / dt + k * dt
    if eta < lam:
        u_star = 0.01 * math.log(lam / eta)
        z = 0.5 * (h(u_star, eta) + S)  # halfway between the minimum of h and h(0) = S
        gap = lambda u, eta=eta, z=z: h(u, eta) - z
        roots = [brentq(gap, a, b) for a, b in ((0.0, u_star), (u_star, 1.0))]
        print(f"dt = {dt} s: eta = {eta:.2f} < lambda; z = {z:.4f} N has slip roots u = "
              f"{roots[0]:.5f} and {roots[1]:.5f} m/s (and stuck, T = z)")
    else:
        u = np.linspace(0.0, 1.0, 100_001)
        assert np.all(np.diff(h(u, eta)) > 0)  # h increasing: one slip root at most
        print(f"dt = {dt} s: eta = {eta:.2f} > lambda; h(u) = g(u) + eta u is increasing on [0, 1] m/s")

# %% [markdown]
# Above $\Delta t^*$ the step has three solutions for such a $z$; below it,
# one slip root at most, and the rule above decides between it and sticking.
# `lumped.simulate_network` checks (4) before it takes a step, and refuses a
# longer step in one line that names the largest admissible one:

# %%
try:
    L.simulate_network(belt("stribeck_velocity = 0.01"), 10.0, 0.05)
except ValueError as err:
    print("ValueError:", err)
run = L.simulate_network(belt("stribeck_velocity = 0.01"), 10.0, 0.02)
print(f"dt = 0.02 s (below dt* = {dt_star:.5f} s): {run.t.size - 1} steps run")

# %% [markdown]
# ## Step 3: the closed-form stick-slip cycle
#
# Take static/kinetic friction without a viscous part. Once the block moves
# with the belt (stuck, $v = V$) the spring loads at the belt's speed until its
# force reaches $S$, at $x = S/k$; there the contact breaks away. While it
# slips backwards relative to the belt ($u < 0$) the contact pushes the block
# forward with $K$, so the slip is harmonic about $K/k$:
# $m\ddot x + kx = K$, from $x = S/k$, $v = V$. It ends when the block's speed
# is $V$ again. SymPy solves the slip and finds its end with the half-angle
# substitution $\tau = \tan(\omega t/2)$, $\omega = \sqrt{k/m}$:

# %%
t_, S_, K_ = sp.symbols("t S K", positive=True)
w_ = sp.sqrt(k_ / m_)
x_ = sp.Function("x")
ode = sp.Eq(m_ * x_(t_).diff(t_, 2), -k_ * x_(t_) + K_)
slip = sp.dsolve(ode, x_(t_), ics={x_(0): S_ / k_, x_(t_).diff(t_).subs(t_, 0): V_}).rhs
th, tau = sp.symbols("theta tau", real=True)
half = {sp.cos(th): (1 - tau**2) / (1 + tau**2), sp.sin(th): 2 * tau / (1 + tau**2)}
v_of_tau = sp.simplify(slip.diff(t_).subs(t_, th / w_).subs(half))
roots = sp.solve(sp.Eq(v_of_tau, V_), tau)
print("slip:", sp.simplify(slip))
print("v = V at tan(w t/2) =", roots)

# %% [markdown]
# The root $\tau = 0$ is the slip's start; the other,
# $\tau = -\omega(S - K)/(kV) < 0$, puts $\omega t/2$ in $(\pi/2, \pi)$, so
# the slip lasts $t_{slip} = 2\bigl(\pi - \arctan(\omega(S - K)/(kV))\bigr)/\omega$,
# longer than half a period. (In between $v < V$: the relative rate keeps its
# sign, as the slip's assumption needs.) There the block is at

# %%
tau_end = next(r for r in roots if r != 0)
x_end = sp.simplify(slip.subs(t_, th / w_).subs(half).subs(tau, tau_end))
print("x at the end of the slip:", x_end)
assert sp.simplify(x_end - (2 * K_ - S_) / k_) == 0

# %% [markdown]
# so it sticks at $x = (2K - S)/k$ (its tension $kx$ is within $S$ since
# $0 \le K \le S$) and rides with the belt to $S/k$ again: the stick lasts
# $t_{stick} = 2(S - K)/(kV)$. The extremes are those of the harmonic slip,
# $K/k \pm A$ with $A = \sqrt{((S - K)/k)^2 + (V/\omega)^2}$, and the slowest
# speed is $-\omega A$ (the slip passes through the turning points since it
# is longer than half a period):

# %%
A_ = sp.sqrt(((S_ - K_) / k_) ** 2 + (V_ / w_) ** 2)
assert sp.simplify((slip - K_ / k_) ** 2 + (slip.diff(t_) / w_) ** 2 - A_**2) == 0  # a circle of radius A
cycle_ = {
    "t_slip": 2 * (sp.pi - sp.atan(w_ * (S_ - K_) / (k_ * V_))) / w_,
    "t_stick": 2 * (S_ - K_) / (k_ * V_),
    "x_max": K_ / k_ + A_,
    "x_min": K_ / k_ - A_,
    "v_min": -w_ * A_,
}
assert sp.simplify(slip.diff(t_).subs(t_, cycle_["t_slip"]) - V_) == 0
values = {m_: m, k_: k, S_: S, K_: K, V_: V}
derived = {name: float(expr.subs(values)) for name, expr in cycle_.items()}
print(", ".join(f"{name} = {value:.6f}" for name, value in derived.items()))

# %% [markdown]
# The package computes the same cycle in one place,
# `lumped.solvers.closed_form_belt.belt_cycle`, which the tests of `exact` and
# backward Euler meet; it writes the slip time as $(\pi + 2\theta_0)/\omega$
# with $\theta_0 = \operatorname{atan2}(V/\omega, (S - K)/k)$, equal to the form
# above since $\arctan a + \arctan(1/a) = \pi/2$. The derivation and the
# package agree (each value is a handful of roundings of numbers below 8, so
# within $10^{-14}$ of the other):

# %%
cycle = belt_cycle(m, k, S, K, V)
package = {"t_slip": cycle.slip_time, "t_stick": cycle.stick_time, "x_max": cycle.x_max, "x_min": cycle.x_min,
           "v_min": cycle.v_min}
assert all(abs(derived[name] - package[name]) <= 1e-14 for name in derived)
print(f"belt_cycle: period {cycle.period:.6f} s = stick {cycle.stick_time:.6f} s + slip {cycle.slip_time:.6f} s; "
      f"the SymPy values agree to 1e-14")

# %% [markdown]
# ## Step 4: `exact` and backward Euler beside the closed form
#
# Every phase of this motion is linear (stick: the belt's motion; slip: a
# harmonic motion under the constant force $K$), so the package's `exact`
# method runs it by matrix exponentials, locating each stop and breakaway by
# Brent's method to a few ulps. Run from rest, the block first slips into
# stick, and from the first breakaway on the motion is the cycle; the period,
# stick and slip times are read off `exact`'s events:

# %%
net = belt()
exact = L.solve(L.Problem(net, 30.0), 1e-2, method="exact")
breaks = np.array([e.time for e in exact.events if e.kind == "breakaway"])
stops = np.array([e.time for e in exact.events if e.kind == "stop"])
stops = stops[stops > breaks[0]][: breaks.size]  # the stop that ends each slip
measured_exact = {"period": np.diff(breaks), "stick": breaks[1:] - stops[:-1], "slip": stops - breaks}
reference = {"period": cycle.period, "stick": cycle.stick_time, "slip": cycle.slip_time}
worst = max(np.abs(measured_exact[name] - reference[name]).max() for name in reference)
assert worst < 1e-12
print(f"exact: {breaks.size} breakaways; period, stick and slip times within 1e-12 s of belt_cycle's")

# %% [markdown]
# (Each event time is a root located to 4 eps relative, below $10^{-14}$ s
# up to 30 s; the bound asserted leaves a factor of ten for other CPUs, and
# is a thousand times tighter than the $10^{-9}$ the tests ask.)
#
# Backward Euler marks each step stuck or slipping (the contact's state).
# Its error has two parts, both of first order. On the slip it damps the
# harmonic motion: a step multiplies the amplitude $R$ about $K/k$ by
# $(1 + \omega^2\Delta t^2)^{-1/2}$, i.e. $R$ decays at the rate
# $\omega^2\Delta t/2$, while the phase is right to $O(\Delta t^2)$. And an
# event falls on the grid: the stick begins at the first step after the rate
# reaches zero, and the breakaway at the last stuck step before the spring's
# force would pass $S$. Start the run *on* the cycle, at the breakaway point
# $(S/k, V)$ at $t = 0$, so that the first slip starts exactly:
#
# * the highest point, reached at the angle $\theta_0$ after the breakaway,
#   is lower by $R\,\omega\theta_0\,\Delta t/2$;
# * the slip ends where the damped circle meets $v = V$, at
#   $|x - K/k| = \sqrt{R^2 - (V/\omega)^2}$, which is closer to $K/k$ by
#   $(R^2/y_0)\,\omega^2 t_{slip}\Delta t/2$ ($y_0 = (S - K)/k$), so the stick
#   is shorter by that over $V$; the slip is longer by $V t_{slip}\Delta t/(2y_0)$
#   (the end angle moves). Together the period is short by
#   $c_0\Delta t$ with $c_0 = \omega^2 t_{slip}\,y_0/(2V)$. The stick's late
#   start on the grid does not enter (the block moves at $V$ in both), but
#   the breakaway's placement does: it comes up to one step early, so the
#   period's error lies between $-(c_0 + 1)\Delta t$ and $-c_0\Delta t$.
#
# Over three halvings of the step:

# %%
omega, y0, R = math.sqrt(k / m), (S - K) / k, math.hypot((S - K) / k, V / math.sqrt(k / m))
theta0 = math.atan2(V / omega, y0)
c_xmax = R * omega * theta0 / 2  # x_max is low by c_xmax dt
c0 = omega**2 * cycle.slip_time * y0 / (2 * V)  # the period is short by c0 dt to (c0 + 1) dt
print(f"first-order model: x_max error -{c_xmax:.4f} dt, period error between -{c0 + 1:.3f} dt and -{c0:.3f} dt")
dts = np.array([1.6e-2, 8e-3, 4e-3, 2e-3])
on_cycle = belt(x0=S / k, v0=V)
be_errors = []
for dt in dts:
    run = L.simulate_network(on_cycle, cycle.period + 2 * dt, dt)
    stuck = run.states[:, 1] == 0
    breaks_be = np.flatnonzero(~stuck[1:] & stuck[:-1])  # the last stuck step before each breakaway
    onset = np.flatnonzero(stuck[1:] & ~stuck[:-1])[0] + 1  # the first stuck step after the slip
    be_errors.append((run.t[breaks_be[1]] - run.t[breaks_be[0]] - cycle.period,
                      run.positions[:onset, 0].max() - cycle.x_max))
period_err, xmax_err = np.array(be_errors).T
for dt, ep, ex in zip(dts, period_err, xmax_err):
    print(f"dt = {dt:g} s: period error {ep:+.3e} s = {ep / dt:+.3f} dt, x_max error {ex:+.3e} m = {ex / dt:+.4f} dt")
slopes = [np.polyfit(np.log(dts), np.log(np.abs(e)), 1)[0] for e in (period_err, xmax_err)]
print(f"fitted orders: period {slopes[0]:.2f}, x_max {slopes[1]:.3f}")

# %% [markdown]
# The assertions below hold the errors to the model, with the terms it
# neglects bounded: the damping's next term and the phase error, both
# relative $O(\rho)$ with $\rho = \omega^2\Delta t\,t_{slip}$ (0.062 at the
# largest step), and the grid's sampling of the highest point,
# $\omega^2 R\,\Delta t^2/8$. A slope fitted to errors that lie within a band
# $[-(c_0 + 1), -c_0]\Delta t$ is 1 to within $\ln((c_0 + 1)/c_0)$ times the
# fit's gain for a perturbation of its points, $4/(5\ln 2)$ over four points
# a halving apart:

# %%
rho = omega**2 * dts * cycle.slip_time
assert np.all((-(c0 + 1) * (1 + rho) * dts <= period_err) & (period_err <= -c0 * (1 - rho) * dts))
assert np.all(np.abs(xmax_err + c_xmax * dts) <= (rho * c_xmax + omega**2 * R * dts / 8) * dts)
band = math.log((c0 + 1) / c0) * 4 / (5 * math.log(2))
assert abs(slopes[0] - 1) <= band and abs(slopes[1] - 1) <= 2 * rho[0]
print(f"rho at the largest step {rho[0]:.3f}; the period's order is 1 within {band:.2f}, "
      f"x_max's within {2 * rho[0]:.2f}")

# %% [markdown]
# Both are first order; the period's errors over $\Delta t$ scatter within
# the band because of where the grid falls at the breakaway, and $x_{max}$'s
# do not (the first slip starts on the grid). After the first cycle they
# do too: a run from rest breaks away at its last stuck step, up to $V\Delta t$
# before $S/k$, which shrinks the slip's radius by up to $(y_0/R)\,V\Delta t$,
# more than the damping's $0.10\,\Delta t$, so two steps' $x_{max}$ errors
# from such a cycle give an "order" that depends on the grid. Runs from rest
# at $\Delta t = 0.05$ and $0.01$ s (the figure's), with `exact`:

# %%
runs = {dt: L.simulate_network(net, 30.0, dt) for dt in (5e-2, 1e-2)}
for dt, run in runs.items():
    stuck = run.states[:, 1] == 0
    onsets = np.flatnonzero(stuck[1:] & ~stuck[:-1]) + 1
    ex = run.positions[onsets[-2] : onsets[-1], 0].max() - cycle.x_max
    low, high = -(y0 / R * V + c_xmax), -c_xmax
    slack = omega**2 * dt * cycle.slip_time * (y0 / R * V + c_xmax) + omega**2 * R * dt / 8
    assert (low - slack) * dt <= ex <= (high + slack) * dt
    print(f"dt = {dt:g} s, last whole cycle: x_max error {ex / dt:+.3f} dt (model: {low:+.3f} dt to {high:+.3f} dt)")

# %% [markdown]
# The phase portrait shows the cycle the runs settle on, with its stick
# segment; `exact` lies on the closed form, backward Euler inside it by its
# damping:

# %%
theta = np.linspace(0.0, 1.0, 400) * cycle.slip_time
slip_x = sp.lambdify(t_, slip.subs(values), "numpy")
slip_v = sp.lambdify(t_, slip.diff(t_).subs(values), "numpy")
assert np.all(slip_v(theta[1:-1]) < V)  # the slip's relative rate keeps its sign, as Step 3 says
closed = (np.concatenate((slip_x(theta), [S / k])), np.concatenate((slip_v(theta), [V])))
stick = ((2 * K - S) / k, S / k, V)
fig = P.belt_phase_portrait(
    {"exact": (exact.positions[:, 0], exact.velocities[:, 0])}
    | {f"backward Euler, $\\Delta t$ = {dt:g} s": (r.positions[:, 0], r.velocities[:, 0]) for dt, r in runs.items()},
    closed,
    stick,
)
_ = P.save_figure(fig, "fr01_belt_phase_portrait")

# %% [markdown]
# ## Step 5: what `tanh` smoothing does
#
# Modelica, Simscape and ModelingToolkit's standard libraries smooth the
# law instead: with a breakaway speed $v_{brk}$,
#
# $$T(u) = \sqrt{2e}\,(S - K)\,e^{-(u/v_{st})^2}\,\frac{u}{v_{st}} + K\tanh\frac{u}{v_{C}},
#   \qquad v_{st} = \sqrt 2\,v_{brk}, \quad v_C = v_{brk}/10, \tag{5}$$
#
# a single-valued force whose peak, $S$ at $u = v_{brk}$ (for $v_C \ll v_{brk}$), stands for
# the static force. Equation (1) becomes an ODE that any integrator runs. We
# take $\varepsilon = v_C = 10^{-2}, 10^{-3}, 10^{-4}$ m/s and integrate it with
# SciPy's `solve_ivp` (RK45, explicit, and LSODA, which switches to a stiff
# method) at `rtol` $= 10^{-8}$, from rest, locating each upward crossing of
# $x = K/k$ (which the cycle makes once, while stuck) as an event:

# %%
def smoothed(u, eps):
    """Eq. (5) with v_C = eps."""
    v_st = math.sqrt(2.0) * 10.0 * eps
    return math.sqrt(2 * math.e) * (S - K) * np.exp(-((u / v_st) ** 2)) * u / v_st + K * np.tanh(u / eps)


def run_smoothed(eps, method):
    crossing = lambda t, y: y[0] - K / k
    crossing.direction = 1
    rhs = lambda t, y: (y[1], (-k * y[0] - smoothed(y[1] - V, eps)) / m)
    return solve_ivp(rhs, (0.0, 25.0), (0.0, 0.0), method=method, rtol=1e-8, atol=1e-10, events=crossing,
                     dense_output=True)


u = np.linspace(0.0, 0.5, 500_001)
print("largest smoothed force:", ", ".join(f"{smoothed(u, e).max():.6f} N" for e in (1e-2, 1e-3, 1e-4)))
smooth = {(eps, method): run_smoothed(eps, method) for eps in (1e-2, 1e-3, 1e-4) for method in ("RK45", "LSODA")}

# %% [markdown]
# The smoothed model has no stick: where the exact block rides with the belt
# the smoothed one must *creep* relative to it, since its force is a function
# of the rate and changes only as the rate does. Over the stick's middle,
# the block between $(2K - S)/k$ and $S/k$ (shrunk by a tenth at either end)
# and moving forward, the largest relative speed, and the period (between the
# last two crossings) against the closed form:

# %%
lo, hi = (2 * K - S) / k, S / k
creep, period_error = {}, {}
for (eps, method), sol in smooth.items():
    t0, t1 = sol.t_events[0][-2:]
    t = np.linspace(t0, t1, 20_001)
    x, v = sol.sol(t)
    middle = (x > lo + 0.1 * (hi - lo)) & (x < hi - 0.1 * (hi - lo)) & (v > 0)
    creep[eps, method] = np.abs(v[middle] - V).max()
    period_error[eps, method] = (t1 - t0) / cycle.period - 1
for eps in (1e-2, 1e-3, 1e-4):
    assert math.isclose(period_error[eps, "RK45"], period_error[eps, "LSODA"], rel_tol=1e-3)
    print(f"eps = {eps:.0e} m/s: largest |v - V| in the stick's middle {creep[eps, 'RK45']:.2g} m/s "
          f"({creep[eps, 'RK45'] / eps:.1f} eps), period {period_error[eps, 'RK45']:+.2g} relative to the exact")

# %% [markdown]
# The creep is a few $\varepsilon$ and the period error falls more slowly
# than $\varepsilon$ (by a factor of about 4.5 for each factor 10): a cycle
# correct to a per cent needs $\varepsilon = 10^{-4}$ m/s. That costs steps.
# Near $u = 0$ the smoothed force has slope $K/\varepsilon$, a time scale
# $m\varepsilon/K$, which an explicit method must resolve; a stiff one need
# not. Step counts of adaptive integrators follow round-off and vary across
# SciPy versions and CPUs, so the counts themselves are printed in brackets,
# which the notebook's check masks (`notebooks/nbval_sanitize.cfg`); what the
# assertions check is their growth:

# %%
steps = {key: sol.t.size - 1 for key, sol in smooth.items()}
nfev = {key: sol.nfev for key, sol in smooth.items()}
for method in ("RK45", "LSODA"):
    counts = "; ".join(f"eps {e:.0e}: {steps[e, method]:.2g} steps, {nfev[e, method]:.2g} evaluations"
                       for e in (1e-2, 1e-3, 1e-4))
    print(f"{method}: [counts vary: {counts}]")
assert steps[1e-4, "RK45"] > 10 * steps[1e-2, "RK45"]  # the explicit method pays for 1/eps
assert steps[1e-4, "LSODA"] < 2 * steps[1e-2, "LSODA"]  # the stiff one does not
print("RK45 takes more than 10 times the steps at eps = 1e-4 than at 1e-2; LSODA fewer than twice as many")

# %% [markdown]
# LSODA's steps do not grow, but its answer is the same smoothed model's: the
# creep and the period error above belong to the model, not to the
# integrator. The figure lays one cycle of each over the exact one, aligned at
# the crossing of $x = K/k$, with the exact stick shaded:

# %%
t_cross = (S / k - K / k) / V  # exact: stick from x = K/k to S/k at V, then the slip, then stick again
t_ref = np.linspace(0.0, cycle.period, 2001)
reference = np.where(
    t_ref < t_cross, V,
    np.where(t_ref < t_cross + cycle.slip_time, slip_v(np.clip(t_ref - t_cross, 0.0, None)), V),
)
curves = {}
for eps in (1e-2, 1e-3, 1e-4):
    sol = smooth[eps, "LSODA"]
    t0, t1 = sol.t_events[0][-2:]
    t = np.linspace(t0, t1, 4001)
    curves[f"$\\varepsilon = {P.sci_tex(eps, show_one=False)}$ m/s"] = (t - t0, sol.sol(t)[1])
stuck = [(0.0, t_cross), (t_cross + cycle.slip_time, cycle.period)]
fig = P.smoothing_creep((t_ref, reference), curves, V, stuck)
_ = P.save_figure(fig, "fr02_smoothing_creep")

# %% [markdown]
# ## Step 6: any falling curve: Leine's law, event-driven beside backward Euler
#
# Leine, van Campen, de Kraker and van den Steen's benchmark (Nonlinear
# Dynamics 16 (1998) 41–54) is the same block, $m = k = 1$ on a belt at
# $V = 0.2$ m/s, with a slip curve that falls smoothly from $F_s = 1$ N,
# $g(s) = F_s/(1 + \delta s)$ with $\delta = 3$ s/m. In the API any such curve
# is one line, a `lumped.SlipCurve`: its static force, the curve, and its
# steepest fall $F_s\delta$ (at $s = 0$), which backward Euler's bound (4)
# reads. It has no closed form; the `event-driven` method integrates each
# slip phase (SciPy's DOP853 at `rtol` $= 10^{-12}$) and locates every stop
# and breakaway by Brent's method (`tests/test_friction_event_driven.py`
# meets an independent event-located `solve_ivp` integration of the
# benchmark to $10^{-8}$). Both methods start on the cycle, at the breakaway
# point $(F_s/k, V)$; `lumped.solvers.event_driven_network.solve_contact` is
# the continuous motion behind the method's trajectory, and gives the
# turning points by Brent's method on its velocity:

# %%
F_s, delta = 1.0, 3.0
leine = L.SlipCurve(F_s, lambda s: F_s / (1 + delta * s), fall=F_s * delta)
leine_belt = L.Network(
    [L.Mass("m", m, F_s / k, V)],
    [L.Spring("spring", ("ground", "m"), k), L.Contact("contact", ("belt", "m"), leine)],
    drivers=[L.Driver("belt", V)],
)
motion = solve_contact(leine_belt, 12.5, rtol=1e-12)
print("events:", ", ".join(f"{e.kind} at {e.time:.6f} s" for e in motion.events))
period_leine = next(e.time for e in motion.events[1:] if e.kind == "breakaway")


def turning_points(motion, t0, t1):
    """Positions where the continuous motion's velocity changes sign in (t0, t1)."""
    grid = np.linspace(t0, t1, 4001)
    v = motion.state(grid)[1]
    where = np.flatnonzero(np.sign(v[1:]) * np.sign(v[:-1]) < 0)
    velocity = lambda t: float(motion.state(np.array([t]))[1][0])
    roots = [brentq(velocity, grid[i], grid[i + 1], xtol=1e-14) for i in where]
    return [float(motion.state(np.array([r]))[0][0]) for r in roots]


x_hi, x_lo = turning_points(motion, 0.0, period_leine)
print(f"event-driven: period {period_leine:.6f} s, x_max {x_hi:.6f} m, x_min {x_lo:.6f} m")

# %% [markdown]
# The block breaks away at once, slips back past the spring's rest and sticks
# again, rides the belt to $F_s/k$, and the cycle repeats. Backward Euler at
# three steps (each below the bound (4), $\Delta t < 0.38$ s): its error over
# $\Delta t$ has a part that varies smoothly with the step and, as in Step 4,
# up to one step from where the grid falls at the breakaway, so at first
# order it stays within a band of width one (widened by the smooth part's own
# $O(\rho)$ change, $\rho = \omega^2\Delta t\,t_{slip}$ at the largest step):

# %%
leine_errors = []
for dt in (8e-3, 4e-3, 2e-3):
    run = L.simulate_network(leine_belt, period_leine + 2 * dt, dt)
    stuck = run.states[:, 1] == 0
    last_stuck = np.flatnonzero(~stuck[1:] & stuck[:-1])
    onset = np.flatnonzero(stuck[1:] & ~stuck[:-1])[0] + 1
    x = run.positions[:onset, 0]
    leine_errors.append([(run.t[last_stuck[1]] - period_leine) / dt, (x.max() - x_hi) / dt, (x.min() - x_lo) / dt])
    print(f"dt = {dt:g} s: period {run.t[last_stuck[1]]:.3f} s, x_max {x.max():.5f} m, x_min {x.min():.5f} m; "
          f"errors over dt: " + ", ".join(f"{e:+.2f}" for e in leine_errors[-1]))
leine_errors = np.array(leine_errors)
t_slip_leine = next(e.time for e in motion.events if e.kind == "stop")
rho_leine = 8e-3 * t_slip_leine  # omega = 1
assert np.all(np.ptp(leine_errors, axis=0) <= [1, 0, 0] + rho_leine * np.abs(leine_errors).max(axis=0))
print(f"the errors over dt vary by {', '.join(f'{d:.2f}' for d in np.ptp(leine_errors, axis=0))} "
      f"(period, x_max, x_min) over a factor 4 in dt: first order")

# %% [markdown]
# ## Step 7: steady sliding on a Stribeck belt, and the Hopf speed
#
# With a smooth Stribeck fall the block can also slide steadily, at rest
# against the spring while the belt slips under it: $x^* = g(V)/k$. Take
# Veraszto and Stépán's hardware-in-the-loop parameters ($m = 0.538$ kg,
# $k = 6957$ N/m, a damper $b_0 = 5.746$ N s/m to the ground, and
# $g(s) = C + (C_0 - C)e^{-c_v s} + b_s s$ with $C = 2$ N, $C_0 = 6$ N,
# $c_v = 10$ s/m, $b_s = 0.2$ N s/m): the `friction` kind with `static` $= C_0$,
# `kinetic` $= C$, `stribeck_velocity` $= 1/c_v$ and `viscous` $= b_s$.
# Near $x^*$ the rate stays negative, $T = -g(V - v)$, and to first order
# $m\ddot y + \bigl(b_0 + g'(V)\bigr)\dot y + k y = 0$ for $y = x - x^*$: steady
# sliding is stable while $b_0 + g'(V) > 0$, and loses stability (a Hopf
# bifurcation) where the curve's fall equals the viscous drag:

# %%
b0, C, C0, cv, bs, mv, kv = 5.746, 2.0, 6.0, 10.0, 0.2, 0.538, 6957.0
s_ = sp.Symbol("s", positive=True)
g_ = C + (C0 - C) * sp.exp(-cv * s_) + bs * s_
V_hopf = sp.solve(sp.Eq(b0 + g_.diff(s_), 0), s_)
assert len(V_hopf) == 1
V_hopf = float(V_hopf[0])
print(f"Hopf speed: b0 + g'(V) = 0 at V = ln((C0 - C) c_v/(b0 + b_s))/c_v = {V_hopf:.5f} m/s")
assert math.isclose(V_hopf, math.log((C0 - C) * cv / (b0 + bs)) / cv, rel_tol=1e-12)


def stribeck_system(speed, offset):
    """The Stribeck belt at ``speed``, the block at rest ``offset`` beyond steady sliding x*; and x*."""
    x_star = float(g_.subs(s_, speed)) / kv
    net = parse_system(f"""
        [[mass]]
        name = "m"
        mass = {mv}
        x0 = {x_star + offset!r}
        [[driver]]
        name = "belt"
        velocity = {speed}
        [[element]]
        name = "spring"
        kind = "spring"
        between = ["ground", "m"]
        stiffness = {kv}
        [[element]]
        name = "damper"
        kind = "dashpot"
        between = ["ground", "m"]
        damping = {b0}
        [[element]]
        name = "contact"
        kind = "friction"
        between = ["belt", "m"]
        static = {C0}
        kinetic = {C}
        stribeck_velocity = {1 / cv}
        viscous = {bs}
    """)
    return net, x_star

# %% [markdown]
# The `event-driven` method integrates the motion itself, so the rates it
# shows are the system's. Start $10^{-6}$ m beyond $x^*$ at rest, at belt
# speeds around the Hopf speed, and fit a line to the logarithm of the swings
# (each maximum of $x$ less the minimum after it) over 1 s. They must meet the
# linear rate $\operatorname{Re}\lambda = -(b_0 + g'(V))/(2m)$ to within the
# terms it drops: the curve's slope averaged over the oscillation moves by
# $(c_v\,\omega A)^2/8$ of its fall for an amplitude $A$ (at most $1.3\times
# 10^{-5}$ m after the growth, at $0.8$ times the Hopf speed), computed below;
# the sampling every $h = 2\times10^{-5}$ s, each extreme taken as the vertex of
# the parabola through three samples, off by $O((\omega h)^2 h)$ in time and
# $O((\omega h)^4)$ relative in value, below $10^{-9}$; and DOP853's error at
# `rtol` $10^{-12}$ on $x^* \approx 4\times10^{-4}$ m over its 250 or so
# steps, below $10^{-6}$ of the oscillation. The bound asserted is twice their
# sum, the last two taken as $10^{-6}$ 1/s each:

# %%
def swings(t, y):
    """Each maximum of y less the minimum after it, at the maximum's time; each extreme the vertex of the
    parabola through its sample and the two beside it (the samples' own times would bias the rate by h/T)."""
    inner = y[1:-1]
    extremes = []
    for where in ((inner > y[:-2]) & (inner >= y[2:]), (inner < y[:-2]) & (inner <= y[2:])):
        i = np.flatnonzero(where) + 1
        a, b, c = y[i - 1], y[i], y[i + 1]
        curvature = a - 2 * b + c
        extremes.append((t[i] + 0.5 * (a - c) / curvature * (t[1] - t[0]), b - (a - c) ** 2 / (8 * curvature)))
    (t_top, top), (t_low, low) = extremes
    after = np.searchsorted(t_low, t_top)
    keep = after < t_low.size
    return t_top[keep], top[keep] - low[after[keep]]


def linear_rate(speed):
    return -(b0 + float(g_.diff(s_).subs(s_, speed))) / (2 * mv)


w_v = math.sqrt(kv / mv)
speeds = V_hopf * np.array([0.8, 0.9, 0.95, 1.05, 1.1, 1.2])
t = np.arange(50_001) * 2e-5
ed_rates = []
for speed in speeds:
    net, x_star = stribeck_system(speed, 1e-6)
    motion = solve_contact(net, 1.0, rtol=1e-12)
    assert not motion.events  # slides throughout: no stop
    ts, sw = swings(t, motion.state(t)[0])
    ed_rates.append(np.polyfit(ts, np.log(sw), 1)[0])
    amplitude = 1e-6 * math.exp(max(linear_rate(speed), 0.0))
    fall = (C0 - C) * cv * math.exp(-cv * speed)
    bound = 2 * ((cv * w_v * amplitude) ** 2 / 8 * fall / (2 * mv) + 1e-6 + 1e-6)
    assert abs(ed_rates[-1] - linear_rate(speed)) <= bound
    print(f"V = {speed:.4f} m/s ({speed / V_hopf:.2f} V_hopf): linear rate {linear_rate(speed):+.3f} 1/s, "
          f"event-driven {ed_rates[-1]:+.3f} 1/s (bound {bound:.0e} 1/s)")

# %% [markdown]
# Growing below the Hopf speed, decaying above it, at the linear rates. Below
# it the growth does not go on: once the oscillation's speed reaches the
# belt's, the block sticks, and the motion settles on a stick-slip cycle.
# From $10^{-5}$ m at $0.9$ and $1.1$ times the Hopf speed, over 6 s:

# %%
t = np.arange(60_001) * 1e-4
growth = {}
for factor in (0.9, 1.1):
    net, x_star = stribeck_system(factor * V_hopf, 1e-5)
    motion = solve_contact(net, 6.0, rtol=1e-10)
    ts, sw = swings(t, motion.state(t)[0])
    rate = linear_rate(factor * V_hopf)
    t_pred = np.linspace(0.0, min(6.0, math.log(2 * sw.max() / sw[0]) / rate) if rate > 0 else 6.0, 200)
    growth[f"$V = {factor:g}\\,V_{{hopf}}$"] = ((ts, sw), (t_pred, sw[0] * np.exp(rate * t_pred)))
    stops = [e.time for e in motion.events if e.kind == "stop"]
    last = sw[ts > 5.5]
    print(f"V = {factor:g} V_hopf: swing {sw[0]:.2e} m at the start, {last.min():.2e} to {last.max():.2e} m "
          f"after 5.5 s; " + (f"{len(stops)} stops, the first at {stops[0]:.2f} s" if stops else "no stop"))
speed_axis = np.linspace(0.7 * V_hopf, 1.3 * V_hopf, 200)
fig = P.stribeck_stability(growth, (speeds, np.array(ed_rates)), (speed_axis, [linear_rate(v) for v in speed_axis]),
                           V_hopf)
_ = P.save_figure(fig, "fr03_stribeck_stability")


# %% [markdown]
# Run backward Euler from $y = 10^{-5}$ m at rest, at belt speeds below and
# above it, and measure the growth rate of the oscillation from its peaks in
# the first and last periods. A backward-Euler step multiplies a mode
# $e^{\lambda t}$ by $1/(1 - \Delta t\,\lambda)$, so its own rate is
# $-\ln|1 - \Delta t\,\lambda|/\Delta t$, lower than $\operatorname{Re}\lambda$
# by about $\omega^2\Delta t/2$ (numerical damping, here 0.65 1/s):

# %%
def stribeck_belt(speed, offset, dt=1e-4, t_end=0.25):
    net, x_star = stribeck_system(speed, offset)
    run = L.simulate_network(net, t_end, dt)
    return run, run.positions[:, 0] - x_star


dt, period = 1e-4, 2 * math.pi / math.sqrt(kv / mv)
n = round(period / dt)
for speed in (0.15, 0.25):
    lam = np.roots([mv, b0 + float(g_.diff(s_).subs(s_, speed)), kv])[0]
    run, y = stribeck_belt(speed, 1e-5, dt)
    i0, i1 = np.abs(y[:n]).argmax(), y.size - n + np.abs(y[-n:]).argmax()
    rate = math.log(abs(y[i1] / y[i0])) / (run.t[i1] - run.t[i0])
    assert np.all(run.states[:, -1] != 0) and np.sign(rate) == np.sign(lam.real)  # slides throughout
    print(f"V = {speed} m/s: Re(lambda) = {lam.real:+.2f} 1/s, backward Euler's linear rate "
          f"{-math.log(abs(1 - dt * lam)) / dt:+.2f} 1/s, measured {rate:+.2f} 1/s")

# %% [markdown]
# Below the Hopf speed the oscillation grows (it will grow into stick-slip),
# above it decays, and the measured rates agree with backward Euler's linear
# prediction to a few per cent (the remainder is the measurement from two
# peaks). The numerical damping moves backward Euler's own Hopf speed down,
# to where its linear rate vanishes:

# %%
def be_rate(speed, dt):
    lam = np.roots([mv, b0 + float(g_.diff(s_).subs(s_, speed)), kv])[0]
    return -math.log(abs(1 - dt * lam)) / dt


for dt in (1e-4, 1e-5):
    print(f"dt = {dt:.0e} s: backward Euler's steady sliding loses stability below "
          f"{brentq(be_rate, 0.05, 0.3, args=(dt,)):.4f} m/s (exact: {V_hopf:.4f} m/s)")

# %% [markdown]
# ## Step 8: a curve invertible neither way, and its jumps
#
# The `curve` element is a relation between rate and tension given by points
# along it, which may fold back in both coordinates. The S through $(0, 0)$,
# $(2, 2)$, $(1, 3)$, $(3, 5)$ has three branches: 1, $T = u$ for $u \le 2$;
# 2, $T = 4 - u$ for $1 \le u \le 2$ (falling); 3, $T = u + 2$ for $u \ge 1$.
# Between $u = 1$ and $2$ each rate has three tensions, so neither $T(u)$ nor
# $u(T)$ is a function, and a mass pulled by a constant $P = 2.5$ N between
# them cannot settle: on branch 1, $m\dot u = P - u$ carries it to the fold
# at $u = 2$ after $m\ln 5$; there the tension must jump, at constant rate
# (a mass's velocity cannot jump), to branch 3, where $m\dot u = P - 2 - u$
# carries it down to the fold at $u = 1$ after $m\ln 3$, and back to branch 1:
# a relaxation oscillation. This is the **delay convention** (the element
# stays on its branch until the branch ends, so it jumps up at $u = 2$ and
# down at $u = 1$: hysteresis). Backward Euler holds the step that reaches a
# fold at the fold's rate and puts the element on the branch beyond from the
# next step; the trajectory records each change of branch as an event:

# %%
pulled = L.Network(
    [L.Mass("m", 1.0)], [L.Curve("c", ("ground", "m"), points=[[0, 0], [2, 2], [1, 3], [3, 5]])],
    [L.Load("m", L.Constant(2.5))],
)
dt = 1e-3
run = L.simulate_network(pulled, 6.0, dt)
exact_jumps = np.cumsum([math.log(5.0)] + [math.log(3.0)] * (len(run.jumps) - 1))  # m = 1 kg
for j, t_exact in zip(run.jumps, exact_jumps):
    print(f"t = {j.time:.3f} s: '{j.element}' jumps from branch {j.before} to {j.after} "
          f"(exact {t_exact:.4f} s, {(j.time - t_exact) / dt:.2f} dt later)")
assert [(j.before, j.after) for j in run.jumps] == [(1, 3), (3, 1), (1, 3), (3, 1)]

# %% [markdown]
# Each jump comes late by backward Euler's own lag on the branches before it
# (on a piece of slope $b$ its step is $u_{n+1} - u_{eq} = (u_n - u_{eq})/(1 +
# b\,\Delta t/m)$, slow by a factor $(1 + h/2)$ at first order, $h = \Delta t/m$)
# and at most one step at each fold: the $k$-th jump is late by between
# $\Delta t\,(S/2)(1 - h/6)$ and $\Delta t\,(S/2 + k)$, with $S$ the sum of the
# $\ln r$ of the stretches before it (`tests/test_curve_element.py` derives
# this and checks the steps exactly):

# %%
late = np.array([j.time for j in run.jumps]) - exact_jumps
k_jump = np.arange(1, late.size + 1)
assert np.all((late > dt * exact_jumps / 2 * (1 - dt / 6)) & (late <= dt * (exact_jumps / 2 + k_jump)))
print("late by " + ", ".join(f"{e / dt:.2f}" for e in late) + " steps; bands: "
      + ", ".join(f"({s / 2 * (1 - dt / 6):.2f}, {s / 2 + k:.2f}]" for s, k in zip(exact_jumps, k_jump)))

# %% [markdown]
# The other convention, **Maxwell's**, would put the element on one branch
# chosen by the rate alone and jump both ways at the one rate where the areas
# cut off between the vertical line $u = c$ and the curve are equal. For this
# S the two areas are $(2 - c)^2$ (between branches 1 and 2) and $(c - 1)^2$
# (between 2 and 3), equal at $c = 3/2$:

# %%
c_, T_ = sp.symbols("c T", real=True)
lower = sp.integrate(T_ - c_, (T_, c_, 2)) + sp.integrate(4 - T_ - c_, (T_, 2, 4 - c_))
upper = sp.integrate(c_ - (4 - T_), (T_, 4 - c_, 3)) + sp.integrate(c_ - (T_ - 2), (T_, 3, c_ + 2))
maxwell = sp.solve(sp.Eq(sp.factor(lower), sp.factor(upper)), c_)
assert maxwell == [sp.Rational(3, 2)]
print(f"areas {sp.factor(lower)} and {sp.factor(upper)}: equal at c = {maxwell[0]}")

# %% [markdown]
# There the pulled mass, below $u = 3/2$ on branch 1 (heading for $u = 2.5$)
# and above it on branch 3 (heading for $u = 0.5$), would be sent back across
# $u = 3/2$ from either side: no relaxation oscillation and no hysteresis,
# but a rate held at $3/2$ with the tension switching between its branches
# (1.5 N and 3.5 N, averaging the pull 2.5 N). The delay convention is the
# one that a stiff spring in series with the curve gives in the limit
# (`lumped.laws.curve`'s docstring), and the one the package runs.

# %% [markdown]
# ## What to take away
#
# * A friction contact with static above kinetic, or a Stribeck fall, has a
#   graph that is monotone neither way; one backward-Euler step of it is the
#   scalar problem (3) with several solutions, and the package picks one by
#   the contact's state: stuck stays stuck within $S$, slipping slips until
#   its rate would change sign.
# * On a falling curve the slip branch itself can give two roots; for one mass
#   the step is unique when $m/\Delta t + k\Delta t$ exceeds the steepest fall
#   $\lambda$, here $\Delta t < 0.02001$ s, and `lumped.simulate_network`
#   refuses a longer step in one line.
# * The belt oscillator's limit cycle has a closed form (period 8.9026 s for
#   these values, 5 s of it stuck), derived here and computed by the package
#   in one place (`belt_cycle`); `exact` meets it to $10^{-12}$ s, backward
#   Euler at first order: its period is short by $4.88\,\Delta t$ (its damping
#   of the slip) to $5.88\,\Delta t$ (the breakaway's place on the grid).
# * Any falling slip curve is one line (`lumped.SlipCurve`): on Leine's
#   benchmark `event-driven` gives the cycle's period, 12.001031 s, and its
#   turning points, and backward Euler approaches them at first order.
# * Smoothing with `tanh` turns the stick into creep of a few $\varepsilon$,
#   misses the period by 19 % to 1 % for $\varepsilon$ from $10^{-2}$ to
#   $10^{-4}$ m/s, and costs an explicit integrator steps in proportion to
#   $1/\varepsilon$.
# * On a Stribeck belt steady sliding is stable above the speed where the
#   curve's fall equals the viscous drag (0.1906 m/s for Veraszto and Stépán's
#   parameters) and unstable below it: `event-driven` grows and decays at the
#   linear rates (fr03), and below it the growth ends in stick-slip; backward
#   Euler's numerical damping moves that speed down in proportion to
#   $\Delta t$.
# * A `curve` invertible neither way makes the motion jump at its folds; the
#   package follows the delay convention (each jump at its own fold:
#   hysteresis), records each change of branch as an event, and backward
#   Euler's jump times are late by its lag, within the derived bands.
