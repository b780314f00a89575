"""The physical pneumatic plant against closed forms and an independent ODE solve.

References (all independent of the plant's integrator):

* charge of a fixed volume through an ISO 6358 orifice, isothermal: the choked phase is a
  straight line of slope k = R T C rho0 p_up sqrt(T0/T) / V; with b = 0 the whole charge is
  p_abs(t) = p_up sin(k t / p_up + asin(p0 / p_up)) (dp/dt = (k/p_up) sqrt(p_up^2 - p^2));
* discharge to the atmosphere p_a: choked p_abs = p0 exp(-K t), K = k / p_up; with b = 0
  p_abs = p_a cosh(acosh(p0 / p_a) - K t);
* b = 0.5: scipy's RK45 (rtol 1e-10) on the same ODE written out here in SI units;
* mass conservation: the flows through the orifices (:meth:`Orifice.mass_flow_kg_per_s`)
  along the plant's trajectory integrate to the change of p_abs V(p) / (R T);
* the FE tube volume: free inflation's inner diameter and the incompressible thick-walled
  cylinder below contact onset.

Units: MPa (gauge unless _abs), mm^3, s, K.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from exofric.control import _pneumatic as pn
from exofric.control._pneumatic import (
    ChargeFit,
    Orifice,
    PneumaticParams,
    PneumaticPlant,
    identify_charge,
    simulate_charge,
    tube_volume_table,
)
from exofric.errors import InputError

R, T0, RHO0, PA = 287.1, 293.15, 1.185, 0.101325   # J/(kg K), K, kg/m^3, MPa abs
V_MM3 = 20000.0
C = 0.1          # dm^3/(s bar)
SUP = 0.6        # MPa gauge


def _params(b: float, *, n: float = 1.0, temp: float = T0, **kw: object) -> PneumaticParams:
    o = Orifice(C, b, laminar_ratio=0.999)
    return PneumaticParams(supply_mpa=SUP, fill=o, vent=o, line_volume_mm3=V_MM3,
                           tube_volume_mm3=0.0, valve="on-off", polytropic_n=n,
                           temperature_k=temp, **kw)  # type: ignore[arg-type]


def _k_mpa_per_s(p_up_abs: float, temp: float = T0, n: float = 1.0) -> float:
    """Choked charge slope in MPa/s, in SI: n R T C rho0 p_up sqrt(T0/T) / V."""
    c_si = C * 1e-3 / 1e5                     # m^3/(s Pa)
    m = c_si * RHO0 * p_up_abs * 1e6 * math.sqrt(T0 / temp)   # kg/s
    return n * R * temp * m / (V_MM3 * 1e-9) / 1e6


def _run(plant: PneumaticPlant, command: float, t: np.ndarray) -> np.ndarray:
    out = [plant.pressure_mpa]
    for a, b in zip(t[:-1], t[1:], strict=True):
        out.append(plant.advance(command, float(b - a)))
    return np.array(out)


def test_constants_are_the_iso_values() -> None:
    assert (pn.RHO0_KG_PER_M3, pn.T0_K, pn.R_AIR_J_PER_KG_K, pn.ATMOSPHERE_MPA) == (
        RHO0, T0, R, PA)


# ---- Orifice --------------------------------------------------------------------------------
def test_orifice_regimes_vectorised_and_signed() -> None:
    o = Orifice(0.2, 0.4, laminar_ratio=0.9999)
    q = 0.2 * 1e-8 * RHO0 * 0.7e6                # choked kg/s at p_up = 0.7 MPa, T = T0
    pd = np.array([0.0, 0.2, 0.28, 0.35, 0.5, 0.7])
    m = o.mass_flow_kg_per_s(0.7, pd)
    r = pd / 0.7
    ref = q * np.where(r <= 0.4, 1.0, np.sqrt(np.clip(1 - ((r - 0.4) / 0.6) ** 2, 0, None)))
    np.testing.assert_allclose(m, ref, rtol=1e-12, atol=1e-18)
    assert m[-1] == 0.0
    # scalar in, float out; reverse flow by sign; temperature
    assert isinstance(o.mass_flow_kg_per_s(0.5, 0.7), float)
    assert o.mass_flow_kg_per_s(0.5, 0.7) == pytest.approx(-o.mass_flow_kg_per_s(0.7, 0.5))
    assert o.mass_flow_kg_per_s(0.7, 0.1, 2 * T0) == pytest.approx(q / math.sqrt(2), rel=1e-12)
    # the scalar path of the plant agrees with the vectorised one
    for p in pd:
        assert o._phi(p / 0.7) * q == pytest.approx(o.mass_flow_kg_per_s(0.7, p), rel=1e-12)


def test_orifice_laminar_range_is_continuous_and_linear() -> None:
    o = Orifice(0.1, 0.3)                       # laminar from r = 0.999
    r = np.array([0.998999999, 0.999, 0.9995, 1.0])
    m = o.mass_flow_kg_per_s(1.0, r)
    assert m[0] == pytest.approx(m[1], rel=1e-4)
    assert m[2] == pytest.approx(0.5 * m[1], rel=1e-12) and m[3] == 0.0


@pytest.mark.parametrize("kw, field", [
    (dict(c_dm3_per_s_bar=0.0), "c_dm3_per_s_bar"), (dict(c_dm3_per_s_bar=0.1, b=1.0), "b"),
    (dict(c_dm3_per_s_bar=0.1, b=0.5, laminar_ratio=0.4), "laminar_ratio"),
])
def test_orifice_rejects_bad_values(kw: dict, field: str) -> None:
    with pytest.raises(InputError, match=field) as e:
        Orifice(**kw)
    assert e.value.param == field


@pytest.mark.parametrize("kw, field", [
    (dict(supply_mpa=0.0), "supply_mpa"), (dict(polytropic_n=1.5), "polytropic_n"),
    (dict(valve="pwm"), "valve"), (dict(proportional_band_mpa=0.0), "proportional_band_mpa"),
    (dict(dead_band_mpa=-1.0), "dead_band_mpa"), (dict(bandwidth_hz=0.0), "bandwidth_hz"),
    (dict(line_volume_mm3=0.0, tube_volume_mm3=0.0), "line_volume_mm3"),
    (dict(tube_table_pressure_mpa=(0.0, 0.1), tube_table_volume_mm3=(5.0, 4.0)),
     "tube_table_volume_mm3"),
    (dict(tube_table_pressure_mpa=(0.0, 0.1), tube_table_volume_mm3=(5.0,)),
     "tube_table_volume_mm3"),
    (dict(fill=0.1), "fill"),
])
def test_params_reject_bad_values(kw: dict, field: str) -> None:
    with pytest.raises(InputError, match=field):
        PneumaticParams(**kw)


def test_params_from_mapping_round_trip() -> None:
    pp = PneumaticParams(fill=Orifice(0.2, 0.4), dead_band_mpa=0.01,
                         tube_table_pressure_mpa=(0.0, 0.3), tube_table_volume_mm3=(2.0e3, 2.5e3))
    assert PneumaticParams.from_mapping(pp.to_dict()) == pp
    with pytest.raises(InputError, match="unknown pneumatic plant key"):
        PneumaticParams.from_mapping({"supply": 0.6})
    with pytest.raises(InputError, match="unknown fill orifice key"):
        PneumaticParams.from_mapping({"fill": {"c": 0.1}})


# ---- charge and discharge against closed forms ---------------------------------------------
def test_choked_charge_is_the_closed_form_line() -> None:
    p_up = SUP + PA
    k = _k_mpa_per_s(p_up)
    t_choke = (0.5 * p_up - PA) / k             # p_abs reaches b p_up
    t = np.linspace(0.0, 0.99 * t_choke, 40)
    p = _run(PneumaticPlant(_params(0.5)), 1.0, t)
    np.testing.assert_allclose(p + PA, PA + k * t, rtol=1e-9)


def test_b0_charge_is_the_closed_form_sine() -> None:
    p_up = SUP + PA
    k = _k_mpa_per_s(p_up)
    phi0 = math.asin(PA / p_up)
    t_end = (math.asin(0.99) - phi0) * p_up / k     # to r = 0.99 (below the laminar range)
    t = np.linspace(0.0, t_end, 200)
    p = _run(PneumaticPlant(_params(0.0)), 1.0, t)
    ref = p_up * np.sin(k * t / p_up + phi0)
    err = np.max(np.abs(p + PA - ref) / ref)
    assert err < 1e-4, err
    # default tolerances give ~1e-6 (measured 1.4e-6)
    assert err < 1e-5


def _ode_si(b: float, fill: bool, n: float = 1.0) -> object:
    """The plant's ODE written out independently in SI units (p in Pa absolute)."""
    c_si = C * 1e-8
    p_up_fill, pa = (SUP + PA) * 1e6, PA * 1e6
    v = V_MM3 * 1e-9

    def rhs(_t: float, y: np.ndarray) -> list[float]:
        p = y[0]
        pu, pdn = (p_up_fill, p) if fill else (p, pa)
        r = pdn / pu
        phi = 1.0 if r <= b else math.sqrt(max(1.0 - ((r - b) / (1.0 - b)) ** 2, 0.0))
        m = c_si * RHO0 * pu * phi
        return [(1.0 if fill else -1.0) * n * R * T0 * m / v]
    return rhs


