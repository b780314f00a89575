"""The FrictionLaw protocol (issue 32): any law plugs into predict, the virtual rig and control.

A third law defined here, F = F0 + k P (friction linear in the pressure, independent of the FE
curves; k = 0 is a constant friction), goes through :func:`exofric.friction.predict`,
:func:`exofric.friction.simulate_law_rig` and
:meth:`exofric.control.CurveFrictionMap.from_law`; each answer is checked against that closed
form. The two shipped laws are checked against hand-computed values of gamma N and
mu_tube S + mu_wall N. Tolerances: 1e-12 relative where the path is interpolation of data that
lie on a line (PCHIP reproduces a line exactly, so only round-off remains); 1e-9 for the
inverse (Brent's xtol is 1e-12 MPa).

Also the frozen value types after the removal of object.__setattr__ for caches and for
objects built by mutation: equality and hash as before (normalised fields; a cache does not
count), and the optimiser's unchecked stresses against the neo-Hookean closed form.
"""

from __future__ import annotations

import pickle
from collections.abc import Mapping
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

from exofric.control import CurveFrictionMap
from exofric.errors import InputError
from exofric.friction import (
    FrictionLaw,
    FrictionModel,
    InterfaceCurves,
    InterfaceFrictionModel,
    RigConfig,
    SqueezeCurve,
    law_columns,
    paper_structures,
    predict,
    simulate_interface_rig,
    simulate_law_rig,
)
from exofric.geometry import Structure
from exofric.material import HyperelasticModel

IDEAL = RigConfig(noise_pct=0.0, pressure_tau_s=0.0)


@dataclass(frozen=True)
class PressureLinearLaw:
    """F = f0_n + k_n_per_mpa P (N): no FE input at all (k = 0: constant friction)."""

    k_n_per_mpa: float
    f0_n: float = 0.0

    @property
    def name(self) -> str:
        return "linear-in-p"

    @property
    def inputs(self) -> tuple[str, ...]:
        return ()

    def friction_of(self, columns: Mapping[str, Any]) -> np.ndarray:
        return self.f0_n + self.k_n_per_mpa * np.asarray(columns["pressure_mpa"], dtype=float)

    def to_dict(self) -> dict[str, Any]:
        return {"law": self.name, "k_n_per_mpa": self.k_n_per_mpa, "f0_n": self.f0_n}


@dataclass(frozen=True)
class NeedsContactArea:
    """A law reading an FE output nobody provides (for the error path)."""

    f0_n: float = 0.0
    name: str = "area"
    inputs: tuple[str, ...] = ("contact_area_mm2",)

    def friction_of(self, columns: Mapping[str, Any]) -> np.ndarray:
        return np.asarray(columns["contact_area_mm2"], dtype=float)

    def to_dict(self) -> dict[str, Any]:
        return {"f0_n": self.f0_n}


def _fake_squeeze(structure: Structure, material: Any, p: np.ndarray) -> SimpleNamespace:
    """N(P) = 400 P (N) and S_wire = 1.1 N, reported per mm of a 116 mm tube."""
    return SimpleNamespace(pressure_mpa=p, squeeze_force_n=400.0 * p,
                           wire_pressure_integral_n_per_mm=440.0 * p / 116.0, length_mm=116.0)


def test_both_laws_and_a_third_are_friction_laws() -> None:
    assert isinstance(FrictionModel(0.7168), FrictionLaw)
    assert isinstance(InterfaceFrictionModel(0.5, 0.2), FrictionLaw)
    assert isinstance(PressureLinearLaw(100.0), FrictionLaw)
    assert not isinstance(0.7, FrictionLaw)
    assert FrictionModel(0.7).name == "gamma"
    assert InterfaceFrictionModel(0.5, 0.2).name == "interfaces"


def test_shipped_laws_friction_of_match_hand_values() -> None:
    cols = {"pressure_mpa": [0.2, 0.4], "squeeze_force_n": [20.0, 100.0],
            "wire_pressure_integral_n": [22.0, 110.0]}
    # gamma N + F0 = 0.5 x (20, 100) + 2; mu_tube S + mu_wall N = 0.5 x (22, 110) + 0.2 x (20, 100)
    assert FrictionModel(0.5, 2.0).friction_of(cols).tolist() == pytest.approx([12.0, 52.0],
                                                                               rel=1e-15)
    assert InterfaceFrictionModel(0.5, 0.2).friction_of(cols).tolist() == pytest.approx(
        [15.0, 75.0], rel=1e-15)


