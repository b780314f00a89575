"""The knee lock through a gait cycle (issue 33): energy, ILC, preview, linear parts, data.

Each check has an independent reference: the sign of the lock's power (a brake can only
absorb), the closed-form contraction of model-inverse ILC on a linear plant written here, the
exact cancellation of a pure delay by the preview, python-control's discretisation and
responses, scipy's bounded least squares, and the literature's knee work per stride.
"""

from __future__ import annotations

import math
from importlib.resources import files

import numpy as np
import pytest

from exofric.control import (
    GAIT_CONTROLLERS,
    GaitSetup,
    IterativeLearning,
    PlantModel,
    PressureMPC,
    compare_gait,
    identify_model,
    simulate_gait,
)
from exofric.control._gait_controllers import _moving_average, box_lsq
from exofric.errors import InputError
from exofric.io import gait_data_path, read_gait


@pytest.fixture(scope="module")
def walk():
    return read_gait(gait_data_path())


# ---- energy: the lock only absorbs -----------------------------------------------------------


@pytest.mark.parametrize("controller", GAIT_CONTROLLERS)
def test_lock_power_never_positive(walk, controller: str) -> None:
    r = simulate_gait(walk, GaitSetup(strides=3), controller=controller)
    n = r.time_s.size // 3
    theta = np.tile(np.append(r.knee_angle_rad[:n], r.knee_angle_rad[0]), 1)
    dth = np.tile(np.diff(theta), 3)
    work = r.torque_nm * dth           # J per sample: torque held over the sample x rotation
    # a brake can only absorb: power <= 0 at every step (to round-off of the products)
    assert work.max() <= 1e-12
    assert not r.wrong_direction
    assert all(m.energy_dissipated_j >= 0.0 for m in r.strides)
    np.testing.assert_allclose(sum(m.energy_dissipated_j for m in r.strides), -work.sum(),
                               rtol=1e-9)


def test_static_friction_and_capstan_keep_the_sign(walk) -> None:
    r = simulate_gait(walk, GaitSetup(strides=2, static_ratio=1.5, wrap_deg=90.0, mu_arc=0.15),
                      controller="pid")
    assert not r.wrong_direction


# ---- ILC: closed-form contraction on a linear first-order plant ------------------------------


def _linear_stride(model_true: PlantModel, u: np.ndarray, dt: float) -> np.ndarray:
    """p[k+1] = a p[k] + b u[k - d] from rest (written here, not the code's)."""
    tau, k_gain, d = model_true.time_constant_s, model_true.gain, model_true.delay_s
    a = math.exp(-dt / tau)
    b = (1.0 - a) * k_gain
    nd = int(round(d / dt))
    p = np.zeros(u.size)
    for k in range(u.size - 1):
        p[k + 1] = a * p[k] + (b * u[k - nd] if k >= nd else 0.0)
    return p


@pytest.mark.parametrize(("gamma", "gain_true"), [(0.3, 1.0), (0.7, 1.0), (1.5, 1.0),
                                                  (0.5, 1.2), (0.5, 0.8)])
def test_ilc_contracts_at_the_closed_form_factor(gamma: float, gain_true: float) -> None:
    # Model-inverse ILC, u_{j+1} = u_j + gamma G^-1 e_j. With the true plant G' = (K'/K) G
    # (same lag and delay, gain off by K'/K), e_{j+1} = (1 - gamma K'/K) e_j exactly, for
    # every sample, as long as the reference starts at rest (r(0) = 0).
    dt, n = 0.002, 400
    model = PlantModel(1.0, 0.05, 0.01)
    true = PlantModel(gain_true, 0.05, 0.01)
    t = np.arange(n) * dt
    ref = np.where((t > 0.1) & (t < 0.5), 0.3 * np.sin(np.pi * (t - 0.1) / 0.4) ** 2, 0.0)
    ilc = IterativeLearning(model, dt, n, gain=gamma)
    rho = abs(1.0 - gamma * gain_true)
    errs = []
    for _ in range(6):
        p = _linear_stride(true, ilc.command, dt)
        e = ref - p
        errs.append(e)
        ilc.learn(e)
    for e0, e1 in zip(errs[:-1], errs[1:], strict=True):
        # exact up to round-off (the recursion is linear): 1e-9 of the error's size
        np.testing.assert_allclose(e1, (1.0 - gamma * gain_true) * e0,
                                   atol=1e-9 * np.abs(errs[0]).max())
        assert np.linalg.norm(e1) == pytest.approx(rho * np.linalg.norm(e0), rel=1e-9)
    assert ilc.contraction == pytest.approx(abs(1.0 - gamma))


