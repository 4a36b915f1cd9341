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
# # 2. Why the textbook model with $\operatorname{sgn}(0) = 0$ fails
#
# **What you will learn.** Section 2.2 of the paper takes the usual textbook
# treatment of a mass with Coulomb-like friction, in which the friction force is
# *prescribed* by the sign of the velocity, and shows that it breaks down for a
# mass released at rest with a small spring stretch, $|x_0| < \mu_s N_f/k$.
# Here we
#
# * prove, with numbers, that this initial-value problem has no classical
#   (Carathéodory) solution;
# * watch what numerical integrators do with it instead: explicit fixed-step
#   schemes chatter, an adaptive Runge-Kutta method collapses its step, and an
#   implicit one "succeeds" with a physically impossible answer;
# * measure how the common fix, replacing $\operatorname{sgn}(v)$ by
#   $\tanh(v/\varepsilon)$, turns sticking into slow creep towards the
#   unstretched spring, at a rate we predict in closed form;
# * see how Filippov's set-valued right-hand side, eq. (11), and the DAE of
#   notebook 1 both pick the one dashpot force, $-k x_0$, that keeps the mass
#   at rest.
#
# The mass starts halfway into the static band, $x_0 = \mu_s N_f/(2k)$: with
# the paper's parameters (section 3) that is $x_0 = 0.005$ m, the stretch of
# its Figure 10, and the numbers and outcomes quoted in the prose are for
# those parameters. The printed ones are for `config/config.yaml` as given.

# %%
# %matplotlib inline
import numpy as np
from scipy.optimize import brentq

import lumped as L
import lumped.studies.config
import lumped.studies.examples
from lumped.solvers import textbook as T
from lumped.plotting.textbook import acceleration_graph, chatter, creep

cfg = lumped.studies.config.load()
osc = lumped.studies.examples.oscillator(cfg)
m, k, tau, dt = cfg["mass"], cfg["stiffness"], cfg["threshold"], cfg["dt"]
x0 = osc.static_band / 2  # halfway into the band: the paper's Figure 10 case
model = T.TextbookModel(osc)  # sgn(0) = 0
print(f"x0 = {x0} m, static band mu_s N_f / k = {osc.static_band} m, k x0 = {k * x0} N")

# %% [markdown]
# ## Step 1: the textbook model
#
# The textbook way writes the dashpot force as a function of the velocity,
# $F_d = \operatorname{sgn}(\dot x)\,(\mu_s N_f + |\dot x|/\gamma)$, and
# substitutes it into the momentum balance (1):
#
# $$m\ddot x = F(t) - kx - \operatorname{sgn}(\dot x)\Bigl(\mu_s N_f + \frac{|\dot x|}{\gamma}\Bigr),
#   \qquad \operatorname{sgn}(0) = 0.$$
#
# Away from $\dot x = 0$ this is the slip branch of eq. (6). At $\dot x = 0$ it
# decrees $F_d = 0$, whereas eq. (6) allows any force in $[-\mu_s N_f,
# \mu_s N_f]$. For our mass ($F = 0$, $x_0 = 0.005$ m, inside the band of
# half-width $0.01$ m) that single choice is the whole trouble.

# %% [markdown]
# ## Step 2: no classical solution
#
# Write the model as $\dot z = f(z)$ with $z = (x, v)$. A solution in the sense
# of Carathéodory, Definition 2.2 and eq. (9), is an absolutely continuous
# $z(t)$ with $z(t) = z_0 + \int_0^t f(z(s))\,ds$. Evaluate $f$ at the initial
# state and just beside it, on either side of $v = 0$:

# %%
for v in (0.0, 1e-12, -1e-12):
    print(f"v = {v:+.0e} m/s:  acceleration = {model.rhs(0.0, np.array([x0, v]))[1]:+.4f} m/s^2")

