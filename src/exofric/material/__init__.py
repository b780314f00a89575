"""Materials: Shore A hardness to Mooney-Rivlin (paper Eqs 2-6), other hyperelastic models, fits.

* :class:`MooneyRivlin` -- the two-parameter, nearly incompressible model (ANSYS convention),
  built from constants or from a Shore A hardness (:meth:`MooneyRivlin.from_shore`).
* :func:`shore_to_modulus` and :data:`CORRELATIONS` -- Eq 3 and other published Shore-to-modulus
  correlations.
* :func:`material_model` and :class:`HyperelasticModel` -- neo-Hookean, Mooney-Rivlin, Yeoh and
  Ogden (N = 1-3), all with Eq 2's volumetric term ``(J - 1)^2 / d``; closed-form uniaxial,
  equibiaxial and planar stresses (engineering or true) and a Drucker check
  (:class:`StabilityCheck`).
* :func:`fit_material` -> :class:`MaterialFit` (per mode :class:`ModeFit`) -- least-squares fit
  to one or several test modes, with standard errors, correlations and the stability check;
  :func:`treloar_1944` -- Treloar's natural rubber data as a reference set;
  :func:`silicone_uniaxial` -- uniaxial curves of three soft-robotics silicones (Soft Robotics
  Materials Database, ODbL).

Units: moduli, stresses and C10, C01, ... in MPa; d in 1/MPa; stretches and Ogden exponents
unitless; hardness in Shore A. ``docs/materials.md`` has the conventions and the checks.

Examples
--------
>>> from exofric.material import MooneyRivlin, fit_material, treloar_1944
>>> round(MooneyRivlin.from_shore(62.5).c10_mpa, 4)
0.6354
>>> fit = fit_material("neo-hookean", **treloar_1944())
>>> fit.model.name, fit.stability.stable
('neo-hookean', True)
"""

from exofric.material._fit import MaterialFit, ModeFit, ModeStability, fit_material
from exofric.material._hyperelastic import (
    HYPERELASTIC_MODELS,
    MODES,
    HyperelasticModel,
    StabilityCheck,
    material_model,
)
from exofric.material._models import (
    CORRELATIONS,
    Correlation,
    MaterialRangeWarning,
    MooneyRivlin,
    shore_to_modulus,
)
from exofric.material._silicone import SILICONE_SOURCE, SILICONES, silicone_uniaxial
from exofric.material._treloar import TRELOAR_SOURCE, treloar_1944

__all__ = ["CORRELATIONS", "Correlation", "HYPERELASTIC_MODELS", "HyperelasticModel", "MODES",
           "MaterialFit", "MaterialRangeWarning", "ModeFit", "ModeStability", "MooneyRivlin",
           "SILICONES", "SILICONE_SOURCE", "StabilityCheck", "TRELOAR_SOURCE", "fit_material",
           "material_model", "shore_to_modulus", "silicone_uniaxial", "treloar_1944"]

# every public function checks its arguments' kinds (InputError naming the parameter)
from exofric._lazy import export_checked  # noqa: E402

export_checked(__name__)
