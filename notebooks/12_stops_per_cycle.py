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
# `lumped.studies.stops` and `lumped.studies.stops_low`) and read here from
# `results/studies/stops.csv` (runs from rest, $r \ge 0.1$) and
# `results/studies/stops_low.csv` (periodic motions by shooting, $r < 0.1$).
# At the end, the counts are set against Hong and Liu's list, and the odd
# counts the runs find are traced to slow transients and to the marginally
# stable motions at $r = 1/2n$.
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
from lumped.studies import stops, stops_low

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
# | `orbit_stops` | stops per period of the periodic motion found by shooting from the run's last state |
# | `orbit_multiplier` | the largest modulus of that motion's Floquet multipliers |
# | `stepped_over` | 1 when the run steps over a stop (a check: see "a stop that only just happens" below), else 0 |
#
# The two `orbit_` columns are an independent check of the run: the motion of the
# forcing's period $T$ is found as the fixed point of the exact period map by
# Newton's method (`lumped.drivers.response.shooting.find_orbit`, notebook
# 13), started from the run's last state. Where the run has converged the two
# counts agree; where they differ, the run had not reached its steady motion,
# and a multiplier close to 1 says why: the distance to that motion shrinks by
# about this factor per period. The definitions are in `lumped.studies.stops`.

# %%
path = Path("..", "results", "studies", "stops.csv")
if path.is_file():
    table = studies.read_csv(path, stops.COLUMNS)
else:  # the notebook opened without a pipeline build: the default grid, computed here (a few seconds)
    table = stops.rows(cfg, *stops.GRID["default"][:2])
# A row exactly on eq. (5)'s boundary (r = 3, F/P = 9/16 is one): there each velocity zero of the nonstop
# motion meets the band's edge, and the last bits of the net force decide whether it is a stop; left out.
edge = np.abs(table["friction_ratio"] - dh.coulomb_boundary(table["frequency_ratio"])) <= 1e-12
print(f"left out, on eq. (5)'s boundary: {[(round(float(a), 3), float(b)) for a, b in zip(table['frequency_ratio'][edge], table['friction_ratio'][edge])]}")
table = {name: column[~edge] for name, column in table.items()}
r, q, spp = table["frequency_ratio"], table["friction_ratio"], table["stops_per_period"]
settled = table["settled"] == 1
print(f"{r.size} rows: {np.unique(r).size} values of r in [{r.min():g}, {r.max():g}], {np.unique(q).size} of F/P")
print(f"K = {stops.PERIODS} periods per window after {stops.TRANSIENT}; not settled: {np.sum(~settled)} rows")
print("not settled at (r, F/P, stops in the two windows):", [
    (round(float(a), 3), float(b), int(c), int(d))
    for a, b, c, d in zip(r[~settled], q[~settled], table["previous_stops"][~settled], table["window_stops"][~settled])
])
orbit = table["orbit_stops"]
steady = settled & (orbit == spp) & (table["stepped_over"] == 0)
print(f"a motion of period T found at {np.sum(orbit >= 0)} of {r.size} rows (Newton failed at {np.sum(orbit == -1)}, "
      f"stepped over a stop at {np.sum(orbit == -2)}); runs that step over a stop: {np.sum(table['stepped_over'] == 1)}")
print(f"rows whose settled run has the periodic motion's count (and steps over no stop): {steady.sum()}")
print("the other rows (r, F/P, run's count, motion's count, largest multiplier):", [
    (round(float(a), 3), float(b), float(c), int(d), round(float(e), 2))
    for a, b, c, d, e in zip(r[~steady], q[~steady], spp[~steady], orbit[~steady], table["orbit_multiplier"][~steady])
])

# %% [markdown]
# ## Below $r = 0.1$: the periodic motions by shooting
#
# At low frequency the slowly driven mass sticks and slips many times per
# period, and a run from rest costs many events per period. There the study
# finds the steady motion directly by shooting, from the state a run from rest
# reaches (`lumped.studies.stops_low`), on a grid that continues the log
# spacing of $r$ below 0.1 with the same values of $F/P$. Its columns are
# `frequency_ratio`, `friction_ratio`, `orbit_stops`, `orbit_multiplier` and
# `orbit_stuck_fraction`:

# %%
low_path = Path("..", "results", "studies", "stops_low.csv")
if low_path.is_file():
    low = studies.read_csv(low_path, stops_low.COLUMNS)
else:  # without a pipeline build: the default grid, computed here (about 1 s)
    low = stops_low.rows(cfg, *stops_low.GRID["default"][:2])