def test_ilc_lowers_the_error_on_the_default_scenario(walk) -> None:
    r = simulate_gait(walk, GaitSetup(strides=6), controller="ilc")
    rms = [m.rms_error_nm for m in r.strides]
    assert rms[-1] < 0.8 * rms[0]


def test_q_filter_frequency_response_is_the_dirichlet_kernel() -> None:
    # zero-phase moving average of N = 2h + 1 samples: H(w) = sin(N w / 2) / (N sin(w / 2))
    h, n = 3, 256
    k = 5
    x = np.cos(2 * np.pi * k * np.arange(n) / n)
    y = _moving_average(x, h)
    w = 2 * np.pi * k / n
    big_n = 2 * h + 1
    np.testing.assert_allclose(y, x * math.sin(big_n * w / 2) / (big_n * math.sin(w / 2)),
                               atol=1e-12)


# ---- preview on a pure delay: exact --------------------------------------------------------


class _Delay:
    """A pure dead time of ``n + 1`` samples: p(k + 1) = u(k - n)."""

    def __init__(self, n: int) -> None:
        self.buf = [0.0] * n
        self.pressure_mpa = 0.0

    def advance(self, command_mpa: float, dt: float) -> float:
        self.buf.append(command_mpa)
        self.pressure_mpa = self.buf.pop(0)
        return self.pressure_mpa


class _Linear:
    """F = s P with its exact inverse."""

    def __init__(self, s: float) -> None:
        self.s = s

    def __call__(self, p: float) -> float:
        return self.s * max(p, 0.0)

    def inverse(self, f: float) -> float:
        return f / self.s


def test_preview_removes_a_pure_delay_exactly(walk) -> None:
    setup = GaitSetup(strides=2, sensor_delay_s=0.0)
    dt, n = setup.dt_s, 20
    delay = PlantModel(1.0, 0.0, (n + 1) * dt)
    ff, pv = (simulate_gait(walk, setup, controller=c, plant=lambda: _Delay(n),
                            friction=_Linear(400.0), model=delay) for c in ("ff", "preview"))
    # without preview the lock's capacity is the demand's delayed by the dead time, exactly,
    # and it acts against the knee's motion (after the flexion peak: against extension)
    n_s = ff.time_s.size // 2
    late = np.abs(np.roll(ff.demand_nm[:n_s], n + 1))
    dth = np.diff(np.append(ff.knee_angle_rad[:n_s], ff.knee_angle_rad[0]))
    np.testing.assert_allclose(ff.torque_nm[:n_s], -np.sign(dth) * late, atol=1e-12)
    assert ff.strides[-1].rms_error_nm > 1.0
    # latencies: the dead time itself, to one sample
    m = ff.strides[-1]
    assert m.engage_latency_ms == pytest.approx(1e3 * (n + 1) * dt, abs=1e3 * dt + 1e-9)
    assert m.release_latency_ms == pytest.approx(1e3 * (n + 1) * dt, abs=1e3 * dt + 1e-9)
    # the preview commands (n + 1) samples ahead: no error at all
    np.testing.assert_allclose(pv.torque_nm, pv.demand_nm, atol=1e-12)
    assert pv.strides[-1].rms_error_nm < 1e-12


# ---- linear parts against python-control --------------------------------------------------


