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
# # 1. Governing equations: from momentum balance to Algorithm 1
#
# **What you will learn.**
#
# * how Newton's second law for a mass on a spring and a Bingham dashpot
#   becomes a *differential-algebraic* system, eqs. (1) to (8) of Darbha,
#   Nakshatrala and Rajagopal (2020);
# * why the dashpot force cannot be written as a function of the velocity,
#   while the velocity *is* a function of the force, and what this means for
#   the initial conditions;
# * how the backward-Euler discretisation, eqs. (12) to (16), turns one time
#   step into a scalar problem for the dashpot force, and how the corrector
#   of Algorithm 1 (its line 8) follows from it, derived here with SymPy and
#   checked against the `lumped` package, including the Coulomb limit
#   $\gamma \to \infty$.
#
# Every statement below is backed by a printed number or an `assert`.

# %%
# %matplotlib inline
import math

import numpy as np
import sympy as sp

import lumped as L
import lumped.studies.config
import lumped.studies.examples
from lumped.laws import bingham_corrector
import lumped.plotting as P
from lumped.model.oscillator import initial_dashpot_force

cfg = lumped.studies.config.load()
osc = lumped.studies.examples.oscillator(cfg)
m, k, tau, gamma, dt = cfg["mass"], cfg["stiffness"], cfg["threshold"], cfg["gamma"], cfg["dt"]
print(f"m = {m} kg, k = {k} N/m, mu_s N_f = {tau} N, gamma = {gamma} m/(N s), dt = {dt} s")

# %% [markdown]
# ## Step 1: balance of linear momentum
#
# Put the origin at the position of the mass when the spring is unstretched, so
# that the displacement $x(t)$ is also the spring's elongation. Three forces
# act on the mass of Figure 3: the external load $F(t)$, the spring force
# $F_s(t)$ and the dashpot force $F_d(t)$, the last two counted positive when
# they pull the mass back towards negative $x$. Newton's second law reads
#
# $$\ddot x = \frac{1}{m}\bigl(F - F_d - F_s\bigr), \tag{1}$$
#
# or, with the velocity $v$ as a second unknown, the first-order pair
#
# $$\dot v = \frac{1}{m}\bigl(F - F_d - F_s\bigr), \qquad \dot x = v. \tag{2a, 2b}$$
#
# Nothing yet says what $F_s$ and $F_d$ are. The usual move is to write each
# as a function of a kinematic quantity ($F_s = kx$, $F_d = c\,v$) and
# substitute, which gives an ODE. The paper instead allows each element to be
# described by an *implicit* relation between its force and its kinematics,
#
# $$0 = \alpha\bigl(x, F_s\bigr), \qquad 0 = \beta\bigl(v, F_d\bigr), \tag{3a, 3b}$$
#
# so that the unknowns are $x, v, F_s, F_d$ and the governing equations are the
# two ODEs (2) together with the two algebraic relations (3): this is
# system (4).

# %% [markdown]
# ## Step 2: the spring and the Bingham dashpot
#
# The spring is linear, $x = F_s/k$ (5). The dashpot holds a Bingham fluid: it
# does not move until the force on it exceeds the threshold $\mu_s N_f$, and
# beyond it the velocity grows linearly with slope $\gamma$:
#
# $$v = \begin{cases} 0, & |F_d| \le \mu_s N_f,\\
#   \gamma\bigl(F_d - \operatorname{sgn}(F_d)\,\mu_s N_f\bigr), & |F_d| > \mu_s N_f. \end{cases} \tag{6}$$
#
# Outside the band the velocity has the sign of the force and its size is
# $\gamma$ times the excess of $|F_d|$ over the threshold, (7a) and (7b).
#
# Read (6) from left to right and every force gives exactly one velocity: $v$
# *is* a function of $F_d$. Read it from right to left at $v = 0$ and a whole
# interval of forces answers: $F_d$ is *not* a function of $v$. The law below
# samples the graph and asks it for the forces compatible with a velocity.

