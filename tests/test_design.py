"""Design search: planted N(P) curves with known answers, the FE check, the CLI and the map."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from exofric.design import DEFAULT_SPACE, parse_sweep, run_sweep, search_designs
from exofric.errors import InputError
from exofric.simulate import squeeze

P = np.round(np.arange(1, 13) * 0.05, 2)   # 0.05 ... 0.6 MPa


def planted(curves: dict[str, np.ndarray], valid: dict[str, bool] | None = None) -> pd.DataFrame:
    """A sweep frame with given N(P) (N) per design name."""
    rows = []
    for i, (name, n) in enumerate(curves.items()):
        rows.append(pd.DataFrame({
            "key": name, "design_index": i, "name": name, "family": "", "status": "ok",
            "pressure_mpa": P, "squeeze_force_n": n, "hole_mm": 10.0 + i, "tube_od_mm": 8.3,
            "tube_id_mm": 4.97, "wire_mm": 1.6, "length_mm": 116.0, "shore": 62.5,
            "deviation_pct": 0.0, "in_validated_region": (valid or {}).get(name, True),
            "contact_onset_pressure_mpa": 0.0, "gamma": 0.7168, "f0_n": 0.0}))
    return pd.concat(rows, ignore_index=True)


def test_linear_curves_are_inverted_exactly():
    # N = a P: PCHIP reproduces a straight line exactly, so P* = N*/a to round-off.
    a = {"a400": 400.0 * P, "a800": 800.0 * P, "a1500": 1500.0 * P}
    s = search_designs(planted(a), 20.0, 0.1, 0.5, gamma=0.8)
    n_star = 20.0 / 0.1 / 0.8                               # 250 N
    t = s.table.set_index("name")
    assert t.loc["a800", "required_pressure_mpa"] == pytest.approx(n_star / 800, rel=1e-12)
    assert t.loc["a1500", "required_pressure_mpa"] == pytest.approx(n_star / 1500, rel=1e-12)
    assert not t.loc["a400", "reaches_target"]            # 400 x 0.5 = 200 N < 250 N
    assert np.isnan(t.loc["a400", "required_pressure_mpa"])
    # T(pmax) = R gamma a pmax, margins by definition
    assert t.loc["a800", "torque_at_pmax_nm"] == pytest.approx(0.1 * 0.8 * 800 * 0.5, rel=1e-12)
    assert t.loc["a800", "pressure_margin_mpa"] == pytest.approx(0.5 - n_star / 800, rel=1e-12)
    assert t.loc["a800", "torque_margin_nm"] == pytest.approx(32.0 - 20.0, rel=1e-12)
    assert [c["name"] for c in s.to_dict()["candidates"]] == ["a1500", "a800"]


def test_quadratic_curves_match_the_analytic_inverse():
    # N = c P^2 (contact-like stiffening), P* = sqrt(N*/c). PCHIP on 0.05 MPa steps has an
    # O(h^3) error: 1e-3 relative bounds it with margin (measured ~4e-5).
    curves = {f"c{c:g}": c * P**2 for c in (600.0, 2000.0, 3000.0)}
    s = search_designs(planted(curves), 30.0, 0.1, 0.6, gamma=0.7168, f0_n=5.0)
    n_star = (30.0 / 0.1 - 5.0) / 0.7168
    for c in (2000.0, 3000.0):
        row = s.table.set_index("name").loc[f"c{c:g}"]
        assert row["required_pressure_mpa"] == pytest.approx(np.sqrt(n_star / c), rel=1e-3)
        assert row["torque_at_pmax_nm"] == pytest.approx(0.1 * (0.7168 * c * 0.36 + 5.0),
                                                         rel=1e-12)   # pmax is a node
    assert s.best["name"] == "c3000" and not s.table.set_index("name").loc["c600",
                                                                           "reaches_target"]


def test_objectives_rank_differently_and_validated_region_is_marked():
    # 'early' reaches 200 N first (linear), 'steep' (cubic) ends higher at pmax.
    curves = {"early": 700.0 * P, "steep": 2400.0 * P**3}
    frame = planted(curves, valid={"early": True, "steep": False})
    by_p = search_designs(frame, 14.0, 0.1, 0.6, gamma=0.7, objective="pressure")
    by_m = search_designs(frame, 14.0, 0.1, 0.6, gamma=0.7, objective="margin")
    assert by_p.best["name"] == "early" and by_m.best["name"] == "steep"
    assert by_m.best["in_validated_region"] is False
    assert by_m.best_validated["name"] == "early"
    only = search_designs(frame, 14.0, 0.1, 0.6, gamma=0.7, objective="margin",
                          validated_only=True)
    assert only.best["name"] == "early" and only.to_dict()["outside_validated"] == 1


def test_target_below_offset_needs_no_pressure_and_bad_inputs():
    frame = planted({"x": 500.0 * P})
    s = search_designs(frame, 0.5, 0.1, 0.6, gamma=0.7, f0_n=10.0)   # 5 N <= F0 = 10 N
    assert s.best["required_pressure_mpa"] == 0.0
    with pytest.raises(InputError, match="pmax_mpa 0.8 MPa is above the sweep.s largest"):
        search_designs(frame, 10.0, 0.1, 0.8)
    with pytest.raises(InputError, match="objective must be one of"):
        search_designs(frame, 10.0, 0.1, 0.6, objective="cheap")
    with pytest.raises(InputError, match="target_torque_nm"):
        search_designs(frame, -1.0, 0.1, 0.6)
    none = search_designs(frame, 1000.0, 0.1, 0.6)
    assert none.best is None and none.to_dict()["reaching"] == 0


def test_bare_design_reaches_the_default_40_nm(cli, tmp_path):
    """`exofric design` without a config finds designs reaching its default 40 Nm (issue 20)."""
    r = cli(["design", "--out", str(tmp_path / "d"), "--no-plot", "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert d["reaching"] >= 1 and d["best"]["torque_at_pmax_nm"] >= 40.0


def test_default_space_parses():
    spec = parse_sweep(DEFAULT_SPACE)
    # 4 x 3 sizes x 2 lengths; d1 = 8.8 leaves no room for d2 >= 1.35
    assert len(spec.designs) == 24 and spec.skipped


@pytest.fixture(scope="module")
def fe_run(tmp_path_factory):
    data = {"pressures_mpa": [0.1, 0.2, 0.3, 0.4, 0.5, 0.6],
            "solver": {"n_radial": 1, "n_circ": 12, "grading": 6.0},
            "grid": {"hole_mm": [10.0], "tube_od_mm": [8.3, 8.8], "wire_mm": [1.1, 1.6]}}
    spec = parse_sweep(data)
    return spec, run_sweep(spec, tmp_path_factory.mktemp("d") / "out", serial=True)


def test_required_pressure_reproduces_the_target_in_a_new_fe_solve(fe_run):
    spec, run = fe_run
    s = search_designs(run.frame, 12.0, 0.1, 0.6)
    best = s.best
    assert best is not None
    d = next(x for x in spec.designs if x.key == best["key"])
    res = squeeze(d.structure(), spec.material.material(d.shore), [best["required_pressure_mpa"]],
                  mesh=spec.solver.mesh(), settings=spec.solver.newton(), keep_fields=False)
    torque = 0.1 * 0.7168 * float(res.squeeze_force_n[0])
    # independent check: the FE solve at P* gives the target torque. Tolerance 2 %:
    # PCHIP interpolation of N(P) between 0.1 MPa steps (measured up to 1.2 % for targets
    # 5-16 Nm on these four designs).
    assert torque == pytest.approx(12.0, rel=0.02)


def test_cli_design_json_and_map(cli, tmp_path):
    cfg = tmp_path / "d.toml"
    cfg.write_text('pressures_mpa = [0.2, 0.4, 0.6]\n[solver]\nn_radial = 1\nn_circ = 12\n'
                   '[grid]\ntube_od_mm = [8.3]\nwire_mm = [1.1, 1.6, 2.0]\n')
    out = tmp_path / "out"
    r = cli(["design", str(cfg), "--target-torque", "12", "--arm", "0.1", "--pmax", "0.6",
             "--gamma", "0.7168", "--out", str(out), "--serial", "--json"])
    assert r.code == 0, r.err
    d = r.json()
    assert d["target_torque_nm"] == 12.0 and d["evaluated"] == 2
    # d2 = 2.0 mm does not fit the 10 mm hole; of 1.1 and 1.6 mm the thicker wire leaves
    # 0.1 mm clearance instead of 0.6 mm, so it is squeezed earlier and harder at every
    # pressure and needs the lower pressure (the objective); it is the base group itself.
    assert d["best"]["name"] == "d1=8.3 d2=1.6" and d["best"]["in_validated_region"] is True
    assert d["sweep"]["skipped"] == 1
    png = out / "design-map.png"
    assert d["plot"] == str(png) and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # margin objective, cached sweep, no plot
    r2 = cli(["design", str(cfg), "--target-torque", "12", "--objective", "margin",
              "--out", str(out), "--no-plot", "--serial", "--json"])
    assert r2.code == 0 and r2.json()["sweep"]["cached"] == 2 and "plot" not in r2.json()
    bad = cli(["design", str(cfg), "--pmax", "0.9", "--out", str(out), "--json"])
    assert bad.code == 2 and "--pmax" in bad.err