def test_b05_charge_matches_rk45() -> None:
    t = np.linspace(0.0, 0.15, 101)
    sol = solve_ivp(_ode_si(0.5, True), (0.0, t[-1]), [PA * 1e6], method="RK45", t_eval=t,
                    rtol=1e-10, atol=1e-6)
    ref = sol.y[0] / 1e6
    assert ref[-1] < 0.99 * (SUP + PA)             # the window stays below the laminar range
    p = _run(PneumaticPlant(_params(0.5)), 1.0, t)
    np.testing.assert_allclose(p + PA, ref, rtol=1e-5)


def test_discharge_closed_forms_and_rk45() -> None:
    p0 = 0.5
    kk = _k_mpa_per_s(1.0) / 1.0                 # K = k / p_up in 1/s
    # b = 0.5: choked exponential while p_a / p <= 0.5
    t_ch = math.log((p0 + PA) / (2 * PA)) / kk
    t = np.linspace(0.0, 0.99 * t_ch, 30)
    p = _run(PneumaticPlant(_params(0.5), p0), 0.0, t)
    np.testing.assert_allclose(p + PA, (p0 + PA) * np.exp(-kk * t), rtol=1e-4)
    tight = _run(PneumaticPlant(_params(0.5), p0, rtol=1e-10, atol_mpa=1e-13), 0.0, t)
    np.testing.assert_allclose(tight + PA, (p0 + PA) * np.exp(-kk * t), rtol=1e-6)
    # b = 0: cosh law down to 1.05 p_a
    a0 = math.acosh((p0 + PA) / PA)
    t = np.linspace(0.0, (a0 - math.acosh(1.05)) / kk, 100)
    p = _run(PneumaticPlant(_params(0.0), p0), 0.0, t)
    ref = PA * np.cosh(a0 - kk * t)
    assert np.max(np.abs(p + PA - ref) / ref) < 1e-4      # default rtol
    # b = 0.5 whole discharge vs RK45
    t = np.linspace(0.0, 0.4, 81)
    sol = solve_ivp(_ode_si(0.5, False), (0.0, t[-1]), [(p0 + PA) * 1e6], method="RK45",
                    t_eval=t, rtol=1e-10, atol=1e-6)
    p = _run(PneumaticPlant(_params(0.5), p0), 0.0, t)
    assert sol.y[0][-1] / 1e6 > 1.002 * PA
    np.testing.assert_allclose(p + PA, sol.y[0] / 1e6, rtol=1e-4)


