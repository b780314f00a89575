"""Property tests of the input checks: any argument gives a result or exofric's InputError.

Random finite, non-finite, huge, negative and non-numeric arguments to the public constructors
(Structure, MooneyRivlin and MooneyRivlin.from_shore, MeshSpec, check_pressures) and random
bytes / random numbers in the files the readers of exofric.io take: the only outcomes allowed
are a valid result or :class:`exofric.errors.InputError` (never a builtin ValueError/TypeError,
a NumPy warning turned error or a crash). No FE solve runs here.

Every public function of every stage (issue 38): each argument of a kind its type hint does not
admit (a bare object, a str for a number, None, True, a dict, a list of junk, complex, bytes;
systematically and drawn at random) is an InputError naming that parameter, before any work.
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


# ---- the Python API's argument kinds (issue 38) ----------------------------------------------
#
# Every function a stage exports checks its arguments' kinds from its type hints
# (exofric._validate): an argument of the wrong kind is an InputError naming the parameter,
# never a builtin TypeError from deep inside nor a string taken for a number. The reference
# for "wrong" is the hint's text, read here independently of exofric._validate: a value is
# wrong for a hint when none of the hint's words admits it (a str is wrong for a hint that
# names no str, Path, Literal, Any or object; None for one without None; ...).

import functools  # noqa: E402
import importlib  # noqa: E402
import inspect  # noqa: E402
import pickle  # noqa: E402
import re  # noqa: E402

STAGE_MODULES = ["exofric.paper", "exofric.material", "exofric.fe", "exofric.simulate",
                 "exofric.calibration", "exofric.friction", "exofric.control",
                 "exofric.hardware", "exofric.design", "exofric.reproduction", "exofric.io",
                 "exofric.plots", "exofric.report"]

#: Parameters that take any object by design (their hint is Any, object, or a protocol of
#: methods that isinstance cannot check); the function checks them itself.
ACCEPTS_ANYTHING = {
    # matplotlib Axes/Figure, or None: matplotlib's own objects
    *(f"exofric.plots.{f}:{a}" for f, a in [
        ("plot_calibration", "ax"), ("plot_material_calibration", "fig"), ("plot_table1", "fig"),
        ("save", "fig"), ("plot_control_cases", "fig"), ("plot_simulation", "ax"),
        ("plot_design_map", "ax"), ("draw_section", "ax"), ("plot_contact_pressure", "ax"),
        ("plot_inflation", "fig"), ("plot_inflation_curve", "ax"), ("plot_squeeze", "fig"),
        ("plot_squeeze_curves", "ax"), ("plot_squeeze_force", "ax"), ("plot_tube_ends", "fig"),
        ("plot_cubic_fit", "ax"), ("plot_gamma_fit", "fig"), ("plot_predictions", "fig"),
        ("plot_torque", "ax"), ("plot_gait", "fig"), ("plot_gait_compare", "fig"),
        ("plot_interface_fit", "fig"), ("plot_material_fit", "fig"), ("plot_pullout_fit", "fig"),
        ("plot_joint_stiffness", "ax"), ("plot_pullout", "ax"), ("plot_reduction", "fig"),
        ("plot_ring_test", "ax")]),
    # results of several kinds drawn by duck typing
    "exofric.plots.plot_cubic_fit:ours", "exofric.plots.plot_cubic_fit:paper_eq8",
    "exofric.plots.plot_pullout_fit:fit", "exofric.plots.plot_joint_stiffness:result",
    "exofric.plots.plot_pullout:result",
    # any JSON-able object / any value to format
    "exofric.io.jsonable:obj", "exofric.io.write_json:obj", "exofric.report.fmt:v",
    # data in several documented forms (arrays, frames, mappings, result objects)
    "exofric.calibration.calibrate:data", "exofric.calibration.calibrate_material:inflation",
    "exofric.calibration.calibrate_material:tensile",
    "exofric.calibration.calibrate_material:ring_mesh",
    "exofric.friction.fit_gamma:friction_pressure_mpa", "exofric.friction.fit_gamma:friction_n",
    "exofric.friction.predict:material", "exofric.friction.law_columns:curves",
    "exofric.friction.fit_pullout:pulls", "exofric.friction.simulate_law_rig:curves",
    "exofric.material.fit_material:uniaxial", "exofric.material.fit_material:biaxial",
    "exofric.material.fit_material:planar",
    "exofric.control.identify_charge:time_s", "exofric.control.identify_charge:pressure_mpa",
    "exofric.control.identify_charge:command_mpa", "exofric.control.closed_loop:source",
    # protocols of methods (a device, a controller, a clock, a plant, an FE problem)
    "exofric.hardware.open_device:plant", "exofric.hardware.open_device:friction",
    "exofric.hardware.run_loop:device", "exofric.hardware.run_loop:controller",
    "exofric.hardware.run_loop:clock", "exofric.fe.solve_path:problem",
}

#: Words of hints this test knows; a hint with another word (a type alias, a protocol) is
#: probed only with a bare object no hint but Any admits.
_BUILTIN_WORDS = {
    "float", "int", "bool", "str", "bytes", "None", "list", "tuple", "dict", "set", "Sequence",
    "Mapping", "Iterable", "Collection", "MutableMapping", "Callable", "Optional", "Union",
    "Literal", "Any", "object", "np", "ndarray", "NDArray", "ArrayLike", "float64", "int64",
    "intp", "bool_", "npt", "Path", "pd", "DataFrame", "Series", "sp", "csr_matrix",
}


class _Junk:
    """A bare object: no hint but Any/object admits it."""

    def __repr__(self) -> str:
        return "<junk>"


@functools.cache
def _public_functions() -> dict[str, object]:
    found: dict[str, object] = {}
    seen: set[int] = set()
    for modname in STAGE_MODULES:
        mod = importlib.import_module(modname)
        for name in mod.__all__:
            obj = getattr(mod, name)
            if inspect.isfunction(obj) and id(obj) not in seen:
                seen.add(id(obj))
                found[f"{modname}.{name}"] = obj
    return found



def _words(hint: str) -> set[str]:
    return set(re.findall(r"[A-Za-z_]\w*", re.sub(r"(['\"]).*?\1", "", hint)))


@functools.cache
def _classes() -> frozenset[str]:
    """The public classes of every stage, by name."""
    return frozenset(n for m in STAGE_MODULES for n in importlib.import_module(m).__all__
                     if inspect.isclass(getattr(importlib.import_module(m), n)))


def _known(words: set[str]) -> bool:
    return words <= _BUILTIN_WORDS | _classes()


def _wrong_values(hint: str, default: object) -> list[object]:
    """Values the hint's words do not admit (never the default: a default is not checked)."""
    w = _words(hint)
    out: list[object] = [_Junk()]
    if not _known(w) or w & {"Any", "object"}:
        return out
    bare_seq = re.search(r"\b(Sequence|list|tuple|Iterable|Collection)\b(?!\[)", hint)
    if not w & {"str", "Path", "Literal"}:
        out += ["0.2", "x" * 500]
    if not w & {"None", "Optional"}:
        out.append(None)
    if not w & {"bool", "ArrayLike"}:
        out.append(True)
    if not w & {"float", "ArrayLike"}:
        out.append(0.5)
    if not w & {"Mapping", "dict", "MutableMapping"}:
        out.append({"a": 1})
    if not bare_seq:
        out.append([_Junk()])
    out += [1 + 2j, b"bytes"]
    return [v for v in out if v is not default]


