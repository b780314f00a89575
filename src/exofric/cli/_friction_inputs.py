"""Inputs the friction commands share (fit-friction, predict, invert, rig, torque, pullout,
stiffness): squeeze curve files, the interface law's FE curves, choice checks and the pull-out
setup of the pull-out flags. Units: MPa, N.

Files are read by :mod:`exofric.io`: squeeze curves (``exofric squeeze --json`` output or a
``pressure_mpa,squeeze_force_n`` CSV).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np

    from exofric.cli._options import ContactFrictionOptions, MaterialOptions
    from exofric.geometry import Structure
    from exofric.simulate import PulloutSetup

__all__ = ["both_mus", "choice", "interface_curves", "pullout_setup", "squeeze_curve"]


def squeeze_curve(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """(pressure MPa, squeezing force N) of a squeeze curve file (JSON or CSV), sorted."""
    from exofric.io import read_squeeze_curve

    df = read_squeeze_curve(path)
    return df["pressure_mpa"].to_numpy(float), df["squeeze_force_n"].to_numpy(float)


def choice(name: str, value: str, allowed: tuple[str, ...]) -> str:
    """``value`` if it is one of ``allowed``; else InputError naming the flag ``name``."""
    from exofric.errors import InputError

    if value not in allowed:
        raise InputError(f"{name} must be one of {', '.join(allowed)}, got {value!r}")
    return value


def interface_curves(path: str, used: set[str]) -> Any:
    """A structure's FE curves S_wire(P), N(P) from an ``exofric squeeze --json`` file."""
    from exofric.errors import InputError
    from exofric.friction import InterfaceCurves
    from exofric.io import read_json

    p = Path(path)
    if not p.is_file():
        raise InputError(f"{path}: file not found", param="squeeze")
    if p.suffix.lower() != ".json":
        raise InputError(f"{p.name}: the interface law needs the JSON of `exofric squeeze ... "
                         "--json` (with 'wire_pressure_integral_n_per_mm'); a CSV holds N(P) "
                         "only", param="squeeze")
    obj = read_json(p)
    if not isinstance(obj, dict):
        raise InputError(f"{p.name}: expected the JSON object of `exofric squeeze --json`",
                         param="squeeze")
    name = p.stem
    k = 2
    while name in used:
        name, k = f"{p.stem}#{k}", k + 1
    used.add(name)
    try:
        return InterfaceCurves.from_squeeze(obj, name=name)
    except InputError as exc:
        raise InputError(f"{p.name}: {exc}", param=exc.param) from None


def both_mus(mu_tube: float | None, mu_wall: float | None) -> None:
    """The interface law takes both coefficients: one of --mu-tube, --mu-wall alone is an
    InputError naming the missing one."""
    from exofric.errors import InputError

    if (mu_tube is None) != (mu_wall is None):
        missing = "mu_wall" if mu_wall is None else "mu_tube"
        raise InputError(f"{missing} is needed too: the interface law takes both --mu-tube "
                         "and --mu-wall", param=missing)


def pullout_setup(structure: Structure, material: MaterialOptions,
                  friction: ContactFrictionOptions, cable_ea: float, ends: str,
                  accuracy: str | None) -> PulloutSetup:
    """The :class:`~exofric.simulate.PulloutSetup` of the pull-out flags (shared with
    ``stiffness``): coefficients unitless, EA in N."""
    from exofric.simulate import PulloutSetup

    return PulloutSetup(structure, material.material(), mu_wire=friction.mu_wire,
                        mu_wall=friction.mu_wall, mu_wire_wall=friction.mu_wire_wall,
                        mu_static=friction.mu_static, cable_ea_n=cable_ea, ends=ends,
                        accuracy=accuracy)