# %% [markdown]
# Three cases exhaust the possibilities for a candidate solution on a short
# interval $[0, T]$:
#
# * **it stays at rest**, $v \equiv 0$, $x \equiv x_0$: then the integral
#   equation demands $0 = v(t) = \int_0^t (-0.5)\,ds = -0.5\,t$, false for every
#   $t > 0$. The intuitive "solution" $x(t) = x_0$ is not a solution;
# * **it moves forward** somewhere, $v(t_1) > 0$: let $t_0$ be the last time
#   before $t_1$ with $v = 0$. On $(t_0, t_1]$ the acceleration is $(-kx -
#   \mu_s N_f - v/\gamma)/m < 0$ as long as $x > -\mu_s N_f/k$, so
#   $v(t_1) = \int_{t_0}^{t_1} \dot v\,ds < 0$, a contradiction;
# * **it moves backward**, $v(t_1) < 0$: the same argument with the
#   acceleration $(-kx + \mu_s N_f - v/\gamma)/m > 0$ while $x < \mu_s N_f/k$
#   gives $v(t_1) > 0$, again a contradiction.
#
# The two sign conditions hold throughout the static band, which we check on a
# grid of states:

# %%
xs = np.linspace(-0.999, 0.999, 201) * osc.static_band
vs = np.geomspace(1e-12, 1e-1, 12)
acc = {s: np.array([[model.rhs(0.0, np.array([x, s * v]))[1] for v in vs] for x in xs])
       for s in (1, -1)}
assert np.all(acc[1] < 0) and np.all(acc[-1] > 0)
print(f"v > 0: acceleration in [{acc[1].min():+.3f}, {acc[1].max():+.3f}] m/s^2, all negative")
print(f"v < 0: acceleration in [{acc[-1].min():+.3f}, {acc[-1].max():+.3f}] m/s^2, all positive")

# %% [markdown]
# Whichever way the mass moves, the friction pushes it back harder than the
# spring pulls; and if it does not move, the spring is unbalanced because the
# model has set the friction to zero. No absolutely continuous function solves
# the problem. Numerical methods do not know this and produce *something*.

# %% [markdown]
# ## Step 3: fixed-step explicit schemes chatter
#
# Forward Euler, from rest: the first step sees $\dot v = -0.5$ and gives
# $v < 0$; the next sees the friction push back with $+1$ N and flips the
# velocity, and so on. We count the sign changes of the velocity over one
# second and look at the dashpot force. The DAE's answer is a mass at rest
# with $F_d = -k x_0 = -0.5$ N at every instant.

# %%
print(" dt (s)   flips of v   F_d > 0   miss (N)   mean F_d (N)   drift (m)")
euler = {}
for h in (1e-3, 1e-4, 1e-5):
    r = euler[h] = T.integrate_fixed(model, 1.0, h, x0=x0, scheme="euler")
    print(f"{h:7.0e} {r.sign_changes:12d} {np.mean(r.F_d > 0):9.1%} {np.abs(r.F_d + k * x0).min():10.3f}"
          f" {r.F_d.mean():+14.5f} {r.x[-1] - x0:+11.2e}")
print("flips of v: sign changes of the velocity in 1 s;  F_d > 0: share of the steps with F_d > 0;\n"
      "miss: smallest |F_d - (-k x0)|, how close F_d comes to the force that holds the mass;\n"
      "mean F_d: time average of F_d;  drift: x(1 s) - x0")
# The textbook force is 0 or at least tau in size, so it misses -k x0 by at least
# min(k x0, tau - k x0) (rounding is monotone, so also in floating point).
assert all(np.abs(r.F_d + k * x0).min() >= min(k * x0, tau - k * x0) for r in euler.values())

