# ---
# jupyter:
#   jupytext:
#     formats: ipynb,py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 16. Self-excited oscillations: from steady sliding to stick-slip
#
# **What you will learn.**
#
# * why a block on a spring, dragged by a belt at a constant speed through a
#   friction contact whose force *falls* with the sliding speed, vibrates with
#   no periodic load at all: steady sliding, its linearisation, and the belt
#   speed where it loses stability (a Hopf point), in closed form for
#   Veraszto and Stépán's Stribeck law; and why Leine's law, with no viscous
#   part, leaves steady sliding unstable at every speed;
# * a limit cycle as a fixed point of the return map to a section, found by
#   Newton's method with the map's exact derivative, and what a stuck contact
#   does to the cycle's Floquet multiplier (it makes it 0);
# * the bifurcation diagram in the belt speed for both laws, by
#   pseudo-arclength continuation: equilibria stable and unstable, the Hopf point against its closed form, the small unstable
#   cycles born there, the stick-slip branch, the fold where the two meet, and
#   long event-driven runs on top;
# * how far a first-order (averaging) approximation of the slip-only cycles
#   goes, and where it fails.
#
# Every statement below is backed by a printed number or an `assert`.

# %%
# %matplotlib inline
import math

import numpy as np
import sympy as sp
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import i1

import lumped as L
import lumped.plotting as P
from lumped.drivers.cycles import Cycle, find_cycle, hopf_points, return_map, steady_sliding
from lumped.drivers.cycles.continuation import continue_branches
from lumped.solvers.closed_form_belt import belt_cycle
from lumped.solvers.event_driven_network import solve_contact

# Leine et al.'s benchmark: m = k = 1, g(s) = F_s / (1 + delta s), no damper.
F_s, delta = 1.0, 3.0
# Veraszto and Stepan's hardware-in-the-loop parameters: g(s) = C + (C0 - C) exp(-c_v s) + b_s s, a damper b0.
mv, kv, b0, C, C0, cv, bs = 0.538, 6957.0, 5.746, 2.0, 6.0, 10.0, 0.2


def leine_g(s):
    return F_s / (1 + delta * s)


def vs_g(s):
    return C + (C0 - C) * np.exp(-cv * s) + bs * s


def leine_belt(V: float, x0: float = 0.0, v0: float = 0.0) -> L.Network:
    """The block (1 kg) on a spring (1 N/m) riding a belt at V through Leine's falling curve."""
    law = L.SlipCurve(F_s, leine_g, fall=F_s * delta)
    return L.Network(
        [L.Mass("m", 1.0, x0, v0)],
        [L.Spring("spring", ("ground", "m"), 1.0), L.Contact("contact", ("belt", "m"), law)],
        drivers=[L.Driver("belt", V)],
    )


def vs_belt(V: float, x0: float = 0.0, v0: float = 0.0) -> L.Network:
    """Veraszto and Stepan's block: a spring and a damper to the ground, a Stribeck contact with a viscous part."""
    contact = L.Friction("contact", ("belt", "m"), static=C0, kinetic=C, stribeck_velocity=1 / cv, viscous=bs)
    return L.Network(
        [L.Mass("m", mv, x0, v0)],
        [L.Spring("spring", ("ground", "m"), kv), L.LinearDashpot("damper", ("ground", "m"), b0), contact],
        drivers=[L.Driver("belt", V)],
    )


print(f"Leine: m = 1 kg, k = 1 N/m, F_s = {F_s} N, delta = {delta} s/m, no damper")
print(f"Veraszto-Stepan: m = {mv} kg, k = {kv} N/m, b0 = {b0} N s/m, C = {C} N, C0 = {C0} N, "
      f"c_v = {cv} s/m, b_s = {bs} N s/m")

# %% [markdown]
# ## Step 1: steady sliding and its linearisation
#
# With $u = \dot x - V$ the contact's rate and the belt faster than the block,
# the contact drags the block forward with $g(V - \dot x)$, and the equation
# of motion is
#
# $$m\ddot x + b_0\dot x + kx = g(V - \dot x) \qquad (\dot x < V). \tag{1}$$
#
# *Steady sliding* is the block at rest while the belt slides under it:
# $x^* = g(V)/k$. For $y = x - x^*$, to first order,
#
# $$m\ddot y + \bigl(b_0 + g'(V)\bigr)\dot y + ky = 0, \qquad
#   \lambda_{1,2} = \frac{-c \pm \sqrt{c^2 - 4mk}}{2m}, \quad c = b_0 + g'(V). \tag{2}$$
#
# SymPy linearises (1) for any slip curve $g$:

