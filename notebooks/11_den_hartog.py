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
# # 11. Study: Den Hartog's forced oscillator with friction
#
# **What you will learn.** How large the steady vibration of a mass on a
# spring becomes under a harmonic force $P \sin \omega t$ when it slides
# against dry friction $F$ (Coulomb), alone or together with the viscous part
# of the paper's Bingham dashpot; the closed form of Den Hartog (1931) for
# motion without stops, derived here as a boundary-value problem over half a
# period; where that motion exists (the mass must leave each turning point at
# once); and how long runs of the exact solver from rest reach it. The data
# are computed by the pipeline in chunks (`rules/studies.smk`,
# `lumped.studies.den_hartog`) and read here from
# `results/studies/den_hartog.csv`. Like notebook 10, the study always takes
# $m$, $k$, $F = \tau$ and $\gamma$ from `config/config.yaml` as committed
# (`lumped.studies.config.default()`): a `--config` override changes only the
# resolution (`studies`).
#
# Source: J. P. Den Hartog, "Forced vibrations with combined Coulomb and
# viscous friction", *Trans. ASME* 53 (APM-53-9), 107-115 (1931); the Coulomb
# formula is also in his textbook *Mechanical Vibrations*.

# %%
import math
from pathlib import Path

import numpy as np

import lumped.studies.config
import lumped.plotting as P
from lumped import studies
from lumped.solvers.exact import solve_exact
from lumped.model.forcing import SwitchedSine
from lumped.studies import den_hartog as dh
from lumped.model.oscillator import Oscillator

cfg = lumped.studies.config.default()  # the committed values, whatever --config overrides
m, k, F = cfg["mass"], cfg["stiffness"], cfg["threshold"]
wn, c = math.sqrt(k / m), 1.0 / cfg["gamma"]
zeta = c / (2 * math.sqrt(k * m))
print(f"m = {m:g} kg, k = {k:g} N/m, F = tau = {F:g} N; omega_n = {wn:g} rad/s")
print(f"the paper's gamma = {cfg['gamma']:g} m/(N s): c = 1/gamma = {c:g} N s/m, damping ratio zeta = {zeta:g}")

# %% [markdown]
# ## The problem
#
# While the mass slides, the Bingham dashpot of eq. (6) resists with
# $F_d = \tau\,\mathrm{sgn}\,v + v/\gamma$, so the equation of motion is
#
# $$ m\ddot x + c\dot x + kx = P\sin(\omega t + \psi) - F\,\mathrm{sgn}\,\dot x, \qquad c = 1/\gamma,\ F = \tau. \tag{1}$$
#
# With $\gamma = \infty$ it is Den Hartog's Coulomb oscillator; with the
# paper's $\gamma = 1$ m/(N s) it is his combined damping, with damping
# ratio $\zeta = c/(2\sqrt{km}) = 0.05$ (printed above). We take that value
# because it is the paper's dashpot, and it is light enough for the friction
# to matter near resonance. We write $r = \omega/\omega_n$ and look for the
# steady motion in which the mass never stops: it slides one way for half a
# period and back the next, $x(t + T/2) = -x(t)$.
#
# ## The closed form: a boundary-value problem over half a period
#
# Put $t = 0$ at a turning point, $x(0) = -X$, $\dot x(0) = 0$, so that
# $\dot x > 0$ until $T/2 = \pi/\omega$. There eq. (1) is linear with the
# constant $-F$: $x = a\sin(\omega t + \theta) - F/k + e(t)$, where
# $a = P/\sqrt{(k - m\omega^2)^2 + (c\omega)^2}$ and the phase lag
# $\phi$ make the usual harmonic response, $\theta = \psi - \phi$, and
# $e$ is a free motion, $(e, \dot e)(t) = \Phi(t)\,e_0$ with $\Phi$ the
# (closed-form) flow of $m\ddot e + c\dot e + ke = 0$. The harmonic part
# changes sign over half a period; the symmetry asks the rest to do the same,
# which gives
#
# $$ (\Phi(T/2) + I)\, e_0 = (2F/k,\ 0), \tag{2}$$
#
# a 2x2 linear system independent of $\psi$. Then $\dot x(0) = 0$ fixes
# $\cos\theta = -e_{0,v}/(a\omega)$ and $x(0) = -X$ gives
#
# $$ X = F/k - e_{0,x} + \sqrt{a^2 - (e_{0,v}/\omega)^2}. \tag{3}$$
#
# For $c = 0$, $\Phi$ is a rotation by $\pi/r$, eq. (2) gives
# $e_0 = (F/k,\ (F/k)\,\omega_n U)$ with $U = \sin(\pi/r)/(1 + \cos(\pi/r))$,
# and eq. (3) becomes Den Hartog's result
#
# $$ \frac{Xk}{P} = \sqrt{\frac{1}{(1 - r^2)^2} - \left(\frac{F}{P}\right)^2 \frac{U^2}{r^2}}. \tag{4}$$
#
# `dh.closed_form` implements eqs. (2) and (3) for any $\zeta < 1$; here it is
# beside eq. (4) typed in directly (the tests compare them over a grid, and
# the combined case with a numerical shooting over half a period):

