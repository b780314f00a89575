"""Argument types of the public functions, checked from their type hints (issue 38).

Every function a stage's ``__init__`` exports is wrapped once, where the package exports it
(:func:`exofric._lazy.lazy_package` and :func:`exofric._lazy.export_checked`), by
:func:`checked`: a call whose argument does not have the type its hint says raises
:class:`~exofric.errors.InputError` naming the parameter (``mu_wall must be a number, got
'0.2' (str) in squeeze()``), instead of a builtin ``TypeError`` deep inside or, worse, a string
accepted as a number. Missing and unexpected arguments are InputErrors too. Values are not
checked here (ranges are the function's own checks), only kinds.

What a hint accepts (the docstrings' promises):

* ``float`` -- any real number (``int``, NumPy scalars, a 0-d array), never ``bool`` or a str;
  ``int`` -- integers (NumPy integers too), never ``bool`` or ``4.0``; ``bool`` -- ``True`` /
  ``False`` (and NumPy's);
* ``str`` -- str; ``Path`` -- a ``str`` or any ``os.PathLike`` (a str is passed on as a
  ``Path`` where the hint is ``Path`` only);
* ``ArrayLike``, ``np.ndarray``, ``NDArray[...]``, ``Sequence[float]`` / ``list[int]`` /
  ``tuple[float, ...]`` -- numbers: a list, tuple or array of real numbers (ints for ``int``),
  a scalar only for ``ArrayLike``; never a str, a mapping, or a list holding strings or None;
* ``Sequence[X]`` of other ``X`` -- a list or tuple of ``X`` (not a str);
  ``tuple[X, Y]`` -- that many values; ``Mapping[K, V]`` -- a mapping of ``K`` to ``V``;
* ``Callable`` -- any callable; ``Literal[...]`` -- the literals' type (the value is the
  function's own check); a class -- an instance of it;
* ``Any``, ``object``, type variables, protocols and names that do not resolve -- anything.

Every public dataclass (data, settings and results: 124 classes) checks its fields the same
way at construction (:func:`checked_init`); the per-iteration states of the contact code are
built with :func:`unchecked` (no user input reaches them).

A parameter left at its default is not checked. The hints are read on a function's first
call (a few hundred microseconds, once); a checked call costs a few microseconds
(``benchmarks/bench_validate.py``).
"""

from __future__ import annotations

import ast
import functools
import inspect
import numbers
import os
import reprlib
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, TypeVar

from exofric.errors import InputError

__all__ = ["checked", "checked_init", "is_checked", "unchecked"]

F = TypeVar("F", bound=Callable[..., Any])

_ANY = None  # a parameter that takes anything: no check
_REPR = reprlib.Repr()
_REPR.maxstring, _REPR.maxother, _REPR.maxlist = 40, 40, 4


@dataclass(frozen=True)
class _Spec:
    """One kind a hint accepts: ``test(value) -> bool`` and what it reads as in a message."""

    test: Callable[[Any], bool]
    says: str


# ---- the elementary kinds --------------------------------------------------------------------

def _is_real(x: Any) -> bool:
    t = type(x)
    if t is float or t is int:     # the common case first: a few hundred nanoseconds
        return True
    if t is bool or t.__name__ == "bool_":
        return False
    if isinstance(x, numbers.Real):
        return True
    return _array_kind(x, "iuf") and getattr(x, "ndim", 1) == 0


def _is_int(x: Any) -> bool:
    t = type(x)
    if t is int:
        return True
    return t is not bool and t.__name__ != "bool_" and isinstance(x, numbers.Integral)


def _is_bool(x: Any) -> bool:
    return type(x) is bool or type(x).__name__ == "bool_"


def _array_kind(x: Any, kinds: str) -> bool:
    """``x`` is a NumPy array whose dtype kind is one of ``kinds``."""
    np = sys.modules.get("numpy")
    return np is not None and isinstance(x, np.ndarray) and x.dtype.kind in kinds


