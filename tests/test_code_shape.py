"""The code's shape, as issue 32 set it: short functions, few parameters, complete objects.

Three structural checks over ``src/exofric`` (read with :mod:`ast` and :mod:`inspect`, nothing
run), each with its exceptions listed here with the reason:

* no function body over 100 lines outside ``cli/`` (the body: the lines after the docstring);
* no public function (a name in a stage's ``__all__``) over 10 parameters, except those in
  ``MANY_PARAMETERS``, each with why a setup object would not be clearer;
* no ``object.__setattr__`` on frozen dataclasses (objects are built complete), except those
  in ``SETATTR`` with the reason.

A new function that breaks a rule fails here with its file and line: split it, group its
parameters into a setup object, or add it to the list with a reason a reviewer accepts.
"""

from __future__ import annotations

import ast
import importlib
import inspect
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "exofric"
STAGES = ["exofric", "exofric.errors", "exofric.paper", "exofric.material", "exofric.geometry",
          "exofric.fe", "exofric.simulate", "exofric.calibration", "exofric.friction",
          "exofric.control", "exofric.hardware", "exofric.design", "exofric.reproduction",
          "exofric.io", "exofric.plots", "exofric.report"]

#: public function -> why it keeps more than 10 parameters
MANY_PARAMETERS: dict[str, str] = {
    "exofric.simulate.squeeze": (
        "the keyword front of SqueezeSetup (setup.solve(P) is the object form): one keyword per "
        "flag of `exofric squeeze`, all but three optional and keyword-only"),
    "exofric.calibration.calibrate": (
        "inflation data, the tube OD and keyword-only options that are each one flag of "
        "`exofric calibrate` (method, bracket, tolerances, the Shore-to-material conversion); "
        "a setup object would be built once and used once"),
    "exofric.errors.check_series": (
        "the one validator of paired series (21 callers): names, units and bounds of x and y "
        "are what it checks, each keyword-only with a neutral default"),
    "exofric.fe.evaluate_friction": (
        "an FE kernel called once per Newton iteration with the arrays of one contact; "
        "its arguments are state (positions, weights, anchors, the normal state), not options"),
    "exofric.fe.polar_mesh": (
        "each keyword is one independent geometric choice of the mesh (sector, grading and "
        "where it points, radial ratio, element kind, centre); MeshSpec is the setup object "
        "of the solvers that call it"),
    "exofric.hardware.run_loop": (
        "the real-time loop's safety options (limits, watchdog, vent at the end, dry run, "
        "baseline) are deliberately explicit keywords at the call that drives hardware, "
        "each one a flag of `exofric control run`"),
    "exofric.design.surrogate_search": (
        "the surrogate, the sweep and the design target (torque, arm, pressure limit), then "
        "keyword-only search options with defaults (candidates, confirmations, friction law, "
        "objective, seed)"),
    "exofric.friction.fit_gamma": (
        "the paper's Eq 7 data as four arrays (friction and squeeze, each pressure and force), "
        "then keyword-only options of the interval (model, method, bootstrap size, seed, "
        "clusters, measurement errors), each a flag of `exofric fit-friction`"),
    "exofric.friction.predict": (
        "structures, law, material and pressures, then keyword-only options of the check "
        "(measured curves, base structure, threshold, arm, torque range, alpha, a second law), "
        "each a flag of `exofric predict`"),
    "exofric.material.fit_material": (
        "a model and three optional test modes (uniaxial, biaxial, planar), then keyword-only "
        "fit options with defaults, each a flag of `exofric material fit`"),
    "exofric.calibration.calibrate_material": (
        "a joint fit over three optional data sets: each keyword belongs to one of them "
        "(inflation with the tube sizes and ends, tensile with its stress kind, ring), to the "
        "hardness prior, or to that set's noise level, so a setup object would only re-spell "
        "the data sets; all but the model are keyword-only with defaults, each one flag of "
        "`exofric calibrate --material`, and a user passes two to five of them"),
    "exofric.control.identify_charge": (
        "a measured charge (time, pressure, command) and keyword-only physical constants of "
        "the gas and the valve (supply, volume, conductance, critical ratio, polytropic "
        "index, temperature, atmosphere), each with a documented default"),
}

