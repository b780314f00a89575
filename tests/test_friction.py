"""Friction model core: FrictionModel, CubicFit (Eq 8), inverse (Eq 9), curve inverse, torque."""

from __future__ import annotations

import numpy as np
import pytest

from exofric import paper
from exofric.errors import InputError
from exofric.friction import CubicFit, FrictionModel, SqueezeCurve, pressure_for_friction, torque

EQ8 = paper.eq8()


def test_friction_model_forward_and_back() -> None:
    m = FrictionModel(0.7168, 3.0)
    n = np.array([0.0, 10.0, 268.55])
    # exact arithmetic: gamma N + F0, and its inverse; 1e-12 is float rounding only
    np.testing.assert_allclose(m.friction(n), 0.7168 * n + 3.0, rtol=1e-14)
    np.testing.assert_allclose(m.squeeze(m.friction(n)), n, atol=1e-12)
    assert isinstance(m.friction(1.0), float)
    assert m.to_dict() == {"gamma": 0.7168, "f0_n": 3.0}
    with pytest.raises(InputError, match="gamma"):
        FrictionModel(0.0)
    with pytest.raises(InputError, match="gamma"):
        FrictionModel(float("nan"))


def test_cubic_fit_recovers_eq8_coefficients() -> None:
    # Acceptance: data generated from Eq 8 over its fit range 0.2-0.6 MPa are fitted back to
    # Eq 8's coefficients within 1e-6 relative (exact data; only conditioning error remains).
    p = np.linspace(0.2, 0.6, 17)
    fit = CubicFit.fit(p, np.polyval(EQ8, p))
    np.testing.assert_allclose(fit.coefficients, EQ8, rtol=1e-6)
    assert fit.r2 == pytest.approx(1.0, abs=1e-12)
    assert (fit.p_min_mpa, fit.p_max_mpa) == (0.2, 0.6)


def test_cubic_fit_matches_numpy_polyfit_on_noisy_data_and_r2() -> None:
    # Independent reference: numpy.polyfit (plain Vandermonde least squares) and the
    # textbook R^2 = 1 - SSres/SStot computed here.
    rng = np.random.default_rng(3)
    p = np.linspace(0.1, 0.7, 25)
    y = np.polyval(EQ8, p) + rng.normal(0.0, 3.0, p.size)
    fit = CubicFit.fit(p, y)
    ref = np.polyfit(p, y, 3)
    np.testing.assert_allclose(fit.coefficients, ref, rtol=1e-8)
    r2 = 1 - np.sum((y - np.polyval(ref, p)) ** 2) / np.sum((y - y.mean()) ** 2)
    assert fit.r2 == pytest.approx(r2, rel=1e-10)
    assert 0.99 < fit.r2 < 1.0


def test_cubic_fit_range_restricts_points() -> None:
    p = np.linspace(0.0, 0.8, 33)
    y = np.where(p < 0.15, 0.0, np.polyval(EQ8, p))      # flat before contact
    fit = CubicFit.fit(p, y, (0.2, 0.6))
    np.testing.assert_allclose(fit.coefficients, EQ8, rtol=1e-6)
    assert (fit.p_min_mpa, fit.p_max_mpa) == (0.2, 0.6)
    with pytest.raises(InputError, match="at least 4"):
        CubicFit.fit([0.1, 0.2, 0.3], [1, 2, 3])
    with pytest.raises(InputError, match="same length"):
        CubicFit.fit([0.1, 0.2, 0.3, 0.4], [1, 2, 3])
    with pytest.raises(InputError, match="finite"):
        CubicFit.fit([0.1, 0.2, 0.3, np.nan], [1, 2, 3, 4])


def test_cubic_call_float_and_array() -> None:
    c = CubicFit(EQ8, 0.2, 0.6)
    assert isinstance(c(0.3), float)
    # Horner by hand at 0.3 MPa
    hand = ((EQ8[0] * 0.3 + EQ8[1]) * 0.3 + EQ8[2]) * 0.3 + EQ8[3]
    assert c(0.3) == pytest.approx(hand, rel=1e-14)
    out = c(np.array([0.2, 0.3]))
    assert isinstance(out, np.ndarray) and out.shape == (2,)