# %%
t_ = sp.Symbol("t")
m_, k_, b_, V_ = sp.symbols("m k b_0 V", positive=True)
g = sp.Function("g")
y = sp.Function("y")(t_)
x_star_ = g(V_) / k_
rhs = -k_ * (x_star_ + y) - b_ * y.diff(t_) + g(V_ - y.diff(t_))  # m x'' = rhs, x = x* + y
eps_ = sp.Symbol("epsilon")
linear = sp.series(rhs.subs(y, eps_ * y).doit(), eps_, 0, 2).removeO().subs(eps_, 1).doit()
c_ = b_ + sp.Subs(g(sp.Symbol("s")).diff(sp.Symbol("s")), sp.Symbol("s"), V_).doit()
assert sp.simplify(linear - (-k_ * y - c_ * y.diff(t_))) == 0
print("m y'' =", sp.simplify(linear))

# %% [markdown]
# Steady sliding is stable while the linearised damping $c = b_0 + g'(V)$ is
# positive and loses stability where it vanishes: a pair of eigenvalues
# crosses the imaginary axis at $\pm i\sqrt{k/m}$ (a Hopf point). For
# Veraszto and Stépán's curve $g'(V) = b_s - (C_0 - C)c_v e^{-c_v V}$, so
#
# $$V_H = \frac{1}{c_v}\ln\frac{(C_0 - C)\,c_v}{b_0 + b_s}. \tag{3}$$
#
# For Leine's law $g'(V) = -F_s\delta/(1 + \delta V)^2 < 0$ at every speed
# and there is no damper: $c < 0$ always, steady sliding is **unstable at every
# belt speed**, and its diagram has no Hopf point: the only motions that can
# attract are cycles.

# %%
s_ = sp.Symbol("s", positive=True)
g_vs = C + (C0 - C) * sp.exp(-cv * s_) + bs * s_
(V_hopf,) = sp.solve(sp.Eq(b0 + g_vs.diff(s_), 0), s_)
V_hopf = float(V_hopf)
assert math.isclose(V_hopf, math.log((C0 - C) * cv / (b0 + bs)) / cv, rel_tol=1e-14)
d_, F_ = sp.symbols("delta F_s", positive=True)
leine_c = sp.simplify((F_ / (1 + d_ * s_)).diff(s_))
print(f"Veraszto-Stepan: V_H = ln((C0 - C) c_v / (b0 + b_s)) / c_v = {V_hopf:.8f} m/s")
print(f"Leine: c = 0 + g'(V) = {leine_c}, negative for every V > 0")


# %% [markdown]
# The package computes steady sliding and its eigenvalues for any such system
# (`lumped.drivers.cycles.steady_sliding`, from the network's springs,
# dashpots and the law's slope, `SlipLaw.slope`, a value with its error
# bound); they meet $x^* = g(V)/k$ and the closed forms (2) to within that
# bound:

# %%
def closed_form(m, k, c):
    root = np.sqrt(complex(c * c - 4 * m * k))
    return np.sort_complex(np.array([(-c - root) / (2 * m), (-c + root) / (2 * m)]))


for name, net_of, g_of, m, k, c_of, speeds in (
    ("Leine", leine_belt, leine_g, 1.0, 1.0, lambda V: -F_s * delta / (1 + delta * V) ** 2, (0.05, 0.2, 0.5)),
    ("Veraszto-Stepan", vs_belt, vs_g, mv, kv, lambda V: b0 + bs - (C0 - C) * cv * math.exp(-cv * V),
     (0.8 * V_hopf, 0.95 * V_hopf, 1.05 * V_hopf, 1.2 * V_hopf)),
):
    for V in speeds:
        net = net_of(V)
        eq = steady_sliding(net)
        bound = net.elements[-1].law.slope(V).error / m
        ref = closed_form(m, k, c_of(V))
        assert math.isclose(eq.position[0], g_of(V) / k, rel_tol=1e-12)
        assert np.all(np.abs(np.sort_complex(eq.eigenvalues) - ref) <= bound + 1e-12 * np.abs(ref))
        print(f"{name:15s} V = {V:.4f} m/s: x* = {eq.position[0]:.4e} m, c = {c_of(V):+.4f} N s/m, max Re(lambda) = "
              f"{eq.max_real_part:+.4f} 1/s ({'stable' if eq.stable else 'unstable'})")

# %% [markdown]
# and `hopf_points` locates where a pair crosses the imaginary axis in any
# parameter of the system file, here the belt's speed (`belt.velocity`): to
# $10^{-8}$ of (3), the reference, for the Veraszto-Stépán belt, and
# nowhere for Leine's:

# %%
(V_located,) = hopf_points(vs_belt(0.2), "belt.velocity", 0.1, 0.3)
assert abs(V_located / V_hopf - 1) <= 1e-8
assert hopf_points(leine_belt(0.2), "belt.velocity", 0.05, 0.5) == []
print(f"hopf_points: {V_located:.8f} m/s (closed form {V_hopf:.8f} m/s, within 1e-8 relative); Leine: none")

