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
# # 14. Sensitivities through stick and slip, and a fit to a record
#
# **What you will learn.** How much the motion of the paper's mass, and where
# it comes to rest, move when a parameter moves: exact derivatives of the
# exact solution, carried through slip, stick and every event
# (`lumped.solvers.sensitivities`); where they do not exist (a half-cycle
# gained or lost); and how they give the exact Jacobian of a least-squares
# fit of the threshold $\tau$, the slope $\gamma$ and the stiffness $k$ to a
# measured record (`lumped.drivers.fit`, `python -m lumped fit`), with what a
# free decay can and cannot tell apart. Then the derivative of the steady
# amplitude under a sine, and the derivatives on each side of a parameter
# value where a forced run's events change. The records here are synthetic:
# the exact motion plus Gaussian noise of a fixed seed.

# %%
import math

import numpy as np

import lumped.plotting as P
import lumped.studies.config
from lumped.drivers.fit import fit
from lumped.drivers.sensitivity import system_sensitivities
from lumped.laws import GROUND, Bingham, Spring
from lumped.model.network import Load, Mass, Network
from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.model.records import Record
from lumped.model.system_parameters import system_parameters, with_values
from lumped.solvers.exact import solve_exact
from lumped.solvers.sensitivities import sensitivities

cfg = lumped.studies.config.default()
m, k, tau, gamma, x0 = (cfg[n] for n in ("mass", "stiffness", "threshold", "gamma", "x0_large"))
print(f"m = {m:g} kg, k = {k:g} N/m, tau = {tau:g} N, gamma = {gamma:g} m/(N s), x0 = {x0:g} m")

# %% [markdown]
# ## Step 1: derivatives phase by phase
#
# In a slip phase of direction $s$ the state $y = (x, v, \sin\theta,
# \cos\theta, 1)$, $\theta = \omega t + \phi$, obeys a linear ODE
# $\dot y = My$, with $-k/m$, $-c/m$ ($c = 1/\gamma$), $P/m$, $-s\tau/m$ and
# $\omega$ in $M$. The derivative $u = \partial y/\partial p$ at a fixed time
# obeys $\dot u = Mu + (\partial M/\partial p)\,y$, so both come out of one
# matrix exponential of the block matrix $[[M, 0], [\partial M/\partial p,
# M]]$ (Van Loan, 1978). Between phases the derivative is carried by the
# rules of notebook 13, now with the parameters in them: a phase that ends
# where $v = 0$ ends at $t_b$ with $\delta t_b = -\delta v_b/\dot v(t_b^-)$;
# a stick holds $x$ and forgets $v$ (the projection); a breakaway where
# $F(t) - kx = \pm\tau$ moves by
# $\delta t_c = -(\partial_p F - x\,\partial_p k - k\,\delta x \mp \partial_p\tau)/\dot F(t_c)$;
# and each phase starts with $u = \delta y - f\,\delta t$, $f$ its own field
# (the saltation of the switch). Against central differences of the exact
# solver, on the paper's free decay:

# %%
t = np.linspace(0.0, cfg["t_end_large"], 81)
paper = {"mass": m, "stiffness": k, "threshold": tau, "gamma": gamma, "x0": x0}


def motion(p):
    """The exact motion of the parameters ``p``: its solution to t[-1]."""
    osc = Oscillator.bingham(p["mass"], p["stiffness"], p["threshold"], p["gamma"])
    return solve_exact(osc, t[-1], x0=p["x0"])


exact = sensitivities(motion(paper), t, list(paper))
worst = 0.0
for j, name in enumerate(paper):
    h = 1e-5 * paper[name]
    plus, minus = (motion(paper | {name: paper[name] + s}).evaluate(t)["x"] for s in (h, -h))
    gap = np.abs((plus - minus) / (2 * h) - exact.x[:, j]).max() / np.abs(exact.x[:, j]).max()
    worst = max(worst, gap)
print(f"central differences (h = 1e-5 p) against the exact derivatives, relative: below 1e-6: {worst < 1e-6}")
print(f"smallest event margin {exact.smallest_margin():.2f}: no change of the event sequence nearby")