def test_paper_inverse_example_0293_not_026() -> None:
    # Sec. 5: F = 54.40 N with Eq 9 = 0.7168 x Eq 8. N = 54.40/0.7168 = 75.893 N -> 0.2926 MPa.
    # The printed 0.26 MPa is where N (not F) equals 54.40 N.
    c = CubicFit(EQ8, 0.2, 0.6)
    p = pressure_for_friction(54.40, c, FrictionModel(0.7168))
    assert p == pytest.approx(0.293, abs=1e-3)
    assert 0.7168 * c(p) == pytest.approx(54.40, rel=1e-12)      # round trip through Eq 9
    # reference: the root of Eq 8 = 54.40 N in [0.2, 0.6] MPa by np.roots (0.2586, printed 0.26)
    roots = np.roots(np.array(EQ8) - np.array([0.0, 0.0, 0.0, 54.40]))
    root = [r.real for r in roots if abs(r.imag) < 1e-12 and 0.2 <= r.real <= 0.6]
    assert len(root) == 1 and c.inverse(54.40) == pytest.approx(root[0], abs=1e-9)
    assert round(c.inverse(54.40), 2) == paper.scalar("target_pressure_mpa")
    # same via the Eq 9 cubic itself
    assert c.scaled(0.7168).inverse(54.40) == pytest.approx(p, rel=1e-12)


def test_inverse_refuses_out_of_range_and_non_monotonic() -> None:
    c = CubicFit(EQ8, 0.2, 0.6)
    lo, hi = c(0.2), c(0.6)
    assert c.inverse(lo) == 0.2 and c.inverse(hi) == 0.6
    with pytest.raises(InputError, match="outside"):
        c.inverse(hi + 0.01)
    with pytest.raises(InputError, match="outside the reachable range"):
        pressure_for_friction(1000.0, c, FrictionModel(0.7168))
    # Eq 8 has a maximum at P = 0.766 MPa (root of N'), so over [0.2, 0.9] it is not monotonic
    wide = CubicFit(EQ8, 0.2, 0.9)
    assert wide.monotonic_sign() == 0
    with pytest.raises(InputError, match="not monotonic"):
        wide.inverse(100.0)
    # decreasing cubic is fine
    dec = CubicFit((0.0, 0.0, -2.0, 1.0), 0.0, 0.4)
    assert dec.monotonic_sign() == -1
    assert dec.inverse(0.6) == pytest.approx(0.2, abs=1e-13)
    # y = (P - 0.3)^3: y' = 0 at 0.3 only (double root), still strictly increasing
    c3 = CubicFit.fit(np.linspace(0, 0.6, 7), (np.linspace(0, 0.6, 7) - 0.3) ** 3)
    assert c3.monotonic_sign() == 1
    assert c3.inverse(0.001) == pytest.approx(0.4, abs=1e-6)


def test_cubic_validation_and_to_dict() -> None:
    with pytest.raises(InputError, match="p_min < p_max"):
        CubicFit(EQ8, 0.6, 0.2)
    with pytest.raises(InputError, match="4 numbers"):
        CubicFit((1.0, 2.0, 3.0), 0.2, 0.6)  # type: ignore[arg-type]
    d = CubicFit(EQ8, 0.2, 0.6, 0.999).to_dict()
    assert d == {"coefficients": list(EQ8), "p_min_mpa": 0.2, "p_max_mpa": 0.6, "r2": 0.999}


def test_curve_inverse_exact_on_fe_like_curve() -> None:
    # A curve with zero force before contact at 0.15 MPa: the inverse reproduces the tabulated
    # nodes, gives the onset for N = 0, and is close to the smooth curve it samples.
    p = np.linspace(0.0, 0.6, 25)
    n = 600.0 * np.clip(p - 0.15, 0.0, None) ** 1.5
    c = SqueezeCurve(p, n)
    assert c.pressure(0.0) == pytest.approx(0.15)               # end of the zero plateau
    for pi, ni in zip(p[7:], n[7:], strict=True):
        assert c.pressure(ni) == pytest.approx(pi, abs=1e-12)
    # between nodes: the sampled curve's inverse is 0.15 + (N/600)^(2/3); PCHIP error < 2e-3
    target = 100.0
    exact = 0.15 + (target / 600.0) ** (2 / 3)
    assert c.pressure(target) == pytest.approx(exact, abs=2e-3)
    m = FrictionModel(0.7, 2.0)
    assert c.pressure_for_friction(0.7 * target + 2.0, m) == pytest.approx(c.pressure(target))
    with pytest.raises(InputError, match="outside the curve's range"):
        c.pressure_for_friction(1e4, m)


def test_torque_paper_numbers() -> None:
    # Sec. 3.2: 180.49 N x 0.10 m = 18.049 Nm (printed 18.05); Sec. 4: 300 N -> 30 Nm
    assert torque(180.49).torque_nm == pytest.approx(paper.scalar("base_friction_moment_nm"),
                                                     abs=5e-3)
    t = torque(300.0, 0.10, (0.0, 40.0))
    assert t.torque_nm == pytest.approx(30.0)
    assert not t.meets_max and t.coverage_pct == pytest.approx(75.0)
    assert torque(450.0).meets_max
    assert torque(450.0).to_dict()["torque_nm"] == pytest.approx(45.0)
    with pytest.raises(InputError, match="arm_radius_m"):
        torque(100.0, 0.0)