# %% [markdown]
# Below $V_H$ the Veraszto-Stépán block's steady sliding grows into oscillation; above it, it
# is stable, but, as Step 3 shows, not the only motion that attracts.
#
# ## Step 2: a limit cycle as a fixed point of the return map
#
# A periodic motion of (1) crosses the line $x = x^*$ upward once a period (it
# circles steady sliding). Take that line as a *section*, its coordinate the
# block's velocity $v > 0$ there, and follow the motion from $(x^*, v)$ to its
# next upward crossing, at $(x^*, P(v))$: the *return map* $P$. A cycle is a
# fixed point, $P(v) = v$; its period, the return time. The package computes
# $P$ by the `event-driven` method's phases (slip, stop, stick, breakaway)
# with each stick and slip event located, and the map's exact derivative
# $P'(v)$ with it (`lumped.drivers.cycles.return_map`; its module docstring
# derives it from Liouville's formula and the events' saltation matrices), so
# Newton's method on $P(v) - v$ converges quadratically. Just above $V_H$ on
# the Veraszto-Stépán belt, from $v = 0.06$ m/s:

# %%
V1 = 1.02 * V_hopf
vs1 = vs_belt(V1)
v = 0.06
for step in range(8):
    p, dp, period = return_map(vs1, v)
    residual = p - v
    if abs(residual) <= 1e-12 * V1:
        print(f"step {step}: v = {v:.8f} m/s, |P(v) - v| below 1e-12 V: converged")
        break
    print(f"step {step}: v = {v:.8f} m/s, P(v) - v = {residual:+.1e} m/s, P'(v) = {dp:.6f}")
    v -= residual / (dp - 1)
cycle1 = find_cycle(vs1, 0.06)
assert abs(cycle1.section - v) <= 1e-10 * V1
print(f"find_cycle: v = {cycle1.section:.8f} m/s, period {cycle1.period:.6f} s, "
      f"amplitude {(cycle1.x_max[0] - cycle1.x_min[0]) / 2:.4e} m, stick phases {cycle1.stick_phases}, slowest slip "
      f"{cycle1.min_slip_speed:.4f} m/s, "
      f"multiplier {cycle1.max_multiplier:.4f} ({'stable' if cycle1.stable else 'unstable'})")

# %% [markdown]
# This cycle never sticks (its smallest slip speed is well above zero), and
# its one nontrivial Floquet multiplier is $P'(v) = 1.0234 > 1$: it is
# **unstable**. It is the small cycle born at the Hopf point on the stable side
# of steady sliding: the Hopf bifurcation is *subcritical*. A motion started
# inside it returns to steady sliding; one started outside grows away from it.
#
# The multiplier is checked against a central difference of the map, whose
# error is its truncation, $h^2|P'''|/6$, estimated as $|D(2h) - D(h)|/3$,
# plus the map's own error (DOP853 at `rtol` $10^{-13}$: about $100\times10^{-13}$
# of $P$, over $h$, twice), with $h = (3\rho)^{1/3}v$ balancing the two:

# %%
rho = 100 * 1e-13
h = (3 * rho) ** (1 / 3) * cycle1.section
D = lambda h: (return_map(vs1, cycle1.section + h)[0] - return_map(vs1, cycle1.section - h)[0]) / (2 * h)
d1, d2 = D(h), D(2 * h)
bound = abs(d2 - d1) + 2 * rho * cycle1.section / h
assert abs(cycle1.max_multiplier - d1) <= bound < 1e-7
print(f"central difference {d1:.5f}, Liouville {cycle1.max_multiplier:.5f}: within their bound, below 1e-7")

# %% [markdown]
# ### What a stuck contact does to the multipliers
#
# Where the motion meets an event, the perturbation of the state jumps by the
# event's *saltation matrix*, $S = I + (f^+ - f^-)\,n^T/(n\cdot f^-)$, with $f^\mp$
# the vector field before and after and $n$ the normal of the event's surface.
# At a *stop* (slip to stick) the surface is $u = 0$ and, in the coordinates
# $(x, u)$, the field before is $(V + u, a)$ (with $u = 0$ there, and $a$ the
# slip's deceleration) and after it $(V, 0)$ (the block rides the belt):

# %%
a_ = sp.Symbol("a", nonzero=True)
f_minus, f_plus, n = sp.Matrix([V_, a_]), sp.Matrix([V_, 0]), sp.Matrix([0, 1])
S = sp.eye(2) + (f_plus - f_minus) * n.T / (n.T * f_minus)[0]
assert S == sp.diag(1, 0)
print("saltation matrix at a stop:", S.tolist(), "; det =", S.det())