def test_adiabatic_choked_charge_is_n_times_faster() -> None:
    t = np.linspace(0.0, 0.02, 11)              # choked throughout (p_abs < 0.35 MPa)
    iso = _run(PneumaticPlant(_params(0.5, n=1.0)), 1.0, t)
    adi = _run(PneumaticPlant(_params(0.5, n=1.4)), 1.0, t)
    np.testing.assert_allclose(adi[1:] / iso[1:], 1.4, rtol=1e-9)
    assert adi[1] == pytest.approx(_k_mpa_per_s(SUP + PA, n=1.4) * t[1], rel=1e-9)


def test_mass_is_conserved_with_a_compliant_tube() -> None:
    """Fill then vent with V(p) from a table: orifice flows along the trajectory integrate to
    the change of the mass p_abs V(p) / (R T) (isothermal), and to zero net over the cycle."""
    from scipy.integrate import trapezoid
    from scipy.interpolate import PchipInterpolator

    tp, tv = (0.0, 0.1, 0.3, 0.6), (2000.0, 2600.0, 3100.0, 3300.0)
    o = Orifice(C, 0.3)
    pp = PneumaticParams(supply_mpa=SUP, fill=o, vent=o, line_volume_mm3=5000.0,
                         tube_table_pressure_mpa=tp, tube_table_volume_mm3=tv, valve="on-off")
    plant = PneumaticPlant(pp, rtol=1e-9, atol_mpa=1e-12)
    dt, n_fill, n_vent = 2e-4, 2000, 6000
    cmd = np.r_[np.ones(n_fill), np.zeros(n_vent)]
    p = np.array([0.0] + [plant.advance(float(u), dt) for u in cmd])
    vol = 5000.0 + PchipInterpolator(tp, tv)(p)
    mass = (p + PA) * 1e6 * vol * 1e-9 / (R * T0)                        # kg
    m_in = o.mass_flow_kg_per_s(SUP + PA, p + PA)
    m_out = o.mass_flow_kg_per_s(p + PA, PA)
    flow = np.where(np.r_[cmd, 0.0] > 0, m_in, -m_out)
    flow[n_fill] = np.nan                                  # the switch sample: split below
    cum_fill = trapezoid(m_in[: n_fill + 1], dx=dt)
    cum_vent = trapezoid(m_out[n_fill:], dx=dt)
    assert not np.isnan(flow[0])
    scale = mass[n_fill] - mass[0]
    assert cum_fill == pytest.approx(scale, rel=1e-5)
    assert cum_vent == pytest.approx(mass[n_fill] - mass[-1], rel=1e-5)
    assert abs((cum_fill - cum_vent) - (mass[-1] - mass[0])) < 1e-5 * scale
    assert abs(p[-1]) < 1e-3                    # vented back to ~0: net mass ~ 0


