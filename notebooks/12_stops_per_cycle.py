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
# # 12. Study: stops per cycle of the forced Coulomb oscillator
#
# **What you will learn.** How many times per forcing period a mass on a
# linear spring with Coulomb friction stops, once its motion under
# $P\sin\omega t$ has settled, over the plane of the friction ratio $F/P$
# and the frequency ratio $r = \omega/\omega_n$; where it never stops
# (Den Hartog's nonstop motion), where it stops twice, four or six times,
# and where it never moves at all. Every count comes from the *events* of
# the exact solution (`lumped.solvers.exact.solve_exact`), not from samples.
# The data are computed by the pipeline in chunks (`rules/studies.smk`,
# `lumped.studies.stops`) and read here from `results/studies/stops.csv`.
# The study takes $m$, $k$ and the friction force $F$ from
# `config/config.yaml` as committed (`lumped.studies.config.default()`): a
# `--config` override changes the other notebooks, and here only the
# resolution (`studies`).

# %%
import math
from pathlib import Path

import numpy as np

import lumped.studies.config
import lumped.plotting as P
from lumped import studies
from lumped.studies import den_hartog as dh
from lumped.studies import stops

cfg = lumped.studies.config.default()  # the committed values, whatever --config overrides
omega_n = math.sqrt(cfg["stiffness"] / cfg["mass"])
print(
    f"m = {cfg['mass']:g} kg, k = {cfg['stiffness']:g} N/m, F = tau = {cfg['threshold']:g} N, gamma = inf "
    f"(Coulomb); omega_n = {omega_n:g} rad/s"
)

# %% [markdown]
# ## The model and its two numbers
#
# With $\gamma = \infty$ the Bingham dashpot of eq. (6) is Coulomb friction:
# the mass sticks ($v = 0$) while the net force $P\sin\omega t - kx$ stays
# in the static band $[-F, F]$, and slips against a constant force
# $F\,\mathrm{sgn}\,v$ otherwise, so between events
# $m\ddot x + kx = P\sin\omega t - F\,\mathrm{sgn}\,\dot x$. Dividing by $P$
# and measuring $x$ in units of $P/k$ and time in units of $1/\omega_n$ leaves
# two numbers, $F/P$ and $r = \omega/\omega_n$: the stop count depends on
# nothing else, so the study fixes $F$ (the committed threshold) and sets
# $P = F/(F/P)$.
#
# Den Hartog (1931) solved the steady motion that never stops; Hong and Liu
# (2000, *J. Sound Vib.* 229(5), 1171-1192) wrote the exact solution as two
# phases with a stick-slip switch and, from its long-term behaviour,
# classified the steady motions by their number of stops per cycle (0, 1,
# 2, 4, ..., 14 in their abstract) in the plane of the force and frequency
# ratios. We have not been able to check their figure itself; what follows
# is the quantity they mapped, computed exactly.
#
# **What counts as a stop.** A zero of $v$ is a *stop* when the net force
# there lies in the band, so the mass sticks (possibly for no time at all,
# possibly for less than any sampling step); it is a *reversal* when the
# net force lies beyond the band, and the mass turns back at once. Nonstop
# motion has two reversals per period and no stop. The exact solver reports
# both as events, with their exact times; the study counts the `stop`
# events. (Algorithm 1 would not do here: it sticks for one step at every
# reversal, notebook 10.)
#
# A first check with no computation: for $F/P \ge 1$ the force
# $|P\sin\omega t| \le P \le F$ never leaves the band of a mass at rest at
# $x = 0$, so it never moves.

# %%
never = stops.run(cfg, 0.7, 1.0)
print(f"F/P = 1, r = 0.7: phases {[p.kind for p in never.phases]}, events {len(never.events)}")

# %% [markdown]
# ## Counting stops on one run
#
# Each row of the study is one such exact run from rest ($x_0 = v_0 = 0$),
# over $T_\mathrm{tr} + 2K$ forcing periods $T = 2\pi/\omega$. The stops are
# counted in the last window of $K$ periods and in the window before it; the
# count has *settled* when the two agree. At $r = 0.16$, $F/P = 0.45$:

# %%
r0, q0 = 0.16, 0.45
run = stops.run(cfg, r0, q0)
period = 2 * math.pi / (r0 * omega_n)
count = stops.count_stops(run, period, stops.PERIODS)
kinds = {k: sum(e.kind == k for e in run.events) for k in ("stop", "reversal", "breakaway")}
print(f"T_tr = {stops.TRANSIENT} periods, K = {stops.PERIODS}; events of the whole run: {kinds}")
print(f"stops in the last two windows: {count.previous_stops}, {count.window_stops}; settled: {count.settled}")
print(f"stops per period {count.window_stops / stops.PERIODS:g}, stuck {count.stuck_fraction:.1%} of the last window")

# %% [markdown]
# ## The data: `results/studies/stops.csv`
#
# One row per point of the grid: $r$ log-spaced over $[0.1, 3]$ (stop
# counts change fastest at low $r$) and $F/P$ at the midpoints of equal
# cells of $(0, 1)$; 12 × 8 points in the default build, 160 × 120 with
# `snakemake --config studies=full`. Columns:
#
# | column | meaning |
# |---|---|
# | `frequency_ratio` | $r = \omega/\omega_n$ |
# | `friction_ratio` | $F/P$ |
# | `window_stops` | stop events in the last window of $K$ forcing periods |
# | `previous_stops` | stop events in the $K$ periods before it |
# | `stops_per_period` | `window_stops` / $K$ |
# | `settled` | 1 when the two windows hold the same number of stops, else 0 |
# | `stuck_fraction` | fraction of the last window the mass spends sticking |
#
# The definitions are in `lumped.studies.stops`.

# %%
path = Path("..", "results", "studies", "stops.csv")
if path.is_file():
    table = studies.read_csv(path, stops.COLUMNS)
else:  # the notebook opened without a pipeline build: the default grid, computed here (about 3 s)
    table = stops.rows(cfg, *stops.GRID["default"][:2])
r, q, spp = table["frequency_ratio"], table["friction_ratio"], table["stops_per_period"]
settled = table["settled"] == 1
print(f"{r.size} rows: {np.unique(r).size} values of r in [{r.min():g}, {r.max():g}], {np.unique(q).size} of F/P")
print(f"K = {stops.PERIODS} periods per window after {stops.TRANSIENT}; not settled: {np.sum(~settled)} rows")
print("not settled at (r, F/P, stops in the two windows):", [
    (round(float(a), 3), float(b), int(c), int(d))
    for a, b, c, d in zip(r[~settled], q[~settled], table["previous_stops"][~settled], table["window_stops"][~settled])
])

# %% [markdown]
# ## Figure sp01: the map
#
# The counts, read from the file:

# %%
values, rows_with = np.unique(spp[settled], return_counts=True)
print("stops per period -> rows (settled):", {float(v): int(n) for v, n in zip(values, rows_with)})
print(f"nonstop (0 stops): {np.mean(spp == 0):.1%} of the map; largest count {spp.max():g} per period")
low = r[spp == spp.max()]
print(f"the largest count at r = {np.array2string(np.unique(low), precision=3)}")
odd = settled & (spp % 2 == 1)
print(f"odd counts (settled): {odd.sum()} rows, at (r, F/P) = {[(round(float(a), 3), float(b)) for a, b in zip(r[odd], q[odd])]}")

# %% [markdown]
# Along each column of the map, where does the motion stop? The smallest
# $F/P$ with stops, per $r$ (the edge of the nonstop region, which Den
# Hartog's analysis predicts; at most twelve columns, evenly spread), and the
# frequencies below which every settled row stops:

# %%
columns = np.unique(r)
for rv in columns[:: -(-columns.size // 12)]:
    col = (r == rv) & settled
    stopping = q[col & (spp > 0)]
    edge = f"{stopping.min():.3f}" if stopping.size else "none on the grid"
    print(f"r = {rv:.3f}: first F/P with stops {edge}; counts {spp[col].astype(int).tolist()}")
nonstop_r = r[settled & (spp == 0)]
print(f"every settled row stops for r < {nonstop_r.min():.3f}; the nonstop rows span r in [{nonstop_r.min():.3f}, {nonstop_r.max():.3f}]")
print(f"rows stuck for more than half the last window: {np.mean(table['stuck_fraction'] > 0.5):.1%}")

# %% [markdown]
# Den Hartog's boundary of motion without stops, eq. (5) of notebook 11
# (`lumped.studies.den_hartog.coulomb_boundary`, claimed for $r \ge 0.5$),
# is an independent prediction of where the zero-stop region ends. Each
# settled row at $r \ge 0.5$ is set against it: below the boundary it should
# not stop, above it it should. Rows within 3 % of the boundary in $F/P$ are
# left out, since the grid cannot place them:

# %%
fine = np.geomspace(dh.BOUNDARY_FROM, 3.0, 2001)
top = np.argmax(dh.coulomb_boundary(fine))
print(f"eq. (5) is highest, F/P = {dh.coulomb_boundary(fine[top]):.3f}, at r = {fine[top]:.3f}; at r = 1 it is pi/4 = {math.pi / 4:.3f}")
edge = dh.coulomb_boundary(np.maximum(r, dh.BOUNDARY_FROM))
judged = settled & (r >= dh.BOUNDARY_FROM) & (np.abs(q / edge - 1) > 0.03)
agree = (spp == 0) == (q < edge)
print(f"rows judged: {judged.sum()}; the map agrees with eq. (5) on {np.sum(judged & agree)}")
print("disagreements at (r, F/P, stops per period):", [
    (round(float(a), 3), round(float(b), 3), float(c)) for a, b, c in zip(r[judged & ~agree], q[judged & ~agree], spp[judged & ~agree])
])

# %%
curve_r = np.geomspace(dh.BOUNDARY_FROM, r.max(), 400)
fig = P.stops_map(r, q, spp, table["settled"], boundary=(curve_r, dh.coulomb_boundary(curve_r)),
                  boundary_label="Den Hartog's boundary, eq. (5)")
_ = P.save_figure(fig, "sp01_stops_map")

# %% [markdown]
# How to read the map, with the numbers printed above: motion without stops
# (zero) occupies the small-$F/P$ part of the map at the higher frequencies,
# bounded by Den Hartog's curve, which is highest just below resonance and
# falls away on both sides (its top and its value $\pi/4$ at $r = 1$ are
# printed above); the
# lines above list the smallest $F/P$ with stops in each column, the rows
# checked against the curve and any that disagree (near $r = 0.5$, where the
# sign of the velocity over the half-period starts to bind, a few can). Towards low frequency the
# slowly driven mass makes several stick-slip steps per half-period, and the
# count rises to the largest value printed. Crosses mark rows whose count had
# not settled after the run (listed with their two window counts above): a
# stop count still changing after the transient, with no viscous damping to
# end it. Hong and Liu's list includes odd counts (one stop per cycle, an
# asymmetric motion); the line "odd counts" says whether this grid holds
# any. The default grid is coarse and can step over narrow regions;
# `studies=full` resolves them.
#
# ## Figure sp02: three motions
#
# Single exact runs, their last two periods, at points of the 0-, 2- and
# many-stop regions (displacement in units of $P/k$, sticking shaded):

# %%
points = ((2.0, 0.3), (0.4, 0.6), (0.1, 0.45))
panels = []
for rv, qv in points:
    sol = stops.run(cfg, rv, qv)
    T = 2 * math.pi / (rv * omega_n)
    c = stops.count_stops(sol, T, stops.PERIODS)
    t = np.linspace(sol.t_end - 2 * T, sol.t_end, 801)
    x = sol.evaluate(t)["x"] * cfg["stiffness"] * qv / cfg["threshold"]  # k x / P, P = F / (F/P)
    sticks = [(a / T, b / T) for a, b in sol.stick_intervals() if b > t[0]]
    panels.append((f"r = {rv:g}, F/P = {qv:g}: {c.window_stops / stops.PERIODS:g} stops per period", t / T, x, sticks))
    print(panels[-1][0], f"(settled: {c.settled}, stuck {c.stuck_fraction:.1%})")

# %%
fig = P.stop_histories(panels)
_ = P.save_figure(fig, "sp02_stop_histories")

# %% [markdown]
# ## A row of the file, recomputed
#
# The file's first row, run again here by `stops.run` and counted by
# `stops.count_stops`, gives the same integers (the exact solver is
# deterministic):

# %%
again = stops.count_stops(stops.run(cfg, r[0], q[0]), 2 * math.pi / (r[0] * omega_n), stops.PERIODS)
print(f"row 0: file {table['window_stops'][0]}, {table['previous_stops'][0]}; again {again.window_stops}, {again.previous_stops}")

# %% [markdown]
# `tests/test_stops_study.py` compares the counts with an independent
# event-driven integration (DOP853 with its own stop and breakaway
# detection) at points of the three regions.
