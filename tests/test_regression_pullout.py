"""Regression pins of the pull-out (issue 39): numbers that only came out of our code.

They catch unintended changes; the independent checks are in tests/test_pullout.py. Base group,
Shore 62.5, draft mesh, mu_wire 0.3, mu_wall 0.5, mu_wire_wall 0.2, R = 0.1 m, 0.6 MPa.
Tolerance 1e-4 relative: the solves are deterministic to ~1e-9; the pins are printed to 6 digits.
"""

from __future__ import annotations

import pytest

from exofric.friction import joint_stiffness
from exofric.geometry import BASE
from exofric.material import MooneyRivlin
from exofric.simulate import section_pullout

MU = {"mu_wire": 0.3, "mu_wall": 0.5, "mu_wire_wall": 0.2}


def test_pin_section_base_group():
    s = section_pullout(BASE, MooneyRivlin.from_shore(62.5), 0.6, accuracy="draft", **MU)
    assert s.initial_stiffness_n_per_mm2 == pytest.approx(0.788050, rel=1e-4)
    assert s.slip_displacement_mm == pytest.approx(1.029412, rel=1e-4)
    assert s.sliding_force_n_per_mm == pytest.approx(1.076324, rel=1e-4)


def test_pin_joint_stiffness_base_group():
    j = joint_stiffness(BASE, MooneyRivlin.from_shore(62.5), [0.6], radius_m=0.1,
                        mu_static=0.36, displacement_mm=2.0, accuracy="draft", **MU)
    assert j.stiffness_nm_per_rad[0] == pytest.approx(PIN_K, rel=1e-4)
    assert j.breakaway_torque_nm[0] == pytest.approx(PIN_T, rel=1e-4)


PIN_K = 2851.233  # Nm/rad
PIN_T = 13.29090  # Nm