def test_volume_and_compliance() -> None:
    pp = PneumaticParams(line_volume_mm3=1000.0, tube_table_pressure_mpa=(0.0, 0.2, 0.4),
                         tube_table_volume_mm3=(2000.0, 2400.0, 2600.0))
    pl = PneumaticPlant(pp)
    v = pl.volume_mm3(np.array([-0.1, 0.0, 0.2, 0.4, 0.6]))
    np.testing.assert_allclose(v, [3000.0, 3000.0, 3400.0, 3600.0, 3600.0 + 0.2 * v[-1] * 0
                                   + 0.2 * pl.compliance_mm3_per_mpa(0.4)])
    dv = pl.compliance_mm3_per_mpa(np.linspace(0.01, 0.39, 9))
    fd = (pl.volume_mm3(np.linspace(0.01, 0.39, 9) + 1e-6)
          - pl.volume_mm3(np.linspace(0.01, 0.39, 9) - 1e-6)) / 2e-6
    np.testing.assert_allclose(dv, fd, rtol=1e-5)
    assert np.all(dv >= 0.0)


# ---- regulator ------------------------------------------------------------------------------
def test_regulator_reaches_the_setpoint_and_dead_band_bounds_the_error() -> None:
    for d in (0.0, 0.01):
        for target, p0 in ((0.3, 0.0), (0.1, 0.4)):
            pl = PneumaticPlant(PneumaticParams(dead_band_mpa=d), p0)
            for _ in range(300):
                p = pl.advance(target, 0.01)
            assert abs(p - target) <= d + 1e-6
            if d > 0:
                assert abs(p - target) == pytest.approx(d, abs=2e-4)   # stops at the band