# %% [markdown]
# $S$ is singular: it removes the direction $u$. Every perturbation of the
# relative speed is wiped out at the stop, since every nearby motion sticks on
# the same line $u = 0$; what is left is a shift along that line, which the
# stick turns into a shift in time (the block rides to the same breakaway
# point whatever its start). The monodromy matrix over a period is a product
# of the phases' Jacobians and the events' saltation matrices, so its
# determinant, the product of the two multipliers, is 0. One of them is the
# trivial multiplier 1 (along the flow); the other is therefore **0**. A
# stick-slip cycle is superstable: a nearby motion joins it exactly at its
# first stop. The return map shows it: on Leine's belt at $V = 0.2$ m/s the
# section is crossed while stuck, at the belt's speed, from any start near it:

# %%
V2 = 0.2
leine2 = leine_belt(V2)
for v in (0.15, 0.2, 0.25):
    p, dp, period = return_map(leine2, v)
    assert p == V2 and dp == 0.0
    print(f"v = {v} m/s: P(v) = {p} m/s exactly, P'(v) = {dp}, return time {period:.6f} s")

# %% [markdown]
# (The return time depends on $v$: the perturbation became a shift in time.)
# The cycle itself, against the independent event-driven run of notebook 15,
# Step 6 (`solve_contact` from the breakaway point, whose period is the time to
# the next breakaway): both integrate at `rtol` $10^{-13}$, and
# `tests/test_friction_event_driven.py` derives $1.8\times10^{-9}$ for either
# one's period, so they agree within $10^{-8}$:

# %%
leine_cycle = find_cycle(leine2, V2)
motion = solve_contact(leine_belt(V2, F_s, V2), 15.0, rtol=1e-13)
period_ed = next(e.time for e in motion.events[1:] if e.kind == "breakaway")
assert abs(leine_cycle.period - period_ed) <= 1e-8
print(f"Leine at V = {V2} m/s: period {leine_cycle.period:.6f} s (event-driven {period_ed:.6f} s), x_max "
      f"{leine_cycle.x_max[0]:.6f} m, x_min {leine_cycle.x_min[0]:.6f} m, stick {leine_cycle.stick_time:.4f} s, "
      f"multiplier {leine_cycle.max_multiplier:g}")

# %% [markdown]
# Where every phase is linear (static above kinetic, no Stribeck fall, no
# damper: notebook 15's belt) the shooting runs on the closed forms, and meets
# `belt_cycle` to round-off; $10^{-10}$ is the bound:

# %%
m, k, S_, K_, V = 1.0, 1.0, 1.0, 0.5, 0.2
sk_belt = L.Network(
    [L.Mass("m", m)],
    [L.Spring("spring", ("ground", "m"), k), L.Friction("contact", ("belt", "m"), static=S_, kinetic=K_)],
    drivers=[L.Driver("belt", V)],
)
shot, ref = find_cycle(sk_belt, V), belt_cycle(m, k, S_, K_, V)
differences = [shot.period - ref.period, shot.x_max[0] - ref.x_max, shot.x_min[0] - ref.x_min,
               shot.stick_time - ref.stick_time]
assert max(abs(d) for d in differences) <= 1e-10
print(f"static/kinetic belt: period {shot.period:.10f} s, x_max {shot.x_max[0]:.10f} m, x_min {shot.x_min[0]:.10f} m;"
      f" belt_cycle's within 1e-10 (period, extremes, stick time)")

# %% [markdown]
# ## Step 3: the bifurcation diagrams in the belt speed
#
# **Leine's law.** Steady sliding is unstable at every speed (Step 1). Nor
# can there be a cycle that only slips: over its period the spring's work is
# zero, and so must be the contact's, $\oint g(V - \dot x)\,\dot x\,dt =
# \oint \bigl(g(V - \dot x) - g(V)\bigr)\dot x\,dt$; but $g$ falls, so the
# integrand has the sign of $\dot x^2$ and the integral is positive: the
# contact feeds energy into every slip-only motion. What remains is stick-slip.
# `continue_branches` (`lumped.drivers.cycles.continuation`) follows steady
# sliding and the cycle found at the range's start by pseudo-arclength in
# (section speed, parameter), Newton's method on $P(v; p) - v$ with the
# map's derivative as the corrector, and reports every Hopf point, fold,
# change of stick phases and multiplier crossing the unit circle as a row of
# its own. From 0.05 to 0.5 m/s:

# %%
leine_rows = continue_branches(leine_belt(0.05), "belt.velocity", 0.05, 0.5, points=46)
leine_eq = [r for r in leine_rows if r.branch == "equilibrium"]
leine_cy = [r for r in leine_rows if r.branch == "cycle"]
assert {r.kind for r in leine_rows} == {"regular"} and not any(r.equilibrium.stable for r in leine_eq)
assert all(r.cycle.stable and r.cycle.stick_phases == 1 and r.cycle.max_multiplier == 0 for r in leine_cy)
print("every row regular: no Hopf point, fold or change of stick phases; every equilibrium unstable, every cycle "
      "stick-slip with one stick a period and multiplier 0")
