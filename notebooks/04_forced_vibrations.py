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
# # 4. Forced vibrations: Figures 5 to 9 (section 3.1)
#
# **What you will learn.** How Algorithm 1 (backward Euler with a
# predictor-corrector for the dashpot force) behaves when the mass starts at
# rest and is pushed by $F(t) = P\sin(5\pi t)$ for one second: a weak push
# ($P = 0.5$ N, eq. 17a) never overcomes the dashpot, a strong one
# ($P = 10$ N, eq. 17b) makes the mass slip back and forth and then stop
# with the spring stretched. Every curve is compared with the exact solution,
# built phase by phase from closed-form pieces (`lumped.solve_exact`), and the
# deviations are printed.

# %%
import lumped.studies.config
import lumped.studies.examples
import lumped.plotting as P
import numpy as np

cfg = lumped.studies.config.load()
runs = lumped.studies.examples.paper(cfg)  # the paper's four runs; here the two forced ones
osc, dt, t_end = (runs["forced_large"].oscillator, runs["forced_large"].dt,
                  runs["forced_large"].t_end)
print(f"m = {osc.mass:.3f} kg, k = {osc.stiffness:.3f} N/m, mu_s N_f = {osc.threshold:.3f} N, "
      f"gamma = {cfg['gamma']:.3f}, dt = {dt:.1e} s, t_end = {t_end:.2f} s")

# %% [markdown]
# ## One step of Algorithm 1
#
# The step from $t_n$ to $t_{n+1}$ forms the predictor (15b),
# $\tilde F = \frac{m}{\Delta t}v^{(n)} + F^{(n+1)} - F_s^{(n)}$, which has the sign
# of the unknown $F_d^{(n+1)}$ (eq. 16). If $|\tilde F| \le \mu_s N_f$ the mass
# sticks and $F_d = \tilde F$; otherwise lines 8 and 9 give the slipping force and
# velocity. The spring force follows from (14). `lumped.backward_euler` runs
# this loop (each paper run's `.algorithm1()` calls it); the exact solution
# switches between a *stick* phase ($v = 0$, $F_d = F - kx$, eq. 11c) and
# *slip* phases (a linear ODE solved in closed form).
#
# ## Weak forcing, eq. (17a): the mass never moves (Figure 5)
#
# When the amplitude of the push stays below the threshold, $\max |F_1| <
# \mu_s N_f$ (Remark 3.1; the first line below), the predictor never leaves the
# band, so every step sticks and the dashpot simply balances the applied force:
# eq. (19), $F_d = F_1$, $x = v = F_s = 0$.

# %%
run = runs["forced_small"]
weak, weak_exact = run.algorithm1(), run.exact()
print(f"max |F_1| = {np.abs(weak.F).max():.4f} N  (threshold {osc.threshold:.4f} N)")
dev = {c: np.abs(getattr(weak, c)).max() for c in ("x", "v", "F_s")}
dev["F_d - F_1"] = np.abs(weak.F_d - weak.F).max()
print("largest deviation from eq. (19):", ", ".join(f"{c} {d:.3e}" for c, d in dev.items()))

# %%
print("exact solution's stick intervals (s):", [f"{a:.4f}-{b:.4f}" for a, b in weak_exact.stick_intervals()])
fig = P.time_history_panels(weak, weak_exact, exact_label="exact: eq. (19), stuck throughout")
_ = P.save_figure(fig, "fig05_forced_small")

# %% [markdown]
# ## Strong forcing, eq. (17b)
#
# Now $\max F_2 = P > \mu_s N_f$: the mass breaks away as soon as
# $|F_2(t)| = \mu_s N_f$, i.e. at $t = \arcsin(\mu_s N_f/P)/(5\pi)$, and then
# slips. Each time the velocity returns to zero the exact solver checks the net
# force $F - kx$: outside the band the motion reverses at once, inside it the
# mass stops.

# %%
run = runs["forced_large"]
strong, exact = run.algorithm1(), run.exact()
f = run.force
print(f"P = {f.amplitude} N: predicted breakaway arcsin(mu_s N_f/P)/(5 pi) = "
      f"{np.arcsin(osc.threshold / f.amplitude) / f.omega:.5f} s")
for e in exact.events:
    print(f"  {e.kind:<12s} t = {e.time:.5f} s   x = {e.x[0]:+.6f} m")
