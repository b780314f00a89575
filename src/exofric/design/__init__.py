"""Design sweeps and search: which structures reach a target joint torque, solved on Dask.

* :func:`parse_sweep` -> :class:`SweepSpec` (grids or families of :class:`Design`, the
  :class:`MaterialSpec` and :class:`SolverSpec`) from a TOML/dict spec.
* :func:`run_sweep` -> :class:`SweepRun` -- every design's squeeze N(P) serially, on local
  worker processes (:class:`SweepPool`) or on any Dask scheduler, streamed to a resumable
  :class:`SweepStore` (Parquet, checksummed: damaged files are quarantined and solved again,
  :func:`verify_sweep` checks a folder); by default :func:`plan_execution` chooses serial or
  workers from the work size (:func:`estimate_design_time_s`, then measured solve times).
* :func:`search_designs` -> :class:`DesignSearch` -- torque at the maximum pressure, least
  pressure reaching the target, margins, the validated region.
* :func:`sweep_groups`, :func:`applicability` -- the dimensionless groups (P/G, c/d1, t/d1,
  d2/d1; response N/(P L d2)) and the distance from the calibration designs in them.
* :func:`fit_surrogate` -> :class:`SqueezeSurrogate` (N(P) over the groups, leave-one-out
  errors); :func:`surrogate_search` -> :class:`SurrogateSearch` explores thousands of
  candidates on it and confirms the best with the FE.

Units: mm, MPa, N, s; torque in Nm, arm radius in m, deviation in %.

Examples
--------
>>> from exofric.design import parse_sweep
>>> spec = parse_sweep({"pressures_mpa": [0.3, 0.6], "grid": {"hole_mm": [10.0, 11.0]}})
>>> len(spec.designs)
2
"""

from exofric.design._dimensionless import (
    APPLICABILITY_THRESHOLD,
    GROUP_SCALES,
    GROUPS,
    Applicability,
    applicability,
    dimensionless_groups,
    squeeze_number,
    sweep_groups,
)
from exofric.design._execution import (
    EXECUTORS,
    ExecutionPlan,
    SweepPool,
    check_scheduler,
    estimate_design_time_s,
    plan_execution,
)
from exofric.design._runner import BLAS_ENV, SweepRun, SweepSummary, run_sweep, solve_design, sweep
from exofric.design._search import (
    DEFAULT_SPACE,
    OBJECTIVES,
    DesignSearch,
    design_metrics,
    search_designs,
)
from exofric.design._spec import (
    Design,
    MaterialSpec,
    SolverSpec,
    SweepSpec,
    design_key,
    parse_sweep,
)
from exofric.design._store import (
    SCHEMA,
    STATUSES,
    SweepCheck,
    SweepStore,
    check_rows,
    load_sweep,
    verify_sweep,
)
from exofric.design._surrogate import (
    SqueezeSurrogate,
    SurrogateSearch,
    candidate_designs,
    fit_surrogate,
    surrogate_search,
)

__all__ = [
    "BLAS_ENV", "DEFAULT_SPACE", "Design", "design_key", "design_metrics", "DesignSearch",
    "estimate_design_time_s", "ExecutionPlan", "EXECUTORS", "load_sweep", "MaterialSpec",
    "OBJECTIVES", "parse_sweep", "plan_execution", "run_sweep", "SCHEMA", "search_designs",
    "solve_design", "SolverSpec", "STATUSES", "sweep", "SweepPool", "SweepRun", "SweepSpec",
    "SweepStore", "SweepSummary", "SweepCheck", "check_rows", "verify_sweep",
    "check_scheduler", "APPLICABILITY_THRESHOLD", "GROUP_SCALES", "GROUPS", "Applicability",
    "applicability", "dimensionless_groups", "squeeze_number", "sweep_groups",
    "SqueezeSurrogate", "SurrogateSearch", "candidate_designs", "fit_surrogate",
    "surrogate_search",
]

# every public function checks its arguments' kinds (InputError naming the parameter)
from exofric._lazy import export_checked  # noqa: E402

export_checked(__name__)
