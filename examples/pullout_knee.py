"""The locked knee: pull the wire through the inflated tube, then K(P) and T_break(P).

Run: ``python examples/pullout_knee.py`` (about 5 s). Units: mm, N, MPa; Nm, rad.
"""

# %%
# 1. One section: the axial response of a unit length of squeezed tube at 0.6 MPa.
# The wire sticks to the tube, slip spreads over the tube-wire arc, and at full sliding the
# force per length is mu_wire S_wire + mu_wire_wall N (the squeeze's contact integrals).
from exofric.friction import joint_stiffness
from exofric.geometry import BASE
from exofric.material import MooneyRivlin
from exofric.simulate import PulloutSetup, pullout, section_pullout

# The problem but its pressure and path: structure, material, the three interfaces'
# coefficients (tube-wire, tube-wall, wire-wall), the squeeze's accuracy.
setup = PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3, mu_wall=0.5,
                     mu_wire_wall=0.2, accuracy="draft")
sec = section_pullout(setup, 0.6)
print(f"section: k0 = {sec.initial_stiffness_n_per_mm2:.3f} N/mm per mm, full slip at "
      f"{sec.slip_displacement_mm:.3f} mm, plateau {sec.sliding_force_n_per_mm:.3f} N/mm")

# %%
# 2. The whole 116 mm tube, cable EA 1.3e5 N, a static coefficient 20% above the kinetic:
# breakaway peak, then sliding; one back-and-forth gives the hysteresis loop.
r = pullout(setup.with_friction(mu_static=0.36), 0.6, displacement_mm=3.0)
print(f"whole length: breakaway {r.static_force_n:.1f} N, sliding {r.sliding_force_n:.1f} N")

# %%
# 3. At the knee (R = 0.1 m): stiffness before slip and breakaway torque over pressure.
j = joint_stiffness(setup, [0.2, 0.4, 0.6], radius_m=0.1)
for p, k, t in zip(j.pressure_mpa, j.stiffness_nm_per_rad, j.breakaway_torque_nm,
                   strict=True):
    print(f"P = {p:.1f} MPa: K = {k:7.1f} Nm/rad, T_break = {t:5.2f} Nm")
