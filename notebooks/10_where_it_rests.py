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
# # 10. Study: where the mass comes to rest
#
# **What you will learn.** Where the mass of Figures 10 to 14 comes to rest
# when it is released at rest from any $x_0$ in $[-1, 1]$ m, with the paper's
# values (section 3.2: $m = 1$ kg, $k = 100$ N/m, $\mu_s N_f = 1$ N,
# $\gamma = 1$ m/(N s)); how Algorithm 1 at the paper's $\Delta t$ compares
# with the exact solution; and for which $x_0$ it rests on the wrong side of
# zero or stops a half-cycle early. The data are computed by the pipeline in
# chunks (`rules/studies.smk`, `lumped.studies.rest`) and read here from
# `results/studies/rest.csv`. The study always takes the paper's values from
# `config/config.yaml` as committed (`lumped.studies.config.default()`): a `--config`
# override changes the other notebooks, and here only the resolution
# (`studies`).

# %%
from pathlib import Path

import numpy as np

import lumped.studies.config
import lumped.plotting as P
from lumped import studies
from lumped.studies import rest
from lumped.drivers.simulation import simulate
from lumped.model.oscillator import Oscillator

cfg = lumped.studies.config.default()  # the paper's values as committed, whatever --config overrides
band = cfg["threshold"] / cfg["stiffness"]  # tau/k (m)
osc = Oscillator.bingham(cfg["mass"], cfg["stiffness"], cfg["threshold"], cfg["gamma"])
print(
    f"m = {cfg['mass']:g} kg, k = {cfg['stiffness']:g} N/m, tau = {cfg['threshold']:g} N, "
    f"gamma = {cfg['gamma']:g} m/(N s), dt = {cfg['dt']:g} s; static band |x| <= tau/k = {band:g} m"
)

# %% [markdown]
# ## What theory says, and what it does not
#
# With no force, the mass is at rest at $x$ exactly when the spring force
# $|kx|$ does not exceed the threshold: eq. (6) gives $v = 0$ for
# $|F_d| \le \mu_s N_f$, and with $v = 0$ the momentum balance makes
# $F_d = -kx$. So every rest position lies in the static band
# $|x| \le \tau/k$, and a mass released at rest inside it never moves. From
# outside it, the mass swings, and can only come to rest where $v = 0$, at
# the end of a half-cycle, the first whose turning point falls inside the band.
#
# For Coulomb friction ($\gamma = \infty$) each half-cycle is a harmonic
# oscillation about $\pm\tau/k$, so the amplitude drops by exactly $2\tau/k$
# per half-cycle and the rest position is a sawtooth in $x_0$. The Bingham
# dashpot of eq. (6) resists with $|F_d| = \tau + |v|/\gamma$ while it moves:
# a viscous part on top of the friction, which takes a share of each swing that
# depends on its speed. The decrement is then not constant, and we do not
# claim a formula for it; the exact solver (`method="exact"`, the piecewise
# closed-form solution) is the reference. Its successive turning points from
# $x_0 = 0.5$ m show the decrement:

# %%
run = simulate(osc, 4.0, cfg["dt"], x0=0.5, method="exact")
sign = np.sign(run.v)
moving = sign != 0
flip = np.flatnonzero(np.diff(sign[moving]) != 0)
extrema = np.abs(run.x[moving][flip])
decrement = -np.diff(np.concatenate(([0.5], extrema)))
print("decrement per half-cycle (m):", np.array2string(decrement, precision=4))
print(f"Coulomb's would be 2 tau/k = {2 * band:g} m; rest at x = {run.rest_position:+.6f} m, t = {run.rest_time:.4f} s")

