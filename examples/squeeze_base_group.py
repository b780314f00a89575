"""The squeezing force N(P) of the paper's base group (Sec. 3.4, Figs 6-7).

The air tube (8.3 / 4.97 mm, Shore 62.5) lies in a 10 mm hole beside a 1.6 mm steel wire,
with a 0.1 mm gap between tube and wire. Inflating the tube closes the gap and squeezes the
wire against the hole wall; the friction on the wire is later modelled as gamma N (Eq 1).
This script computes N(P) with the plane-strain FE model, finds the pressure at which the
tube first touches the wire, checks the vertical force balance and sets N at 0.6 MPa beside
the paper's 268.55 N.

Run it from the repository root::

    python examples/squeeze_base_group.py    # writes squeeze_base_group.png here

Units: mm, N, MPa. N is the total over the tube length L = 116 mm.
"""

# %%
# The structure and the material
# -------------------------------
#
# ``ef.BASE`` is the base group of Table 3: hole D = 10 mm, tube outer diameter d1 = 8.3 mm,
# wire d2 = 1.6 mm, tube length L = 116 mm. The paper prints no tube inner diameter; 4.97 mm
# reproduces its Table 1 inflation columns (see docs/paper-notes.md, Part 3).

import numpy as np

import exofric as ef
from exofric import paper

structure = ef.BASE
material = ef.MooneyRivlin.from_shore(62.5)
clearance_mm = structure.clearance_mm               # D - d1 - d2 = 0.1 mm
pressures_mpa = np.round(np.arange(0.05, 0.601, 0.05), 2)   # 0.05, 0.1, ..., 0.6 MPa

# %%
# The squeeze simulation
# ----------------------
#
# ``ef.squeeze`` solves half of the section (symmetric about the line through the three
# centres): a Mooney-Rivlin tube under internal follower pressure, in frictionless penalty
# contact with the rigid hole and wire. Gravity is an explicit option; by default the tube's
# weight is left out (``gravity="none"``). The default accuracy ("standard") solves on two
# nested meshes (3 x 32 and 3 x 16 quadratic elements graded toward the wire), returns the
# finer answer and estimates its discretisation error per pressure; it is within 1 % of the
# mesh-converged N from the first pressure where N reaches 1 % of N(0.6 MPa). Forces come per
# unit depth (N/mm) and as totals over L (N); the contact onset is bracketed to 2e-4 MPa.

result = ef.squeeze(structure, material, pressures_mpa)
squeeze_force_n = result.squeeze_force_n
n_at_0_6_mpa_n = float(squeeze_force_n[-1])
contact_onset_mpa = result.contact_onset_pressure_mpa
n_error_estimate_pct = result.estimate.pct

# %%
# Vertical force balance
# ----------------------
#
# The wire pushes the tube down with N and the hole wall pushes it up; without gravity nothing
# else acts on the tube vertically (the pressure has no net force), so at every pressure the
# wall force must equal N; the residual is round-off. With ``gravity="toward-wall"`` the wall
# would carry N plus the weight.

equilibrium_residual_n = float(np.max(np.abs(result.wall_force_n - squeeze_force_n)))

# %%
# Beside the paper
# ----------------
#
# The paper's ANSYS model gives 268.55 N at 0.6 MPa (Fig 7); exofric gives about 240 N,
# 10.5 % less (10.6 % with the calibrated ID of 4.9666 mm). The gap is documented in
# docs/paper-notes.md (S1): neither the unprinted tube ID nor the slip in Table 2's C10 explains
# it (each pair of constants and ID fitted to Table 1 gives the same N to 0.1 %); exofric's
# number is converged in mesh, contact penalty and load steps and matches an independent FElupe
# model; and the paper's curves also differ in shape (S2). The remaining candidates (ANSYS
# contact settings, element formulation) cannot be checked from the text.

paper_n_at_0_6_mpa_n = paper.scalar("base_squeeze_force_at_0_6_mpa_n")
gap_to_paper_pct = 100.0 * (n_at_0_6_mpa_n / paper_n_at_0_6_mpa_n - 1.0)

# %%
# How nonlinear is N(P)?
# ----------------------
#
# The paper calls the curve "almost linear". Doubling the pressure from 0.3 to 0.6 MPa
# multiplies N by about 5: the curve is convex after contact (paper-notes S3).

n_ratio_0_6_over_0_3 = float(squeeze_force_n[-1] / squeeze_force_n[pressures_mpa == 0.3][0])

print(f"clearance tube-wire: {clearance_mm:.2f} mm")
print(f"contact onset: {contact_onset_mpa:.4f} MPa")
print(" P (MPa)   N (N)   wire contact half-width (mm)   N error estimate (%)")
for p, n, w, e in zip(pressures_mpa, squeeze_force_n, result.contact.wire_contact_halfwidth_mm,
                      n_error_estimate_pct, strict=True):
    print(f"  {p:4.2f}   {n:7.2f}   {w:6.3f}   {e:6.2f}")
print(f"N(0.6 MPa) = {n_at_0_6_mpa_n:.2f} N; paper {paper_n_at_0_6_mpa_n:.2f} N "
      f"({gap_to_paper_pct:+.1f} %, see docs/paper-notes.md S1)")
print(f"wall force - N: max {equilibrium_residual_n:.1e} N (gravity {result.gravity})")
print(f"N(0.6) / N(0.3) = {n_ratio_0_6_over_0_3:.2f}")

# %%
# Figure
# ------
#
# ``exofric.plots.plot_squeeze`` draws the deformed sections at 0.2, 0.4 and 0.6 MPa coloured by
# von Mises stress (Fig 6) and N(P) with the contact onset (Fig 7); the paper's 268.55 N is
# added to the N(P) panel as a star.

if __name__ == "__main__":
    from exofric.plots import plot_squeeze, save

    fig = plot_squeeze(result)
    ax_n = next(a for a in fig.axes if a.get_ylabel().startswith("squeezing force"))
    ax_n.plot([0.6], [paper_n_at_0_6_mpa_n], "*", ms=12, color="tab:red",
              label="paper, ANSYS (Fig 7)")
    ax_n.legend(fontsize=8)
    print("wrote", save(fig, "squeeze_base_group.png"))