# %%
law = osc.dashpot
forces = np.linspace(-tau, tau, 2001)  # the whole static band
assert np.all(law.velocity(forces) == 0.0)  # one velocity, v = 0, for all of them
print("forces compatible with v = 0     :", law.force_interval(0.0))
print("forces compatible with v = 0.5   :", law.force_interval(0.5))
print("velocity of F_d = 1.5, -0.3, -2.0:", law.velocity(np.array([1.5, -0.3, -2.0])) + 0.0)

# %% [markdown]
# So the inverse graph is an interval at $v = 0$ and a single point
# elsewhere, where it is the slip force
# $F_d = \operatorname{sgn}(v)\,\mu_s N_f + v/\gamma$ of (7). The figure is
# the paper's Figure 1, drawn both ways: (a)
# the force against the velocity, a relation with a vertical segment at
# $v = 0$, and (b) the velocity as a function of the force, with a flat piece.

# %%
fig = P.bingham_pair(law)

# %% [markdown]
# ## Step 3: a semi-explicit DAE
#
# Eliminating $x$ with (5) leaves the spring force as the second
# differential variable:
#
# $$\dot v = \frac{1}{m}\bigl(F - F_s - F_d\bigr), \qquad \dot F_s = k\,v, \qquad
#   0 = \beta\bigl(v, F_d\bigr). \tag{8a, 8b, 8c}$$
#
# Two equations are ODEs for $(v, F_s)$; the third constrains the *algebraic*
# unknown $F_d$, which has no derivative anywhere. This is a semi-explicit DAE.
# Its character changes with the branch of (6):
#
# * while slipping, (8c) can be solved for $F_d$ (it is the slip force (7)), and
#   (8) is an ODE in disguise;
# * while sticking, (8c) says only $v = 0$ and does not contain $F_d$ at all.
#   The force is then fixed by asking the constraint to *keep* holding:
#   $\dot v = 0$ in (8a) gives $F_d = F - F_s$. The force is whatever the
#   rest of the system needs, provided it stays in the band.
#
# That hidden condition is exactly what an ODE with a prescribed $F_d(v)$
# cannot express; notebook 2 shows what goes wrong when one tries.

# %% [markdown]
# ## Step 4: consistent initial conditions
#
# Initial values must satisfy the algebraic relations, not only the ODEs: given
# $x_0$ and $v_0$, the spring force is $F_s(0) = k x_0$ by (5) and $F_d(0)$ must
# lie on the graph (6) above $v_0$. For a moving mass that fixes $F_d(0)$
# uniquely (the slip force); for a mass at rest any value in the band is
# consistent with (6). The paper's examples take $F_d(0) = 0$. The package
# picks the one value of the band that also makes $\dot v(0) = 0$, namely
# $F(0) - k x_0$, when it lies in the band (and the band edge the mass is
# pushed towards otherwise). Both are consistent; they differ only at $t = 0$,
# since the first step of Algorithm 1 does not use $F_d(0)$.

# %%
def on_graph(v, fd):
    """(v, F_d) satisfies (6); for gamma = inf a slipping F_d is the band edge sgn(v) mu_s N_f."""
    if math.isinf(gamma) and v != 0:
        return fd == math.copysign(tau, v)  # the slip branch is vertical: v is not phi(F_d)
    return math.isclose(law.velocity(fd), v, abs_tol=1e-15)


for x0, v0 in [(0.005, 0.0), (0.5, 0.0), (0.0, 0.3)]:
    fd0 = initial_dashpot_force(osc, 0.0, x0, v0)
    assert on_graph(v0, fd0)  # (5) and (6) hold at t = 0
    print(f"x0 = {x0:5.3f} m, v0 = {v0:3.1f} m/s:  F_s(0) = {k * x0:5.2f} N, "
          f"F_d(0) = {fd0:+.3f} N, band of (6) = {law.force_interval(v0)}")

# %% [markdown]
# For $x_0 = 0.005$ m the mass can rest with the dashpot carrying $-k x_0 =
# -0.5$ N; for $x_0 = 0.5$ m the spring pulls with 50 N, far above the
# threshold, so the mass must start moving even though any $|F_d(0)| \le 1$ N
# is formally consistent at $t = 0$.

