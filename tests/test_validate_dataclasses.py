"""Every public dataclass checks its fields' kinds at construction (issue 38, item 1).

The data, settings and result classes a user can construct (and rebuild, e.g. from
``to_dict()``) are walked from every stage's ``__all__`` (and ``exofric.__all__``); for each
field whose hint a value of another kind cannot satisfy, a value of a wrong kind is given and
must be an :class:`~exofric.errors.InputError` whose ``param`` is that field and whose one line
names the class. The wrong value is chosen from the hint's TEXT here (a str for a hint naming
no str/Path/Literal; a number for a str/Path/Literal hint; a bare object for a hint of type
aliases), independently of :mod:`exofric._validate`, which reads the hints itself.

Valid instances come from a small registry of cheap factories (no FE solve): on those the
wrong value is also given through ``dataclasses.replace`` (all other fields valid), and
``replace(instance)`` with nothing changed must still construct (the check accepts what the
code itself builds). A class not in the registry is probed with the wrong field alone: the
kind of every given argument is checked before the missing-argument check (a stated property
of ``_validate._bind``), so the InputError names the wrong field, not a missing one.

Time: about 1 s (no solve; the registry's factories are closed forms and constructors).
"""

from __future__ import annotations

import dataclasses
import functools
import importlib
import inspect
import pkgutil
import re
import timeit
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import exofric
from exofric._validate import is_checked
from exofric.errors import InputError

#: Fields whose hint admits any object by design (the class checks them itself, or they hold a
#: duck-typed collaborator): the reason beside each.
ACCEPTS_ANYTHING = {
    # a protocol of methods (anything with friction(P) / pressure(F)): duck-typed maps
    "ControlSetup.model_map": "FrictionMapLike is a Protocol of methods",
    # hint Any: measured data documented as array-likes of several forms, checked by the class
    "InterfaceTest.pressure_mpa": "array-like of several forms (hint Any), checked in the class",
    "InterfaceTest.friction_n": "array-like of several forms (hint Any), checked in the class",
    "InterfaceTest.groups": "labels of any kind (hint Any)",
    # private state carried for methods, not a user's input
    "MaterialCalibration._problem": "private: the fit's problem object",
    "SqueezeSurrogate._onset": "private: a fitted scikit-learn-like model",
    "SqueezeSurrogate._curve": "private: a fitted scikit-learn-like model",
    # hint Any although documented narrower (MeshSpec or None, LackOfFit or None,
    # StepMetrics or None): the hint is the module owner's to tighten
    "PulloutSetup.mesh": "hint Any (documented MeshSpec or None)",
    "PullFitSettings.mesh": "hint Any (documented MeshSpec or None)",
    "InterfaceFit.lack_of_fit": "hint Any (documented LackOfFit or None)",
    "LoopResult.metrics": "hint Any (documented StepMetrics or None)",
}


#: Classes with a hand-written ``__init__`` that checks every argument itself (through
#: :func:`exofric.errors.check_series`, which refuses text and None): not wrapped, so that their
#: messages keep their context ("squeeze curve: pressure_mpa must be a list of numbers").
OWN_INIT = {
    "SqueezeCurve": "its __init__ checks both series (check_series)",
}


class _Junk:
    """A bare object: no hint but Any/object/a protocol admits it."""

    def __repr__(self) -> str:
        return "<junk>"


def _packages() -> list[str]:
    return ["exofric"] + [f"exofric.{m.name}" for m in pkgutil.iter_modules(exofric.__path__)
                          if m.ispkg and not m.name.startswith("_")
                          and m.name not in ("cli", "data")]


@functools.cache
def public_dataclasses() -> dict[str, type]:
    """Every dataclass a package's ``__all__`` exports, by class name (one home each)."""
    out: dict[str, type] = {}
    for pkg in _packages():
        mod = importlib.import_module(pkg)
        for name in getattr(mod, "__all__", []):
            obj = getattr(mod, name)
            if inspect.isclass(obj) and dataclasses.is_dataclass(obj):
                assert out.get(obj.__name__, obj) is obj, f"two public classes {obj.__name__}"
                out[obj.__name__] = obj
    return out


def _words(hint: str) -> set[str]:
    return set(re.findall(r"[A-Za-z_]\w*", re.sub(r"(['\"]).*?\1", "", hint)))


_BUILTIN = {"float", "int", "bool", "str", "None", "list", "tuple", "dict", "Sequence",
            "Mapping", "Callable", "Optional", "Literal", "Any", "object", "np", "ndarray",
            "NDArray", "ArrayLike", "float64", "int64", "intp", "bool_", "npt", "Path", "pd",
            "DataFrame", "Series", "Iterable"}


def _top_level(hint: str) -> str:
    """The hint without its brackets' contents: ``tuple[dict[str, Any], ...]`` -> ``tuple``."""
    prev = None
    while prev != hint:
        prev, hint = hint, re.sub(r"\[[^\[\]]*\]", "", hint)
    return hint


