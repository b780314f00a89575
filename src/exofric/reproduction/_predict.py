"""Stages 5 and 8 of ``exofric reproduce``: prediction for the Table 3 structures, torque.

* Stage 5 (Figs 8-10, Table 4): :func:`stage_prediction` -- F = gamma N(P) for the seven
  Table 3 structures against SYNTHETIC virtual-rig curves, deviation metrics and the ANOVA.
* Stage 8 (Sec 3.2, Sec 4): :func:`stage_torque` -- T = F R at 0.6 MPa per structure against
  the knee's 0-40 Nm.

Pure computation (no printing, no files); each stage returns a frozen result with
``to_dict()`` and its :class:`~exofric.reproduction.Comparison` rows. These names are
also importable from :mod:`exofric.reproduction`.

Units: mm, N, MPa, m, Nm; errors and differences in %.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import TYPE_CHECKING, Any

import numpy as np

from exofric import paper
from exofric._validate import checked_init
from exofric.friction import (
    MeasuredCurve,
    PredictionSet,
    RigRun,
    match_squeeze,
    paper_structures,
    predict,
    simulate_rig,
    torque,
)
from exofric.geometry import Structure
from exofric.material import MooneyRivlin
from exofric.reproduction._compare import Comparison
from exofric.reproduction._squeeze import GammaStage
from exofric.simulate import SqueezeResult

if TYPE_CHECKING:
    from exofric.reproduction._pipeline import ReproduceConfig

__all__ = ["PredictionStage", "TorqueStage", "stage_prediction", "stage_torque"]


# ----------------------------------------------------------------------------- stage 5


@checked_init
@dataclass(frozen=True)
class PredictionStage:
    """Predictions for the seven Table 3 structures against SYNTHETIC measured curves.

    Every structure's rig plants the same ``gamma_true`` (no per-structure effect), so the
    errors and p-values show what the Coulomb model gives when it holds, plus noise: the
    paper's published maximum errors (-12 % ... +189 %) and p-values are not reproducible
    without its raw curves.

    Attributes
    ----------
    structures : tuple of Structure
        Tests 1-7 of Table 3 (sizes in mm), test 1 the base group.
    squeezes : tuple of SqueezeResult
        FE squeeze N(P) of each structure (N vs MPa), in ``structures`` order.
    runs : tuple of RigRun
        SYNTHETIC virtual-rig test of each structure (MPa, N); test 1's is the gamma stage's.
    predictions : PredictionSet
        F = gamma N(P) (N) per structure against its rig curve, with deviations and ANOVA.
    rows : tuple of dict
        One per test: group, structure (mm), deviations (%), clearance (mm), validated
        region, contact onset (MPa), maximum relative errors (%) and p-values, ours and the
        paper's, and the number of rig points.
    warnings : tuple of str
        Warnings raised while predicting (structures outside the validated region).
    comparisons : tuple of Comparison
        Maximum relative errors (%), ANOVA p-values (unitless) and Table 3 deviations (%)
        beside the paper's.

    Examples
    --------
    >>> s = fast_result.prediction    # reproduce(ReproduceConfig.for_mode(fast=True))
    >>> [st.name for st in s.structures][:3], len(s.runs), len(s.warnings)
    (['test 1', 'test 2', 'test 3'], 7, 2)
    """

    structures: tuple[Structure, ...]
    squeezes: tuple[SqueezeResult, ...] = field(repr=False)
    runs: tuple[RigRun, ...] = field(repr=False)
    predictions: PredictionSet = field(repr=False)
    rows: tuple[dict[str, Any], ...]
    warnings: tuple[str, ...]
    comparisons: tuple[Comparison, ...]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (mm, MPa, N, %)."""
        return {
            "synthetic": True,
            "rows": [dict(r) for r in self.rows],
            "predictions": self.predictions.to_dict(),
            "rigs": [r.to_dict() for r in self.runs],
            "warnings": list(self.warnings),
            "comparisons": [c.to_dict() for c in self.comparisons],
        }


def _rig_points(res: SqueezeResult, set_points: tuple[float, ...]) -> np.ndarray:
    """Rig set points (MPa) at which the squeeze curve is positive (contact reached)."""
    sp = np.asarray(set_points, dtype=float)
    n, _ = match_squeeze(res.pressure_mpa, res.squeeze_force_n, sp, edge_tol_mpa=0.0)
    return sp[np.nan_to_num(n) > 1e-9]


