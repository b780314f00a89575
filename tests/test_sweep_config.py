"""Sweep definitions: grid/family/explicit expansion, impossible designs, cache keys, errors."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from exofric.design import load_sweep, parse_sweep
from exofric.errors import InputError

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
P = [0.2, 0.4, 0.6]


def test_small_example_grid_has_twelve_designs_four_impossible_with_reasons():
    spec = load_sweep(EXAMPLES / "sweep-small.toml")
    assert len(spec.designs) == 12 and len(spec.runnable) == 8 and len(spec.skipped) == 4
    for d in spec.skipped:
        # the reason names the dimensions and the arithmetic: d1 + d2 > D
        assert "tube and wire do not fit" in d.skip_reason
        assert f"{d.tube_od_mm + d.wire_mm:g} mm" in d.skip_reason
        assert d.tube_od_mm + d.wire_mm > d.hole_mm
    for d in spec.runnable:
        assert d.tube_od_mm + d.wire_mm <= d.hole_mm
    # default tube ID keeps the base wall-to-diameter ratio: ID = 4.97 x d1 / 8.3
    d88 = next(d for d in spec.designs if d.tube_od_mm == 8.8)
    assert d88.tube_id_mm == pytest.approx(4.97 * 8.8 / 8.3, abs=1e-6)  # rounded to 1 nm
    assert len({d.key for d in spec.designs}) == 12


def test_paper_example_has_table3_and_families():
    spec = load_sweep(EXAMPLES / "sweep-paper.toml")
    names = [d.name for d in spec.designs]
    assert names[:7] == [f"test {i}" for i in range(1, 8)]
    t2 = spec.designs[1]
    assert (t2.hole_mm, t2.tube_od_mm, t2.wire_mm) == (7.5, 6.2, 1.1)
    fam = [d for d in spec.designs if d.family == "proportional, d2 snapped"]
    # x0.75 of (10, 8.3, 1.6): D = 7.5, d1 = 6.225, d2 = 1.2 snapped to the 1.1 mm cable
    x075 = next(d for d in fam if d.name.endswith("x0.75"))
    assert (x075.hole_mm, x075.tube_od_mm, x075.wire_mm) == (7.5, 6.225, 1.1)
    assert x075.tube_id_mm == pytest.approx(4.97 * 0.75, abs=1e-9)
    # the 'd2 alone x0.6875' family member equals test 7 and is kept once, as "test 7"
    assert not any(d.name == "d2 alone x0.6875" for d in spec.designs)
    assert spec.skipped and all("do not fit" in d.skip_reason for d in spec.skipped)


def test_wall_thickness_and_impossible_tube():
    spec = parse_sweep({"pressures_mpa": P, "grid": {"wall_mm": [1.0, 4.15, 5.0]}})
    ids = [d.tube_id_mm for d in spec.designs]
    assert ids == pytest.approx([6.3, 0.0, -1.7])   # ID = d1 - 2 t with d1 = 8.3 mm
    assert [d.skipped for d in spec.designs] == [False, True, True]
    assert ("tube_id_mm (tube inner diameter) must be in [0.01, 1000] mm, got 0"
            in spec.designs[1].skip_reason)


def test_impossible_hardness_is_skipped_not_fatal():
    spec = parse_sweep({"pressures_mpa": P, "grid": {"shore": [62.5, 120.0]}})
    assert [d.skipped for d in spec.designs] == [False, True]
    assert "shore" in spec.designs[1].skip_reason and "100" in spec.designs[1].skip_reason


def test_keys_follow_solve_inputs_not_postprocessing():
    base = {"pressures_mpa": P, "grid": {"wire_mm": [1.1, 1.6]}}
    k0 = [d.key for d in parse_sweep(base).designs]
    assert [d.key for d in parse_sweep({**base, "gamma": 0.5, "arm_radius_m": 0.2,
                                        "name": "other"}).designs] == k0
    assert [d.key for d in parse_sweep({**base, "solver": {"n_circ": 12}}).designs] != k0
    assert [d.key for d in parse_sweep({**base, "pressures_mpa": [0.2, 0.6]}).designs] != k0
    assert [d.key for d in parse_sweep({**base, "material": {"poisson": 0.49}}).designs] != k0
    # the same geometry from two sources is one design (first name kept)
    dup = parse_sweep({**base, "design": [{"name": "mine", "wire_mm": 1.6}]})
    assert [d.name for d in dup.designs] == ["mine", "d2=1.1"]


def test_family_scales_selected_dimensions():
    spec = parse_sweep({"pressures_mpa": P, "family": [
        {"name": "f", "scale": [1.1], "scaled": ["hole_mm", "tube_od_mm"]}]})
    d = spec.designs[0]
    assert (d.hole_mm, d.tube_od_mm, d.tube_id_mm, d.wire_mm) == (11.0, 9.13, 4.97, 1.6)


@pytest.mark.parametrize(
    ("data", "match"),
    [
        ({"pressures_mpa": P, "grid": {"hole": [10]}}, "unknown key 'hole'"),
        ({"pressures_mpa": P, "grid": {"tube_id_mm": 5, "wall_mm": 1}}, "both tube_id_mm"),
        ({"pressures_mpa": [0.4, 0.2], "grid": {}}, "strictly increasing"),
        ({"pressures_mpa": P, "grid": {"wire_mm": ["a"]}}, "must be a number"),
        ({"pressures_mpa": P}, "defines no designs"),
        ({"grid": {}}, "needs pressures_mpa"),
        ({"pressures_mpa": P, "grid": {}, "solver": {"n_circ": 2.5}}, "integer"),
        ({"pressures_mpa": P, "grid": {}, "gamma": -1}, "gamma must be > 0"),
        ({"pressures_mpa": P, "family": [{"name": "x"}]}, "needs 'scale'"),
        ({"pressures_mpa": P, "grid": {"wire_mm": []}}, "at least one"),
    ],
)
def test_bad_definitions_raise_one_line_input_errors(data, match):
    with pytest.raises(InputError, match=match) as exc:
        parse_sweep(data)
    assert "\n" not in str(exc.value)


def test_load_sweep_reports_toml_errors(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text("pressures_mpa = [0.1,\n")
    with pytest.raises(InputError, match="not valid TOML"):
        load_sweep(f)
    with pytest.raises(InputError, match="does not exist"):
        load_sweep(tmp_path / "missing.toml")
    data = tomllib.loads((EXAMPLES / "sweep-small.toml").read_text())
    assert parse_sweep(data).name == "small"
