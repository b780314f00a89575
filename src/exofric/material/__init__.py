"""Silicone material: Shore A hardness to Mooney-Rivlin constants (paper Eqs 2-6).

* :class:`MooneyRivlin` -- the two-parameter, nearly incompressible model (ANSYS convention),
  built from constants or from a Shore A hardness (:meth:`MooneyRivlin.from_shore`).
* :func:`shore_to_modulus` and :data:`CORRELATIONS` -- Eq 3 and other published Shore-to-modulus
  correlations.

Units: moduli and C10, C01 in MPa; d in 1/MPa; hardness in Shore A.

Examples
--------
>>> from exofric.material import MooneyRivlin
>>> round(MooneyRivlin.from_shore(62.5).c10_mpa, 4)
0.6354
"""

from exofric.material._models import (
    CORRELATIONS,
    Correlation,
    MaterialRangeWarning,
    MooneyRivlin,
    shore_to_modulus,
)

__all__ = ["CORRELATIONS", "Correlation", "MaterialRangeWarning", "MooneyRivlin",
           "shore_to_modulus"]