# %% [markdown]
# The turning points are read from the exact solution sampled on the grid
# $t_n = n\Delta t$ (the last sample before $v$ changes sign; near a turning
# point $|x - x_\mathrm{turn}| \le \tfrac12 \max|\ddot x|\,\Delta t^2 \approx
# 5\times10^{-7}$ m). The decrement falls from swing to swing as the speed,
# and with it the viscous part, falls, and stays above Coulomb's $2\tau/k$.
#
# ## The data: `results/studies/rest.csv`
#
# One row per $x_0$ of `np.linspace(-1, 1, N)` (m), $N$ = 400 in the default
# build and 20000 with `snakemake --config studies=full`, each run free
# vibration from rest ($v_0 = 0$, no force) for 6 s (from $x_0 = 1$ m the
# exact solution rests at 4.40 s; a run still moving at 6 s stops the build
# rather than write a NaN). Columns:
#
# | column | meaning |
# |---|---|
# | `x0` | initial displacement (m) |
# | `alg1_rest_time`, `exact_rest_time` | start of the final rest (s): the grid time of Algorithm 1's first step of its last run of $v_n = 0$; the exact event time |
# | `alg1_rest_position`, `exact_rest_position` | displacement at rest (m) |
# | `alg1_stops`, `exact_stops` | steps with $v_n = 0$ after $v_{n-1} \ne 0$ (grid steps entering the stick branch from motion) |
#
# The definitions are `lumped.drivers.sweep`'s. $N$ is even so that the grid misses
# $x_0 = 0$ and the band edges $\pm\tau/k$; the last section shows why.

# %%
path = Path("..", "results", "studies", "rest.csv")
if path.is_file():
    table = studies.read_csv(path, rest.COLUMNS)
else:  # the notebook opened without a pipeline build: the default grid, computed here (about 4 s)
    table = rest.rows(cfg, rest.GRID["default"][0])
x0, exact, alg1 = table["x0"], table["exact_rest_position"], table["alg1_rest_position"]
print(f"{x0.size} values of x0 from {x0[0]:g} to {x0[-1]:g} m")
print(
    f"exact rest positions within [{exact.min():+.6f}, {exact.max():+.6f}] m, "
    f"Algorithm 1's within [{alg1.min():+.6f}, {alg1.max():+.6f}] m; band edge {band:g} m"
)

# %% [markdown]
# ## Figure st01: the rest position against $x_0$
#
# The exact rest position (line) is a sawtooth in the band whose teeth get
# longer in $x_0$ as $|x_0|$ grows: each tooth is the set of $x_0$ that rest
# after the same number of half-cycles, and its jump is where the last
# turning point touches the band edge. It is odd in $x_0$ (the system is
# symmetric). Algorithm 1 (dots) follows it, shifted.

# %%
fig = P.rest_positions(x0, exact, alg1, band, cfg["dt"])
_ = P.save_figure(fig, "st01_rest_position")

# %% [markdown]
# ## Where Algorithm 1 goes wrong
#
# Two failures, read from the columns:
#
# * **wrong side of zero**: the two rest positions have opposite signs;
# * **a half-cycle early**: Algorithm 1 comes to rest at least a quarter of
#   a period $2\pi\sqrt{m/k}$ before the exact solution. A later half-cycle
#   ends half a period later, so a rest-time gap of that size is a missing
#   half-cycle, not a time-stepping error (which is of order $\Delta t$); the
#   check below counts turning points on single runs to confirm it.

# %%
error = alg1 - exact
quarter = 0.25 * 2 * np.pi * np.sqrt(cfg["mass"] / cfg["stiffness"])
gap = table["alg1_rest_time"] - table["exact_rest_time"]
wrong = np.sign(alg1) != np.sign(exact)
early, late = gap < -quarter, gap > quarter
worst = int(np.argmax(np.abs(error)))
print(f"wrong side of zero: {wrong.mean():.2%} of x0 ({wrong.sum()} of {x0.size})")
print(f"half-cycle early:   {early.mean():.2%} of x0 ({early.sum()}); half-cycle late: {late.sum()}")
print(
    f"both at once: {np.sum(wrong & early)}; |exact rest position| where on the wrong side: "
    f"at most {np.abs(exact[wrong]).max():.2e} m"
)
print(
    f"largest |rest-position error| {abs(error[worst]):.3e} m at x0 = {x0[worst]:+.4f} m "
    f"({abs(error[worst]) / band:.0%} of tau/k)"
)
on_time = ~(early | late)
print(f"rest-time gap where the half-cycles agree: {gap[on_time].min():+.2e} to {gap[on_time].max():+.2e} s")
for name, mask in (("wrong side", wrong), ("half-cycle early", early)):
    spans = ", ".join(f"[{a:+.3f}, {b:+.3f}]" for a, b in P.studies.intervals(x0, mask))
    print(f"{name} x0 intervals (m): {spans}")

