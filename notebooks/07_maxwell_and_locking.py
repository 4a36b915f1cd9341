# ---
# jupyter:
#   jupytext:
#     formats: ipynb,py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 7. The Maxwell element and a relation invertible neither way
#
# **What you will learn.** Two elements built from the Bingham dashpot of
# eq. (6). The *Maxwell-Bingham* element puts a spring in series with the
# dashpot: held at a fixed stretch it relaxes, but only down to the threshold,
# never to zero, and below the threshold it does not relax at all. The
# *locking* Bingham dashpot adds a speed limit: no motion below the threshold,
# no speed above $v_{\text{lock}}$, whatever the force. Its graph can be read
# neither as force from rate nor as rate from force, yet backward Euler
# integrates it exactly as it integrates the others. Each claim is checked
# against a closed form.

# %%
import math

import lumped as L
import lumped.plotting as P
import numpy as np
from lumped import Bingham, LockingBingham, Mass, MaxwellBingham, Network, Spring, simulate_network

print("elements:", ", ".join(cls.__name__ for cls in (MaxwellBingham, LockingBingham)))

# %% [markdown]
# ## The Maxwell-Bingham element
#
# A spring of stiffness $k_m$ (N/m) in series with a Bingham dashpot
# (threshold $\mu_s N_f$, slope $\gamma$) carries one force $f$ through both.
# The element's elongation rate $w$ (m/s) is the sum of the spring's, $\dot f/k_m$,
# and the dashpot's, $\varphi(f)$, with $\varphi$ eq. (6):
# $$\dot f = k_m\,\big(w - \varphi(f)\big), \qquad \varphi(f) = \gamma\,\operatorname{sgn}(f)\,\max(|f| - \mu_s N_f,\ 0).$$
# The force is the element's state: it is not fixed by $e$ and $w$ at one
# instant, it remembers the history.
#
# ### Relaxation under a held stretch
#
# Hold the element at a fixed elongation ($w = 0$) with an initial force
# $f_0$. If $|f_0| \le \mu_s N_f$ the dashpot holds and nothing changes. If
# $f_0 > \mu_s N_f$ the dashpot creeps, $\dot f = -k_m\gamma\,(f - \mu_s N_f)$,
# and the force relaxes exponentially to the threshold, not to zero:
# $$f(t) = \mu_s N_f + (f_0 - \mu_s N_f)\,e^{-k_m\gamma t}.$$
# Backward Euler replaces the exponential by $(1 + \Delta t\,k_m\gamma)^{-n}$
# at $t_n = n\Delta t$: a first-order approximation of the same curve.
#
# The stretch is $0.05$ m; with $f_0 = k_m \times 0.05 = 5$ N the spring
# takes all of it and the dashpot starts unstretched (a sudden stretch),
# while $f_0 = 0.5$ N describes a dashpot that has already crept by
# $0.05 - 0.5/k_m$. To hold the stretch, the element joins the ground to a mass that a Coulomb
# element of very large threshold glues to the ground (it sticks, so the mass
# does not move at all).

# %%
k_m, tau, gamma, dt = 100.0, 1.0, 1.0, 1e-3  # N/m, N, m/(N s), s
stretch = 0.05  # m


def held(f0: float) -> Network:
    """The Maxwell-Bingham element at a held stretch, starting with force f0 (N)."""
    glue = Bingham("glue", ("ground", "m"), 1e6, math.inf)
    element = MaxwellBingham("maxwell", ("ground", "m"), k_m, tau, gamma, force0=f0)
    return Network([Mass("m", 1.0, stretch)], [glue, element])


runs = {f0: simulate_network(held(f0), 0.1, dt) for f0 in (0.5, 5.0)}
for f0, tr in runs.items():
    print(f"f0 = {f0} N: mass moved {np.abs(tr.positions[:, 0] - stretch).max():.1e} m; force at t = 0.1 s {tr.forces[-1, 1]:.6f} N")

