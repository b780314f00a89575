"""Stages 6-7 of ``exofric reproduce``: the paper's Section 5, cubic fit, inverse and control.

* Stage 6 (Eq 8, Fig 11): :func:`stage_cubic` -- least-squares cubic of our test-5 N(P)
  beside Eq 8, and the pressure for the 54.40 N target by every route (Eq 9, Eq 8 without
  gamma, our cubic, the exact inverse of our FE curve).
* Stage 7 (Fig 12): :func:`stage_control` -- PD/PI/PID with and without the model
  feedforward, on Eq 9 and on our test-5 FE curve.

Pure computation (no printing, no files); each stage returns a frozen result with
``to_dict()`` and its :class:`~exofric.reproduction.Comparison` rows. These names are
also importable from :mod:`exofric.reproduction`.

Units: N, MPa, s; differences in %.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from exofric import paper
from exofric._validate import checked_init
from exofric.control import CurveFrictionMap
from exofric.friction import CubicFit, FrictionModel, SqueezeCurve, pressure_for_friction
from exofric.reproduction._compare import Comparison
from exofric.reproduction._fig12 import CompareResult, ControlSetup, compare
from exofric.simulate import SqueezeResult

__all__ = ["CubicStage", "ControlStage", "stage_cubic", "stage_control"]


# ----------------------------------------------------------------------------- stage 6


@checked_init
@dataclass(frozen=True)
class CubicStage:
    """Cubic N(P) for test 5 (Eq 8) beside the paper's, and the pressure for 54.40 N (MPa).

    Attributes
    ----------
    pressure_mpa : tuple of float
        Our test-5 pressures within Eq 8's fit range, 0.2-0.6 MPa.
    squeeze_force_n : tuple of float
        Our FE squeezing force N (N) at those pressures.
    ours : CubicFit
        Least-squares cubic of those points (coefficients in N/MPa^k).
    paper_eq8 : CubicFit
        The paper's Eq 8 (N vs MPa).
    gamma : float
        Our fitted gamma (unitless) used for our inverses.
    inverse : dict of str to float
        Pressure (MPa) for the target friction by each route: ``paper_printed_mpa`` (0.26),
        ``eq9_mpa``, ``eq8_without_gamma_mpa``, ``our_cubic_mpa``, ``our_exact_curve_mpa``.
    comparisons : tuple of Comparison
        Eq 8 coefficients (N/MPa^k), R^2, N at 0.4 and 0.6 MPa (N) and the pressures for
        the target (MPa) beside the paper's.

    Examples
    --------
    >>> s = fast_result.cubic         # reproduce(ReproduceConfig.for_mode(fast=True))
    >>> s.inverse["paper_printed_mpa"], round(s.inverse["eq9_mpa"], 4), len(s.pressure_mpa)
    (0.26, 0.2926, 9)
    """

    pressure_mpa: tuple[float, ...]
    squeeze_force_n: tuple[float, ...]
    ours: CubicFit
    paper_eq8: CubicFit
    gamma: float
    inverse: dict[str, float]
    comparisons: tuple[Comparison, ...]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (MPa, N)."""
        return {
            "pressure_mpa": list(self.pressure_mpa),
            "squeeze_force_n": list(self.squeeze_force_n),
            "eq8_at_pressures_n": self.paper_eq8(np.asarray(self.pressure_mpa)).tolist(),
            "ours": self.ours.to_dict(),
            "paper_eq8": self.paper_eq8.to_dict(),
            "gamma": self.gamma,
            "inverse_mpa": dict(self.inverse),
            "comparisons": [c.to_dict() for c in self.comparisons],
        }