def _numbers(kinds: str, scalar: bool) -> Callable[[Any], bool]:
    """Test: a list/tuple/array of numbers of dtype kinds ``kinds`` (a scalar if ``scalar``)."""
    plain = {float, int} if "f" in kinds else {int} if "i" in kinds else {bool}

    def test(x: Any) -> bool:
        t = type(x)
        if t is list or t is tuple:    # plain numbers: no NumPy call (0.02 us per element)
            if set(map(type, x)) <= plain:
                return True
        elif t.__name__ == "ndarray":   # its dtype says it, no copy
            return bool(x.dtype.kind in kinds) and (scalar or x.ndim > 0)
        elif isinstance(x, (str, bytes, Mapping)) or x is None:
            return False
        elif scalar and (_is_real(x) or (_is_bool(x) and "b" in kinds)):
            return True
        elif not hasattr(x, "__len__"):
            return False
        import numpy as np

        try:
            a = np.asarray(x)
        except (TypeError, ValueError):    # ragged nests and the like
            return False
        return bool(a.dtype.kind in kinds) and (scalar or a.ndim > 0)

    return test


REAL = _Spec(_is_real, "a number")
INT = _Spec(_is_int, "an integer")
BOOL = _Spec(_is_bool, "True or False")
STR = _Spec(lambda x: isinstance(x, str), "a string")
NONE = _Spec(lambda x: x is None, "None")
PATH = _Spec(lambda x: isinstance(x, (str, os.PathLike)), "a path (str or pathlib.Path)")
CALLABLE = _Spec(callable, "a callable")
ARRAY = _Spec(_numbers("biuf", scalar=True), "numbers (a number, a list or an array)")
_ELEMENT_KINDS = {id(REAL): "biuf", id(INT): "iu", id(BOOL): "b"}


def _union(specs: list[_Spec | None]) -> _Spec | None:
    if any(s is _ANY for s in specs):
        return _ANY
    parts: list[_Spec] = []
    for sp in specs:
        if sp is not None and all(sp.says != q.says for q in parts):
            parts.append(sp)
    if len(parts) == 1:
        return parts[0]
    a, b, *rest = (q.test for q in parts)
    says = " or ".join(q.says for q in parts)
    if not rest:
        return _Spec(lambda x: a(x) or b(x), says)
    return _Spec(lambda x: a(x) or b(x) or any(t(x) for t in rest), says)


def _seq_of(elem: _Spec | None, what: str = "list") -> _Spec:
    """A list/tuple/array of numbers (element kind REAL/INT/BOOL) or a list/tuple of ``elem``."""
    if elem is not None and id(elem) in _ELEMENT_KINDS:
        return _Spec(_numbers(_ELEMENT_KINDS[id(elem)], scalar=False),
                     f"a {what} or array of {_plural(elem.says)}")

    def test(x: Any) -> bool:
        if isinstance(x, (str, bytes, Mapping)) or not hasattr(x, "__iter__"):
            return False
        if elem is None or not isinstance(x, (list, tuple)):
            return True          # other iterables are not consumed here
        return all(elem.test(v) for v in x)

    return _Spec(test, f"a {what}" + ("" if elem is None else f" of {_plural(elem.says)}"))


def _plural(says: str) -> str:
    """``"a number"`` -> ``"numbers"``; longer phrases as ``"items (each: ...)"``."""
    if says == BOOL.says:
        return "True/False"
    head, _, noun = says.partition(" ")
    if head in ("a", "an") and noun.isidentifier():
        return f"{noun}s"
    return f"items (each {says})"


def _fixed(elems: list[_Spec | None]) -> _Spec:
    n = len(elems)

    def test(x: Any) -> bool:
        if isinstance(x, (str, bytes, Mapping)) or not hasattr(x, "__len__") or len(x) != n:
            return False
        return all(e is None or e.test(v) for e, v in zip(elems, x, strict=True))

    what = "numbers" if all(e is REAL for e in elems) else "values"
    return _Spec(test, f"a sequence of {n} {what}")


def _mapping(key: _Spec | None, value: _Spec | None) -> _Spec:
    def test(x: Any) -> bool:
        if not isinstance(x, Mapping):
            return False
        return all((key is None or key.test(k)) and (value is None or value.test(v))
                   for k, v in x.items())

    return _Spec(test, "a mapping (dict)")


def _instance(cls: type) -> _Spec | None:
    if cls is float:
        return REAL
    if cls is int:
        return INT
    if cls is bool:
        return BOOL
    if cls is str:
        return STR
    if getattr(cls, "_is_protocol", False) and not getattr(cls, "_is_runtime_protocol", False):
        return _ANY
    if cls is object:
        return _ANY
    return _Spec(lambda x: isinstance(x, cls), _article(cls.__name__))


def _article(name: str) -> str:
    return f"{'an' if name[:1].lower() in 'aeiou' else 'a'} {name}"