# %%
for r, fp in ((0.8, 0.2), (1.3, 0.5), (2.0, 0.6)):
    u = math.sin(math.pi / r) / (1 + math.cos(math.pi / r))
    eq4 = math.sqrt(1 / (1 - r * r) ** 2 - (fp * u / r) ** 2)
    ours = dh.closed_form(m, 0.0, k, F, F / fp, r * wn).amplitude * k * fp / F
    assert abs(eq4 - ours) < 1e-13  # two roundings apart; printed to 10 decimals, clear of the last bits
    print(f"r = {r}, F/P = {fp}: eq. (4) {eq4:.10f}, eqs. (2)-(3) {ours:.10f}")

# %% [markdown]
# ## Where the motion without stops exists
#
# Eq. (3) is a motion of eq. (1) only if (i) the root is real and $X > 0$,
# (ii) the mass leaves the turning point at once: there $\dot x = 0$, and it
# slides only if the net force exceeds the friction, $P\sin\psi + kX > F$,
# and (iii) $\dot x$ keeps its sign over the half-period (checked at 512
# points). For Coulomb friction (ii) reads $m\omega^2 X > F$, i.e.
# $r^2\,Xk/P > F/P$, and with eq. (4) squared the boundary is
#
# $$ \frac{F}{P} < \frac{r^2}{|1 - r^2|\sqrt{1 + r^2 U^2}}. \tag{5}$$
#
# At resonance it tends to $\pi/4$: below that ratio the Coulomb amplitude
# grows without bound at $r = 1$, as Den Hartog found. At low frequency,
# $r$ below about 0.5, (iii) and further solutions with several reversals per
# half-period take over, and we do not claim eq. (5) there.
# `dh.coulomb_boundary` is eq. (5); below, its verdict is set beside the
# closed form's own test of (i) to (iii) just inside and just outside it.
# Notebook 12 draws it over the map of stops per cycle.

# %%
for r in (0.6, 0.9, 0.99, 1.2, 2.0, 2.5):
    edge = float(dh.coulomb_boundary(r))  # eq. (5)
    inside = dh.closed_form(m, 0.0, k, F, F / (0.98 * edge), r * wn).nonstop
    outside = dh.closed_form(m, 0.0, k, F, F / (1.02 * edge), r * wn).nonstop
    print(f"r = {r}: eq. (5) F/P < {edge:.4f}; closed_form admissible at 0.98x: {inside}, at 1.02x: {outside}")
print(f"pi/4 = {math.pi / 4:.4f}")

# %% [markdown]
# ## One long run: reaching the steady state
#
# Each row of the study is one run of the exact solver (`solve_exact`,
# piecewise closed form, events to a few ulps) from rest, for
# `dh.TRANSIENT` = 30 s and then two windows of $K$ = 5 forcing periods. The
# viscous part decays like $e^{-\zeta\omega_n t}$, 2 s per e-fold here, so
# 30 s is 15 e-folds; Coulomb friction alone has no such rate and settles
# more slowly near resonance. The summary is the sweep's (`lumped.drivers.sweep`:
# `steady_amplitude`, `stops_per_period`) read from the events instead of a
# sampled grid: $|x|$ is largest where $\dot x = 0$, which is an event, or at
# an end of the window, so it is exact (the tests check it against the
# sampled definition). Here is one run, with combined damping:

# %%
fp, r = 0.2, 0.8
p, w = F / fp, r * wn
osc = Oscillator.bingham(m, k, F, cfg["gamma"])
window = dh.PERIODS * 2 * math.pi / w
run = solve_exact(osc, dh.TRANSIENT + 2 * window, force=SwitchedSine(p, w, 0.0, math.inf))
t = np.linspace(0.0, run.t_end, 4001)
x = run.evaluate(t)["x"]
steady = dh.steady_state(osc, p, w)
form = dh.closed_form(m, c, k, F, p, w)
print(f"F/P = {fp}, r = {r}: closed form X = {form.amplitude * 1e3:.9f} mm")
print(
    f"last window {steady.amplitude * 1e3:.9f} mm, the one before {steady.previous * 1e3:.9f} mm, stops {steady.stops}"
)
fig = P.den_hartog_history(t, x, form.amplitude, (run.t_end - window, run.t_end))
_ = P.save_figure(fig, "dh02_steady_state")

