"""Every public name is documented, with units and an example (python-control style meta-test).

Walks ``exofric.__all__`` and every public subpackage's ``__all__``; for each public function,
each public class (its constructor or dataclass fields) and each public method or property of
those classes it parses the numpydoc docstring (:mod:`numpydoc.docscrape`) and checks that

(a) there is a docstring with a summary line;
(b) every parameter of the signature is in ``Parameters`` (dataclasses: ``Parameters`` or
    ``Attributes``; ``a, b : float`` documents both; ``*args``/``**kwargs`` must be documented
    under that name);
(c) nothing is documented in ``Parameters`` that the signature does not take (and a class's
    ``Attributes`` are real attributes);
(d) every parameter, field or property that is a physical quantity says its unit: a unit suffix
    in its name (``pressure_mpa``, ``hole_mm``, ``k_n_per_mm``) or a unit in its description
    (``(MPa)``, ``in mm``, ``N/mm``, ``unitless``); "physical quantity" is decided by the reviewed
    name patterns in ``PHYSICAL`` and the exceptions live in ``ALLOW_NO_UNIT`` with a reason each;
(e) every public function and class has an ``Examples`` section (the examples themselves run in
    ``make test`` through ``--doctest-modules``).

The constants of :mod:`exofric.defaults` are checked for a ``#:`` doc comment (with a unit when
they are physical). A failure names the object and the missing item.
"""

from __future__ import annotations

import ast
import dataclasses
import enum
import functools
import importlib
import inspect
import re
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

docscrape = pytest.importorskip("numpydoc.docscrape")

#: The public import paths: the top-level facade and every stage's ``__all__``.
MODULES = [
    "exofric",
    "exofric.errors",
    "exofric.paper",
    "exofric.material",
    "exofric.geometry",
    "exofric.fe",
    "exofric.defaults",
    "exofric.simulate",
    "exofric.calibration",
    "exofric.friction",
    "exofric.control",
    "exofric.hardware",
    "exofric.design",
    "exofric.reproduction",
    "exofric.io",
    "exofric.plots",
    "exofric.report",
]

# ---------------------------------------------------------------------------------------------
# (d) units. A name is a physical quantity when one of its ``_``-separated words matches one of
# these patterns (reviewed list: add a word here rather than skipping an object).
PHYSICAL = [
    r"pressures?", r"forces?", r"frictions?", r"loads?",
    r"torques?", r"tensions?", r"stress(es)?", r"diameters?", r"radius", r"radii", r"lengths?",
    r"width", r"halfwidth", r"height", r"thickness", r"wall", r"hole", r"wire", r"od", r"gap",
    r"clearance", r"displacements?", r"stroke", r"penetration", r"times?", r"t", r"dt",
    r"duration", r"delay", r"dead", r"tau", r"settling", r"rise", r"horizon", r"period",
    r"frequency", r"freq", r"rate", r"speed", r"velocity", r"modulus", r"moduli", r"shear",
    r"c10", r"c01", r"mu", r"bulk", r"kappa", r"stiffness", r"penalty", r"density", r"gravity",
    r"area", r"volume", r"gamma", r"gammas", r"kp", r"ki", r"kd", r"gain", r"gains", r"slope",
    r"overshoot", r"setpoint", r"setpoints", r"hardness", r"shore", r"stretch", r"strain",
    r"angle", r"theta", r"noise", r"pull", r"tol",
    r"rtol", r"atol", r"itae", r"error", r"errors", r"deviation", r"weight", r"mass",
]
_PHYSICAL_RE = re.compile(r"^(?:" + "|".join(PHYSICAL) + r")$")
#: Words that make a name a count, ratio of like quantities' settings, flag or label instead
#: (``n_radial``, ``c01_ratio``, ``c10_convention``, ``p_value``, ``gain_assumed``).
NOT_PHYSICAL = {"n", "ratio", "divisor", "convention", "kind", "assumed", "value", "name",
                "label", "index", "count", "method", "fn"}
