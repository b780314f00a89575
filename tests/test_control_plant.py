"""Plant models: lag + dead time + saturation + PWM against closed forms; friction maps."""

from __future__ import annotations

import math

import numpy as np
import pytest

from exofric import paper
from exofric.control import (
    CubicFrictionMap,
    CurveFrictionMap,
    PlantParams,
    PressurePlant,
    local_slope,
    simulate,
)
from exofric.errors import InputError
from exofric.friction import CubicFit


@pytest.fixture
def eq9() -> CubicFrictionMap:
    return CubicFrictionMap(CubicFit(paper.eq8(), 0.2, 0.6), paper.scalar("gamma"))


@pytest.mark.parametrize("delay", [0.0, 0.2, 0.123])
def test_lag_delay_matches_analytic_step(delay):
    # Reference: p(t) = K u (1 - exp(-(t - theta)/tau)) for t > theta, 0 before. The update
    # is exact for piecewise-constant input (also for a delay that is not a multiple of dt),
    # so only round-off remains: tolerance 1e-12 MPa.
    prm = PlantParams(gain=0.9, time_constant_s=0.8, delay_s=delay)
    pl = PressurePlant(prm)
    dt, u = 0.01, 0.5
    got = np.array([pl.advance(u, dt) for _ in range(400)])
    t = dt * np.arange(1, 401)
    ref = 0.9 * u * (1.0 - np.exp(-np.clip(t - delay, 0.0, None) / 0.8))
    np.testing.assert_allclose(got, ref, atol=1e-12)


def test_saturation_limits_pressure():
    pl = PressurePlant(PlantParams(time_constant_s=0.1, delay_s=0.0, p_max_mpa=0.6))
    for _ in range(400):                       # 40 tau: e^-40 ~ 4e-18
        p = pl.advance(5.0, 0.01)
    assert p == pytest.approx(0.6, abs=1e-12) and p <= 0.6
    for _ in range(400):
        p = pl.advance(-5.0, 0.01)
    assert p == pytest.approx(0.0, abs=1e-12) and p >= 0.0


def test_pwm_periodic_steady_state_matches_closed_form():
    # 3/2 valves: inflate to Ps for d T, exhaust to 0 for (1-d) T. The periodic steady state
    # at the start of each period is p0 = Ps b (1 - a)/(1 - a b), a = e^{-dT/tau},
    # b = e^{-(1-d)T/tau} (derived in the module notes); and the time-mean is d Ps.
    ps, tau, T, d = 0.6, 0.8, 0.02, 0.4
    # Dead time of 3 whole periods, so samples fall at the start of an inflate phase.
    pl = PressurePlant(PlantParams(time_constant_s=tau, delay_s=3 * T, p_max_mpa=ps,
                                   pwm_period_s=T))
    for _ in range(2000):                      # 40 s = 50 tau: periodic to round-off
        p = pl.advance(d * ps, T)
    a, b = math.exp(-d * T / tau), math.exp(-(1 - d) * T / tau)
    assert p == pytest.approx(ps * b * (1 - a) / (1 - a * b), rel=1e-10)
    # The mean of a first-order response to a periodic input equals the input's mean; the
    # sampled value is the ripple minimum, within the ripple ~ Ps T/tau = 0.015 MPa of d Ps.
    assert abs(p - d * ps) < ps * T / tau


def test_pwm_loop_requires_period_equal_to_dt():
    with pytest.raises(InputError, match="pwm_period_s"):
        simulate(_const_controller(0.3), PlantParams(pwm_period_s=0.02), lambda p: p, 1.0,
                 duration_s=1.0, dt=0.01)


def _const_controller(u: float):
    from exofric.control import Controller, PIDGains

    return Controller(PIDGains(0.0), bias_mpa=u)


def test_sensor_noise_is_seeded_and_has_the_set_std():
    prm = PlantParams(noise_n=2.0, seed=7)
    r1 = simulate(_const_controller(0.3), prm, lambda p: 100.0 * p, 30.0, duration_s=20.0)
    r2 = simulate(_const_controller(0.3), prm, lambda p: 100.0 * p, 30.0, duration_s=20.0)
    np.testing.assert_array_equal(r1.measured_n, r2.measured_n)
    noise = r1.measured_n - r1.friction_n
    # 2001 samples: the sample std is within 3 x 2/sqrt(2*2000) = 0.095 N of 2 N (3 sigma).
    assert noise.std() == pytest.approx(2.0, abs=0.095)


