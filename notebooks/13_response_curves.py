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
# (Coulomb) or $c = 1/\gamma$ (the paper's Bingham dashpot). Steps 4 to 6 do
# the same for a network of several masses (the monodromy of the exact network
# map, a two-mass curve with two resonances) and show why friction of this
# kind leaves no fold and no unstable motion to find.

# %%
import math
from pathlib import Path

import numpy as np

import lumped.plotting as P
import lumped.studies.config
from lumped import studies
from lumped.drivers.response import find_orbit
from lumped.drivers.response.curve import response_curve
from lumped.model.files import parse_system
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
# other point. $\partial G/\partial\omega$ is exact too: it is carried through
# the phases beside the monodromy, a slip phase moving with $\omega$ through its
# particular solution, a breakaway through $P\sin\omega t_c$, and the period's
# end through $dT/d\omega = -T/\omega$ (`lumped.solvers.monodromy.derivatives`;
# a network's phases are differentiated the same way). With both exact, each Newton iterate
# costs one period map, and the predictor (a cubic through the last two points
# and their tangents) is close enough that most points take two maps. Between
# neighbours the branch is tested for
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
unstable = sum(int((~b["stable"]).sum()) for b in branches.values())
print(f"{len(branches)} branches, {unstable} unstable points")
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
# (two or three per point, each a fraction of a millisecond; `benchmarks/bench_response.py`
# times the curve against the long runs), with its stability from the multipliers instead of
# from waiting; it would show a coexisting or an unstable motion, were there
# one, which no run from rest can reach; and it places the start of motion
# without stops to the bisection's precision instead of the grid's. At these
# friction ratios the answer is that there is none: over $r \in [0.2, 3]$ each
# point of a branch is stable and, being isolated ($M - I$ invertible there),
# the only $T$-periodic motion at its frequency (step 7 says why), so the long
# runs lost nothing but time. Motions of period $nT$ are another matter, which
# neither the branch nor the runs from rest rule out (step 7).

# %% [markdown]
# ## Step 4: following the branch in another parameter
#
# The same corrector follows the periodic motion in any parameter $\lambda$
# at a fixed frequency: $G(u) = \Pi(x, v; \lambda) - (x, v)$ with
# $u = (x, v, \lambda)$, $\partial G/\partial\lambda$ a central difference of
# the exact map. `response_curve(..., vary=NAME, omega=W)` (and
# `python -m lumped response ... --omega W --vary NAME=START:STOP`) takes the
# force's `amplitude` or any numeric parameter of the system file. Here the
# Coulomb oscillator at $r = 0.8$ under $P = 2.5$ N is followed in its
# friction force $F$ from 0.2 N to 2.4 N: where the motion has no stops, eq. (4)
# at each $F$ is the reference again, and the stops must begin where eq. (5)
# puts the end of motion without stops, at $F/P \approx 0.817$ for $r = 0.8$.

# %%
coulomb = parse_system(Path("..", "examples", "figure3.toml").read_text().replace("gamma = 1.0 ", "gamma = inf "))
curve_f = response_curve(coulomb, "m", 2.5, 0.2, 2.4, points=40, vary="dashpot.threshold", omega=0.8 * wn).columns
f_vals, stops_f = curve_f["dashpot.threshold"], curve_f["stops_per_period"]
worst_f = 0.0
for f_j, x_j, s_j in zip(f_vals, curve_f["amplitude_m"], stops_f):
    form = dh.closed_form(m, 0.0, k, f_j, 2.5, 0.8 * wn)
    if s_j == 0 and form.nonstop:
        worst_f = max(worst_f, abs(x_j - form.amplitude) / form.amplitude)
(first_stop,) = f_vals[curve_f["kind"] == "stops-change"]
print(f"from F = {f_vals[0]:g} to {f_vals[-1]:g} N the stops begin at F = {first_stop:.3f} N")
print(f"F/P there {first_stop / 2.5:.4f}; eq. (5) at r = 0.8: F/P < {float(dh.coulomb_boundary(0.8)):.4f}")
print(f"largest relative difference from eq. (4) where there are no stops: below 1e-9: {worst_f < 1e-9}")

