"""Identification of lag, dead time and gain from noisy step responses (planted truths)."""

from __future__ import annotations

import numpy as np
import pytest

from exofric.control import PlantParams, PressurePlant, fopdt_response, identify_step
from exofric.errors import InputError

TAU, THETA = 0.8, 0.2


@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4])
def test_recovers_planted_lag_and_delay_without_command(seed):
    # Planted truth: 0.4 MPa step at t = 0, tau = 0.8 s, theta = 0.2 s, sampled at 100 Hz
    # with Gaussian sensor noise of 5 kPa (1.25 % of the step). Acceptance: within 5 %.
    rng = np.random.default_rng(seed)
    t = np.arange(-0.5, 6.0, 0.01)
    p = 0.05 + 0.4 * (1.0 - np.exp(-np.clip(t - THETA, 0.0, None) / TAU))
    p = p + rng.normal(0.0, 0.005, t.size)
    r = identify_step(t, p)
    assert r.time_constant_s == pytest.approx(TAU, rel=0.05)
    assert r.delay_s == pytest.approx(THETA, rel=0.05)
    assert r.step_mpa == pytest.approx(0.4, rel=0.02)
    assert r.gain_assumed and r.gain == 1.0
    assert r.r2 > 0.99 and r.rmse_mpa == pytest.approx(0.005, rel=0.15)
    # The reported standard errors are consistent with the actual error (|err| < 4 se).
    assert abs(r.time_constant_s - TAU) < 4 * r.stderr_time_constant_s
    assert abs(r.delay_s - THETA) < 4 * r.stderr_delay_s


@pytest.mark.parametrize("seed", [10, 11, 12])
def test_recovers_gain_lag_delay_with_command_from_simulated_rig(seed):
    # Data from the independent stepping simulator (PressurePlant) with a fractional delay,
    # an up step then a down step; the fit uses the analytic sum of step responses.
    prm = PlantParams(gain=0.93, time_constant_s=0.65, delay_s=0.137)
    pl = PressurePlant(prm, p0_mpa=0.93 * 0.1)
    dt = 0.01
    t = np.arange(0.0, 8.0, dt)
    u = np.where(t < 1.0, 0.1, np.where(t < 4.5, 0.45, 0.2))
    p = np.empty_like(t)
    p[0] = pl.pressure_mpa
    for k in range(1, t.size):
        p[k] = pl.advance(u[k - 1], dt)
    p += np.random.default_rng(seed).normal(0.0, 0.004, t.size)
    r = identify_step(t, p, u)
    assert r.time_constant_s == pytest.approx(0.65, rel=0.05)
    assert r.delay_s == pytest.approx(0.137, rel=0.05)
    assert r.gain == pytest.approx(0.93, rel=0.02)
    assert not r.gain_assumed
    assert r.to_plant().time_constant_s == r.time_constant_s


def test_fopdt_response_matches_stepping_plant():
    # Two independent implementations of the same model agree to round-off.
    prm = PlantParams(gain=1.2, time_constant_s=0.5, delay_s=0.07, p_max_mpa=5.0)
    pl = PressurePlant(prm, p0_mpa=0.12)
    t = np.arange(0.0, 3.0, 0.01)
    u = np.where(t < 0.5, 0.1, 0.3)
    p = [pl.pressure_mpa] + [pl.advance(u[k - 1], 0.01) for k in range(1, t.size)]
    ref = fopdt_response(t, u, gain=1.2, time_constant_s=0.5, delay_s=0.07)
    np.testing.assert_allclose(p, ref, atol=1e-12)


def test_identification_input_errors():
    t = np.linspace(0.0, 1.0, 50)
    with pytest.raises(InputError):
        identify_step(t[:5], t[:5])
    with pytest.raises(InputError, match="t = 0"):
        identify_step(t + 1.0, t)                       # step time not inside the record
    with pytest.raises(InputError, match="never changes"):
        identify_step(t, t, np.ones_like(t))
    with pytest.raises(InputError, match="never changes"):
        identify_step(t - 0.5, np.zeros_like(t))