for r in (leine_cy[0], leine_cy[-1]):
    c = r.cycle
    print(f"V = {r.value:.2f} m/s: period {c.period:.4f} s, x from {c.x_min[0]:+.4f} to {c.x_max[0]:+.4f} m, "
          f"stuck {c.stick_time / c.period:.0%} of it")

# %% [markdown]
# Long runs by `event-driven` from $10^{-3}$ m beside steady sliding at rest
# grow (at the linear rate $F_s\delta/(2(1 + \delta V)^2)$, above 0.24 1/s) into
# the stick-slip cycle within 120 s; their extremes over the last 40 s, sampled
# every $10^{-3}$ s (which lowers a maximum by at most $\omega^2 A h^2/8 <
# 10^{-6}$ m), meet the cycles' (found by Newton's method from the belt's
# speed at the runs' speeds):

# %%
def settled_extremes(network: L.Network, t_end: float, last: float, h: float) -> tuple[float, float]:
    """The largest and smallest position of the event-driven run over its last ``last`` seconds."""
    x = solve_contact(network, t_end, rtol=1e-10).state(np.arange(t_end - last, t_end, h))[0]
    return float(x.max()), float(x.min())


def branches(rows):
    """The equilibria (value, position, stable) and the cycles (value, x_max, x_min, stable) of the rows, in order."""
    eq = [(r.value, r.equilibrium.position[0], r.equilibrium.stable) for r in rows if r.branch == "equilibrium"]
    cy = [(r.value, r.cycle.x_max[0], r.cycle.x_min[0], r.cycle.stable) for r in rows if r.branch == "cycle"]
    return tuple(np.array(col) for col in zip(*eq)), tuple(np.array(col) for col in zip(*cy))


run_speeds = np.array([0.1, 0.2, 0.3, 0.4, 0.5])
leine_runs = np.array([settled_extremes(leine_belt(V, leine_g(V) + 1e-3), 120.0, 40.0, 1e-3) for V in run_speeds])
at_runs = [find_cycle(leine_belt(V), V) for V in run_speeds]
worst = max(max(abs(hi - c.x_max[0]), abs(lo - c.x_min[0])) for (hi, lo), c in zip(leine_runs, at_runs))
assert worst < 1e-6
print(f"long runs at V = {', '.join(f'{V:g}' for V in run_speeds)} m/s: extremes within 1e-6 m of the cycles'")
leine_equilibria, leine_cycles = branches(leine_rows)
fig = P.bifurcation_diagram(leine_equilibria, {"stick-slip cycle": leine_cycles}, (run_speeds, *leine_runs.T))
_ = P.save_figure(fig, "cy01_bifurcation_leine")

# %% [markdown]
# The diagram is the simplest one: an unstable equilibrium at every speed,
# surrounded by a superstable stick-slip cycle whose amplitude grows with the
# belt's speed; no Hopf point, no slip-only cycle, no fold.
#
# **The Veraszto-Stépán law.** Here steady sliding is stable above $V_H$.
# From half to 1.6 times $V_H$, the continuation starts the cycle branch at
# the Hopf point (branch switching onto its small cycles) and follows it
# through everything it meets; the rows that are not regular:

# %%
vs_rows = continue_branches(vs_belt(V_hopf), "belt.velocity", 0.5 * V_hopf, 1.6 * V_hopf, points=30)
marked = [r for r in vs_rows if r.kind != "regular"]
assert [(r.branch, r.kind) for r in marked] == [
    ("equilibrium", "hopf"), ("cycle", "hopf"), ("cycle", "stick-slip-onset"), ("cycle", "fold")]
hopf_row, onset, fold = marked[1:]
assert abs(hopf_row.value / V_hopf - 1) <= 1e-8
assert abs(fold.value - onset.value) < 1e-4 * V_hopf
print(f"hopf at V = {hopf_row.value:.8f} m/s (within 1e-8 of (3)): zero amplitude, multiplier "
      f"{hopf_row.cycle.max_multiplier:.4f}")
for r, digits in ((onset, 5), (fold, 3)):
    c = r.cycle
    print(f"{r.kind:16s} at V = {r.value / V_hopf:.{digits}f} V_H: stick phases {c.stick_phases}, amplitude "
          f"{(c.x_max[0] - c.x_min[0]) / 2:.3e} m, multiplier {c.max_multiplier:.4f}")
cycle_rows = [r for r in vs_rows if r.branch == "cycle" and r.kind == "regular"]
assert all(r.cycle.stable == (r.cycle.stick_phases > 0) for r in cycle_rows)  # stick-slip stable, slip-only not
slip_rows = [r for r in cycle_rows if r.cycle.stick_phases == 0]
assert all(V_hopf < r.value < onset.value for r in slip_rows)

