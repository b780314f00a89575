"""An integrator removes any constant offset, whatever the feedforward and the model's errors.

Issue 30: PI with the 2-DOF model feedforward held 50.05 N for a 54.4 N target when the
identified plant gain (0.968) entered the pressure model, because the feedback tracked the
model's prediction g(K g^-1(r)) instead of the set-point. The oracle here is the closed-loop
simulation (:func:`exofric.control.simulate`), itself checked against python-control's
discrete-time closed loop (``test_closed_loop_simulation_equals_python_control``) and, with an
exact model, against the closed-form FOPDT response.
"""

from __future__ import annotations

import math

import control as ct
import numpy as np
import pytest
from hypothesis import Phase, given, settings
from hypothesis import strategies as st

from exofric import paper
from exofric.control import (
    Controller,
    CubicFrictionMap,
    ModelFeedforward,
    PIDGains,
    PlantParams,
    ScheduledController,
    fopdt_response,
    local_slope,
    rule_gains,
    simulate,
)
from exofric.friction import CubicFit

DT = 0.01
#: Steady-state band of the acceptance, fraction of the set-point: 0.5 % (issue 30).
BAND = 0.005
MODEL_MAP = CubicFrictionMap(CubicFit(paper.eq8(), 0.2, 0.6), paper.scalar("gamma"))


def _closed_loop(kind: str, mode: str, model: PlantParams, true: PlantParams,
                 gamma_err: float, target: float, *, scheduled: bool = False,
                 duration_s: float = 25.0) -> np.ndarray:
    """Friction (N) of a loop whose controller knows ``model``; the plant is ``true``."""
    true_map = MODEL_MAP.scaled(1.0 + gamma_err)
    p_ff = MODEL_MAP.inverse(target)
    slope = local_slope(MODEL_MAP, p_ff) * model.gain
    gains = rule_gains(kind, slope, model.time_constant_s, model.delay_s).gains
    if mode == "none":
        ff = None
    elif mode == "static":
        ff = ModelFeedforward(MODEL_MAP.inverse, gain=model.gain, p_max_mpa=model.p_max_mpa)
    else:
        ff = ModelFeedforward(MODEL_MAP.inverse, MODEL_MAP, time_constant_s=model.time_constant_s,
                              delay_s=model.delay_s, gain=model.gain, p_max_mpa=model.p_max_mpa)
    # The command range is wide enough for the weakest plant (gain 0.5): the tube pressure
    # itself is bounded by the true plant's p_max (0.6 MPa).
    opts = {"u_max": 1.5, "feedforward": ff}
    ctrl = (ScheduledController(gains, MODEL_MAP, slope_ref_n_per_mpa=local_slope(MODEL_MAP, p_ff),
                                **opts) if scheduled else Controller(gains, **opts))
    sim = simulate(ctrl, true, true_map, target, duration_s=duration_s, dt=DT)
    return sim.friction_n


def _steady(f: np.ndarray) -> float:
    """Mean friction (N) over the last 2 s."""
    return float(np.mean(f[-int(2.0 / DT):]))


def test_identified_gain_in_the_model_no_longer_leaves_an_offset():
    # The case: plant identified from examples/step.csv (gain 0.968, lag 0.349 s, dead
    # time 0.081 s), used both as the model and as the simulated plant; target 54.4 N.
    plant = PlantParams(gain=0.9681, time_constant_s=0.3492, delay_s=0.0809)
    for kind in ("pi", "pid"):
        for mode in ("static", "2dof"):
            f = _closed_loop(kind, mode, plant, plant, 0.0, 54.4, duration_s=15.0)
            assert _steady(f) == pytest.approx(54.4, rel=BAND), (kind, mode)
    # gain 0.9 in model and plant: the issue saw 41.07 N (-24 %)
    plant = PlantParams(gain=0.9)
    f = _closed_loop("pi", "2dof", plant, plant, 0.0, 54.4)
    assert _steady(f) == pytest.approx(54.4, rel=BAND)


def _check_settles(kind, mode, gain_true, model_knows_gain, tau_true, delay_true, gamma_err,
                   target, scheduled):
    model = PlantParams(gain=gain_true if model_knows_gain else 1.0, time_constant_s=0.8,
                        delay_s=0.2)
    true = PlantParams(gain=gain_true, time_constant_s=tau_true, delay_s=delay_true)
    f = _closed_loop(kind, mode, model, true, gamma_err, target, scheduled=scheduled,
                     duration_s=40.0)
    assert _steady(f) == pytest.approx(target, rel=BAND)
    assert np.ptp(f[-int(2.0 / DT):]) < BAND * target          # settled, not oscillating


@settings(max_examples=40, deadline=None, derandomize=True,
          phases=[Phase.explicit, Phase.reuse, Phase.generate])
