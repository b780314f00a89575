"""Property tests of the input checks: any argument gives a result or exofric's InputError.

Random finite, non-finite, huge, negative and non-numeric arguments to the public constructors
(Structure, MooneyRivlin and MooneyRivlin.from_shore, MeshSpec, check_pressures) and random
bytes / random numbers in the files the readers of exofric.io take: the only outcomes allowed
are a valid result or :class:`exofric.errors.InputError` (never a builtin ValueError/TypeError,
a NumPy warning turned error or a crash). No FE solve runs here.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from exofric import defaults  # noqa: E402
from exofric.errors import InputError, PlausibilityWarning, check_pressures  # noqa: E402
from exofric.fe import MeshSpec  # noqa: E402
from exofric.geometry import Structure  # noqa: E402
from exofric.material import MooneyRivlin  # noqa: E402

FAST = settings(max_examples=150, deadline=None,
                suppress_health_check=[HealthCheck.function_scoped_fixture])

#: numbers of every kind: finite, NaN/inf, huge, tiny, negative, ints, near-physical sizes
NUMBER = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(min_value=1e-3, max_value=20.0),
    st.integers(min_value=-(10**30), max_value=10**30),
    st.sampled_from([0.0, -0.0, -1.0, 1e300, -1e300, 1e-300, 5e-324, 1e308]),
)
#: anything a Python caller might pass by mistake
ANYTHING = st.one_of(NUMBER, st.text(max_size=8), st.none(), st.booleans(),
                     st.lists(st.floats(), max_size=3))


def _call(fn, *args, **kwargs):
    """Run ``fn``; None if it raised InputError (warnings of exofric's own kind are allowed)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)  # NumPy overflow etc. is a failure
        warnings.simplefilter("ignore", PlausibilityWarning)  # implausible but valid: allowed
        try:
            return fn(*args, **kwargs)
        except InputError as exc:
            assert "\n" not in str(exc)
            return None


@FAST
@given(ANYTHING, ANYTHING, ANYTHING, ANYTHING, ANYTHING)
def test_structure_result_or_input_error(hole, od, idm, wire, length):
    s = _call(Structure, hole, od, idm, wire, length)
    if s is not None:
        for v in (s.hole_mm, s.tube_od_mm, s.tube_id_mm, s.wire_mm, s.length_mm):
            assert isinstance(v, float) and defaults.SIZE_MIN_MM <= v <= defaults.SIZE_MAX_MM
        assert 0.0 < s.tube_id_mm < s.tube_od_mm and s.clearance_mm >= 0.0


@FAST
@given(ANYTHING, ANYTHING, ANYTHING)
def test_mooney_rivlin_result_or_input_error(c10, c01, d):
    m = _call(MooneyRivlin, c10, c01, d)
    if m is not None:
        assert all(isinstance(v, float) and math.isfinite(v)
                   for v in (m.c10_mpa, m.c01_mpa, m.d_per_mpa))
        assert m.c10_mpa + m.c01_mpa > 0.0 and m.d_per_mpa > 0.0
        assert math.isfinite(m.bulk_modulus) and math.isfinite(m.youngs_modulus)


@FAST
@given(ANYTHING, st.one_of(st.sampled_from(["paper", "gent", "qi", "astm-log10"]), ANYTHING),
       ANYTHING, ANYTHING)
def test_from_shore_result_or_input_error(shore, correlation, ratio, poisson):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # MaterialRangeWarning: allowed, says why
        m = _call(MooneyRivlin.from_shore, shore, correlation, ratio, poisson)
    if m is not None:
        assert 0.0 < float(m.shore) < 100.0 and m.c10_mpa > 0.0 and m.d_per_mpa > 0.0


MESH_INT = st.one_of(st.integers(min_value=-(10**12), max_value=10**12),
                     st.integers(min_value=1, max_value=300), ANYTHING)


@FAST
@given(MESH_INT, MESH_INT, st.one_of(st.sampled_from(["quad9", "quad4"]), st.text(max_size=6)),
       st.one_of(st.floats(min_value=1.0, max_value=50.0), NUMBER),
       st.one_of(st.sampled_from(["mixed", "displacement"]), st.text(max_size=6)))
def test_meshspec_result_or_input_error(nr, nc, kind, grading, formulation):
    m = _call(MeshSpec, nr, nc, kind, grading, formulation)
    if m is not None:
        assert 1 <= m.n_radial <= defaults.MESH_MAX_N_RADIAL
        assert 1 <= m.n_circ <= defaults.MESH_MAX_N_CIRC
        assert m.n_radial * m.n_circ <= defaults.MESH_MAX_ELEMENTS
        assert 1.0 <= m.grading <= defaults.MESH_MAX_GRADING


def test_meshspec_bounds_keep_the_finest_test_meshes_and_quote_memory():
    assert MeshSpec(12, 256).n_circ == 256 and MeshSpec(8, 256, grading=6.0).n_radial == 8
    with pytest.raises(InputError, match=r"GiB") as exc:
        MeshSpec(2, 100_000)
    assert exc.value.param == "n_circ"


@FAST
@given(st.lists(ANYTHING, max_size=8), st.one_of(st.floats(min_value=0.1, max_value=10.0)),
       st.booleans())
def test_check_pressures_result_or_input_error(values, max_mpa, allow_zero):
    arr = _call(check_pressures, "pressures_mpa", values, max_mpa=max_mpa, allow_zero=allow_zero)
    if arr is not None:
        assert arr.ndim == 1 and arr.size == len(values)
        assert (arr >= 0).all() and (arr <= max_mpa).all() and (arr[1:] > arr[:-1]).all()


@FAST
@given(ANYTHING, ANYTHING)
def test_inflate_sizes_result_or_input_error(od, idm):
    """Tube diameters of any kind: refused with InputError before any solve, or accepted
    (only physical ones reach the solver, on the cheapest mesh, at one low pressure)."""
    from exofric.geometry import check_size_mm

    ok = _call(check_size_mm, "tube_od_mm", od) is not None and \
        _call(check_size_mm, "tube_id_mm", idm) is not None
    if not ok:
        from exofric.simulate import inflate

        assert _call(inflate, od, idm, MooneyRivlin.from_shore(62.5), [0.01]) is None


@FAST
@given(ANYTHING)
def test_fit_gamma_seed_result_or_input_error(seed):
    from exofric.friction import fit_gamma

    p = [0.3, 0.4, 0.5, 0.6]
    fit = _call(fit_gamma, p, [50.0, 80.0, 120.0, 170.0], p, [70.0, 110.0, 170.0, 240.0],
                ci="bootstrap", n_boot=20, seed=seed)
    assert fit is None or fit.gamma > 0


# ---- readers of exofric.io -------------------------------------------------------------------

def _readers():
    from exofric import io

    return {
        "inflation": io.read_inflation_table,
        "squeeze": io.read_squeeze_curve,
        "friction": io.read_friction_table,
        "step": io.read_step_response,
        "json": io.read_json,
        "toml": io.read_toml,
    }


READERS = sorted(_readers())
SUFFIX = {"json": ".json", "toml": ".toml", "squeeze": ".csv"}


def _read(tmp_path: Path, reader: str, data: bytes, suffix: str | None = None):
    p = tmp_path / f"f{SUFFIX.get(reader, '.csv') if suffix is None else suffix}"
    p.write_bytes(data)
    try:
        return _call(_readers()[reader], p)
    finally:
        p.unlink()


@pytest.mark.parametrize("reader", READERS)
@settings(max_examples=60, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.binary(max_size=200))
def test_readers_random_bytes(tmp_path, reader, data):
    _read(tmp_path, reader, data)


CELL = st.one_of(NUMBER.map(repr), st.sampled_from(["", "nan", "inf", "-inf", "1e999", "x",
                                                    " ", '"', "1,2"]))
HEADERS = {
    "inflation": "pressure_mpa,outer_diameter_mm",
    "squeeze": "pressure_mpa,squeeze_force_n",
    "friction": "pressure_mpa,friction_n,test",
    "step": "time_s,friction_n,pressure_mpa",
}


@pytest.mark.parametrize("reader", sorted(HEADERS))
@settings(max_examples=60, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(rows=st.lists(st.lists(CELL, min_size=1, max_size=4), max_size=6))
def test_csv_readers_random_numbers(tmp_path, reader, rows):
    text = HEADERS[reader] + "\n" + "\n".join(",".join(r) for r in rows) + "\n"
    _read(tmp_path, reader, text.encode())


@settings(max_examples=60, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(p=st.lists(NUMBER, max_size=5), n=st.lists(NUMBER, max_size=5))
def test_squeeze_json_random_numbers(tmp_path, p, n):
    import json

    text = json.dumps({"pressure_mpa": p, "squeeze_force_n": n})
    _read(tmp_path, "squeeze", text.encode(), ".json")
