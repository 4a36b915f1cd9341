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
# # 6. The implicit spring of Figure 2 as dynamics
#
# **What you will learn.** The paper's Figure 2 draws a spring restrained by an
# inextensible string as a *graph*; here a mass hangs on it and moves. You
# will see why its displacement is a function of its force but not the
# reverse, what happens when the string goes taut (an impact: the velocity
# drops to zero within two steps, and the kinetic energy is lost), and how that
# impact moves the position where the mass finally comes to rest.
# `lumped.simulate_network` integrates it with backward Euler; every claim is checked
# against a closed form or the exact event-driven solver, and printed.
#
# This notebook and the next two extend the replication (notebooks 01 to 05)
# into a tutorial on networks; their figures are `ext01` to `ext06`.

# %%
import math

import lumped as L
import lumped.plotting as P
import numpy as np
from lumped import Bingham, Mass, MaxwellBingham, Network, Spring, SpringString, simulate_network
from scipy.optimize import brentq

m, k, length = 1.0, 100.0, 0.2  # kg, N/m, m: the mass, the spring and the string's length L
tau, gamma = 5.0, 1.0  # N, m/(N s): the Bingham dashpot's threshold mu_s N_f and slope (eq. 6)
x0, dt = -0.5, 1e-4  # m (spring compressed), s
print(f"m = {m} kg, k = {k} N/m, L = {length} m, mu_s N_f = {tau} N, gamma = {gamma}, x0 = {x0} m, dt = {dt:.0e} s")

# %% [markdown]
# ## The graph: $e \le L$
#
# Let $e$ be the elongation of the element (m) and $f$ its tension (N). While
# the string is slack ($e < L$) the spring alone carries the load, $f = ke$.
# At $e = L$ the string is taut and carries any further tension, so *every*
# $f \ge kL$ belongs to the graph: a vertical half-line. Read from the force,
# the elongation is single-valued, $e = \min(f/k, L)$; read from the
# elongation, $e = L$ admits a whole ray of forces, and $e > L$ none at all.
# So $e$ is a function of $f$, but $f$ is not a function of $e$: the same
# reversal as the Bingham dashpot's, with position in place of velocity.
# `SpringString.force_interval` returns the set of forces for an elongation:

# %%
element = SpringString("s", ("ground", "m"), stiffness=k, length=length)
for e in (0.1, length, 0.25):
    lo, hi = element.force_interval(e, 0.0)
    print(f"e = {e:.2f} m  ->  " + ("no force: not on the graph" if math.isnan(lo) else f"f in [{lo}, {hi}] N"))
forces = np.array([-10.0, 10.0, 20.0, 50.0, 500.0])
print("f (N):", forces, " e = min(f/k, L) (m):", np.minimum(forces / k, length))

# %% [markdown]
# ## A mass on the implicit spring, with friction
#
# The mass starts at rest with the spring compressed ($x_0 = -0.5$ m) and
# swings towards $+x$; the string stops it at $x = L$. A Bingham dashpot to
# the ground adds the friction that makes the rest position depend on the
# history (notebook 05). Written as the obvious network, one mass with a
# spring-string and a Bingham element both to the ground, it runs:

# %%
obvious = Network([Mass("m", m, x0)], [element, Bingham("d", ("ground", "m"), tau, gamma)])
run_obvious = simulate_network(obvious, 1.5, dt)
for r in np.flatnonzero((run_obvious.force_min != run_obvious.force_max).any(axis=1)):
    print(f"t = {run_obvious.t[r]:.4f} s: v = {run_obvious.velocities[r, 0]}, held {run_obvious.forces[r].sum():.6g} N")
    for e, name in enumerate(obvious.element_names):
        lo, hi, f = run_obvious.force_min[r, e], run_obvious.force_max[r, e], run_obvious.forces[r, e]
        print(f"  {name}: any force in [{lo:.6g}, {hi:.6g}] N; least-norm split {f:.6g} N")

# %% [markdown]
# The motion is unique, the forces are not, on the step where the string is
# taut and the dashpot sticks at the same time: both fix their rate ($w = 0$)
# and together they must balance the mass's momentum, so any split of that
# held force between a force $f_s \ge kL$ and a force $|f_d| \le \mu_s N_f$ is
# a solution (see `Network`'s Notes). The run says so: each element's
# admissible interval (`force_min`, `force_max`), and as `forces` the split of
# least norm. To know the split, model what decides it: the dashpot is mounted
# on a stiff spring of stiffness $k_m$, a `MaxwellBingham` element (notebook
# 07), whose force is always a function of the motion. The mount deflects by
# its force over $k_m$, which bounds what it changes:

