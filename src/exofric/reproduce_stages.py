"""The stages of ``exofric reproduce``: the paper's study redone, each number beside the paper's.

Each ``stage_*`` function is a pure computation (no printing, no files) returning a frozen
result with ``to_dict()``; :mod:`exofric.reproduce` runs them in order and times them.
Every printed number of the paper that a stage checks becomes a :class:`Comparison` row
(paper value, our value, difference). Rows built on the virtual rig's output are flagged
``synthetic``: the paper's raw friction curves are not published.

Stages here: 1 Table 2 (Eqs 3-6), 2 calibration (Table 1, Fig 5b), 3 base squeeze (Figs 6-7),
4 gamma (Fig 4, Eq 7). Stages 5-8 (prediction and ANOVA, cubic fit and inverse, control,
torque) and the pipeline itself are in :mod:`exofric.reproduce`.

Units: mm, N, MPa, s, Nm; errors and differences in %.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from . import paper
from .calibrate import CalibrationResult, InflationData, calibrate, make_model, material_for
from .friction_fit import GammaFit, fit_gamma
from .geometry import Structure
from .materials import MooneyRivlin
from .rig import RigConfig, RigRun, simulate_rig
from .simulate import MeshSpec, SqueezeResult, squeeze

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

#: Sensitivity step of the tube inner diameter (mm) for dN/dID in the squeeze discussion.
ID_STEP_MM = 0.05


def printed_decimals(value: float) -> int:
    """Decimals with which a paper value was printed (from its shortest repr), e.g. 4.0033 -> 4.

    Examples
    --------
    >>> printed_decimals(0.00575), printed_decimals(62.5), printed_decimals(268.55)
    (5, 1, 2)
    """
    text = repr(float(value))
    if "e" in text or "E" in text:
        mant, exp = text.lower().split("e")
        dec = len(mant.split(".")[1].rstrip("0")) if "." in mant else 0
        return max(0, dec - int(exp))
    return len(text.split(".")[1].rstrip("0")) if "." in text else 0


@dataclass(frozen=True)
class Comparison:
    """One paper number beside ours.

    Attributes
    ----------
    quantity : str
        What is compared (with the paper's table/figure/equation).
    unit : str
        Unit of both values ('' for unitless).
    paper_value, our_value : float or None
        None when the paper prints no value (e.g. the tube ID) or we have none.
    note : str
        Why they differ, or what the row means.
    synthetic : bool
        True when our value comes from synthetic (virtual-rig) data.

    Examples
    --------
    >>> c = Comparison("N at 0.6 MPa", "N", 268.55, 240.1)
    >>> round(c.difference, 2), round(c.difference_pct, 2)
    (-28.45, -10.59)
    """

    quantity: str
    unit: str
    paper_value: float | None
    our_value: float | None
    note: str = ""
    synthetic: bool = False

    @property
    def difference(self) -> float | None:
        """ours - paper (in ``unit``), None if either is missing."""
        if self.paper_value is None or self.our_value is None:
            return None
        return float(self.our_value - self.paper_value)

    @property
    def difference_pct(self) -> float | None:
        """100 (ours - paper) / |paper| (%), None if undefined."""
        d = self.difference
        if d is None or self.paper_value == 0:
            return None
        return float(100.0 * d / abs(float(self.paper_value)))  # type: ignore[arg-type]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready row: values in ``unit``, ``difference_pct`` in %."""
        return {
            "quantity": self.quantity,
            "unit": self.unit,
            "paper_value": self.paper_value,
            "our_value": self.our_value,
            "difference": self.difference,
            "difference_pct": self.difference_pct,
            "note": self.note,
            "synthetic": self.synthetic,
        }


def _f(x: Any) -> float:
    return float(x)


# ----------------------------------------------------------------------------- stage 1


@dataclass(frozen=True)
class Table2Stage:
    """Table 2 from Eqs 3-6 at the paper's Shore 62.5, beside the printed values.

    ``rows`` holds, per parameter: the printed value, ours by Eqs 3-6 exactly, ours with
    the paper's C10 slip (C10 = G/2/1.005), and whether each rounds to the printed digits.
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
    poisson = 0.498
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
            sv = 2.0 * (slip.c10 + slip.c01)
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
    columns : tuple of dict
        Per Table 1 Shore column: pressures (MPa), the paper's and our diameters (mm),
        the differences (%), and both average errors vs the test column (%).
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
        Free-inflation mesh (default :data:`exofric.simulate.DEFAULT_INFLATION_MESH`).

    Returns
    -------
    CalibrationStage

    Examples
    --------
    >>> s = stage_calibration()                              # doctest: +SKIP
    >>> round(s.tube_id_mm, 3), round(s.shore, 2)            # doctest: +SKIP
    (4.967, 62.57)
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


# ----------------------------------------------------------------------------- stage 3


@dataclass(frozen=True)
class SqueezeStage:
    """Base-group squeeze N(P) (Figs 6-7) and what moves N at 0.6 MPa.

    Attributes
    ----------
    result : SqueezeResult
        The base squeeze with fields (deformed sections, stress) on the full mesh.
    sensitivity : tuple of dict
        N at 0.6 MPa (N) for variants on the sensitivity mesh: baseline, tube ID -/+
        :data:`ID_STEP_MM`, the paper's printed (slipped) constants with their fitted ID,
        the paper's Shore 62.5, and a 10x softer contact penalty; each with its change from the
        baseline in %.
    """

    result: SqueezeResult
    sensitivity: tuple[dict[str, Any], ...]
    dn_did_n_per_mm: float
    id_to_match_paper_mm: float
    comparisons: tuple[Comparison, ...]

    @property
    def n_at_max_n(self) -> float:
        """Squeezing force at the highest pressure (N)."""
        return float(self.result.squeeze_force_n[-1])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (MPa, N, mm)."""
        return {
            "squeeze": self.result.to_dict(),
            "n_at_0_6_mpa_n": self.n_at_max_n,
            "sensitivity": [dict(s) for s in self.sensitivity],
            "dn_did_n_per_mm": self.dn_did_n_per_mm,
            "id_to_match_paper_mm": self.id_to_match_paper_mm,
            "comparisons": [c.to_dict() for c in self.comparisons],
        }


def stage_squeeze(
    base: Structure,
    material: MooneyRivlin,
    pressures_mpa: np.ndarray,
    *,
    mesh: MeshSpec,
    sensitivity_mesh: MeshSpec,
    slip_tube_id_mm: float,
) -> SqueezeStage:
    """Stage 3: base squeeze N(P) (N vs MPa) and the sensitivity of N(0.6 MPa).

    Parameters
    ----------
    base : Structure
        Base group with the calibrated tube ID (mm).
    material : MooneyRivlin
        Calibrated tube material.
    pressures_mpa : ndarray
        Increasing pressures (MPa), ending at 0.6.
    mesh, sensitivity_mesh : MeshSpec
        Mesh of the main solve and of the (cheaper) sensitivity solves.
    slip_tube_id_mm : float
        Tube ID (mm) fitted with the printed (slipped) constants.

    Examples
    --------
    >>> import numpy as np
    >>> from exofric.geometry import BASE
    >>> from exofric.simulate import MeshSpec
    >>> m = MeshSpec(1, 12, grading=6.0)
    >>> s = stage_squeeze(BASE, MooneyRivlin.from_shore(62.5), np.array([0.3, 0.6]), mesh=m,
    ...                   sensitivity_mesh=m, slip_tube_id_mm=5.05)   # doctest: +SKIP
    >>> round(s.n_at_max_n)                                           # doctest: +SKIP
    240
    """
    main = squeeze(base, material, pressures_mpa, mesh=mesh, keep_fields=True)
    pmax = [float(pressures_mpa[-1])]
    t2 = paper.table2()
    printed = MooneyRivlin(float(t2["c10_mpa"]), float(t2["c01_mpa"]), float(t2["d_per_mpa"]),
                           shore=float(t2["shore"]), correlation="paper (printed Table 2)")

    def n_of(s: Structure, m: MooneyRivlin, penalty: float | None = None) -> float:
        kw: dict[str, Any] = {} if penalty is None else {"penalty": penalty}
        r = squeeze(s, m, pmax, mesh=sensitivity_mesh, keep_fields=False, **kw)
        return float(r.squeeze_force_n[-1])

    def with_id(tid: float) -> Structure:
        return Structure(base.hole_mm, base.tube_od_mm, tid, base.wire_mm, base.length_mm,
                         base.name)

    from .simulate import DEFAULT_PENALTY

    n0 = n_of(base, material)
    variants = [
        ("baseline (calibrated ID and Shore, Eq 4 constants)", n0),
        (f"tube ID - {ID_STEP_MM:g} mm", n_of(with_id(base.tube_id_mm - ID_STEP_MM), material)),
        (f"tube ID + {ID_STEP_MM:g} mm", n_of(with_id(base.tube_id_mm + ID_STEP_MM), material)),
        (f"printed Table 2 constants (C10 slip) with their ID {slip_tube_id_mm:.4f} mm",
         n_of(with_id(slip_tube_id_mm), printed)),
        ("Shore 62.5 exactly (the paper's)", n_of(base, MooneyRivlin.from_shore(62.5))),
        ("contact penalty / 10 (1e4 N/mm^3)", n_of(base, material, 0.1 * DEFAULT_PENALTY)),
    ]
    sens = tuple({"variant": name, "n_at_0_6_mpa_n": n, "change_pct": 100.0 * (n / n0 - 1.0)}
                 for name, n in variants)
    dn_did = (variants[2][1] - variants[1][1]) / (2.0 * ID_STEP_MM)
    n06 = float(main.squeeze_force_n[-1])
    need_id = base.tube_id_mm + (paper.scalar("base_squeeze_force_at_0_6_mpa_n") - n06) / dn_did
    comps = (
        Comparison("squeezing force N at 0.6 MPa, base group (Fig 7)", "N",
                   paper.scalar("base_squeeze_force_at_0_6_mpa_n"), n06,
                   f"tube ID {base.tube_id_mm:.4f} mm; matching 268.55 N would need an ID of "
                   f"about {need_id:.2f} mm (dN/dID = {dn_did:.1f} N/mm)"),
    )
    return SqueezeStage(main, sens, float(dn_did), float(need_id), comps)


# ----------------------------------------------------------------------------- stage 4


@dataclass(frozen=True)
class GammaStage:
    """gamma (Eq 7) from SYNTHETIC virtual-rig friction on the base squeeze curve (Fig 4).

    The rig plants ``gamma_true`` (the paper's 0.7168); recovering it checks the pipeline,
    not the paper. ``gamma_published_point`` = 180.49 N / our N(0.6 MPa) is the only gamma
    that rests on a measured number of the paper.
    """

    rig: RigRun
    fit: GammaFit
    gamma_true: float
    gamma_published_point: float
    gamma_paper_pair: float
    comparisons: tuple[Comparison, ...]
    synthetic: bool = field(default=True)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (unitless gamma, N, MPa, %)."""
        return {
            "synthetic": self.synthetic,
            "gamma": self.fit.gamma,
            "gamma_true": self.gamma_true,
            "gamma_published_point": self.gamma_published_point,
            "gamma_paper_pair": self.gamma_paper_pair,
            "fit": self.fit.to_dict(),
            "rig": self.rig.to_dict(),
            "comparisons": [c.to_dict() for c in self.comparisons],
        }


def stage_gamma(
    squeeze_result: SqueezeResult,
    *,
    gamma_true: float,
    set_points_mpa: np.ndarray,
    rig: RigConfig,
    seed: int,
) -> GammaStage:
    """Stage 4: fit gamma (Eq 7) to SYNTHETIC rig friction on our base N(P) (N, MPa).

    Parameters
    ----------
    squeeze_result : SqueezeResult
        Base squeeze curve.
    gamma_true : float
        The gamma planted in the virtual rig (unitless).
    set_points_mpa : ndarray
        Rig pressure set points (MPa) with N > 0.
    rig : RigConfig
        Virtual-rig settings (noise etc.).
    seed : int
        Rig seed.

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> p = np.linspace(0.1, 0.6, 11); curve = SimpleNamespace(pressure_mpa=p,
    ...     squeeze_force_n=800.0 * (p - 0.05) ** 2)
    >>> g = stage_gamma(curve, gamma_true=0.7, set_points_mpa=p[2:], rig=RigConfig(), seed=1)
    >>> abs(g.fit.gamma / 0.7 - 1) < 0.01
    True
    """
    p, n = squeeze_result.pressure_mpa, squeeze_result.squeeze_force_n
    run = simulate_rig(p, n, gamma_true, set_points_mpa, config=rig, seed=seed)
    fit = fit_gamma(run.pressure_mpa, run.friction_n, p, n)
    f_meas = paper.scalar("base_friction_at_0_6_mpa_n")
    n_paper = paper.scalar("base_squeeze_force_at_0_6_mpa_n")
    n06 = float(n[-1])
    g_pub = f_meas / n06
    g_pair = f_meas / n_paper
    comps = (
        Comparison("gamma (Eq 7)", "", paper.scalar("gamma"), fit.gamma,
                   f"SYNTHETIC: the rig planted gamma_true = {gamma_true:g}; agreement is by "
                   "construction", synthetic=True),
        Comparison("gamma relative error (Sec 3.5)", "%", paper.scalar("gamma_relative_error_pct"),
                   fit.relative_error_pct, "SYNTHETIC: mean |relative error| of the fit; rig "
                   f"noise {rig.noise_pct:g}% per sample", synthetic=True),
        Comparison("gamma from the published point, 180.49 N / N(0.6 MPa)", "",
                   paper.scalar("gamma"), g_pub,
                   f"paper's measured friction / our N; the paper's own pair gives "
                   f"180.49/268.55 = {g_pair:.4f}"),
        Comparison("predicted friction at 0.6 MPa, base (Fig 4)", "N", f_meas, fit.gamma * n06,
                   "gamma (synthetic fit) x our N(0.6 MPa)", synthetic=True),
    )
    return GammaStage(run, fit, float(gamma_true), g_pub, g_pair, comps)
