"""Options, option groups and parsers shared by several commands (one owner: no command imports
another command's module). Units: mm for structures, MPa for material constants.
"""

from __future__ import annotations

import functools
import inspect
import re
import sys
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, ClassVar, TypeVar

import typer

from exofric.cli._common import JSON_OPTION, parse_floats

if TYPE_CHECKING:
    from exofric.geometry import Structure
    from exofric.material import HyperelasticModel, MooneyRivlin

__all__ = ["C01_OPTION", "C10_OPTION", "D_OPTION", "HOLE_OPTION", "MODEL_HELP", "MODEL_OPTION",
           "PARAMS_HELP", "PARAMS_OPTION", "PULLOUT_ENDS_HELP", "SHORE_OPTION", "TUBE_ID_OPTION",
           "TUBE_OD_OPTION", "WIRE_OPTION", "ContactFrictionOptions", "FrictionLawOptions",
           "MaterialOptions", "OptionGroup", "OutputOptions", "StructureOptions",
           "TensileSpecimenOptions", "grouped", "material_from_options"]

R = TypeVar("R")

MODEL_HELP = ("Hyperelastic model instead of the Shore route: neo-hookean, mooney-rivlin, yeoh "
              "or ogden (ogden1-3; constants from --params; --d optional). Not with "
              "--shore/--c10/--c01.")
PARAMS_HELP = ("Comma-separated constants of --model (MPa; alpha unitless): neo-hookean C10; "
               "mooney-rivlin C10,C01; yeoh C10,C20,C30; ogden mu1,alpha1[,mu2,alpha2[,mu3,"
               "alpha3]].")


def material_from_options(
    shore: float | None,
    c10: float | None,
    c01: float | None,
    d: float | None,
    correlation: str = "paper",
    model: str | None = None,
    params: str | None = None,
) -> MooneyRivlin | HyperelasticModel:
    """MooneyRivlin from --shore, with --c10/--c01/--d overriding the derived constants.

    With --model (and --params), the named hyperelastic model instead (``d`` from --d or its
    default); not together with --shore, --c10 or --c01.
    """
    import re

    from exofric.errors import InputError
    from exofric.material import MooneyRivlin, material_model

    if model is not None or params is not None:
        if model is None:
            raise InputError("params needs --model (the model it parametrises)", param="params")
        if (shore, c10, c01) != (None, None, None):
            raise InputError("model takes its constants from --params: not with --shore, --c10 "
                             "or --c01", param="model")
        if params is None:
            raise InputError(f"params: give the constants of --model {model} "
                             "(comma-separated, MPa)", param="params")
        vals = parse_floats("--params", params)
        try:
            return material_model(model, vals, d=d)
        except InputError as exc:  # name the constants as the --params help does (c10, ...)
            raise InputError(re.sub(r"\b(c\d\d)_mpa\b", r"\1", str(exc)),
                             param=exc.param) from None
    if shore is None and None in (c10, c01, d):
        raise InputError("give --shore, or all of --c10, --c01 and --d, or --model and --params")
    base = MooneyRivlin.from_shore(shore, correlation) if shore is not None else None
    return MooneyRivlin(
        c10 if c10 is not None else base.c10,  # type: ignore[union-attr]
        c01 if c01 is not None else base.c01,  # type: ignore[union-attr]
        d if d is not None else base.d,  # type: ignore[union-attr]
        shore if (c10, c01, d) == (None, None, None) else None,
        correlation if (c10, c01, d) == (None, None, None) else None,
    )


# The material option group: every command that builds a tube material takes these six (then
# material_from_options); declared once.
SHORE_OPTION: Any = typer.Option(None, help="Shore A hardness (Eqs 3-6).")
C10_OPTION: Any = typer.Option(None, help="Override C10 (MPa).")
C01_OPTION: Any = typer.Option(None, help="Override C01 (MPa).")
D_OPTION: Any = typer.Option(None, help="Override d (1/MPa).")
MODEL_OPTION: Any = typer.Option(None, "--model", help=MODEL_HELP)
PARAMS_OPTION: Any = typer.Option(None, "--params", help=PARAMS_HELP)

#: The tube ends of the pull-out problem (pullout, stiffness).
PULLOUT_ENDS_HELP = ("Tube ends: fixed (end fittings hold the tube axially) or free (the tube may "
                     "slide on the hole wall once its wall arc slides).")

# The structure option group (mm): the hole, the tube and the wire of a structure.
HOLE_OPTION: Any = typer.Option(..., help="Hole diameter D (mm).")
TUBE_OD_OPTION: Any = typer.Option(..., help="Tube outer diameter d1 (mm).")
TUBE_ID_OPTION: Any = typer.Option(..., help="Tube inner diameter (mm).")
WIRE_OPTION: Any = typer.Option(..., help="Wire diameter d2 (mm).")