def test_fopdt_discretisation_matches_python_control() -> None:
    control = pytest.importorskip("control")
    m = PlantModel(0.9, 0.08, 0.0)
    ts = 0.01
    sysd = control.c2d(control.tf([m.gain], [m.time_constant_s, 1.0]), ts, method="zoh")
    a, b, _ = m.discrete(ts)
    num, den = (np.ravel(x[0][0]) for x in control.tfdata(sysd))
    # zoh of K/(tau s + 1): b / (z - a)
    assert num[-1] / den[0] == pytest.approx(b, rel=1e-12)
    assert -den[-1] / den[0] == pytest.approx(a, rel=1e-12)


def test_mpc_prediction_is_the_discrete_step_response() -> None:
    control = pytest.importorskip("control")
    m = PlantModel(1.1, 0.05, 0.0)
    mpc = PressureMPC(m, 0.01, 12, 0.0, 0.6)
    sysd = control.c2d(control.tf([m.gain], [m.time_constant_s, 1.0]), 0.01, method="zoh")
    u = np.linspace(0.1, 0.5, 12)
    resp = control.forced_response(sysd, T=np.arange(13) * 0.01, U=np.append(u, 0.0))
    # row i of the prediction matrix: p_{i+1} from u_0..u_i (from rest)
    np.testing.assert_allclose(mpc.g @ u, np.squeeze(resp.outputs)[1:], rtol=1e-10)


def test_identified_model_of_a_lag_and_delay(walk) -> None:
    control = pytest.importorskip("control")
    from exofric.control import PlantParams, PressurePlant

    tau, d = 0.1, 0.02
    m = identify_model(lambda: PressurePlant(PlantParams(time_constant_s=tau, delay_s=d)),
                       0.3, 0.001)
    # two-point fit of an exact first order + dead time: t2 and t63 of the python-control step
    t = np.arange(0.0, 1.0, 0.001)
    _, y = control.step_response(control.tf([1.0], [tau, 1.0]), T=t)
    t63 = float(t[np.argmax(y >= 1 - math.exp(-1))]) + d
    assert m.gain == pytest.approx(1.0, abs=1e-6)
    assert m.time_constant_s + m.delay_s == pytest.approx(t63, abs=2e-3)   # 1-2 samples


def test_box_lsq_equals_scipy_lsq_linear() -> None:
    from scipy.optimize import lsq_linear

    rng = np.random.default_rng(7)
    for _ in range(100):
        nr, nc = int(rng.integers(6, 40)), int(rng.integers(2, 16))
        nc = min(nc, nr)
        a = rng.normal(size=(nr, nc))
        b = 3.0 * rng.normal(size=nr)
        ref = lsq_linear(a, b, bounds=(-0.2, 0.5), method="bvls", tol=1e-14).x
        np.testing.assert_allclose(box_lsq(a, b, -0.2, 0.5), ref, atol=1e-9)


# ---- the shipped data ------------------------------------------------------------------------


def test_shipped_stride_has_plausible_knee_work(walk) -> None:
    # Level walking: the knee is a net absorber over a stride (Winter, Biomechanics and Motor
    # Control of Human Movement, 4th ed., 2009, Ch. 7: K1, K3, K4 absorb, K2 generates); the
    # knee does ~39-45 % of the leg's negative and ~16-22 % of its positive work at 1-1.5 m/s
    # (Montgomery JR, Grabowski AM, R Soc Open Sci 5:180550, 2018, PMC6124028: knee/leg
    # negative work 0.39-0.45, positive 0.16-0.22 on level ground), i.e. negative/positive
    # ~1.8-2.8 when the leg's positive and negative work balance; allowed 1.5-4 (subjects).
    # Net work per stride -0.1 to -0.6 J/kg (a deliberately wide band).
    mass = walk.body_mass_kg
    net = walk.knee_work_j / mass
    dth = np.diff(walk.knee_angle_rad)
    m_mid = 0.5 * (walk.knee_moment_nm[1:] + walk.knee_moment_nm[:-1])
    w = m_mid * dth
    neg, pos = -w[w < 0].sum(), w[w > 0].sum()
    assert -0.6 < net < -0.1, net                      # measured -0.263 J/kg
    assert 1.5 < neg / pos < 4.0, neg / pos            # measured 2.83
    peak_ext = -walk.knee_moment_nm.min() / mass
    assert 0.3 < peak_ext < 1.5                        # Nm/kg; measured 0.76
    assert walk.stance_fraction == pytest.approx(0.66, abs=0.05)   # ~60 % of the stride


