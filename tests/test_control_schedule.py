"""Gain scheduling, hysteresis-aware feedforward and the strategy comparison (issue 17).

Independent references: closed forms (bumpless transfer, gains at a known slope of F = a P^2,
the backlash branches), the plain Controller (constant slope), python-control (closed loop of
PI + first-order lag), and the ordering/2 % band of the comparison (no golden numbers).
"""

from __future__ import annotations

import math

import control as ct
import numpy as np
import pytest

from exofric.control import (
    Controller,
    HysteresisInverse,
    HystereticFrictionMap,
    PIDGains,
    PlantParams,
    PressurePlant,
    ScheduledController,
    StrategyOptions,
    compare_strategies,
    friction_inverse,
    setpoint_profile,
    simulate,
)
from exofric.errors import InputError
from exofric.reproduction import ControlSetup

DT = 0.01
GAINS = PIDGains(kp=0.0017, ki=0.0019, kd=0.00015)


@pytest.mark.parametrize("schedule_on", ["target", "measured"])
@pytest.mark.parametrize("with_ff", [False, True])
def test_constant_slope_equals_plain_controller_exactly(schedule_on, with_ff):
    # Linear map: dF/dP = 400 N/MPa everywhere = slope_ref, so the factor is 1 and the
    # scheduled loop must be bit-identical to the plain Controller's.
    fmap = lambda p: 400.0 * p  # noqa: E731
    ff = (lambda f: f / 400.0) if with_ff else None
    prof = setpoint_profile([(0.0, 60.0), (4.0, 30.0)])
    plain = simulate(Controller(GAINS, feedforward=ff), PlantParams(), fmap, prof,
                     duration_s=8.0)
    sched = ScheduledController(GAINS, fmap, slope_ref_n_per_mpa=400.0,
                                schedule_on=schedule_on, feedforward=ff)
    res = simulate(sched, PlantParams(), fmap, prof, duration_s=8.0)
    assert sched.gain_factor == 1.0 and sched.gains is sched.nominal_gains
    np.testing.assert_array_equal(res.command_mpa, plain.command_mpa)
    np.testing.assert_array_equal(res.friction_n, plain.friction_n)


def test_gains_at_known_slope_of_quadratic_map_and_floor():
    # F = a P^2: the target F sits at P = sqrt(F/a) where dF/dP = 2 sqrt(a F).
    a, ref = 250.0, 300.0
    c = ScheduledController(GAINS, lambda p: a * p * p, slope_ref_n_per_mpa=ref)
    for f in (5.0, 20.0, 60.0):
        c.step(f, 0.0, DT)
        factor = ref / (2.0 * math.sqrt(a * f))
        assert c.operating_pressure_mpa == pytest.approx(math.sqrt(f / a), rel=1e-10)
        assert c.gain_factor == pytest.approx(factor, rel=1e-8)
        assert c.gains.kp == pytest.approx(GAINS.kp * factor, rel=1e-8)
        assert c.gains.ki == pytest.approx(GAINS.ki * factor, rel=1e-8)
        assert c.gains.kd == pytest.approx(GAINS.kd * factor, rel=1e-8)
    # Below contact onset (here P = 0, dF/dP = 0) the floor bounds the gains: 0.1 x ref.
    assert c.factor_at(0.0) == pytest.approx(10.0)
    c2 = ScheduledController(GAINS, lambda p: a * p * p, slope_ref_n_per_mpa=ref,
                             floor_n_per_mpa=60.0)
    assert c2.factor_at(0.0) == pytest.approx(5.0)


def test_bumpless_gain_change_closed_form_pi():
    # PI on F = 100 P^2 scheduled on the measured pressure; same signals on three samples,
    # pressure 0.3 MPa (slope 60) then 0.15 MPa (slope 30): f1 = 1, f2 = 2.
    g = PIDGains(kp=0.002, ki=0.004)
    c = ScheduledController(g, lambda p: 100.0 * p * p, slope_ref_n_per_mpa=60.0,
                            schedule_on="measured", u_max=10.0)
    r, y = 9.0, 4.0
    e = r - y
    u1 = c.step(r, y, DT, pressure_mpa=0.3)
    u2 = c.step(r, y, DT, pressure_mpa=0.15)
    u3 = c.step(r, y, DT, pressure_mpa=0.15)
    assert c.gain_factor == pytest.approx(2.0, rel=1e-9)
    assert u1 == pytest.approx(g.kp * e, rel=1e-12)
    # Bumpless: no jump (f2 - f1) kp e = 0.01 MPa at the switch; only the integral moves.
    assert u2 == pytest.approx(u1 + g.ki * e * DT, rel=1e-9)
    assert u3 == pytest.approx(u2 + 2.0 * g.ki * e * DT, rel=1e-9)


