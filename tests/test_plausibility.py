"""Plausibility of data that parses (issue 21, part 2).

Physically impossible data is an error (exit 2); implausible data is a warning, one
``exofric: warning:`` line on stderr and an entry of the ``warnings`` list of ``--json``. The
rules and their thresholds are in :mod:`exofric.defaults` (``PLAUSIBLE_*``); the references
here are constructed data on either side of each threshold and closed forms.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from exofric import defaults
from exofric.calibration import InflationData
from exofric.control import identify_step
from exofric.errors import InputError, PlausibilityWarning
from exofric.friction import SqueezeCurve
from exofric.material import MooneyRivlin

P = np.array([0.1, 0.2, 0.3, 0.4])


def _no_plausibility_warning(fn, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlausibilityWarning)
        return fn(*args, **kwargs)


# ---- inflation data: an inflating tube grows --------------------------------------------------

def test_shrinking_tube_is_refused() -> None:
    with pytest.raises(InputError, match="an inflating tube grows"):
        InflationData(P, np.array([9.0, 8.9, 8.7, 8.5]))


def test_dip_beyond_scatter_warns_and_within_scatter_does_not() -> None:
    tol = defaults.PLAUSIBLE_OD_DROP_REL
    od = np.array([8.5, 8.8, 8.8 * (1 - 2 * tol), 9.3])  # a dip of 1% between 0.2 and 0.3 MPa
    with pytest.warns(PlausibilityWarning, match="between 0.2 and 0.3 MPa"):
        InflationData(P, od)
    od_ok = np.array([8.5, 8.8, 8.8 * (1 - 0.5 * tol), 9.3])  # within the 0.5% scatter
    _no_plausibility_warning(InflationData, P, od_ok)


def test_flat_data_warns() -> None:
    with pytest.warns(PlausibilityWarning, match="does not grow"):
        InflationData(P, np.full(4, 8.3))


# ---- squeeze curves: N grows with P -----------------------------------------------------------

def test_falling_squeeze_curve_is_refused() -> None:
    with pytest.raises(InputError, match="grows with pressure"):
        SqueezeCurve([0.1, 0.3, 0.6], [200.0, 120.0, 40.0])


def test_squeeze_curve_dip_warns_and_a_zero_curve_does_not() -> None:
    with pytest.warns(PlausibilityWarning, match="falls from 100 to 90 N"):
        SqueezeCurve([0.1, 0.3, 0.4, 0.6], [10.0, 100.0, 90.0, 240.0])
    _no_plausibility_warning(SqueezeCurve, [0.01, 0.02], [0.0, 0.0])  # before contact
    _no_plausibility_warning(SqueezeCurve, [0.1, 0.3, 0.6], [10.0, 100.0, 240.0])


# ---- step identification: the model must describe the data -----------------------------------

def test_noise_is_not_a_step_response() -> None:
    t = np.linspace(0.0, 10.0, 300)
    p = 0.3 + 0.01 * np.random.default_rng(3).standard_normal(t.size)
    with pytest.warns(PlausibilityWarning, match="R\\^2"):
        plant = identify_step(t, p)
    assert plant.r2 < defaults.PLAUSIBLE_IDENTIFY_MIN_R2


def test_a_clean_first_order_step_does_not_warn() -> None:
    # closed form of a first-order lag with dead time: 0.4 (1 - exp(-(t - 0.5) / 1.2)) MPa
    t = np.linspace(0.0, 10.0, 300)
    p = np.where(t > 0.5, 0.4 * (1.0 - np.exp(-(t - 0.5) / 1.2)), 0.0)
    p = p + 0.002 * np.random.default_rng(4).standard_normal(t.size)
    plant = _no_plausibility_warning(identify_step, t, p)
    assert plant.r2 > 0.99
    assert plant.time_constant_s == pytest.approx(1.2, rel=0.05)


# ---- materials: nearly incompressible ---------------------------------------------------------

def _poisson(c10: float, c01: float, d: float) -> float:
    """Small-strain Poisson ratio from K = 2/d and mu = 2 (c10 + c01) (linear elasticity)."""
    k, mu = 2.0 / d, 2.0 * (c10 + c01)
    return (3 * k - 2 * mu) / (2 * (3 * k + mu))


def test_negative_poisson_is_refused_and_a_compressible_one_warns() -> None:
    c10, c01 = 0.635, 0.032
    d_zero = 3.0 / (2.0 * (c10 + c01))  # nu = 0 exactly
    assert _poisson(c10, c01, 1.01 * d_zero) < 0.0
    with pytest.raises(InputError, match="Poisson ratio"):
        MooneyRivlin(c10, c01, 1.01 * d_zero)
    d_soft = 0.5  # nu ~ 0.35 for these constants
    assert 0.0 < _poisson(c10, c01, d_soft) < defaults.PLAUSIBLE_POISSON_MIN
    with pytest.warns(PlausibilityWarning, match="Poisson ratio"):
        MooneyRivlin(c10, c01, d_soft)
    _no_plausibility_warning(MooneyRivlin.from_shore, 62.5)  # the paper's 0.498


# ---- the CLI: one line, exit codes, the --json warnings list ------------------------------------

def _csv(path: Path, rows: list[tuple[float, float]], header: str) -> Path:
    path.write_text(header + "\n" + "\n".join(f"{a},{b}" for a, b in rows) + "\n")
    return path


def test_cli_calibrate_refuses_and_warns(cli, tmp_path: Path) -> None:
    head = "pressure_mpa,outer_diameter_mm"
    bad = _csv(tmp_path / "shrink.csv", [(0.1, 9.0), (0.2, 8.8), (0.3, 8.5)], head)
    r = cli(["calibrate", "--data", str(bad), "--tube-od", "8.3", "--tube-id", "4.97",
             "--method", "bounded"])
    assert r.code == 2 and r.err.strip().count("\n") == 0 and "grows" in r.err
    dip = _csv(tmp_path / "dip.csv", [(0.1, 8.5), (0.2, 8.8), (0.3, 8.7), (0.4, 9.3)], head)
    r = cli(["calibrate", "--data", str(dip), "--tube-od", "8.3", "--tube-id", "4.97",
             "--method", "bounded", "--json"])
    assert r.code == 0
    assert r.err.count("exofric: warning:") == 1 and "Traceback" not in r.err
    assert any("between 0.2 and 0.3 MPa" in w for w in r.json()["warnings"])


def test_cli_identify_noise_warns_in_json(cli, tmp_path: Path) -> None:
    t = np.linspace(0.0, 10.0, 200)
    p = 0.3 + 0.01 * np.random.default_rng(1).standard_normal(t.size)
    f = _csv(tmp_path / "noise.csv", list(zip(t, p, strict=True)), "time_s,pressure_mpa")
    r = cli(["control", "identify", str(f), "--json"])
    assert r.code == 0
    assert any("R^2" in w for w in r.json()["warnings"])
