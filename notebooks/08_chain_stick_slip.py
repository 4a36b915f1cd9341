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
# # 8. A chain of masses: stick-slip travelling along it
#
# **What you will learn.** What a row of masses does when each one sits on a
# rough floor and one end is suddenly pushed: the masses do not start
# together, as they would in a chain of springs alone, but one after the other,
# as the spring force reaching each one passes its friction threshold. A slip
# front travels down the chain, masses stop and start again, and the front
# dies out after a number of masses set by the load. You will measure the
# front's speed and compare it with the speed of waves in the same chain
# without friction, $\sqrt{k/m}$ masses per second.

# %%
import math

import lumped as L
import lumped.plotting as P
import numpy as np
from lumped import Bingham, Load, Mass, Network, Spring, simulate_network

n_mass, m, k, tau = 12, 1.0, 100.0, 1.0  # masses; kg, N/m, N (each mass's friction threshold mu_s N_f)
dt, t_end = 1e-3, 2.5  # s
print(f"{n_mass} masses of {m} kg, springs k = {k} N/m, friction threshold {tau} N each, dt = {dt} s")

# %% [markdown]
# ## The network
#
# Mass $i$ ($i = 0, \dots, 11$) is joined to mass $i+1$ by a spring of
# stiffness $k$ and to the ground by a Coulomb element (a Bingham dashpot with
# $\gamma = \infty$, threshold $\mu_s N_f$): the Burridge-Knopoff model of a
# sliding block chain. The last mass is tied to a wall by one more spring.
# Everything starts at rest and unstretched; at $t = 0$ a constant force $F$
# is applied to mass 0 (`L.Constant(F)`, on from $t = 0$).
# The friction elements all join a mass to the ground, so no loop of elements
# that can stick is closed and every step is well posed (`Network`'s Notes).


# %%
def chain(push: float, threshold: float = tau) -> Network:
    """Masses m00..m11, springs between neighbours and to the wall, friction to the ground."""
    names = [f"m{i:02d}" for i in range(n_mass)]
    springs = [Spring(f"k{i:02d}", (a, b), k) for i, (a, b) in enumerate(zip(names, names[1:]), 1)]
    springs.append(Spring("wall", (names[-1], "ground"), k))
    friction = [Bingham(f"f{i:02d}", ("ground", n), threshold, math.inf) for i, n in enumerate(names)] if threshold else []
    load = Load(names[0], L.Constant(push))
    return Network([Mass(n, m) for n in names], springs + friction, [load])


run = simulate_network(chain(6.0), t_end, dt)
print(f"F = 6 N: {len(run.network.elements)} elements, {run.t.size - 1} steps")

# %% [markdown]
# ## The slip front
#
# Mass $i$ is *still* while $v_i = 0$ exactly: its friction element is on its
# rigid piece, holding any force up to $\mu_s N_f$. In a chain of springs
# alone every mass would move (a little) as soon as the force is applied; here
# a mass waits until the springs on either side pull it with more than
# $\mu_s N_f$. The time each mass first moves:

# %%
def first_moves(tr) -> np.ndarray:
    """Time (s) of each mass's first nonzero velocity; nan if it never moves."""
    moving = tr.velocities != 0
    return np.where(moving.any(axis=0), tr.t[np.argmax(moving, axis=0)], np.nan)


def slips(tr) -> np.ndarray:
    """Number of separate slip episodes (runs of v != 0) of each mass."""
    moving = (tr.velocities != 0).astype(int)
    return np.sum(np.diff(moving, axis=0, prepend=0) == 1, axis=0)


print("first moves at t (s):", " ".join(f"{t:.3f}" for t in first_moves(run)))
print("slip episodes:       ", slips(run))

# %% [markdown]
# The front reaches one mass after another, about every 0.13 s in the middle
# of the chain and more slowly towards its end, where the push arrives weaker; several
# masses stop and start again (more than one slip episode): the stick-slip
# travels with the front. The last mass never moves. Figure ext05 is the
# space-time picture: mass index upwards, time to the right, moving masses
# dark.

# %%
fig = P.stick_map(run)
_ = P.save_figure(fig, "ext05_chain_stick_map")

# %% [markdown]
# ## Against a chain without friction
#
# Without the friction elements the chain is linear:
# $m\ddot x_i = k(x_{i+1} - 2x_i + x_{i-1})$. A wave $e^{\mathrm{i}(qi - \omega t)}$
# solves it when $\omega = 2\sqrt{k/m}\,|\sin(q/2)|$; its energy travels at
# the group velocity $d\omega/dq = \sqrt{k/m}\cos(q/2)$ masses per second,
# at most $c = \sqrt{k/m}$, reached by the longest waves. So the response to the
# push builds up at mass $i$ around $t \approx i/c$ (it is not exactly zero
# before: the discrete chain answers at once, but exponentially weakly). The
# same network with the thresholds set to zero shows the difference in kind:
# at $t = 0.1$ s every mass of the frictionless chain has moved, while in the
# chain with friction only the masses the front has reached have:

# %%
c = math.sqrt(k / m)
linear = simulate_network(chain(6.0, threshold=0.0), 0.1, dt)
print(f"c = sqrt(k/m) = {c:.1f} masses/s")
print(f"at t = 0.1 s: masses moved without friction {int(np.sum(linear.positions[-1] != 0))}, "
      f"with friction {int(np.sum(run.positions[run.t <= 0.1 + dt / 2][-1] != 0))}")

# %% [markdown]
# The front's speed is the slope of mass index against first-move time,
# fitted over the masses it reaches after the first two (the first mass moves
# at once, the second as soon as one spring is stretched). How fast the front
# goes and how far it gets depend on the push $F$: a push just above
# $\mu_s N_f$ can overcome the friction of about $F/\mu_s N_f$ masses at rest,
# and a sudden one overshoots that, as a load suddenly put on a spring
# stretches it twice as far as the same load put on slowly.

