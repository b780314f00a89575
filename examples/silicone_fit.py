"""Fit hyperelastic models to a published silicone tensile curve (Dragon Skin 20, uniaxial).

Run: ``python examples/silicone_fit.py`` (about 5 s; it writes silicone_fit.png). The curve is
shipped with exofric: the Soft Robotics Materials Database (Marechal et al., Soft Robotics
8(3) 2021, doi:10.1089/soro.2019.0115, ODbL 1.0), ASTM D412 die C, to failure. Units: stretch
(unitless), nominal stress (MPa), moduli (MPa).
"""

# %%
# 1. The shipped curve: stretch and nominal (engineering) stress.
import warnings

from exofric.errors import PlausibilityWarning
from exofric.material import fit_material, silicone_uniaxial

stretch, stress_mpa = silicone_uniaxial("dragon-skin-20")
print(f"{stretch.size} points, stretch {stretch.min():.2f}-{stretch.max():.2f}, "
      f"stress up to {stress_mpa.max():.3f} MPa")

# %%
# 2. Four models fitted to the same curve. Every fit is admissible (Drucker-stable over the
# data, a positive shear modulus); Mooney-Rivlin's unconstrained optimum is not (C10 + C01 < 0
# on silicone), so its fit is constrained, and says so.
fits = {}
for name in ("neo-hookean", "mooney-rivlin", "yeoh", "ogden2"):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PlausibilityWarning)
        fits[name] = fit_material(name, uniaxial=(stretch, stress_mpa))
for name, fit in fits.items():
    print(f"{name:14s} RMS {1e3 * fit.modes['uniaxial'].rms_mpa:7.2f} kPa, shear modulus "
          f"{fit.model.shear_modulus_mpa:.4f} MPa, admissible {fit.admissible}, constrained "
          f"{fit.constrained}")

if __name__ == "__main__":
    from exofric.plots import save

    print("wrote", save(fits["ogden2"].plot(), "silicone_fit.png"))