# ---- reading a hint --------------------------------------------------------------------------

_NAMED: dict[str, _Spec | None] = {
    "float": REAL, "Real": REAL, "int": INT, "Integral": INT, "bool": BOOL, "str": STR,
    "Path": PATH, "PurePath": PATH, "PathLike": PATH, "Any": _ANY, "object": _ANY,
    "ArrayLike": ARRAY, "ndarray": _seq_of(REAL, "list"), "NDArray": _seq_of(REAL, "list"),
    "Callable": CALLABLE, "None": NONE, "NoneType": NONE,
}
_SEQUENCES = {"Sequence", "Collection", "Iterable", "list", "tuple", "set", "frozenset",
              "MutableSequence", "AbstractSet"}
_MAPPINGS = {"Mapping", "dict", "MutableMapping"}


class _Reader:
    """Turns one function's annotation strings into :class:`_Spec` (names from its module)."""

    def __init__(self, fn: Callable[..., Any]) -> None:
        # the module the hints were written in (past decorators such as @contextmanager)
        self.globals: dict[str, Any] = getattr(inspect.unwrap(fn), "__globals__", {})
        self._tc: dict[str, tuple[str, str | None]] | None = None

    def spec(self, hint: Any) -> _Spec | None:
        if isinstance(hint, str):
            try:
                node = ast.parse(hint, mode="eval").body
            except SyntaxError:
                return _ANY
            return self.node(node)
        return self.runtime(hint)

    def node(self, n: ast.expr) -> _Spec | None:
        if isinstance(n, ast.Constant):
            if n.value is None:
                return NONE
            return self.spec(n.value) if isinstance(n.value, str) else _ANY
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.BitOr):
            return _union([self.node(n.left), self.node(n.right)])
        if isinstance(n, ast.Subscript):
            return self.subscript(_last(n.value), n.slice)
        name = _last(n)
        if name in _NAMED:
            return _NAMED[name]
        if name in _SEQUENCES:
            return _seq_of(None)
        if name in _MAPPINGS:
            return _mapping(None, None)
        return self.runtime(self.resolve(n))

    def subscript(self, name: str, sl: ast.expr) -> _Spec | None:
        args = list(sl.elts) if isinstance(sl, ast.Tuple) else [sl]
        if name in ("Optional", "Union"):
            return _union([self.node(a) for a in args] + ([NONE] if name == "Optional" else []))
        if name == "Literal":
            kinds = {type(a.value) for a in args if isinstance(a, ast.Constant)}
            return self.runtime(kinds.pop()) if len(kinds) == 1 else _ANY
        if name == "NDArray":
            return _NAMED["NDArray"]
        if name == "tuple" and not (len(args) == 2 and _is_ellipsis(args[1])):
            return _fixed([self.node(a) for a in args])
        if name in _SEQUENCES:
            return _seq_of(self.node(args[0]))
        if name in _MAPPINGS and len(args) == 2:
            return _mapping(self.node(args[0]), self.node(args[1]))
        if name == "Callable":
            return CALLABLE
        return self.node(ast.Name(id=name)) if name not in ("type", "Annotated") else _ANY

    def resolve(self, n: ast.expr) -> Any:
        """The object a (dotted) name in a hint means, or None (then: anything)."""
        parts: list[str] = []
        while isinstance(n, ast.Attribute):
            parts.insert(0, n.attr)
            n = n.value
        if not isinstance(n, ast.Name):
            return None
        obj = self.base(n.id)
        for p in parts:
            obj = obj.child(p) if isinstance(obj, _NotLoaded) else getattr(obj, p, None)
        return obj

    def base(self, name: str) -> Any:
        if name in self.globals:
            return self.globals[name]
        where = self.type_checking().get(name)
        if where is None:
            import builtins

            return getattr(builtins, name, None)
        module, attr = where
        mod = sys.modules.get(module)
        if mod is None:      # resolved when a call needs it (see _NotLoaded)
            return _NotLoaded(module, () if attr is None else (attr,))
        return mod if attr is None else getattr(mod, attr, None)

    def type_checking(self) -> dict[str, tuple[str, str | None]]:
        if self._tc is None:
            self._tc = _type_checking_imports(self.globals.get("__file__"))
        return self._tc

    def runtime(self, obj: Any) -> _Spec | None:
        if isinstance(obj, _NotLoaded):
            return _Spec(obj.test, _article(obj.attrs[-1] if obj.attrs else obj.module))
        if obj is None or obj is type(None):
            return NONE if obj is type(None) else _ANY
        if isinstance(obj, str):
            return self.spec(obj)
        if isinstance(obj, type) and not hasattr(obj, "__origin__"):
            return _instance(obj)
        return self.alias(obj)

    def alias(self, obj: Any) -> _Spec | None:
        """A runtime typing object (``Literal[...]``, ``Callable[...]``, a union)."""
        import typing

        origin, args = typing.get_origin(obj), typing.get_args(obj)
        np_typing = sys.modules.get("numpy.typing")
        if np_typing is not None and obj is getattr(np_typing, "ArrayLike", None):
            return ARRAY
        if origin is typing.Literal:
            kinds = {type(a) for a in args}
            return self.runtime(kinds.pop()) if len(kinds) == 1 else _ANY
        if origin is typing.Union or type(obj).__name__ == "UnionType":
            return _union([self.runtime(a) for a in args])
        if isinstance(obj, typing.ForwardRef):
            return self.spec(obj.__forward_arg__)
        if origin is None:
            return _ANY     # a TypeVar, NewType, ...
        name = getattr(origin, "__name__", "")
        if callable(obj) and name == "Callable":
            return CALLABLE
        if name in _SEQUENCES:
            return _seq_of(self.runtime(args[0]) if args else None)
        if name in _MAPPINGS:
            return _mapping(*(self.runtime(a) for a in args)) if len(args) == 2 \
                else _mapping(None, None)
        return self.runtime(origin) if isinstance(origin, type) else _ANY