#: Types that are never a quantity (``pressure : bool`` is a switch).
_NOT_QUANTITY_TYPE = re.compile(r"^\s*(bool|str|path|callable|\{)", re.IGNORECASE)

#: Name suffixes that are units (``pressure_mpa``, ``k_n_per_mm``, ``error_pct``, ``omega_rad_s``).
UNIT_SUFFIXES = {
    "mm", "mm2", "mm3", "m", "mpa", "kpa", "pa", "n", "nm", "nmm", "s", "ms", "hz", "pct",
    "deg", "rad", "mm_s", "mm_s2", "t_per_mm3", "shore", "shore_a",
}
_UNIT_SUFFIX_RE = re.compile(
    r"_(?:" + "|".join(sorted(UNIT_SUFFIXES, key=len, reverse=True)) + r")$|_per_\w+$"
)

# Units recognised in a description: unambiguous unit words anywhere; one-letter units (N, s, t)
# inside parentheses, after "in"/"per", or in a compound (N/mm, MPa/N, 1/s).
_UNITS = r"mm|mm\^?[23]|MPa|kPa|Pa|Nm|N|s|ms|Hz|rad|deg|%|t|g|kg|m|Shore|unitless|dimensionless"
_UNIT_ANYWHERE = re.compile(
    r"(?<![\w.])(?:mm|MPa|kPa|Nm|Hz|rad/s|unitless|dimensionless|Shore\s*A|percent|"
    r"seconds?|newtons?|millimet(?:re|er)s?|degrees?|radians?)(?![\w])|%|"
    r"(?<![\w])(?:" + _UNITS + r")(?:\^-?\d)?\s*/\s*(?:" + _UNITS + r")(?![\w])|"
    r"(?<![\w])1/(?:" + _UNITS + r")(?![\w])|"
    r"\b(?:in|per)\s+(?:" + _UNITS + r")(?![\w])"
)
_PAREN = re.compile(r"\(([^()]*)\)")
_PAREN_UNIT = re.compile(r"(?<![\w.])(?:" + _UNITS + r")(?:\^-?\d)?(?![\w])")

#: Physical-looking names that do not carry a unit, each with the reason. Keys are
#: ``"<object id>:<name>"`` or ``"*:<name>"`` for a name that means the same everywhere.
ALLOW_NO_UNIT: dict[str, str] = {
}


#: Known gaps, one ``"<test> <id>"`` each: docstrings not yet completed when this test landed
#: (2026 restructuring; other modules were being edited at the same time). Each is a strict
#: xfail, so completing a docstring makes its entry fail until it is deleted here. Shrink only.
KNOWN_GAPS: frozenset[str] = frozenset({
})


def _is_physical(name: str, type_: str = "") -> bool:
    if _NOT_QUANTITY_TYPE.match(type_):
        return False
    words = name.lower().strip("*").split("_")
    if NOT_PHYSICAL & set(words):
        return False
    return any(_PHYSICAL_RE.match(w) for w in words)


def _has_unit_suffix(name: str) -> bool:
    return bool(_UNIT_SUFFIX_RE.search(name.lower()))


def _has_unit_text(text: str) -> bool:
    if _UNIT_ANYWHERE.search(text):
        return True
    return any(_PAREN_UNIT.search(g) for g in _PAREN.findall(text))


# ---------------------------------------------------------------------------------------------
# Walking the public API.


@dataclasses.dataclass(frozen=True)
class Item:
    """One documented object: ``ident`` names it in failures."""

    ident: str
    obj: Any
    kind: str  # "function", "class", "method", "property"
    owner: type | None = None


def _unwrap(obj: Any) -> Any:
    if isinstance(obj, functools._lru_cache_wrapper):  # paper.load
        return obj.__wrapped__
    return obj