@functools.cache
def _probes() -> list[tuple[str, str, str, object]]:
    """(function, parameter, hint, default) of every checked parameter of every function."""
    out = []
    for qual, fn in _public_functions().items():
        for p in inspect.signature(fn).parameters.values():
            if p.kind is p.VAR_KEYWORD or p.annotation is p.empty:
                continue
            if f"{qual}:{p.name}" in ACCEPTS_ANYTHING:
                continue
            out.append((qual, p.name, str(p.annotation), p.default))
    return out


def _call_with(qual: str, param: str, value: object) -> BaseException | None:
    fn = _public_functions()[qual]
    kind = inspect.signature(fn).parameters[param].kind
    try:
        if kind is inspect.Parameter.VAR_POSITIONAL:
            fn(value)
        else:
            fn(**{param: value})
    except BaseException as exc:  # noqa: BLE001 - the test inspects whatever came out
        return exc
    return None


def test_every_public_function_checks_its_arguments_and_keeps_its_signature():
    from exofric._validate import is_checked

    funcs = _public_functions()
    assert len(funcs) > 150
    for qual, fn in funcs.items():
        assert is_checked(fn), qual
        raw = inspect.unwrap(fn)
        assert inspect.signature(fn) == inspect.signature(raw) and fn.__doc__ == raw.__doc__
        assert pickle.loads(pickle.dumps(fn)) is fn, qual   # by reference, for process pools
    import exofric

    for name in exofric.__all__:   # the top-level names are the same checked objects
        obj = getattr(exofric, name)
        if inspect.isfunction(obj):
            assert is_checked(obj) and any(obj is f for f in funcs.values()), name


def test_accepts_anything_lists_only_real_parameters():
    funcs = _public_functions()
    for entry in ACCEPTS_ANYTHING:
        qual, param = entry.split(":")
        assert qual in funcs and param in inspect.signature(funcs[qual]).parameters, entry


@pytest.mark.parametrize("module", STAGE_MODULES)
def test_a_wrong_kind_is_an_input_error_naming_the_parameter(module):
    """Every checked parameter of every function, each value its hint does not admit: an
    InputError whose ``param`` is that parameter and whose one line names it."""
    bad = []
    for qual, param, hint, default in _probes():
        if not qual.startswith(module + "."):
            continue
        for value in _wrong_values(hint, default):
            exc = _call_with(qual, param, value)
            ok = isinstance(exc, InputError) and exc.param == param and \
                str(exc).startswith(param + " ") and "\n" not in str(exc) and len(str(exc)) < 300
            if not ok:
                bad.append(f"{qual}({param}={value!r:.20}) [{hint}] -> {exc!r:.200}")
    assert not bad, "\n".join(bad)