# %% [markdown]
# ## The data: `results/studies/den_hartog.csv`
#
# One row per damping ($\zeta = 0$, then the paper's 0.05), friction ratio
# $F/P \in \{0.2, 0.4, 0.6, 0.8\}$ and frequency ratio $r$ on
# `np.linspace(0.2, 2.5, N)`, $N$ = 6 in the default build and 120 with
# `snakemake --config studies=full` ($r = 1$ exactly is kept off the grid:
# there the undamped Coulomb amplitude is unbounded for $F/P < \pi/4$). The
# force is $P\sin\omega t$ with $P = F/(F/P)$. Columns:
#
# | column | meaning |
# |---|---|
# | `damping` | $\zeta = c/(2\sqrt{km})$; 0 for Coulomb friction alone |
# | `friction_ratio` | $F/P$ |
# | `frequency_ratio` | $r = \omega/\omega_n$ |
# | `amplitude_ratio` | simulated $Xk/P$: largest $\lvert x\rvert$ over the last $K = 5$ forcing periods, times $k/P$ |
# | `amplitude_change` | $\lvert X - X'\rvert/X$, $X'$ the same over the 5 periods before: how far from steady the run still is |
# | `stops_per_period` | stop events of the exact solution in the last window, divided by 5 |
# | `closed_form` | $Xk/P$ of eqs. (2)-(3); `nan` where the root is not real and positive |
# | `nonstop` | 1 where that motion is admissible (conditions (i)-(iii)), 0 elsewhere |

# %%
path = Path("..", "results", "studies", "den_hartog.csv")
if path.is_file():
    table = studies.read_csv(path, dh.COLUMNS)
else:  # the notebook opened without a pipeline build: the default grid, computed here (about 3 s)
    table = dh.rows(cfg, dh.GRID["default"][0])
n = table["damping"].size
print(f"{n} rows: r from {table['frequency_ratio'].min():g} to {table['frequency_ratio'].max():g}")

# %% [markdown]
# ## Figure dh01: amplitude ratio against frequency ratio
#
# Curves: eqs. (2)-(3), solid where the motion without stops is admissible,
# dotted where the formula has a root but the mass would stop. Points: the
# long runs, filled where the last window has no stop, hollow where it has.

# %%
ratios = np.linspace(*dh.RATIO_RANGE, 231)
ratios = ratios[np.abs(ratios - 1) > 1e-9]
curves = {(z, f): dh.curve(cfg, z, f, ratios) for z in (0.0, zeta) for f in dh.FRICTION_RATIOS}
fig = P.den_hartog_amplitudes(table, curves)
_ = P.save_figure(fig, "dh01_amplitude")

# %% [markdown]
# ## Simulations against the closed form
#
# The closed form predicts which runs stop; the simulation counts stop events.
# Where both say "no stop", the simulated amplitude is compared with
# eqs. (2)-(3), and the residual is set beside `amplitude_change`, the
# distance from the steady state that is left after the run:

# %%
predicted = table["nonstop"] == 1
moving = table["stops_per_period"] == 0
print(f"closed form admissible and no stop in the run: {np.sum(predicted & moving)} of {n} rows")
print(f"admissible but the run stops: {np.sum(predicted & ~moving)}", end="; ")
print(f"not admissible but no stop: {np.sum(~predicted & moving)}")
both = predicted & moving
error = np.abs(table["amplitude_ratio"] - table["closed_form"]) / table["closed_form"]
settled = both & (table["amplitude_change"] < 1e-8)
print(f"settled rows (amplitude change < 1e-8): {settled.sum()}", end=", ")
print(f"largest |simulated/closed form - 1| {error[settled].max():.1e}")
for j in np.flatnonzero(both & ~settled):
    where = f"zeta {table['damping'][j]:g}, F/P {table['friction_ratio'][j]:g}, r {table['frequency_ratio'][j]:.4f}"
    print(f"  not settled: {where}: error {error[j]:.1e}, amplitude change {table['amplitude_change'][j]:.1e}")

# %% [markdown]
# Where the run has settled, simulation and closed form agree to the relative
# error printed above, below $10^{-7}$ on both the default and the full grid.
# The error is the transient still left, not round-off: on the full grid (960 rows, all 550 verdicts "no stop" agreeing
# as here) the rows settled to $10^{-10}$ agree to $6\times10^{-11}$ and those
# settled to $10^{-12}$ to $4\times10^{-13}$, while one Coulomb row near the
# boundary ($F/P = 0.6$, $r = 0.915$) changes by only $5\times10^{-10}$
# between windows yet is $5\times10^{-8}$ off: close to the boundary the
# approach is slow and the window-to-window change understates the distance.
# The rows that have not settled are listed above with their amplitude
# change. On both grids most are Coulomb rows near resonance, where friction
# alone removes energy slowly; the others lie at lower frequency with small
# friction, and any with the viscous part ($\zeta = 0.05$) are within a few
# parts in $10^8$ of steady.
#
# The hollow points: beyond the boundary the mass sticks for part of every
# half-period, and its amplitude falls below the (dotted) formula, which no
# longer describes a motion. At $F/P = 0.8 > \pi/4$ the Coulomb oscillator
# has no motion without stops at any $r \ge 1$ on the grid:

# %%
for z in (0.0, zeta):
    rows = (table["damping"] == z) & (table["friction_ratio"] == 0.8) & (table["frequency_ratio"] >= 1)
    print(f"zeta = {z:g}, F/P = 0.8, r >= 1: stops per period {np.unique(table['stops_per_period'][rows])}")
largest = {z: np.nanmax(np.where(table["damping"] == z, table["amplitude_ratio"], np.nan)) for z in (0.0, zeta)}
print("largest simulated Xk/P on the grid:", {f"zeta {z:g}": round(float(v), 3) for z, v in largest.items()})
