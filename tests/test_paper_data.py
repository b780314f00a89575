"""The shipped paper data: complete, internally consistent where the paper is."""

from __future__ import annotations

import math

import pytest

from exofric import paper


def test_scalars_present_with_provenance():
    raw = paper.load()["scalars"]
    for key in [
        "gamma",
        "gamma_relative_error_pct",
        "base_friction_at_0_6_mpa_n",
        "base_squeeze_force_at_0_6_mpa_n",
        "test3_max_friction_n",
        "tube_length_mm",
        "arm_radius_m",
        "target_friction_n",
        "target_pressure_mpa",
        "settling_pd_model_s",
        "settling_pi_s",
        "settling_pi_model_s",
        "settling_pid_s",
        "settling_pid_model_s",
        "knee_torque_max_nm",
    ]:
        assert key in raw and raw[key]["provenance"]
    assert paper.scalar("gamma") == 0.7168
    assert paper.scalar("base_squeeze_force_at_0_6_mpa_n") == 268.55


def test_reported_arithmetic_the_paper_gets_right():
    # 180.49 N x 0.10 m = 18.05 Nm (Section 3.2); 300 N x 0.1 m = 30 Nm (Section 4).
    assert paper.scalar("base_friction_at_0_6_mpa_n") * paper.scalar(
        "arm_radius_m"
    ) == pytest.approx(paper.scalar("base_friction_moment_nm"), abs=0.005)
    assert paper.scalar("test3_max_friction_n") * paper.scalar("arm_radius_m") == pytest.approx(
        paper.scalar("test3_torque_nm")
    )
    # Settling reductions: (5.73-4.20)/5.73 = 26.7% ("26%"), (6.17-4.39)/6.17 = 28.8% ("29%").
    s = paper.scalar
    assert 100 * (1 - s("settling_pi_model_s") / s("settling_pi_s")) == pytest.approx(26.7, abs=0.1)
    assert 100 * (1 - s("settling_pid_model_s") / s("settling_pid_s")) == pytest.approx(
        28.8, abs=0.1
    )


def test_tables_shapes():
    t1 = paper.table1()
    assert len(t1["pressure_mpa"]) == 4 and len(t1["simulated_outer_diameter_mm"]) == 4
    rows = paper.table3()
    assert [r["test"] for r in rows] == list(range(1, 8))
    assert rows[0]["max_relative_deviation_pct"] is None
    assert rows[6]["max_relative_deviation_pct"] == 31.3
    # Clearance D - d1 - d2 of the base group is 0.1 mm; tests 6 and 7 have 1.5 and 0.6 mm.
    clear = [r["hole_mm"] - r["tube_od_mm"] - r["wire_mm"] for r in rows]
    assert clear[0] == pytest.approx(0.1) and clear[5] == pytest.approx(1.5)
    assert clear[6] == pytest.approx(0.6)
    assert paper.table4()[7] == 0.0075
    assert paper.eq8() == (-1957.4, 2412.8, -251.95, -7.9531)


def test_to_dict_is_json_clean():
    import json

    d = paper.to_dict()
    text = json.dumps(d, allow_nan=False)
    assert "NaN" not in text and math.isfinite(d["scalars"]["gamma"])


def test_shipped_csvs():
    from exofric.io import read_table

    sim = read_table(
        paper.data_path("table1_simulated.csv"), ["pressure_mpa", "outer_diameter_mm", "shore"]
    )
    assert len(sim) == 16 and sorted(set(sim["shore"])) == [60.0, 62.5, 65.0, 70.0]
    with pytest.raises(FileNotFoundError):
        paper.data_path("nope.csv")