@settings(max_examples=100, deadline=None)
@given(data=st.data())
def test_random_wrong_kinds_are_input_errors(data):
    """Random text, bytes, complex numbers, nested lists and dicts for random parameters."""
    qual, param, hint, default = data.draw(st.sampled_from(_probes()))
    w = _words(hint)
    kinds = [st.builds(_Junk), st.complex_numbers(allow_nan=False).filter(lambda z: z.imag),
             st.binary(max_size=8)]
    if _known(w) and not w & {"Any", "object"}:
        if not w & {"str", "Path", "Literal"}:
            kinds.append(st.text(max_size=8))
        if not w & {"Mapping", "dict", "MutableMapping"}:
            kinds.append(st.dictionaries(st.text(max_size=3), st.integers(), min_size=1))
        if not re.search(r"\b(Sequence|list|tuple|Iterable|Collection)\b(?!\[)", hint):
            kinds.append(st.lists(st.one_of(st.builds(_Junk), st.just(1j)), min_size=1,
                                  max_size=3))
    value = data.draw(st.one_of(kinds))
    exc = _call_with(qual, param, value)
    assert isinstance(exc, InputError) and exc.param == param, (qual, param, value, exc)


def test_the_reported_calls_and_the_kinds_that_keep_working(tmp_path):
    """Issue 38's two calls; lists for arrays, NumPy scalars for numbers, str for paths."""
    import numpy as np

    import exofric as ef
    from exofric import io

    with pytest.raises(InputError, match=r"^log must be a DataFrame or a mapping") as e1:
        ef.reduce_log(12345)
    with pytest.raises(InputError, match=r"^mu_wall must be a number, got '0.2' \(str\)"):
        ef.squeeze(ef.BASE, MooneyRivlin.from_shore(62.5), [0.6], mu_wall="0.2")
    with pytest.raises(InputError, match=r"^material is required by squeeze\(\)") as e3:
        ef.squeeze(ef.BASE)
    with pytest.raises(InputError, match=r"^bogus_mm is not a parameter of torque\(\)"):
        ef.torque(180.0, bogus_mm=1.0)
    assert (e1.value.param, e3.value.param) == ("log", "material")
    # NumPy scalars are numbers; a Python int is a float
    a = ef.torque(np.float64(180.49), arm_radius_m=np.float64(0.1))
    b = ef.torque(180.49, arm_radius_m=0.1)
    assert a.to_dict() == b.to_dict()
    # array_like: lists, tuples and arrays alike (fit_gamma: the closed form on exact data)
    p, n = [0.2, 0.4, 0.6], [10.0, 20.0, 30.0]
    f1 = ef.fit_gamma(p, [7.0, 14.0, 21.0], tuple(p), np.array(n), ci="analytic")
    assert f1.gamma == pytest.approx(0.7, rel=1e-12)
    # str or Path for paths
    io.write_json({"a": 1}, str(tmp_path / "a.json"))
    assert io.read_json(tmp_path / "a.json") == io.read_json(str(tmp_path / "a.json"))


@pytest.mark.parametrize(("cls", "kwargs", "field"), [
    ("exofric.fe:NewtonSettings", {"max_iter": "5"}, "max_iter"),
    ("exofric.fe:MeshSpec", {"n_radial": "4"}, "n_radial"),
    ("exofric.friction:ReduceSettings", {"smooth_s": "0.1"}, "smooth_s"),
    ("exofric.friction:PullFitSettings", {"n_z": "20"}, "n_z"),
    ("exofric.simulate:PulloutNumerics", {"n_path": "30"}, "n_path"),
])
def test_settings_objects_check_their_fields(cls: str, kwargs: dict, field: str) -> None:
    """The user-facing settings dataclasses refuse a value of the wrong kind at construction
    (issue 38: they accepted strings or raised a plain TypeError), naming the field."""
    import importlib

    mod, name = cls.split(":")
    klass = getattr(importlib.import_module(mod), name)
    with pytest.raises(InputError) as exc:
        klass(**kwargs)
    assert exc.value.param == field and name in str(exc.value)
    assert "must be" in str(exc.value)           # a kind check, not "unexpected argument"


def test_setups_check_their_fields() -> None:
    from exofric.geometry import BASE
    from exofric.material import MooneyRivlin
    from exofric.simulate import PulloutSetup, SqueezeSetup

    mat = MooneyRivlin.from_shore(62.5)
    with pytest.raises(InputError) as exc:
        SqueezeSetup(BASE, mat, mu_wall="0.2")  # type: ignore[arg-type]
    assert exc.value.param == "mu_wall"
    with pytest.raises(InputError) as exc:
        PulloutSetup(BASE, mat, mu_wire=0.3, mu_wall=0.5, mu_wire_wall=0.2,
                     cable_ea_n="stiff")  # type: ignore[arg-type]
    assert exc.value.param == "cable_ea_n"
