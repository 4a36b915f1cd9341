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
# # 13. Response curves by shooting and continuation
#
# **What you will learn.** How to compute the steady forced response of the
# friction oscillator of notebook 11 directly, without running each point to
# its steady state: the periodic motion is the fixed point of the exact map over
# one forcing period, found by Newton's method with the derivative of that map
# (the monodromy matrix, whose eigenvalues, the Floquet multipliers, give its
# stability), and followed in the forcing frequency by pseudo-arclength
# continuation. The package does it in `lumped.solvers.monodromy` (the map and
# its derivative, from the exact solver's phases) and `lumped.drivers.response`
# (Newton and the continuation); `python -m lumped response` writes a curve to
# a file. The system is notebook 11's: $m\ddot x + c\dot x + kx = P\sin\omega t
# - F\,\mathrm{sgn}\,\dot x$ with the committed $m$, $k$, $F = \tau$, and $c = 0$
# (Coulomb) or $c = 1/\gamma$ (the paper's Bingham dashpot).

# %%
import math
from pathlib import Path

import numpy as np

import lumped.plotting as P
import lumped.studies.config
from lumped import studies
from lumped.drivers.response import find_orbit
from lumped.drivers.response.curve import response_curve
from lumped.model.oscillator import Oscillator
from lumped.model.problem import oscillator_network
from lumped.solvers.monodromy import period_map
from lumped.studies import den_hartog as dh

cfg = lumped.studies.config.default()
m, k, F = cfg["mass"], cfg["stiffness"], cfg["threshold"]
wn, zeta = math.sqrt(k / m), 1.0 / cfg["gamma"] / (2 * math.sqrt(k * m))
print(f"m = {m:g} kg, k = {k:g} N/m, F = {F:g} N, omega_n = {wn:g} rad/s, zeta = {zeta:g}")

# %% [markdown]
# ## Step 1: the period map and its derivative
#
# Let $z = (x, v)$ at $t = 0$ and $\Pi(z)$ the state at $T = 2\pi/\omega$ of
# the exact motion from it (`solve_exact`: slip phases in closed form, stick
# phases exact). A periodic motion is a fixed point, $\Pi(z) = z$. Newton
# needs $M = \partial\Pi/\partial z$. The motion is a chain of phases whose
# ends are events, and an event's time moves with $z$; so we carry
# $D = \partial(t, x, v)/\partial z$ at the start of each phase, starting from
# $D = [0;\ I]$ at $t = 0$:
#
# * **Slip** from $(t_a, z_a)$: $\dot z = Az + b(t)$ is linear with
#   $A = [[0, 1], [-k/m, -c/m]]$, so at a fixed end time the state varies by
#   $\delta z_b = e^{A(t_b - t_a)}(\delta z_a - f(t_a, z_a)\,\delta t_a)$, $f$
#   the phase's vector field (a later start is the same motion shifted).
#   If the phase ends where $v = 0$ (a stop or a reversal), then
#   $0 = \delta v_b + \dot v(t_b^-)\,\delta t_b$ fixes $\delta t_b = -\delta v_b / \dot v(t_b^-)$;
#   $\delta x_b$ is unchanged (since $v_b = 0$) and $\delta v = 0$ there.
#   The next phase's term $-f^{+}\,\delta t$ uses its *own* field: that is the
#   saltation matrix of the switch, $I + (f^+ - f^-)\,n^T/(n^T f^-)$ with
#   $n = (0, 1)$, written as two steps.
# * **Stick** from a stop at $x_b$: $v = 0$ and $x = x_b$ whatever happened
#   before, so only $\delta x_b$ survives (the stop's time drops out: the
#   derivative *projects*, and $M$ gets a zero multiplier). The breakaway at
#   $t_c$ where $P\sin\omega t_c - kx_b = \pm F$ moves by
#   $\delta t_c = k\,\delta x_b / (P\omega\cos\omega t_c)$; since the net force
#   there just equals the friction, the next slip starts with zero
#   acceleration and $f\,\delta t_c = 0$: the breakaway's shift does not
#   reach the motion to first order.
#
# $M$ is the $(x, v)$ rows of $D$ at $t = T$. Here it is beside central
# differences of the exact map, for a motion without stops and one with two:

# %%
for gamma, fp, r in ((math.inf, 0.4, 0.7), (cfg["gamma"], 0.8, 1.5)):
    osc, p = Oscillator.bingham(m, k, F, gamma), F / fp
    orbit = find_orbit(osc, p, r * wn)
    h = 1e-6 * np.array([p / k, p / k * wn])
    cols = [(period_map(osc, p, r * wn, *(orbit.state + e)).end - period_map(osc, p, r * wn, *(orbit.state - e)).end) / (2 * e.sum()) for e in np.diag(h)]
    gap = np.abs(np.column_stack(cols) - orbit.period.monodromy) * h[None, :] / h[:, None]
    print(f"gamma {gamma:g}, F/P {fp}, r {r}: {orbit.stops} stops, |M - differences| < 1e-6: {gap.max() < 1e-6}")

# %% [markdown]
# The differences' own error is about the map's round-off over the step,
# $10^{-13}/10^{-6}$; `tests/test_response.py` makes the same comparison on
# five cases. The stick's projection shows as a zero multiplier:

# %%
osc = Oscillator.bingham(m, k, F, cfg["gamma"])
orbit = find_orbit(osc, F / 0.4, 0.5 * wn)
mu = np.sort(np.abs(orbit.multipliers))
print(f"F/P 0.4, r 0.5: {orbit.stops} stops per period, |multipliers| {mu[0]:.3f} and {mu[1]:.3f}: stable {orbit.stable}")

# %% [markdown]
# ## Step 2: following the branch in the frequency
#
# The unknowns are $u = (x, v, \omega)$ (scaled by $P/k$, $\omega_n P/k$ and
# $\omega_n$) and the branch is $G(u) = \Pi(x, v; \omega) - (x, v) = 0$, a curve
# in three dimensions. From a point with unit tangent $t$ (the null vector of
# $\partial G/\partial u$) we step $ds$ along $t$ and correct with Newton on
# $G = 0$ together with $t\cdot(u - u_{pred}) = 0$: because $\omega$ is an
# unknown, a fold where the branch turns back in $\omega$ is passed like any
# other point. $\partial G/\partial\omega$ is a central difference of the exact
# map (the monodromy is analytic). Between neighbours the branch is tested for
# a change in the stops per period, and for a multiplier crossing $+1$
# ($\det(M - I)$ changes sign: a fold) or $-1$ ($\det(M + I)$: period
# doubling); each change is located by bisection and kept as a row of its kind.
# With $c = 0$ and $F/P < \pi/4$ the amplitude grows without bound at
# $\omega_n$: the branch is cut at $Xk/P = 50$ and taken up on the other side.

# %%
ratios = (0.2, 0.4, 0.6, 0.8)
branches, changes = {}, []
for z, gamma in ((0.0, math.inf), (zeta, cfg["gamma"])):
    net = oscillator_network(Oscillator.bingham(m, k, F, gamma))
    for fp in ratios:
        curve = response_curve(net, "m", F / fp, 0.2 * wn, 3.0 * wn, points=60).columns
        branches[(z, fp)] = {"r": curve["omega"] / wn, "ratio": curve["amplitude_m"] * k * fp / F, **curve}
        for j in np.flatnonzero(curve["kind"] != "regular"):
            stops = curve["stops_per_period"]
            after = stops[min(j + 1, len(stops) - 1)]  # the regular neighbours, clear of the change itself
            changes.append((z, fp, curve["kind"][j], curve["omega"][j] / wn, stops[j - 1], after))
n = sum(len(b["r"]) for b in branches.values())
unstable = sum(int((~b["stable"]).sum()) for b in branches.values())
print(f"{len(branches)} branches, {n} points, {unstable} unstable")
for z, fp, kind, r, before, after in changes:
    print(f"zeta {z:g}, F/P {fp}: {kind} at r = {r:.3f} ({before:.0f} -> {after:.0f} stops)")