# %% [markdown]
# ## Step 5: backward Euler, eqs. (12) to (15)
#
# On the grid $t_n = n\,\Delta t$ write $z^{(n)} \approx z(t_n)$ (12) and
# evaluate every term of (8) at the *new* level $t_{n+1}$:
#
# $$\frac{v^{(n+1)} - v^{(n)}}{\Delta t} = \frac{1}{m}\bigl(F^{(n+1)} - F_s^{(n+1)} - F_d^{(n+1)}\bigr),
# \qquad \frac{F_s^{(n+1)} - F_s^{(n)}}{\Delta t} = k\,v^{(n+1)},
# \qquad 0 = \beta\bigl(v^{(n+1)}, F_d^{(n+1)}\bigr). \tag{13a, 13b, 13c}$$
#
# The second line gives the new spring force from the new velocity (14).
# Substituting it into the first leaves one linear relation between the two
# unknowns $v^{(n+1)}$ and $F_d^{(n+1)}$, (15a), in which all known quantities
# are gathered into the *predictor* $\tilde F^{(n+1)}$ (15b). SymPy does the
# algebra:

# %%
m_, k_, dt_, g_, tau_ = sp.symbols("m k Delta_t gamma mu_sN_f", positive=True)
v0_, v1_, F1_, Fs0_, Fd1_, s_ = sp.symbols("v_n v_n1 F_n1 F_sn F_dn1 s", real=True)
Fs1 = Fs0_ + dt_ * k_ * v1_  # eq. (14)
eq13a = sp.Eq((v1_ - v0_) / dt_, (F1_ - Fs1 - Fd1_) / m_)
Ftilde = m_ / dt_ * v0_ + F1_ - Fs0_  # eq. (15b)
lhs_15a, rhs_15a = (1 + dt_**2 * k_ / m_) * v1_, dt_ / m_ * (Ftilde - Fd1_)
assert sp.simplify((eq13a.lhs - eq13a.rhs) * dt_ - (lhs_15a - rhs_15a)) == 0
print("(15a):", sp.Eq(lhs_15a, rhs_15a))

# %% [markdown]
# The coefficient $1 + \Delta t^2 k/m$ of $v^{(n+1)}$ and the factor
# $\Delta t/m$ are both positive, so (15a) says $v^{(n+1)}$ has the sign of
# $\tilde F^{(n+1)} - F_d^{(n+1)}$. Combined with (7a), $\operatorname{sgn} v =
# \operatorname{sgn} F_d$ in slip, this forces
#
# $$\operatorname{sgn}\tilde F^{(n+1)} = \operatorname{sgn} F_d^{(n+1)}, \tag{16}$$
#
# and in stick ($v^{(n+1)} = 0$) (15a) gives $F_d^{(n+1)} = \tilde F^{(n+1)}$
# outright. The gain is that $\tilde F^{(n+1)}$ is known before the step: it
# tells us on which branch of (6) the new state lies, and in which direction.
# We check (16) on a full run in Step 8.

# %% [markdown]
# ## Step 6: the corrector of line 8, derived
#
# *Stick.* If $|\tilde F^{(n+1)}| \le \mu_s N_f$, the pair $v^{(n+1)} = 0$,
# $F_d^{(n+1)} = \tilde F^{(n+1)}$ satisfies both (15a) and the stick branch of
# (6): lines 5 and 6 of Algorithm 1.
#
# *Slip.* Otherwise put the slip branch of (6),
# $v^{(n+1)} = \gamma(F_d^{(n+1)} - s\,\mu_s N_f)$ with
# $s = \operatorname{sgn}\tilde F^{(n+1)}$ from (16), into (15a) and solve the
# linear equation for $F_d^{(n+1)}$:

# %%
Ft_ = sp.Symbol("Ftilde", real=True)
a, b = 1 + dt_**2 * k_ / m_, dt_ / m_
slip_15a = sp.Eq(a * g_ * (Fd1_ - s_ * tau_), b * (Ft_ - Fd1_))  # (15a) with v from (6)
Fd_derived = sp.solve(slip_15a, Fd1_)[0]
Fd_line8 = (g_ * a * s_ * tau_ + b * Ft_) / (g_ * a + b)  # Algorithm 1, line 8 as published
assert sp.simplify(Fd_derived - Fd_line8) == 0
print("F_d =", sp.simplify(Fd_derived))

