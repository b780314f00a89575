"""Calibration methods: bisection (the paper's), bounded minimisation, joint least squares.

Each method takes validated :class:`~exofric.calibration.InflationData`, a
(memoised) forward model ``model(shore, tube_id_mm, pressures_mpa) -> OD (mm)``
and returns a :class:`~exofric.calibration.CalibrationResult`.

* :func:`bisection`: the paper's §3.3 procedure. The trial hardnesses are the
  bracket ends and its midpoint first (the paper's 60, 65, 70), then midpoints of
  the half-bracket where the *mean signed* relative diameter error changes sign
  (simulated diameters above the measured ones = material too soft), until the
  *average absolute* error drops below ``tol_pct`` (the paper's 0.5%).
* :func:`bounded`: minimise the average absolute error over the bracket
  (``scipy.optimize.minimize_scalar(method="bounded")``).
* :func:`joint`: Shore hardness and tube inner diameter together by nonlinear
  least squares on the relative errors (``scipy.optimize.least_squares``), with
  standard errors ``sqrt(diag((J^T J)^-1 s^2))`` and their correlation.
* :func:`known_hardness`: each point's hardness is given; fit only the tube ID.

A trial at which the model fails (pressure above the tube's limit pressure, no
convergence) counts as infinitely soft: average error ``inf``, and it is kept
in the history with the model's message.

Units: mm, MPa, errors in %.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.optimize import least_squares, minimize_scalar

from exofric._lsq import correlation, lsq_covariance, residual_variance, standard_errors
from exofric.calibration._result import InflationData, Trial, relative_errors_pct
from exofric.errors import ConvergenceError, InputError

__all__ = ["Evaluator", "bisection", "bounded", "joint", "known_hardness", "Fit"]

ModelFn = Callable[[float, float, np.ndarray], np.ndarray]
_FAILED_RESIDUAL = 10.0  # relative residual (1000%) given to a failed trial in least squares


class Evaluator:
    """Runs trials of one calibration: simulates the data points, records the history.

    Parameters
    ----------
    model : callable
        ``model(shore, tube_id_mm, pressures_mpa) -> OD (mm)``, ideally memoised.
    data : InflationData
        Measured points; with a ``shore`` column, its values override ``shore``.

    Examples
    --------
    >>> from exofric.calibration import paper_table1_model
    >>> ev = Evaluator(paper_table1_model(), InflationData.paper_test())
    >>> t = ev.trial(62.5, 4.97)
    >>> round(t.average_error_pct, 2), len(ev.history)
    (0.46, 1)
    """

    def __init__(self, model: ModelFn, data: InflationData) -> None:
        self.model = model
        self.data = data
        self.history: list[Trial] = []
        self.failures: list[Exception] = []
        self._seen: dict[tuple[float | None, float], Trial] = {}

    def simulate(self, shore: float | None, tube_id_mm: float) -> np.ndarray:
        """Model outer diameters (mm) at the data points (may raise the model's errors).

        Parameters
        ----------
        shore : float or None
            Trial Shore A hardness, in (0, 100); None only when the data have a ``shore``
            column (its per-point values are used).
        tube_id_mm : float
            Trial tube inner diameter (mm), below the outer diameter.

        Returns
        -------
        numpy.ndarray
            Outer diameters (mm), one per data point.
        """
        d = self.data
        out = np.empty(len(d))
        for g, idx in d.groups():  # loop over hardness groups (a handful), not points
            s = g if g is not None else shore
            if s is None:
                raise InputError("shore is required when the data have no shore column")
            out[idx] = self.model(s, tube_id_mm, d.pressure_mpa[idx])
        return out

    def trial(self, shore: float | None, tube_id_mm: float) -> Trial:
        """Evaluate (or recall) one trial and add it to the history once.

        A model failure (:class:`InputError`, :class:`ConvergenceError`) gives a trial with
        infinite errors and a note instead of raising.

        Parameters
        ----------
        shore : float or None
            Trial Shore A hardness, in (0, 100); None when the data carry a ``shore`` column.
        tube_id_mm : float
            Trial tube inner diameter (mm).

        Returns
        -------
        Trial
        """
        key = (None if shore is None else float(shore), float(tube_id_mm))
        if key in self._seen:
            return self._seen[key]
        try:
            sim = self.simulate(shore, tube_id_mm)
            r = relative_errors_pct(sim, self.data.outer_diameter_mm)
            t = Trial(key[0], key[1], float(np.mean(np.abs(r))), float(np.mean(r)),
                      float(np.max(np.abs(r))), tuple(sim.tolist()))
        except (InputError, ConvergenceError) as exc:
            self.failures.append(exc)
            nan = (float("nan"),) * len(self.data)
            t = Trial(key[0], key[1], float("inf"), float("inf"), float("inf"), nan,
                      note=f"model failed: {exc}")
        self._seen[key] = t
        self.history.append(t)
        return t

    def raise_if_all_failed(self, bracket: tuple[float, float] | None = None) -> None:
        """Raise if no trial succeeded: the first model failure, or a message about ``bracket``.

        When the model failed at every hardness of a Shore ``bracket``, up to its upper edge,
        because the tube inflates without bound (pressure beyond its limit pressure) or does
        not converge, the tube is too soft throughout: the message says that the hardness lies
        above the bracket and to widen it upward, instead of blaming the data's pressures.

        Parameters
        ----------
        bracket : (float, float) or None
            The Shore A bracket (lo, hi) searched, or None (re-raise the first failure).

        Raises
        ------
        InputError
            About ``bracket``, or the first failure itself.
        ConvergenceError
            The first failure, when it was one and no bracket explains it.
        """
        if not (self.failures and all(not np.isfinite(t.average_error_pct)
                                      for t in self.history)):
            return
        first = self.failures[0]
        if bracket is not None:
            lo, hi = bracket
            soft = [f for f in self.failures
                    if isinstance(f, ConvergenceError) or "limit pressure" in str(f)]
            if len(soft) == len(self.failures):
                raise InputError(
                    f"bracket [{lo:g}, {hi:g}] lies below the hardness: at every trial Shore up "
                    f"to its upper edge {hi:g} the tube is too soft to hold the data's pressures "
                    f"(up to {float(np.max(self.data.pressure_mpa)):g} MPa; it inflates without "
                    f"bound), so the best value is above {hi:g}: widen the bracket upward",
                    param="bracket") from None
        raise first


def bisection(
    ev: Evaluator,
    tube_id_mm: float,
    bracket: tuple[float, float] = (60.0, 70.0),
    tol_pct: float = 0.5,
    *,
    xtol: float = 0.01,
    max_iter: int = 40,
) -> tuple[Trial, bool, list[str]]:
    """The paper's bisection on Shore hardness at a fixed tube ID (mm).

    Evaluates ``lo, (lo+hi)/2, hi``; stops if the best has average error < ``tol_pct``
    (%). Otherwise bisects the half-bracket where the mean signed error changes
    sign, stopping at the first midpoint below ``tol_pct`` or when the bracket is
    narrower than ``xtol`` (Shore A); then the last midpoint (where the signed error
    changes sign) is returned with ``converged=False`` and a note. Returns (chosen
    trial, converged, notes).

    Parameters
    ----------
    ev : Evaluator
        The data and model; every trial lands in ``ev.history``.
    tube_id_mm : float
        Fixed tube inner diameter (mm).
    bracket : tuple of float
        Shore A hardness range ``(lo, hi)``, ``0 < lo < hi < 100`` (paper: 60, 70).
    tol_pct : float
        Stop when the average absolute diameter error is below it (%), > 0 (paper: 0.5).
    xtol : float
        Stop when the bracket is narrower than this (Shore A), > 0.
    max_iter : int
        Largest number of bisection steps.

    Returns
    -------
    trial : Trial
    converged : bool
    notes : list of str

    Examples
    --------
    >>> from exofric.calibration import paper_table1_model
    >>> ev = Evaluator(paper_table1_model(), InflationData.paper_test())
    >>> t, ok, _ = bisection(ev, 5.0)
    >>> [h.shore for h in ev.history], t.shore
    ([60.0, 65.0, 70.0, 62.5], 62.5)
    """
    lo, hi = bracket
    mid = 0.5 * (lo + hi)
    first = [ev.trial(s, tube_id_mm) for s in (lo, mid, hi)]
    ev.raise_if_all_failed((lo, hi))
    best = min(first, key=lambda t: t.average_error_pct)
    if best.average_error_pct < tol_pct:
        return best, True, []
    sgn = [np.sign(t.mean_signed_error_pct) for t in first]
    if sgn[0] * sgn[1] <= 0:
        a, b, sa = lo, mid, sgn[0]
    elif sgn[1] * sgn[2] <= 0:
        a, b, sa = mid, hi, sgn[1]
    else:
        # simulated diameters above the measured ones everywhere: too soft even at the upper
        # edge, so the hardness is above the bracket; below them: too stiff even at the lower
        # edge, the hardness is below it
        if sgn[0] > 0:
            side, edge, way = "above", f"upper edge {hi:g}", "upward (raise its upper end)"
            where = f"above {hi:g}"
        else:
            side, edge, way = "below", f"lower edge {lo:g}", "downward (lower its lower end)"
            where = f"below {lo:g}"
        raise InputError(
            f"bracket [{lo:g}, {hi:g}] does not contain the hardness: simulated diameters are "
            f"{side} the measured ones at both ends, so the best value lies at the bracket's "
            f"{edge} or beyond (hardness {where}); widen the bracket {way}",
            param="bracket")
    t = first[1]
    for _ in range(max_iter):
        if b - a <= xtol:
            break
        m = 0.5 * (a + b)
        t = ev.trial(m, tube_id_mm)
        if t.average_error_pct < tol_pct:
            return t, True, []
        s = np.sign(t.mean_signed_error_pct)
        if s == 0:
            break
        if s == sa:
            a = m
        else:
            b = m
    best = min(ev.history, key=lambda h: h.average_error_pct)
    return t, False, [
        f"average error never fell below {tol_pct:g}%: the bracket closed at Shore "
        f"{t.shore:.4g}, where the mean signed error changes sign (average error "
        f"{t.average_error_pct:.3g}%); the lowest average error seen was "
        f"{best.average_error_pct:.3g}% at Shore {best.shore:.4g}"
    ]


def bounded(
    ev: Evaluator,
    tube_id_mm: float,
    bracket: tuple[float, float] = (60.0, 70.0),
    tol_pct: float = 0.5,
    *,
    xtol: float = 0.01,
    max_iter: int = 60,
) -> tuple[Trial, bool, list[str]]:
    """Minimise the average error (%) over the Shore bracket at a fixed tube ID (mm).

    Uses ``scipy.optimize.minimize_scalar(method="bounded")`` (Brent, derivative
    free, so the kinks of the absolute errors are harmless). Returns (best trial,
    converged, notes); ``tol_pct`` only adds a note when it is not met.

    Parameters
    ----------
    ev : Evaluator
        The data and model; every trial lands in ``ev.history``.
    tube_id_mm : float
        Fixed tube inner diameter (mm).
    bracket : tuple of float
        Shore A hardness range ``(lo, hi)``, ``0 < lo < hi < 100``.
    tol_pct : float
        Average error (%) above which a note is added.
    xtol : float
        Absolute tolerance on the hardness (Shore A), > 0.
    max_iter : int
        Largest number of function evaluations of the minimiser.

    Returns
    -------
    trial : Trial
    converged : bool
    notes : list of str

    Examples
    --------
    >>> from exofric.calibration import paper_table1_model
    >>> ev = Evaluator(paper_table1_model(), InflationData.paper_test())
    >>> t, ok, notes = bounded(ev, 4.97)
    >>> round(t.shore, 1), ok
    (63.9, True)
    """
    lo, hi = bracket

    def f(s: float) -> float:
        e = ev.trial(float(s), tube_id_mm).average_error_pct
        return e if np.isfinite(e) else 1e6

    res = minimize_scalar(f, bounds=(lo, hi), method="bounded",
                          options={"xatol": xtol, "maxiter": max_iter})
    ev.raise_if_all_failed((lo, hi))
    t = ev.trial(float(res.x), tube_id_mm)
    notes = []
    if min(t.shore - lo, hi - t.shore) <= 2 * xtol:  # type: ignore[operator]
        low = t.shore - lo <= hi - t.shore  # type: ignore[operator]
        edge, way = (f"lower edge {lo:g}", "downward") if low else (f"upper edge {hi:g}",
                                                                   "upward")
        notes.append(f"the lowest average error is at the bracket's {edge} (Shore "
                     f"{t.shore:.4g}): the hardness may lie {'below' if low else 'above'} "
                     f"[{lo:g}, {hi:g}]; widen the bracket {way}")
    if t.average_error_pct >= tol_pct:
        notes.append(f"best average error {t.average_error_pct:.3g}% is not below {tol_pct:g}%")
    return t, bool(res.success), notes


class Fit:
    """Outcome of a least-squares fit: best trial, parameters, covariance summary.

    Parameters
    ----------
    trial : Trial
        The trial at the optimum.
    x : numpy.ndarray
        Fitted parameters in the fit's order (``joint``: Shore A, tube ID in mm;
        ``known_hardness``: tube ID in mm).
    stderr : numpy.ndarray
        Their standard errors, same units as ``x``.
    corr : float or None
        Correlation of the two parameters of a two-parameter fit (unitless, in [-1, 1]).
    converged : bool
        Whether the least-squares solver reported success.
    notes : list of str
        Caveats (bounds reached, parameters not separable).

    Examples
    --------
    >>> import numpy as np
    >>> t = Trial(62.5, 4.97, 0.2, 0.1, 0.4, (8.5, 8.8))
    >>> Fit(t, np.array([4.97]), np.array([0.01]), None, True, []).x.tolist()
    [4.97]
    """

    def __init__(self, trial: Trial, x: np.ndarray, stderr: np.ndarray, corr: float | None,
                 converged: bool, notes: list[str]) -> None:
        self.trial, self.x, self.stderr, self.corr = trial, x, stderr, corr
        self.converged, self.notes = converged, notes


def _least_squares(
    ev: Evaluator,
    unpack: Callable[[np.ndarray], tuple[float | None, float]],
    x0: np.ndarray,
    lo: np.ndarray,
    hi: np.ndarray,
    steps: np.ndarray,
    max_nfev: int,
    names: tuple[str, ...],
) -> Fit:
    meas = ev.data.outer_diameter_mm

    def fun(x: np.ndarray) -> np.ndarray:
        t = ev.trial(*unpack(x))
        if not np.isfinite(t.average_error_pct):
            return np.full(meas.size, _FAILED_RESIDUAL)
        return np.asarray(t.outer_diameter_mm) / meas - 1.0

    def jac(x: np.ndarray) -> np.ndarray:
        # forward differences with fixed absolute steps, turned back at an upper bound;
        # the probes go through the memoised model but are not trials of the history
        f0 = fun(x)
        J = np.empty((meas.size, x.size))
        for k in range(x.size):  # one column per parameter (1 or 2)
            h = steps[k] if x[k] + steps[k] <= hi[k] else -steps[k]
            xk = x.copy()
            xk[k] += h
            try:
                fk = ev.simulate(*unpack(xk)) / meas - 1.0
            except (InputError, ConvergenceError) as exc:
                raise ConvergenceError(
                    f"model failed in a Jacobian probe at {xk.tolist()}: {exc}"
                ) from exc
            J[:, k] = (fk - f0) / h
        return J

    f_start = fun(x0)
    ev.raise_if_all_failed()
    if np.all(f_start == _FAILED_RESIDUAL):
        raise ev.failures[0]
    res = least_squares(fun, x0, jac=jac, bounds=(lo, hi), method="trf", x_scale="jac",
                        ftol=1e-10, xtol=1e-8, gtol=1e-10, max_nfev=max_nfev)
    t = ev.trial(*unpack(res.x))
    J = jac(res.x)
    n, p = J.shape
    notes: list[str] = []
    jtj_inv = lsq_covariance(J)
    stderr = standard_errors(jtj_inv * residual_variance(res.fun, p))    # NaN without dof
    if n <= p:
        notes.append(f"{n} points for {p} parameters: no degrees of freedom for standard errors")
    corr = float(correlation(jtj_inv)[0, 1]) if p == 2 else None
    if res.status <= 0:
        notes.append(f"least squares stopped before converging ({res.message})")
    for k in range(p):
        if min(res.x[k] - lo[k], hi[k] - res.x[k]) <= 1e-6 * (hi[k] - lo[k]):
            notes.append(
                f"{names[k]} stopped at its bound {res.x[k]:.4g} (allowed [{lo[k]:.4g}, "
                f"{hi[k]:.4g}]): the least-squares optimum lies beyond it, so the standard "
                "errors are only indicative"
            )
    return Fit(t, res.x, stderr, corr, res.status > 0, notes)


#: Hardness range (Shore A) the joint fit searches: the Shore A scale's useful part for rubber.
JOINT_SHORE_BOUNDS: tuple[float, float] = (20.0, 80.0)


def joint(
    ev: Evaluator,
    shore0: float,
    tube_id0_mm: float,
    tube_od_mm: float,
    *,
    shore_bounds: tuple[float, float] = JOINT_SHORE_BOUNDS,
    steps: tuple[float, float] = (0.01, 0.001),
    max_nfev: int = 60,
) -> Fit:
    """Fit Shore hardness and tube inner diameter (mm) together by least squares.

    Residuals are the relative diameter errors ``sim/meas - 1``; standard errors
    are ``sqrt(diag((J^T J)^-1) s^2)`` with ``s^2 = |r|^2/(n - 2)`` and ``J`` by
    forward differences (steps 0.01 Shore, 0.001 mm). When ``|corr| > 0.99`` the
    fit says that the data cannot separate hardness and wall thickness.

    Parameters
    ----------
    ev : Evaluator
        The data (without a ``shore`` column) and model.
    shore0 : float
        Starting hardness (Shore A), clipped to ``shore_bounds``.
    tube_id0_mm : float
        Starting tube inner diameter (mm), clipped to [0.02, 0.98] x ``tube_od_mm``.
    tube_od_mm : float
        Undeformed tube outer diameter (mm), > 0; bounds the inner diameter.
    shore_bounds : tuple of float
        Allowed hardness range (Shore A).
    steps : tuple of float
        Forward-difference steps (Shore A, mm), > 0.
    max_nfev : int
        Largest number of residual evaluations.

    Returns
    -------
    Fit
        ``x = [shore, tube_id_mm]`` (Shore A, mm).

    Examples
    --------
    >>> import numpy as np
    >>> def model(shore, tube_id_mm, p):  # a toy forward model: OD (mm)
    ...     return 8.3 + p * (100 - shore) / 50 + p**2 * (tube_id_mm - 4)
    >>> p = np.array([0.1, 0.2, 0.3, 0.4])
    >>> ev = Evaluator(model, InflationData(p, model(62.5, 4.97, p)))  # planted data
    >>> fit = joint(ev, 60.0, 4.8, 8.3)
    >>> fit.x.round(2).tolist()
    [62.5, 4.97]
    """
    lo = np.array([shore_bounds[0], 0.02 * tube_od_mm])
    hi = np.array([shore_bounds[1], 0.98 * tube_od_mm])
    x0 = np.clip(np.array([shore0, tube_id0_mm], dtype=float), lo, hi)
    fit = _least_squares(ev, lambda x: (float(x[0]), float(x[1])), x0, lo, hi,
                         np.asarray(steps, float), max_nfev, ("shore", "tube_id_mm"))
    if fit.corr is not None and abs(fit.corr) > 0.99:
        fit.notes.append(
            f"the data cannot separate hardness and wall thickness (correlation "
            f"{fit.corr:.4f}): a thinner wall looks like a softer material, so the two are "
            "nearly interchangeable; fix one (e.g. a measured --tube-id) to pin the other"
        )
    return fit


def known_hardness(
    ev: Evaluator,
    tube_id0_mm: float,
    tube_od_mm: float,
    *,
    step: float = 0.001,
    max_nfev: int = 40,
) -> Fit:
    """Fit only the tube inner diameter (mm) when each point's hardness is known.

    Parameters
    ----------
    ev : Evaluator
        The data (with a ``shore`` column) and model.
    tube_id0_mm : float
        Starting tube inner diameter (mm), clipped to [0.02, 0.98] x ``tube_od_mm``.
    tube_od_mm : float
        Undeformed tube outer diameter (mm), > 0.
    step : float
        Forward-difference step (mm), > 0.
    max_nfev : int
        Largest number of residual evaluations.

    Returns
    -------
    Fit
        ``x = [tube_id_mm]`` (mm).

    Examples
    --------
    >>> import numpy as np
    >>> def model(shore, tube_id_mm, p):  # a toy forward model: OD (mm)
    ...     return 8.3 + p * (100 - shore) / 50 + p**2 * (tube_id_mm - 4)
    >>> p = np.array([0.1, 0.2, 0.3, 0.4])
    >>> data = InflationData(p, model(62.5, 4.97, p), shore=np.full(4, 62.5))
    >>> known_hardness(Evaluator(model, data), 4.8, 8.3).x.round(3).tolist()
    [4.97]
    """
    if ev.data.shore is None:
        raise InputError("known-hardness calibration needs a 'shore' column in the data")
    lo, hi = np.array([0.02 * tube_od_mm]), np.array([0.98 * tube_od_mm])
    x0 = np.clip(np.array([tube_id0_mm], dtype=float), lo, hi)
    return _least_squares(ev, lambda x: (None, float(x[0])), x0, lo, hi,
                          np.array([step]), max_nfev, ("tube_id_mm",))