def test_regulator_hysteresis_branches() -> None:
    """Slow up and down command ramps: the pressure branches are ~hysteresis apart."""
    h = 0.04
    pl = PneumaticPlant(PneumaticParams(hysteresis_mpa=h), 0.0)
    up_u = np.linspace(0.0, 0.5, 1001)
    up = np.array([pl.advance(float(u), 0.01) for u in up_u])      # 0.05 MPa/s
    down_u = up_u[::-1]
    down = np.array([pl.advance(float(u), 0.01) for u in down_u])
    grid = np.linspace(0.15, 0.35, 11)
    gap = np.interp(grid, up, up_u) - np.interp(grid, down[::-1], down_u[::-1])
    # the command needed for a pressure on the way up exceeds the way down by h
    np.testing.assert_allclose(gap, h, rtol=0.05)


def test_regulator_command_filter_slows_the_response() -> None:
    fast = PneumaticPlant(PneumaticParams())
    slow = PneumaticPlant(PneumaticParams(bandwidth_hz=1.0))
    pf = [fast.advance(0.3, 0.01) for _ in range(20)]
    ps = [slow.advance(0.3, 0.01) for _ in range(20)]
    assert ps[-1] < pf[-1]
    for _ in range(300):
        ps.append(slow.advance(0.3, 0.01))
    assert ps[-1] == pytest.approx(0.3, abs=1e-4)


def test_plant_interface_and_bad_input() -> None:
    from exofric.control._simulate import PlantLike

    pl = PneumaticPlant(PneumaticParams())
    assert isinstance(pl, PlantLike)
    pl.advance(0.2, 0.05)
    assert pl.time_s == pytest.approx(0.05)
    with pytest.raises(InputError, match="finite"):
        pl.advance(float("nan"), 0.01)
    with pytest.raises(InputError, match="dt"):
        pl.advance(0.2, 0.0)
    with pytest.raises(InputError, match="p0_mpa"):
        PneumaticPlant(PneumaticParams(), -1.0)