@dataclass(frozen=True)
class _NotLoaded:
    """A class of a module not imported when the hints were read (``pd.DataFrame``).

    Its test imports nothing: while the module is not imported no argument can be one of its
    classes; once it is, the class is looked up (a name that is not a class accepts anything).
    """

    module: str
    attrs: tuple[str, ...]

    def child(self, attr: str) -> _NotLoaded:
        return _NotLoaded(self.module, (*self.attrs, attr))

    def test(self, x: Any) -> bool:
        obj: Any = sys.modules.get(self.module)
        if obj is None:
            return False
        for a in self.attrs:
            obj = getattr(obj, a, None)
        return not isinstance(obj, type) or isinstance(x, obj)


def _last(n: ast.expr) -> str:
    if isinstance(n, ast.Attribute):
        return n.attr
    return n.id if isinstance(n, ast.Name) else ""


def _is_ellipsis(n: ast.expr) -> bool:
    return isinstance(n, ast.Constant) and n.value is Ellipsis


@functools.cache
def _type_checking_imports(path: str | None) -> dict[str, tuple[str, str | None]]:
    """Names imported under ``if TYPE_CHECKING:`` in the module at ``path`` -> (module, attr)."""
    if not path:
        return {}
    from pathlib import Path

    try:
        tree = ast.parse(Path(path).read_text(encoding="utf-8"))
    except (OSError, SyntaxError, ValueError):
        return {}
    out: dict[str, tuple[str, str | None]] = {}
    for node in tree.body:
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            for stmt in node.body:
                if isinstance(stmt, ast.ImportFrom) and stmt.module and stmt.level == 0:
                    out.update({a.asname or a.name: (stmt.module, a.name) for a in stmt.names})
                elif isinstance(stmt, ast.Import):
                    out.update({(a.asname or a.name).split(".")[0]:
                                (a.name if a.asname else a.name.split(".")[0], None)
                                for a in stmt.names})
    return out


# ---- the wrapper -----------------------------------------------------------------------------

@dataclass(frozen=True)
class _Plan:
    """One function's parameters, read once: the checks and the binding rules."""

    name: str
    positional: tuple[str, ...]
    keywords: frozenset[str]
    n_required: int                       # the first n positional parameters are required
    kw_required: tuple[str, ...]          # required keyword-only parameters
    var_positional: str | None
    var_keyword: bool
    checks: dict[str, tuple[Callable[[Any], bool], Any]]  # name -> (test, default)
    says: dict[str, str]                  # name -> what its hint accepts, for messages
    to_path: frozenset[str]               # ``Path``-only hints: a str is passed on as a Path


