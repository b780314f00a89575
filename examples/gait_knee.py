"""The knee lock through walking: can a friction brake deliver a torque profile stride after stride?

Run: ``python examples/gait_knee.py`` (about 5 s; it writes gait_knee.png).
Units: s, rad (deg printed), Nm, N, MPa, normal litres, J.
"""

# %%
# 1. One stride of walking: OpenSim's example data (Apache-2.0), right knee flexion and
# moment from heel strike to heel strike. The knee absorbs energy over a stride (net work < 0).

import numpy as np

from exofric.control import (
    GaitSetup,
    Orifice,
    PneumaticParams,
    compare_gait,
    simulate_gait,
)
from exofric.io import gait_data_path, read_gait

walk = read_gait(gait_data_path())
print(f"{walk.source}: {walk.duration_s:.3f} s stride, flexion "
      f"{np.degrees(walk.knee_angle_rad.min()):.1f}-{np.degrees(walk.knee_angle_rad.max()):.1f}"
      f" deg, net knee work {walk.knee_work_j:.1f} J ({walk.knee_work_j / walk.body_mass_kg:.3f}"
      " J/kg)")

# %%
# 2. The demand: 30 % of the biological moment while the knee flexes under an extension
# moment in early stance (loading response) -- the only part of stance a brake can assist.
setup = GaitSetup(assist=0.3, strides=10)
ff = simulate_gait(walk, setup, controller="ff")
print(f"demand window {ff.window}, peak {ff.peak_demand_nm:.1f} Nm; supply model "
      f"{ff.model.to_dict()}")

# %%
# 3. Every controller on the default valve (ISO 6358 C = 0.05 dm^3/(s bar), 1 m of 4 mm
# hose): the metrics of the 10th stride, and the lock never pushes (power <= 0).
table = compare_gait(walk, setup)
print(table.format())
assert not any(r.wrong_direction for r in table.results)

# %%
# 4. A sizing question: a vent port of larger conductance releases faster.
for c_vent in (0.05, 0.1, 0.2):
    plant = PneumaticParams(vent=Orifice(c_vent))
    r = simulate_gait(walk, setup, controller="mpc", plant=plant)
    m = r.strides[-1]
    print(f"vent C {c_vent:4.2f} dm3/(s bar): MPC RMS error {m.rms_error_nm:.2f} Nm, release "
          f"{m.release_latency_ms:.0f} ms, unwanted torque {m.unwanted_torque_nms:.2f} N m s")

if __name__ == "__main__":
    from exofric.plots import plot_gait, save

    print("wrote", save(plot_gait(table.results[0]), "gait_knee.png"))