def stage_cubic(test5: SqueezeResult, gamma: float, target_n: float) -> CubicStage:
    """Stage 6: least-squares cubic of our test-5 N(P) on 0.2-0.6 MPa and the inverses (MPa).

    Parameters
    ----------
    test5 : SqueezeResult
        Test-5 squeeze curve (anything with ``pressure_mpa`` in MPa and ``squeeze_force_n``
        in N); the points within Eq 8's 0.2-0.6 MPa are fitted.
    gamma : float
        Our fitted gamma (unitless) for our inverses (Eq 9 uses the paper's 0.7168).
    target_n : float
        Target friction (N), the paper's 54.40 N.

    Returns
    -------
    CubicStage

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> p = np.round(np.arange(4, 13) * 0.05, 10)    # 0.2-0.6 MPa, where Eq 8 is > 0
    >>> t5 = SimpleNamespace(pressure_mpa=p, squeeze_force_n=np.polyval(paper.eq8(), p))
    >>> c = stage_cubic(t5, 0.7168, 54.40)          # Eq 8 itself: the fit returns Eq 8
    >>> round(c.ours.coefficients[0], 3), round(c.inverse["our_cubic_mpa"], 4)
    (-1957.4, 0.2926)
    """
    lo, hi = (float(x) for x in paper.load()["eq8"]["fit_range_mpa"])
    p, n = np.asarray(test5.pressure_mpa), np.asarray(test5.squeeze_force_n)
    keep = (p >= lo - 1e-12) & (p <= hi + 1e-12)
    ours = CubicFit.fit(p[keep], n[keep], (lo, hi))
    eq8 = CubicFit(paper.eq8(), lo, hi)
    g_paper = paper.scalar("gamma")
    inv = {
        "paper_printed_mpa": paper.scalar("target_pressure_mpa"),
        "eq9_mpa": pressure_for_friction(target_n, eq8, FrictionModel(g_paper)),
        "eq8_without_gamma_mpa": eq8.inverse(target_n),
        "our_cubic_mpa": pressure_for_friction(target_n, ours, FrictionModel(gamma)),
        "our_exact_curve_mpa": SqueezeCurve(p, n).pressure_for_friction(
            target_n, FrictionModel(gamma)),
    }
    names = ("c3 (P^3)", "c2 (P^2)", "c1 (P)", "c0")
    units = ("N/MPa^3", "N/MPa^2", "N/MPa", "N")
    comps = [Comparison(f"Eq 8 coefficient {nm}", u, pc, oc, "our FE, least squares on "
                        f"{int(keep.sum())} points, {lo:g}-{hi:g} MPa")
             for nm, u, pc, oc in zip(names, units, eq8.coefficients, ours.coefficients,
                                      strict=True)]
    comps += [
        Comparison("R^2 of the cubic (Fig 11)", "", paper.scalar("cubic_r2"), ours.r2),
        Comparison("test 5: N at 0.6 MPa (Eq 8 vs our FE)", "N", eq8(hi), float(n[keep][-1])),
        Comparison("test 5: N at 0.4 MPa (Eq 8 vs our FE)", "N", eq8(0.4),
                   float(np.interp(0.4, p, n))),
        Comparison(f"pressure for {target_n:g} N from Eq 9 (Sec 5)", "MPa",
                   inv["paper_printed_mpa"], inv["eq9_mpa"],
                   "the paper's own Eq 9 inverted; its 0.26 is Eq 8 inverted without gamma "
                   f"({inv['eq8_without_gamma_mpa']:.4f} MPa)"),
        Comparison(f"pressure for {target_n:g} N, our FE curve and gamma", "MPa",
                   inv["paper_printed_mpa"], inv["our_exact_curve_mpa"],
                   "exact inverse of our FE N(P) (PCHIP) with our gamma", synthetic=True),
    ]
    return CubicStage(tuple(p[keep].tolist()), tuple(n[keep].tolist()), ours, eq8, gamma, inv,
                      tuple(comps))


# ----------------------------------------------------------------------------- stage 7


@checked_init
@dataclass(frozen=True)
class ControlStage:
    """The six Fig 12 cases on the paper's Eq 9 map, and on our test-5 FE curve with our gamma.

    Attributes
    ----------
    paper_map : CompareResult
        PD/PI/PID without and with the model on Eq 9 (gamma 0.7168), target in N,
        settling times in s.
    our_map : CompareResult
        The same on our test-5 FE curve N(P) (PCHIP) times our gamma.
    comparisons : tuple of Comparison
        Settling times (s), the PD final friction (N) and the settling-time reductions (%)
        on Eq 9, beside the paper's.

    Examples
    --------
    >>> s = fast_result.control       # reproduce(ReproduceConfig.for_mode(fast=True))
    >>> len(s.paper_map.cases), s.paper_map.target_n, round(s.our_map.reduction_pct("pi"), 1)
    (6, 54.4, 38.4)
    """

    paper_map: CompareResult = field(repr=False)
    our_map: CompareResult = field(repr=False)
    comparisons: tuple[Comparison, ...]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (N, MPa, s, %)."""
        return {"paper_map": self.paper_map.to_dict(), "our_map": self.our_map.to_dict(),
                "comparisons": [c.to_dict() for c in self.comparisons]}


def stage_control(test5: SqueezeResult, gamma: float, target_n: float) -> ControlStage:
    """Stage 7: PD/PI/PID with and without the model feedforward (s, N).

    On the paper's Eq 9 and on our test-5 FE curve N(P) (PCHIP, not our cubic: a cubic
    fitted on 0.2-0.6 MPa is not physical below 0.2 MPa) times our gamma.

    Parameters
    ----------
    test5 : SqueezeResult
        Test-5 squeeze curve (``pressure_mpa`` in MPa, ``squeeze_force_n`` in N, arrays).
    gamma : float
        Our fitted gamma (unitless) for the FE-curve map.
    target_n : float
        Step target friction (N), the paper's 54.40 N.

    Returns
    -------
    ControlStage

    Examples
    --------
    >>> r = fast_result             # = reproduce(ReproduceConfig.for_mode(fast=True))
    >>> round(r.control.paper_map.reduction_pct("pi"), 1)
    32.7
    """
    setup = ControlSetup.default(target_n=target_n)
    res = compare(setup)
    fe_map = CurveFrictionMap(tuple(test5.pressure_mpa.tolist()),
                              tuple(test5.squeeze_force_n.tolist()), gamma)
    ours = compare(ControlSetup.default(target_n=target_n, model_map=fe_map))
    comps = []
    note = ("assumed plant (lag 0.8 s, dead time 0.2 s) and rule-tuned gains: the paper prints "
            "neither; 2% band")
    for c in res.cases:
        lab = f"{c.controller.upper()}{' + model' if c.feedforward else ''}"
        if c.paper_settling_time_s is None:
            comps.append(Comparison(f"{lab}: final friction (paper: 'steady-state error')", "N",
                                    None, c.metrics.final_friction_n, note))
            continue
        comps.append(Comparison(f"{lab}: settling time (Fig 12)", "s", c.paper_settling_time_s,
                                c.metrics.settling_time_s, note))
    for k in ("pi", "pid"):
        comps.append(Comparison(f"{k.upper()}: settling-time reduction with the model", "%",
                                paper.scalar(f"settling_reduction_{k}_pct"), res.reduction_pct(k),
                                note))
    return ControlStage(res, ours, tuple(comps))