# %% [markdown]
# The same derivatives are written by the command line, as columns
# `dx_m/d<name>` beside `t, x, v, ...`:
#
# ```bash
# python -m lumped simulate --x0 0.5 --t-end 4 --method exact --sensitivities dashpot.threshold,dashpot.gamma,spring.stiffness --output s.csv
# ```
#
# ## Step 2: where the mass rests, against the threshold
#
# Released at rest from $x_0$, the mass swings in half-cycles until a turning
# point falls inside the static band $|x| \le \tau/k$ (notebook 10). A larger
# $\tau$ means fewer half-cycles. Where the count changes, the last turning
# point lies on the band's edge: on one side it is the stop, on the other a
# reversal followed by one more half-cycle of vanishing amplitude. So the
# rest *position* is continuous in $\tau$ (the motion depends continuously on
# the parameters, and the added half-cycle starts with no amplitude), but its
# derivative jumps there, and the rest *time* jumps by that half-cycle's
# duration, half a damped period $\pi/q$. We scan $\tau$ with the exact
# derivative at each point and locate each change by bisection down to
# neighbouring doubles:

# %%
def count(tau_):
    return len(motion(paper | {"threshold": tau_}).event_times("reversal"))


def bisect(lo, hi):
    """Neighbouring doubles lo < hi with one half-cycle more at lo than at hi."""
    at_lo = count(lo)  # lo moves only to points of its count: one run per halving
    while math.nextafter(lo, hi) < hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if count(mid) == at_lo else (lo, mid)
    return lo, hi


t = np.array([0.0, 20.0])  # long enough for every rest of the scan
taus = np.linspace(0.5, 3.0, 251)
runs = [motion(paper | {"threshold": v}) for v in taus]
rest = np.array([r.rest_position for r in runs])
slope = np.array([sensitivities(r, (), ["threshold"]).rest_position[0] for r in runs])
counts = np.array([len(r.event_times("reversal")) for r in runs])
kinks = [bisect(taus[i], taus[i + 1]) for i in np.flatnonzero(np.diff(counts))]
print(f"{len(kinks)} changes of the half-cycle count for tau in [{taus[0]:g}, {taus[-1]:g}] N")

# %% [markdown]
# At each change, the two sides' derivatives (exact, at the two neighbouring
# doubles) and what `sensitivities` reports on each side for the other one
# (its `switches`: the rest after the half-cycle gained or lost, derived in
# closed form); the rest position's gap across the change; and the jump of the
# rest time against $\pi/q$:

# %%
q = math.sqrt(k / m - (1 / gamma / (2 * m)) ** 2)
marks, worst_switch, worst_gap, worst_jump = [], 0.0, 0.0, 0.0
for lo, hi in kinks:
    more, fewer = motion(paper | {"threshold": lo}), motion(paper | {"threshold": hi})
    s_more, s_fewer = (sensitivities(r, (), ["threshold"]) for r in (more, fewer))
    lose = next(w for w in s_more.switches if w.kind == "lose")
    gain = next(w for w in s_fewer.switches if w.kind == "gain")
    left, right = s_more.rest_position[0], s_fewer.rest_position[0]
    worst_switch = max(worst_switch, abs(lose.rest_position[0] - right), abs(gain.rest_position[0] - left))
    worst_gap = max(worst_gap, abs(more.rest_position - fewer.rest_position))
    worst_jump = max(worst_jump, abs(more.rest_time - fewer.rest_time - math.pi / q))
    marks.append((lo, left, right))
    print(f"tau = {lo:.4f} N: d(rest)/d(tau) jumps from {1e3 * left:+.1f} to {1e3 * right:+.1f} mm/N")
print(f"each side's switch against the other side's derivative: below 1e-9 m/N: {worst_switch < 1e-9}")
print(f"rest position's gap across a change: below 1e-15 m: {worst_gap < 1e-15}")
print(f"rest time's jump against pi/q = {math.pi / q:.4f} s: within 1e-9 s: {worst_jump < 1e-9}")