def stage_prediction(
    base_result: SqueezeResult, gamma: GammaStage, material: MooneyRivlin, cfg: ReproduceConfig
) -> PredictionStage:
    """Stage 5: F = gamma N(P) for the Table 3 structures vs SYNTHETIC curves; Table 4 ANOVA.

    Runs the FE squeeze for tests 2-7 (test 1 is ``base_result``) and one virtual-rig test
    per structure (seed ``cfg.seed + k``). Units: mm, MPa, N, %.

    Parameters
    ----------
    base_result : SqueezeResult
        Base-group (test 1) squeeze N(P) of stage 3 (N vs MPa); its structure is the base
        that Table 3 scales.
    gamma : GammaStage
        Stage 4: its rig run is test 1's measured curve and its fitted model (gamma
        unitless) makes the predictions.
    material : MooneyRivlin
        Calibrated tube material (MPa, 1/MPa).
    cfg : ReproduceConfig
        Pressures (MPa), squeeze mesh, rig set points (MPa), ``gamma_true``, rig settings,
        seed and lever arm (m).

    Returns
    -------
    PredictionStage

    Examples
    --------
    >>> r = fast_result             # = reproduce(ReproduceConfig.for_mode(fast=True))
    >>> [row["in_validated_region"] for row in r.prediction.rows]
    [True, True, True, True, True, False, False]
    """
    from exofric.simulate import squeeze

    base = base_result.structure
    structs = paper_structures(base)
    p = np.asarray(cfg.pressures_mpa, dtype=float)
    curves = {structs[0].name: base_result}
    for s in structs[1:]:
        curves[s.name] = squeeze(s, material, p, mesh=cfg.squeeze_mesh, keep_fields=False)
    runs = [gamma.rig]
    for k, s in enumerate(structs[1:], start=2):
        r = curves[s.name]
        runs.append(simulate_rig(r.pressure_mpa, r.squeeze_force_n, cfg.gamma_true,
                                 _rig_points(r, cfg.rig_pressures_mpa), config=cfg.rig,
                                 seed=cfg.seed + k))
    measured = {s.name: MeasuredCurve.of(r.pressure_mpa, r.friction_n)
                for s, r in zip(structs, runs, strict=True)}

    def from_curves(s: Structure, _m: Any, pe: np.ndarray) -> Any:
        # the squeeze was solved on the grid; the rig's logged pressures (within 2e-4 MPa of
        # the set points) are read off it by monotone PCHIP, as in fit_gamma
        r = curves[s.name]
        n, _ = match_squeeze(r.pressure_mpa, r.squeeze_force_n, pe)
        return SimpleNamespace(pressure_mpa=pe, squeeze_force_n=n,
                               contact_onset_pressure_mpa=r.contact_onset_pressure_mpa)

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        pset = predict(structs, gamma.fit.model, material, p, squeeze_fn=from_curves,
                       measured=measured, base=base, arm_radius_m=cfg.arm_radius_m)
    t3 = {int(r["test"]): r for r in paper.table3()}
    t4 = paper.table4()
    max_err = dict(zip(paper.load()["max_relative_error"]["test"],
                       paper.load()["max_relative_error"]["max_relative_error_pct"], strict=True))
    anova = {a.name.split(" vs ")[0]: a for a in pset.anova}
    rows, comps = [], []
    for pr in pset.predictions:
        k = int(pr.structure.name.split()[-1])
        dev = pr.deviation
        a = anova.get(pr.structure.name)
        row = {
            "test": k, "group": t3[k]["group"], "structure": pr.structure.to_dict(),
            "paper_deviation_printed_pct": t3[k]["max_relative_deviation_pct"],
            "deviation_pct": dev.deviation_pct, "paper_deviation_pct": dev.paper_deviation_pct,
            "tube_ref_deviation_pct": dev.tube_ref_deviation_pct,
            "clearance_mm": dev.clearance_mm, "in_validated_region": dev.in_validated_region,
            "contact_onset_pressure_mpa": pr.contact_onset_pressure_mpa,
            "paper_max_relative_error_pct": max_err.get(k),
            "max_relative_error_pct": pr.max_relative_error_pct,
            "paper_p_value": t4.get(k), "p_value": None if a is None else a.p_value,
            "n_rig_points": len(pr.measured.pressure_mpa) if pr.measured else 0,
        }
        rows.append(row)
        if k in max_err:
            comps.append(Comparison(f"test {k}: maximum relative error (Figs 8-10)", "%",
                                    float(max_err[k]), pr.max_relative_error_pct,
                                    "SYNTHETIC curves with one gamma_true for all structures",
                                    synthetic=True))
        if k in t4 and a is not None:
            comps.append(Comparison(f"test {k}: ANOVA p-value vs base (Table 4)", "", t4[k],
                                    a.p_value, "SYNTHETIC", synthetic=True))
        if t3[k]["max_relative_deviation_pct"] is not None:
            comps.append(Comparison(f"test {k}: maximum relative deviation (Table 3)", "%",
                                    float(t3[k]["max_relative_deviation_pct"]),
                                    dev.paper_deviation_pct, "100 max|s - 1|, one of several "
                                    "readings (the paper gives no formula)"))
    msgs = tuple(str(w.message) for w in caught)
    return PredictionStage(structs, tuple(curves[s.name] for s in structs), tuple(runs), pset,
                           tuple(rows), msgs, tuple(comps))


