"""``exofric torque``: joint torque from friction, T = F R, optionally through the knee arc.

Units: friction N, arm radius m, torque Nm, wrap angle deg, pressure MPa. The capstan factor
exp(+-mu_arc theta) and the meaning of ``--direction`` are derived in
:mod:`exofric.friction._torque`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, ClassVar

import typer

from exofric.cli._common import JSON_OPTION, console, emit, kv_table, narrow_table, parse_floats
from exofric.cli._friction_inputs import both_mus, interface_curves
from exofric.cli._options import OptionGroup, grouped

__all__ = ["register"]


def _friction_curve(squeeze: str, gamma: float | None, mu_tube: float | None,
                    mu_wall: float | None, f0: float, pressures: str | None) -> dict[str, Any]:
    """Friction (N) at pressures (MPa) from a squeeze file and one law."""
    import numpy as np

    from exofric.errors import InputError
    from exofric.friction import FrictionModel, InterfaceFrictionModel, match_squeeze

    both_mus(mu_tube, mu_wall)
    if (gamma is None) == (mu_tube is None):
        raise InputError("with --squeeze give one law: --gamma, or --mu-tube and --mu-wall",
                         param="gamma")
    path = Path(squeeze)
    if not path.is_file():
        raise InputError(f"{squeeze}: file not found", param="squeeze")
    out: dict[str, Any] = {"squeeze": str(squeeze)}
    if gamma is not None:
        from exofric.io import read_squeeze_curve

        law = FrictionModel(gamma, f0)
        df = read_squeeze_curve(path)
        ps, ns = df["pressure_mpa"].to_numpy(float), df["squeeze_force_n"].to_numpy(float)
        p = ps if pressures is None else np.asarray(parse_floats("--pressures", pressures))
        n, inside = match_squeeze(ps, ns, p)
        s = None
    else:
        ilaw = InterfaceFrictionModel(float(mu_tube), float(mu_wall), f0)  # type: ignore[arg-type]
        curves = interface_curves(squeeze, set())
        p = (np.asarray(curves.pressure_mpa) if pressures is None
             else np.asarray(parse_floats("--pressures", pressures)))
        s, n, inside = curves.at(p)
    if not np.all(inside):
        bad = p[~inside][0]
        raise InputError(f"pressures {bad:g} MPa is outside the squeeze curve's range",
                         param="pressures")
    if np.any(p < 0):
        raise InputError("pressures must be >= 0 MPa", param="pressures")
    if gamma is not None:
        f = law.friction(n)
        out.update(law.to_dict())
        out["law"] = "gamma"
    else:
        f = ilaw.friction_n(np.asarray(s), n)
        out.update(ilaw.to_dict())
        out["wire_pressure_integral_n"] = np.asarray(s).tolist()
    out.update({"pressure_mpa": p.tolist(), "squeeze_force_n": np.asarray(n).tolist(),
                "friction_n": np.asarray(f).tolist()})
    return out


class _Capstan(OptionGroup):
    """The wire over the knee arc: wrap (deg), coefficient wire-arc (unitless), direction."""

    wrap_deg: float
    mu_arc: float
    direction: str
    OPTIONS: ClassVar[dict[str, Any]] = {
        "wrap_deg": typer.Option(0.0, "--wrap-deg", help="Wrap angle of the wire over the knee "
                                 "arc in degrees (0: T = F R)."),
        "mu_arc": typer.Option(0.0, "--mu-arc", help="Friction coefficient of the wire on the "
                               "arc (unitless)."),
        "direction": typer.Option("locking", help="locking (the joint pulls the wire over the "
                                  "arc: T = F R exp(+mu_arc theta)) or buffering (the wire "
                                  "slides back toward the block: exp(-mu_arc theta))."),
    }


class _Required(OptionGroup):
    """The required joint torque range (Nm)."""

    required_min: float
    required_max: float
    OPTIONS: ClassVar[dict[str, Any]] = {
        "required_min": typer.Option(0.0, "--required-min", help="Required torque range "
                                     "minimum in Nm."),
        "required_max": typer.Option(40.0, "--required-max", help="Required torque in Nm "
                                     "(knee: 40)."),
    }


@grouped
def torque_cmd(
    friction: float | None = typer.Option(None, help="Friction force F at the block in N "
                                          "(e.g. 180.49, the base group at 0.6 MPa)."),
    squeeze: str | None = typer.Option(None, help="Instead of --friction: a squeeze file "
                                       "(JSON of `exofric squeeze --json`, or CSV for "
                                       "gamma) and a law (--gamma or --mu-tube/--mu-wall) "
                                       "give F at --pressures."),
    gamma: float | None = typer.Option(None, help="With --squeeze: F = gamma N + F0."),
    mu_tube: float | None = typer.Option(None, "--mu-tube", help="With --squeeze: "
                                         "wire-on-tube coefficient (unitless) of "
                                         "F = mu_tube S_wire + mu_wall N + F0."),
    mu_wall: float | None = typer.Option(None, "--mu-wall", help="With --squeeze: "
                                         "wire-on-wall coefficient (unitless)."),
    f0: float = typer.Option(0.0, "--f0", help="With --squeeze: drag F0 in N."),
    pressures: str | None = typer.Option(None, help="With --squeeze: pressures in MPa "
                                         "(default: the curve's)."),
    arm_radius: float = typer.Option(0.10, help="Lever arm R in m (paper: 0.10)."),
    capstan: _Capstan = _Capstan.options(),
    required: _Required = _Required.options(),
    as_json: bool = JSON_OPTION,
) -> None:
    """Joint torque T = F R x exp(+-mu_arc theta) from block friction. N, m, Nm, deg.

    The wire leaves the friction block and wraps the knee arc (paper Fig 2): sliding over
    the arc multiplies the tension by the capstan factor, up when the joint drives the wire
    (locking), down when the wire slides back toward the block (buffering).
    """
    from exofric.errors import InputError
    from exofric.friction import torque

    wrap_deg, mu_arc, direction = capstan.wrap_deg, capstan.mu_arc, capstan.direction
    required_min, required_max = required.required_min, required.required_max
    if direction not in ("locking", "buffering"):
        raise InputError(f"direction must be locking or buffering, got {direction!r}",
                         param="direction")
    if (friction is None) == (squeeze is None):
        raise InputError("give exactly one of --friction N or --squeeze FILE (with a law)",
                         param="friction")
    req = (required_min, required_max)
    kw: dict[str, Any] = {"wrap_deg": wrap_deg, "mu_arc": mu_arc, "direction": direction}
    if friction is not None:
        if any(v is not None for v in (gamma, mu_tube, mu_wall, pressures)):
            raise InputError("gamma, mu_tube, mu_wall and pressures go with --squeeze, "
                             "not --friction", param="friction")
        t = torque(friction, arm_radius, req, **kw)
        d = t.to_dict()
        lo = torque(friction, arm_radius, req, **{**kw, "direction": "buffering"})
        hi = torque(friction, arm_radius, req, **{**kw, "direction": "locking"})
        d["torque_band_nm"] = [lo.torque_nm, hi.torque_nm]

        def render() -> None:
            rows = [("friction at the block F", f"{t.friction_n:g}", "N"),
                    ("arm radius R", f"{t.arm_radius_m:g}", "m"),
                    ("wrap over the knee arc", f"{t.wrap_deg:g}", "deg"),
                    ("mu_arc", f"{t.mu_arc:g}", ""),
                    ("direction", t.direction, ""),
                    ("capstan factor", f"{t.capstan:.4f}", ""),
                    ("torque T", f"{t.torque_nm:.3f}", "Nm"),
                    ("T = F R (no wrap)", f"{t.friction_n * t.arm_radius_m:.3f}", "Nm"),
                    ("buffering .. locking", f"{lo.torque_nm:.3f} .. {hi.torque_nm:.3f}",
                     "Nm"),
                    (f"meets {t.required_max_nm:g} Nm", "yes" if t.meets_max else "NO",
                     ""),
                    ("coverage of the range", f"{t.coverage_pct:.1f}", "%")]
            console.print(kv_table("Joint torque", rows))

        emit(d, as_json, render)
        return
    curve = _friction_curve(str(squeeze), gamma, mu_tube, mu_wall, f0, pressures)
    checks = [torque(f, arm_radius, req, **kw) for f in curve["friction_n"]]
    top = checks[-1]
    d = {**curve, "torque_nm": [c.torque_nm for c in checks],
         "arm_radius_m": top.arm_radius_m, "wrap_deg": top.wrap_deg, "mu_arc": top.mu_arc,
         "direction": top.direction, "capstan_factor": top.capstan,
         "required_min_nm": top.required_min_nm, "required_max_nm": top.required_max_nm,
         "max_friction_n": top.friction_n, "max_torque_nm": top.torque_nm,
         "meets_max": top.meets_max, "coverage_pct": top.coverage_pct}
    if top.torque_nm < 0 or top.friction_n < 0:
        raise InputError("friction came out negative at the highest pressure; check --f0",
                         param="f0")

    def render_curve() -> None:
        t = narrow_table(f"Joint torque ({curve['law']}, R = {arm_radius:g} m, wrap "
                         f"{wrap_deg:g} deg, {direction}, factor {top.capstan:.4f})",
                         ["P MPa", "F N", "T Nm"])
        for pp, ff, c in zip(curve["pressure_mpa"], curve["friction_n"], checks,
                             strict=True):
            t.add_row(f"{pp:g}", f"{ff:.2f}", f"{c.torque_nm:.3f}")
        console.print(t)
        console.print(f"at {curve['pressure_mpa'][-1]:g} MPa: T = {top.torque_nm:.2f} Nm, "
                      f"{'meets' if top.meets_max else 'below'} the required "
                      f"{top.required_max_nm:g} Nm ({top.coverage_pct:.1f} % of the range)")

    emit(d, as_json, render_curve)


def register(app: typer.Typer) -> None:
    """Add ``torque`` to ``app``."""
    app.command("torque")(torque_cmd)