# %% [markdown]
# ## Figure fit01: the rest position against the threshold
#
# Upper panel: the rest position of the exact solution. Lower panel: its
# exact derivative with respect to $\tau$ at each point of the scan, with
# the one-sided derivatives at each change of the half-cycle count (open
# circle: from below, filled: from above). Between changes the rest position
# is nearly a straight line in $\tau$; at each change the slope's sign flips,
# with the side of the band on which the mass stops, and its size shrinks as
# the half-cycles become fewer. The rest position itself never jumps (printed
# above: its gap across a change is below $10^{-15}$ m); what jumps is the
# rest time, by $\pi/q$.

# %%
fig = P.summary_kinks(taus, rest, slope, marks)
_ = P.save_figure(fig, "fit01_rest_kinks")

# %% [markdown]
# ## Step 3: a fit to a noisy free decay
#
# The record: the paper's free decay sampled every 10 ms for 4 s, with noise
# of standard deviation 1 mm (seed 1). The system is the paper's, named as
# `examples/figure3.toml` names it (the mass `m`, the elements `spring` and
# `dashpot`), with $\tau = 0.8$ N, $\gamma = 1.3$ m/(N s) and $k = 101$ N/m
# as the start. `fit` calls SciPy's `least_squares` with the
# Jacobian $\partial x(t_i)/\partial(\tau, \gamma, k)$ from Step 1; the
# standard errors are those of the linearised model at the estimate,
# $s^2 (J^TJ)^{-1}$ with $s^2 = |r|^2/(n - p)$.

# %%
def system(force=None):
    """The paper's system as a system file names it: the mass m, the elements spring and dashpot."""
    between = (GROUND, "m")
    elements = [Spring("spring", between, k), Bingham("dashpot", between, tau, gamma)]
    return Network([Mass("m", m, x0)], elements, [] if force is None else [Load("m", force)])


def record(net, times, noise, seed):
    """The exact motion of ``net`` at ``times`` plus Gaussian noise (m) of the seed."""
    solution, _ = system_sensitivities(net, times, ["m.x0"])
    rng = np.random.default_rng(seed)
    return Record(times, {"m": solution.evaluate(times)["x"] + noise * rng.standard_normal(times.size)})


free = "dashpot.threshold,dashpot.gamma,spring.stiffness"
truth = system()
start = with_values(truth, system_parameters(truth, free), [0.8, 1.3, 101.0])
data = record(truth, np.linspace(0.0, 4.0, 401), 1e-3, seed=1)
result = fit(start, data, free)
for name, value, se, true in zip(result.parameters, result.estimate, result.standard_error, [tau, gamma, k]):
    print(f"{name:18s} {value:8.3f} +- {se:.1g}   (truth {true:g}; {abs(value - true) / se:.1f} standard errors off)")
print(f"residual std {1e3 * result.residual_std:.2f} mm (noise 1 mm); corr(tau, gamma) = {result.correlation[0, 1]:.2f}")

# %% [markdown]
# ## Figure fit02: the record, the fit and the residuals
#
# Grey dots: the record; line: the fitted motion; lower panel: data less fit,
# which is the noise alone if the model is right (no pattern left, spread
# about 1 mm).

# %%
fig = P.fit_record(result)
_ = P.save_figure(fig, "fit02_free_decay_fit")

# %% [markdown]
# ## Step 4: what a free decay can and cannot tell apart
#
# **The scale of the forces.** Without a load, $m\ddot x + c\dot x + kx = -s\tau$
# is unchanged when $m$, $k$, $\tau$ and $c = 1/\gamma$ are multiplied by the
# same number: a free decay determines $k/m$, $\tau/m$ and $c/m$, never $m$.
# Freed as well, the mass makes the Jacobian's columns exactly dependent, and
# the fit says so: the smallest singular value of the relative Jacobian
# $J\,\mathrm{diag}(\theta)$ is at round-off, and its singular vector is the
# scaling $(1, -1, 1, 1)/2$ in $d\ln(\tau, \gamma, k, m)$ (printed with the
# first coefficient positive). No standard error is given for any of the four.