# %% [markdown]
# The derivation reproduces the published line 8. The package writes the same
# corrector differently (see `lumped.laws.bingham_corrector`): dividing
# numerator and denominator by $\gamma\,\Delta t/m$ and naming
#
# $$\eta = \frac{m}{\Delta t} + k\,\Delta t, \qquad c = \frac{1}{\gamma},$$
#
# it becomes $F_d^{(n+1)} = (\eta\, s\,\mu_s N_f + c\,\tilde F^{(n+1)})/(\eta + c)$,
# and line 9, $v^{(n+1)} = \gamma(F_d^{(n+1)} - s\,\mu_s N_f)$, becomes
# $v^{(n+1)} = (\tilde F^{(n+1)} - s\,\mu_s N_f)/(\eta + c)$. Symbolically:

# %%
eta_, c_ = m_ / dt_ + k_ * dt_, 1 / g_
Fd_package = (eta_ * s_ * tau_ + c_ * Ft_) / (eta_ + c_)
v_line9 = g_ * (Fd_line8 - s_ * tau_)
v_package = (Ft_ - s_ * tau_) / (eta_ + c_)
assert sp.simplify(Fd_package - Fd_line8) == 0
assert sp.simplify(v_package - v_line9) == 0
print("divided-through F_d - line 8 :", sp.simplify(Fd_package - Fd_line8))
print("divided-through v   - line 9 :", sp.simplify(v_package - v_line9))

# %% [markdown]
# ### The Coulomb limit $\gamma \to \infty$
#
# Remark 2.1 of the paper notes that the Bingham graph looks like Coulomb
# friction as $\gamma \to \infty$ (a vertical slip branch). Line 8 has a finite
# limit there, $F_d \to s\,\mu_s N_f$, and so does line 9 (SymPy below), but the
# published *form* cannot be evaluated at $\gamma = \infty$: numerator and
# denominator both become infinite. With $c = 1/\gamma = 0$ the divided-through
# form is an ordinary quotient.

# %%
print("limit of line 8 :", sp.simplify(sp.limit(Fd_line8, g_, sp.oo)))
print("limit of line 9 :", sp.simplify(sp.limit(v_line9, g_, sp.oo)))
assert sp.simplify(sp.limit(Fd_line8, g_, sp.oo) - s_ * tau_) == 0


def line8_published(Ft, gam, eta=m / dt + k * dt):
    """Lines 8 and 9 exactly as printed (a = eta * dt/m, b = dt/m)."""
    a_, b_, s = eta * dt / m, dt / m, math.copysign(1.0, Ft)
    fd = (gam * a_ * s * tau + b_ * Ft) / (gam * a_ + b_)
    return fd, gam * (fd - s * tau)


with np.errstate(invalid="ignore"):
    print("published form, gamma = inf :", [float(z) for z in line8_published(-50.0, np.inf)])
print("bingham_corrector, c = 0    :", bingham_corrector(-50.0, m / dt + k * dt, tau, 0.0))

# %% [markdown]
# The published form yields `nan` for both the force and the velocity
# ($\infty/\infty$, then $\infty \cdot 0$); the package's form returns the
# Coulomb answer, $F_d = -\mu_s N_f$ and a finite velocity. For finite
# $\gamma$ the two forms agree to rounding, over predictors on both sides of
# the band and slopes from very viscous to nearly Coulomb:

# %%
rng = np.random.default_rng(0)
predictors = rng.uniform(-100, 100, 2000)
predictors = predictors[np.abs(predictors) > tau]  # slip steps only
for gam in (1e-3, 1.0, 1e3, 1e8):
    pub = np.array([line8_published(Ft, gam) for Ft in predictors])
    pkg = np.array([bingham_corrector(Ft, m / dt + k * dt, tau, 1 / gam) for Ft in predictors])
    rel = np.abs(pub - pkg) / np.abs(pkg)  # columns: F_d, v
    assert rel[:, 0].max() < 1e-13
    print(f"gamma = {gam:7.0e}: largest relative difference  F_d {rel[:, 0].max():.0e}, "
          f"v {rel[:, 1].max():.0e}")