kinds = [e.kind for e in exact.events]
n_slip = sum(p.kind == "slip" for p in exact.phases)
print(f"{kinds.count('reversal')} reversals, {kinds.count('stop')} stop(s); "
      f"{n_slip} slip and {len(exact.stick_intervals())} stick phases")

# %% [markdown]
# The solver names five kinds of event. A *breakaway* ends a stick phase (the
# net force leaves the band), a *reversal* ends a slip phase with the net force
# outside the band (the mass turns round) and a *stop* ends one with the net
# force inside it (the mass sticks). A *switch* marks $t = 1$ s, where
# eq. (17) switches $F$ off. A stop is not necessarily final: while $F$ is on,
# the net force $F - kx$ can leave the band again and cause a breakaway. A
# *rest* is the stop that is final: the mass sticks and the force is zero
# from then on, so nothing can move it again. It is dated from the start of
# that stick phase, so a stop after the force is off appears twice, as `stop`
# and as `rest` at the same time:

# %%
for e in exact.events:
    if e.kind in ("stop", "rest"):
        net = f(e.time) - osc.stiffness * e.x[0]
        print(f"  {e.kind:<5s} t = {e.time:.5f} s: force off (t > {f.until} s): "
              f"{e.time > f.until}, |net force| = |F - kx| = {abs(net):.4f} N")
print(f"rest time (from then on at rest for ever): {exact.rest_time:.5f} s")

# %% [markdown]
# The numbers a reader would check: when and where the mass comes to rest
# (`nan` if it is still moving at $t_{\text{end}}$), the largest excursion,
# and how far Algorithm 1 is from the exact solution at the grid points.

# %%
ex = exact.sample(dt)
print(f"rest time:     Algorithm 1 {strong.rest_time:.4f} s, exact {exact.rest_time:.5f} s")
print(f"rest position: Algorithm 1 {strong.rest_position:.6f} m, exact {exact.rest_position:.6f} m")
print(f"peak |x|:      Algorithm 1 {np.abs(strong.x).max():.6f} m, exact {np.abs(ex.x).max():.6f} m")
print(f"peak |v|:      Algorithm 1 {np.abs(strong.v).max():.5f} m/s, exact {np.abs(ex.v).max():.5f} m/s")

# %% [markdown]
# The dashpot force jumps by $2\mu_s N_f$ at every reversal and Algorithm 1
# reverses a few steps off the exact time, so near a reversal the two
# dashpot forces can differ by the whole jump. The deviation is therefore
# also printed *away from switches*: at points more than five steps from every
# exact event where both solutions move in the same direction (or both stick).

# %%
event_t = np.array([e.time for e in exact.events])
far = np.abs(strong.t[:, None] - event_t[None, :]).min(axis=1) > 5 * dt
far &= np.sign(strong.v) == np.sign(ex.v)
diff = {c: np.abs(getattr(strong, c) - getattr(ex, c)) for c in ("x", "v", "F_s", "F_d")}
for c, d in diff.items():
    print(f"max |{c:<3s} - exact|: all points {d.max():.3e}, away from switches {d[far].max():.3e}")

# %% [markdown]
# Away from the switches the dashpot force is not exact either: it inherits
# the error of the state. While slipping,
# $F_d = \operatorname{sgn}(v)\,\mu_s N_f + v/\gamma$ in both solutions, so the
# forces differ by the velocity error over $\gamma$; while sticking at rest, $F_d = F - kx$, so they differ by $k$
# times the error of the rest position.

# %%
slip_far, stick_far = far & (strong.v != 0), far & (strong.v == 0)
dv_over_gamma = diff["v"][slip_far] * osc.dashpot.viscosity
print(f"slipping: max |F_d - exact| {diff['F_d'][slip_far].max(initial=0.0):.3e} N, "
      f"max |v - exact|/gamma {dv_over_gamma.max(initial=0.0):.3e} N")
print(f"sticking: max |F_d - exact| {diff['F_d'][stick_far].max(initial=0.0):.3e} N, "
      f"max k |x - exact| {osc.stiffness * diff['x'][stick_far].max(initial=0.0):.3e} N")

# %% [markdown]
# ### Displacement (Figure 6)
#
# The mass swings about the unstretched position while the force acts, and
# keeps swinging after the force is switched off at $t = 1$ s, each turning
# point closer to $x = 0$ than the last (printed below), until it stops with
# the spring stretched, or is still moving at $t_{\text{end}}$ if the push was
# strong enough.

