"""The virtual friction rig: determinism, physics of the log, reduction, CSV round trip."""

from __future__ import annotations

import numpy as np
import pytest

from exofric import paper
from exofric.errors import InputError
from exofric.friction import CubicFit, RigConfig, simulate_rig

EQ8 = CubicFit(paper.eq8(), 0.2, 0.6)
P = np.linspace(0.2, 0.6, 41)
N = EQ8(P)
SET = np.array([0.2, 0.3, 0.4, 0.5, 0.6])


def test_deterministic_with_seed_and_different_without() -> None:
    a = simulate_rig(P, N, 0.7168, SET, seed=3)
    b = simulate_rig(P, N, 0.7168, SET, seed=3)
    c = simulate_rig(P, N, 0.7168, SET, seed=4)
    assert a == b and a.to_csv_text() == b.to_csv_text()
    np.testing.assert_array_equal(a.raw_force_n, b.raw_force_n)
    assert a.friction_n != c.friction_n


def test_noise_free_rig_reproduces_gamma_n_exactly() -> None:
    # Without noise, offset or drift the reduced friction is gamma N(P_set) + drag: the pressure
    # lag (tau 0.3 s) has decayed by exp(-2.95/0.3) = 5e-5 of the 0.1 MPa step when the
    # sliding window starts, so 1e-3 relative bounds what remains of it.
    cfg = RigConfig(noise_pct=0.0, drag_n=2.0)
    run = simulate_rig(P, N, 0.7, SET, config=cfg)
    np.testing.assert_allclose(run.friction_n, 0.7 * EQ8(SET) + 2.0, rtol=1e-3)
    np.testing.assert_allclose(run.pressure_mpa, SET, rtol=1e-3)
    cfg0 = RigConfig(noise_pct=0.0, pressure_tau_s=0.0)
    run0 = simulate_rig(P, N, 0.7, SET, config=cfg0)
    np.testing.assert_allclose(run0.friction_n, 0.7 * EQ8(SET), rtol=1e-12)


def test_rig_between_curve_nodes_against_closed_form() -> None:
    # The test above sets points on the curve's nodes, where interpolation is exact. Here the
    # set points lie midway between the nodes and the truth is Eq 8 itself (np.polyval), not the
    # rig's own curve: noise-free, no lag, the reduced friction is gamma M(P) with M the rig's
    # PCHIP of the samples. Its error vs gamma N(P) is the pointwise interpolation error: < 0.5 %
    # with nodes every 0.05 MPa (measured 0.33 %, largest at the low-force end, see
    # tests/test_friction_fit.py for the bound) and < 1e-6 with 400 nodes (h = 1.0e-3 MPa,
    # set points off the nodes too; O(h^3) predicts ~1e-8).
    cfg = RigConfig(noise_pct=0.0, pressure_tau_s=0.0)
    mid = np.round(np.arange(0.225, 0.576, 0.05), 3)
    exact = 0.7 * np.polyval(paper.eq8(), mid)
    for n_nodes, rtol in ((9, 5e-3), (400, 1e-6)):
        nodes = np.linspace(0.2, 0.6, n_nodes)
        run = simulate_rig(nodes, np.polyval(paper.eq8(), nodes), 0.7, mid, config=cfg)
        np.testing.assert_allclose(run.friction_n, exact, rtol=rtol)


def test_log_shape_and_wire_kinematics() -> None:
    cfg = RigConfig(noise_pct=0.0, pressure_tau_s=0.0, sample_rate_hz=50.0, settle_s=1.0,
                    pull_s=4.0, pull_speed_mm_per_s=2.0, ramp_mm=1.0)
    run = simulate_rig(P, N, 0.7, SET[:2], config=cfg, repeats=2)
    m = int((1.0 + 4.0) * 50)
    assert run.time_s.size == 4 * m                      # 2 set points x 2 repeats
    np.testing.assert_allclose(np.diff(run.time_s), 1 / 50.0, rtol=1e-9)
    x = run.displacement_mm[:m]
    assert x[: 50].max() == 0.0                          # slack while settling
    assert x[-1] == pytest.approx(2.0 * (4.0 - 1 / 50), rel=1e-9)   # v t at the last sample
    f = run.raw_force_n[:m]
    i = 50 + 12                          # 12 samples of pulling: x = 0.24 s x 2 mm/s = 0.48 mm
    assert f[i] == pytest.approx(0.48 * 0.7 * EQ8(0.2), rel=1e-9)     # linear ramp over 1 mm
    assert f[50 + 25] == pytest.approx(0.7 * EQ8(0.2), rel=1e-9)      # sliding from 1 mm on
    assert run.test == ("1", "1", "2", "2")
    assert "test,pressure_mpa,friction_n" in run.to_csv_text()


