"""Calibrate the pull-out friction coefficients from measured force-displacement curves.

A pull of the wire through the inflated tube, logged with its displacement, is a curve F(x):
the force rises while the wire sticks to the tube, then levels off when the whole length
slides. The plateau is L (mu_wire S_wire + mu_wire_wall N), and since S_wire / N hardly changes
with pressure, the plateaus alone cannot split mu_wire from mu_wire_wall. The rise can: the
wire-wall line contact carries its share as soon as the wire moves, the tube's share builds up
over the tube's shear. This script plants known coefficients, makes noisy pulls at two
pressures with the forward model, fits them back with pull-clustered 95 % intervals, and
compares with what the plateaus alone would say.

Run: ``python examples/pullout_calibration.py`` (about 20 s; writes pullout_calibration.png
when run as a script). Units: mm, N, MPa; coefficients unitless. SYNTHETIC data.
"""

# %%
# 1. The structure, the material and the planted truth.
# The base group of the paper (116 mm tube), Shore 62.5 silicone. mu_wall is taken as known
# here (with fixed tube ends it only shows when the wall arc slips; see the docs).
import numpy as np

from exofric.friction import PullFitSettings, fit_pullout
from exofric.geometry import BASE
from exofric.material import MooneyRivlin
from exofric.simulate import PulloutNumerics, PulloutSetup, SqueezeSetup, pullout

MAT = MooneyRivlin.from_shore(62.5)
TRUTH = {"mu_wire": 0.3, "mu_wall": 0.5, "mu_wire_wall": 0.15}
PRESSURES = (0.3, 0.6)              # MPa
TRAVEL_MM = 2.0                     # each pull's travel: well past the breakaway (~1.1 mm)
# a cheap model (draft mesh, 20 cable elements, 30 load steps): the data come from the same one
SETTINGS = PullFitSettings(accuracy="draft", n_z=20, n_path=30)

# %%
# 2. Noisy pulls: three per pressure, each with its own 2 % friction scatter (pull to
# pull, as real rigs show) and 0.2 N load-cell noise per sample.
rng = np.random.default_rng(7)
squeeze = SqueezeSetup(BASE, MAT, accuracy="draft").solve(list(PRESSURES))
pulls = []
for k, p in enumerate(PRESSURES):
    r = pullout(PulloutSetup(BASE, MAT, numerics=PulloutNumerics(n_z=20, n_path=30), **TRUTH),
                p, displacement_mm=TRAVEL_MM, first_loading=True, squeeze_result=squeeze,
                squeeze_index=k)
    x = np.linspace(0.0, TRAVEL_MM, 160)
    clean = np.interp(x, r.displacement_mm, r.force_n)
    for rep in range(3):
        force = clean * (1.0 + 0.02 * rng.standard_normal()) + 0.2 * rng.standard_normal(x.size)
        pulls.append({"label": f"{p:g} MPa #{rep + 1}", "pressure_mpa": p,
                      "displacement_mm": x, "force_n": np.abs(force)})

# %%
# 3. Fit mu_wire and mu_wire_wall to the whole curves.
fit = fit_pullout(BASE, MAT, pulls, mu_wall=TRUTH["mu_wall"], mu_wire_wall="fit",
                  settings=SETTINGS)
print(fit.to_frame().to_string(index=False, float_format=lambda v: f"{v:.4f}"))
for name in fit.fitted:
    inside = fit.ci_low[name] <= TRUTH[name] <= fit.ci_high[name]
    print(f"{name}: planted {TRUTH[name]:.3f}, fitted {fit.estimate[name]:.4f} "
          f"[{fit.ci_low[name]:.4f}, {fit.ci_high[name]:.4f}] "
          f"({'covers' if inside else 'MISSES'} the truth)")

# %%
# 4. What the plateaus alone would give: the same two unknowns from the sliding forces,
# on columns L S_wire and L N that are nearly parallel (condition number >> 1).
pl = fit.plateau
print(f"plateaus alone: mu_wire {pl['mu_wire']:.3f} +- {pl['se_cr1'][0]:.3f}, mu_wire_wall "
      f"{pl['mu_wire_wall']:.3f} +- {pl['se_cr1'][1]:.3f} (condition number "
      f"{pl['condition_number']:.0f}); the curves: condition number {fit.condition_number:.1f}")

if __name__ == "__main__":
    from exofric.plots import save

    print("wrote", save(fit.plot(), "pullout_calibration.png"))
