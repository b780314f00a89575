"""Checks made once and early (issue 38, items 4-5): the pulled end's travel, and bad inputs
found by the hostile corpus of this pass (each listed where it is tested).

Time: < 2 s (no solve: every check fires before the squeeze).
"""

from __future__ import annotations

import math
import time
import warnings

import pytest

from exofric.errors import InputError, PlausibilityWarning
from exofric.geometry import BASE
from exofric.material import MooneyRivlin


@pytest.fixture(scope="module")
def setup():
    from exofric.simulate import PulloutSetup

    return PulloutSetup(BASE, MooneyRivlin.from_shore(62.5), mu_wire=0.3, mu_wall=0.5,
                        mu_wire_wall=0.2)


@pytest.mark.parametrize("bad", [0.0, -1.0, 116.5, 1e9, math.nan, math.inf])
def test_joint_stiffness_and_pullout_refuse_the_same_travel_before_any_solve(setup, bad):
    """One check (PulloutSetup.travel_mm) in both, the same message, in well under the
    seconds a squeeze takes (bound 1 s: no solve ran)."""
    from exofric.friction import joint_stiffness
    from exofric.simulate import pullout

    msgs = []
    for call in (lambda: joint_stiffness(setup, [0.3, 0.6], radius_m=0.1, displacement_mm=bad),
                 lambda: pullout(setup, 0.6, displacement_mm=bad)):
        t0 = time.perf_counter()
        with pytest.raises(InputError) as exc:
            call()
        assert time.perf_counter() - t0 < 1.0
        assert exc.value.param == "displacement_mm"
        msgs.append(str(exc.value))
    assert msgs[0] == msgs[1] and "(0, 116] mm (the tube length)" in msgs[0]


def test_a_long_travel_warns_once_from_the_check(setup):
    with warnings.catch_warnings(record=True) as got:
        warnings.simplefilter("always")
        assert setup.travel_mm(12) == 12.0
    assert [w.category for w in got] == [PlausibilityWarning]
    assert "displacement_mm = 12 mm" in str(got[0].message)


# ---- found by this pass's hostile corpus (issue 38, item 5) ----------------------------------

def _tensile(tmp_path, rows: list[str], header: str = "strain,stress_mpa"):
    p = tmp_path / "t.csv"
    p.write_text(header + "\n" + "\n".join(rows) + "\n")
    return p


def test_a_column_named_twice_is_refused_by_every_table_reader(tmp_path):
    """Was: the tensile reader kept one of two 'stress_mpa' columns silently (exit 0)."""
    from exofric.io import read_stress_stretch, read_table

    p = _tensile(tmp_path, ["0.1,0.02,0.03", "0.2,0.04,0.05"], "strain,stress_mpa,Stress_MPa")
    for read in (lambda: read_stress_stretch(p), lambda: read_table(p, ["strain"])):
        with pytest.raises(InputError, match=r"column 'stress_mpa' is in the file 2 times "
                                             r"\(columns 2, 3\); rename all but one$"):
            read()


def test_a_non_finite_tensile_cell_reads_as_written(tmp_path):
    """Was: 'is empty' for a cell holding nan, 'np.float64(inf)' for inf."""
    from exofric.io import read_stress_stretch

    for cell, says in [("nan", "is empty or NaN"), ("inf", "is not a finite number: inf")]:
        p = _tensile(tmp_path, ["0.1,0.02", f"0.2,{cell}", "0.3,0.06"])
        with pytest.raises(InputError, match=f"column 'stress_mpa' {says}$"):
            read_stress_stretch(p)


def test_a_fit_with_as_many_points_as_parameters_says_it_interpolates():
    """Was: a neo-Hookean 'fitted' to one point with R^2 and standard errors nan, silently."""
    import numpy as np

    from exofric.material import fit_material

    with warnings.catch_warnings(record=True) as got:
        warnings.simplefilter("always")
        fit = fit_material("neo-hookean", uniaxial=(np.array([1.2]), np.array([0.1])))
    assert any(w.category is PlausibilityWarning and "exactly" in str(w.message) for w in got)
    assert fit.model.params[0] > 0