def _public_members(cls: type) -> Iterator[tuple[str, Any]]:
    """Public methods and properties defined by ``cls`` or its exofric bases."""
    seen: set[str] = set()
    for klass in cls.__mro__:
        if not klass.__module__.startswith("exofric"):
            continue
        for name, member in vars(klass).items():
            if name.startswith("_") or name in seen:
                continue
            seen.add(name)
            if isinstance(member, (staticmethod, classmethod)):
                yield name, member.__func__
            elif isinstance(member, property):
                yield name, member
            elif isinstance(member, functools.cached_property):
                yield name, member
            elif inspect.isfunction(member):
                yield name, member


def _collect() -> tuple[list[Item], list[tuple[str, str]]]:
    items: list[Item] = []
    constants: list[tuple[str, str]] = []
    seen: set[int] = set()
    # subpackages first, so a facade name is reported under its home
    for modname in [*MODULES[1:], MODULES[0]]:
        mod = importlib.import_module(modname)
        for name in mod.__all__:
            obj = _unwrap(getattr(mod, name))
            if id(obj) in seen:
                continue
            seen.add(id(obj))
            ident = f"{modname}.{name}"
            if inspect.isclass(obj):
                items.append(Item(ident, obj, "class"))
                for mname, member in _public_members(obj):
                    key = id(member)
                    if key in seen:
                        continue
                    seen.add(key)
                    kind = "property" if isinstance(
                        member, (property, functools.cached_property)) else "method"
                    items.append(Item(f"{ident}.{mname}", member, kind, obj))
            elif inspect.isfunction(obj):
                items.append(Item(ident, obj, "function"))
            elif modname == "exofric.defaults":
                constants.append((modname, name))
    return items, constants


ITEMS, CONSTANTS = _collect()
_IDS = [it.ident for it in ITEMS]
CALLABLES = [it for it in ITEMS if it.kind in ("function", "class", "method")]
TOPLEVEL = [it for it in ITEMS if it.kind in ("function", "class")]


def _raw_doc(obj: Any) -> str:
    if isinstance(obj, (property, functools.cached_property)):
        doc = obj.__doc__ or ""
    else:
        doc = obj.__dict__.get("__doc__") if inspect.isclass(obj) else obj.__doc__
        doc = doc or ""
    if inspect.isclass(obj) and dataclasses.is_dataclass(obj) and doc.startswith(
            obj.__name__ + "("):
        return ""  # the signature dataclasses writes when there is no docstring
    return inspect.cleandoc(doc)


@functools.cache
def _parsed(ident: str) -> Any:
    obj = next(it.obj for it in ITEMS if it.ident == ident)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an unknown section or malformed block fails loudly
        return docscrape.NumpyDocString(_raw_doc(obj))


def _names(section: list[Any]) -> dict[str, tuple[str, str]]:
    """``{name: (type, description)}``; ``a, b : float`` documents ``a`` and ``b``."""
    out: dict[str, tuple[str, str]] = {}
    for p in section:
        for n in p.name.split(","):
            n = n.strip()
            if n:
                out[n] = (p.type, " ".join(p.desc))
    return out


def _strip_stars(name: str) -> str:
    return name.lstrip("*")


def _has_own_init(cls: type) -> bool:
    if dataclasses.is_dataclass(cls):
        return True
    if issubclass(cls, (BaseException, enum.Enum)) or getattr(cls, "_is_protocol", False):
        return False
    return any(
        "__init__" in vars(k) or "__new__" in vars(k)
        for k in cls.__mro__ if k.__module__.startswith("exofric")
    )


def _signature_params(item: Item) -> list[inspect.Parameter] | None:
    obj = item.obj
    if item.kind == "class":
        if not _has_own_init(obj):
            return None
        sig = inspect.signature(obj)
    else:
        sig = inspect.signature(obj)
    params = list(sig.parameters.values())
    if item.kind == "method" and params and params[0].name in ("self", "cls"):
        params = params[1:]
    return params