# %%
fig = P.time_history(strong, exact, "x")
_ = P.save_figure(fig, "fig06_forced_large_x")
after = [e for e in exact.events if e.kind == "reversal" and e.time > f.until]
print(f"|x| at the reversals after t = {f.until} s (m):", [round(abs(e.x[0]), 6) for e in after])
x_end = exact.evaluate(np.array([t_end]))["x"][0]
print(f"at t_end = {t_end} s: x = {x_end:+.6f} m, at rest: {exact.rest_time <= t_end}")

# %% [markdown]
# ### Velocity (Figure 7)
#
# In the exact solution the velocity is exactly zero before the breakaway and
# from the final stop on (if the mass stops before $t_{\text{end}}$), and
# nowhere else: at a reversal it passes through zero without resting.
# Algorithm 1 has the same intervals of $v = 0$, each within a few steps of the
# exact one (printed below); any further run of $v = 0$ it prints is a single
# grid point next to a reversal, where the predictor of one step fell inside
# the band (notebook 5 explains why).

# %%
fig = P.time_history(strong, exact, "v")
_ = P.save_figure(fig, "fig07_forced_large_v")
spans = lambda runs, d: ", ".join(f"[{a:.{d}f}, {b:.{d}f}]" for a, b in runs)  # noqa: E731
print("exact:       v == 0 on", spans(exact.stick_intervals(), 5), "s")
print("Algorithm 1: v == 0 on", spans(strong.stick_intervals(), 4), "s")

# %% [markdown]
# ### Spring force (Figure 8)
#
# $F_s = kx$, so this is Figure 6 scaled by $k$. Once the mass has stopped, its
# final value is the force the stretched spring keeps exerting on the mass at
# rest.

# %%
fig = P.time_history(strong, exact, "F_s")
_ = P.save_figure(fig, "fig08_forced_large_Fs")
print(f"final spring force: Algorithm 1 {strong.F_s[-1]:.4f} N, exact {ex.F_s[-1]:.4f} N")

# %% [markdown]
# ### Dashpot force (Figure 9)
#
# While slipping, $|F_d| \ge \mu_s N_f$ and $F_d$ has the sign of $v$ (eq. 7a);
# at a reversal it jumps from one edge of the band to the other. At rest it
# takes whatever value inside the band balances the spring, $-kx$ once the
# force is off.

# %%
fig = P.time_history(strong, exact, "F_d")
_ = P.save_figure(fig, "fig09_forced_large_Fd")
slip = strong.v != 0
print(f"min |F_d| while slipping: {np.abs(strong.F_d[slip]).min():.4f} N")
print(f"sign(F_d) == sign(v) at every slipping point: {bool(np.all(np.sign(strong.F_d[slip]) == np.sign(strong.v[slip])))}")
print(f"F_d at the end: {strong.F_d[-1]:+.4f} N (-k x = {-strong.F_s[-1]:+.4f} N), "
      f"at rest: {strong.v[-1] == 0}")

# %% [markdown]
# ## What to take away
#
# * Below the threshold (eq. 17a) Algorithm 1 reproduces eq. (19) exactly: the
#   printed deviations are zero, because every step takes the stick branch and
#   the dashpot force equals the applied force.
# * Above it (eq. 17b) the mass breaks away at $\arcsin(\mu_s N_f/P)/(5\pi)$,
#   reverses several times while forced and after, and (with the paper's values)
#   comes to rest with the spring still stretched and the dashpot holding it
#   there. The numbers:

# %%
print(f"breakaway at {exact.event_times('breakaway')[0]:.5f} s; "
      f"{kinds.count('reversal')} reversals, {len(after)} of them after t = {f.until} s")
print(f"rest from t = {exact.rest_time:.4f} s at x = {exact.rest_position:.6f} m")

# %% [markdown]
# * Algorithm 1 follows the exact displacement to the printed maximum
#   deviation and stops within a few steps of the exact rest time. Its dashpot
#   force differs by up to the whole jump $2\mu_s N_f$ at the grid points next
#   to the jumps, and elsewhere by the error of the state it is computed from:
#   $|v - v_{\text{exact}}|/\gamma$ while slipping, $k\,|x - x_{\text{exact}}|$
#   at rest.

# %%
print(f"with dt = {dt:.0e} s: max |x - exact| = {diff['x'].max():.1e} m, "
      f"rest time off by {(strong.rest_time - exact.rest_time) / dt:+.1f} steps")
print(f"max |F_d - exact|: {diff['F_d'].max():.2f} N at all points, "
      f"{diff['F_d'][far].max():.1e} N away from switches")