# %% [markdown]
# The velocity changes sign about once every two steps, at every step size: the
# number of sign changes grows like $1/(2\Delta t)$ and does not converge. The
# dashpot force jumps between $\approx +1$ and $\approx -1$ N (a quarter of the
# steps at $+1$) and never comes closer than $0.5$ N to the force that would
# hold the mass (the column "miss"). Two things do converge as $\Delta t \to 0$: the drift of the mass
# (proportional to $\Delta t$) and the *time average* of the chattering force,
# which approaches $-0.5$ N. Keep that average in mind for Step 6.
#
# The classical fourth-order Runge-Kutta method hides the chatter inside its
# steps. Its stages are evaluated at velocities of both signs; we record them
# with a model that logs every velocity it is called with.

# %%
stage_v = []


class LoggingModel(T.TextbookModel):
    def rhs(self, t, z):
        stage_v.append(z[1])
        return super().rhs(t, z)


print(" dt (s)   flips of v   mixed steps   mean F_d (N)   drift (m)")
rk4 = {}
for h in (1e-3, 1e-4, 1e-5):
    stage_v.clear()
    r = rk4[h] = T.integrate_fixed(LoggingModel(osc), 1.0, h, x0=x0, scheme="rk4")
    s = np.sign(np.reshape(stage_v, (-1, 4)))
    mixed = np.mean((s.max(axis=1) > 0) & (s.min(axis=1) < 0))
    print(f"{h:7.0e} {r.sign_changes:12d} {mixed:13.1%} {r.F_d.mean():+14.5f} {r.x[-1] - x0:+11.2e}")
print("mixed steps: share of the steps whose four stages see velocities of both signs")

# %% [markdown]
# At the step points RK4's velocity never changes sign; it settles to a small
# negative value, of order $\Delta t$, so the dashpot force sits at $-1$ N and
# the mass creeps towards the spring's rest length at a speed proportional to
# $\Delta t$. Inside the steps, about half of them (61% at $\Delta t = 10^{-3}$,
# 51% and 50% at the smaller steps: the column "mixed steps") evaluate the
# right-hand side on both sides of $v = 0$: the chatter is still there,
# averaged away by the Runge-Kutta weights. The figure shows the first two
# milliseconds of both schemes against the DAE (dashed). Forward Euler is the
# wide light line: between its jumps to $+1$ N it sits at $-1$ N together with
# RK4, the thin line drawn on top of it.

# %%
reference = L.backward_euler(osc, 1.0, dt, x0=x0)
fig = chatter({r"forward Euler, $\Delta t = 10^{-4}$": euler[1e-4],
               r"RK4, $\Delta t = 10^{-4}$": rk4[1e-4]}, reference, t_max=2e-3)

# %% [markdown]
# ## Step 4: an adaptive integrator collapses its step
#
# An adaptive method tries to meet a tolerance by shrinking its step near the
# discontinuity. Here the discontinuity is *everywhere* along the computed path,
# so the step keeps shrinking. We give `solve_ivp`'s RK45 a budget of $10^5$
# right-hand-side evaluations (the wall-time budget is set far out of reach, so
# the outcome is deterministic on one machine) and ask it for one second. Its
# step sizes follow round-off here (every step straddles the discontinuity),
# so the run is printed as the decades it falls in, not to its last digits.

# %%
rk45 = T.integrate_adaptive(model, 1.0, x0=x0, method="RK45", rtol=1e-8, atol=1e-10,
                            max_nfev=100_000, max_seconds=600.0)
steps = rk45.t.size - 1
assert not rk45.finished and 1e-6 < rk45.t_reached < 1e-4 and 1e3 < steps < 1e4 and 1e-9 < rk45.median_step < 1e-8
print(f"finished: {rk45.finished}, t reached: between 1e-6 and 1e-4 s of 1 s")
print(f"evaluations: {rk45.nfev >= 100_000 and 'the budget of 1e5'}, accepted steps: between 1e3 and 1e4, "
      f"median step: between 1e-9 and 1e-8 s")

# %% [markdown]
# After $10^5$ evaluations RK45 has advanced about $10^{-5}$ s, with a median
# step of a couple of nanoseconds; at that pace one second would take of the
# order of $10^{10}$ evaluations.
#
# An implicit, stiff solver is not a way out. `solve_ivp`'s BDF method reports
# success after a few dozen evaluations, but its answer is impossible: a model
# whose only non-conservative force dissipates cannot *gain* energy, and this
# one gains a lot.

