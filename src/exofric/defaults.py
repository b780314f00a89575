"""exofric's defaults, in one place: meshes, contact, density, Newton settings, validity limits.

The API keywords, the CLI options and the sweep specs take their defaults from here, so a change
here changes them all. Every value says its unit and where it was checked. This module imports
nothing (it sits at the bottom of the layers, and the CLI reads it at start-up): meshes and
Newton settings are the keyword arguments of :class:`exofric.fe.MeshSpec` and
:class:`exofric.fe.NewtonSettings` (``MeshSpec(**SQUEEZE_MESH)``).

Units: mm, N, MPa, s; density in t/mm^3 (consistent with N, mm, s).

Examples
--------
>>> from exofric import defaults
>>> from exofric.fe import MeshSpec
>>> MeshSpec(**defaults.SQUEEZE_MESH).n_circ, defaults.CONTACT_PENALTY_N_PER_MM3
(24, 100000.0)
"""

from types import MappingProxyType
from typing import Any, Final

__all__ = [
    "CONTACT_PENALTY_N_PER_MM3",
    "INFLATION_MESH",
    "INFLATION_NEWTON",
    "MR_STRETCH_LIMIT",
    "NEWTON",
    "SILICONE_DENSITY_T_PER_MM3",
    "SQUEEZE_MESH",
    "SQUEEZE_NEWTON",
]

#: Free-inflation mesh: quarter model, 2 x 6 quad9 (130 dofs); within 3e-5 of the 1D reference
#: for 8.3/4.97 mm up to 0.6 MPa (tests/test_fe_inflate.py, convergence study).
INFLATION_MESH: Final[MappingProxyType[str, Any]] = MappingProxyType(
    {"n_radial": 2, "n_circ": 6, "kind": "quad9", "grading": 1.0, "formulation": "mixed"})

#: Squeeze mesh: half model, 2 x 24 quad9 graded 6:1 toward the wire (490 dofs); within 0.05%
#: of an 8 x 96 mesh at 0.6 MPa (tests/test_squeeze.py).
SQUEEZE_MESH: Final[MappingProxyType[str, Any]] = MappingProxyType(
    {"n_radial": 2, "n_circ": 24, "kind": "quad9", "grading": 6.0, "formulation": "mixed"})

#: Contact penalty (N/mm^3, MPa of contact pressure per mm of penetration): penetration
#: ~3e-5 mm at 0.6 MPa for the base group; 10x stiffer changes N by 1e-5.
CONTACT_PENALTY_N_PER_MM3: Final = 1e5

#: Silicone density (t/mm^3 = 1.1 g/cm^3) for the squeeze's self-weight regulariser.
SILICONE_DENSITY_T_PER_MM3: Final = 1.1e-9

#: Newton settings shared by every load path (tolerances relative to the problem's scales;
#: ``max_iter`` iterations per sub-step before a cut-back; ``max_step`` in MPa).
NEWTON: Final[MappingProxyType[str, Any]] = MappingProxyType({
    "tol_r": 1e-9, "tol_u": 1e-10, "max_iter": 15, "max_cutbacks": 12, "max_step": 0.05,
    "min_step": 1e-6, "line_search_halvings": 8, "extrapolate": True,
})

#: Newton settings of the free inflation (largest pressure step 0.05 MPa).
INFLATION_NEWTON: Final[MappingProxyType[str, Any]] = MappingProxyType(
    {**NEWTON, "max_step": 0.05})

#: Newton settings of the squeeze (largest pressure step 0.025 MPa; contact needs smaller steps).
SQUEEZE_NEWTON: Final[MappingProxyType[str, Any]] = MappingProxyType(
    {**NEWTON, "max_step": 0.025})

#: Largest principal stretch for which the paper claims its two-parameter Mooney-Rivlin model
#: holds ("100-150% material deformation", §3.3); beyond it results are extrapolations.
MR_STRETCH_LIMIT: Final = 2.5