# %%
k_mount = 1e5  # N/m, a thousand times the spring


def impact_network(string: bool) -> Network:
    """The mass on the spring (with the string if asked) and the mounted dashpot."""
    spring = SpringString("s", ("ground", "m"), k, length) if string else Spring("s", ("ground", "m"), k)
    return Network([Mass("m", m, x0)], [spring, MaxwellBingham("d", ("ground", "m"), k_mount, tau, gamma)])


t_end = 1.5
run = simulate_network(impact_network(True), t_end, dt)
free = simulate_network(impact_network(False), t_end, dt)
print(f"largest mount deflection max |f_d| / k_m = {np.abs(run.forces[:, 1]).max() / k_mount:.1e} m")

# %% [markdown]
# ## Before the impact: a damped harmonic swing
#
# Until the string goes taut the mass slides in one direction ($v > 0$), so the
# dashpot's force is $\mu_s N_f + v/\gamma$ and the motion is the damped
# oscillator $m\ddot x + \dot x/\gamma + kx = -\mu_s N_f$ about the centre
# $x_c = -\mu_s N_f/k$. With $\omega_0 = \sqrt{k/m}$, damping ratio
# $\zeta = 1/(2\gamma\sqrt{mk})$ and $\omega_d = \omega_0\sqrt{1-\zeta^2}$,
# from rest at $x_0$:
# $$x(t) = x_c + (x_0 - x_c)\,e^{-\zeta\omega_0 t}\Big(\cos\omega_d t + \frac{\zeta\omega_0}{\omega_d}\sin\omega_d t\Big),
# \qquad v(t) = -(x_0 - x_c)\,\frac{\omega_0^2}{\omega_d}\,e^{-\zeta\omega_0 t}\sin\omega_d t .$$
# The impact time $t^*$ is the first root of $x(t^*) = L$, and $v^* = v(t^*)$
# the speed the string has to stop.

# %%
w0, zeta, xc = math.sqrt(k / m), 1 / (2 * gamma * math.sqrt(m * k)), -tau / k
wd = w0 * math.sqrt(1 - zeta**2)


def swing(t):
    """x and v of the first swing, in closed form (the formulas above)."""
    decay = (x0 - xc) * np.exp(-zeta * w0 * t)
    return xc + decay * (np.cos(wd * t) + zeta * w0 / wd * np.sin(wd * t)), -decay * w0**2 / wd * np.sin(wd * t)


t_hit = brentq(lambda t: swing(t)[0] - length, 0.0, math.pi / wd)
v_hit = float(swing(t_hit)[1])
before = run.t < t_hit - dt
print(f"closed form: impact at t* = {t_hit:.5f} s with v* = {v_hit:.5f} m/s")
print(f"max |x - closed form| before the impact: {np.abs(run.positions[before, 0] - swing(run.t[before])[0]).max():.1e} m")

# %% [markdown]
# ## The impact: the velocity drops to zero within two steps
#
# The string's step graph (see `SpringString`) lets a step end *exactly* at
# $e = L$: the step that would carry the mass past $L$ stops it there, with
# the velocity $(L - e_n)/\Delta t$ that just reaches $L$, and the next step
# finds the string taut and the velocity $0$. Nothing bounces back: backward
# Euler, like Moreau's sweeping process, makes the impact perfectly
# inelastic (restitution 0). `rigid` marks the steps on which the string is
# taut.

# %%
taut = np.flatnonzero(run.rigid[:, 0])
n = taut[0]
print(f"string taut on steps {taut.tolist()} (t = {run.t[n]:.4f} s; closed form t* = {t_hit:.4f} s)")
print(f"elongation there: {run.states[taut, 0].tolist()} (exactly L)")
for i in range(n - 1, n + 3):
    print(f"  t = {run.t[i]:.4f} s: x = {run.positions[i, 0]:+.6f} m, v = {run.velocities[i, 0]:+.5f} m/s, string force {run.forces[i, 0]:9.1f} N")

# %% [markdown]
# In the exact motion the velocity jumps from $v^*$ to 0 at $t^*$: the string
# exerts an impulse $m v^*$ and removes the whole kinetic energy
# $\tfrac12 m v^{*2}$ (the string anchors the mass to the ground, so the
# relative motion is all the motion). Backward Euler spreads the impulse over
# the two taut steps, each carrying a force of order $m v^*/\Delta t$; the
# impulse beyond the spring's own $kL$ is $\sum \Delta t\,(f - kL)$, and the
# kinetic energy drops from its value before the impact to zero:

# %%
impulse = dt * np.sum(run.forces[taut, 0] - k * length)
kinetic = 0.5 * m * run.velocities[:, 0] ** 2
print(f"impulse of the string: {impulse:.4f} N s; m v* = {m * v_hit:.4f} N s "
      f"({100 * (1 - impulse / (m * v_hit)):.2f} % less)")
print(f"kinetic energy: {kinetic[n - 1]:.4f} J before the impact, {kinetic[taut[-1]]:.4f} J after; "
      f"1/2 m v*^2 = {0.5 * m * v_hit**2:.4f} J ({100 * (1 - kinetic[n - 1] / (0.5 * m * v_hit**2)):.2f} % less)")

# %% [markdown]
# Both fall short of the exact values by about a third of a per cent. The gap is backward
# Euler's first-order error: its velocity at the last step before the impact
# is already a little below $v^*$, and the dashpot takes a share of the
# impulse during the two taut steps; `tests/test_network.py` shows the error
# of the whole motion falling as $\Delta t$.
#
# ## After the impact, and where the mass comes to rest
#
# Once the string has stopped the mass at $x = L$ with $v = 0$, the problem
# starts afresh: the mass on the spring and the dashpot, released from rest at
# $L$ (the string goes slack at once, since $kL > \mu_s N_f$ pulls it back).
# The exact event-driven solver of the paper's system (`lumped.solve_exact`)
# gives that motion, shifted by $t^*$; without the string it gives the whole
# motion from $x_0$. Each ends with a *stop*: the mass sticks where the spring
# force $|kx|$ has fallen inside the band $\mu_s N_f$.

# %%
osc = L.Oscillator.bingham(m, k, tau, gamma)
after = L.solve_exact(osc, t_end - t_hit, x0=length)
without = L.solve_exact(osc, t_end, x0=x0)
for name, sol in (("with the string", after), ("without it", without)):
    turns = [f"{e.x[0]:+.4f}" for e in sol.events if e.kind == "reversal"]
    print(f"exact, {name}: turning points {turns} m, rest at x = {sol.rest_position:+.5f} m")

# %% [markdown]
# The impact takes away the energy the first swing still had at $x = L$, so the
# mass with the string starts its decay from $L$ instead of from the first
# turning point ($+0.3345$ m above): it needs fewer swings to enter the band,
# and ends on the *other side* of $x = 0$, with less energy left in the
# spring. In the networks the mount keeps a small ripple after the dashpot
# sticks (it is a spring without damping while the dashpot holds; only
# backward Euler's numerical damping shrinks it), so the rest position is read
# as the mean over the last 0.2 s:

# %%
late = run.t > t_end - 0.2
for name, tr, sol in (("with the string", run, after), ("without it", free, without)):
    x_late = tr.positions[late, 0]
    print(f"{name}: network rest {x_late.mean():+.5f} m (ripple {np.ptp(x_late):.0e} m), "
          f"exact {sol.rest_position:+.5f} m")
print(f"stored energy at rest: with the string {0.5 * k * after.rest_position**2:.4f} J, "
      f"without {0.5 * k * without.rest_position**2:.4f} J")

# %% [markdown]
# Figure ext01 shows both runs with the exact references: the string's length
# as a dotted line, the flat top where the string stops the mass, and the
# two different rest positions.

# %%
exact_after = after.evaluate(np.linspace(0, t_end - t_hit, 2001))
t_before = np.linspace(0, t_hit, 400)
x_ref = np.r_[swing(t_before)[0], exact_after["x"]]
v_ref = np.r_[swing(t_before)[1], exact_after["v"]]
t_ref = np.r_[t_before, t_hit + exact_after["t"]]
fig = P.network_panels(
    {"with the string (network)": run, "without the string (network)": free},
    [("x", "m"), ("v", "m")],
    references={("x", "m"): {"exact, with the string": (t_ref, x_ref)}, ("v", "m"): {"exact, with the string": (t_ref, v_ref)}},
    levels={("x", "m"): {"$L$": length}},
)
_ = P.save_figure(fig, "ext01_spring_string_impact")

# %% [markdown]
# ## What to take away
#
# * The spring with a string is a relation $e = \min(f/k, L)$: elongation from
#   force, not force from elongation. In a dynamic run the vertical part of the
#   graph acts as a perfectly inelastic stop.
# * Backward Euler resolves the stop without any event detection: one step
#   ends exactly at $L$, the next has velocity 0, and the kinetic energy is
#   gone (printed above, against $\tfrac12 m v^{*2}$).
# * With friction, the impact changes the history and so the rest position:
#   here it moves it from one side of $x = 0$ to the other.
# * A taut string and a sticking dashpot in parallel leave their forces
#   undetermined (the motion is unique); the run reports each one's admissible
#   interval, and a stiff mount is what determines the split.