@pytest.mark.parametrize("gains", [GAINS, PIDGains(kp=0.0017, kd=0.00015)])
def test_bumpless_gain_change_closed_form_with_moving_signals(gains):
    # Compared with the old (fixed f1) controller at the switching sample, the scheduled
    # output differs only by (rho - 1) x the change of the P and D terms since the previous
    # sample: u_s - u_old = (rho - 1) [kp1 (e2 - e1) + D2_old - D1] (no jump from the gains).
    fmap = lambda p: 100.0 * p * p  # noqa: E731
    kw = {"slope_ref_n_per_mpa": 60.0, "schedule_on": "measured", "u_max": 10.0}
    s = ScheduledController(gains, fmap, **kw)
    old = Controller(gains, u_max=10.0)            # f1 = 1 at 0.3 MPa: nominal gains
    r, y1, y2 = 9.0, 3.0, 3.5
    assert s.step(r, y1, DT, pressure_mpa=0.3) == old.step(r, y1, DT)
    d1 = old.derivative_mpa
    u_old = old.step(r, y2, DT)
    d2 = old.derivative_mpa
    u_s = s.step(r, y2, DT, pressure_mpa=0.2)      # slope 40: f2 = rho = 1.5
    rho = 1.5
    assert s.gain_factor == pytest.approx(rho, rel=1e-9)
    expected = u_old + (rho - 1.0) * (gains.kp * ((r - y2) - (r - y1)) + d2 - d1)
    assert u_s == pytest.approx(expected, rel=1e-9, abs=1e-15)
    jump = (rho - 1.0) * (gains.kp * (r - y2) + d2)        # what a naive switch would add
    assert abs(jump) > 100 * abs(u_s - expected) + 1e-4


def test_reset_restores_nominal_gains_and_bumpless_start():
    c = ScheduledController(GAINS, lambda p: 100.0 * p * p, slope_ref_n_per_mpa=60.0)
    c.step(2.25, 0.0, DT)
    assert c.gain_factor == pytest.approx(2.0)
    c.reset(output=0.25)
    assert c.gain_factor == 1.0 and c.gains == GAINS
    assert c.step(2.25, 1.0, DT) == pytest.approx(0.25, rel=1e-12)
    assert c.state()["gain_factor"] == pytest.approx(2.0)


def test_scheduled_pi_settles_where_fixed_pi_is_slow_or_oscillates():
    # Cubic map F = 2000 P^3 (slope 9x smaller at 2 N, 3.4x larger at 333 N than at 54 N),
    # PI tuned tight (SIMC tau_c = theta) at 54 N: fixed gains crawl at 2 N and exceed the
    # gain margin (pi) at 333 N; scheduled gains keep the loop of the tuning point.
    t = compare_strategies(PlantParams(), lambda p: 2000.0 * p**3, targets_n=(54.0, 2.0, 333.0),
                           options=StrategyOptions(controllers=("pi",), feedforwards=("none",),
                                                   tune_target_n=54.0, tau_c_s=0.2,
                                                   duration_s=20.0))
    mid = t.get("up 54 N", "pi", "none", False)
    for target in (2.0, 333.0):
        fixed = t.get(f"up {target:g} N", "pi", "none", False)
        sched = t.get(f"up {target:g} N", "pi", "none", True)
        assert sched.settling_time_s is not None
        assert abs(sched.steady_state_error_n) < 0.02 * target
        assert fixed.settling_time_s is None or fixed.settling_time_s > sched.settling_time_s
        # Scheduled: about the settling time of the tuning point (same loop gain).
        assert sched.settling_time_s < 1.5 * mid.settling_time_s
    assert t.get("up 2 N", "pi", "none", True).gain_factor == pytest.approx(9.0, rel=1e-3)


def test_hysteretic_map_is_a_backlash_in_pressure():
    g = lambda p: 100.0 * p  # noqa: E731
    h = HystereticFrictionMap.from_play(g, 0.05)
    ps = [0.3, 0.5, 0.48, 0.42, 0.3, 0.32, 0.45]
    # Reference: play operator x_k = clip(x_{k-1}, P - w, P + w), F = g(x).
    x, ref = 0.0, []
    for p in ps:
        x = min(max(x, p - 0.05), p + 0.05)
        ref.append(g(x))
    np.testing.assert_allclose([h(p) for p in ps], ref, rtol=1e-12)
    h.reset()
    assert h.friction_n == 0.0


def test_hysteresis_inverse_picks_branch_by_direction():
    inv = HysteresisInverse.from_play(lambda p: 100.0 * p, 0.05)
    out = [(round(inv(f), 9), inv.branch) for f in (30.0, 40.0, 30.0, 30.0, 35.0)]
    assert out == [(0.35, "up"), (0.45, "up"), (0.25, "down"), (0.25, "down"), (0.4, "up")]
    curve = {"pressure_mpa": [0.2, 0.4, 0.6, 0.6, 0.4, 0.2],
             "kinetic_n": [10.0, 30.0, 50.0, 56.0, 36.0, 16.0],
             "branch": ["up", "up", "up", "down", "down", "down"]}
    cinv = HysteresisInverse.from_curve(curve)
    # Both branches are straight lines (slope 100 N/MPa): up F = 100 P - 10, down 100 P - 4.
    assert cinv(30.0) == pytest.approx(0.4) and cinv(36.0) == pytest.approx(0.46)
    assert cinv(26.0) == pytest.approx(0.3) and cinv.branch == "down"
    with pytest.raises(InputError, match="down branch"):
        HysteresisInverse.from_curve({k: v[:4] for k, v in curve.items()})


