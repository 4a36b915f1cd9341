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
# # 5. Free vibrations: Figures 10 to 14 (section 3.2)
#
# **What you will learn.** What the Bingham oscillator does when it is released
# from rest with the spring stretched and no external force: a small stretch
# ($x_0 = 0.005$ m) never moves the mass, a large one ($x_0 = 0.5$ m) makes it
# swing with shrinking amplitude until it sticks, and it sticks *away* from the
# unstretched position. That last fact means the rest state is not found by
# minimising the stored energy. Algorithm 1 is compared with the exact
# solution throughout, and the numbers behind each statement are printed.

# %%
import lumped.studies.config
import lumped.studies.examples
import lumped.plotting as P
import numpy as np

cfg = lumped.studies.config.load()
runs = lumped.studies.examples.paper(cfg)  # the paper's four runs; here the two free ones
osc, dt = runs["free_large"].oscillator, runs["free_large"].dt
k, tau, band = osc.stiffness, osc.threshold, osc.static_band
print(f"m = {osc.mass:.3f} kg, k = {k:.3f} N/m, mu_s N_f = {tau:.3f} N, "
      f"gamma = {cfg['gamma']:.3f}, dt = {dt:.1e} s")
print(f"static band: the unforced mass can rest wherever |x| <= mu_s N_f / k = {band:.4f} m")

# %% [markdown]
# ## A stretch inside the static band (Figure 10)
#
# With $x_0 = 0.005$ m the spring pulls with $kx_0 = 0.5$ N, less than the
# threshold. The first predictor of Algorithm 1 is $\tilde F = -kx_0$, inside the
# band, so the step sticks and sets $F_d = -kx_0$; nothing changes afterwards.
# This is the case a model with $\operatorname{sgn}(0) = 0$ cannot describe: it
# would leave the spring force unbalanced.

# %%
run = runs["free_small"]
small, small_exact, x0 = run.algorithm1(), run.exact(), run.x0
print(f"x0 = {x0:.4f} m, F_s(0) = k x0 = {k * x0:.4f} N, inside the static band: {abs(x0) <= band}")
print(f"max |x - x0| = {np.abs(small.x - x0).max():.3e} m, max |v| = {np.abs(small.v).max():.3e} m/s")
print(f"max |F_d + k x0| = {np.abs(small.F_d + k * x0).max():.3e} N")

# %% [markdown]
# The exact solver records a single event for this run, a *rest* at $t = 0$:
# the mass starts at rest with the net force inside the band and no external
# force ever acts, so it is at rest for ever from the start.

# %%
print("exact events:", [(e.kind, e.time) for e in small_exact.events])
print(f"exact: rest from t = {small_exact.rest_time:.4f} s at x = {small_exact.rest_position:.6f} m")
fig = P.time_history_panels(small, small_exact)
_ = P.save_figure(fig, "fig10_free_small")

# %% [markdown]
# ## A stretch far outside the band (Figures 11 to 14)
#
# With $x_0 = 0.5$ m the spring force (50 N) is far above the threshold, so the
# mass slips at once. In each slip phase it obeys
# $m\ddot x + \dot x/\gamma + kx = -\operatorname{sgn}(v)\,\mu_s N_f$, a damped
# oscillator about the shifted centre $-\operatorname{sgn}(v)\,\mu_s N_f/k$.
# When the velocity reaches zero the exact solver compares the spring force with
# the threshold: above it the mass turns round (a *reversal*), at or below it
# the mass sticks (a *stop*). Without an external force a stop is final, so
# the solver also lists it as the *rest*, the time from which the mass stays
# at rest for ever: `stop` and `rest` appear at the same time.

# %%
run = runs["free_large"]
large, exact, x0, t_end = run.algorithm1(), run.exact(), run.x0, run.t_end
for e in exact.events:
    print(f"  {e.kind:<9s} t = {e.time:.5f} s   x = {e.x[0]:+.6f} m   |kx| = {abs(k * e.x[0]):.4f} N")

# %% [markdown]
# ### Counting stick and slip phases
#
# The exact solution has one slip phase per half-swing and at most one stick
# phase, the final one. Algorithm 1 also has isolated grid points with
# $v = 0$. One is $t = 0$, the initial condition $v_0 = 0$ (the first step
# already slips). Any other sits next to a reversal: there the predictor
# $\tilde F = m v^{(n)}/\Delta t - F_s^{(n)}$ adds the momentum of the last
# step to the spring force, which pull in opposite directions just before the
# turning point; when they nearly cancel, $|\tilde F| \le \mu_s N_f$ and that
# one step sticks, and the next slips back.

# %%
slips = [p for p in exact.phases if p.kind == "slip"]
sticks = exact.stick_intervals()
print(f"exact: {len(slips)} slip phases, {len(sticks)} stick phase(s): "
      + (", ".join(f"[{a:.5f}, {b:.5f}] s" for a, b in sticks) or "none"))