# %% [markdown]
# ## Step 5: the monodromy of a network
#
# A network of linear springs, Bingham and Coulomb elements and linear dashpots
# moves, between events, by a linear ODE fixed by its *mode*: which friction
# elements stick, which slip and which way (notebook 8). Written in the full
# state $y = (x, v)$ of its $n$ masses it is $\dot y = By + b(t)$ with
# $B = \begin{pmatrix}0 & I\\ -GK & -GC\end{pmatrix}$, where $K = A\,\mathrm{diag}(k)A^T$
# and $C = A\,\mathrm{diag}(c)A^T$ gather the elements that do not stick ($A$
# the incidence matrix) and $G = S(S^T m S)^{-1}S^T$, $S$ the membership of
# the masses in the groups that sticking elements join (a group held to the
# ground has no column: its masses stay put). A phase starts from $Qy$ with
# $Q = \mathrm{diag}(I, Gm)$: a group moves with its momentum's velocity. The
# rules of step 1 carry over:
#
# * **within a phase** from $(t_a, y_a)$ to a fixed $t_b$:
#   $\delta y_b = e^{B(t_b - t_a)}Q\,(\delta y_a - f^+\delta t_a)$, $f^+$ the
#   phase's own field at its start;
# * **at an event**, where $g = r\cdot y$ reaches zero (a slipping element's
#   rate, or a sticking one's $\tau \mp f$, its reaction being linear in $y$
#   with the load's time dependence): $\delta t_b = -r\cdot\delta y_b/\dot g$,
#   and the state there varies by $\delta y_b + f^-\delta t_b$. With the next
#   phase's $-f^+\delta t_b$ this is the saltation matrix
#   $I + (f^+ - f^-)\,r^T/(r^T f^-)$ of a stop ($\dot g = r^T f^-$); at a
#   breakaway the two fields agree (the force equals the threshold on both
#   sides), and at a slip-to-stick the next phase's $Q$ projects onto the
#   stuck subspace.
#
# An element that sticks through the whole period may hold any elongation in
# its band, each one periodic: the monodromy keeps it exactly ($rM = r$, a
# multiplier 1). Such neutral directions are held where they are along the
# branch and left out of the stability. Below, $M$ beside central differences
# of the exact network map, on the two-mass example of the next step at three
# frequencies: both contacts stopping twice a period, one stopping briefly,
# and none.

# %%
from lumped.drivers.response import continue_orbits
from lumped.drivers.response.systems import Scales, response_system
from lumped.drivers.response.systems import period_map as any_period_map
from lumped.model.files import load_system, parse_system

text = Path("..", "examples", "two_mass_response.toml").read_text()
system, p2 = response_system(parse_system(text), "m1"), 5.0
s2 = Scales.of(system, p2)
h2 = 1e-6 * np.repeat([s2.x, s2.v], 2)
for w in (3.0, 5.5, 8.0):
    orbit = find_orbit(system, p2, w)
    ends = [[any_period_map(system, p2, w, orbit.state + sign * e).end for sign in (1, -1)] for e in np.diag(h2)]
    fd = np.column_stack([(a - b) / (2 * e) for (a, b), e in zip(ends, h2)])
    gap = np.abs(fd - orbit.period.monodromy) * h2[None, :] / h2[:, None]
    print(f"omega {w:g} rad/s: {orbit.stops} stops, |M - differences| < 1e-6: {gap.max() < 1e-6}")

