"""Friction force control (paper §5, Fig 12, Eqs 10-11): plant, PID, identification, metrics.

* :mod:`~exofric.control.plant` -- pressure supply (lag + dead time + saturation, PWM valves,
  sensor noise, model mismatch) and friction maps F(P) with their inverses.
* :mod:`~exofric.control.pid` -- :class:`Controller` (discrete PID/PI/PD, filtered derivative,
  limits, anti-windup, bumpless start) and :class:`ModelFeedforward` (static or 2-DOF).
* :mod:`~exofric.control.identify` -- lag/delay/gain from a recorded step response.
* :mod:`~exofric.control.simulate` -- the closed loop at a fixed sample time.
* :mod:`~exofric.control.metrics` -- rise/settling time, overshoot, steady-state error, ITAE.
* :mod:`~exofric.control.tuning` -- IMC/SIMC rule and ITAE optimisation under saturation.
* :mod:`~exofric.control.cases` -- the six Fig 12 cases beside the paper's numbers.

Units: friction N, pressure MPa, time s; gains kp MPa/N, ki MPa/(N s), kd MPa s/N.

Examples
--------
>>> from exofric.control import ControlSetup, compare
>>> res = compare(ControlSetup.default())
>>> sorted(res.to_dict()["settling_reduction_pct"])
['pi', 'pid']
"""

from .cases import CaseResult, CompareResult, ControlSetup, compare, run_case
from .identify import IdentifiedPlant, fopdt_response, identify_step
from .metrics import StepMetrics, itae, step_metrics
from .pid import Controller, ModelFeedforward, PIDGains
from .plant import CubicFrictionMap, CurveFrictionMap, PlantParams, PressurePlant, local_slope
from .simulate import SimulationResult, setpoint_profile, simulate
from .tuning import TuningResult, itae_gains, rule_gains

__all__ = [
    "CaseResult",
    "CompareResult",
    "ControlSetup",
    "Controller",
    "CubicFrictionMap",
    "CurveFrictionMap",
    "IdentifiedPlant",
    "ModelFeedforward",
    "PIDGains",
    "PlantParams",
    "PressurePlant",
    "SimulationResult",
    "StepMetrics",
    "TuningResult",
    "compare",
    "fopdt_response",
    "identify_step",
    "itae",
    "itae_gains",
    "local_slope",
    "rule_gains",
    "run_case",
    "setpoint_profile",
    "simulate",
    "step_metrics",
]