single = [a for a, b in large.stick_intervals() if a == b]
print(f"Algorithm 1: {len(large.stick_intervals())} runs of v == 0, {len(single)} of one grid "
      "point, at t =", ", ".join(f"{t:.4f}" for t in single), "s")

# %%
reversals = exact.event_times("reversal")
for t in [t for t in single if t > 0]:  # t = 0 is the initial condition
    n = int(round(t / dt))  # the grid point; F~ is the predictor of the step that reached it
    Ft = osc.mass / dt * large.v[n - 1] - large.F_s[n - 1]  # eq. (15b) with F = 0
    print(f"  t = {t:.4f} s: F~ = {Ft:+.4f} N (band {tau} N), "
          f"nearest exact reversal {np.abs(reversals - t).min() / dt:.1f} steps away")

# %% [markdown]
# ### Where and when the mass stops
#
# The final stick begins when the velocity vanishes with $|kx| \le \mu_s N_f$.
# The spring is then still stretched: the dashpot holds a force $F_d = -kx$ inside
# its band. The energy stored in the spring there is not zero, so the state of
# least energy ($x = 0$) is *not* where the motion ends. (If the mass is still
# moving at $t_{\text{end}}$, the rest time and position print as `nan`.)

# %%
print(f"rest time:     Algorithm 1 {large.rest_time:.4f} s, exact {exact.rest_time:.5f} s")
print(f"rest position: Algorithm 1 {large.rest_position:.6f} m, exact {exact.rest_position:.6f} m")
print(f"spring force at rest: exact {k * exact.rest_position:.4f} N (band {tau:.4f} N)")
print(f"stored energy: initial {0.5 * k * x0**2:.4f} J, at rest {0.5 * k * exact.rest_position**2:.3e} J")

# %% [markdown]
# Deviation from the exact solution at the grid points, over the whole run and
# away from switches (more than five steps from every event, both solutions
# moving the same way), as in the previous notebook.

# %%
ex = exact.sample(dt)
event_t = np.array([e.time for e in exact.events])
far = np.abs(large.t[:, None] - event_t[None, :]).min(axis=1) > 5 * dt
far &= np.sign(large.v) == np.sign(ex.v)
for c in ("x", "v", "F_s", "F_d"):
    d = np.abs(getattr(large, c) - getattr(ex, c))
    print(f"max |{c:<3s} - exact|: all points {d.max():.3e}, away from switches {d[far].max():.3e}")

# %% [markdown]
# ### Displacement (Figure 11)
#
# Each half-swing starts at rest at a distance $|x|$ from $x = 0$, that is
# $|x| - \mu_s N_f/k$ from the centre of its slip phase, and ends half a damped
# period later at $r\,(|x| - \mu_s N_f/k)$ on the other side of the centre,
# where $r = \exp(-\pi\zeta/\sqrt{1 - \zeta^2})$ and
# $\zeta = 1/(2\gamma\sqrt{mk})$ is the damping ratio of the slip phase. The
# amplitude therefore shrinks by two parts in every half-swing: the
# *threshold* (Coulomb-like) loss $(1 + r)\,\mu_s N_f/k$, the same in every
# half-swing, and the *viscous* loss $(1 - r)\,|x|$, proportional to the
# amplitude. The viscous part is the larger of the two while $|x|$ exceeds
# $\frac{1 + r}{1 - r}\,\mu_s N_f/k$:

# %%
zeta = osc.dashpot.viscosity / (2 * np.sqrt(osc.mass * k))
r = np.exp(-np.pi * zeta / np.sqrt(1 - zeta**2))  # amplitude ratio about the centre
crossover = (1 + r) / (1 - r) * band if r < 1 else np.inf
print(f"zeta = {zeta:.4f}, r = {r:.4f}: threshold loss {(1 + r) * band:.4f} m per half-swing, "
      f"viscous loss larger while |x| > {crossover:.4f} m")

# %%
fig = P.time_history(large, exact, "x")
_ = P.rest_inset(fig.axes[0], large, exact, band)  # the stretched rest, which the 0.4 m axis hides
_ = P.save_figure(fig, "fig11_free_large_x")
turns = np.abs([e.x[0] for e in exact.events if e.kind == "reversal"])
start = np.r_[abs(x0), turns[:-1]]  # |x| at the start of each half-swing ending in a reversal
loss = start - turns
print("exact turning points |x| (m):", np.array2string(turns, precision=4))
print("loss per half-swing (m):     ", np.array2string(loss, precision=4))
print("  viscous part (1 - r)|x|:   ", np.array2string((1 - r) * start, precision=4))
# the residual is round-off, a few ulps of |x0| = 0.5 m (1.1e-16 m each), so its bound is printed
assert np.abs(loss - (1 - r) * start - (1 + r) * band).max(initial=0.0) < 1e-15
print("  largest |loss - (1 - r)|x| - (1 + r) mu_s N_f/k|: below 1e-15 m (round-off)")

