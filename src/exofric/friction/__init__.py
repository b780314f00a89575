"""The friction stage (paper §3.2, §4, §5): from a squeeze curve N(P) to friction and predictions.

Units: pressure P in MPa, squeezing force N and friction F in N (totals over the tube length),
torque in Nm, arm radius in m.

* :class:`FrictionModel` -- the Coulomb-type model F = gamma N + F0 (Eq 1; F0 = 0 in the paper).
* :class:`CubicFit` -- a cubic polynomial y(P) over a pressure range (Eq 8), with R^2 and a
  bracketed inverse (Brent) that refuses targets outside the fitted range or non-monotonic fits.
* :func:`pressure_for_friction` -- the paper's Section 5 inverse: the pressure that gives a
  target friction, via N = (F - F0) / gamma and the cubic inverse.
* :class:`SqueezeCurve` -- a validated tabulated squeeze curve N(P) with monotone (PCHIP)
  interpolation, its slope dN/dP and its exact inverse P(N) (:meth:`SqueezeCurve.pressure`,
  :meth:`SqueezeCurve.pressure_for_friction`): the one interpolant of FE curves and the one
  inverse of it, which the paper lacked.
* :func:`fit_gamma` -> :class:`GammaFit` -- gamma (Eq 7) from rig data with a CI (cluster-robust
  with replicate pulls, or errors-in-variables) and a :class:`LackOfFit` F test.
* :func:`predict` -> :class:`PredictionSet` -- friction of other structures (Table 3) and the
  applicability check; :func:`anova_vs_base` (Table 4).
* :class:`InterfaceFrictionModel` -- the interface-resolved law F = mu_tube S_wire +
  mu_wall N_wall (+ F0) (issue 15); :class:`InterfaceCurves` (a structure's FE S_wire(P),
  N(P)), :class:`InterfaceTest`, :func:`fit_interfaces` -> :class:`InterfaceFit` (both
  coefficients with CIs, their correlation and an identifiability verdict);
  :func:`simulate_interface_rig` -> :class:`InterfaceRigRun` (the virtual rig planting it).
* :class:`FrictionLaw` -- what a friction law is to its consumers (a ``typing.Protocol``:
  ``name``, ``inputs``, ``f0_n``, ``friction_of(columns)``, ``to_dict()``); both laws above
  are one, and :func:`predict`, :func:`simulate_law_rig` and
  :meth:`exofric.control.CurveFrictionMap.from_law` take any; :func:`law_columns` reads the
  columns a law needs off curves.
* :func:`torque` -- T = F R, optionally through a capstan wrap over the knee arc
  (exp(+-mu_arc theta), by the direction of motion), and a requirement check (knee 0-40 Nm).
* :func:`simulate_rig` -- the virtual friction rig (synthetic, labelled as such);
  :func:`simulate_law_rig` -- the same rig planting any :class:`FrictionLaw` on FE curves;
  :func:`simulate_raw_log` -- the same rig writing raw time-series logs with planted truths.
* :func:`reduce_log` -> :class:`RigReduction` -- a raw rig log (time, pressure, force,
  displacement) segmented into plateaus and pulls: static and kinetic friction per pull with
  autocorrelation-aware errors, direction bias, up/down hysteresis.
* :func:`fit_pullout` -> :class:`PulloutFit` -- mu_wire, mu_wall, mu_wire_wall and mu_static
  from measured force-displacement pulls (:func:`pulls_from_reduction`), pull-clustered
  intervals, coefficients the pulls cannot identify reported as such.

Examples
--------
>>> from exofric import paper
>>> from exofric.friction import CubicFit, FrictionModel, pressure_for_friction
>>> cubic = CubicFit(paper.eq8(), 0.2, 0.6)
>>> model = FrictionModel(0.7168)
>>> round(pressure_for_friction(54.40, cubic, model), 3)   # Eq 9 inverse (paper prints 0.26)
0.293
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from exofric._lazy import lazy_package

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from exofric.friction._curve import SqueezeCurve
    from exofric.friction._fit import (
        GammaFit,
        LackOfFit,
        fit_gamma,
        match_squeeze,
        relative_errors,
    )
    from exofric.friction._interfaces import (
        IdentifiabilityWarning,
        InterfaceCurves,
        InterfaceFit,
        InterfaceFrictionModel,
        InterfaceRigRun,
        InterfaceTest,
        fit_interfaces,
        simulate_interface_rig,
    )
    from exofric.friction._law import FrictionLaw, law_columns
    from exofric.friction._model import CubicFit, FrictionModel, pressure_for_friction
    from exofric.friction._predict import (
        ApplicabilityWarning,
        Deviation,
        LawPrediction,
        MeasuredCurve,
        Prediction,
        PredictionSet,
        deviation,
        paper_structures,
        predict,
        structures_from_dict,
    )
    from exofric.friction._pullfit import (
        PullFitSettings,
        PulloutFit,
        fit_pullout,
        pulls_from_reduction,
    )
    from exofric.friction._rawrig import RawRigConfig, RawRigLog, simulate_raw_log
    from exofric.friction._reduce import (
        ReduceSettings,
        RigReduction,
        friction_curve,
        integrated_autocorr_time,
        pool_pulls,
        reduce_log,
    )
    from exofric.friction._rig import RigConfig, RigRun, simulate_law_rig, simulate_rig
    from exofric.friction._stats import AnovaResult, anova_vs_base, one_way_anova
    from exofric.friction._stiffness import JointStiffness, joint_stiffness
    from exofric.friction._torque import TorqueCheck, capstan_factor, torque


# Lazy facade (PEP 562): importing one name does not load the whole stage; each name is loaded
# from its module on first use.
# The TYPE_CHECKING imports above are the one list of public names: __all__ and the facade
# are derived from them (exofric._lazy.lazy_package).
__getattr__, __dir__, __all__ = lazy_package(__name__, __file__)
