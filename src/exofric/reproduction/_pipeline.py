"""``exofric reproduce``: the paper's whole study redone, with every number beside the paper's.

:func:`reproduce` runs eight stages in order and returns a frozen :class:`ReproduceResult`;
:mod:`exofric.report` turns it into ``report.html``, figures and ``results.json``. Pure
computation: no printing, no files. This module holds the configuration, the pipeline and its
result; the stages live in :mod:`exofric.reproduction` (1-2),
:mod:`exofric.reproduction` (3-4), :mod:`exofric.reproduction` (5, 8) and
:mod:`exofric.reproduction` (6-7), the comparison rows and :func:`paper_checks` in
:mod:`exofric.reproduction`; the stage names of 5-8 and :func:`paper_checks` are
importable from here too.

1. Table 2 from Eqs 3-6 (with the printed C10 slip).
2. Calibration (Table 1, Fig 5b): tube ID from the paper's ANSYS columns, Shore from the test.
3. Base squeeze N(P) (Figs 6-7) and what moves N(0.6 MPa).
4. gamma (Eq 7, Fig 4) from SYNTHETIC virtual-rig friction.
5. Prediction for the seven Table 3 structures (Figs 8-10), deviation metrics, ANOVA (Table 4).
6. Cubic fit for test 5 (Eq 8, Fig 11) and the inverse for 54.40 N.
7. Control (Fig 12): six cases, settling times.
8. Torque at 0.6 MPa per structure against the knee's 0-40 Nm.

Units: mm, N, MPa, s, Nm; differences in %.

Examples
--------
>>> cfg = ReproduceConfig.for_mode(fast=True)
>>> cfg.squeeze_mesh.n_circ, cfg.pressures_mpa[-1]
(12, 0.6)
"""

from __future__ import annotations

import platform
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from exofric import defaults, paper
from exofric._display import DisplayMixin
from exofric._validate import checked_init
from exofric._version import __version__
from exofric.fe import MeshSpec
from exofric.friction import RigConfig
from exofric.geometry import Structure
from exofric.material import MooneyRivlin
from exofric.reproduction._compare import Comparison, paper_checks
from exofric.reproduction._control import ControlStage, CubicStage, stage_control, stage_cubic
from exofric.reproduction._predict import (
    PredictionStage,
    TorqueStage,
    _rig_points,
    stage_prediction,
    stage_torque,
)
from exofric.reproduction._stages import (
    CalibrationStage,
    GammaStage,
    SqueezeStage,
    Table2Stage,
    stage_calibration,
    stage_gamma,
    stage_squeeze,
    stage_table2,
)

__all__ = ["ReproduceConfig", "ReproduceResult", "StageTime", "STAGES", "reproduce",
           "software_versions", "paper_checks", "FAST_SQUEEZE_MESH", "FAST_INFLATION_MESH"]

#: Coarse meshes of ``--fast`` (CI): N(0.6 MPa) within 0.1% of the default mesh's.
FAST_SQUEEZE_MESH = MeshSpec(n_radial=1, n_circ=12, grading=6.0)


def _level_mesh(level: str) -> MeshSpec:
    """The mesh whose N an accuracy level returns (``exofric squeeze --accuracy level``).

    The report solves on the ``draft`` level's mesh, so its N(P) is the one ``exofric squeeze
    --accuracy draft`` prints, and the report names that level (issue 34: it said "converged
    meshes" on a mesh no level used).

    Parameters
    ----------
    level : {'draft', 'standard', 'fine'}
        A key of :data:`exofric.defaults.SQUEEZE_ACCURACY`.

    Returns
    -------
    MeshSpec

    Examples
    --------
    >>> m = _level_mesh("draft")
    >>> m.n_radial, m.n_circ
    (2, 24)
    """
    spec = {k: v for k, v in defaults.SQUEEZE_ACCURACY[level].items() if k != "coarsen"}
    return MeshSpec(**spec)
#: The inflation mesh of ``--fast`` (CI), coarse as :data:`FAST_SQUEEZE_MESH`.
FAST_INFLATION_MESH = MeshSpec(n_radial=1, n_circ=4)

