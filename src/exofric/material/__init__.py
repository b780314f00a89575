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

from __future__ import annotations

from typing import TYPE_CHECKING

from exofric._lazy import lazy_package

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
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


# Lazy facade (PEP 562): ``exofric material --shore`` and the Mooney-Rivlin constants load
# neither NumPy nor the fits; each name is loaded from its module on first use, every public
# function checked (InputError naming the parameter; exofric._lazy.lazy_package). The
# TYPE_CHECKING imports above are the one list of public names.
__getattr__, __dir__, __all__ = lazy_package(__name__, __file__)