@pytest.mark.parametrize("k", [0.0, 150.0])
def test_a_third_law_plugs_into_predict(k: float) -> None:
    law = PressureLinearLaw(k, f0_n=5.0)
    grid = np.array([0.2, 0.4, 0.6])
    r = predict(paper_structures()[:2], law, None, grid, squeeze_fn=_fake_squeeze,
                arm_radius_m=0.1)
    for pr in r.predictions:
        assert pr.law == "linear-in-p"
        assert pr.predicted_friction_n == pytest.approx(5.0 + k * grid, rel=1e-12)
        assert pr.torque.torque_nm == pytest.approx((5.0 + k * 0.6) * 0.1, rel=1e-12)
    d = r.to_dict()
    assert d["law"] == "linear-in-p" and d["gamma"] is None and d["k_n_per_mpa"] == k
    assert d["structures"][0]["k_n_per_mpa"] == k and d["structures"][0]["f0_n"] == 5.0


def test_a_third_law_beside_gamma_in_predict() -> None:
    law = PressureLinearLaw(150.0)
    grid = np.array([0.3, 0.6])
    r = predict(paper_structures()[:1], law, None, grid, squeeze_fn=_fake_squeeze, compare=0.7)
    laws = {lp.law: lp for lp in r.predictions[0].laws}
    assert laws["linear-in-p"].predicted_friction_n == pytest.approx(150.0 * grid, rel=1e-12)
    assert laws["gamma"].predicted_friction_n == pytest.approx(0.7 * 400.0 * grid, rel=1e-12)
    with pytest.raises(InputError, match="compare"):
        predict(paper_structures()[:1], law, None, grid, squeeze_fn=_fake_squeeze,
                compare=PressureLinearLaw(1.0))


def test_predict_names_a_curve_no_squeeze_gives() -> None:
    with pytest.raises(InputError, match="contact_area_mm2"):
        predict(paper_structures()[:1], NeedsContactArea(), None, [0.4],
                squeeze_fn=_fake_squeeze)


@pytest.mark.parametrize("k", [0.0, 150.0])
def test_a_third_law_plugs_into_the_virtual_rig(k: float) -> None:
    curve = SqueezeCurve([0.1, 0.2, 0.4, 0.6], [0.0, 80.0, 160.0, 240.0])
    run = simulate_law_rig(PressureLinearLaw(k, f0_n=5.0), curve, config=IDEAL, repeats=2)
    p = np.array([0.2, 0.4, 0.6] * 2)       # default set points: the nodes where N > 0
    assert run.pressure_mpa == pytest.approx(p, rel=1e-12)
    assert run.friction_n == pytest.approx(5.0 + k * p, rel=1e-12)
    assert run.true_friction_n == pytest.approx(5.0 + k * p, rel=1e-12)


def test_shipped_laws_in_the_law_rig_match_hand_values() -> None:
    curves = InterfaceCurves([0.2, 0.4, 0.6], [22.0, 110.0, 264.0], [20.0, 100.0, 240.0], "a")
    run = simulate_law_rig(InterfaceFrictionModel(0.5, 0.2), curves, config=IDEAL)
    assert run.friction_n == pytest.approx([15.0, 75.0, 180.0], rel=1e-12)
    run = simulate_law_rig(FrictionModel(0.5), curves, [0.4], config=IDEAL)
    assert run.friction_n == pytest.approx([50.0], rel=1e-12)
    # simulate_interface_rig is this rig with the interface law planted
    irun = simulate_interface_rig(curves, 0.5, 0.2, config=IDEAL)
    assert irun.friction_n == pytest.approx([15.0, 75.0, 180.0], rel=1e-12)


def test_law_rig_names_the_missing_curve() -> None:
    curve = SqueezeCurve([0.2, 0.6], [20.0, 240.0])
    with pytest.raises(InputError, match="wire_pressure_integral_n"):
        simulate_law_rig(InterfaceFrictionModel(0.5, 0.2), curve)
    with pytest.raises(InputError, match="3 values for 2 pressures"):
        law_columns(FrictionModel(0.5), {"pressure_mpa": [0.2, 0.6],
                                         "squeeze_force_n": [1.0, 2.0, 3.0]})


def test_a_third_law_plugs_into_the_control_map() -> None:
    nodes = SimpleNamespace(pressure_mpa=(0.2, 0.4, 0.6))       # the law reads no FE curve
    g = CurveFrictionMap.from_law(PressureLinearLaw(150.0, f0_n=5.0), nodes)
    p = np.array([0.2, 0.3, 0.5, 0.6, 0.8])           # 0.8: the linear extension, slope k
    assert g(p) == pytest.approx(5.0 + 150.0 * p, rel=1e-12)
    assert g(0.1) == pytest.approx((5.0 + 150.0 * 0.2) * 0.1 / 0.2, rel=1e-12)  # to (0, 0)
    assert g.inverse(50.0) == pytest.approx((50.0 - 5.0) / 150.0, rel=1e-9)
    assert g.scaled(1.2)(0.4) == pytest.approx(1.2 * (5.0 + 60.0), rel=1e-12)


