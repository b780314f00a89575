"""Step metrics against python-control's step_info and closed forms; ITAE."""

from __future__ import annotations

import math

import control as ct
import numpy as np
import pytest

from exofric.control import PlantParams, itae, step_metrics
from exofric.errors import InputError
from exofric.reproduction import ControlSetup, run_case


@pytest.mark.parametrize(
    "kind,ff,mismatch",
    [("pi", False, 0.0), ("pid", False, 0.0), ("pi", True, 0.0), ("pid", True, 0.1),
     ("pd", True, 0.0), ("pi", False, -0.1)],
)
def test_settling_rise_overshoot_agree_with_python_control(kind, ff, mismatch):
    # Same simulated data, python-control's step_info with yfinal = the target and the same
    # 2 % band / 10-90 % limits. Tolerance: one sample time (0.01 s) for times, as stated in
    # the brief; both use "first sample after the last one outside the band" and "first
    # sample at or beyond the limit", so in practice they agree exactly. Overshoot: 1e-9 %.
    setup = ControlSetup.default(plant=PlantParams(mismatch=mismatch))
    res = run_case(setup, kind, feedforward=ff)
    sim, m = res.simulation, res.metrics
    info = ct.step_info(sim.friction_n, sim.time_s, yfinal=setup.target_n,
                        SettlingTimeThreshold=0.02, RiseTimeLimits=(0.1, 0.9))
    dt = setup.dt
    assert m.settling_time_s is not None
    assert m.settling_time_s == pytest.approx(info["SettlingTime"], abs=dt)
    assert m.rise_time_s == pytest.approx(info["RiseTime"], abs=dt)
    assert m.overshoot_pct == pytest.approx(info["Overshoot"], abs=1e-9)


def test_first_order_closed_forms():
    # y = 1 - exp(-t/tau): rise (10-90 %) = tau ln 9, settling (2 %) = tau ln 50. Sampled at
    # dt, our times are the first sample at/after the exact instants: error in [0, dt).
    tau, dt = 0.7, 0.001
    t = np.arange(0.0, 10.0, dt)
    m = step_metrics(t, 1.0 - np.exp(-t / tau), 1.0)
    assert 0.0 <= m.settling_time_s - tau * math.log(50.0) < dt
    assert abs(m.rise_time_s - tau * math.log(9.0)) < dt
    assert m.overshoot_pct == 0.0
    assert m.steady_state_error_n == pytest.approx(0.0, abs=1e-5)


def test_second_order_overshoot_closed_form_and_downward_step():
    # Underdamped 2nd order: overshoot = 100 exp(-zeta pi / sqrt(1 - zeta^2)) (exact peak);
    # sampled at 1 ms the peak is found within 1e-4 %.
    zeta, wn = 0.3, 4.0
    sys = ct.tf([wn**2], [1.0, 2 * zeta * wn, wn**2])
    t = np.arange(0.0, 10.0, 0.001)
    _, y = ct.step_response(sys, t)
    m = step_metrics(t, y, 1.0)
    exact = 100 * math.exp(-zeta * math.pi / math.sqrt(1 - zeta**2))
    assert m.overshoot_pct == pytest.approx(exact, abs=1e-4)
    # The same response mirrored (a downward step from 5 to 4) has the same metrics.
    md = step_metrics(t, 5.0 - y, 4.0)
    assert md.overshoot_pct == pytest.approx(m.overshoot_pct, rel=1e-12)
    assert md.settling_time_s == m.settling_time_s and md.rise_time_s == m.rise_time_s


def test_never_settled_and_steady_state_error():
    t = np.linspace(0.0, 10.0, 1001)
    y = 40.0 * (1.0 - np.exp(-t))            # ends at 40 N for a 54.4 N target
    m = step_metrics(t, y, 54.4)
    assert m.settling_time_s is None and m.rise_time_s is None
    assert m.steady_state_error_n == pytest.approx(14.4, abs=0.01)
    with pytest.raises(InputError):
        step_metrics(t, y, 0.0)                # no step
    with pytest.raises(InputError):
        step_metrics(t[::-1], y, 1.0)


def test_itae_closed_form():
    # e = exp(-t/T): ITAE = integral t exp(-t/T) dt = T^2 (trapezoid at 1 ms: 1e-6 rel).
    t = np.linspace(0.0, 60.0, 60001)
    assert itae(t, np.exp(-t / 3.0)) == pytest.approx(9.0, rel=1e-6)