def test_provenance_and_licence_are_packaged() -> None:
    d = files("exofric") / "data" / "gait"
    prov = (d / "PROVENANCE.md").read_text(encoding="utf-8")
    lic = (d / "LICENSE-Apache-2.0.txt").read_text(encoding="utf-8")
    assert "Apache License" in lic and "Version 2.0" in lic
    for key in ("opensim-core", "Apache", "Rajagopal", "heel strike", "85.27"):
        assert key in prov
    assert "Apache-2.0" in gait_data_path().read_text(encoding="utf-8").splitlines()[1]


# ---- bad input -------------------------------------------------------------------------------


def test_cadence_outside_range() -> None:
    for bad in (0.2, 2.5):
        with pytest.raises(InputError) as e:
            GaitSetup(cadence_hz=bad)
        assert e.value.param == "cadence_hz" and "\n" not in str(e.value)


def test_ilc_refuses_non_periodic_data(walk) -> None:
    class Half:
        time_s = walk.time_s[:500]
        knee_angle_rad = walk.knee_angle_rad[:500]
        knee_moment_nm = walk.knee_moment_nm[:500]

    with pytest.raises(InputError) as e:
        simulate_gait(Half(), GaitSetup(strides=2), controller="ilc")
    assert "periodic" in str(e.value) and "\n" not in str(e.value)
    with pytest.warns(UserWarning, match="periodic"):
        simulate_gait(Half(), GaitSetup(strides=1), controller="ff")


def test_unknown_controller_and_no_demand(walk) -> None:
    with pytest.raises(InputError, match="controller must be one of"):
        simulate_gait(walk, controller="bangbang")

    class Flat:
        time_s = np.linspace(0.0, 1.0, 100, endpoint=False)
        knee_angle_rad = 0.3 * np.sin(2 * np.pi * time_s)
        knee_moment_nm = 0.0 * time_s

    with pytest.raises(InputError, match="no demand"):
        simulate_gait(Flat(), controller="ff")


def test_compare_table_and_frames(walk) -> None:
    c = compare_gait(walk, GaitSetup(strides=1), controllers=("ff", "mpc"))
    df = c.to_frame()
    assert list(df["controller"]) == ["ff", "mpc"]
    assert "RMS err" in c.format()
    r = c.results[0]
    assert len(r.to_frame()) == r.time_s.size
    d = r.to_dict()
    assert d["summary"]["1"]["wrong_direction"] is False


def test_example_script() -> None:
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "examples" / "gait_knee.py"
    spec = importlib.util.spec_from_file_location("exofric_example_gait_knee", path)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    # the script's data are the shipped stride: its net work is the trapezoid of M d(theta)
    w = mod.walk
    ref = float(np.sum(0.5 * (w.knee_moment_nm[1:] + w.knee_moment_nm[:-1])
                       * np.diff(w.knee_angle_rad)))
    assert w.knee_work_j == pytest.approx(ref, rel=1e-12)
    assert [r.controller for r in mod.table.results] == list(GAIT_CONTROLLERS)
    # the demand is assist x the moment inside the window, zero outside (by construction of
    # the scenario, checked here against the data resampled independently)
    assert mod.ff.peak_demand_nm == pytest.approx(0.3 * -w.knee_moment_nm[60:260].min(),
                                                  rel=0.02)
    assert not any(r.wrong_direction for r in mod.table.results)