def test_plant_params_validation_and_mapping():
    assert PlantParams.from_mapping({"delay_s": 0.1}).delay_s == 0.1
    with pytest.raises(InputError, match="unknown plant key"):
        PlantParams.from_mapping({"tau": 1.0})
    for bad in ({"time_constant_s": 0.0}, {"delay_s": -1.0}, {"mismatch": -1.0},
                {"noise_n": float("nan")}, {"seed": 1.5}):
        with pytest.raises(InputError):
            PlantParams.from_mapping(bad)


def test_eq9_map_inside_fit_and_clipping(eq9):
    # Inside 0.2-0.6 MPa the map is gamma x Eq 8 (Eq 9): e.g. F(0.6) = 0.7168 x 286.6865 N
    # (by hand: -1957.4 x 0.216 + 2412.8 x 0.36 - 251.95 x 0.6 - 7.9531).
    c = paper.eq8()
    for p in (0.2, 0.3, 0.45, 0.6):
        assert eq9(p) == pytest.approx(0.7168 * np.polyval(c, p), rel=1e-12)
    assert eq9(0.6) == pytest.approx(0.7168 * 286.6865, rel=1e-12)
    # Contact onset: the real root of Eq 8 below 0.2 MPa; F = 0 below it, continuous at it.
    roots = np.roots(c)
    onset = float(min(r.real for r in roots if abs(r.imag) < 1e-12 and 0 < r.real < 0.2))
    assert onset == pytest.approx(0.1441, abs=1e-3)
    assert eq9(onset - 1e-6) == 0.0 and eq9(0.0) == 0.0
    assert eq9(onset + 1e-6) == pytest.approx(0.0, abs=1e-3)
    # Vector and scalar agree; non-decreasing on 0..0.8 MPa (linear extension above 0.6).
    p = np.linspace(0.0, 0.8, 801)
    f = eq9(p)
    np.testing.assert_allclose(f, [eq9(float(x)) for x in p], rtol=1e-12, atol=1e-12)
    assert np.all(np.diff(f) >= 0)
    # Above 0.6 MPa: a line with Eq 9's end slope gamma dN/dP(0.6) (numpy's polyder of Eq 8;
    # central difference on a line: exact up to round-off, 1e-8 relative).
    end_slope = 0.7168 * float(np.polyval(np.polyder(c), 0.6))
    assert local_slope(eq9, 0.7) == pytest.approx(end_slope, rel=1e-8)


def test_eq9_inverse_and_mismatch(eq9):
    # Reference: the root of 0.7168 x Eq 8 = 54.40 N in [0.2, 0.6] MPa by np.roots
    # (0.29265 MPa; the paper prints 0.26). Bracketing tolerance of the inverse: 1e-9 MPa.
    c = 0.7168 * np.array(paper.eq8()) - np.array([0.0, 0.0, 0.0, 54.40])
    root = [r.real for r in np.roots(c) if abs(r.imag) < 1e-12 and 0.2 <= r.real <= 0.6]
    assert len(root) == 1 and eq9.inverse(54.40) == pytest.approx(root[0], abs=1e-9)
    for f in (20.0, 54.4, 150.0, 200.0):
        assert eq9(eq9.inverse(f)) == pytest.approx(f, rel=1e-10)
    true = eq9.scaled(1.1)
    assert true(0.4) == pytest.approx(1.1 * eq9(0.4), rel=1e-12)
    with pytest.raises(InputError, match="outside"):
        eq9.inverse(300.0)


def test_curve_map_reproduces_sampled_cubic(eq9):
    # A curve sampled from Eq 8 every 0.05 MPa: PCHIP between nodes stays within 1% of the
    # cubic (smooth data, 9 nodes); its inverse is exact at the nodes.
    p = np.linspace(0.2, 0.6, 9)
    n = np.polyval(paper.eq8(), p)
    curve = CurveFrictionMap(tuple(p), tuple(n), paper.scalar("gamma"))
    x = np.linspace(0.2, 0.6, 81)
    np.testing.assert_allclose(curve(x), eq9(x), rtol=1e-2)
    assert curve.inverse(float(eq9(0.4))) == pytest.approx(0.4, abs=1e-9)
    assert curve(0.0) == 0.0 and curve(0.1) >= 0.0         # prepended (0, 0), clipped
    assert curve(0.7) > curve(0.6)                           # linear extension
    with pytest.raises(InputError):
        CurveFrictionMap((0.2, 0.1), (1.0, 2.0), 0.7)
