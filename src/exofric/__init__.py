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

from exofric._lazy import lazy_package
from exofric._version import __version__

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from exofric.calibration import CalibrationResult, InflationData, calibrate
    from exofric.control import Controller, GaitSetup, PIDGains, PlantParams, simulate_gait
    from exofric.design import SweepSpec, parse_sweep, run_sweep, search_designs
    from exofric.errors import ConvergenceError, InputError
    from exofric.fe import MeshSpec
    from exofric.friction import (
        CubicFit,
        FrictionModel,
        GammaFit,
        fit_gamma,
        joint_stiffness,
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
    from exofric.simulate import (
        InflationResult,
        PulloutSetup,
        SqueezeResult,
        inflate,
        pullout,
        squeeze,
    )




# Lazy facade (SPEC 1 style): ``import exofric`` stays cheap (the CLI and every Dask worker
# import it), and each name is loaded from its one home on first use. The TYPE_CHECKING imports
# above are the one list of names: __all__ and the facade are derived from them.
__getattr__, __dir__, __all__ = lazy_package(__name__, __file__, extra=("__version__",))