# ---- FE tube volume --------------------------------------------------------------------------
def test_tube_volume_table_against_inflation_and_closed_form() -> None:
    from exofric.fe import MeshSpec
    from exofric.geometry import BASE
    from exofric.material import MooneyRivlin
    from exofric.simulate import inflate, squeeze
    from exofric.simulate._analytic import incompressible_inflation

    mat = MooneyRivlin.from_shore(62.5)
    pres = [0.0, 0.01, 0.02, 0.04]              # below contact onset (0.054 MPa)
    r = squeeze(BASE, mat, pres, mesh=MeshSpec(2, 12), gravity="none")
    assert np.all(r.squeeze_force_n == 0.0) and np.all(r.contact.wall_contact_arc_mm == 0.0)
    p, v = tube_volume_table(r)
    np.testing.assert_array_equal(p, pres)
    length = BASE.length_mm
    assert v[0] == pytest.approx(math.pi * BASE.tube_id_mm**2 / 4 * length, rel=1e-4)
    ri = inflate(BASE.tube_od_mm, BASE.tube_id_mm, mat, pres, mesh=MeshSpec(2, 12))
    np.testing.assert_allclose(v, math.pi * ri.inner_diameter_mm**2 / 4 * length, rtol=1e-4)
    ic = incompressible_inflation(BASE.tube_od_mm, BASE.tube_id_mm, mat.shear_modulus,
                                  np.array(pres))
    np.testing.assert_allclose(v, math.pi * ic.inner_diameter_mm**2 / 4 * length, rtol=1e-3)
    # the volume table drives the plant
    pp = PneumaticParams(tube_table_pressure_mpa=tuple(p), tube_table_volume_mm3=tuple(v))
    assert PneumaticPlant(pp).compliance_mm3_per_mpa(0.015) > 0.0
    # half length: half volume; no displacements: a clear error
    assert tube_volume_table(r, 58.0)[1][2] == pytest.approx(0.5 * v[2])
    r2 = squeeze(BASE, mat, [0.0, 0.01], mesh=MeshSpec(2, 12), gravity="none",
                 keep_fields=False)
    with pytest.raises(InputError, match="keep_fields"):
        tube_volume_table(r2)


# ---- identification ------------------------------------------------------------------------
PLANT = PneumaticParams(fill=Orifice(0.08, 0.3), vent=Orifice(0.05, 0.3))
V_TOT = PLANT.total_volume_mm3(0.0)


def test_identify_charge_noise_free_recovers_c_within_half_percent() -> None:
    df = simulate_charge(PLANT, duration_s=2.0, delay_s=0.015)
    fit = identify_charge(df.time_s, df.pressure_mpa, command_mpa=df.command_mpa,
                          supply_mpa=0.6, volume_mm3=V_TOT)
    assert isinstance(fit, ChargeFit)
    assert fit.c_fill_dm3_per_s_bar == pytest.approx(0.08, rel=5e-3)
    assert fit.c_vent_dm3_per_s_bar == pytest.approx(0.05, rel=5e-3)
    assert fit.delay_s == pytest.approx(0.015, abs=1e-3)
    assert fit.r2 > 0.99999 and fit.fixed == ("volume",)
    # the FOPDT fit beside it: a worse description of the same data
    assert fit.fopdt is not None and fit.fopdt.r2 < fit.r2
    d = fit.to_dict()
    assert d["fopdt"]["time_constant_s"] > 0 and d["fixed"] == ["volume"]
    frame = fit.to_frame()
    assert len(frame) == len(df) and float(frame.residual_mpa.abs().max()) < 1e-4


def test_identify_charge_two_volumes_recovers_c_and_v_with_noise() -> None:
    """Planted C and V from two noisy runs (0.002 MPa, 100 Hz), one with a known 20 cm^3
    reservoir added: within 5 % (measured ~0.3 %); noise-free within 0.5 %."""
    added = 20000.0
    big = PneumaticParams(fill=PLANT.fill, vent=PLANT.vent,
                          line_volume_mm3=PLANT.line_volume_mm3 + added)
    for noise, tol in ((0.002, 0.05), (0.0, 0.005)):
        d1 = simulate_charge(PLANT, duration_s=3.0, noise_mpa=noise, seed=3)
        d2 = simulate_charge(big, duration_s=3.0, noise_mpa=noise, seed=4)
        fit = identify_charge([d1.time_s.to_numpy(), d2.time_s.to_numpy()],
                              [d1.pressure_mpa.to_numpy(), d2.pressure_mpa.to_numpy()],
                              command_mpa=[d1.command_mpa.to_numpy(), d2.command_mpa.to_numpy()],
                              supply_mpa=0.6, added_volume_mm3=[0.0, added])
        assert fit.c_fill_dm3_per_s_bar == pytest.approx(0.08, rel=tol)
        assert fit.c_vent_dm3_per_s_bar == pytest.approx(0.05, rel=tol)
        assert fit.volume_mm3 == pytest.approx(V_TOT, rel=tol)
        assert fit.fixed == () and set(fit.run.tolist()) == {0, 1}
        if noise:
            assert fit.rmse_mpa == pytest.approx(noise, rel=0.2)
            # the standard errors are consistent with the errors
            assert abs(fit.volume_mm3 - V_TOT) < 4 * fit.stderr_volume_mm3