# --- Option groups --------------------------------------------------------------------------
# typer takes one function parameter per option. A command that needs a group of options (a
# structure, a material, a friction law, its outputs) takes the group as ONE parameter, typed
# with an OptionGroup and defaulting to Group.options(...), and is decorated with @grouped: the
# decorator shows typer the group's fields as options in the group's place (names, flags, help
# and defaults unchanged) and hands the command the group built from them. OptionGroup is a
# small frozen record rather than a dataclass: ~20 groups are built at import, and
# ``exofric --help`` would pay ~1-3 ms for each dataclass.


class OptionGroup:
    """Base of a frozen record whose fields are options of a command (see :func:`grouped`).

    A subclass annotates its fields (the Python parameter names: ``tube_od`` is ``--tube-od``;
    a subclass of a group adds fields after its base's) and, in ``OPTIONS``, the typer option of
    each field that has one declared once; a command gives the rest, or its own variant of
    one, with :meth:`options`. Instances take the fields by position or name, compare equal
    field by field and cannot be changed.
    """

    #: field name -> the typer option of that field (shared declaration)
    OPTIONS: ClassVar[dict[str, Any]] = {}
    #: the field names, in order (set for each subclass from its annotations)
    FIELDS: ClassVar[tuple[str, ...]] = ()

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        own = [k for k, v in cls.__dict__.get("__annotations__", {}).items()
               if not str(v).startswith(("ClassVar", "typing.ClassVar"))]
        cls.FIELDS = (*cls.FIELDS, *(k for k in own if k not in cls.FIELDS))

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        if len(args) > len(self.FIELDS):
            raise TypeError(f"{type(self).__name__} takes {len(self.FIELDS)} fields")
        values = dict(zip(self.FIELDS, args, strict=False))
        twice = set(values) & set(kwargs)
        missing = [f for f in self.FIELDS if f not in values and f not in kwargs]
        unknown = set(kwargs) - set(self.FIELDS)
        if twice or missing or unknown:
            raise TypeError(f"{type(self).__name__}: fields {', '.join(self.FIELDS)} "
                            f"(twice: {sorted(twice)}, missing: {missing}, unknown: "
                            f"{sorted(unknown)})")
        for k in self.FIELDS:
            object.__setattr__(self, k, values[k] if k in values else kwargs[k])

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} is frozen")

    def __eq__(self, other: object) -> bool:
        return isinstance(other, OptionGroup) and type(other) is type(self) \
            and self.to_dict() == other.to_dict()

    def __hash__(self) -> int:
        return hash((type(self), *(repr(v) for v in self.to_dict().values())))

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={v!r}" for k, v in self.to_dict().items())
        return f"{type(self).__name__}({inner})"

    def to_dict(self) -> dict[str, Any]:
        """The fields, in order: ``{name: value}``."""
        return {k: getattr(self, k) for k in self.FIELDS}

    @classmethod
    def options(cls, **overrides: Any) -> Any:
        """The default of a command's group parameter: options differing from ``OPTIONS``.

        Each value is a typer option, or ``(annotation, option)`` when the field's type differs
        in this command (``plot=(Path, typer.Option(None, help=...))`` gives ``<path>``).
        """
        unknown = set(overrides) - set(cls.FIELDS)
        if unknown:
            raise TypeError(f"{cls.__name__} has no field {', '.join(sorted(unknown))}")
        return _GroupOptions(cls, overrides)


class _GroupOptions:
    """A group parameter's default: the group and the options this command words itself."""

    __slots__ = ("group", "overrides")

    def __init__(self, group: type[OptionGroup], overrides: dict[str, Any]) -> None:
        self.group, self.overrides = group, overrides


_FIELD_TYPES: dict[str, dict[str, Any]] = {}


def _field_types(group: type[OptionGroup]) -> dict[str, Any]:
    """The fields' annotations, evaluated where each field is declared (only the fields:
    ``typing.get_type_hints`` would evaluate every ClassVar of the hierarchy too, which costs
    start-up time); once per group."""
    key = f"{group.__module__}.{group.__qualname__}"
    if key in _FIELD_TYPES:
        return _FIELD_TYPES[key]
    out: dict[str, Any] = _FIELD_TYPES.setdefault(key, {})
    for cls in reversed(group.__mro__):
        env = vars(sys.modules[cls.__module__])
        for name, ann in vars(cls).get("__annotations__", {}).items():
            if name in group.FIELDS:
                out[name] = eval(ann, env) if isinstance(ann, str) else ann  # noqa: S307
    return out


