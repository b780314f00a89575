"""The calibrate() entry point: pick a method, build the forward model, run, time it."""

from __future__ import annotations

import time
from collections.abc import Mapping
from typing import Any

import numpy as np

from exofric import defaults as D
from exofric.calibration._methods import Evaluator, bisection, bounded, joint, known_hardness
from exofric.calibration._models import (
    DEFAULT_MODEL,
    C10Convention,
    CachedModel,
    ModelFn,
    make_model,
    material_for,
)
from exofric.calibration._result import CalibrationResult, InflationData
from exofric.errors import InputError, check_positive, check_range

__all__ = ["METHODS", "calibrate"]

#: The calibration methods :func:`calibrate` accepts (``method=``): bisection on the hardness
#: (the paper's), a bounded 1-D minimisation, a joint hardness and tube-ID fit, or the tube ID
#: at a known hardness.
METHODS = ("bisection", "bounded", "joint", "known-hardness")


def _check_bracket(bracket: tuple[float, float]) -> tuple[float, float]:
    if len(bracket) != 2:
        raise InputError(f"bracket must be two Shore A values lo,hi, got {list(bracket)}")
    lo = check_range("bracket lo", bracket[0], 0.0, 100.0, lo_open=True, hi_open=True)
    hi = check_range("bracket hi", bracket[1], 0.0, 100.0, lo_open=True, hi_open=True)
    if not lo < hi:
        raise InputError(f"bracket must have lo < hi (Shore A), got {lo:g},{hi:g}")
    return lo, hi


def _joint_identifiable(shore: float | None, tube_id_mm: float, od: float,
                        corr: float | None, notes: list[str]) -> bool:
    """False (with a note saying what data would fix it) when the joint fit ends on a bound of
    its search (Shore 20-80, ID 2-98 % of the OD): the optimum is not in the data's reach.
    A correlation above 0.99 inside the bounds is weak identification (wide but valid standard
    errors; ``joint`` adds its note), not a failure."""
    from exofric.calibration._methods import JOINT_SHORE_BOUNDS

    at = []
    if shore is not None and min(abs(shore - b) for b in JOINT_SHORE_BOUNDS) < 0.05:
        at.append(f"Shore {shore:.3g} is at the search bound {JOINT_SHORE_BOUNDS}")
    if min(abs(tube_id_mm - f * od) for f in (0.02, 0.98)) < 1e-3 * od:
        at.append(f"the tube ID {tube_id_mm:.3g} mm is at its bound")
    if not at:
        return True
    high = f"; hardness and ID correlate at {corr:.4f}" if corr is not None and abs(corr) > 0.99 \
        else ""
    notes.append(f"not identifiable ({'; '.join(at)}{high}): inflation data alone cannot tell "
                 "a softer tube from a thinner wall. What fixes it: a measured tube ID "
                 "(--tube-id, then only the hardness is fitted) or a durometer reading (a shore "
                 "column: only the ID is fitted).")
    return False


def _as_data(data: object) -> InflationData:
    """``data`` as InflationData: itself, a mapping with ``pressure_mpa`` and
    ``outer_diameter_mm`` (and ``shore``) lists, or a DataFrame with those columns."""
    if isinstance(data, InflationData):
        return data
    if hasattr(data, "columns") and hasattr(data, "attrs"):
        return InflationData.from_frame(data)
    if isinstance(data, Mapping):
        extra = sorted(set(data) - {"pressure_mpa", "outer_diameter_mm", "shore"})
        if extra or not {"pressure_mpa", "outer_diameter_mm"} <= set(data):
            raise InputError("data as a mapping needs the keys pressure_mpa (MPa) and "
                             "outer_diameter_mm (mm), optionally shore; got "
                             f"{', '.join(sorted(map(str, data))) or 'none'}", param="data")
        return InflationData(**{k: data[k] for k in data})
    raise InputError("data must be InflationData (e.g. InflationData.paper_test(), "
                     "InflationData.from_frame(read_inflation_table(path))), a DataFrame or a "
                     f"mapping of lists, got {type(data).__name__}", param="data")