# %%
scaled = fit(truth, data, free + ",m.mass")
(null,) = [c for c in scaled.combinations if not c.identified]
u = null.coefficients * np.sign(null.coefficients[0])
print(f"sigma_min/sigma_max below 1e-8: {null.ratio < 1e-8}; direction (tau, gamma, k, m): {np.round(u, 2) + 0.0}")
print(f"standard errors given: {int(np.isfinite(scaled.standard_error).sum())} of 4")

# %% [markdown]
# **Threshold against slope.** Both dissipate: early on, when the mass is
# fast, the viscous force $|v|/\gamma$ dominates and a larger $\tau$ can be
# traded for a larger $\gamma$; near the rest, where $v$ is small, the
# viscous force fades and $\tau$ alone sets how far from zero the mass stops. A record that stops
# before the rest sees mostly the trade-off: the correlation of $\tau$ with
# $\gamma$ approaches 1 and their standard errors grow (same noise, the first
# $T$ seconds of the record):

# %%
for T in (1.0, 2.0, 4.0):
    short = Record(data.t[data.t <= T], {"m": data.x["m"][data.t <= T]})
    r = fit(start, short, free)
    rel = r.standard_error / r.estimate
    print(f"T = {T:g} s: relative standard errors tau {rel[0]:.1%}, gamma {rel[1]:.1%}, k {rel[2]:.2%}; corr(tau, gamma) {r.correlation[0, 1]:.3f}")

# %% [markdown]
# ## Step 5: a forced record
#
# Under a known load the scale is fixed by the load's amplitude, and the mass
# is identified with the rest. The record: the same mass under
# $30\sin 7t$ N from $t = 0$, 4 s, same noise. The mass reverses without
# stopping: not because the force stays on, but because the friction is small
# against the load, $F/P = 1/30$ at $r = \omega/\omega_n = 0.7$, where the
# steady motion has no stops (notebook 12's map; the count is printed below).
# All four parameters are freed, from 20 % off in
# $\tau$, 30 % in $\gamma$, 1 % in $k$ and 5 % in $m$.

# %%
forced = system(SwitchedSine(30.0, 7.0))
names4 = free + ",m.mass"
data4 = record(forced, np.linspace(0.0, 4.0, 401), 1e-3, seed=1)
result4 = fit(with_values(forced, system_parameters(forced, names4), [0.8, 1.3, 101.0, 1.05]), data4, names4)
for name, value, se, true in zip(result4.parameters, result4.estimate, result4.standard_error, [tau, gamma, k, m]):
    print(f"{name:18s} {value:8.4f} +- {se:.1g}   (truth {true:g}; {abs(value - true) / se:.1f} standard errors off)")
stops = sum(e.kind == "stop" for e in system_sensitivities(forced, data4.t, ["m.x0"])[0].events)
print(f"all identified: {bool(result4.identified.all())}; corr(k, m) = {result4.correlation[2, 3]:.2f}; stops: {stops}")

# %% [markdown]
# **The fit grows over the record.** From Step 3's start ($\tau = 0.8$ N)
# the fit crossed the change of half-cycle count at $\tau = 0.9346$ N of
# Step 2 without harm: the residual is continuous there, only its derivative
# has a kink. From a start that stops the mass too
# early (a $\tau$ half as large again, a $\gamma$ half as small), a local fit
# to the whole record settles at a worse minimum with fewer half-cycles (it
# did so here before issue 31, with a residual standard deviation far above
# the noise). So `fit` first fits the record's first eighth, where the start
# still follows the motion, then twice as much, and so on to the whole
# record, each from the last estimate; and it does so from three more starts
# spread around the file's values, to find other minima that fit as well
# (then the parameters they move are reported not identified). From that
# start it ends at Step 3's estimate:

# %%
far = fit(with_values(truth, system_parameters(truth, free), [1.5, 0.5, 100.0]), data, free)
same = np.allclose(far.estimate, result.estimate, rtol=1e-6)
print(f"from tau = 1.5, gamma = 0.5: tau = {far.estimate[0]:.3f} N, residual std {1e3 * far.residual_std:.2f} mm; Step 3's: {same}")