def _group_parameters(group: type[OptionGroup], overrides: dict[str, Any]
                      ) -> list[inspect.Parameter]:
    hints = _field_types(group)
    out = []
    for name in group.FIELDS:
        annotation, option = hints[name], overrides.get(name, group.OPTIONS.get(name))
        if isinstance(option, tuple):
            annotation, option = option
        if option is None:
            raise TypeError(f"{group.__name__}.{name}: no option declared (give it with "
                            f"{group.__name__}.options({name}=typer.Option(...)))")
        out.append(inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=option,
                                     annotation=annotation))
    return out


def grouped(func: Callable[..., R]) -> Callable[..., R]:
    """Let the typer command ``func`` take :class:`OptionGroup` parameters.

    Each parameter whose default is ``Group.options(...)`` (``Group`` an OptionGroup) is shown
    to typer as the group's fields, in order, in its place, with the options of ``OPTIONS`` or
    those given to ``options``; the command is called with the group built from them.
    Register the result with ``app.command(NAME)(command)``.

    Examples
    --------
    >>> import inspect
    >>> @grouped
    ... def cmd(st: StructureOptions = StructureOptions.options(), as_json: bool = False) -> str:
    ...     return f"D = {st.hole} mm, d1 = {st.tube_od} mm, json {as_json}"
    >>> list(inspect.signature(cmd).parameters)
    ['hole', 'tube_od', 'tube_id', 'wire', 'as_json']
    >>> cmd(hole=10.0, tube_od=8.3, tube_id=4.97, wire=1.6, as_json=True)
    'D = 10.0 mm, d1 = 8.3 mm, json True'
    """
    sig = inspect.signature(func)
    params: list[inspect.Parameter] = []
    groups: dict[str, tuple[type[OptionGroup], list[str]]] = {}
    for p in sig.parameters.values():
        if isinstance(p.default, _GroupOptions):
            sub = _group_parameters(p.default.group, p.default.overrides)
            groups[p.name] = (p.default.group, [q.name for q in sub])
            params.extend(sub)
        else:   # annotations stay as written: typer resolves them in func's module
            params.append(p.replace(kind=inspect.Parameter.KEYWORD_ONLY))
    names = [p.name for p in params]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise TypeError(f"{func.__name__}: option(s) {', '.join(twice)} given twice")

    @functools.wraps(func)
    def command(**kwargs: Any) -> R:
        for name, (group, members) in groups.items():
            kwargs[name] = group(**{m: kwargs.pop(m) for m in members})
        return func(**kwargs)

    command.__signature__ = sig.replace(parameters=params)  # type: ignore[attr-defined]
    command.__annotations__ = {**{p.name: p.annotation for p in params},
                               "return": sig.return_annotation}
    return command


class StructureOptions(OptionGroup):
    """The structure group (mm): hole D, tube outer d1 and inner diameter, wire d2."""

    hole: float
    tube_od: float
    tube_id: float
    wire: float
    OPTIONS: ClassVar[dict[str, Any]] = {"hole": HOLE_OPTION, "tube_od": TUBE_OD_OPTION,
                                         "tube_id": TUBE_ID_OPTION, "wire": WIRE_OPTION}

    def structure(self, length_mm: float) -> Structure:
        """The :class:`~exofric.geometry.Structure` of these diameters and ``length_mm``."""
        from exofric.geometry import Structure

        return Structure(self.hole, self.tube_od, self.tube_id, self.wire, length_mm)


class MaterialOptions(OptionGroup):
    """The material group: --shore (Eqs 3-6) with --c10/--c01/--d overrides, or --model and
    --params (see :func:`material_from_options`)."""

    shore: float | None
    c10: float | None
    c01: float | None
    d: float | None
    model: str | None
    params: str | None
    OPTIONS: ClassVar[dict[str, Any]] = {"shore": SHORE_OPTION, "c10": C10_OPTION,
                                         "c01": C01_OPTION, "d": D_OPTION,
                                         "model": MODEL_OPTION, "params": PARAMS_OPTION}

    def material(self, correlation: str = "paper") -> MooneyRivlin | HyperelasticModel:
        """The tube material these options give (:func:`material_from_options`)."""
        return material_from_options(self.shore, self.c10, self.c01, self.d, correlation,
                                     model=self.model, params=self.params)


class FrictionLawOptions(OptionGroup):
    """The friction-law group: --law gamma or interfaces, and the interface law's --mu-tube and
    --mu-wall (unitless). Each command words its own help (``options``)."""

    law: str
    mu_tube: float | None
    mu_wall: float | None