# %%
bdf = T.integrate_adaptive(model, 1.0, x0=x0, method="BDF", rtol=1e-8, atol=1e-10,
                           max_nfev=100_000, max_seconds=600.0)
energy = lambda x, v: 0.5 * m * v**2 + 0.5 * k * x**2  # noqa: E731
gain = energy(bdf.x[-1], bdf.v[-1]) / energy(x0, 0.0)
a0 = model.rhs(0.0, np.array([x0, 0.0]))[1]  # the acceleration at v = 0, -k x0 / m
off_path = np.abs(bdf.x - (x0 + a0 * bdf.t**2 / 2)).max()
assert bdf.nfev < 100 and off_path < 1e-7  # BDF's count and error follow round-off: printed as bounds
print(f"finished: {bdf.finished}, evaluations: fewer than 100, "
      f"x({bdf.t[-1]:.3g}) = {bdf.x[-1]:+.4f} m, v = {bdf.v[-1]:+.4f} m/s")
print(f"energy: {energy(x0, 0.0):.3g} J at t = 0, {energy(bdf.x[-1], bdf.v[-1]):.3g} J at "
      f"t = {bdf.t[-1]:.3g} s, {gain:.0f} times as much")
print(f"largest distance from x0 + a0 t^2/2 (a0 = {a0:+.3f} m/s^2): below 1e-7 m")

# %% [markdown]
# The returned path, $x \approx x_0 + a_0 t^2/2$ ($x_0 - t^2/4$
# with the paper's values), is that of a mass under the constant acceleration
# $a_0 = -kx_0/m$ ($-0.5$ m/s²) that the right-hand side has only at $v = 0$:
# as if the spring force stayed frozen at its initial value $-kx_0$ and friction
# were absent once the mass moved. A silent
# wrong answer is worse than the honest stall of RK45.

# %% [markdown]
# ## Step 5: regularisation creeps instead of sticking
#
# A common repair smooths the switch: $\operatorname{sgn}(v) \to \tanh(v/\varepsilon)$
# with a small velocity scale $\varepsilon$. The ODE then has a unique smooth
# solution, but its only equilibrium is $x = 0$, $v = 0$: the minimiser of the
# spring energy, not the stretched rest state of the real device. For
# $|v| \ll \varepsilon$ the friction acts like a very strong viscous damper,
# $\mu_s N_f\, v/\varepsilon$, and the mass slowly creeps. Neglecting inertia
# the force balance $kx + \mu_s N_f \tanh(v/\varepsilon) + v/\gamma = 0$ fixes
# the creep velocity $v_{qs}(x)$ (quasi-static: found below by a root finder).
# Linearised at $x = 0$, with $c = 1/\gamma$,
#
# $$v_{qs} \approx -\frac{k\,\varepsilon}{\mu_s N_f + c\,\varepsilon}\,x,$$
#
# valid when $k|x| \ll \mu_s N_f$: an exponential decay at the rate
# $k\varepsilon/(\mu_s N_f + c\varepsilon)$, the definition the article uses
# (`TextbookModel.creep_rates`, whose second value keeps the inertia: the slow
# root of $m s^2 + (c + \mu_s N_f/\varepsilon) s + k = 0$). We integrate for
# five seconds with an adaptive stiff solver (LSODA), measure the rate
# $\dot x/x$ at the end and compare it with both linear rates and with
# $v_{qs}(x)/x$.