#: (key, title) of each stage, in order.
STAGES: tuple[tuple[str, str], ...] = (
    ("table2", "Table 2: material parameters (Eqs 3-6)"),
    ("calibration", "Calibration: tube ID and Shore (Table 1, Fig 5b)"),
    ("squeeze", "Base-group squeeze N(P) (Figs 6-7)"),
    ("gamma", "Equivalent coefficient gamma (Eq 7, Fig 4)"),
    ("prediction", "Prediction for Table 3 structures, ANOVA (Figs 8-10, Table 4)"),
    ("cubic", "Cubic fit for test 5 and the inverse (Eq 8, Fig 11)"),
    ("control", "Friction control (Fig 12)"),
    ("torque", "Torque at 0.6 MPa vs the knee's 0-40 Nm"),
)

#: ``on_stage(key, title, index, total, finished, wall_time_s)`` progress callback.
StageCallback = Callable[[str, str, int, int, bool, float | None], None]


@checked_init
@dataclass(frozen=True)
class ReproduceConfig:
    """Settings of a reproduction run (mm, MPa, s).

    Attributes
    ----------
    fast : bool
        Coarse meshes for CI (``--fast``).
    squeeze_mesh, inflation_mesh : MeshSpec
        Main squeeze and free-inflation meshes (default: the converged ones of
        :mod:`exofric.simulate`).
    sensitivity_mesh : MeshSpec
        Mesh of the N(0.6 MPa) sensitivity solves (differences only).
    pressures_mpa : tuple of float
        Squeeze pressures (MPa), 0.05 to 0.6.
    rig_pressures_mpa : tuple of float
        Virtual-rig set points (MPa), 0.2 to 0.6 (only those with N > 0 are used).
    gamma_true : float
        gamma planted in the virtual rig for every structure (the paper's 0.7168).
    rig : RigConfig
        Virtual-rig settings (2% load-cell noise by default).
    seed : int
        Rig seed of the base group; test k uses ``seed + k``.
    target_friction_n : float
        The Section 5 target (N).
    arm_radius_m : float
        Lever arm for the torque (m).

    Examples
    --------
    >>> cfg = ReproduceConfig()              # the draft accuracy's mesh, the paper's numbers
    >>> cfg.fast, cfg.gamma_true, cfg.target_friction_n, cfg.arm_radius_m
    (False, 0.7168, 54.4, 0.1)
    >>> cfg.pressures_mpa[0], cfg.rig_pressures_mpa[0]   # MPa
    (0.05, 0.2)
    """

    fast: bool = False
    squeeze_mesh: MeshSpec = field(default_factory=lambda: _level_mesh("draft"))
    inflation_mesh: MeshSpec = MeshSpec(**defaults.INFLATION_MESH)
    sensitivity_mesh: MeshSpec = FAST_SQUEEZE_MESH
    pressures_mpa: tuple[float, ...] = tuple(round(0.05 * i, 10) for i in range(1, 13))
    rig_pressures_mpa: tuple[float, ...] = tuple(round(0.2 + 0.05 * i, 10) for i in range(9))
    gamma_true: float = field(default_factory=lambda: paper.scalar("gamma"))
    rig: RigConfig = field(default_factory=RigConfig)
    seed: int = 0
    target_friction_n: float = field(default_factory=lambda: paper.scalar("target_friction_n"))
    arm_radius_m: float = field(default_factory=lambda: paper.scalar("arm_radius_m"))

    @classmethod
    def for_mode(cls, fast: bool = False) -> ReproduceConfig:
        """Default (the draft accuracy's squeeze mesh) or ``fast`` (coarse meshes) configuration.

        Parameters
        ----------
        fast : bool
            Use :data:`FAST_SQUEEZE_MESH` and :data:`FAST_INFLATION_MESH` (``--fast``, CI)
            instead of the draft accuracy's squeeze mesh and the inflation mesh of
            :mod:`exofric.defaults`.

        Returns
        -------
        ReproduceConfig

        Examples
        --------
        >>> ReproduceConfig.for_mode(fast=True).inflation_mesh.n_circ
        4
        """
        if fast:
            return cls(True, FAST_SQUEEZE_MESH, FAST_INFLATION_MESH, FAST_SQUEEZE_MESH)
        return cls()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (MPa, N, m)."""
        return {
            "fast": self.fast,
            "squeeze_mesh": self.squeeze_mesh.to_dict(),
            "inflation_mesh": self.inflation_mesh.to_dict(),
            "sensitivity_mesh": self.sensitivity_mesh.to_dict(),
            "pressures_mpa": list(self.pressures_mpa),
            "rig_pressures_mpa": list(self.rig_pressures_mpa),
            "gamma_true": self.gamma_true,
            "rig": self.rig.to_dict(),
            "seed": self.seed,
            "target_friction_n": self.target_friction_n,
            "arm_radius_m": self.arm_radius_m,
        }


# ----------------------------------------------------------------------------- pipeline


@checked_init
@dataclass(frozen=True)
class StageTime:
    """Wall time (s) of one stage.

    Attributes
    ----------
    key : str
        Stage key (see :data:`STAGES`), e.g. ``"table2"``.
    title : str
        Stage title.
    wall_time_s : float
        Wall-clock time of the stage (s).

    Examples
    --------
    >>> StageTime("table2", "Table 2", 0.01).to_dict()
    {'key': 'table2', 'title': 'Table 2', 'wall_time_s': 0.01}
    """

    key: str
    title: str
    wall_time_s: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (s)."""
        return {"key": self.key, "title": self.title, "wall_time_s": self.wall_time_s}