# %% [markdown]
# ## Step 6: a two-mass response curve
#
# `examples/two_mass_response.toml` is a chain: a spring of $k = 100$ N/m
# from the wall to block m1, one from m1 to m2 ($m = 1$ kg each), and a
# Bingham contact ($\tau = 1$ N, $\gamma = 1$ m/(N s)) from each block to the
# floor; $P = 5$ N acts on m1. Without friction its natural frequencies are
# $\omega^2 = (k/m)(3 \mp \sqrt 5)/2$. The command in the file's header writes
# its curve; here is the same branch from Python (`continue_orbits` keeps the
# orbits):

# %%
branch = continue_orbits(system, p2, 2.0, 25.0, points=30)
orbits2 = [pt.orbit for pt in branch.points]
omega2 = np.array([o.omega for o in orbits2])
amp2 = np.array([o.amplitudes for o in orbits2])
kind2, stable2 = np.array([pt.kind for pt in branch.points]), np.array([o.stable for o in orbits2])
natural = np.sort(np.sqrt(np.linalg.eigvals(system.stiffness / system.parts.m[:, None]).real))
print(f"all points stable: {stable2.all()}; natural frequencies {natural[0]:.2f} and {natural[1]:.2f} rad/s")
for lo, hi in ((2.0, 10.0), (10.0, 25.0)):
    j = np.flatnonzero((omega2 > lo) & (omega2 < hi))[np.argmax(amp2[(omega2 > lo) & (omega2 < hi), 0])]
    print(f"peak near {omega2[j]:.1f} rad/s: m1 {1e3 * amp2[j, 0]:.0f} mm, m2 {1e3 * amp2[j, 1]:.0f} mm")
stops2 = np.array([o.stops for o in orbits2])
for j in np.flatnonzero(kind2 == "stops-change"):
    print(f"stops change at {omega2[j]:.1f} rad/s: {stops2[j - 1]} -> {stops2[min(j + 1, stops2.size - 1)]}")

# %% [markdown]
# At the first peak the blocks swing together, m2 further than m1 (the first
# mode's shape is $(1, 1.62)$); at the second against each other (the second
# mode's is $(1, -0.62)$), with the amplitude ratios near those of the modes.
# Below 3.9 rad/s each contact sticks twice a period; near the first peak,
# m1's contact stops briefly at each turn; above 21.8 rad/s m2's does.
#
# **The check.** With the contacts' thresholds set to zero the chain is linear,
# its contacts dashpots of damping $c = 1/\gamma$, and the steady motion is
# $\mathrm{Im}(X e^{i\omega t})$ with $(K - \omega^2 M + i\omega C)X = F$:

# %%
chain = parse_system(text.replace("threshold = 1.0", "threshold = 0.0"))
linear = response_curve(chain, "m1", p2, 2.0, 25.0, points=20).columns
parts = response_system(chain, "m1").parts
damping, force = parts.b @ np.diag(parts.c) @ parts.b.T, np.array([p2, 0.0])
closed2 = np.array([np.abs(np.linalg.solve(system.stiffness - w * w * np.diag(system.parts.m) + 1j * w * damping, force)) for w in linear["omega"]])
rel = max(np.max(np.abs(linear[f"amplitude_{n}"] - closed2[:, i]) / closed2[:, i]) for i, n in enumerate(("m1", "m2")))
print(f"without friction: largest relative gap to the closed form below 1e-10: {rel < 1e-10}")
for lo, hi in ((2.0, 10.0), (10.0, 25.0)):
    j = np.flatnonzero((linear["omega"] > lo) & (linear["omega"] < hi))[np.argmax(linear["amplitude_m1"][(linear["omega"] > lo) & (linear["omega"] < hi)])]
    print(f"without friction, peak near {linear['omega'][j]:.1f} rad/s: m1 {1e3 * linear['amplitude_m1'][j]:.0f} mm")

# %% [markdown]
# ## Figure rc02: the two-mass response curve
#
# Each block's amplitude along the branch (solid: stable), squares where the
# stops per period change, the chain without friction dotted, its natural
# frequencies as vertical lines. Friction lowers both peaks and moves the
# first one down in frequency.