lr, lq, ls = low["frequency_ratio"], low["friction_ratio"], low["orbit_stops"]
print(f"{lr.size} rows: {np.unique(lr).size} values of r in [{lr.min():.3f}, {lr.max():.3f}]; "
      f"Newton failed at {np.sum(ls == -1)}, stepped over a stop at {np.sum(ls == -2)}")
mult = low["orbit_multiplier"][ls >= 0]
print(f"multipliers: median {np.median(mult):.2f}, largest {mult.max():.2f}; odd counts: {np.sum((ls > 0) & (ls % 2 == 1))} rows")
lv, ln = np.unique(ls, return_counts=True)
print("stops per period -> rows:", {int(v): int(n) for v, n in zip(lv, ln)})
for rv in np.unique(lr)[:: -(-np.unique(lr).size // 6)]:
    print(f"r = {rv:.3f}: counts {ls[lr == rv].tolist()}")

# %% [markdown]
# The stick phases erase most of the memory of the initial state: the
# median multiplier printed is close to 0, so the motion is reached from rest
# within a few periods. The count grows as $r$ falls, by two at a time (a
# stop in each half-period of a motion symmetric under $x(t + T/2) = -x(t)$;
# the odd counts, if any are printed, are the subject of a section below),
# and is largest at intermediate $F/P$ (the rows printed above). A check of the
# largest count against a long run from rest (the two methods share only the
# exact phases):

# %%
k = int(np.argmax(ls))
check = stops.count_stops(stops.run(cfg, lr[k], lq[k]), 2 * math.pi / (lr[k] * omega_n), stops.PERIODS)
print(f"r = {lr[k]:.3f}, F/P = {lq[k]}: shooting {ls[k]} stops per period; run from rest "
      f"{check.window_stops / stops.PERIODS:g} (settled: {check.settled})")

# %% [markdown]
# ## Figure sp01: the map
#
# The counts, read from the files: for $r \ge 0.1$ the runs' (the first
# lines below), for $r < 0.1$ the periodic motions':

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
judged = steady & (r >= dh.BOUNDARY_FROM) & (np.abs(q / edge - 1) > 0.03)
agree = (spp == 0) == (q < edge)
print(f"rows judged: {judged.sum()}; the map agrees with eq. (5) on {np.sum(judged & agree)}")
print("disagreements at (r, F/P, stops per period):", [
    (round(float(a), 3), round(float(b), 3), float(c)) for a, b, c in zip(r[judged & ~agree], q[judged & ~agree], spp[judged & ~agree])
])

# %%
curve_r = np.geomspace(dh.BOUNDARY_FROM, r.max(), 400)
fig = P.stops_map(
    np.concatenate([lr, r]), np.concatenate([lq, q]), np.concatenate([ls, spp]),
    np.concatenate([ls >= 0, steady]), boundary=(curve_r, dh.coulomb_boundary(curve_r)),
    boundary_label="Den Hartog's boundary, eq. (5)", marked_label="run not settled to the periodic motion",
    split=(stops.R_RANGE[0], r"$r < 0.1$: shooting; $r \geq 0.1$: runs from rest"),
)
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
# count rises to the largest value printed, and further below $r = 0.1$
# (left of the dotted line). Crosses mark rows whose run had not settled to
# the periodic motion (listed above with the run's and the motion's counts):
# a transient still changing after the run, with no viscous damping to end
# it. The default grid is coarse and can step over narrow regions;
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
# ## The odd counts: slow transients, and the marginal motions at $r = 1/2n$
#
# The full grid (`studies=full`, 160 × 120 runs) holds one row with 3 stops
# per period in both windows, the cell (30, 4) of its axes, and rows with 1. Is the row of 3
# a transient not yet settled, an asymmetric or subharmonic motion, or an
# artefact of what is counted? Its run from rest, counted as the study does:

# %%
r_full, q_full = stops.grid(*stops.GRID["full"][:2])
r3, q3 = r_full[30], q_full[4]
T3 = 2 * math.pi / (r3 * omega_n)
c3 = stops.count_stops(stops.run(cfg, r3, q3), T3, stops.PERIODS)
print(f"r = {r3:.3f}, F/P = {q3:g}: {c3.window_stops / stops.PERIODS:g} stops per period in both windows (settled: {c3.settled})")

# %% [markdown]
# Run on for 120 periods, counting the stops in each period, and shoot for
# the motion of period $T$:

# %%
osc = lumped.Oscillator.bingham(cfg["mass"], cfg["stiffness"], cfg["threshold"], math.inf)
force = lumped.SwitchedSine(cfg["threshold"] / q3, r3 * omega_n)
long = lumped.solvers.exact.solve_exact(osc, 120 * T3, force=force)
per = np.histogram(long.event_times("stop"), bins=np.arange(121) * T3)[0]
change = int(np.flatnonzero(per != per[0])[0])
print(f"stops per period: {per[0]} in periods 1 to {change}, then {sorted(set(per[change:].tolist()))} up to period 120")
o3 = stops.orbit_count(cfg, r3, q3)
print(f"the motion of period T: {o3.stops} stops per period, largest multiplier {o3.multiplier:.4f}")
print(f"periods for a deviation to shrink by e: about {-1 / math.log(o3.multiplier):.0f}")

# %% [markdown]
# So the row of 3 is a transient. The stop times within a period show what
# it is: the motion of period $T$ has two stops, half a period apart; during
# the transient the motion carries an asymmetry that decays by the multiplier
# printed above per period, and while it lasts one extra velocity zero, in
# one half of the period only, falls inside the static band:

# %%
for n in (10, change - 1, change + 5):
    when = long.event_times("stop")
    inside = when[(when > n * T3) & (when <= (n + 1) * T3)] / T3 - n
    print(f"period {n + 1}: stops at t/T = {np.array2string(inside, precision=2)}")
scale = np.array([cfg["threshold"] / q3 / cfg["stiffness"], cfg["threshold"] / q3 / cfg["stiffness"] * omega_n])
z = long.evaluate(np.array([10.0, 11.0]) * T3)
drift = np.abs(np.diff(z["x"])[0]) / scale[0], np.abs(np.diff(z["v"])[0]) / scale[1]
print(f"state at t = 11 T minus state at t = 10 T: |dx| = {drift[0]:.0e} P/k, |dv| = {drift[1]:.0e} P omega_n/k")

# %% [markdown]
# An odd count cannot belong to a symmetric motion ($x(t + T/2) = -x(t)$
# maps each stop to another half a period later), so the three-stop motion
# is asymmetric. It is not subharmonic (each period repeats the last to
# within the slow drift printed, with the same three stops at nearly the same
# phases, where a motion of period $2T$ or $3T$ would alternate), and not a
# matter of convention (its stops lie inside the period, not at $t = 0$ or
# $T$). The two windows of 4 periods read it as steady because the
# multiplier is so close to 1. The rows listed above as "the other rows"
# are mostly of this kind (on the full build they hold the rows of 1 and
# 3): a multiplier near 1, at small $F/P$, where friction takes little
# energy per period, or near $r = 1/2, 1/4, 1/6$. Their distances from the
# nearest $r = 1/2n$:

# %%
nearest = 1 / (2 * np.maximum(np.round(1 / (2 * r[~steady])), 1))
print("r, F/P, distance to the nearest 1/2n:", [
    (round(float(a), 3), float(b), round(float(abs(a - c)), 3)) for a, b, c in zip(r[~steady], q[~steady], nearest)
])

# %% [markdown]
# The others are at the edges of regions. (The row at $r = 3$, $F/P = 9/16$,
# left out above, lies exactly on Den Hartog's boundary, eq. (5): there the
# nonstop motion's velocity zeros meet the edge of the static band, and
# whether each is a stop of zero duration or a reversal is decided by the
# last bits of the net force, a counting convention's edge rather than a
# motion of its own.) The section "a stop that only just happens" below
# checks every row for a stop stepped over.
#
# Those frequencies are special. Csernák, Stépán and Shaw (2007, *Nonlinear
# Dyn.* 50, 93-109) report that at excitation frequencies $\Omega = 1/2n$
# (the frequency ratio, as we read their notation) the typical symmetric,
# non-sticking motions are joined by a continuum of asymmetric, marginally
# stable ones; we know their result from its abstract and have not checked
# their formulae. Shooting at exactly those frequencies finds motions with a
# Floquet multiplier equal to 1 within Newton's accuracy, that is marginally
# stable. Where $M - I$ is regular to its computed accuracy, Newton lands on
# an asymmetric one (an odd count) whose one stop per period lasts a tiny
# fraction of the period. Where it is singular to that accuracy (the
# continuum itself), Newton's steps are least-norm
# (`lumped.drivers.response.shooting.least_norm_step`) and stop at the member
# of the family nearest the state a run from rest reaches, which may be the
# symmetric motion without stops. The run from rest keeps the count:

# %%
marginal = []
for n, qv in ((1, 0.2), (2, 0.02), (3, 0.02)):
    oc = stops.orbit_count(cfg, 1 / (2 * n), qv)
    marginal.append(oc.stops)
    print(f"r = 1/{2 * n}, F/P = {qv}: {oc.stops} stop per period, stuck {oc.stuck_fraction:.0e} of it; "
          f"|multiplier - 1| < 1e-5: {abs(oc.multiplier - 1) < 1e-5}")
half = stops.run(cfg, 0.5, 0.2)
c_half = stops.count_stops(half, 2 * math.pi / (0.5 * omega_n), stops.PERIODS)
print(f"run from rest at r = 1/2, F/P = 0.2: {c_half.window_stops / stops.PERIODS:g} stop per period (settled: {c_half.settled})")

# %% [markdown]
# ## A stop that only just happens
#
# Near the edge between two regions, where a new pair of short stops
# appears, the velocity's minimum in a slip phase only just reaches zero: it
# dips below zero for a moment (about a millisecond at the cell below) and
# the mass stops there. The exact solver brackets each stop on a grid of
# sample times (`lumped.solvers.closed_form`), whose spacing, $\pi/(32\omega_n)$
# and more, is longer than such a dip; it therefore also looks, between two
# samples that both keep the slip's direction, for a minimum of the velocity
# along it (the acceleration changing sign against it), and stops where that
# minimum reaches zero. Without that step the dip would be stepped over and
# the mass would slip on in the wrong direction, with one stop of the pair
# missed: an odd count. `stops.steps_over_a_stop` checks every period and
# run of the study for such a phase (the study would mark the motion
# `orbit_stops = -2` and the run `stepped_over = 1`). On the full
# low-frequency grid the cell (17, 16) is one where the dip occurs:

# %%
rl_full, ql_full = stops_low.grid(*stops_low.GRID["full"][:2])
rg, qg = rl_full[17], ql_full[16]
Tg = 2 * math.pi / (rg * omega_n)
graze = lumped.drivers.response.shooting.find_orbit(osc, cfg["threshold"] / qg, rg * omega_n)
print(f"r = {rg:.4f}, F/P = {qg:.4f}: Newton's motion has {graze.stops} stops per period; "
      f"steps over a stop: {stops.steps_over_a_stop(graze.period.solution)}")
run_g = stops.run(cfg, rg, qg)
cg = stops.count_stops(run_g, Tg, stops.PERIODS)
print(f"the run from rest: {cg.window_stops / stops.PERIODS:g} stops per period (settled: {cg.settled}), "
      f"steps over a stop: {stops.steps_over_a_stop(run_g)}; the study's row: {stops.orbit_count(cfg, rg, qg).stops}")
print(f"rows marked -2 here: {np.sum(table['orbit_stops'] == -2)} of {r.size} (r >= 0.1), {np.sum(ls == -2)} of {lr.size} (r < 0.1)")

# %% [markdown]
# ## Compared with Hong and Liu's list
#
# Hong and Liu's abstract lists steady motions with 0, 1, 2, 4, 6, 8, 10, 12
# and 14 stops per cycle. The steady counts here are those of the periodic
# motions (the runs' where they agree with them, the shooting's below
# $r = 0.1$), with the one-stop motions at $r = 1/2n$ shown above:

# %%
ours = set(np.unique(orbit[steady]).tolist()) | set(np.unique(ls[ls >= 0]).tolist()) | set(marginal)
theirs = {0, 1, 2, 4, 6, 8, 10, 12, 14}
print(f"found by both: {sorted(ours & theirs)}")
print(f"only here: even {sorted(c for c in ours - theirs if c % 2 == 0)}, odd {sorted(c for c in ours - theirs if c % 2)}")
print(f"only in Hong and Liu's list: {sorted(theirs - ours)}")
print(f"the runs' counts that are not those of a periodic motion: {sorted(set(spp[settled & ~steady].tolist()))}")
above = np.concatenate([lr[ls > 14], r[steady & (spp > 14)]])
print(f"counts above 14 only for r <= {above.max():.3f}" if above.size else "no count above 14 on this grid")

# %% [markdown]
# Every count of their list appears here, the high ones (8 to 14) only
# below $r = 0.1$, where the runs of the map above did not reach. The even
# counts above 14 found here all lie at lower frequencies still (printed
# above): the count keeps growing as $r$ falls, so a list that ends at 14
# reflects the lowest frequency mapped, which we have not been able to read
# from their paper. Odd counts other than 1 appear here only as transients
# of the runs (the row of 3 above; the last line but one lists those of
# this grid); among the periodic motions found, the odd counts "only here"
# are printed (none on this grid). The count 1 is both a transient
# near $r = 1/2n$ and, at $r = 1/2n$ exactly, a marginally stable asymmetric
# motion that a run from rest keeps: a classification from the long-term
# behaviour of runs, which is how their abstract describes theirs, counts it
# as one stop per cycle.
#
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
# detection) at points of the three regions; below $r = 0.1$ it compares
# the shooting's counts of 8 to 14 with runs from rest of the package's
# event-driven method (slip phases by DOP853), and it checks the row of 3,
# the one-stop motion at $r = 1/2$ and the stop that only just happens.
