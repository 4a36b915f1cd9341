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
# # 3. Constitutive pictures: Figures 1 to 4
#
# **What you will learn.** Why a Bingham dashpot cannot be written as "force =
# function of velocity" while "velocity = function of force" works; how the same
# reversal happens for a spring restrained by an inextensible string; and what
# the mass-spring-dashpot system of the paper looks like. The pictures are the
# paper's Figures 1 to 4; every number quoted in the text is printed below a
# code cell, so that `nbval` checks it.
#
# All parameters come from `config/config.yaml` (or the file named by
# `$LUMPED_CONFIG`, which the Snakemake pipeline sets).

# %%
import lumped as L
import lumped.studies.config
import lumped.studies.examples
import lumped.plotting as P
import numpy as np

cfg = lumped.studies.config.load()
law = L.BinghamDashpot(cfg["threshold"], cfg["gamma"])
print(f"threshold mu_s N_f = {law.threshold:.3f} N, slope gamma = {law.gamma:.3f} m/(N s)")

# %% [markdown]
# ## The Bingham dashpot read both ways (Figure 1)
#
# Eq. (6) gives the velocity from the force: nothing moves while
# $|F_d| \le \mu_s N_f$, and outside that band $|v| = \gamma(|F_d| - \mu_s N_f)$
# with the sign of $F_d$ (eqs. 7a, 7b). Read the other way round, a moving
# dashpot has exactly one force, $F_d = \operatorname{sgn}(v)\,\mu_s N_f + v/\gamma$,
# but a dashpot at rest admits *every* force of the band. The force is a set at
# $v = 0$; the velocity is a single value for every force.

# %%
for v in (-0.5, 0.0, 0.5):
    lo, hi = law.force_interval(v)
    print(f"v = {v:+.2f} m/s  ->  F_d in [{lo:+.3f}, {hi:+.3f}] N")
forces = np.array([-2.0, -1.0, -0.3, 0.0, 0.3, 1.0, 2.0])
print("F_d (N):", np.array2string(forces, precision=2, sign="+"))
print("v (m/s):", np.array2string(law.velocity(forces) + 0.0, precision=2, sign="+"))  # + 0.0: no -0

# %% [markdown]
# Panel (a) draws the force against the velocity, with the vertical segment at
# $v = 0$; panel (b) draws the velocity as a function of the force.

# %%
fig = P.bingham_pair(law)
_ = P.save_figure(fig, "fig01_bingham_relations")

# %% [markdown]
# ## A spring held back by a string (Figure 2)
#
# Put a linear spring of stiffness $k$ in parallel with a slack, inextensible
# string that becomes taut when the displacement reaches $L$. Below $L$ the
# spring alone carries $F = kx$. At $x = L$ the string takes whatever extra
# tension is applied, so every $F \ge kL$ is admissible there and $x$ never
# exceeds $L$. Force as a function of displacement fails at $x = L$; displacement
# as a function of force, $x = \min(F/k, L)$, is defined everywhere. The sketch
# uses $k = L = 1$ (the paper gives no values).

# %%
k_string, length = 1.0, 1.0
for force in (0.5, 1.0, 5.0, 50.0):
    print(f"F = {force:5.1f}  ->  x = {min(force / k_string, length):.3f}")

# %%
fig = P.string_spring_triptych(stiffness=k_string, length=length)
_ = P.save_figure(fig, "fig02_spring_with_string")

# %% [markdown]
# ## The system studied (Figure 3)
#
# A mass $m$ on rollers is tied to a wall by a linear spring (eq. 5) and a
# Bingham dashpot (eq. 6) side by side and driven by an external force $F(t)$.
# Its displacement $x$ is measured from the position where the spring is
# unstretched, and balance of momentum gives eq. (1):
# $m\ddot x = F - F_s - F_d$.

# %%
osc = lumped.studies.examples.oscillator(cfg)
print(f"m = {osc.mass:.3f} kg, k = {osc.stiffness:.3f} N/m")
print(f"largest |x| at which the unforced mass can rest: mu_s N_f / k = {osc.static_band:.4f} m")
fig = P.oscillator_schematic()
_ = P.save_figure(fig, "fig03_mass_spring_dashpot")

# %% [markdown]
# ## The two constants of the Bingham law (Figure 4)
#
# The picture the numerical examples rely on: a flat stretch of width
# $2\mu_s N_f$ on which the dashpot sticks, and two straight branches of slope
# $\gamma$. Letting $\gamma \to \infty$ turns the branches vertical and gives the
# Coulomb graph (Remark 2.1). The slope is measured below through its inverse,
# the rise of the slip force $F_d = \operatorname{sgn}(v)\,\mu_s N_f + v/\gamma$
# per unit velocity, which stays finite (zero) in the Coulomb limit.

# %%
fig = P.bingham_pictorial(law)
_ = P.save_figure(fig, "fig04_bingham_pictorial")
inverse_slope = (law.slip_force(1.0) - law.slip_force(0.5)) / (1.0 - 0.5)
print(f"measured 1/slope outside the band: {inverse_slope:.3f} N s/m (1/gamma = {1 / law.gamma:.3f})")

# %% [markdown]
# ## What to take away
#
# * At $v = 0$ the Bingham dashpot's force is any value in
#   $[-\mu_s N_f, \mu_s N_f]$ (printed above as $[-1, 1]$ N): the force is not a
#   function of the velocity, whereas the velocity is a function of the force.
# * The string-restrained spring has the same structure with force and
#   displacement: $x = \min(F/k, L)$ is single-valued, $F(x)$ is not at $x = L$.
# * In the system of Figure 3 the dashpot force is therefore an *unknown* of the
#   equations of motion, fixed by the algebraic constraint (8c), which makes them
#   a differential-algebraic system; the next two notebooks solve it.
