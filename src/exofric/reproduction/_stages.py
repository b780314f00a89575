"""Stages 1-2 of ``exofric reproduce``: Table 2 (Eqs 3-6) and the calibration (Table 1, Fig 5b).

Each ``stage_*`` function is a pure computation (no printing, no files) returning a frozen
result with ``to_dict()``; :mod:`exofric.reproduction` runs them in order and times them.
Every printed number of the paper that a stage checks becomes a
:class:`~exofric.reproduction.Comparison` row (paper value, our value, difference).
Rows built on the virtual rig's output are flagged ``synthetic``: the paper's raw friction
curves are not published.

Stages here: 1 Table 2 (Eqs 3-6), 2 calibration (Table 1, Fig 5b). The other stages:
3 base squeeze (Figs 6-7) and 4 gamma (Fig 4, Eq 7) in :mod:`exofric.reproduction`
(their names are also importable from here), 5 prediction and ANOVA and 8 torque in
:mod:`exofric.reproduction`, 6 cubic fit and inverse and 7 control in
:mod:`exofric.reproduction`; the pipeline itself is in :mod:`exofric.reproduction`.
:class:`Comparison` and :func:`printed_decimals` (from :mod:`exofric.reproduction`) are
importable from here too.

Units: mm, N, MPa, s, Nm; errors and differences in %.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from exofric import defaults as D
from exofric import paper
from exofric._validate import checked_init
from exofric.calibration import (
    CalibrationResult,
    InflationData,
    calibrate,
    make_model,
    material_for,
)
from exofric.fe import MeshSpec
from exofric.material import MooneyRivlin
from exofric.reproduction._compare import Comparison, printed_decimals
from exofric.reproduction._squeeze import ID_STEP_MM as ID_STEP_MM
from exofric.reproduction._squeeze import GammaStage, SqueezeStage, stage_gamma, stage_squeeze

__all__ = [
    "Comparison",
    "Table2Stage",
    "CalibrationStage",
    "SqueezeStage",
    "GammaStage",
    "stage_table2",
    "stage_calibration",
    "stage_squeeze",
    "stage_gamma",
    "printed_decimals",
]


def _f(x: Any) -> float:
    return float(x)


# ----------------------------------------------------------------------------- stage 1


@checked_init
@dataclass(frozen=True)
class Table2Stage:
    """Table 2 from Eqs 3-6 at the paper's Shore 62.5, beside the printed values.

    ``rows`` holds, per parameter: the printed value, ours by Eqs 3-6 exactly, ours with
    the paper's C10 slip (C10 = G/2/1.005), and whether each rounds to the printed digits.

    Attributes
    ----------
    shore : float
        The paper's hardness (Shore A), 62.5.
    rows : tuple of dict
        One per Table 2 parameter: ``key``, ``quantity``, ``unit`` (MPa, 1/MPa or ''),
        ``paper_value``, ``eq_value`` (Eqs 3-6), ``slip_value`` (printed C10 slip),
        ``printed_decimals``, ``eq_matches_printed``, ``slip_matches_printed``, ``note``.
    material : MooneyRivlin
        Eqs 3-6 at ``shore`` exactly (C10, C01 in MPa, d in 1/MPa).
    slip_material : MooneyRivlin
        The same with the paper's C10 slip (what Table 2 prints).
    comparisons : tuple of Comparison
        One row per parameter: printed value beside Eqs 3-6 (MPa, 1/MPa).

    Examples
    --------
    >>> s = stage_table2()
    >>> s.shore, round(s.material.c10_mpa, 4), round(s.slip_material.c10_mpa, 4)   # C10 in MPa
    (62.5, 0.6354, 0.6639)
    """

    shore: float
    rows: tuple[dict[str, Any], ...]
    material: MooneyRivlin
    slip_material: MooneyRivlin
    comparisons: tuple[Comparison, ...]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (MPa, 1/MPa)."""
        return {
            "shore": self.shore,
            "rows": [dict(r) for r in self.rows],
            "material": self.material.to_dict(),
            "slip_material": self.slip_material.to_dict(),
            "comparisons": [c.to_dict() for c in self.comparisons],
        }