_NORMALISE = (
    "normalisation in __post_init__ only: the public constructor takes ints, NumPy scalars, "
    "lists and arrays and stores floats and tuples of float (hash, equality, one JSON form); "
    "a frozen dataclass sets a field only this way, as its generated __init__ does (each "
    "site says so in a comment)")

#: file -> why its object.__setattr__ stay (caches are cached_property, objects built
#: by mutation are built complete; issue 32 took the count from 44 to 30)
SETATTR: dict[str, str] = {
    name: _NORMALISE for name in (
        "geometry.py", "material/_models.py", "material/_hyperelastic.py",
        "control/_pneumatic.py", "friction/_curve.py", "friction/_interfaces.py",
        "friction/_model.py", "calibration/_material.py", "calibration/_result.py")
} | {"cli/_options.py": (
    "OptionGroup.__init__ is the frozen record's own constructor, setting each field once; "
    "the CLI's ~20 option groups are plain classes because dataclasses cost start-up time")}


def _functions() -> list[tuple[Path, ast.FunctionDef | ast.AsyncFunctionDef]]:
    out = []
    for path in sorted(SRC.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                out.append((path, node))
    return out


def _body_lines(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    body = node.body
    first = body[0]
    if (isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
            and isinstance(first.value.value, str)):
        if len(body) == 1:
            return 0
        first = body[1]
    return int(node.end_lineno or first.lineno) - first.lineno + 1


def test_no_function_body_over_100_lines_outside_cli() -> None:
    long = [f"{p.relative_to(SRC)}:{n.lineno} {n.name} ({_body_lines(n)} lines)"
            for p, n in _functions() if "cli" not in p.relative_to(SRC).parts
            and _body_lines(n) > 100]
    assert not long, long


def _public_functions() -> dict[str, object]:
    found: dict[str, object] = {}
    for mod_name in STAGES:
        mod = importlib.import_module(mod_name)
        for name in getattr(mod, "__all__", []):
            obj = getattr(mod, name)
            if inspect.isfunction(obj):
                found.setdefault(f"{obj.__module__.split('._')[0]}.{name}", obj)
    return found


def test_public_functions_have_at_most_10_parameters() -> None:
    many = {}
    for name, fn in _public_functions().items():
        n = len([p for p in inspect.signature(fn).parameters.values()  # type: ignore[arg-type]
                 if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)])
        if n > 10 and name not in MANY_PARAMETERS:
            many[name] = n
    assert not many, f"over 10 parameters (group them, or list them with a reason): {many}"


def test_the_exceptions_are_still_needed() -> None:
    """An exception whose function got shorter (or went away) leaves the list."""
    funcs = _public_functions()
    for name in MANY_PARAMETERS:
        assert name in funcs, f"{name} is no longer public: remove it from MANY_PARAMETERS"
        n = len(inspect.signature(funcs[name]).parameters)  # type: ignore[arg-type]
        assert n > 10, f"{name} has {n} parameters now: remove it from MANY_PARAMETERS"


def test_objects_are_built_complete() -> None:
    uses = []
    for path in sorted(SRC.rglob("*.py")):
        for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if "object.__setattr__(" in line and not line.lstrip().startswith("#"):
                if path.relative_to(SRC).as_posix() not in SETATTR:
                    uses.append(f"{path.relative_to(SRC)}:{i}")
    assert not uses, f"object.__setattr__ (build the object complete instead): {uses}"


@pytest.mark.parametrize("name", sorted(MANY_PARAMETERS))
def test_every_exception_has_a_reason(name: str) -> None:
    assert len(MANY_PARAMETERS[name].split()) >= 8