# %%
def creep_velocity(x, eps):
    """Root of k x + tau tanh(v/eps) + v/gamma = 0, for 0 < k x < tau.

    The balance is k x > 0 at v = 0 and negative at twice the frictionless
    root, v = -2 eps artanh(k x/tau), since tanh(2a) > tanh(a) for a > 0 and
    v/gamma <= 0 there: a bracket also for gamma = inf, where the root is the
    frictionless one itself.
    """
    balance = lambda v: k * x + tau * np.tanh(v / eps) + osc.dashpot.viscosity * v  # noqa: E731
    return brentq(balance, -2 * eps * np.arctanh(k * x / tau), 0.0, xtol=1e-300, rtol=1e-15)


print("eps (m/s)  x(5 s) (m)  k x/tau   rate (1/s)  rate/linear  rate/inertial  rate/q-s  inertia")
smooth = {}
for eps in (1e-2, 1e-3, 1e-4, 1e-5):
    model = T.TextbookModel(osc, eps=eps)
    run = smooth[eps] = T.integrate_adaptive(model, 5.0, x0=x0, method="LSODA", rtol=1e-8,
                                             atol=1e-12, max_seconds=600.0)
    x, rate = run.x[-1], run.v[-1] / run.x[-1]
    linear, inertial = model.creep_rates()  # -k eps/(tau + c eps), and with m x'' kept
    quasi = creep_velocity(x, eps) / x
    inertia = m * k * eps**2 / tau**2  # relative size of the neglected m x''
    assert run.finished and run.v[-1] != 0.0 and abs(rate / quasi - 1) < 2 * inertia + 1e-5
    print(f"{eps:9.0e} {x:10.2e} {k * x / tau:8.4f} {rate:11.4f} {rate / linear:11.3f}"
          f" {rate / inertial:13.3f} {rate / quasi:9.4f} {inertia:8.0e}")
print("rate: measured v/x at 5 s;  linear: -k eps/(tau + c eps), quasi-static, linearised at x = 0;\n"
      "inertial: the slow root of m s^2 + (c + tau/eps) s + k = 0;  q-s: v_qs(x)/x at that x;\n"
      "inertia: m k eps^2/tau^2, relative size of the neglected m x''")

# %% [markdown]
# The measured creep rate is proportional to $\varepsilon$, as predicted. It
# matches the quasi-static rate $v_{qs}/x$ (column "rate/q-s") up to the
# inertia that the force balance neglects: with the damping
# $b \approx \mu_s N_f/\varepsilon$ the slow decay rate of
# $m\ddot x + b\dot x + kx = 0$ differs from $k/b$ by a relative amount
# $\approx mk/b^2 = mk\varepsilon^2/(\mu_s N_f)^2$, the column "inertia":
# 1% for $\varepsilon = 10^{-2}$, $10^{-4}$ for $\varepsilon = 10^{-3}$, and
# below the printed digits for smaller $\varepsilon$.
#
# Against the linear quasi-static rate $-k\varepsilon/(\mu_s N_f + c\varepsilon)$
# (column "rate/linear") the measured rate is within 10%. For the three
# smaller $\varepsilon$ the excess is the nonlinearity of $\tanh$: at
# $t = 5$ s the mass is still at $x$ between 0.003 and 0.005 m, so $kx/\mu_s N_f$
# (printed) is still 0.3 to 0.5. For $\varepsilon = 10^{-2}$ the mass has crept
# almost to $x = 0$, where $\tanh$ is linear ($kx/\mu_s N_f$ below 0.01), and the
# 1% excess is inertia, not nonlinearity: the measured rate is the slow root
# of the linearised equation with $m\ddot x$ kept (column "rate/inertial",
# 1.000).
#
# Making $\varepsilon$ smaller slows the creep but never stops it: the velocity
# at 5 s is small but not zero in every run (asserted above), and the only
# state the regularised model can rest in is $x = 0$. In the figure the dashed
# line is the DAE's rest position, which the smallest $\varepsilon$ follows
# closely but still leaves.

# %%
fig = creep(smooth, rest=reference.rest_position)

