"""Friction force control by inflation pressure (generic: any friction map F(P), any plant).

* :class:`PlantParams`, :class:`PressurePlant` -- pressure supply (lag + dead time + saturation,
  PWM valves, sensor noise, model mismatch); :class:`CubicFrictionMap`,
  :class:`CurveFrictionMap` -- friction maps F(P) with their inverses.
* :class:`Controller` (discrete PID/PI/PD, filtered derivative, limits, anti-windup, bumpless
  start) and :class:`ModelFeedforward` (static or 2-DOF).
* :func:`identify_step` -- lag/delay/gain from a recorded step response.
* :class:`PneumaticPlant` (:class:`PneumaticParams`, :class:`Orifice`) -- the physical plant:
  ISO 6358 valve ports, regulator, line and tube volume (:func:`tube_volume_table` from the FE),
  gas law; :func:`simulate_charge` and :func:`identify_charge` (:class:`ChargeFit`) -- sonic
  conductance and volume from charge/discharge transients.
* :func:`closed_loop` -- the one call: a friction step with tuned gains, the model
  feedforward and the plant, from a structure, a squeeze result or a friction map
  (:class:`ClosedLoopResult`, with ``.plot()``).
* :func:`simulate` -- the closed loop at a fixed sample time (any :class:`PlantLike` plant).
* :class:`ScheduledController` (gains scheduled on dF/dP), :class:`HysteresisInverse`
  (branch-aware feedforward), :class:`HystereticFrictionMap` (two-branch friction for a
  simulated plant), :func:`compare_strategies` -- controllers beyond fixed PID compared.
* :func:`step_metrics` -- rise/settling time, overshoot, steady-state error, ITAE.
* :func:`rule_gains`, :func:`itae_gains` -- IMC/SIMC rule and ITAE optimisation under saturation.

The paper's Fig 12 experiment (its plant, Eq 9 map and settling times) is in
:mod:`exofric.reproduction`.

Units: friction N, pressure MPa, time s; gains kp MPa/N, ki MPa/(N s), kd MPa s/N.

Examples
--------
>>> from exofric.control import rule_gains
>>> t = rule_gains("pi", 400.0, 0.3, 0.05)     # slope N/MPa, lag s, dead time s
>>> t.gains.kp > 0
True
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from exofric._lazy import lazy_package

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from exofric.control._closed_loop import ClosedLoopResult, closed_loop
    from exofric.control._gait import (
        GAIT_CONTROLLERS,
        GaitComparison,
        GaitLike,
        GaitResult,
        GaitSetup,
        GaitSizing,
        StrideMetrics,
        compare_gait,
        identify_model,
        simulate_gait,
        size_valve,
    )
    from exofric.control._gait_controllers import (
        IterativeLearning,
        PlantModel,
        PressureMPC,
        PreviewFeedforward,
    )
    from exofric.control._identify import IdentifiedPlant, fopdt_response, identify_step
    from exofric.control._metrics import StepMetrics, itae, step_metrics
    from exofric.control._pid import AntiWindup, Controller, ModelFeedforward, PIDGains
    from exofric.control._plant import (
        CubicFrictionMap,
        CurveFrictionMap,
        PlantParams,
        PressurePlant,
        local_slope,
    )
    from exofric.control._pneumatic import (
        ChargeFit,
        Orifice,
        PneumaticParams,
        PneumaticPlant,
        identify_charge,
        simulate_charge,
        tube_volume_table,
    )
    from exofric.control._schedule import (
        HysteresisInverse,
        HystereticFrictionMap,
        ScheduledController,
        StrategyOptions,
        StrategyRow,
        StrategyTable,
        compare_strategies,
        friction_inverse,
    )
    from exofric.control._simulate import PlantLike, SimulationResult, setpoint_profile, simulate
    from exofric.control._tuning import CONTROLLERS, TuningResult, itae_gains, rule_gains


# Lazy facade (PEP 562): importing one name does not load the whole stage; each name is loaded
# from its module on first use.
# The TYPE_CHECKING imports above are the one list of public names: __all__ and the facade
# are derived from them (exofric._lazy.lazy_package).
__getattr__, __dir__, __all__ = lazy_package(__name__, __file__)