# %% [markdown]
# With the paper's values ($\zeta = 0.05$) the viscous part dominates the first
# half-swings and the loss falls with the amplitude; only below the printed
# crossover does the constant threshold loss take over. A Coulomb dashpot
# ($\gamma = \infty$, so $r = 1$) would lose exactly $2\mu_s N_f/k$ in every
# half-swing.
#
# Algorithm 1 swings a little less far each time than the exact solution: the
# numerical damping of backward Euler. Its turning points are taken at the
# last grid point before each sign change of $v$:

# %%
v, x = large.v[large.v != 0], large.x[large.v != 0]
turns_a1 = np.abs(x[np.flatnonzero(np.sign(v[1:]) != np.sign(v[:-1]))])
print(f"half-swings ending in a reversal: Algorithm 1 {turns_a1.size}, exact {turns.size}")
n = min(turns.size, turns_a1.size)
print("exact - Algorithm 1 at the turning points (m):",
      np.array2string(turns[:n] - turns_a1[:n], precision=5))

# %% [markdown]
# ### Velocity (Figure 12)
#
# Between reversals the exact velocity is one arc of a damped oscillation; it
# passes through zero at each reversal without resting and stays zero from the
# stop on (Algorithm 1 rests for the single grid points counted above). Its
# largest magnitude comes in the first half-swing, before the first reversal,
# and Algorithm 1's peak is slightly below the exact one, again the numerical
# damping.

# %%
fig = P.time_history(large, exact, "v")
_ = P.save_figure(fig, "fig12_free_large_v")
t_peak = ex.t[np.argmax(np.abs(ex.v))]
print(f"peak |v|: Algorithm 1 {np.abs(large.v).max():.5f} m/s, exact {np.abs(ex.v).max():.5f} m/s "
      f"at t = {t_peak:.4f} s (first reversal at {reversals[0]:.4f} s)")

# %% [markdown]
# ### Spring force (Figure 13)
#
# $F_s = kx$, so Figure 13 is Figure 11 scaled by $k$. It starts at $kx_0$, far
# outside the band, and once the mass has stopped it ends inside the band: the
# force the stretched spring keeps exerting on the mass at rest.

# %%
fig = P.time_history(large, exact, "F_s")
_ = P.save_figure(fig, "fig13_free_large_Fs")
print(f"max |F_s - k x| of Algorithm 1: {np.abs(large.F_s - k * large.x).max():.1e} N")
print(f"F_s: initial {large.F_s[0]:.4f} N, final Algorithm 1 {large.F_s[-1]:.4f} N, "
      f"exact {ex.F_s[-1]:.4f} N (band {tau:.4f} N)")

# %% [markdown]
# ### Dashpot force (Figure 14)
#
# While slipping $|F_d| = \mu_s N_f + |v|/\gamma$; at each reversal it jumps
# across the band, and at rest it settles at $-kx$, inside the band.

# %%
fig = P.time_history(large, exact, "F_d")
_ = P.save_figure(fig, "fig14_free_large_Fd")
slip = large.v != 0
slip_law = tau + np.abs(large.v[slip]) * osc.dashpot.viscosity  # mu_s N_f + |v|/gamma
print(f"max ||F_d| - (mu_s N_f + |v|/gamma)| while slipping: "
      f"{np.abs(np.abs(large.F_d[slip]) - slip_law).max():.1e} N")
print(f"F_d at the end: Algorithm 1 {large.F_d[-1]:+.4f} N (-k x = {-k * large.x[-1]:+.4f} N), "
      f"exact {ex.F_d[-1]:+.4f} N")

# %% [markdown]
# ## What to take away
#
# * A stretch inside the static band ($|x_0| \le \mu_s N_f/k$) never moves the
#   mass: the printed deviations of $x$ and $v$ are zero and the dashpot force
#   is exactly $-kx_0$.
# * From a stretch far outside it the mass swings with shrinking amplitude, by
#   a viscous loss proportional to the amplitude plus a constant threshold
#   loss per half-swing, and (with the paper's values) sticks for good with the
#   spring still stretched, held by a dashpot force inside the band. The rest
#   position depends on the history, not on where the stored energy is least.
#   The numbers:

# %%
print(f"{len(slips)} slip phases ({turns.size} reversals); "
      f"rest from t = {exact.rest_time:.4f} s at x = {exact.rest_position:+.6f} m")

# %% [markdown]
# * Backward Euler's numerical damping shrinks every swing of Algorithm 1 a
#   little; the rest position, where the last swing happens to end, inherits
#   the accumulated difference. A ten times coarser step makes the
#   difference larger (about tenfold from the paper's
#   $\Delta t = 10^{-4}$ s), and the rest position can then land on the
#   other side of $x = 0$, as it does with the paper's parameters:

# %%
for h in (dt, 10 * dt):
    a1 = run.algorithm1(dt=h)
    print(f"dt = {h:.0e} s: rest time off by {(a1.rest_time - exact.rest_time) / h:+.1f} steps, "
          f"rest position {a1.rest_position:+.6f} m (exact {exact.rest_position:+.6f} m)")