class ContactFrictionOptions(OptionGroup):
    """The wire's contact friction (unitless Coulomb coefficients) of the pull-out problem:
    tube-wire, tube-hole wall, wire-hole wall, and the static coefficient. ``OPTIONS`` words
    them once for ``pullout`` and ``stiffness``."""

    mu_wire: float
    mu_wall: float
    mu_wire_wall: float
    mu_static: float | None
    OPTIONS: ClassVar[dict[str, Any]] = {
        "mu_wire": typer.Option(..., "--mu-wire", help="Kinetic Coulomb coefficient tube-wire "
                                "(axial), [0, 2]."),
        "mu_wall": typer.Option(..., "--mu-wall", help="Coulomb coefficient tube-hole wall, "
                                "[0, 2]."),
        "mu_wire_wall": typer.Option(..., "--mu-wire-wall", help="Coulomb coefficient wire-hole "
                                     "wall (line contact), [0, 2]."),
        "mu_static": typer.Option(None, "--mu-static", help="Static coefficient of the wire's "
                                  "interfaces (>= --mu-wire): breakaway peak."),
    }


class OutputOptions(OptionGroup):
    """The output group: the figure (--plot PATH; each command words its help) and --json."""

    plot: str | None
    as_json: bool
    OPTIONS: ClassVar[dict[str, Any]] = {"as_json": JSON_OPTION}


class TensileSpecimenOptions(OptionGroup):
    """How a tensile test file is read: stress and strain kind, the specimen's gauge length
    (mm), cross-section (mm^2) or width and thickness (mm). ``OPTIONS`` words them as
    ``material --fit`` does; ``calibrate`` words its own."""

    stress_kind: str | None
    strain_kind: str | None
    gauge_length_mm: float | None
    area_mm2: float | None
    width_mm: float | None
    thickness_mm: float | None
    OPTIONS: ClassVar[dict[str, Any]] = {
        "stress_kind": typer.Option(
            None, "--stress-kind", help="engineering or true stress in the CSVs; wins over a "
            "file's '# stress_kind:' line (default: the header's word, else engineering)."),
        "strain_kind": typer.Option(
            None, "--strain-kind", help="engineering (stretch = 1 + e) or true (stretch = "
            "exp(e)) strain in the CSVs (default: the header's word, else engineering)."),
        "gauge_length_mm": typer.Option(
            None, "--gauge-length", help="Specimen gauge length (mm): stretch = 1 + extension "
            "/ gauge length (or a '# gauge_length_mm:' line)."),
        "area_mm2": typer.Option(
            None, "--area", help="Specimen initial cross-section (mm^2): stress = load / area "
            "(or --width and --thickness, or a '# area_mm2:' line)."),
        "width_mm": typer.Option(
            None, "--width", help="Specimen width (mm); area = width x thickness."),
        "thickness_mm": typer.Option(
            None, "--thickness", help="Specimen thickness (mm); area = width x thickness."),
    }


# --- Help that reads at any width (issue 34) --------------------------------------------------
_SINGLE_NEWLINE = re.compile(r"(?<=\S)[ \t]*\n[ \t]*(?=\S)")


def tidy_help(cmd: Any) -> Any:
    """Make the help of the click command tree ``cmd`` read well at any width; return ``cmd``.

    Flags (``--json``, ``--feedforward``) show no ``<bool>`` metavar: they take no value. Help
    text hard-wrapped in the docstrings (single newlines) is joined, so rich wraps it to the
    terminal instead of breaking lines at the source's 100 columns; paragraphs (blank lines) and
    click's ``\\b`` verbatim blocks are kept.

    Examples
    --------
    >>> import typer
    >>> app = typer.Typer()
    >>> @app.command()
    ... def hello(loud: bool = typer.Option(False, "--loud")) -> None:
    ...     '''Say hello,
    ...     wrapped by hand.'''
    >>> cmd = tidy_help(typer.main.get_command(app))
    >>> cmd.help, [p.metavar for p in cmd.params if p.name == 'loud']
    ('Say hello, wrapped by hand.', [''])
    """
    def unwrap(text: str | None) -> str | None:
        if not text:
            return text
        paras = inspect.cleandoc(text).split("\n\n")
        return "\n\n".join(p if p.startswith("\b") else _SINGLE_NEWLINE.sub(" ", p)
                           for p in paras)

    for param in getattr(cmd, "params", ()):
        if getattr(param, "is_flag", False) and getattr(param, "metavar", None) is None:
            param.metavar = ""
        if getattr(param, "help", None):
            param.help = unwrap(param.help)
    if callable(getattr(cmd, "get_help_option", None)):   # --help is made per context
        cmd.get_help_option = functools.partial(_quiet_help_option, cmd.get_help_option)
    if getattr(cmd, "help", None):
        cmd.help = unwrap(cmd.help)
    if getattr(cmd, "short_help", None):
        cmd.short_help = unwrap(cmd.short_help)
    for sub in getattr(cmd, "commands", {}).values():
        tidy_help(sub)
    return cmd


def _quiet_help_option(make: Callable[[Any], Any], ctx: Any) -> Any:
    opt = make(ctx)
    if opt is not None and getattr(opt, "metavar", None) is None:
        opt.metavar = ""
    return opt
