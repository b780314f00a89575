"""Stages 3-4 of ``exofric reproduce``: the base-group squeeze N(P) and gamma.

* Stage 3 (Figs 6-7): :func:`stage_squeeze` -- the FE squeeze of the base group and what moves
  N at 0.6 MPa (tube ID, the printed C10 slip, Shore, contact penalty).
* Stage 4 (Fig 4, Eq 7): :func:`stage_gamma` -- gamma fitted to SYNTHETIC virtual-rig friction
  on that curve, and the gamma implied by the paper's one published measured point.

Pure computation (no printing, no files); each stage returns a frozen result with
``to_dict()`` and its :class:`~exofric.reproduction.Comparison` rows. These names are
also importable from :mod:`exofric.reproduction`.

Units: mm, N, MPa; errors and differences in %.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from exofric import defaults, paper
from exofric._validate import checked_init
from exofric.fe import MeshSpec
from exofric.friction import GammaFit, RigConfig, RigRun, fit_gamma, simulate_rig
from exofric.geometry import Structure
from exofric.material import MooneyRivlin
from exofric.reproduction._compare import Comparison
from exofric.simulate import SqueezeResult, squeeze

__all__ = ["ID_STEP_MM", "SqueezeStage", "GammaStage", "stage_squeeze", "stage_gamma"]

#: Sensitivity step of the tube inner diameter (mm) for dN/dID in the squeeze discussion.
ID_STEP_MM = 0.05


# ----------------------------------------------------------------------------- stage 3


@checked_init
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
    dn_did_n_per_mm : float
        Sensitivity dN/dID of N(0.6 MPa) to the tube inner diameter (N/mm), central
        difference over +/- :data:`ID_STEP_MM`.
    id_to_match_paper_mm : float
        Tube ID (mm) at which N(0.6 MPa) would reach the paper's 268.55 N (linear in ID).
    comparisons : tuple of Comparison
        N at 0.6 MPa (N) beside the paper's Fig 7 value.

    Examples
    --------
    >>> s = fast_result.squeeze       # reproduce(ReproduceConfig.for_mode(fast=True)): coarse
    >>> round(s.n_at_max_n, 1), round(s.dn_did_n_per_mm, 1), round(s.id_to_match_paper_mm, 2)
    (239.8, 93.8, 5.27)
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
    >>> from exofric.fe import MeshSpec
    >>> m = MeshSpec(1, 12, grading=6.0)
    >>> s = stage_squeeze(BASE, MooneyRivlin.from_shore(62.5), np.array([0.3, 0.6]), mesh=m,
    ...                   sensitivity_mesh=m, slip_tube_id_mm=5.05)
    >>> round(s.n_at_max_n)
    241
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


    n0 = n_of(base, material)
    variants = [
        ("baseline (calibrated ID and Shore, Eq 4 constants)", n0),
        (f"tube ID - {ID_STEP_MM:g} mm", n_of(with_id(base.tube_id_mm - ID_STEP_MM), material)),
        (f"tube ID + {ID_STEP_MM:g} mm", n_of(with_id(base.tube_id_mm + ID_STEP_MM), material)),
        (f"printed Table 2 constants (C10 slip) with their ID {slip_tube_id_mm:.4f} mm",
         n_of(with_id(slip_tube_id_mm), printed)),
        ("Shore 62.5 exactly (the paper's)", n_of(base, MooneyRivlin.from_shore(62.5))),
        ("contact penalty / 10 (1e4 N/mm^3)",
         n_of(base, material, 0.1 * defaults.CONTACT_PENALTY_N_PER_MM3)),
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


@checked_init
@dataclass(frozen=True)
class GammaStage:
    """gamma (Eq 7) from SYNTHETIC virtual-rig friction on the base squeeze curve (Fig 4).

    The rig plants ``gamma_true`` (the paper's 0.7168); recovering it checks the pipeline,
    not the paper. ``gamma_published_point`` = 180.49 N / our N(0.6 MPa) is the only gamma
    that rests on a measured number of the paper.

    Attributes
    ----------
    rig : RigRun
        The SYNTHETIC virtual-rig test on the base curve (pressures in MPa, friction in N).
    fit : GammaFit
        gamma fitted to the rig friction (Eq 7), with its errors (%).
    gamma_true : float
        gamma planted in the rig (unitless), the paper's 0.7168.
    gamma_published_point : float
        The paper's measured 180.49 N over our N(0.6 MPa) (unitless).
    gamma_paper_pair : float
        The paper's own pair, 180.49 N / 268.55 N (unitless).
    comparisons : tuple of Comparison
        gamma (unitless), its relative error (%) and the friction at 0.6 MPa (N) beside
        the paper's.
    synthetic : bool
        Always True: the fitted gamma rests on virtual-rig data.

    Examples
    --------
    >>> g = fast_result.gamma         # reproduce(ReproduceConfig.for_mode(fast=True))
    >>> g.gamma_true, round(g.gamma_paper_pair, 4), round(g.fit.gamma, 4)
    (0.7168, 0.6721, 0.7173)
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
