"""``exofric invert``: the pressure (MPa) that gives a target friction (N), inverse of Eq 9.

Squeeze curves are read by :mod:`exofric.io` (``exofric squeeze --json`` output or a
``pressure_mpa,squeeze_force_n`` CSV).
"""

from __future__ import annotations

from typing import Any

import typer

from exofric.cli._common import JSON_OPTION, console, emit, kv_table, parse_floats
from exofric.cli._friction_inputs import squeeze_curve

__all__ = ["register"]


def _two(name: str, text: str) -> tuple[float, float]:
    """Two comma-separated numbers (low, high) of the option ``name``."""
    from exofric.errors import InputError

    v = parse_floats(name, text)
    if len(v) != 2:
        raise InputError(f"{name} must be two numbers 'low,high', got {len(v)}")
    return (v[0], v[1])


def invert(
    gamma: float = typer.Option(..., help="Equivalent coefficient gamma."),
    target_friction: float = typer.Option(..., help="Required friction force in N."),
    cubic: str | None = typer.Option(None, help="Cubic N(P) coefficients c3,c2,c1,c0 "
                                     "(N, MPa), e.g. Eq 8."),
    squeeze: str | None = typer.Option(None, help="Squeeze curve file: exact (PCHIP) "
                                       "inverse, plus a cubic fitted over --range."),
    p_range: str = typer.Option("0.2,0.6", "--range", help="Pressure range low,high in "
                                "MPa (paper: 0.2,0.6)."),
    f0: float = typer.Option(0.0, "--f0", help="Affine offset F0 in N."),
    as_json: bool = JSON_OPTION,
) -> None:
    """Pressure (MPa) that gives a target friction (N): inverse of Eq 9 (Sec. 5)."""
    from exofric.errors import InputError
    from exofric.friction import CubicFit, FrictionModel, SqueezeCurve, pressure_for_friction

    if (cubic is None) == (squeeze is None):
        raise InputError("give exactly one of --cubic c3,c2,c1,c0 or --squeeze FILE")
    lo, hi = _two("--range", p_range)
    model = FrictionModel(gamma, f0)
    d: dict[str, Any] = {"target_friction_n": target_friction, "gamma": gamma, "f0_n": f0,
                         "target_squeeze_force_n": model.squeeze(target_friction)}
    if cubic is not None:
        c = parse_floats("--cubic", cubic)
        if len(c) != 4:
            raise InputError(f"--cubic must be 4 numbers c3,c2,c1,c0, got {len(c)}")
        fit = CubicFit((c[0], c[1], c[2], c[3]), lo, hi)
        d["method"] = "cubic"
        d["pressure_mpa"] = pressure_for_friction(target_friction, fit, model)
    else:
        ps, ns = squeeze_curve(str(squeeze))
        d["method"] = "curve (PCHIP)"
        d["pressure_mpa"] = SqueezeCurve(ps, ns).pressure_for_friction(target_friction,
                                                                      model)
        fit = CubicFit.fit(ps, ns, (lo, hi))
        try:
            d["cubic_pressure_mpa"] = pressure_for_friction(target_friction, fit, model)
        except InputError:
            d["cubic_pressure_mpa"] = None
    d["cubic"] = fit.to_dict()
    d["p_min_mpa"], d["p_max_mpa"] = fit.p_min_mpa, fit.p_max_mpa
    from exofric import paper

    is_paper = (cubic is not None and all(
        abs(a - b) <= 1e-6 * max(1.0, abs(b)) for a, b in zip(fit.coefficients, paper.eq8(),
                                                              strict=True))
        and abs(target_friction - paper.scalar("target_friction_n")) < 1e-9
        and abs(gamma - paper.scalar("gamma")) < 1e-9 and f0 == 0.0)
    if is_paper:
        d["paper_pressure_mpa"] = paper.scalar("target_pressure_mpa")

    def render() -> None:
        rows = [("target friction F", f"{target_friction:g}", "N"),
                ("squeezing force N = (F - F0)/gamma", f"{d['target_squeeze_force_n']:.4f}",
                 "N"),
                (f"pressure ({d['method']})", f"{d['pressure_mpa']:.4f}", "MPa")]
        if d.get("cubic_pressure_mpa") is not None:
            rows.append(("pressure (fitted cubic)", f"{d['cubic_pressure_mpa']:.4f}", "MPa"))
        console.print(kv_table("Inverse of Eq 9", rows))
        if "paper_pressure_mpa" in d:
            console.print(f"paper (Sec 5): {d['paper_pressure_mpa']:g} MPa for this target; "
                          f"Eq 9 as printed has its root at {d['pressure_mpa']:.4f} MPa "
                          "(docs/paper-notes.md)")

    emit(d, as_json, render)


def register(app: typer.Typer) -> None:
    """Add the ``invert`` command."""
    app.command("invert")(invert)