def _cli(args: list[str]) -> tuple[int, str]:
    import contextlib
    import io

    from exofric.cli import run

    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = run(args)
    return code, err.getvalue().strip()


@pytest.mark.parametrize("opt", [["--length", "-5"], ["--shore", "30"],
                                 ["--model", "neo-hookean", "--params", "0.3"]])
def test_gait_refuses_a_tube_option_without_the_tube(opt):
    """Was: ``gait --length -5`` (or --shore, --model) without --hole etc. ran on the paper's
    Eq 9 map with the option silently ignored (exit 0)."""
    code, err = _cli(["gait", "--strides", "1", "--controller", "ff", *opt, "--json"])
    assert code == 2 and err.count("\n") == 0
    assert err.startswith(f"exofric: error: {opt[0]} sets the FE friction map's tube")


def test_a_number_left_out_of_a_list_is_refused():
    """Was: ``--pressures 0.3,,0.6`` solved 0.3 and 0.6 as if nothing were missing."""
    code, err = _cli(["squeeze", "--hole", "10", "--tube-od", "8.3", "--tube-id", "4.97",
                      "--wire", "1.6", "--shore", "62.5", "--pressures", "0.3,,0.6"])
    assert code == 2 and "--pressures has an empty item after 0.3 in '0.3,,0.6'" in err
    from exofric.cli._common import parse_floats

    assert parse_floats("--pressures", "0.3, 0.6,") == [0.3, 0.6]   # a trailing comma is fine


def test_a_structures_file_error_names_the_file_and_its_keys(tmp_path, monkeypatch):
    """Was: ``--structures file: structure 1: --hole (hole diameter D) must be ...`` and
    ``allowed: --hole, --length, name, --tube-id, ...``: the file's keys shown as flags."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text('[[structure]]\nname = "a"\nhole_mm = -10.0\n'
                                     'tube_od_mm = 8.3\nwire_mm = 1.6\nbogus_mm = 3\n')
    code, err = _cli(["predict", "--gamma", "0.7168", "--structures", "s.toml", "--pressures",
                      "0.3"])
    assert code == 2
    assert err == ("exofric: error: s.toml: structure 1 has unknown key 'bogus_mm' (allowed: "
                   "hole_mm, length_mm, name, tube_id_mm, tube_od_mm, wire_mm)")


@pytest.mark.filterwarnings("ignore:constrained fit")   # the fit of this nonsense curve
def test_measured_forces_and_stresses_of_the_wrong_sign_warn(tmp_path):
    """Was: a ring curve of negative forces and a tensile curve with a negative stress in
    tension were compared and fitted without a word."""
    import numpy as np

    from exofric.io import read_ring_test
    from exofric.material import fit_material

    p = tmp_path / "ring.csv"
    p.write_text("displacement_mm,force_n\n0.1,-0.2\n0.2,-0.45\n0.3,-0.7\n")
    with pytest.warns(PlausibilityWarning, match=r"'force_n' is negative in 3 of 3 rows"):
        read_ring_test(p)
    lam, stress = np.array([0.8, 1.1, 1.2, 1.3]), np.array([0.05, -0.02, -0.04, 0.055])
    with pytest.warns(PlausibilityWarning, match=r"sign of the other direction at 3 of 4 "
                                                 r"points \(first: stretch 0.8"):
        fit_material("neo-hookean", uniaxial=(lam, stress))


@pytest.mark.parametrize("bad", ["0.2", ["0.1", "0.2"], [None, 0.2], [0.1, "0.2"]])
def test_a_series_of_text_is_not_taken_for_numbers(bad):
    """Was: check_series converted text ("0.1") to numbers, so SqueezeCurve(["0.1", "0.2"],
    ...) was a curve (the class checks its arguments itself, not through checked_init)."""
    from exofric.errors import check_series
    from exofric.friction import SqueezeCurve

    with pytest.raises(InputError, match=r"^p must be a list of numbers$"):
        check_series("p", bad, min_points=1)
    n = [1.0] * (1 if isinstance(bad, str) else len(bad))
    with pytest.raises(InputError, match=r"^squeeze curve: pressure_mpa must be a list of "):
        SqueezeCurve(bad, n)
    assert check_series("p", [1, 2.5])[0].tolist() == [1.0, 2.5]