def test_shipped_laws_in_the_control_map_match_hand_values() -> None:
    curves = InterfaceCurves([0.2, 0.4, 0.6], [22.0, 110.0, 264.0], [20.0, 100.0, 240.0])
    g = CurveFrictionMap.from_law(InterfaceFrictionModel(0.5, 0.2), curves)
    assert [g(x) for x in (0.2, 0.4, 0.6)] == pytest.approx([15.0, 75.0, 180.0], rel=1e-12)
    n = SqueezeCurve([0.2, 0.4, 0.6], [80.0, 160.0, 240.0])       # N = 400 P
    g = CurveFrictionMap.from_law(FrictionModel(0.5), n)
    assert g(np.array([0.25, 0.5])) == pytest.approx([50.0, 100.0], rel=1e-12)
    assert g.inverse(100.0) == pytest.approx(0.5, rel=1e-9)


# -- frozen value types: normalised fields, caches outside equality -----------------------------

def test_value_types_compare_and_hash_by_normalised_fields() -> None:
    a = Structure(10, 8.3, 5, 1.6)
    b = Structure(np.float64(10.0), 8.3, 5.0, 1.6)
    assert a == b and hash(a) == hash(b) and type(a.hole_mm) is float
    c1 = SqueezeCurve(np.array([0.2, 0.4]), np.array([10.0, 30.0]))
    c2 = SqueezeCurve([0.2, 0.4], [10, 30])
    c1(0.3)                                   # builds its interpolant (a cache, not a field)
    assert c1 == c2 and hash(c1) == hash(c2) and c1.pressure_mpa == (0.2, 0.4)
    assert pickle.loads(pickle.dumps(c1))(0.3) == pytest.approx(20.0, rel=1e-12)
    m1 = CurveFrictionMap((0.2, 0.4), (20.0, 60.0), 0.5)
    m2 = CurveFrictionMap((0.2, 0.4), (20.0, 60.0), 0.5)
    m1(0.3)
    assert m1 == m2 and hash(m1) == hash(m2)
    i1 = InterfaceCurves([0.2, 0.6], [22.0, 264.0], [20.0, 240.0], "a")
    i2 = InterfaceCurves(np.array([0.2, 0.6]), [22, 264], [20, 240], "a")
    i1.at([0.4])
    assert i1 == i2 and hash(i1) == hash(i2)
    assert InterfaceFrictionModel(1, 0) == InterfaceFrictionModel(1.0, 0.0)


def test_interface_curves_interpolate_lines_exactly() -> None:
    # S = 440 P + 4, N = 400 P on the nodes: PCHIP reproduces lines, inside and at the edges
    p = np.array([0.2, 0.3, 0.5, 0.6])
    c = InterfaceCurves(p, 440.0 * p + 4.0, 400.0 * p)
    s, n, inside = c.at([0.25, 0.6, 0.603, 0.7])
    assert inside.tolist() == [True, True, True, False]
    x = np.array([0.25, 0.6, 0.603])
    assert s[:3] == pytest.approx(440.0 * x + 4.0, rel=1e-12)
    assert n[:3] == pytest.approx(400.0 * x, rel=1e-12)
    assert np.isnan(s[3]) and np.isnan(n[3])


def test_trial_stress_of_an_invalid_material_is_the_closed_form() -> None:
    # neo-Hookean uniaxial nominal stress 2 C10 (l - l^-2), also for a negative C10 (a trial
    # point of an optimiser, which no HyperelasticModel may hold)
    lam = np.array([0.8, 1.0, 1.5, 2.5])
    for c10 in (0.4, -0.3):
        got = HyperelasticModel.trial_stress_mpa("neo-hookean", (c10,), "uniaxial", lam)
        assert got == pytest.approx(2.0 * c10 * (lam - lam ** -2.0), rel=1e-13, abs=1e-15)
    # Mooney-Rivlin mu = 2 (C10 + C01)
    assert HyperelasticModel.trial_shear_modulus_mpa("mooney-rivlin", (0.3, -0.5)) == \
        pytest.approx(-0.4, rel=1e-15)
    with pytest.raises(InputError):
        HyperelasticModel("neo-hookean", (-0.3,))