def _wrong_value(hint: str) -> object | None:
    """A value of a kind ``hint`` does not admit, from its text (None: it admits anything).

    Only the outer kind is probed (a str is no tuple, whatever the tuple holds).
    """
    w = _words(_top_level(hint))
    if w & {"Any", "object"}:
        return None
    if not w <= _BUILTIN | set(_public_classes()):
        return _Junk()                     # a type alias: a bare object is no kind it names
    if not w & {"str", "Path", "Literal"}:
        return "0.2"                       # a str where numbers/arrays/classes are meant
    if not w & {"float", "int", "ArrayLike", "ndarray", "NDArray"}:
        return 1.5                         # a number where a str/Path/literal is meant
    return _Junk()


@functools.cache
def _public_classes() -> frozenset[str]:
    return frozenset(n for p in _packages() for n in importlib.import_module(p).__all__
                     if inspect.isclass(getattr(importlib.import_module(p), n)))


# ---- valid instances (cheap: closed forms and constructors, no FE solve) ------------------------

def _registry() -> dict[str, Callable[[], Any]]:
    from exofric import control, design, fe, friction, geometry, hardware, material, simulate

    mr = material.MooneyRivlin.from_shore(62.5)
    cubic = friction.CubicFit((0.0, 1.0, 2.0, 3.0), 0.0, 0.6)
    return {
        "Structure": lambda: geometry.BASE,
        "MooneyRivlin": lambda: mr,
        "HyperelasticModel": lambda: material.material_model("ogden1", [0.4, 2.0]),
        "MeshSpec": fe.MeshSpec, "NewtonSettings": fe.NewtonSettings,
        "SolverStats": fe.SolverStats,
        "RigidCircle": lambda: fe.RigidCircle((0.0, 0.0), 4.0, inside=True),
        "SqueezeSetup": lambda: simulate.SqueezeSetup(geometry.BASE, mr),
        "PulloutNumerics": simulate.PulloutNumerics,
        "PulloutSetup": lambda: simulate.PulloutSetup(geometry.BASE, mr, mu_wire=0.3,
                                                      mu_wall=0.5, mu_wire_wall=0.2),
        "ErrorEstimate": simulate.ErrorEstimate,
        "InflationCurve": lambda: simulate.incompressible_inflation(8.3, 4.97, 0.6, [0.1, 0.2]),
        "ClearanceDistribution": lambda: simulate.ClearanceDistribution.uniform(0.0, 0.2),
        "FrictionModel": lambda: friction.FrictionModel(0.7, 1.0),
        "CubicFit": lambda: cubic,
        "SqueezeCurve": lambda: friction.SqueezeCurve((0.2, 0.4), (10.0, 20.0)),
        "MeasuredCurve": lambda: friction.MeasuredCurve((0.2, 0.4), (7.0, 14.0)),
        "InterfaceFrictionModel": lambda: friction.InterfaceFrictionModel(0.2, 0.4),
        "RigConfig": friction.RigConfig, "RawRigConfig": friction.RawRigConfig,
        "ReduceSettings": friction.ReduceSettings, "PullFitSettings": friction.PullFitSettings,
        "TorqueCheck": lambda: friction.torque(180.49),
        "PIDGains": lambda: control.PIDGains(1.0, 0.5, 0.0),
        "PlantParams": control.PlantParams, "GaitSetup": control.GaitSetup,
        "PneumaticParams": control.PneumaticParams, "StrategyOptions": control.StrategyOptions,
        "Orifice": lambda: control.Orifice(1.0),
        "PlantModel": lambda: control.PlantModel(2.0, 0.1),
        "CubicFrictionMap": lambda: control.CubicFrictionMap(cubic, 0.7),
        "MaterialSpec": design.MaterialSpec, "SolverSpec": design.SolverSpec,
        "Reading": lambda: hardware.Reading(0.3, 12.0, 5),
        "SafetyLimits": hardware.SafetyLimits,
    }


def _instances() -> dict[str, Any]:
    out = {}
    for name, make in _registry().items():
        out[name] = make()
    return out


def test_every_public_dataclass_is_checked():
    classes = public_dataclasses()
    assert len(classes) > 100
    unchecked = [n for n, c in classes.items() if not is_checked(c.__init__)]
    assert sorted(unchecked) == sorted(OWN_INIT), \
        f"public dataclasses without @checked_init: {sorted(set(unchecked) - set(OWN_INIT))}"
    for name, cls in classes.items():           # the signature and docs are the class's own
        raw = inspect.unwrap(cls.__init__)
        assert str(inspect.signature(cls.__init__)) == str(inspect.signature(raw)), name


def _probes() -> list[tuple[str, str, str, object]]:
    """(class, field, hint, wrong value) for every init field of every public dataclass."""
    out = []
    for name, cls in public_dataclasses().items():
        for f in dataclasses.fields(cls):
            if f.init and f"{name}.{f.name}" not in ACCEPTS_ANYTHING:
                out.append((name, f.name, str(f.type), _wrong_value(str(f.type))))
    return out