# ----------------------------------------------------------------------------- stage 8


@checked_init
@dataclass(frozen=True)
class TorqueStage:
    """Predicted torque T = F R at 0.6 MPa per structure against the knee's 0-40 Nm.

    Attributes
    ----------
    rows : tuple of dict
        One per structure: ``name``, ``pressure_mpa``, then the
        :class:`~exofric.friction.TorqueCheck` fields (``friction_n``, ``arm_radius_m``,
        ``torque_nm``, the knee's range in Nm, ``meets_max``, ``coverage_pct``).
    comparisons : tuple of Comparison
        Base and test 3 torques (Nm) and test 3 friction (N) beside the paper's.

    Examples
    --------
    >>> s = fast_result.torque        # reproduce(ReproduceConfig.for_mode(fast=True))
    >>> s.rows[0]["name"], round(s.rows[0]["torque_nm"], 1), s.rows[0]["meets_max"]
    ('test 1', 17.2, False)
    """

    rows: tuple[dict[str, Any], ...]
    comparisons: tuple[Comparison, ...]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (N, m, Nm, %)."""
        return {"rows": [dict(r) for r in self.rows],
                "comparisons": [c.to_dict() for c in self.comparisons]}


def stage_torque(pred: PredictionStage, arm_radius_m: float) -> TorqueStage:
    """Stage 8: T = gamma N(0.6 MPa) R (Nm) per structure; paper's 18.05 and 30 Nm beside.

    Parameters
    ----------
    pred : PredictionStage
        Stage 5: the predicted friction F(P) (N) of each structure; its last pressure
        (0.6 MPa) is used.
    arm_radius_m : float
        Lever arm R (m), the paper's 0.10 m.

    Returns
    -------
    TorqueStage

    Examples
    --------
    >>> r = fast_result             # = reproduce(ReproduceConfig.for_mode(fast=True))
    >>> [round(t["torque_nm"], 1) for t in r.torque.rows][:3]
    [17.2, 12.0, 21.3]
    """
    lo, hi = paper.scalar("knee_torque_min_nm"), paper.scalar("knee_torque_max_nm")
    rows = []
    for pr in pred.predictions.predictions:
        t = torque(float(pr.predicted_friction_n[-1]), arm_radius_m, (lo, hi))
        rows.append({"name": pr.structure.name, "pressure_mpa": pr.pressure_mpa[-1],
                     **t.to_dict()})
    by = {r["name"]: r for r in rows}
    comps = (
        Comparison("base torque at 0.6 MPa (Sec 3.2)", "Nm",
                   paper.scalar("base_friction_moment_nm"), by["test 1"]["torque_nm"],
                   "paper: measured 180.49 N x 0.10 m; ours: predicted gamma N x 0.10 m"),
        Comparison("test 3 torque, the largest (Sec 4)", "Nm", paper.scalar("test3_torque_nm"),
                   by["test 3"]["torque_nm"], "paper: measured 300 N x 0.10 m; ours: predicted"),
        Comparison("test 3 friction at 0.6 MPa (Sec 4)", "N", paper.scalar("test3_max_friction_n"),
                   by["test 3"]["friction_n"], "paper: measured; ours: predicted"),
    )
    return TorqueStage(tuple(rows), comps)