def _plan(fn: Callable[..., Any], name: str) -> _Plan:
    sig = inspect.signature(fn)
    reader = _Reader(fn)
    checks: dict[str, tuple[Callable[[Any], bool], Any]] = {}
    says: dict[str, str] = {}
    pos, kw, kw_req, to_path = [], set(), [], set()
    n_req, var_pos, var_kw = 0, None, False
    for p in sig.parameters.values():
        if p.kind is p.VAR_KEYWORD:
            var_kw = True
            continue
        if p.kind is p.VAR_POSITIONAL:
            var_pos = p.name
        elif p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD):
            pos.append(p.name)
            n_req += p.default is p.empty
        if p.kind is not p.POSITIONAL_ONLY and p.kind is not p.VAR_POSITIONAL:
            kw.add(p.name)
        if p.kind is p.KEYWORD_ONLY and p.default is p.empty:
            kw_req.append(p.name)
        spec = _ANY if p.annotation is p.empty else reader.spec(p.annotation)
        if spec is None and p.annotation == "Any" and _documented_array(fn, p.name):
            spec = ARRAY
        if spec is not None:
            checks[p.name], says[p.name] = (spec.test, p.default), spec.says
            if isinstance(p.annotation, str) and \
                    p.annotation.replace(" ", "") in ("Path", "Path|None"):
                to_path.add(p.name)
    return _Plan(name, tuple(pos), frozenset(kw), n_req, tuple(kw_req), var_pos, var_kw,
                 checks, says, frozenset(to_path))


def _documented_array(fn: Callable[..., Any], name: str) -> bool:
    """The numpydoc type of ``name`` in ``fn``'s docstring is exactly ``array_like`` (numbers).

    For a parameter hinted ``Any`` whose docstring promises an array (``displacements_mm :
    array-like``): checked as numbers.
    """
    import re

    doc = inspect.getdoc(fn) or ""
    for line in doc.splitlines():
        m = re.match(r"^([\w, *]+) : (.+)$", line)
        if m and name in [n.strip() for n in m.group(1).split(",")]:
            kind = m.group(2).strip().removesuffix(", optional")
            return re.fullmatch(r"array[_-]like( of (float|numbers?))?( \(.*\))?", kind) \
                is not None
    return False


def _fail(plan: _Plan, param: str, value: Any) -> InputError:
    got = _REPR.repr(value)
    return InputError(f"{param} must be {plan.says[param]}, got {got} ({type(value).__name__}) "
                      f"in {plan.name}()", param=param)