# %%
fig = P.network_response(omega2, {"m1": amp2[:, 0], "m2": amp2[:, 1]}, stable2, kind2, (linear["omega"], {"m1": linear["amplitude_m1"], "m2": linear["amplitude_m2"]}), natural)
_ = P.save_figure(fig, "rc02_two_mass_response")

# %% [markdown]
# ## Step 7: why no branch here folds
#
# None of the curves above has a fold or an unstable motion, and that is no
# accident of the parameters. We looked for one where it would be most likely:
# a block on a spring with a light second block held by a Coulomb contact (a
# spring that slips, so the system softens with the amplitude), and two
# oscillators joined by a Coulomb pad (which stiffens it), over forces near the
# threshold and light damping. The flanks grew steep, but every multiplier stayed
# inside the unit circle. The reason holds for every system of this class.
# Take two motions under the same load and their difference $(\delta x, \delta v)$,
# with the energy $E = \tfrac12\delta v^T m\,\delta v + \tfrac12\delta x^T K\delta x$.
# It changes at the rate $-\delta v^T C\,\delta v - \sum_e \delta w_e\,\delta f_e$, where $w_e$
# is element $e$'s rate and $f_e$ its force. Each friction element's law is a
# monotone *graph* between rate and force (set-valued at zero rate, where the
# contact sticks: the force is no function of the rate, the original's point), and
# monotone is all the argument needs: $\delta w_e\,\delta f_e \ge 0$ for any two
# points of the graph, so every term is at most zero and $E$ never grows.
# Written with $L$, $E = \tfrac12|L\,\delta y|^2$, the period map is
# non-expansive in this energy norm, $|LML^{-1}|_2 \le 1$ (the convergence
# argument of Leine and van de Wouw, *Stability and Convergence of Mechanical
# Systems with Unilateral Constraints*, Springer 2008, for monotone set-valued
# friction). What that proves, and no more:
#
# * no Floquet multiplier of a $T$-periodic motion lies outside the unit
#   circle, so no branch of them loses stability through a fold or a
#   period-doubling bifurcation;
# * the $T$-periodic motions at one frequency form a convex set (for a
#   non-expansive map in a Euclidean norm the midpoint of two fixed points is
#   one): two of them coexist only with the whole segment between them, as the
#   neutral families of a contact that sticks through the period do.
#
# It does not exclude motions of period $nT$ (a non-expansive map may have
# points of period $n$; a rotation is one), nor decide whether the convex set
# is a single motion. For the forced oscillator with dry friction, Csernák and
# Stépán (2006, *J. Sound Vib.* 295, 649-658) and Csernák, Stépán and Shaw
# (2007, *Nonlinear Dyn.* 50, 93-109) report such motions: subharmonic and
# marginally stable families (notebook 12 meets the latter at $r = 1/2n$); we
# know their results from their abstracts. Along the two-mass branch:

# %%
energy = np.block([[np.linalg.cholesky(system.stiffness).T, np.zeros((2, 2))], [np.zeros((2, 2)), np.diag(np.sqrt(system.parts.m))]])
norms = [np.linalg.norm(energy @ o.period.monodromy @ np.linalg.inv(energy), 2) for o in orbits2]
print(f"largest |L M L^-1| on the branch: {max(norms):.3f}; largest multiplier {max(o.max_multiplier for o in orbits2):.3f}")

# %% [markdown]
# (Any $L$ with $L^TL$ the energy's matrix gives the same norm; here the
# Cholesky factor of $K$.) `tests/test_response_network.py` checks the bound on
# orbits of one mass, of this chain, of the block with a light block on a
# Coulomb contact and of the two oscillators joined by a pad. An unstable
# $T$-periodic motion needs what this class lacks: an elastic element that is
# not linear (a gap, a hardening spring) or a friction force that falls as the
# rate grows. Within the class, the $T$-periodic motions at each frequency
# form one convex set, none of them unstable; the curves above follow it, and
# the long runs of notebook 11 land on it.
