"""exofric's defaults, in one place: meshes, contact, density, Newton settings, validity limits.

The API keywords, the CLI options and the sweep specs take their defaults from here, so a change
here changes them all. Every value says its unit and where it was checked.

Units: mm, N, MPa, s; density in t/mm^3 (consistent with N, mm, s).

Examples
--------
>>> from exofric import defaults
>>> defaults.SQUEEZE_MESH.n_circ, defaults.CONTACT_PENALTY_N_PER_MM3
(24, 100000.0)
"""

from __future__ import annotations

from exofric.fe import MeshSpec, NewtonSettings

__all__ = [
    "CONTACT_PENALTY_N_PER_MM3",
    "INFLATION_MESH",
    "INFLATION_NEWTON",
    "MR_STRETCH_LIMIT",
    "SILICONE_DENSITY_T_PER_MM3",
    "SQUEEZE_MESH",
    "SQUEEZE_NEWTON",
]

#: Free-inflation mesh: quarter model, 2 x 6 quad9 (130 dofs); within 3e-5 of the 1D reference
#: for 8.3/4.97 mm up to 0.6 MPa (tests/test_fe_inflate.py, convergence study).
INFLATION_MESH = MeshSpec(n_radial=2, n_circ=6)

#: Squeeze mesh: half model, 2 x 24 quad9 graded 6:1 toward the wire (490 dofs); within 0.05%
#: of an 8 x 96 mesh at 0.6 MPa (tests/test_squeeze.py).
SQUEEZE_MESH = MeshSpec(n_radial=2, n_circ=24, grading=6.0)

#: Contact penalty (N/mm^3, MPa of contact pressure per mm of penetration): penetration
#: ~3e-5 mm at 0.6 MPa for the base group; 10x stiffer changes N by 1e-5.
CONTACT_PENALTY_N_PER_MM3 = 1e5

#: Silicone density (t/mm^3 = 1.1 g/cm^3) for the squeeze's self-weight regulariser.
SILICONE_DENSITY_T_PER_MM3 = 1.1e-9

#: Newton settings of the free inflation (largest pressure step 0.05 MPa).
INFLATION_NEWTON = NewtonSettings(max_step=0.05)

#: Newton settings of the squeeze (largest pressure step 0.025 MPa; contact needs smaller steps).
SQUEEZE_NEWTON = NewtonSettings(max_step=0.025)

#: Largest principal stretch for which the paper claims its two-parameter Mooney-Rivlin model
#: holds ("100-150% material deformation", §3.3); beyond it results are extrapolations.
MR_STRETCH_LIMIT = 2.5