# %% [markdown]
# The forces agree to an ulp or two. The velocities of line 9 lose digits in
# proportion to $\gamma$ (relative differences from $10^{-14}$ at
# $\gamma = 10^{-3}$ to $10^{-3}$ at $\gamma = 10^{8}$): line 9 multiplies the small difference
# $F_d - s\,\mu_s N_f \approx (\tilde F - s\,\mu_s N_f)/(\gamma \eta)$, whose
# absolute rounding error is that of $F_d$ itself, by $\gamma$; its relative
# error therefore grows in proportion to $\gamma$. That cancellation is the
# second reason the package evaluates the velocity as
# $(\tilde F - s\,\mu_s N_f)/(\eta + c)$.

# %% [markdown]
# ## Step 7: Algorithm 1, one step by hand
#
# Here is the whole algorithm for one step, written out as the paper lists it
# (lines 3 to 11, in the divided-through form of line 8):

# %%
def algorithm1_step(v_n, Fs_n, F_n1, m=m, k=k, dt=dt, tau=tau, c=1.0 / gamma):
    Ft = m / dt * v_n + F_n1 - Fs_n  # line 3, eq. (15b)
    if abs(Ft) <= tau:  # lines 5-6: stick
        v, Fd = 0.0, Ft
    else:  # lines 8-9
        eta, s = m / dt + k * dt, math.copysign(1.0, Ft)
        Fd = (eta * s * tau + c * Ft) / (eta + c)
        v = (Ft - s * tau) / (eta + c)
    Fs = Fs_n + dt * k * v  # line 11, eq. (14)
    return {"x": Fs / k, "v": v, "F_s": Fs, "F_d": Fd, "F~": Ft}


# %% [markdown]
# Compare it with the first step of `L.backward_euler` from rest at
# $x_0 = 0.5$ m (slip, $\tilde F = -50$ N) and at $x_0 = 0.005$ m (stick,
# $\tilde F = -0.5$ N). The hand step and the package's step perform the same
# floating-point operations, so they must agree to the last bit.

# %%
for x0 in (0.5, 0.005):
    hand = algorithm1_step(0.0, k * x0, 0.0)
    run = L.backward_euler(osc, dt, dt, x0=x0)
    pkg = {name: getattr(run, name)[1] for name in ("x", "v", "F_s", "F_d")}
    assert all(hand[name] == pkg[name] for name in pkg)
    print(f"x0 = {x0}:  F~ = {hand['F~']:+.4f} N, F_d = {hand['F_d']:+.10f} N, "
          f"v = {hand['v']:+.10e} m/s, x = {hand['x']:.10f} m  (package: identical)")

# %% [markdown]
# With $\mu_s N_f = 1$ N and $\tilde F = -50$ N, lines 8 and 9 give for the
# slip step $F_d = -(\eta + 50\,c)/(\eta + c)$ and $v = -49/(\eta + c)$. The
# implicit step's $\eta = m/\Delta t + k\,\Delta t$ is large (about
# $m/\Delta t$), so in one step the mass picks up only a small velocity and the
# force lies just beyond the threshold (exactly on it for $c = 0$):

# %%
eta, c = m / dt + k * dt, 1.0 / gamma
print(f"eta = {eta:.8g} kg/s, c = {c:g} N s/m:  -(eta + 50 c)/(eta + c) = "
      f"{-(eta + 50 * c) / (eta + c):+.10f} N, -49/(eta + c) = {-49 / (eta + c):+.10e} m/s")

# %% [markdown]
# Both agree with the hand step above. For the stick step the mass stays put
# and the dashpot carries exactly the spring's pull, $-k x_0 = -0.5$ N.

# %% [markdown]
# ## Step 8: eq. (16) and the stick condition on a full run
#
# Take the paper's forced run of eq. (17b), the one of its Figures 6 to 9
# (`lumped.studies.examples.paper()["forced_large"]`): from rest at $x = 0$, pushed by
# $F(t) = P \sin(5\pi t)$ until the force is switched off. Run Algorithm 1 and
# rebuild, from the stored trajectory, the predictor (15b) of every step.