# %% [markdown]
# The Hopf point is *subcritical*: the cycles born there (multiplier 1 at
# zero amplitude) lie on the stable side of steady sliding, $V > V_H$, and
# are unstable (Step 2's 1.0234 at $1.02\,V_H$). As the speed rises they grow
# and their slowest slip speed falls, until at $1.42585\,V_H$ the cycle touches
# the belt's speed: it *grazes* the stuck state (`stick-slip-onset`). There
# the branch has a kink: past it every cycle sticks once a period and the
# branch turns back toward lower speeds as the stick-slip cycle, stable,
# down to the range's start. The `fold` row is that turn on the stick-slip
# side of the kink, its multiplier 0 against the slip side's 1.5645: it does
# not pass through 1 as at a smooth fold but jumps across the unit circle,
# the *discontinuous* fold of Leine and van Campen, which a continuation
# watching only for $\mu = 1$ would miss. (The two rows are the kink's two
# sides, each located by bisection along its own piece; they are within
# $10^{-4}\,V_H$ of each other.) Beyond it neither cycle exists.
#
# **The Hopf point from the cycles.** Near a Hopf point the speed is a series
# in the cycles' squared amplitude, $V = V_H + c_1 a^2 + c_2 a^4 + \dots$, so a
# line through the two smallest cycles in $(a^2, V)$, and a parabola through
# the three smallest, meet $a = 0$ near $V_H$; the parabola errs by the next
# term, smaller than the one the line leaves out (their difference), which
# is the tolerance asserted. Three small cycles by Newton's method (Step 2)
# from section speeds near their linear size:

# %%
small_factors = np.array([1.002, 1.005, 1.01])
small = [find_cycle(vs_belt(f * V_hopf), v0) for f, v0 in zip(small_factors, (0.0175, 0.028, 0.04))]
assert all(c.stick_phases == 0 and not c.stable for c in small)
a2 = np.array([((c.x_max[0] - c.x_min[0]) / 2) ** 2 for c in small])
line, parabola = (np.polyval(np.polyfit(a2[: deg + 1], small_factors[: deg + 1] * V_hopf, deg), 0.0) for deg in (1, 2))
assert abs(parabola - V_hopf) <= abs(parabola - line) and abs(parabola / V_hopf - 1) < 1e-7
print(f"V at zero amplitude: line {line:.7f} m/s, parabola {parabola:.7f} m/s; closed form (3) {V_hopf:.7f} m/s "
      f"(the parabola within 1e-7 relative, the line {abs(line / V_hopf - 1):.1e})")

# %% [markdown]
# **The grazing from the cycles.** The same independent way: the slowest
# slip speed of slip-only cycles found by Newton's method at $1.40$, $1.41$ and
# $1.42\,V_H$ (each from the section speed interpolated between the
# continuation's slip-only cycles, which selects the slip-only cycle there),
# extrapolated to 0 by a line through the last two and a parabola through all
# three, meets the continuation's onset within their difference:

# %%
near_factors = np.array([1.40, 1.41, 1.42])
slip_values, slip_sections = np.array([(r.value, r.cycle.section) for r in slip_rows]).T


def slip_only_cycle(f: float) -> Cycle:
    """The slip-only cycle at f V_H by Newton's method from the section speed interpolated on the branch."""
    return find_cycle(vs_belt(f * V_hopf), np.interp(f * V_hopf, slip_values, slip_sections))


near = [slip_only_cycle(f) for f in near_factors]
assert all(c.stick_phases == 0 and not c.stable for c in near)
slowest = np.array([c.min_slip_speed for c in near])
V_line, V_parabola = (np.roots(np.polyfit(near_factors[2 - deg :] * V_hopf, slowest[2 - deg :], deg))[-1].real
                      for deg in (1, 2))
assert abs(V_parabola - onset.value) <= abs(V_parabola - V_line)
print(f"slowest slip speed {', '.join(f'{s:.5f}' for s in slowest)} m/s at "
      f"{', '.join(f'{f:.2f}' for f in near_factors)} V_H: zero at {V_parabola:.5f} m/s (line {V_line:.5f} m/s); "
      f"the continuation's onset {onset.value:.5f} m/s")

# %% [markdown]
# Long runs, by `event-driven` over 8 s, from two starts: $10^{-5}$ m beside
# steady sliding at rest, and stuck on the belt at $x^*$ (moving at $V$). Their
# swing over the last 0.2 s (3.6 periods) is called *rest* below $10^{-7}$ m:

# %%
run_factors = np.array([0.6, 0.8, 1.1, 1.25, 1.4, 1.55])
vs_runs = {}
for f in run_factors:
    V = f * V_hopf
    x_star = float(vs_g(V)) / kv
    vs_runs[f] = [settled_extremes(vs_belt(V, *start), 8.0, 0.2, 1e-5) for start in ((x_star + 1e-5, 0.0), (x_star, V))]
    described = [("rest" if hi - lo < 1e-7 else f"swing {hi - lo:.4e} m") for hi, lo in vs_runs[f]]
    print(f"V = {f:.2f} V_H: from beside steady sliding: {described[0]}; from stuck: {described[1]}")