def stage_table2() -> Table2Stage:
    """Stage 1: Table 2 (MPa, 1/MPa) from Eqs 3-6 beside the printed values.

    Examples
    --------
    >>> s = stage_table2()
    >>> [r["key"] for r in s.rows if not r["eq_matches_printed"]]
    ['c01_mpa', 'c10_mpa', 'd_per_mpa']
    """
    printed = paper.table2()
    shore = float(printed["shore"])
    mat = MooneyRivlin.from_shore(shore)
    slip = material_for(shore, c10_convention="paper-slip")
    poisson = D.POISSON
    ours: dict[str, Any] = {**mat.to_dict(), "shore": shore, "poisson": poisson}
    ours_slip: dict[str, Any] = {**slip.to_dict(), "shore": shore, "poisson": poisson}
    labels = {
        "shore": ("H_S (Shore A)", ""), "e0_mpa": ("E0 (Eq 3)", "MPa"),
        "g_mpa": ("G = E0/3 (Eq 4)", "MPa"), "c01_mpa": ("C01 (Eq 5)", "MPa"),
        "c10_mpa": ("C10 (Eqs 4-5)", "MPa"), "poisson": ("mu, Poisson's ratio", ""),
        "d_per_mpa": ("d (Eq 6)", "1/MPa"),
    }
    notes = {
        "c10_mpa": "printed C10 = G/2/1.005 (slip for /1.05); Eq 4 gives G/2/1.05",
        "c01_mpa": "printed C01 = 0.05 x the slipped C10",
        "d_per_mpa": "printed d follows the slipped constants (0.004/0.6971 = 0.005738, "
                     "printed rounded up to 0.00575)",
        "g_mpa": "the slipped constants give 2(C10 + C01) = 1.3942 MPa, 4.5% above G",
    }
    rows, comps = [], []
    for key, (label, unit) in labels.items():
        pv = float(printed[key])
        dec = printed_decimals(pv)
        ov, sv = float(ours[key]), float(ours_slip[key])
        if key == "g_mpa":  # the slip column's G as implied by its constants
            sv = 2.0 * (slip.c10_mpa + slip.c01_mpa)
        rows.append({
            "key": key, "quantity": label, "unit": unit, "paper_value": pv,
            "eq_value": ov, "slip_value": sv, "printed_decimals": dec,
            "eq_matches_printed": math.isclose(round(ov, dec), pv, abs_tol=1e-12),
            "slip_matches_printed": math.isclose(round(sv, dec), pv, abs_tol=1e-12),
            "note": notes.get(key, ""),
        })
        comps.append(Comparison(f"Table 2 {label}", unit, pv, ov, notes.get(key, "")))
    return Table2Stage(shore, tuple(rows), mat, slip, tuple(comps))


# ----------------------------------------------------------------------------- stage 2


@checked_init
@dataclass(frozen=True)
class CalibrationStage:
    """Tube ID from the paper's ANSYS columns, then Shore from the test column (Table 1).

    Attributes
    ----------
    id_fit, id_fit_slip : CalibrationResult
        Known-hardness fits of the tube ID (mm) to the 16 printed ANSYS diameters, with
        Eq 4's constants and with the printed (slipped) ones.
    bisection, bounded : CalibrationResult
        Shore from the test diameters with the fitted ID: the paper's bisection and a
        bounded minimisation of the average error.
    tube_od_mm : float
        Tube outer diameter d1 (mm), Table 1's 8.3 mm.
    columns : tuple of dict
        Per Table 1 Shore column: pressures (MPa), the paper's and our diameters (mm),
        the differences (%), and both average errors vs the test column (%).
    comparisons : tuple of Comparison
        Table 1 diameters (mm) and average errors (%), the fitted tube ID (mm), the
        identified Shore (Shore A) and its average error (%), each beside the paper's.

    Examples
    --------
    >>> s = fast_result.calibration   # reproduce(ReproduceConfig.for_mode(fast=True)): coarse
    >>> s.tube_od_mm, round(s.tube_id_mm, 3), round(s.shore, 2)    # mm, mm, Shore A
    (8.3, 4.966, 62.57)
    """

    tube_od_mm: float
    id_fit: CalibrationResult
    id_fit_slip: CalibrationResult
    bisection: CalibrationResult
    bounded: CalibrationResult
    columns: tuple[dict[str, Any], ...]
    comparisons: tuple[Comparison, ...]

    @property
    def tube_id_mm(self) -> float:
        """The calibrated tube inner diameter (mm, Eq 4 constants)."""
        return self.id_fit.tube_id_mm

    @property
    def shore(self) -> float:
        """The calibrated Shore A hardness (the paper's bisection)."""
        return float(self.bisection.shore)  # type: ignore[arg-type]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (mm, MPa, %)."""
        def fit(r: CalibrationResult) -> dict[str, Any]:
            d = r.to_dict()
            d.pop("history", None)
            d["history_shore"] = [t.shore for t in r.history]
            d["history_average_error_pct"] = [t.average_error_pct for t in r.history]
            return d

        return {
            "tube_od_mm": self.tube_od_mm,
            "tube_id_mm": self.tube_id_mm,
            "tube_id_stderr_mm": self.id_fit.tube_id_stderr_mm,
            "tube_id_slip_mm": self.id_fit_slip.tube_id_mm,
            "shore": self.shore,
            "shore_bounded": self.bounded.shore,
            "id_fit": fit(self.id_fit),
            "id_fit_slip": fit(self.id_fit_slip),
            "bisection": fit(self.bisection),
            "bounded": fit(self.bounded),
            "columns": [dict(c) for c in self.columns],
            "comparisons": [c.to_dict() for c in self.comparisons],
        }


