"""Fit hyperelastic models to Treloar's (1944) rubber data: uniaxial, equibiaxial, pure shear.

Treloar's three tests on one vulcanised natural rubber are the classic check of a
hyperelastic model: a model fitted to one mode often misses the others. This script fits
neo-Hookean, Yeoh and a three-term Ogden model to all three modes at once with
:func:`exofric.material.fit_material`, prints each fit's parameters with their standard errors
and the per-mode RMS, checks Drucker stability over each mode's data range, and shows where
Mooney-Rivlin turns unstable (equibiaxial tension, beyond the equibiaxial data). With your own data,
``exofric material --model yeoh --fit uniaxial.csv --fit-planar planar.csv`` does the same.

Run it from the repository root::

    python examples/treloar_fit.py            # writes treloar_fit.png here

Units: stress in MPa (nominal), stretch unitless.
"""

# %%
# The data
# --------
#
# ``treloar_1944()`` returns stretch and nominal stress (MPa) per mode: 24 uniaxial points up to
# stretch 7.6, 16 equibiaxial up to 4.45 and 13 pure-shear up to 4.97 (provenance in
# ``exofric.material.TRELOAR_SOURCE``).

import warnings

from exofric.errors import InputError
from exofric.material import fit_material, treloar_1944

data = treloar_1944()
n_points = {mode: len(stretch) for mode, (stretch, _) in data.items()}

# %%
# Three models, all three modes at once
# -------------------------------------
#
# Absolute residuals (MPa): every point counts by its stress error. The neo-Hookean model has
# one parameter and cannot follow the upturn at large stretch; Yeoh follows uniaxial and pure
# shear but not equibiaxial; the three-term Ogden model follows all three (its six parameters
# are strongly correlated, and the fit says so in a warning).

with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # the Ogden fit warns about its correlated parameters
    fits = {name: fit_material(name, **data) for name in ("neo-hookean", "yeoh", "ogden3")}

params = {name: dict(zip(f.model.param_names, f.model.params, strict=True))
          for name, f in fits.items()}
rms_mpa = {name: {mode: m.rms_mpa for mode, m in f.modes.items()} for name, f in fits.items()}
shear_modulus_mpa = {name: f.model.shear_modulus_mpa for name, f in fits.items()}
stable = {name: f.stability.stable for name, f in fits.items()}

# %%
# Mooney-Rivlin: stable where the data are, unstable beyond
# ----------------------------------------------------------
#
# Fitted to all three modes, C01 comes out negative. Each mode is checked over its own data's
# stretch range plus a 10 % margin (``defaults.FIT_STABILITY_MARGIN_REL``), where the fit is
# stable, so it is accepted (not constrained). Asked for the whole uniaxial range 1-7.6 in every
# mode (``stability_range``), the per-mode report warns: the equibiaxial stress turns over
# near stretch 7, far beyond the equibiaxial data (4.45). A fit that is unstable inside the
# data is refused with ``constrain=False``, and the default fit is constrained to a stable one.

try:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the report's warning about the equibiaxial mode
        mr = fit_material("mooney-rivlin", **data, stability_range=(1.0, 7.6))
    mooney_rivlin_refused = False
    mooney_rivlin_biaxial_unstable_from = mr.stability_report["biaxial"].unstable_from
    refusal = ""
except InputError as exc:
    mooney_rivlin_refused = True
    mooney_rivlin_biaxial_unstable_from = None
    refusal = str(exc)

if __name__ == "__main__":
    for name, f in fits.items():
        print(f"{name}: mu = {shear_modulus_mpa[name]:.4f} MPa, stable: {stable[name]}")
        for n, v, se in zip(f.model.param_names, f.model.params, f.stderr, strict=True):
            print(f"  {n:>8} = {v: .6g} +- {se:.2g}")
        print("  RMS (MPa): " + ", ".join(f"{k} {v:.3f}" for k, v in rms_mpa[name].items()))
    print("mooney-rivlin:", refusal if mooney_rivlin_refused else
          f"accepted; equibiaxial unstable from stretch {mooney_rivlin_biaxial_unstable_from}")
    from exofric.plots import save

    print("wrote", save(fits["ogden3"].plot(), "treloar_fit.png"))