# %% [markdown]
# Below $V_H$ both starts end on the stick-slip cycle. Between $V_H$ and the
# fold the two motions *coexist*: the start inside the unstable slip-only
# cycle returns to steady sliding, the stuck start stays on the stick-slip
# cycle (it sticks at once and joins it at its first stop). Above the fold both
# come to rest. The stick-slip runs meet the cycles to within the sampling
# every $10^{-5}$ s (below $\omega^2 A h^2/8 = 4\times10^{-10}$ m) and the
# runs' DOP853 error at `rtol` $10^{-10}$:

# %%
for f in run_factors[run_factors * V_hopf < fold.value]:
    c = find_cycle(vs_belt(f * V_hopf), f * V_hopf)
    hi, lo = vs_runs[f][1]
    assert max(abs(hi - c.x_max[0]), abs(lo - c.x_min[0])) < 1e-8
print("stuck starts below the fold: extremes within 1e-8 m of the stick-slip cycles'")
settled = [(f * V_hopf, hi, lo) for f in run_factors for hi, lo in vs_runs[f]]
vs_equilibria, vs_cycles = branches(vs_rows)
fig = P.bifurcation_diagram(
    vs_equilibria,
    {"cycle": vs_cycles},
    tuple(np.array(settled).T),
    {f"Hopf: {hopf_row.value:.4f} m/s": (hopf_row.value, hopf_row.cycle.x_max[0]),
     f"grazing and fold: {onset.value:.4f} m/s": (onset.value, onset.cycle.x_max[0])},
)
_ = P.save_figure(fig, "cy02_bifurcation_stribeck")

# %% [markdown]
# ## Step 4: an analytical approximation, and where it fails
#
# Thomsen and Fidlin (Int. J. Non-Linear Mech. 38 (2003) 389–403) derive
# approximate amplitudes for the belt oscillator with a friction law that
# first falls and then rises with the sliding speed: for pure slip, and for
# stick-slip by a perturbation analysis of the stick phase linked to the slip
# through continuity and periodicity. We could retrieve only their abstract,
# not the text: the cubic form of their law,
# $\mu(v_r) = \mu_s\operatorname{sgn}v_r - k_1 v_r + k_3 v_r^3$, and their
# amplitude expressions could not be checked, so they are **not** quoted or
# used here.
#
# What can be derived and checked is the first-order approximation of the
# *pure-slip* cycles that such analyses start from (Krylov–Bogoliubov
# averaging, our derivation): with the damping small against $\sqrt{km}$, take
# $y = a\cos\theta$, $\dot y = -w\sin\theta$ ($w = a\omega$, $\omega =
# \sqrt{k/m}$); a cycle dissipates in the damper what the contact puts in over
# a period,
#
# $$b_0\,w\,\pi = -\int_0^{2\pi} g(V + w\sin\theta)\sin\theta\,d\theta,$$
#
# and for Veraszto and Stépán's curve the integral is a Bessel function,
# $\int_0^{2\pi}e^{-c_v w\sin\theta}\sin\theta\,d\theta = -2\pi I_1(c_v w)$:
#
# $$(b_0 + b_s)\,w = 2(C_0 - C)\,e^{-c_v V}\,I_1(c_v w). \tag{4}$$
#
# As $w \to 0$, $I_1(z) \approx z/2$ and (4) becomes $c = 0$, the Hopf
# condition (3); since $I_1(z)/z$ grows with $z$, the cycles of (4) lie at
# $V > V_H$: averaging predicts the subcritical branch. Solving (4) for $w$
# (checked against the integral by quadrature), against the computed slip-only
# cycles' speed at the section, where the block is fastest:

# %%
def averaged_w(V: float) -> float:
    """The velocity amplitude w > 0 of (4) at V > V_H (Brent's method between 1e-9 and 1 m/s)."""
    balance = lambda w: (b0 + bs) * w - 2 * (C0 - C) * math.exp(-cv * V) * i1(cv * w)
    return brentq(balance, 1e-9, 1.0, xtol=1e-15)


w_test, V_test = 0.1, 1.2 * V_hopf
integral = quad(lambda th: vs_g(V_test + w_test * math.sin(th)) * math.sin(th), 0, 2 * math.pi, epsabs=1e-13)[0]
assert math.isclose(-integral + bs * w_test * math.pi, 2 * math.pi * (C0 - C) * math.exp(-cv * V_test)
                    * i1(cv * w_test), rel_tol=1e-10)