# %%
print(f"{'F (N)':>6} {'moved':>6} {'2F/mu_s N_f':>12} {'front speed':>12} {'/ c':>6}")
for push in (3.0, 6.0, 20.0, 60.0):  # the other pushes run to 1.5 s, past every first move
    tr = run if push == 6.0 else simulate_network(chain(push), 1.5, dt)
    first = first_moves(tr)
    reached = np.flatnonzero(np.isfinite(first))
    speed = np.polyfit(first[reached[2:]], reached[2:], 1)[0]
    print(f"{push:6.0f} {reached.size:6d} {2 * push / tau:12.0f} {speed:12.2f} {speed / c:6.2f}")

# %% [markdown]
# The numbers say three things. The number of masses that ever move grows with
# the push and, for the two smaller pushes, stays just below $2F/\mu_s N_f$
# (the two larger ones move the whole chain).
# The front is slower than $c$ for small pushes, where a mass must wait for a
# spring force well above the weak start of the wave; with a larger push the
# threshold is reached earlier in the wave's rise and the front's speed
# approaches $c$, and for the largest push slightly passes it, since a strong
# push makes even the weak early part of the response exceed $\mu_s N_f$.
# (No closed form exists for these times; `tests/test_network_tutorial.py`
# checks that they converge as $\Delta t$ is halved.)
#
# ## Where the chain comes to rest
#
# Once every mass has stopped, each still mass is in equilibrium with its
# friction force inside the band: $|f_i| \le \mu_s N_f$, where $f_i$ balances
# the two springs' pull (and the push, on mass 0). Positions at the end, and
# the largest friction force over the band:

# %%
friction = [i for i, name in enumerate(run.network.element_names) if name.startswith("f")]
print(f"at t = {t_end} s: still masses {int(np.sum(run.velocities[-1] == 0))} of {n_mass}, "
      f"the last to stop from t = {np.nanmax(run.rest_times):.3f} s")
print("positions (mm):", np.array2string(1e3 * run.positions[-1], precision=1))
print(f"max |f_i| / mu_s N_f at the end: {np.abs(run.forces[-1, friction]).max() / tau:.3f}")

# %% [markdown]
# Figure ext06 shows every mass's position, shifted up by its index so that
# the curves do not overlap: the front's arrival is where a flat line starts
# to rise, and every line is flat for good after the time printed above. (The
# short sticks in the middle of the chain, clear in ext05, are barely visible
# at this scale.)

# %%
fig = P.chain_positions(run)
_ = P.save_figure(fig, "ext06_chain_positions")

# %% [markdown]
# ## Several masses, accurately: the orders per event type
#
# Backward Euler is of order one, on a chain as on one mass. A network of
# linear springs, Bingham and Coulomb elements and linear dashpots (this
# chain is one) also runs with `method="event-locating"`, time stepping with
# event location (`event-capturing` is its former name, still accepted): within a mode
# (which elements stick, which way the others slip) the motion obeys a linear
# ODE, stepped by the trapezoidal rule; when an element stops, breaks away or
# a load switches, the crossing is located inside the step on the partial
# trapezoidal step, and the new mode is chosen there. `method="exact"` solves
# the same modes by the matrix exponential, and serves as the reference.
#
# `lumped.studies.accuracy.networks` runs both fixed-step methods on three
# small networks (a Coulomb chain and a Bingham chain under a sine switched
# off at 1 s, a tree of three masses released from rest) at three steps and
# fits, per kind of event, the slope of the error's logarithm against
# $\log \Delta t$ (the time error of the events, paired element by element;
# at the switch-off, whose time is given, the displacement error). The table
# gives the smallest and largest slope over the three networks.

# %%
import lumped.studies.accuracy.networks as AN

steps = (2e-3, 1e-3, 5e-4)
orders = AN.network_orders(AN.network_study(steps), steps)
print(f"steps {steps} s; fitted orders, smallest to largest over {len(AN.NETWORK_CASES)} networks")
print(f"{'':18s}" + "".join(f"{kind:>16s}" for kind in (*AN.NETWORK_KINDS, "max |x - x_ref|")))

def two(x: float) -> str:
    return f"{round(x, 2) + 0.0:.2f}"  # + 0.0: a slope of -1e-15 (round-off about 0) prints 0.00, not -0.00


for method, row in orders.items():
    cells = [row[q] for q in (*AN.NETWORK_KINDS, "max_x")]
    print(f"{method:18s}" + "".join(f"{f'{two(c[0])} to {two(c[1])}' if c else '-':>16s}" for c in cells))

# %% [markdown]
# The event-locating method keeps order two through every kind of event, as
# it does for one mass (notebook 9). Backward Euler's largest displacement
# error falls as $\Delta t$ (slopes just below one). Its events are read off
# the grid, so each is dated to within a step, and where a network has a
# single event of a kind, the error jumps with where that event falls
# between two grid points: those slopes scatter widely about one. Where the
# motion took another course at a coarse step (an element sticking once
# more or less than in the reference), the events are not paired and that
# network's slope is left out.

# %% [markdown]
# ## What to take away
#
# * Thresholds turn a chain's instantaneous (if weak) response into a front:
#   ahead of it the masses are exactly still, behind it they slip, stop and
#   slip again.
# * The front moves at a speed set by the push, below the wave speed
#   $\sqrt{k/m}$ masses per second for moderate pushes and near it for large
#   ones, and dies out after roughly $2F/\mu_s N_f$ masses.
# * Backward Euler needs no event detection for any of this: each step finds
#   which elements stick by its active-set iteration, and a still mass has
#   velocity exactly zero.