# %% [markdown]
# With $f_0 = 0.5$ N, inside the band, the force stays $0.5$ N; with
# $f_0 = 5$ N it falls to the threshold $1$ N and stays there. The check
# against both closed forms, the discrete one (to rounding) and the
# exponential (to first order in $\Delta t$):

# %%
tr, f0 = runs[5.0], 5.0
n = np.arange(tr.t.size)
discrete = tau + (f0 - tau) / (1 + dt * k_m * gamma) ** n
exact = tau + (f0 - tau) * np.exp(-k_m * gamma * tr.t)
# 1e-12 N: the closed form and the step round differently, by a few ulps of 5 N per step
print(f"|f - discrete closed form| below 1e-12 N at every step: {np.abs(tr.forces[:, 1] - discrete).max() < 1e-12}")
print(f"max |f - exponential| = {np.abs(tr.forces[:, 1] - exact).max():.4f} N (dt k_m gamma = {dt * k_m * gamma})")
print(f"held force of f0 = 0.5 N: max |f - 0.5| = {np.abs(runs[0.5].forces[:, 1] - 0.5).max():.0e} N")

# %% [markdown]
# So the force at which the element slips is the dashpot's threshold: a
# Maxwell-Bingham element holds any force up to $\mu_s N_f$ indefinitely
# (a solid), and relaxes any larger force down to it (a fluid above a yield
# stress). The relaxation leaves a permanent set: the dashpot, unstretched at
# first, has crept by $(f_0 - \mu_s N_f)/k_m$, the stretch the spring gave up. Figure ext02 draws both
# runs with the exponential.

# %%
spring_part = tr.forces[-1, 1] / k_m
print(f"dashpot's stretch after relaxing: {stretch - spring_part:.5f} m "
      f"(closed form (f0 - mu_s N_f)/k_m at t -> inf: {(f0 - tau) / k_m:.5f} m)")
fig = P.network_history(
    {f"$f_0 = {f}$ N": r for f, r in runs.items()},
    "force",
    "maxwell",
    references={"exponential relaxation": (tr.t, exact)},
    levels={r"$\mu_s N_f$": tau},
)
_ = P.save_figure(fig, "ext02_maxwell_relaxation")

# %% [markdown]
# ## The locking Bingham dashpot: invertible neither way
#
# Add to the Bingham law a speed limit $v_{\text{lock}}$: the rate $w$ may not
# exceed $v_{\text{lock}}$ in magnitude, and holding it there takes any force
# beyond $\mu_s N_f + v_{\text{lock}}/\gamma$. Take $\gamma = \infty$
# (Coulomb). The graph then has
#
# * a vertical segment at $w = 0$ for $|f| \le \mu_s N_f$: the force is not a
#   function of the rate (as for every Bingham dashpot);
# * horizontal segments $f = \pm\mu_s N_f$ for $0 < |w| < v_{\text{lock}}$:
#   the rate is not a function of the force either;
# * vertical rays at $w = \pm v_{\text{lock}}$ for $|f| \ge \mu_s N_f$: the
#   lock.
#
# Neither $f(w)$ nor $w(f)$ exists; the graph is still *monotone* (a larger
# rate never needs a smaller force), and that is all backward Euler needs
# (`Network`'s Notes). `force_interval` gives the set of forces at each rate:

# %%
lock = LockingBingham("lock", ("ground", "m"), threshold=1.0, gamma=math.inf, v_lock=2.0)
for w in (0.0, 1.0, 2.0, 2.5):
    lo, hi = lock.force_interval(0.0, w)
    print(f"w = {w:.1f} m/s  ->  " + ("no force: beyond the lock" if math.isnan(lo) else f"f in [{lo}, {hi}] N"))
fig = P.locking_graph(lock, f_max=3.0)
_ = P.save_figure(fig, "ext03_locking_graph")