def test_size_valve_picks_the_first_conductance_meeting_the_target(walk) -> None:
    from exofric.control import size_valve

    s = size_valve(walk, GaitSetup(strides=2), controller="ff", conductances=(0.02, 0.4),
                   target_rms_pct=20.0)
    # a 20x larger port fills 20x faster: the error must drop (0.02 barely engages the lock)
    assert s.rms_error_pct[1] < s.rms_error_pct[0]
    ok = [c for c, e in zip(s.conductance, s.rms_error_pct, strict=True) if e <= 20.0]
    assert s.smallest_conductance == (ok[0] if ok else None)
    with pytest.raises(InputError, match="ascending"):
        size_valve(walk, conductances=(0.2, 0.1))


# ---- the command line ------------------------------------------------------------------------


def test_cli_json_keys_per_controller_and_stride(cli) -> None:
    r = cli(["gait", "--strides", "2", "--controller", "ff", "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert {"data", "setup", "plant", "friction", "model", "controllers", "table",
            "paper_fig12_settling_s", "warnings"} <= set(d)
    ff = d["controllers"]["ff"]
    assert len(ff["strides"]) == 2
    assert {"rms_error_nm", "rms_error_pct", "peak_error_nm", "engage_latency_ms",
            "release_latency_ms", "air_nl", "peak_pressure_mpa", "valve_duty",
            "energy_dissipated_j", "wrong_direction"} <= set(ff["strides"][0])
    assert d["paper_fig12_settling_s"]["pi_model"] == 4.20


@pytest.mark.parametrize(("args", "needle"), [
    (["--cadence", "2.5"], "--cadence must be in [0.3, 2] Hz"),
    (["--controller", "bangbang"], "controller must be one of"),
    (["--assist", "1.5"], "assist"),
])
def test_cli_bad_input_one_line_exit_2(capsys, args: list[str], needle: str) -> None:
    from exofric.cli import run

    code = run(["gait", "--strides", "1", *args])
    err = capsys.readouterr().err
    assert code == 2
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and needle in lines[0], err
    assert "Traceback" not in err


def test_cli_data_without_moment(capsys, tmp_path) -> None:
    from exofric.cli import run

    p = tmp_path / "kin.csv"
    t = np.arange(0.0, 1.0, 0.01)
    p.write_text("time_s,knee_angle_deg\n" + "\n".join(f"{x},{30 * math.sin(x)}" for x in t))
    code = run(["gait", "--data", str(p), "--strides", "1"])
    err = capsys.readouterr().err
    assert code == 2 and "no knee moment column" in err and "Traceback" not in err


def test_plot_draws_four_rows_on_a_given_figure(walk) -> None:
    from matplotlib.figure import Figure

    r = simulate_gait(walk, GaitSetup(strides=2), controller="ff")
    fig = r.plot(Figure())
    assert len(fig.axes) == 4
    assert fig.axes[0].get_ylabel() == "knee torque (Nm)"
    # the delivered torque drawn is the result's, over the last strides shown
    line = fig.axes[0].lines[1]
    np.testing.assert_allclose(line.get_ydata(), r.torque_nm)


def test_air_per_stride_is_the_gas_law_fill(walk) -> None:
    # One fill and one vent per stride at constant volume (no tube table): the air drawn is
    # (p_max - p_min) V / (R T) (isothermal ideal gas), in normal litres at 1.185 kg/m^3
    # (ISO 8778). The code sums positive mass increments sample by sample.
    from exofric.control import PneumaticParams

    pp = PneumaticParams()
    r = simulate_gait(walk, GaitSetup(strides=3), controller="ff", plant=pp)
    n = r.time_s.size // 3
    p = r.pressure_mpa[2 * n: 3 * n]
    v_m3 = (pp.line_volume_mm3 + pp.tube_volume_mm3) * 1e-9
    kg = (p.max() - p.min()) * 1e6 * v_m3 / (287.1 * pp.temperature_k)
    # 1 %: the pressure's minimum and the stride's end differ slightly (the vent is slow)
    assert r.strides[-1].air_nl == pytest.approx(kg / 1.185 * 1e3, rel=0.01)
