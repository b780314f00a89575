"""Closed, open and plane-strain tubes: what the ends do to inflation, the squeeze and C01.

The paper models the air tube in plane strain: its axial stretch is 1. A real air tube is
closed at both ends, so the pressure on the end caps also stretches it along its axis; a tube
whose ends are free to slide over plugs (open ends) carries no axial force and shortens. This
script inflates the paper's tube (8.3 / 4.97 mm, Shore 62.5) all three ways, each beside its
incompressible reference, squeezes the base group with closed ends, and shows that
Mooney-Rivlin's C01, which plane strain cannot see, matters once the ends are closed.

Run it from the repository root::

    python examples/tube_ends.py            # writes tube_ends.png here

Units: mm, N, MPa; stretches unitless.
"""

# %%
# Free inflation with three end conditions
# ----------------------------------------
#
# ``inflate(..., ends=)`` adds one unknown, the uniform axial stretch (generalised plane
# strain). Each result's ``analytic_outer_diameter_mm()`` is its incompressible reference: the
# plane-strain closed form, or the semi-analytic thick tube with closed or open ends
# (:func:`exofric.simulate.tube_inflation`, solved with scipy, independent of the FE).

import numpy as np

from exofric.geometry import BASE
from exofric.material import MooneyRivlin
from exofric.simulate import inflate, squeeze, tube_inflation

OD, ID = 8.3, 4.97
pressures_mpa = [0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4]
material = MooneyRivlin.from_shore(62.5)
results = {ends: inflate(OD, ID, material, pressures_mpa, ends=ends)
           for ends in ("plane-strain", "closed", "open")}
od_mm = {e: r.outer_diameter_mm for e, r in results.items()}
axial_stretch = {e: r.axial_stretch for e, r in results.items()}

# The FE against the references: the gap is the material's compressibility (nu = 0.498), not
# the mesh; it shrinks in proportion to d (tests/test_fe_ends.py).
reference_gap_pct = {e: float(np.max(np.abs(r.outer_diameter_mm
                                             / r.analytic_outer_diameter_mm() - 1.0)) * 100)
                     for e, r in results.items()}

# %%
# The squeeze with closed ends
# ----------------------------
#
# The caps' force lengthens the squeezed tube by ~15 % at 0.6 MPa; its wall is thinner and the
# squeeze force per mm of tube in the hole is ~10 % lower than in plane strain.

sq = {ends: squeeze(BASE, material, [0.3, 0.6], ends=ends, keep_fields=False)
      for ends in ("plane-strain", "closed")}
n_at_0_6_mpa_n_per_mm = {e: float(r.squeeze_force_n_per_mm[-1]) for e, r in sq.items()}
squeeze_axial_stretch = float(sq["closed"].axial_stretch[-1])

# %%
# C01 matters with closed ends
# ----------------------------
#
# In incompressible plane strain I1 = I2, so only C10 + C01 counts. With closed ends the axial
# stretch tells them apart: at fixed C10 + C01, C01 = C10 inflates the closed tube more than
# C01 = 0 (and, exactly, does not lengthen it at all).

total = material.c10 + material.c01
split = {"c01 = 0": MooneyRivlin(total, 0.0, material.d),
         "c01 = c10": MooneyRivlin(0.5 * total, 0.5 * total, material.d)}
c01_effect_pct = {}
for ends in ("plane-strain", "closed", "open"):
    a, b = (inflate(OD, ID, m, [0.4], ends=ends, keep_fields=False).outer_diameter_mm[0]
            for m in split.values())
    c01_effect_pct[ends] = float(b / a - 1.0) * 100
c01_equal_axial_stretch = float(
    tube_inflation(OD, ID, split["c01 = c10"], [0.4], ends="closed").axial_stretch[0])

if __name__ == "__main__":
    for e in results:
        print(f"{e:>12}: OD {od_mm[e][-1]:.4f} mm, axial stretch {axial_stretch[e][-1]:.4f} at "
              f"0.4 MPa; max gap to the incompressible reference {reference_gap_pct[e]:.3f} %")
    print("squeeze N(0.6 MPa):", {e: round(v, 4) for e, v in n_at_0_6_mpa_n_per_mm.items()},
          f"N/mm; closed-end axial stretch {squeeze_axial_stretch:.3f}")
    print("C01 = C10 vs C01 = 0 at fixed C10 + C01, OD change at 0.4 MPa (%):",
          {e: round(v, 3) for e, v in c01_effect_pct.items()})
    from exofric.plots import plot_tube_ends, save

    print("wrote", save(plot_tube_ends(list(results.values())), "tube_ends.png"))