@checked_init
@dataclass(frozen=True)
class ReproduceResult(DisplayMixin):
    """Everything :func:`reproduce` computed, stage by stage, with timings and versions.

    Attributes
    ----------
    config : ReproduceConfig
        The settings of the run (meshes, pressures in MPa, target in N, arm in m).
    table2 : Table2Stage
        Stage 1, Table 2 from Eqs 3-6 (MPa, 1/MPa).
    calibration : CalibrationStage
        Stage 2, tube ID (mm) and Shore (Shore A) from Table 1.
    squeeze : SqueezeStage
        Stage 3, base-group N(P) (N vs MPa) and its sensitivity.
    gamma : GammaStage
        Stage 4, gamma (Eq 7; unitless) from SYNTHETIC rig friction.
    prediction : PredictionStage
        Stage 5, predictions (N) for the Table 3 structures and the ANOVA.
    cubic : CubicStage
        Stage 6, cubic fit of test 5 and the pressures (MPa) for the target.
    control : ControlStage
        Stage 7, the Fig 12 control cases (s, N).
    torque : TorqueStage
        Stage 8, torque (Nm) at 0.6 MPa per structure.
    stage_times : tuple of StageTime
        Wall time of each stage (s), in stage order.
    versions : dict of str to str
        :func:`software_versions` of the run.
    wall_time_s : float
        Wall time of the whole run (s).
    paper_checks : tuple of Comparison
        :func:`paper_checks`: the paper's numbers against its own equations (units per row).

    Examples
    --------
    >>> r = fast_result             # = reproduce(ReproduceConfig.for_mode(fast=True))
    >>> r.config.fast, list(r.stages())[:3], len(r.paper_checks)
    (True, ['table2', 'calibration', 'squeeze'], 7)
    >>> stage, row = r.comparisons()[0]
    >>> stage, row.unit
    ('table2', '')
    """

    config: ReproduceConfig
    table2: Table2Stage
    calibration: CalibrationStage
    squeeze: SqueezeStage
    gamma: GammaStage
    prediction: PredictionStage
    cubic: CubicStage
    control: ControlStage
    torque: TorqueStage
    stage_times: tuple[StageTime, ...]
    versions: dict[str, str]
    wall_time_s: float
    paper_checks: tuple[Comparison, ...] = ()

    def stages(self) -> dict[str, Any]:
        """Stage results by key, in order."""
        return {k: getattr(self, k) for k, _ in STAGES}

    def comparisons(self) -> list[tuple[str, Comparison]]:
        """All (stage key, comparison) rows, in stage order."""
        return [(k, c) for k, s in self.stages().items() for c in s.comparisons]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: config, every stage, all comparisons, timings (s), versions."""
        return {
            "exofric_version": self.versions.get("exofric", __version__),
            "config": self.config.to_dict(),
            "stages": {k: s.to_dict() for k, s in self.stages().items()},
            "comparisons": [{"stage": k, **c.to_dict()} for k, c in self.comparisons()],
            "paper_checks": [c.to_dict() for c in self.paper_checks],
            "stage_times": [t.to_dict() for t in self.stage_times],
            "wall_time_s": self.wall_time_s,
            "versions": dict(self.versions),
        }


def software_versions() -> dict[str, str]:
    """Versions of Python, exofric and the numerical libraries used.

    Examples
    --------
    >>> sorted(software_versions())[:3]
    ['control', 'exofric', 'matplotlib']
    """
    from importlib.metadata import PackageNotFoundError, version

    out = {"exofric": __version__, "python": platform.python_version(),
           "platform": platform.platform()}
    for dist in ("numpy", "scipy", "scikit-fem", "matplotlib", "control", "pandas", "rich"):
        try:
            out[dist] = version(dist)
        except PackageNotFoundError:
            out[dist] = "not installed"
    return out


def reproduce(
    config: ReproduceConfig | None = None, on_stage: StageCallback | None = None
) -> ReproduceResult:
    """Run the paper's study (stages 1-8) and return every number beside the paper's.

    Parameters
    ----------
    config : ReproduceConfig, optional
        Default: the draft accuracy's squeeze mesh (:meth:`ReproduceConfig.for_mode`).
    on_stage : callable, optional
        Progress callback ``(key, title, index, total, finished, wall_time_s)``, called
        before (``finished=False``) and after each stage.

    Returns
    -------
    ReproduceResult

    Examples
    --------
    >>> r = fast_result             # = reproduce(ReproduceConfig.for_mode(fast=True))
    >>> round(r.cubic.inverse["eq9_mpa"], 3), len(r.stage_times)
    (0.293, 8)
    """
    cfg = config or ReproduceConfig()
    times: list[StageTime] = []
    out: dict[str, Any] = {}
    t_all = time.perf_counter()
    p = np.asarray(cfg.pressures_mpa, dtype=float)

    def run(key: str, fn: Callable[[], Any]) -> Any:
        idx = [k for k, _ in STAGES].index(key)
        title = STAGES[idx][1]
        if on_stage:
            on_stage(key, title, idx, len(STAGES), False, None)
        t0 = time.perf_counter()
        res = fn()
        dt = time.perf_counter() - t0
        times.append(StageTime(key, title, dt))
        if on_stage:
            on_stage(key, title, idx, len(STAGES), True, dt)
        out[key] = res
        return res

    run("table2", stage_table2)
    cal: CalibrationStage = run("calibration", lambda: stage_calibration(cfg.inflation_mesh))
    mat = MooneyRivlin.from_shore(cal.shore)
    t1 = paper.table3()[0]
    base = Structure(float(t1["hole_mm"]), cal.tube_od_mm, cal.tube_id_mm, float(t1["wire_mm"]),
                     paper.scalar("tube_length_mm"), "test 1")
    sq: SqueezeStage = run("squeeze", lambda: stage_squeeze(
        base, mat, p, mesh=cfg.squeeze_mesh, sensitivity_mesh=cfg.sensitivity_mesh,
        slip_tube_id_mm=cal.id_fit_slip.tube_id_mm))
    gm: GammaStage = run("gamma", lambda: stage_gamma(
        sq.result, gamma_true=cfg.gamma_true,
        set_points_mpa=_rig_points(sq.result, cfg.rig_pressures_mpa), rig=cfg.rig,
        seed=cfg.seed))
    pr: PredictionStage = run("prediction", lambda: stage_prediction(sq.result, gm, mat, cfg))
    t5 = next(s for s in pr.squeezes if s.structure.name == "test 5")
    run("cubic", lambda: stage_cubic(t5, gm.fit.gamma, cfg.target_friction_n))
    run("control", lambda: stage_control(t5, gm.fit.gamma, cfg.target_friction_n))
    run("torque", lambda: stage_torque(pr, cfg.arm_radius_m))
    return ReproduceResult(config=cfg, stage_times=tuple(times), versions=software_versions(),
                           wall_time_s=time.perf_counter() - t_all, paper_checks=paper_checks(),
                           **out)