def test_identify_charge_given_c_finds_volume_from_noisy_log() -> None:
    df = simulate_charge(PLANT, duration_s=2.0, noise_mpa=0.002, seed=1)
    fit = identify_charge(df.time_s, df.pressure_mpa, command_mpa=df.command_mpa,
                          supply_mpa=0.6, c_dm3_per_s_bar=0.08)
    assert fit.volume_mm3 == pytest.approx(V_TOT, rel=0.05)
    assert fit.c_vent_dm3_per_s_bar == pytest.approx(0.05, rel=0.05)


def test_identify_charge_fits_b_and_a_single_step_without_command() -> None:
    pp = PneumaticParams(fill=Orifice(0.08, 0.45), vent=Orifice(0.05, 0.45))
    df = simulate_charge(pp, duration_s=1.6, step_s=0.1, fill_s=1.5)
    t = df.time_s.to_numpy() - 0.1
    fit = identify_charge(t, df.pressure_mpa, supply_mpa=0.6, volume_mm3=V_TOT,
                          critical_ratio=0.3, fit_b=True)
    assert fit.b_fitted and fit.critical_ratio == pytest.approx(0.45, abs=0.01)
    assert fit.c_fill_dm3_per_s_bar == pytest.approx(0.08, rel=5e-3)
    assert math.isnan(fit.c_vent_dm3_per_s_bar)


def test_identify_charge_bad_data() -> None:
    df = simulate_charge(PLANT, duration_s=1.0)
    t, p, u = df.time_s.to_numpy(), df.pressure_mpa.to_numpy(), df.command_mpa.to_numpy()
    with pytest.raises(InputError, match="not separately identifiable"):
        identify_charge(t, p, command_mpa=u, supply_mpa=0.6)
    with pytest.raises(InputError, match="above the supply"):
        identify_charge(t, p, command_mpa=u, supply_mpa=0.3, volume_mm3=V_TOT)
    with pytest.raises(InputError, match="no charge or discharge"):
        identify_charge(t, np.zeros_like(p), command_mpa=u, supply_mpa=0.6, volume_mm3=V_TOT)
    with pytest.raises(InputError, match="never switches"):
        identify_charge(t, p, command_mpa=np.zeros_like(u), supply_mpa=0.6, volume_mm3=V_TOT)
    with pytest.raises(InputError, match="at least 10"):
        identify_charge(t[:5], p[:5], command_mpa=u[:5], supply_mpa=0.6, volume_mm3=V_TOT)
    with pytest.raises(InputError, match="added_volume_mm3"):
        identify_charge(t, p, command_mpa=u, supply_mpa=0.6, volume_mm3=V_TOT,
                        added_volume_mm3=[0.0, 1.0])


def test_simulate_charge_log() -> None:
    df = simulate_charge(PLANT, duration_s=1.0, dt_s=0.01, step_s=0.1, fill_s=0.4,
                         delay_s=0.02)
    assert list(df.columns) == ["time_s", "pressure_mpa", "command_mpa"]
    assert df.command_mpa.max() == 0.6 and df.command_mpa.iloc[-1] == 0.0
    # nothing happens before the step plus the valve delay
    assert np.all(df.pressure_mpa[df.time_s <= 0.12 + 1e-9] == 0.0)
    assert df.pressure_mpa[df.time_s > 0.13].iloc[0] > 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        simulate_charge(PLANT, duration_s=0.5, noise_mpa=0.001)