sections = np.array([r.cycle.section for r in slip_rows])
relative = np.array([averaged_w(r.value) for r in slip_rows]) / sections - 1
at_graze = averaged_w(onset.value) / onset.cycle.section - 1
assert np.all(np.abs(relative) <= abs(at_graze))
print(f"relative difference: growing along the continuation's slip-only cycles to {at_graze:+.1e} at the grazing one")
table_factors = (1.002, 1.1, 1.2, 1.3, 1.4)
table = [slip_only_cycle(f) for f in table_factors]
assert all(c.stick_phases == 0 and not c.stable for c in table)
for f, c in zip(table_factors, table):
    w = averaged_w(f * V_hopf)
    print(f"V = {f:.3f} V_H: averaging w = {w:.5f} m/s, computed {c.section:.5f} m/s "
          f"(relative {w / c.section - 1:+.1e}); amplitude w/omega {w / math.sqrt(kv / mv):.4e} m, "
          f"computed {(c.x_max[0] - c.x_min[0]) / 2:.4e} m")

# %% [markdown]
# Averaging meets the slip-only branch to $2.5\times10^{-5}$ at $1.002\,V_H$
# and drifts to 0.7 % as the cycle grows to the graze. It even places the grazing well: its
# cycle ends where its speed reaches the belt's, $w = V$:

# %%
V_graze_avg = brentq(lambda V: averaged_w(V) - V, 1.01 * V_hopf, 2 * V_hopf)
print(f"averaging's grazing: w = V at {V_graze_avg:.5f} m/s = {V_graze_avg / V_hopf:.4f} V_H; "
      f"computed {onset.value:.5f} m/s ({V_graze_avg / onset.value - 1:+.1%})")

# %% [markdown]
# Where it **fails** is everywhere the contact sticks. Averaging knows no
# stick-slip cycle: below $V_H$ (4) has no root at all (its right-hand side
# exceeds the left for every $w > 0$, since $2I_1(z)/z > 1$), so it predicts
# unbounded growth where the runs settle on a stick-slip cycle of finite swing;
# between $V_H$ and the fold it sees only the unstable cycle, not the stable
# stick-slip one that coexists with steady sliding, whose swing is 1.77 times the
# slip-only cycle's at $1.1\,V_H$; and for Leine's law, with no damper, the
# contact's averaged work is positive at every $w < V$ (as the exact argument
# of Step 3 says: it only feeds energy in), so again it predicts growth and no
# amplitude:

# %%
for f in (0.6, 0.8):
    V = f * V_hopf
    w = np.linspace(1e-6, V, 2001)[1:]
    assert np.all(2 * (C0 - C) * math.exp(-cv * V) * i1(cv * w) > (b0 + bs) * w)  # no root of (4)
    print(f"V = {f} V_H: no cycle from (4); the runs' stick-slip swing {vs_runs[f][1][0] - vs_runs[f][1][1]:.4e} m")
swing_ratio = (vs_runs[1.1][1][0] - vs_runs[1.1][1][1]) / (table[1].x_max[0] - table[1].x_min[0])
print(f"V = 1.1 V_H: stick-slip swing / slip-only cycle's swing = {swing_ratio:.2f}")
w_grid = np.linspace(1e-3, 0.5, 50)
for V in (0.05, 0.5):
    integrand = lambda th, w, V=V: leine_g(V + w * math.sin(th)) * math.sin(th)
    work = [-quad(integrand, 0, 2 * math.pi, args=(w,))[0] for w in w_grid[w_grid < V]]
    assert min(work) > 0
print("Leine: the contact's averaged work per cycle is positive at every w < V for V = 0.05 and 0.5 m/s")

# %% [markdown]
# ## What to take away
#
# * Steady sliding on a belt loses stability where the linearised damping,
#   the viscous terms plus the friction curve's slope, vanishes: at
#   $V_H = 0.19062$ m/s in closed form for Veraszto and Stépán's parameters;
#   never for Leine's law with no damper, whose steady sliding is unstable at
#   every speed.
# * A limit cycle is a fixed point of the return map to $x = x^*$; Newton's
#   method with the map's exact derivative converges in a few steps. A stuck
#   contact makes the saltation matrix singular, so a stick-slip cycle's
#   nontrivial multiplier is exactly 0: it is superstable.
# * For Leine's law the diagram is a superstable stick-slip cycle around an
#   unstable equilibrium at every speed from 0.05 to 0.5 m/s (cy01). For
#   Veraszto and Stépán's, the Hopf point is subcritical: unstable slip-only
#   cycles grow from it (multiplier 1.0234 at $1.02\,V_H$) until they graze the
#   belt's speed at $1.426\,V_H$, where they meet the stick-slip branch in a
#   discontinuous fold; between $V_H$ and the fold, steady sliding and
#   stick-slip coexist (cy02), as the long runs show.
# * First-order averaging gives the slip-only cycles in closed form (a Bessel
#   function), within 0.7 % over the whole branch, but knows nothing of sticking:
#   below the Hopf speed, and for Leine's law, it predicts growth without
#   bound where the motion settles on stick-slip. Thomsen and Fidlin's own
#   expressions could not be checked and are not used.