# %%
forced = lumped.studies.examples.paper(cfg)["forced_large"]
run = forced.algorithm1()
Ft = m / dt * run.v[:-1] + run.F[1:] - run.F_s[:-1]  # eq. (15b) for steps 1..N
Fd, v = run.F_d[1:], run.v[1:]
stick = v == 0.0
print(f"P = {forced.force.amplitude} N until t = {forced.force.until} s, t_end = {forced.t_end} s, "
      f"dt = {forced.dt} s: {Ft.size} steps, {(~stick).sum()} slip, {stick.sum()} stick")

# %% [markdown]
# First check, eq. (16): the predictor has the sign of the new dashpot force,
# at every step, slip or stick.

# %%
assert np.array_equal(np.sign(Ft), np.sign(Fd))  # eq. (16), every step
print(f"sgn(F~) == sgn(F_d) at {np.sum(np.sign(Ft) == np.sign(Fd))} of {Ft.size} steps")

# %% [markdown]
# Second check, the hidden condition of Step 3: while the mass is *held* at
# rest ($v = 0$ before and after the step) the dashpot carries $F - F_s$,
# exactly. On a step where the mass *arrives* at rest, $v^{(n)} \ne 0 =
# v^{(n+1)}$, the stick force is $\tilde F = F - F_s + m v^{(n)}/\Delta t$
# instead: the extra term is the discrete impulse that stops the mass, so
# those steps are counted apart.

# %%
held = stick & (run.v[:-1] == 0.0)  # at rest before and after the step
arrive = stick & ~held
assert np.array_equal(Fd[held], (run.F - run.F_s)[1:][held])  # stick: F_d = F - F_s
extra, impulse = (Fd - (run.F - run.F_s)[1:])[arrive], (m / dt * run.v[:-1])[arrive]
print(f"held at rest: {held.sum()} steps, F_d == F - F_s at all of them")
print(f"arrivals at rest: {arrive.sum()} steps, F_d - (F - F_s) =",
      np.array2string(extra, precision=4), "N, m v(n)/dt =", np.array2string(impulse, precision=4), "N")

# %% [markdown]
# Third check: (15a), the equation both branches solve, holds to rounding.

# %%
residual = (1 + dt**2 * k / m) * v - dt / m * (Ft - Fd)  # eq. (15a)
print(f"largest |residual of (15a)|: {np.abs(residual).max():.1e} m/s")

# %% [markdown]
# Fourth check: every stick force lies in the band of (6), so each stick step
# is consistent with the graph of the dashpot.

# %%
assert np.all(np.abs(Fd[stick]) <= tau)
print(f"largest |F_d| in stick: {np.abs(Fd[stick]).max(initial=0.0):.4f} N  (<= mu_s N_f = {tau} N)")

# %% [markdown]
# ## What to take away
#
# * For a Bingham dashpot the velocity is a function of the force, eq. (6), but
#   at rest a whole interval of forces, here $[-1, 1]$ N, is compatible with
#   $v = 0$. The dashpot force is therefore an unknown of the problem, and the
#   equations of motion form the semi-explicit DAE (8).
# * Consistent initial data satisfy (5) and (6); at rest $F_d(0)$ may be any
#   value in the band, and it is the dynamics that selects the force, as
#   $F - F_s$ while the mass sticks.
# * One backward-Euler step reduces to (15a); since the predictor $\tilde F$
#   has the sign of the new dashpot force, eq. (16), which held at every step
#   of the forced run in Step 8, it decides between stick and slip before the
#   step.
# * Line 8 of Algorithm 1 is the solution of (15a) on the slip branch. Divided
#   through by $\gamma$ it agrees with the published form to an ulp or two and,
#   unlike it, stays finite in the Coulomb limit $\gamma = \infty$.
#
# Notebook 2 shows what happens to the same mass when the dashpot force is
# instead prescribed from the velocity, as in the textbook treatment.
