"""Fit the equivalent friction coefficient gamma (Eq 7) to synthetic rig data.

The paper measures the friction F(P) on a test rig and fits one coefficient gamma so that
F = gamma N(P), where N(P) is the simulated squeezing force (Eq 1, Eq 7). This script plants
a known gamma, generates rig data with :func:`exofric.simulate_rig` (a virtual rig with sensor
noise on force and pressure and the paper's data reduction), and recovers gamma with its 95 %
confidence interval using :func:`exofric.fit_gamma`. With real data, only the last step
changes: pass the measured pressures and forces instead.

Run it from the repository root::

    python examples/fit_gamma.py             # writes fit_gamma.png here

Units: MPa, N; gamma is unitless.
"""

# %%
# The squeeze curve N(P)
# ----------------------
#
# gamma is fitted against the simulated squeezing force of the same structure, here the base
# group (see ``squeeze_base_group.py``) at 0.05 MPa steps up to 0.6 MPa. ``keep_fields=False``
# drops the displacement and stress fields, which the fit does not need.

import numpy as np

import exofric as ef
from exofric import paper
from exofric.friction import RigConfig

material = ef.MooneyRivlin.from_shore(62.5)
squeeze_pressure_mpa = np.round(np.arange(0.05, 0.601, 0.05), 2)
curve = ef.squeeze(ef.BASE, material, squeeze_pressure_mpa, keep_fields=False)

# %%
# Synthetic rig data with a planted gamma
# ---------------------------------------
#
# The virtual rig pulls the wire at 2 mm/s at each pressure set point after 2 s of settling,
# logs the force at 100 Hz with 2 % proportional noise, and reduces each pull to one friction
# value (mean over the steady sliding window, tared on the settling window), as the paper
# did. The tube pressure follows the set point with a 0.3 s lag, and here its reading also
# carries 0.003 MPa of sensor noise. Three repeated tests at 0.15-0.6 MPa give 30 points.
# The planted value is the paper's gamma = 0.7168. The output is labelled SYNTHETIC wherever
# it is written.

gamma_true = paper.scalar("gamma")
rig_pressures_mpa = np.round(np.arange(0.15, 0.601, 0.05), 2)
rig_config = RigConfig(noise_pct=2.0, pressure_noise_mpa=0.003)
rig = ef.simulate_rig(
    curve.pressure_mpa,
    curve.squeeze_force_n,
    gamma_true,
    rig_pressures_mpa,
    config=rig_config,
    seed=1,
    repeats=3,
)

# %%
# The Eq 7 least-squares fit
# --------------------------
#
# ``fit_gamma`` interpolates N(P) at each measured pressure and minimises
# sum (gamma N_i - F_i)^2, which has the closed form gamma = sum N_i F_i / sum N_i^2. The 95 %
# interval is a t interval with a heteroscedasticity-robust (HC3) standard error, since the
# rig's noise grows with the force. ``relative_error_pct`` is the mean absolute relative
# error, the reading of the paper's "relative error of 10.68 %" argued in docs/paper-notes.md
# (F3); it is small here because synthetic data follow the model exactly apart from noise.

fit = ef.fit_gamma(rig.pressure_mpa, rig.friction_n, curve.pressure_mpa, curve.squeeze_force_n)
gamma_fit = fit.gamma
gamma_ci95 = fit.gamma_ci95
relative_error_pct = fit.relative_error_pct

# %%
# An affine alternative
# ---------------------
#
# A rig with a constant drag (seal, pulley) adds an offset F0: ``model="affine"`` fits
# F = gamma N + F0 and reports F0 with its own interval. On these data F0 is compatible with 0.

affine = ef.fit_gamma(rig.pressure_mpa, rig.friction_n, curve.pressure_mpa,
                      curve.squeeze_force_n, model="affine")
f0_n = affine.model.f0_n
f0_ci95_n = affine.f0_ci95_n or (float("nan"), float("nan"))

print(f"planted gamma: {gamma_true:.4f}")
print(f"fitted gamma:  {gamma_fit:.5f}, 95 % CI [{gamma_ci95[0]:.5f}, {gamma_ci95[1]:.5f}] "
      f"({fit.n_points} points)")
print(f"mean |relative error|: {relative_error_pct:.2f} %")
print(f"affine fit: gamma {affine.gamma:.5f}, F0 = {f0_n:+.3f} N, 95 % CI "
      f"[{f0_ci95_n[0]:+.3f}, {f0_ci95_n[1]:+.3f}] N")

# %%
# Figure
# ------
#
# ``exofric.plots.plot_gamma_fit`` shows the data with the fitted line, the residuals in N and
# the relative errors in %.

if __name__ == "__main__":
    from exofric.plots import plot_gamma_fit, save

    fig = plot_gamma_fit(fit, f"SYNTHETIC rig data, planted gamma = {gamma_true:g}")
    print("wrote", save(fig, "fit_gamma.png"))