def _is_named_error(exc: BaseException | None, cls: str, field: str) -> bool:
    if not (isinstance(exc, InputError) and exc.param == field and "\n" not in str(exc)
            and len(str(exc)) < 300):
        return False
    if cls in OWN_INIT:                          # its own words, naming the field
        return f"{field} must be" in str(exc)
    return str(exc).startswith(f"{field} must be ") and f"in {cls}()" in str(exc)


def _raised(fn: Callable[[], Any]) -> BaseException | None:
    try:
        fn()
    except BaseException as exc:  # noqa: BLE001 - the test inspects whatever came out
        return exc
    return None


def test_a_wrong_kind_in_any_field_is_an_input_error_naming_it():
    """Every field of every public dataclass: the wrong kind alone, and (registry) in an
    otherwise valid instance through ``dataclasses.replace``; 0 fields may accept it."""
    classes, inst = public_dataclasses(), _instances()
    probes = _probes()
    bad, n_str = [], 0
    for cls_name, field, hint, wrong in probes:
        if wrong is None:
            bad.append(f"{cls_name}.{field} [{hint}] admits anything: list it with a reason")
            continue
        n_str += isinstance(wrong, str)
        cls = classes[cls_name]
        if cls_name not in OWN_INIT:   # its own __init__ needs its other arguments first
            exc = _raised(lambda cls=cls, field=field, wrong=wrong: cls(**{field: wrong}))
            if not _is_named_error(exc, cls_name, field):
                bad.append(f"{cls_name}({field}={wrong!r}) [{hint}] -> {exc!r:.200}")
        if cls_name in inst:
            exc = _raised(lambda c=inst[cls_name], field=field, wrong=wrong:
                          dataclasses.replace(c, **{field: wrong}))
            if not _is_named_error(exc, cls_name, field):
                bad.append(f"replace({cls_name}, {field}={wrong!r}) -> {exc!r:.200}")
    assert not bad, "\n".join(bad)
    # the count: 140 of 372 fields took a string; now every field that should refuse
    # one is probed with one (and the rest with a number or a bare object)
    assert len(probes) > 700 and n_str > 500, (len(probes), n_str)


def test_the_fields_that_accept_anything_are_real_and_stated():
    classes = public_dataclasses()
    for entry in ACCEPTS_ANYTHING:
        cls, field = entry.split(".")
        assert field in {f.name for f in dataclasses.fields(classes[cls])}, entry
        hint = str(classes[cls].__dataclass_fields__[field].type)
        assert _wrong_value(hint) is None or cls == "ControlSetup", entry


def test_valid_instances_rebuild_through_the_check():
    """The registry's instances (built by the library itself) pass their own check again."""
    inst = _instances()
    assert len(inst) >= 30
    for name, obj in inst.items():
        again = dataclasses.replace(obj)
        assert type(again) is type(obj), name


def test_kinds_that_keep_working():
    """NumPy scalars for numbers, ints for floats, lists/tuples/arrays for arrays, None where
    the hint says ``| None``; bool is not a number."""
    from exofric.friction import FrictionModel, SqueezeCurve
    from exofric.hardware import Reading

    assert FrictionModel(np.float64(0.7), 1).gamma == pytest.approx(0.7)
    assert Reading(np.float32(0.3), 1, None).sample_id is None
    assert SqueezeCurve([0.2, 0.4], np.array([1.0, 2.0])).pressure_mpa is not None
    with pytest.raises(InputError, match=r"^gamma must be a number, got True \(bool\) in "
                                         r"FrictionModel\(\)"):
        FrictionModel(True)


def test_the_check_costs_microseconds_and_the_per_iteration_states_skip_it():
    """Construction cost of the classes built per step. ContactState/FrictionState are built
    on every Newton iteration (~900 per draft squeeze): the contact code builds them with
    ``unchecked`` (cheaper than the checked constructor). Reading (per device sample, >= 1 ms
    apart) and PathPoint (per load step) keep the check: it adds ~4-13 us (bound 100 us, a
    tenth of a 1 kHz sample period, on a loaded 2-core machine; benchmarks/bench_validate.py
    has the medians)."""
    from exofric._validate import unchecked
    from exofric.fe import ContactState, PathPoint
    from exofric.hardware import Reading

    a = np.zeros(200)

    def cost(make: Callable[[], Any]) -> float:
        return min(timeit.repeat(make, number=200, repeat=5)) / 200

    for cls, args in [(Reading, (0.3, 12.0, 5)), (PathPoint, (0.5, a, 3, 1)),
                      (ContactState, (0.0, a, a, a, a))]:
        raw, obj = inspect.unwrap(cls.__init__), object.__new__(cls)
        plain = cost(lambda r=raw, o=obj, a=args: r(o, *a))
        checked = cost(lambda c=cls, a=args: c(*a))
        assert checked - plain < 100e-6, cls.__name__
    assert cost(lambda: unchecked(ContactState, 0.0, a, a, a, a)) < \
        cost(lambda: ContactState(0.0, a, a, a, a))
    assert unchecked(Reading, 0.3, 12.0, 5) == Reading(0.3, 12.0, 5)
    src = inspect.getsource(importlib.import_module("exofric.fe._contact"))
    assert "unchecked(ContactState," in src and "unchecked(FrictionState," in src