def test_hysteresis_aware_feedforward_removes_the_error_after_a_downward_step():
    # Feedforward only (all gains 0): the friction at the end is what the feedforward
    # pressure gives on the branch the tube is on. Eq 9 map, backlash w = 0.01 MPa.
    g = ControlSetup.default().model_map
    w = 0.01
    prof = setpoint_profile([(0.0, 150.0), (30.0, 54.4)])
    off = PIDGains(0.0)

    def run(ff):
        c = Controller(off, feedforward=ff)
        return simulate(c, PlantParams(), HystereticFrictionMap.from_play(g, w), prof,
                        duration_s=60.0)

    plain = run(lambda f: friction_inverse(g, f))
    aware = run(HysteresisInverse.from_play(g, w))
    sse_plain = 54.4 - plain.friction_n[-1]
    sse_aware = 54.4 - aware.friction_n[-1]
    # Closed form: plain inverse P = g^-1(54.4) on the down branch gives g(P + w).
    p_plain = friction_inverse(g, 54.4)
    assert sse_plain == pytest.approx(54.4 - g(p_plain + w), abs=1e-6)
    assert abs(sse_aware) < 1e-6 < 0.1 < abs(sse_plain)
    # Before the step (rising to 150 N) the plain inverse sits on the up branch: too low.
    i = int(round(29.9 / DT))
    assert aware.friction_n[i] == pytest.approx(150.0, abs=1e-6)
    assert plain.friction_n[i] == pytest.approx(g(friction_inverse(g, 150.0) - w), abs=1e-6)


def test_scheduled_pi_with_linear_map_matches_python_control():
    # PI (constant factor 2 from slope_ref = 2 x the map's slope) on a first-order lag, no
    # delay, no saturation, F = K P: the sampled loop is exactly C(z) G_zoh(z) in feedback.
    k_map, tau = 300.0, 0.5
    g = PIDGains(kp=0.002, ki=0.005)
    plant = PlantParams(time_constant_s=tau, delay_s=0.0, p_max_mpa=10.0)
    c = ScheduledController(g, lambda p: k_map * p, slope_ref_n_per_mpa=2.0 * k_map,
                            u_max=10.0)
    res = simulate(c, PressurePlant(plant), lambda p: k_map * p, 40.0, duration_s=5.0)
    kp, ki = 2.0 * g.kp, 2.0 * g.ki
    cz = ct.tf([kp, ki * DT - kp], [1.0, -1.0], DT)
    gz = ct.c2d(ct.tf([k_map], [tau, 1.0]), DT, "zoh")
    loop = ct.feedback(cz * gz, 1)
    ref = ct.forced_response(loop, res.time_s, np.full(res.time_s.size, 40.0)).outputs
    np.testing.assert_allclose(res.friction_n, ref, rtol=1e-8, atol=1e-9)


def test_simulate_accepts_plant_objects():
    c1, c2 = Controller(GAINS), Controller(GAINS)
    fmap = ControlSetup.default().model_map
    params = PlantParams(noise_n=0.5, seed=3)
    a = simulate(c1, params, fmap, 54.4, duration_s=3.0)
    b = simulate(c2, PressurePlant(params), fmap, 54.4, duration_s=3.0, noise_n=0.5, seed=3)
    np.testing.assert_array_equal(a.friction_n, b.friction_n)
    np.testing.assert_array_equal(a.measured_n, b.measured_n)
    with pytest.raises(InputError, match="p0_mpa"):
        simulate(Controller(GAINS), PressurePlant(params), fmap, 54.4, p0_mpa=0.1)
    with pytest.raises(InputError, match="plant must be"):
        simulate(Controller(GAINS), object(), fmap, 54.4)  # type: ignore[arg-type]


def test_compare_strategies_bad_input():
    s = ControlSetup.default()
    with pytest.raises(InputError, match="feedforward"):
        compare_strategies(s.plant, s.model_map, options=StrategyOptions(feedforwards=("magic",)))
    with pytest.raises(InputError, match="controller"):
        compare_strategies(s.plant, s.model_map, options=StrategyOptions(controllers=("p",)))
    with pytest.raises(InputError, match="onset"):
        compare_strategies(s.plant, lambda p: 0.0, options=StrategyOptions(tune_target_n=10.0))
    with pytest.raises(InputError, match="schedule_on"):
        ScheduledController(GAINS, s.model_map, slope_ref_n_per_mpa=1.0,
                            schedule_on="pressure")  # type: ignore[arg-type]
