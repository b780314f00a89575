"""exofric: friction modelling, prediction and control for friction-based variable-stiffness
structures (Ma et al., Actuators 2021).

The package reads as the paper's pipeline, one subpackage per stage:
:mod:`~exofric.paper` (the paper as data) -> :mod:`~exofric.material` (Shore to Mooney-Rivlin),
:mod:`~exofric.geometry` -> :mod:`~exofric.fe` (discretisation and solver) ->
:mod:`~exofric.simulate` (inflate, squeeze) -> :mod:`~exofric.calibration`,
:mod:`~exofric.friction` -> :mod:`~exofric.control` -> :mod:`~exofric.design`,
:mod:`~exofric.reproduction` -> :mod:`~exofric.report` -> :mod:`~exofric.cli`, with files in
:mod:`~exofric.io`, pictures in :mod:`~exofric.plots` and defaults in :mod:`~exofric.defaults`.

The names a researcher reaches for first are importable from here; each has one home in its
stage's subpackage (``ef.squeeze is exofric.simulate.squeeze``).

Units everywhere: mm, N, MPa, s (Nm for torque).

Examples
--------
>>> import exofric as ef
>>> r = ef.squeeze(ef.BASE, ef.MooneyRivlin.from_shore(62.5), [0.6])
>>> round(float(r.squeeze_force_n[0]))
241
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from exofric._lazy import facade
from exofric._version import __version__

# Lazy facade (SPEC 1 style): ``import exofric`` stays cheap (the CLI and every Dask worker
# import it), and each name is loaded from its one home on first use.
_HOME: dict[str, str] = {
    "CalibrationResult": "exofric.calibration",
    "InflationData": "exofric.calibration",
    "calibrate": "exofric.calibration",
    "Controller": "exofric.control",
    "PIDGains": "exofric.control",
    "PlantParams": "exofric.control",
    "SweepSpec": "exofric.design",
    "parse_sweep": "exofric.design",
    "run_sweep": "exofric.design",
    "search_designs": "exofric.design",
    "ConvergenceError": "exofric.errors",
    "InputError": "exofric.errors",
    "MeshSpec": "exofric.fe",
    "CubicFit": "exofric.friction",
    "FrictionModel": "exofric.friction",
    "GammaFit": "exofric.friction",
    "fit_gamma": "exofric.friction",
    "predict": "exofric.friction",
    "pressure_for_friction": "exofric.friction",
    "reduce_log": "exofric.friction",
    "simulate_raw_log": "exofric.friction",
    "simulate_rig": "exofric.friction",
    "torque": "exofric.friction",
    "BASE": "exofric.geometry",
    "Structure": "exofric.geometry",
    "MooneyRivlin": "exofric.material",
    "shore_to_modulus": "exofric.material",
    "ReproduceConfig": "exofric.reproduction",
    "ReproduceResult": "exofric.reproduction",
    "reproduce": "exofric.reproduction",
    "InflationResult": "exofric.simulate",
    "SqueezeResult": "exofric.simulate",
    "inflate": "exofric.simulate",
    "squeeze": "exofric.simulate",
}

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from exofric.calibration import CalibrationResult, InflationData, calibrate
    from exofric.control import Controller, PIDGains, PlantParams
    from exofric.design import SweepSpec, parse_sweep, run_sweep, search_designs
    from exofric.errors import ConvergenceError, InputError
    from exofric.fe import MeshSpec
    from exofric.friction import (
        CubicFit,
        FrictionModel,
        GammaFit,
        fit_gamma,
        predict,
        pressure_for_friction,
        reduce_log,
        simulate_raw_log,
        simulate_rig,
        torque,
    )
    from exofric.geometry import BASE, Structure
    from exofric.material import MooneyRivlin, shore_to_modulus
    from exofric.reproduction import ReproduceConfig, ReproduceResult, reproduce
    from exofric.simulate import InflationResult, SqueezeResult, inflate, squeeze



__all__ = [
    "BASE",
    "CalibrationResult",
    "Controller",
    "ConvergenceError",
    "CubicFit",
    "FrictionModel",
    "GammaFit",
    "InflationData",
    "InflationResult",
    "InputError",
    "MeshSpec",
    "MooneyRivlin",
    "PIDGains",
    "PlantParams",
    "ReproduceConfig",
    "ReproduceResult",
    "Structure",
    "SqueezeResult",
    "SweepSpec",
    "__version__",
    "calibrate",
    "fit_gamma",
    "inflate",
    "parse_sweep",
    "predict",
    "pressure_for_friction",
    "reduce_log",
    "reproduce",
    "run_sweep",
    "search_designs",
    "shore_to_modulus",
    "simulate_raw_log",
    "simulate_rig",
    "squeeze",
    "torque",
]

__getattr__, __dir__ = facade(__name__, _HOME, __all__)