# %% [markdown]
# No multiplier leaves the unit circle on these branches: every periodic motion
# found is stable, and there is no fold or period doubling over $r \in [0.2, 3]$
# at these friction ratios. What changes along them is the number of stops per
# period, at the points listed above.
#
# ## Step 3: the checks
#
# **Den Hartog's closed form.** On the Coulomb branches, where the motion has
# no stops, the amplitude is notebook 11's eq. (4); Newton's tolerance
# ($10^{-11}$ of $P/k$ in the residual) bounds the difference far below the
# $10^{-9}$ printed against:

# %%
worst = 0.0
for fp in ratios:
    b = branches[(0.0, fp)]
    for r, ratio, stops in zip(b["r"], b["ratio"], b["stops_per_period"]):
        form = dh.closed_form(m, 0.0, k, F, F / fp, r * wn)
        if stops == 0 and form.nonstop:
            worst = max(worst, abs(ratio - form.amplitude * k * fp / F) / ratio)
print(f"largest relative difference from eq. (4) on the branches: below 1e-9: {worst < 1e-9}")

# %% [markdown]
# **Where the stops begin.** The Coulomb branch at $F/P = 0.4$ loses its stops
# where notebook 11's eq. (5) says the motion without stops begins:

# %%
for z, fp, kind, r, before, after in changes:
    if z == 0 and after == 0 and r >= dh.BOUNDARY_FROM:
        print(f"F/P {fp}: stops end at r = {r:.4f}; eq. (5) there: F/P < {float(dh.coulomb_boundary(r)):.4f}")

# %% [markdown]
# **The long runs of notebook 11.** Each settled row of `den_hartog.csv` (one
# run from rest for 30 s and more) lies on the branch: the branch's orbit at
# that frequency, found by Newton from the run's neighbourhood, has the run's
# amplitude ($|x|$ largest over the last window, equal to our half range for
# these symmetric motions).

# %%
path = Path("..", "results", "studies", "den_hartog.csv")
table = studies.read_csv(path, dh.COLUMNS) if path.is_file() else dh.rows(cfg, dh.GRID["default"][0])
settled = np.flatnonzero(table["amplitude_change"] < 1e-8)
gap = []
for j in settled:
    gamma = math.inf if table["damping"][j] == 0 else cfg["gamma"]
    p = F / table["friction_ratio"][j]
    orbit = find_orbit(Oscillator.bingham(m, k, F, gamma), p, table["frequency_ratio"][j] * wn)
    gap.append(abs(orbit.amplitude * k / p - table["amplitude_ratio"][j]) / table["amplitude_ratio"][j])
print(f"{len(settled)} settled runs of {table['damping'].size}; largest relative gap to the orbit below 1e-7: {max(gap) < 1e-7}")

# %% [markdown]
# ## Figure rc01: the response curves
#
# Solid lines: the stable branches (an unstable one would be dashed; there is
# none here); squares: where the stops per period change; black dotted: Den
# Hartog's closed form where its motion without stops is admissible; hollow
# circles: notebook 11's long runs from rest.

# %%
grid = np.linspace(0.2, 3.0, 281)
grid = grid[np.abs(grid - 1) > 1e-9]
closed = {(z, fp): dh.curve(cfg, z, fp, grid) for z in (0.0, zeta) for fp in ratios}
fig = P.response_curves(branches, closed, table)
_ = P.save_figure(fig, "rc01_response_curves")

# %% [markdown]
# **What the curve shows that brute force could not.** A long run from rest
# finds one motion per frequency, only if it settles, and only the one its
# initial state leads to; near resonance notebook 11's runs had not settled
# after 30 s. The branch gives every point at the cost of a few period maps
# (some milliseconds each), with its stability from the multipliers instead of
# from waiting; it would show a coexisting or an unstable motion, were there
# one, which no run from rest can reach; and it places the start of motion
# without stops to the bisection's precision instead of the grid's. At these
# friction ratios the answer is that there is none: over $r \in [0.2, 3]$ each
# branch is a single stable motion, so the long runs lost nothing but time.