# %% [markdown]
# ### A run where the lock is reached
#
# A unit mass on a spring ($k = 100$ N/m) released from $x_0 = 0.5$ m with the
# locking dashpot to the ground. Without the lock it would slide as a Coulomb
# oscillator about $x_c = \mu_s N_f/k = 0.01$ m, $x = x_c + (x_0 - x_c)\cos\omega t$,
# reaching the speed $(x_0 - x_c)\,\omega = 4.9$ m/s. With the lock:
#
# 1. it slides until $|v| = v_{\text{lock}}$, at $t_1 = \arcsin\!\big(v_{\text{lock}}/((x_0 - x_c)\omega)\big)/\omega$;
# 2. it then moves at exactly $-v_{\text{lock}}$: the acceleration is 0, so
#    the dashpot carries the spring's whole force $kx$, which the lock allows
#    while $kx \ge \mu_s N_f$, that is down to $x = x_c$;
# 3. from $x_c$ it slides again as a Coulomb oscillator, now from
#    $v = -v_{\text{lock}}$, with amplitude $v_{\text{lock}}/\omega$ about $x_c$; its later
#    swings are slower than the lock and never reach it again.
#
# Phase 3 is the paper's system (spring and Coulomb dashpot), solved by
# `lumped.solve_exact`; phases 1 and 2 are the closed forms above.

# %%
k, x0, t_end, dt = 100.0, 0.5, 1.5, 1e-4
net = Network([Mass("m", 1.0, x0)], [Spring("k", ("ground", "m"), k), lock])
run = simulate_network(net, t_end, dt)
v = run.velocities[:, 0]
print(f"largest |v| = {float(np.abs(v).max())!r} m/s (v_lock = {lock.v_lock!r}); "
      f"steps at exactly -v_lock: {int(np.sum(v == -lock.v_lock))}")

# %%
omega, xc = math.sqrt(k), lock.threshold / k
t1 = math.asin(lock.v_lock / ((x0 - xc) * omega)) / omega
x1 = xc + (x0 - xc) * math.cos(omega * t1)
t2 = t1 + (x1 - xc) / lock.v_lock  # the lock holds down to x = xc
slide = L.solve_exact(L.Oscillator.bingham(1.0, k, lock.threshold, math.inf), t_end - t2, x0=xc, v0=-lock.v_lock)
locked = run.t[v == -lock.v_lock]
print(f"locked: closed form [{t1:.4f}, {t2:.4f}] s, network [{locked[0]:.4f}, {locked[-1]:.4f}] s")


def reference(t):
    """x of the three phases: slide, lock, slide (exact solver)."""
    phase3 = slide.evaluate(np.clip(t - t2, 0.0, None))["x"]
    return np.where(t < t1, xc + (x0 - xc) * np.cos(omega * t), np.where(t < t2, x1 - lock.v_lock * (t - t1), phase3))


print(f"max |x - reference| over the run: {np.abs(run.positions[:, 0] - reference(run.t)).max():.1e} m")

# %% [markdown]
# The speed never passes $v_{\text{lock}}$; it reaches it *exactly* (the
# lock is a rigid piece of the step graph, so the step that would exceed it
# ends on it), holds it for the printed interval, and the positions follow the
# three-phase reference to within backward Euler's first-order error.
# Figure ext04 shows the velocity with the lock's level.

# %%
t_ref = np.linspace(0.0, t_end, 3001)
fig = P.network_panels(
    {"network, backward Euler": run},
    [("x", "m"), ("v", "m")],
    references={("x", "m"): {"closed form and exact solver": (t_ref, reference(t_ref))}},
    levels={("v", "m"): {r"$-v_{\mathrm{lock}}$": -lock.v_lock}},
)
_ = P.save_figure(fig, "ext04_locking_run")

# %% [markdown]
# ## What to take away
#
# * A spring in series with a Bingham dashpot is a solid below the threshold
#   and relaxes above it, but only down to the threshold: the printed force
#   ends at $\mu_s N_f$, with a permanent set $(f_0 - \mu_s N_f)/k_m$.
# * The locking dashpot's graph is a function neither way. Backward Euler needs
#   only that it is monotone: the step that would exceed the lock ends on it,
#   and the printed largest speed is $v_{\text{lock}}$ exactly.