def stage_calibration(mesh: MeshSpec | None = None) -> CalibrationStage:
    """Stage 2: tube ID (mm) from the paper's simulated columns, Shore from the test data.

    Parameters
    ----------
    mesh : MeshSpec, optional
        Free-inflation mesh (default :data:`exofric.defaults.INFLATION_MESH`).

    Returns
    -------
    CalibrationStage

    Examples
    --------
    >>> from exofric.fe import MeshSpec
    >>> s = stage_calibration(MeshSpec(1, 4))                # coarse mesh, as in the fast mode
    >>> round(s.tube_id_mm, 3), round(s.shore, 2)            # default mesh: (4.967, 62.57)
    (4.966, 62.57)
    """
    t1 = paper.table1()
    od = float(t1["tube_od_mm"])
    model = make_model("fe", od, mesh=mesh)
    sim = InflationData.paper_simulated()
    test = InflationData.paper_test()
    id_fit = calibrate(sim, od, method="known-hardness", model=model, tube_id_mm=4.97)
    slip_model = make_model("fe", od, mesh=mesh, c10_convention="paper-slip")
    id_fit_slip = calibrate(sim, od, method="known-hardness", model=slip_model, tube_id_mm=4.97,
                            c10_convention="paper-slip")
    tid = id_fit.tube_id_mm
    bis = calibrate(test, od, method="bisection", model=model, tube_id_mm=tid)
    bnd = calibrate(test, od, method="bounded", model=model, tube_id_mm=tid)
    p_tab = np.asarray(t1["pressure_mpa"], dtype=float)
    d_test = np.asarray(t1["test_outer_diameter_mm"], dtype=float)
    cols, comps = [], []
    for shore, col, avg in zip(t1["simulated_shore"], t1["simulated_outer_diameter_mm"],
                               t1["average_error_pct"], strict=True):
        idx = np.flatnonzero(sim.shore == shore)
        ours = id_fit.simulated_mm[idx]
        pcol = np.asarray(col, dtype=float)
        diff = 100.0 * (ours / pcol - 1.0)
        our_avg = float(np.mean(np.abs(100.0 * (ours / d_test - 1.0))))
        paper_avg = float(np.mean(np.abs(100.0 * (pcol / d_test - 1.0))))
        cols.append({
            "shore": float(shore), "pressure_mpa": p_tab.tolist(),
            "paper_outer_diameter_mm": pcol.tolist(), "our_outer_diameter_mm": ours.tolist(),
            "difference_pct": diff.tolist(), "max_abs_difference_pct": float(np.abs(diff).max()),
            "paper_average_error_pct": float(avg), "paper_average_error_recomputed_pct": paper_avg,
            "our_average_error_pct": our_avg,
        })
        for p, pv, ov in zip(p_tab, pcol, ours, strict=True):
            comps.append(Comparison(f"Table 1 OD, {shore:g} Hs, {p:g} MPa", "mm", float(pv),
                                    float(ov), "our FE with the fitted tube ID"))
        comps.append(Comparison(f"Table 1 average error, {shore:g} Hs", "%", float(avg), our_avg,
                                "mean |sim - test| / test"))
    comps += [
        Comparison("tube inner diameter (not printed)", "mm", None, tid,
                   "least squares on the 16 printed ANSYS diameters (Eq 4 constants)"),
        Comparison("Shore hardness (bisection, Table 1)", "Shore A", 62.5, _f(bis.shore),
                   "paper's bisection with our FE; " + ("tolerance met" if bis.converged
                                                        else "0.5% tolerance not met")),
        Comparison("average error at the identified Shore", "%", 0.46, bis.average_error_pct,
                   "vs the test column"),
    ]
    return CalibrationStage(od, id_fit, id_fit_slip, bis, bnd, tuple(cols), tuple(comps))
