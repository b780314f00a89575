"""Predict the friction of the paper's Table 3 structures and check where the model applies.

With gamma fitted on the base group, the paper predicts the friction of six other
hole-tube-wire structures as F = gamma N(P), simulating N(P) for each (Sec. 4, Table 3), and
finds the prediction valid while the structure stays within about 20 % of the base. This
script does the same with :func:`exofric.predict` on :func:`exofric.friction.paper_structures`,
shows the deviation metrics behind the applicability check and the torque each structure
reaches on a 0.10 m lever arm.

Run it from the repository root::

    python examples/predict_structures.py    # writes predict_structures.png here

Units: mm, MPa, N, Nm; gamma and deviations unitless / in %.
"""

# %%
# The structures
# --------------
#
# ``paper_structures()`` returns the seven rows of Table 3 (test 1 is the base group) as
# :class:`exofric.Structure` objects. Table 3 prints the hole D, tube outer diameter d1 and
# wire d2 only; the tube inner diameter is taken with the base's wall-to-diameter ratio,
# ID = 4.97 d1 / 8.3 mm, and every tube is 116 mm long.

import warnings

import numpy as np

import exofric as ef
from exofric import paper
from exofric.friction import ApplicabilityWarning, paper_structures

structures = paper_structures()
material = ef.MooneyRivlin.from_shore(62.5)
gamma = paper.scalar("gamma")                         # 0.7168, fitted on the base group
pressures_mpa = np.round(np.arange(0.1, 0.601, 0.05), 2)

# %%
# Predictions
# -----------
#
# ``ef.predict`` runs the squeeze simulation for each structure, multiplies N(P) by gamma and
# checks the torque T = F R at the highest pressure against the knee's 0-40 Nm (R = 0.10 m,
# paper Fig 2b). For every structure whose deviation from the base exceeds 20 % it emits an
# ``ApplicabilityWarning``; here they are collected instead of printed.

with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always", ApplicabilityWarning)
    predictions = ef.predict(structures, gamma, material, pressures_mpa).predictions
flagged = [str(w.message).split(":")[0] for w in caught
           if issubclass(w.category, ApplicabilityWarning)]

friction_at_0_6_mpa_n = {p.structure.name: p.predicted_friction_n[-1] for p in predictions}
torque_at_0_6_mpa_nm = {p.structure.name: p.torque.torque_nm for p in predictions}
contact_onset_mpa = {p.structure.name: p.contact_onset_pressure_mpa for p in predictions}

# %%
# The applicability check
# -----------------------
#
# Each structure's diameters divided by the base's give three scale factors s = (s_D, s_d1,
# s_d2). exofric's ``deviation_pct`` = 100 (max s / min s - 1) measures how far a structure is
# from a *proportional* resize of the base (0 for any pure scaling) and drives the 20 % flag:
# tests 2-5 pass, tests 6 and 7 do not, as the paper concluded from its measurements.
# The paper does not define its own "maximum relative deviation" column; the reading
# ``paper_deviation_pct`` = 100 max |s - 1| reproduces it for tests 4-7 (docs/paper-notes.md,
# F4). ``clearance_mm`` = D - d1 - d2 is the gap the tube must close before any friction
# appears: 0 mm for test 4, 1.5 mm for test 6, whose contact therefore starts late.

deviation_pct = {p.structure.name: p.deviation.deviation_pct for p in predictions}
paper_deviation_pct = {p.structure.name: p.deviation.paper_deviation_pct for p in predictions}
clearance_mm = {p.structure.name: p.structure.clearance_mm for p in predictions}

# %%
# A proportional resize
# ---------------------
#
# In plane strain at a fixed pressure, a structure scaled by s in every diameter (tube ID
# included) has the same stresses on an s times larger section, so N per unit depth, and with
# the same length the total N and F, scale by s. Its deviation is 0 %: the model should carry
# over exactly, which is what the 20 % criterion tries to capture for near-proportional
# structures like tests 2 and 3.

scale = 1.23                                          # test 3's hole scale, 12.3 / 10 mm
resized = ef.BASE.scaled(scale, f"base x {scale:g}")
resized_prediction = ef.predict([resized], gamma, material, pressures_mpa,
                                base=ef.BASE).predictions[0]       # deviation from the base
scaled_friction_ratio = resized_prediction.predicted_friction_n[-1] / friction_at_0_6_mpa_n[
    "test 1"]

print(" structure  D / d1 / d2 (mm)      clearance  deviation  paper col.   F(0.6)   T(0.6)")
for p in predictions:
    s = p.structure
    name = s.name
    print(f" {name:8s}  {s.hole_mm:4.1f} / {s.tube_od_mm:4.1f} / {s.wire_mm:3.1f}   "
          f"{clearance_mm[name]:5.2f} mm  {deviation_pct[name]:6.1f} %  "
          f"{paper_deviation_pct[name]:6.2f} %  {friction_at_0_6_mpa_n[name]:6.1f} N  "
          f"{torque_at_0_6_mpa_nm[name]:5.1f} Nm")
print("outside the validated region (> 20 %):", ", ".join(flagged))
print(f"{resized.name}: F(0.6) / F_base(0.6) = {scaled_friction_ratio:.4f} (scale {scale:g})")

# %%
# Figure
# ------
#
# Left: predicted F(P), dashed where the structure is outside the validated region. Right:
# ``exofric.plots.plot_torque`` with the knee's 40 Nm and the paper's 30 Nm for test 3
# (300 N x 0.10 m, Sec. 4). No structure reaches 40 Nm at 0.6 MPa; exofric's 21 Nm for test 3
# is 29 % below the paper's measurement, a gap no choice of the unprinted tube ID closes
# (docs/paper-notes.md, D1-D2).

if __name__ == "__main__":
    import matplotlib.pyplot as plt

    from exofric.plots import plot_torque, save

    fig, (ax_f, ax_t) = plt.subplots(1, 2, figsize=(12, 4.6))
    for p in predictions:
        style = "-" if p.deviation.in_validated_region else "--"
        ax_f.plot(p.pressure_mpa, p.predicted_friction_n, style, marker="o", ms=3,
                  label=f"{p.structure.name} ({p.deviation.deviation_pct:.1f} %)")
    ax_f.set_xlabel("pressure P (MPa)")
    ax_f.set_ylabel(f"predicted friction F = {gamma:g} N (N)")
    ax_f.set_title("Table 3 structures (deviation from base; dashed: > 20 %)", fontsize=10)
    ax_f.grid(alpha=0.3)
    ax_f.legend(fontsize=8)
    names = list(torque_at_0_6_mpa_nm)
    plot_torque(names, list(torque_at_0_6_mpa_nm.values()), ax_t, limit_nm=40.0,
                limit_label="knee requirement 40 Nm",
                reference=([names.index("test 3")], [paper.scalar("test3_torque_nm")],
                           "paper, test 3 (Sec. 4)"))
    ax_t.set_ylim(0.0, 52.0)
    ax_t.legend(fontsize=8, loc="upper left", ncol=3)
    fig.tight_layout()
    print("wrote", save(fig, "predict_structures.png"))