def _param_key(p: inspect.Parameter) -> str:
    if p.kind is p.VAR_POSITIONAL:
        return "*" + p.name
    if p.kind is p.VAR_KEYWORD:
        return "**" + p.name
    return p.name



def _cases(test: str, items: list[Any], ids: list[str]) -> list[Any]:
    """Parametrise ``test`` over ``items``; a ``KNOWN_GAPS`` entry is a strict xfail."""
    out = []
    for item, ident in zip(items, ids, strict=True):
        marks = ([pytest.mark.xfail(strict=True, reason="known gap (KNOWN_GAPS): document it")]
                 if f"{test} {ident}" in KNOWN_GAPS else [])
        out.append(pytest.param(item, id=ident, marks=marks))
    return out


# ---------------------------------------------------------------------------------------------
# The checks.


def test_walk_is_not_empty() -> None:
    """The walk found the public API (guards against an import path silently going missing)."""
    assert len(TOPLEVEL) > 150, len(TOPLEVEL)
    assert any(it.ident == "exofric.simulate.squeeze" for it in ITEMS)


@pytest.mark.parametrize("item", _cases("test_summary", ITEMS, _IDS))
def test_summary(item: Item) -> None:
    """(a) a docstring with a one-line summary."""
    doc = _parsed(item.ident)
    assert _raw_doc(item.obj), f"{item.ident}: no docstring"
    assert doc["Summary"] and doc["Summary"][0].strip(), f"{item.ident}: no summary line"


@pytest.mark.parametrize("item", _cases("test_parameters_documented", CALLABLES,
                                         [it.ident for it in CALLABLES]))
def test_parameters_documented(item: Item) -> None:
    """(b) every signature parameter is documented; (c) nothing extra is documented."""
    params = _signature_params(item)
    if params is None:
        return
    doc = _parsed(item.ident)
    documented = _names(doc["Parameters"]) | _names(doc["Other Parameters"])
    is_dc = item.kind == "class" and dataclasses.is_dataclass(item.obj)
    attrs = _names(doc["Attributes"]) if is_dc else {}
    bare = {_strip_stars(n) for n in documented} | set(attrs)
    missing = []
    for p in params:
        key = _param_key(p)
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            ok = key in documented or p.name in documented
        else:
            ok = p.name in bare
        if not ok:
            missing.append(key)
    assert not missing, f"{item.ident}: parameter(s) not in Parameters: {', '.join(missing)}"
    sig_names = {p.name for p in params}
    extra = [n for n in documented if _strip_stars(n) not in sig_names]
    assert not extra, f"{item.ident}: documented but not in the signature: {', '.join(extra)}"


@pytest.mark.parametrize("item", _cases(
    "test_attributes_exist", [it for it in TOPLEVEL if it.kind == "class"],
    [it.ident for it in TOPLEVEL if it.kind == "class"]))
def test_attributes_exist(item: Item) -> None:
    """(c) a class's documented Attributes are real attributes (fields, properties, methods)."""
    doc = _parsed(item.ident)
    cls = item.obj
    fields = {f.name for f in dataclasses.fields(cls)} if dataclasses.is_dataclass(cls) else set()
    annotated = set()
    for k in cls.__mro__:
        annotated |= set(getattr(k, "__annotations__", {}))
    try:  # attributes set in a method (``self.calls = 0``)
        assigned = set(re.findall(r"self\.(\w+)\s*(?::[^=]+)?=", inspect.getsource(cls)))
    except (OSError, TypeError):
        assigned = set()
    bogus = [n for n in _names(doc["Attributes"])
             if n not in fields | annotated | assigned and not hasattr(cls, n)]
    assert not bogus, f"{item.ident}: Attributes not on the class: {', '.join(bogus)}"