# %% [markdown]
# ## Step 6: Filippov's set-valued right-hand side and the DAE
#
# Filippov's way out, eqs. (10) and (11), keeps the two slip branches for
# $v \ne 0$ and replaces the single value at $v = 0$ by a *set* of
# accelerations,
#
# $$\mathcal F_0 = \Bigl\{\Bigl(\tfrac{1}{m}\bigl(F - F_s - F_d\bigr),\ 0\Bigr) : |F_d| \le \mu_s N_f\Bigr\}. \tag{11c}$$
#
# The set is convex, and the conditions of Filippov's existence theorem hold,
# so a solution exists. At $x_0$ the set of accelerations is an interval;
# if it contains $0$, the mass can stay at rest, with the dashpot force that
# makes the acceleration vanish.

# %%
lo, hi = osc.dashpot.force_interval(0.0)
acc_set = sorted(((0.0 - k * x0 - lo) / m, (0.0 - k * x0 - hi) / m))
selected = 0.0 - k * x0  # the F_d of the band with zero acceleration
assert acc_set[0] <= 0.0 <= acc_set[1] and lo <= selected <= hi
print(f"accelerations at v = 0: [{acc_set[0]:+.2f}, {acc_set[1]:+.2f}] m/s^2, contains 0")
print(f"zero acceleration at F_d = F - k x0 = {selected:+.2f} N, inside [{lo}, {hi}] N")

# %%
fig = acceleration_graph(osc, x0, v_max=0.5)

# %% [markdown]
# The figure is the picture of Step 2 completed: the two slip branches start at
# $-1.5$ and $+0.5$ m/s² on either side of $v = 0$, and the segment (11c) joins
# them, crossing zero at $F_d = -0.5$ N. The textbook model picked the single
# point $F_d = 0$ (acceleration $-0.5$) from that segment; Filippov's
# formulation lets the dynamics pick the point that works.
#
# The DAE of notebook 1 makes the same choice without being told: Algorithm 1
# and the exact event-driven solver treat $F_d$ as an unknown and return it.

# %%
exact = L.solve_exact(osc, 1.0, x0=x0)
sampled = exact.sample(dt)
assert np.all(reference.v == 0.0) and np.all(reference.F_d == selected)
assert np.all(sampled.v == 0.0) and np.all(sampled.F_d == selected)
print(f"Algorithm 1: F_d in [{reference.F_d.min():+.4f}, {reference.F_d.max():+.4f}] N, "
      f"rest from t = {reference.rest_time} s at x = {reference.rest_position} m")
print(f"exact solver: events {[(e.kind, e.time) for e in exact.events]}, "
      f"F_d = {sampled.F_d[0]:+.4f} N, rest at x = {exact.rest_position} m")

# %% [markdown]
# ## What to take away
#
# * With $\operatorname{sgn}(0) = 0$ the textbook model of a mass at rest inside
#   the static band has no classical solution: at $v = 0$ the acceleration is
#   $-0.5$ m/s², for $v > 0$ it is below $-1.5$, for $v < 0$ above $+0.5$.
# * Numerical methods hide this in different ways: forward Euler flips the
#   velocity about once every two steps, whatever the step; RK4 drifts with
#   stages on both sides of $v = 0$; RK45 stalls near $t = 10^{-5}$ s after
#   $10^5$ evaluations; BDF "succeeds" with a trajectory that gains energy.
# * Regularising with $\tanh(v/\varepsilon)$ gives a well-posed ODE whose mass
#   creeps towards $x = 0$ at the rate $\approx k\varepsilon/(\mu_s N_f + c\varepsilon)$
#   (within 10%; near $x = 0$ the rest is inertia, and to about $10^{-4}$ or
#   better with the quasi-static balance once $\varepsilon \le 10^{-3}$): it
#   never sticks, and its rest state is the
#   energy minimiser, not the stretched state the device keeps.
# * The dashpot force at rest must be an unknown. Filippov's set (11c) and the
#   DAE solvers select $F_d = -k x_0 = -0.5$ N, the value the chattering
#   forward-Euler force only reaches on average.