# %% [markdown]
# The two failures sit at the two kinds of edge of the sawtooth. Where the
# exact last turning point lies just outside the band, the exact solution
# makes one more short swing, about the band edge, that ends on the same
# side; Algorithm 1, whose backward-Euler steps take a little energy out of
# every swing, has its turning point just inside the band and stops there: a
# half-cycle early, on the right side, by up to the length of that last
# swing. Where the rest position is close to zero, Algorithm 1's small shift
# is enough to put it on the other side. The two never happen at the same
# $x_0$, and on this grid Algorithm 1 never makes an extra half-cycle (none
# late, printed above).
#
# ## Figure st02: the failures' intervals

# %%
fig = P.rest_discrepancies(x0, error, wrong, early)
_ = P.save_figure(fig, "st02_wrong_side")

# %% [markdown]
# ## Checking "a half-cycle early" on single runs
#
# The study does not store turning points, so here they are counted on
# single runs (both methods on the grid: a turning point is a change of sign
# of $v$ across any zeros), at the first $x_0$ of each half-cycle-early interval:


# %%
def turning_points(traj) -> int:
    """Changes of sign of the nonzero velocities of a run."""
    s = np.sign(traj.v[traj.v != 0])
    return int(np.count_nonzero(s[1:] != s[:-1]))


for a, _b in P.studies.intervals(x0, early)[:4]:
    be = simulate(osc, rest.T_END, cfg["dt"], x0=a, method="backward-euler")
    ex = simulate(osc, rest.T_END, cfg["dt"], x0=a, method="exact")
    print(
        f"x0 = {a:+.4f} m: half-cycles (turning points + 1) Algorithm 1 {turning_points(be) + 1}, "
        f"exact {turning_points(ex) + 1}; rest at {be.rest_position:+.6f} and {ex.rest_position:+.6f} m"
    )

# %% [markdown]
# The `stops` columns tell one more thing: the exact solution stops once
# (at its final rest), while Algorithm 1 also sticks for single steps at some
# turning points, where the corrector lands on $v_n = 0$ exactly:

# %%
moved = np.abs(x0) > band
for name in ("exact", "alg1"):
    counts = np.bincount(table[f"{name}_stops"][moved])
    print(f"{name:5s} stops -> rows:", {s: int(n) for s, n in enumerate(counts) if n})

# %% [markdown]
# ## Why the grid has an even number of points
#
# An odd grid over $[-1, 1]$ contains $x_0 = -\tau/k$ up to round-off:
# `np.linspace(-1, 1, 401)[198]` is $-0.010000000000000009$ m, outside the
# band by $9\times10^{-18}$ m. The exact solver moves off the edge and
# comes to rest; Algorithm 1 computes a velocity of order $10^{-16}$ m/s,
# too small to change $x$ in floating point, and never reaches $v = 0$:

# %%
edge = np.linspace(-1, 1, 401)[198]
be = simulate(osc, rest.T_END, cfg["dt"], x0=edge, method="backward-euler")
ex = simulate(osc, rest.T_END, cfg["dt"], x0=edge, method="exact")
print(
    f"x0 = {edge!r} m: Algorithm 1 at t = {be.t[-1]:g} s: v = {be.v[-1]:.2e} m/s, x - x0 = {be.x[-1] - edge:.1e} m, "
    f"rest time {be.rest_time}; exact rests at t = {ex.rest_time:.4f} s"
)

# %% [markdown]
# This is round-off at a point of measure zero, not a property of the
# method; the study keeps off it rather than write a row that never rests.