# %% [markdown]
# **What the standard errors are.** Those of the model linearised at the
# estimate, for independent Gaussian noise of one variance.
# `benchmarks/bench_fit.py` counts how often two standard errors hold the
# truth over 100 records like Step 3's (its counts are on the benchmarks
# page), and `tests/test_fit.py` asserts at least 90 of 100 for each
# parameter. They say nothing of a wrong model, nor of a minimum that none of
# the starts reached.

# %% [markdown]
# ## Step 6: the steady amplitude under a sine
#
# Under $P\sin\omega t$ that stays on, the mass settles on a periodic motion:
# a fixed point $z^*$ of the period map, $\Pi(z^*; p) = z^*$ (notebook 13,
# `find_orbit`). Differentiating that identity (the implicit function
# theorem) gives its derivative,
# $dz^*/dp = (I - M)^{-1}\,d\Pi/dp$, with the monodromy matrix $M$ and
# $d\Pi/dp$ the derivative of the state at the end of the period from Step 1,
# plus $f(T)\,dT/d\omega$ for $\omega$, since the period $T = 2\pi/\omega$
# moves with it. The amplitude $A$ (half of $\max x - \min x$) is taken at
# two turning points, where $v = 0$, so its derivative is that of $x$ there,
# with the initial state moving by $dz^*/dp$. The paper's forced oscillator,
# its sine kept on ($P = 10$ N, $\omega = 5\pi$ rad/s, $r = \omega/\omega_n
# = 1.57$), against central differences of the amplitudes of periodic motions
# found by Newton to a residual of $10^{-13}$ (step $10^{-5}p$):

# %%
from lumped.drivers.response import find_orbit
from lumped.drivers.steady_sensitivity import steady_amplitude_sensitivities

P, omega = cfg["force_amplitude_large"], cfg["force_omega_over_pi"] * math.pi
names6 = ["dashpot.threshold", "dashpot.gamma", "spring.stiffness", "m.mass", "force.amplitude", "force.omega"]
steady = steady_amplitude_sensitivities(system(), "m", P, omega, names6)
print(steady.summary())
paper6 = dict(zip(names6, [tau, gamma, k, m, P, omega]))


def amplitude(p):
    osc = Oscillator.bingham(p["m.mass"], p["spring.stiffness"], p["dashpot.threshold"], p["dashpot.gamma"])
    return find_orbit(osc, p["force.amplitude"], p["force.omega"], steady.orbit.state, tol=1e-13).amplitude


for name, d in steady.derivatives.items():
    h = 1e-5 * paper6[name]
    fd = (amplitude(paper6 | {name: paper6[name] + h}) - amplitude(paper6 | {name: paper6[name] - h})) / (2 * h)
    print(f"dA/d({name}) = {1e3 * d:8.3g} mm per unit; central difference within 1e-6 of it: {abs(fd - d) < 1e-6 * abs(d)}")
print(f"A/P = {1e3 * steady.amplitude / P:.3g} mm/N")

# %% [markdown]
# Above resonance the mass controls the motion: a heavier mass moves less.
# $dA/dP$ is a little larger than $A/P$: the threshold takes a nearly fixed
# bite out of the amplitude, so the amplitude grows faster than in
# proportion to the force. `tests/test_steady_sensitivities.py` checks the
# same computation against two closed forms to $10^{-9}$: the viscous
# oscillator's $X = (P/k)/\sqrt{(1-r^2)^2 + (2\zeta r)^2}$ and Den Hartog's
# amplitude of Coulomb motion without stops (notebook 11), both
# differentiated by hand.
#
# **Where a stop appears.** At a lower frequency the mass stops twice per
# period at small $P$ and slides through at large $P$. Between, a stop
# appears where the net force at a turning point sits on the band's edge;
# the amplitude there is given from both sides (`one_sided`, the periodic
# motions at $p \mp 10^{-9}p$). Bisecting $P$ at $\omega = 5$ rad/s:

# %%
osc5, lo, hi = Oscillator.bingham(m, k, tau, gamma), 3.45, 3.5
z5 = find_orbit(osc5, lo, 5.0).state
while math.nextafter(lo, hi) < hi:
    mid = 0.5 * (lo + hi)
    orbit5 = find_orbit(osc5, mid, 5.0, z5)
    lo, hi, z5 = (mid, hi, orbit5.state) if orbit5.stops == 2 else (lo, mid, z5)
edge = steady_amplitude_sensitivities(osc5, None, lo, 5.0, ["force_amplitude"], z5)
(side,) = edge.one_sided
print(f"P = {lo:.4f} N: stops per period {side.stops_below} below, {side.stops_above} above")
print(f"dA/dP below and above: {1e3 * side.below:.3g} and {1e3 * side.above:.3g} mm/N; apart by less than 1e-9 of them: {edge.kink < 1e-9}")

# %% [markdown]
# The stops per period jump, but the amplitude has no kink: the stick that
# appears starts with the net force on the band's edge, so with zero
# acceleration, and its start moves the motion after it at second order
# only.
#
# ## Step 7: one-sided derivatives of a forced run
#
# The paper's forced run: $10\sin 5\pi t$ N for one second from rest at
# $x = 0$, then the free decay to rest. As in Step 2, the number of
# half-cycles after the force goes off changes with $\tau$; at the change the
# rest position has a kink and the rest time jumps. `one_sided` solves the
# problem at $\tau \mp \delta$ ($\delta = 10^{-9}\tau$), differentiates each
# side, and reports both derivatives and the jumps. Bisecting the change
# nearest the paper's $\tau$, and comparing each side with a one-sided
# difference (step $10^{-6}$ N, taken on that side only):

# %%
from lumped.solvers.one_sided import one_sided


def forced(tau_):
    osc = Oscillator.bingham(m, k, tau_, gamma)
    return solve_exact(osc, 20.0, force=SwitchedSine(P, omega, 0.0, cfg["force_until"]))


def kinds(tau_):
    return [e.kind for e in forced(tau_).events]


lo, hi = 0.925, 0.95
while math.nextafter(lo, hi) < hi:
    mid = 0.5 * (lo + hi)
    lo, hi = (mid, hi) if kinds(mid) == kinds(0.925) else (lo, mid)
(cut,) = one_sided(forced(lo), ["threshold"])
h = 1e-6
for label, sign, d in (("below", -1, cut.below), ("above", 1, cut.above)):
    near, far = (forced(lo + sign * n * h) for n in (1, 2))
    fd = sign * (far.rest_position - near.rest_position) / h
    print(f"{label}: d(rest)/d(tau) = {1e3 * d.rest_position[0]:+.1f} mm/N; one-sided difference within 1e-6 of it: {abs(fd - d.rest_position[0]) < 1e-6 * abs(fd)}")
print(f"tau = {lo:.4f} N: rest position jump below 1e-12 m: {abs(cut.rest_position_jump) < 1e-12}")
print(f"rest time jump {abs(cut.rest_time_jump):.4f} s against pi/q = {math.pi / q:.4f} s")

# %% [markdown]
# Below the change the mass makes one more half-cycle after the force goes
# off and rests on the other side of zero, so the slope of the rest position
# changes sign, as for the free decay of Step 2, and the rest time jumps by
# that half-cycle, half a damped period $\pi/q$; the position itself does
# not jump. Where the change falls while the force is on, the
# event sequence changes too (a reversal becomes a stop with a breakaway at
# once, as for the steady amplitude above), but the motion keeps its
# derivative: only the events' times have kinks. Where the force only
# touches the band's edge, a breakaway and a stop appear on one side, their
# times with slopes that grow as $\delta^{-1/2}$, while the motion moves by
# $\delta^2$ only. And a force that goes off just as the mass would break
# away cuts a stick short: there the rest time jumps by the rest of the
# stick (`tests/test_one_sided.py` checks these cases against one-sided
# differences on each side, and the breakaway's slope against its closed
# form).
