"""Option texts and parsers shared by several commands (one owner: no command imports another
command's module). Units: MPa for material constants.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import typer

from exofric.cli._common import parse_floats

if TYPE_CHECKING:
    from exofric.material import HyperelasticModel, MooneyRivlin

__all__ = ["C01_OPTION", "C10_OPTION", "D_OPTION", "HOLE_OPTION", "MODEL_HELP", "MODEL_OPTION",
           "PARAMS_HELP", "PARAMS_OPTION", "SHORE_OPTION", "TUBE_ID_OPTION", "TUBE_OD_OPTION",
           "WIRE_OPTION", "material_from_options"]

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

# The structure option group (mm): the hole, the tube and the wire of a structure.
HOLE_OPTION: Any = typer.Option(..., help="Hole diameter D (mm).")
TUBE_OD_OPTION: Any = typer.Option(..., help="Tube outer diameter d1 (mm).")
TUBE_ID_OPTION: Any = typer.Option(..., help="Tube inner diameter (mm).")
WIRE_OPTION: Any = typer.Option(..., help="Wire diameter d2 (mm).")