def calibrate(
    data: InflationData | Mapping[str, Any] | Any,
    tube_od_mm: float,
    *,
    tube_id_mm: float | None = None,
    method: str | None = None,
    fit_tube_id: bool = False,
    bracket: tuple[float, float] = (60.0, 70.0),
    tol_pct: float = 0.5,
    model: str | ModelFn = DEFAULT_MODEL,
    correlation: str = "paper",
    c01_ratio: float = 0.05,
    poisson: float = D.POISSON,
    c10_convention: C10Convention = "eq4",
    xtol: float = 0.01,
    ends: str = "plane-strain",
) -> CalibrationResult:
    """Identify Shore A hardness and/or tube inner diameter from inflation data.

    Parameters
    ----------
    data : InflationData, DataFrame or mapping
        Measured pressures (MPa) and outer diameters (mm); with a ``shore`` column
        the hardness is known and only the tube ID is fitted (``known-hardness``). A
        DataFrame or a mapping of lists with keys ``pressure_mpa``, ``outer_diameter_mm``
        (and ``shore``) is converted; anything else is an InputError.
    tube_od_mm : float
        Undeformed tube outer diameter (mm), e.g. 8.3.
    tube_id_mm : float, optional
        Tube inner diameter (mm): fixed for ``bisection``/``bounded``, the starting
        guess for ``joint``/``known-hardness`` (default 0.6 ``tube_od_mm``).
    method : {'bisection', 'bounded', 'joint', 'known-hardness'}, optional
        Default: ``known-hardness`` with a shore column, ``joint`` when
        ``fit_tube_id``, else ``bisection``.
    fit_tube_id : bool
        Fit the tube ID as well (``joint``).
    bracket : (float, float)
        Shore A bracket (default (60, 70), the paper's); ``joint`` starts at its middle.
    tol_pct : float
        Stopping criterion of the bisection: average absolute relative error (%).
    model : str or callable
        ``'fe'``, ``'1d'`` or ``'paper-table1'`` (see :func:`make_model`), or any
        ``model(shore, tube_id_mm, pressures_mpa) -> OD (mm)``; memoised.
    correlation, c01_ratio, poisson, c10_convention
        Material construction from hardness (Eqs 3-6; see :func:`material_for`).
    xtol : float
        Shore A resolution of ``bisection``/``bounded``.
    ends : {'plane-strain', 'closed', 'open'}
        Tube end condition of the ``'fe'`` model (the others are plane strain only: an
        InputError otherwise).

    Returns
    -------
    CalibrationResult

    Examples
    --------
    >>> r = calibrate(InflationData.paper_test(), 8.3, tube_id_mm=5.0, model="paper-table1",
    ...               method="bounded")
    >>> 62 < r.shore < 64
    True
    """
    t0 = time.perf_counter()
    data = _as_data(data)
    od = check_positive("tube_od_mm", tube_od_mm, "mm")
    tol = check_positive("tol_pct", tol_pct, "%")
    lo, hi = _check_bracket(tuple(bracket))  # type: ignore[arg-type]
    if tube_id_mm is not None:
        tid = check_positive("tube_id_mm", tube_id_mm, "mm")
        if tid >= od:
            raise InputError(f"tube_id_mm must be < tube_od_mm ({od:g} mm), got {tid:g}")
    known = data.shore is not None
    if method is None:
        method = "known-hardness" if known else ("joint" if fit_tube_id else "bisection")
    if method not in METHODS:
        raise InputError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    if known and method != "known-hardness":
        raise InputError(f"the data have a shore column (known hardness): only the tube ID can be "
                         f"fitted, so method must be 'known-hardness', got {method!r}")
    if method == "known-hardness" and not known:
        raise InputError("method 'known-hardness' needs a 'shore' column in the data")
    if method in ("bisection", "bounded"):
        if fit_tube_id:
            raise InputError(f"fit_tube_id needs method 'joint', got {method!r}")
        if tube_id_mm is None:
            raise InputError(f"method {method!r} needs tube_id_mm (mm) or fit_tube_id",
                             param="tube_id_mm")
    if ends != "plane-strain" and not isinstance(model, str):
        raise InputError(f"ends {ends!r} applies to the built-in 'fe' model, not to a model "
                         "you pass", param="ends")
    if isinstance(model, CachedModel):
        cm = model
    elif isinstance(model, str):
        cm = make_model(model, od, correlation=correlation, c01_ratio=c01_ratio, poisson=poisson,
                        c10_convention=c10_convention, ends=ends)
    else:
        cm = CachedModel(model, getattr(model, "__name__", "custom"))
    calls0 = cm.calls
    ev = Evaluator(cm, data)
    id0 = 0.6 * od if tube_id_mm is None else float(tube_id_mm)
    stderr_s = stderr_id = corr = None
    identifiable = True
    if method == "bisection":
        best, ok, notes = bisection(ev, id0, (lo, hi), tol, xtol=xtol)
    elif method == "bounded":
        best, ok, notes = bounded(ev, id0, (lo, hi), tol, xtol=xtol)
    elif method == "joint":
        fit = joint(ev, 0.5 * (lo + hi), id0, od)
        best, ok, notes = fit.trial, fit.converged, fit.notes
        stderr_s, stderr_id, corr = float(fit.stderr[0]), float(fit.stderr[1]), fit.corr
        identifiable = _joint_identifiable(best.shore, best.tube_id_mm, od, corr, notes)
        ok = ok and identifiable
    else:
        fit = known_hardness(ev, id0, od)
        best, ok, notes = fit.trial, fit.converged, fit.notes
        stderr_id = float(fit.stderr[0])
    shore = best.shore
    mat = None
    if shore is not None:
        mat = material_for(shore, correlation=correlation, c01_ratio=c01_ratio, poisson=poisson,
                           c10_convention=c10_convention)
    return CalibrationResult(
        method=method,
        model=cm.name,
        tube_od_mm=od,
        tube_id_mm=best.tube_id_mm,
        shore=shore,
        material=mat,
        data=data,
        simulated_mm=np.asarray(best.outer_diameter_mm, dtype=float),
        history=tuple(ev.history),
        converged=ok,
        notes=tuple(notes),
        tol_pct=tol,
        bracket=(lo, hi),
        shore_stderr=stderr_s,
        tube_id_stderr_mm=stderr_id,
        correlation=corr,
        identifiable=identifiable,
        n_model_calls=cm.calls - calls0,
        elapsed_s=time.perf_counter() - t0,
    )