def test_offset_is_tared_but_drag_is_not() -> None:
    base = RigConfig(noise_pct=0.0, pressure_tau_s=0.0)
    off = RigConfig(noise_pct=0.0, pressure_tau_s=0.0, offset_n=7.0)
    notare = RigConfig(noise_pct=0.0, pressure_tau_s=0.0, offset_n=7.0, tare=False)
    r0 = simulate_rig(P, N, 0.7, SET, config=base)
    np.testing.assert_allclose(simulate_rig(P, N, 0.7, SET, config=off).friction_n,
                               r0.friction_n, atol=1e-9)
    np.testing.assert_allclose(simulate_rig(P, N, 0.7, SET, config=notare).friction_n,
                               np.array(r0.friction_n) + 7.0, atol=1e-9)


def test_drift_leaves_small_residual_after_tare() -> None:
    # Drift d N/s: the tare window centre is at 1.5 s of each 7 s step and the sliding window
    # centre at (2.95 + 7)/2 = 4.975 s, so the residual bias is d x 3.475 s.
    cfg = RigConfig(noise_pct=0.0, pressure_tau_s=0.0, drift_n_per_s=0.1)
    r = simulate_rig(P, N, 0.7, SET, config=cfg)
    bias = np.array(r.friction_n) - 0.7 * EQ8(SET)
    np.testing.assert_allclose(bias, 0.1 * 3.475, rtol=1e-2)


def test_noise_level_of_reduced_points() -> None:
    # 2 % per-sample relative noise averaged over the sliding window (ramp 0.5 s, 10 % discard
    # -> 4.05 s x 100 Hz = 405 samples) leaves 2 %/sqrt(405) = 0.0994 % per point; across 60
    # repeats the sample sd of the relative error should be within 25 % of that.
    run = simulate_rig(P, N, 0.7, SET, seed=9, repeats=60)
    rel = np.array(run.friction_n) / np.array(run.true_friction_n) - 1
    assert np.std(rel, ddof=1) == pytest.approx(0.02 / np.sqrt(405), rel=0.25)
    assert abs(np.mean(rel)) < 3 * 0.02 / np.sqrt(405 * rel.size)


def test_csv_header_is_synthetic_and_to_dict() -> None:
    run = simulate_rig(P, N, 0.7168, SET, seed=1)
    text = run.to_csv_text()
    assert text.startswith("# SYNTHETIC")
    assert "pressure_mpa,friction_n\n" in text
    assert len([ln for ln in text.splitlines() if not ln.startswith("#")]) == 1 + SET.size
    d = run.to_dict()
    assert d["synthetic"] is True and d["n_points"] == SET.size and d["seed"] == 1


def test_rig_input_errors() -> None:
    with pytest.raises(InputError, match="outside the squeeze curve"):
        simulate_rig(P, N, 0.7, [0.1, 0.3])
    with pytest.raises(InputError, match="strictly increasing"):
        simulate_rig(P, N, 0.7, [0.3, 0.3])
    with pytest.raises(InputError, match="gamma_true"):
        simulate_rig(P, N, -1.0, SET)
    with pytest.raises(InputError, match="noise_pct"):
        RigConfig(noise_pct=-1.0)
    with pytest.raises(InputError, match="pull_s is too short"):
        RigConfig(pull_s=0.5, ramp_mm=1.0, pull_speed_mm_per_s=2.0)
    with pytest.raises(InputError, match="repeats"):
        simulate_rig(P, N, 0.7, SET, repeats=0)
    # default set points: the curve's pressures with N > 0
    run = simulate_rig(np.array([0.0, 0.1, 0.2, 0.3]), np.array([0.0, 0.0, 5.0, 9.0]), 0.7)
    assert run.pressure_mpa == pytest.approx((0.2, 0.3), rel=1e-3)