def _unit_cases() -> Iterator[tuple[str, str, str, str]]:
    for it in ITEMS:
        if it.kind == "property":
            yield it.ident, it.ident.rsplit(".", 1)[1], "", _raw_doc(it.obj)
            continue
        doc = _parsed(it.ident)
        entries = _names(doc["Parameters"]) | _names(doc["Other Parameters"])
        if it.kind == "class":
            entries |= _names(doc["Attributes"])
        for name, (type_, desc) in entries.items():
            yield it.ident, name, type_, desc


UNIT_CASES = [(i, n, f"{t} {d}".strip()) for i, n, t, d in _unit_cases() if _is_physical(n, t)]


@pytest.mark.parametrize("case", _cases("test_units", UNIT_CASES,
                                         [f"{i}:{n}" for i, n, _ in UNIT_CASES]))
def test_units(case: tuple[str, str, str]) -> None:
    """(d) a physical quantity says its unit, in its name or its description."""
    ident, name, desc = case
    if f"{ident}:{name}" in ALLOW_NO_UNIT or f"*:{name}" in ALLOW_NO_UNIT:
        return
    assert _has_unit_suffix(name) or _has_unit_text(desc), (
        f"{ident}: {name!r} is a physical quantity without a unit (name suffix such as _mm, "
        f"_mpa, _n, _s or a unit in its description); description: {desc!r}")


def test_known_gaps_are_real() -> None:
    """Every KNOWN_GAPS entry names a test case that exists (renamed objects leave no stale
    entries)."""
    ids = {f"test_summary {i}" for i in _IDS}
    ids |= {f"test_parameters_documented {it.ident}" for it in CALLABLES}
    ids |= {f"test_attributes_exist {it.ident}" for it in TOPLEVEL if it.kind == "class"}
    ids |= {f"test_units {i}:{n}" for i, n, _ in UNIT_CASES}
    ids |= {f"test_examples {it.ident}" for it in TOPLEVEL}
    stale = sorted(KNOWN_GAPS - ids)
    assert not stale, f"KNOWN_GAPS entries that match no test case: {stale}"


def test_allow_list_is_used() -> None:
    """Every allow-list entry still matches something (no stale exceptions)."""
    names = {n for _, n, _ in UNIT_CASES} | {f"{i}:{n}" for i, n, _ in UNIT_CASES}
    stale = [k for k in ALLOW_NO_UNIT
             if (k[2:] if k.startswith("*:") else k) not in names]
    assert not stale, f"allow-list entries that match nothing: {stale}"


@pytest.mark.parametrize("item", _cases("test_examples", TOPLEVEL,
                                         [it.ident for it in TOPLEVEL]))
def test_examples(item: Item) -> None:
    """(e) every public function and class has an Examples section."""
    doc = _parsed(item.ident)
    assert any(line.strip() for line in doc["Examples"]), f"{item.ident}: no Examples section"


def _doc_comments(modname: str) -> dict[str, str]:
    """``#:`` comments above each module-level assignment."""
    path = Path(importlib.import_module(modname).__file__ or "")
    lines = path.read_text().splitlines()
    out: dict[str, str] = {}
    for node in ast.parse(path.read_text()).body:
        targets = []
        if isinstance(node, ast.Assign):
            targets = [t.id for t in node.targets if isinstance(t, ast.Name)]
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            targets = [node.target.id]
        comment: list[str] = []
        i = node.lineno - 2
        while i >= 0 and lines[i].lstrip().startswith("#:"):
            comment.insert(0, lines[i].lstrip()[2:].strip())
            i -= 1
        for t in targets:
            out[t] = " ".join(comment)
    return out


@pytest.mark.parametrize("modname,name", CONSTANTS, ids=[f"{m}.{n}" for m, n in CONSTANTS])
def test_default_constants(modname: str, name: str) -> None:
    """Each default has a ``#:`` doc comment, with its unit when it is physical."""
    comment = _doc_comments(modname).get(name, "")
    assert comment, f"{modname}.{name}: no '#:' doc comment"
    if _is_physical(name):
        assert _has_unit_suffix(name) or _has_unit_text(comment), (
            f"{modname}.{name}: physical constant without a unit")