def _bind(plan: _Plan, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    """Check every argument given, then that none is missing or unexpected."""
    pos, checks = plan.positional, plan.checks
    n, na = len(pos), len(args)
    if na > n and plan.var_positional is None:
        raise InputError(f"{plan.name}() takes {n} positional argument{'s' * (n != 1)}, got "
                         f"{na}: give the others by name", param=None)
    for i, a in enumerate(args):
        name = pos[i] if i < n else plan.var_positional or ""
        e = checks.get(name)
        if e is not None and a is not e[1] and not e[0](a):
            raise _fail(plan, name, a)
    for k, v in kwargs.items():
        e = checks.get(k)
        if e is not None:
            if v is not e[1] and not e[0](v):
                raise _fail(plan, k, v)
        elif k not in plan.keywords and not plan.var_keyword:
            raise InputError(f"{k} is not a parameter of {plan.name}()", param=k)
        if k in pos[:na]:
            raise InputError(f"{k} is given twice (by position and by name) in {plan.name}()",
                             param=k)
    missing = [r for r in pos[na:plan.n_required] if r not in kwargs] if na < plan.n_required \
        else []
    missing += [r for r in plan.kw_required if r not in kwargs]
    if missing:
        raise InputError(f"{missing[0]} is required by {plan.name}() (missing argument)",
                         param=missing[0])


def _as_paths(plan: _Plan, args: tuple[Any, ...], kwargs: dict[str, Any]
              ) -> tuple[tuple[Any, ...], dict[str, Any]]:
    """The arguments with a str given for a ``Path``-only parameter made a Path."""
    from pathlib import Path

    pos = plan.positional
    args = tuple(Path(a) if i < len(pos) and pos[i] in plan.to_path and type(a) is str else a
                 for i, a in enumerate(args))
    kwargs = {k: Path(v) if k in plan.to_path and type(v) is str else v
              for k, v in kwargs.items()}
    return args, kwargs


def checked(fn: F, module: str | None = None, name: str | None = None) -> F:
    """``fn`` with its arguments' kinds checked from its type hints (:class:`InputError`).

    The wrapper keeps ``fn``'s name, docstring and signature (``functools.wraps``:
    ``inspect.signature`` and the docs read ``fn``'s); the hints are read on the first call.

    Parameters
    ----------
    fn : callable
        A public function (its annotations may be strings: ``from __future__ import
        annotations``).
    module, name : str, optional
        The public import path it is exported under (``"exofric.simulate"``, ``"squeeze"``):
        the wrapper's ``__module__`` and ``__qualname__``, so that pickle finds the wrapper
        itself there.

    Returns
    -------
    callable
        The checked function (``is_checked`` is True for it).

    Examples
    --------
    >>> def area_mm2(width_mm: float, height_mm: float = 1.0) -> float:
    ...     '''Area (mm^2).'''
    ...     return width_mm * height_mm
    >>> safe = checked(area_mm2)
    >>> safe(2.0, height_mm=3)
    6.0
    >>> safe("2")
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: width_mm must be a number, got '2' (str) in area_mm2()
    """
    if is_checked(fn):
        return fn
    label = name or fn.__name__
    plans: list[_Plan] = []

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        plan = plans[0] if plans else _first_plan(plans, fn, label)
        _bind(plan, args, kwargs)
        if plan.to_path:
            args, kwargs = _as_paths(plan, args, kwargs)
        return fn(*args, **kwargs)

    wrapper.__exofric_checked__ = True  # type: ignore[attr-defined]
    if module is not None:
        wrapper.__module__ = module
        wrapper.__qualname__ = label
    return wrapper  # type: ignore[return-value]


def _first_plan(plans: list[_Plan], fn: Callable[..., Any], label: str) -> _Plan:
    plans.append(_plan(fn, label))
    return plans[0]


def is_checked(fn: object) -> bool:
    """True if ``fn`` is a :func:`checked` wrapper.

    Parameters
    ----------
    fn : object
        Any object.

    Returns
    -------
    bool
        Whether calls of ``fn`` check their arguments' kinds.

    Examples
    --------
    >>> from exofric.simulate import squeeze
    >>> is_checked(squeeze)
    True
    """
    return bool(getattr(fn, "__exofric_checked__", False))


C = TypeVar("C", bound=type)


def checked_init(cls: C) -> C:
    """Class decorator: the constructor of ``cls`` checks its arguments' kinds like :func:`checked`.

    For a public settings dataclass (apply it above ``@dataclass``): a field given a value of
    the wrong kind raises :class:`~exofric.errors.InputError` naming the field and the class,
    at construction, whoever constructs it.

    Parameters
    ----------
    cls : type
        The class (its ``__init__`` type hints are the fields').

    Returns
    -------
    type
        ``cls``, its ``__init__`` checked.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @checked_init
    ... @dataclass(frozen=True)
    ... class Pull:
    ...     "One pull."
    ...     speed_mm_per_s: float = 1.0
    >>> Pull(2).speed_mm_per_s
    2
    >>> Pull(speed_mm_per_s="fast")
    Traceback (most recent call last):
    ...
    exofric.errors.InputError: speed_mm_per_s must be a number, got 'fast' (str) in Pull()
    """
    cls._exofric_raw_init = cls.__init__  # type: ignore[attr-defined,misc]  # unchecked()
    cls.__init__ = checked(cls.__init__, name=cls.__name__)  # type: ignore[misc]
    return cls


T = TypeVar("T")


def unchecked(cls: type[T], *args: Any, **kwargs: Any) -> T:
    """An instance of a :func:`checked_init` class built without the kind check.

    For the states a solver builds on every Newton iteration from values it computed itself
    (:class:`~exofric.fe.ContactState`, :class:`~exofric.fe.FrictionState`: some 900 per
    draft squeeze), where the check's ~5-12 microseconds would be paid for nothing; everything
    a user constructs goes through the checked constructor.

    Parameters
    ----------
    cls : type
        A class decorated with :func:`checked_init`.
    *args, **kwargs
        Its constructor's arguments.

    Returns
    -------
    object
        ``cls(*args, **kwargs)``, built by its own ``__init__`` without the kind check.

    Examples
    --------
    >>> from exofric.hardware import Reading
    >>> unchecked(Reading, 0.3, 12.0).force_n
    12.0
    """
    obj = cls.__new__(cls)
    cls._exofric_raw_init(obj, *args, **kwargs)  # type: ignore[attr-defined]
    return obj