@given(
    kind=st.sampled_from(["pi", "pid"]),
    mode=st.sampled_from(["none", "static", "2dof"]),
    gain_true=st.floats(0.5, 2.0),
    model_knows_gain=st.booleans(),
    tau_true=st.floats(0.3, 1.2),
    delay_true=st.floats(0.05, 0.25),
    gamma_err=st.floats(-0.3, 0.3),
    target=st.floats(20.0, 60.0),
    scheduled=st.booleans(),
)
def test_integral_action_reaches_the_setpoint_under_any_model_error(
        kind, mode, gain_true, model_knows_gain, tau_true, delay_true, gamma_err, target,
        scheduled):
    # Plant static gains in [0.5, 2] against a model of gain 1 (the default) or of the plant's
    # own gain (an identified plant: the case), plant lags and dead times over the
    # identified ranges (examples/step.csv: 0.35 s, 0.08 s; the default 0.8 s, 0.2 s) against a
    # 0.8 s / 0.2 s model, gamma errors of +-30 %: every PI/PID, with every feedforward,
    # scheduled or not, settles within 0.5 % of the set-point. The target is reachable: it
    # needs at most 0.39 MPa of the 0.6 MPa supply, a command of at most 0.78 of 1.5 MPa.
    _check_settles(kind, mode, gain_true, model_knows_gain, tau_true, delay_true, gamma_err,
                   target, scheduled)


@pytest.mark.parametrize("kind", ["pi", "pid"])
@pytest.mark.parametrize("mode", ["none", "static", "2dof"])
def test_integral_action_at_the_corners_of_the_model_errors(kind, mode):
    # The corners of the same box (random draws rarely reach them): gain 0.5 and 2, the model
    # nominal or identified, the fastest plant with the longest dead time and the slowest with
    # the shortest, gamma -30 % and +30 %, the highest target. (All 768 corners of kind x mode
    # x scheduling x gain x model x (tau, delay) x gamma x target {20, 60} N were run once:
    # worst steady-state error below 0.5 %.)
    for gain_true in (0.5, 2.0):
        for knows in (False, True):
            for tau, delay in ((0.3, 0.25), (1.2, 0.05)):
                for gamma_err in (-0.3, 0.3):
                    _check_settles(kind, mode, gain_true, knows, tau, delay, gamma_err, 60.0,
                                   False)


def test_exact_model_2dof_output_is_the_model_response_in_closed_form():
    # With an exact linear model the 2-DOF reference equals the plant's own response, so the
    # feedback adds nothing and y(t) = k * FOPDT step response of u_ff (closed form).
    k_map, plant = 250.0, PlantParams(gain=0.8, time_constant_s=0.5, delay_s=0.1)
    target = 40.0
    inv, fwd = (lambda f: f / k_map), (lambda p: k_map * p)
    ff = ModelFeedforward(inv, fwd, time_constant_s=0.5, delay_s=0.1, gain=0.8)
    ctrl = Controller(PIDGains(0.004, 0.01), u_max=2.0, feedforward=ff)
    sim = simulate(ctrl, plant, fwd, target, duration_s=5.0, dt=DT)
    u_ff = target / k_map / 0.8
    # At rest under 0 MPa until t = 0, then u_ff held from t = 0 (a sample at -dt carries the 0).
    t = np.r_[-DT, sim.time_s]
    cmd = np.r_[0.0, np.full(sim.time_s.size, u_ff)]
    ref = k_map * fopdt_response(t, cmd, gain=0.8, time_constant_s=0.5, delay_s=0.1)[1:]
    np.testing.assert_allclose(sim.friction_n, ref, atol=1e-9)          # round-off
    np.testing.assert_allclose(sim.command_mpa, u_ff, rtol=1e-12)


def test_closed_loop_simulation_equals_python_control():
    # The oracle checked once: PI on a linear map through a lag with a whole-sample dead time,
    # unsaturated, is the discrete closed loop C G / (1 + C G) with the exact ZOH plant
    # G(z) = k K (1 - a) z^-d / (z - a), a = exp(-dt/tau), and C(z) = kp + ki dt / (z - 1).
    k_map, gain, tau, d = 300.0, 0.9, 0.6, 12
    kp, ki = 0.0015, 0.004
    plant = PlantParams(gain=gain, time_constant_s=tau, delay_s=d * DT, p_max_mpa=10.0)
    c = Controller(PIDGains(kp, ki), u_min=-1e6, u_max=1e6, antiwindup="none")
    sim = simulate(c, plant, lambda p: k_map * p, 30.0, duration_s=6.0, dt=DT)
    a = math.exp(-DT / tau)
    g = ct.tf([k_map * gain * (1 - a)], np.r_[[1.0, -a], np.zeros(d)], DT)
    cz = ct.tf([kp, ki * DT - kp], [1.0, -1.0], DT)
    loop = ct.feedback(cz * g, 1)
    ref = ct.forced_response(loop, sim.time_s, np.full(sim.time_s.size, 30.0)).outputs
    np.testing.assert_allclose(sim.friction_n, ref, rtol=1e-9, atol=1e-9)
