"""Fit a hyperelastic model to uniaxial, equibiaxial and planar test data at once.

Least squares with the analytic Jacobians of the closed forms in
:mod:`exofric.material._kernels` on the nominal (engineering) stress of every data point of
every mode given, stacked in one residual vector: :func:`scipy.optimize.least_squares`
(trust-region reflective, bounded) for the models linear in their parameters, a vectorised
Levenberg-Marquardt over all starts at once for Ogden.
Data given as true (Cauchy) stress are converted first: in all three modes the loaded
direction's ``sigma = l P``.

Admissible fits (issue 31): shear modulus > 0 and ``dP/dl`` above a floor along every measured
mode over its data range plus ``defaults.FIT_STABILITY_MARGIN_REL``. When the best least-squares
fit is not admissible, the constrained optimum is found with SLSQP (stability constraints on a
grid, refined where a 401-point check fails) and reported as constrained. Ogden fits start
from the discrete local minima of the variable-projection cost over a grid of exponents
(every combination evaluated at once), run on the exponents alone (mu by bounded linear least
squares on equilibrated columns, Kaufman's Jacobian), all starts in one batched
Levenberg-Marquardt: first on at most ``_SCAN_POINTS`` points per mode, then the best distinct
runs on all the data, with each exponent also tried at its bound (a term fitting the last
points alone creeps there); the best three are polished on all parameters, again at once
(issue 37). Unmeasured modes are only reported (and warned about).

Residuals are **absolute** (MPa) by default: a rig's stress error is mostly the load cell's
and the area's, roughly the same size at every point, and absolute residuals stay defined at
``P = 0`` (the unloaded point). ``residuals="relative"`` divides by the measured stress
(what many papers and FElupe's ``relative=True`` fit), weighting the small-strain points
more; it refuses data with a zero stress.

Parameter uncertainty: the covariance ``s^2 (J^T J)^+`` from the Jacobian ``J`` of the
residuals at the optimum and the residual variance ``s^2 = SSR / (n - p)``; standard errors are
its diagonal's square roots, the correlation matrix its normalised form (a linearisation: with a
bound active or strongly correlated parameters they are indicative only).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from exofric import defaults as D
from exofric._display import DisplayMixin
from exofric._lsq import correlation, lsq_covariance, standard_errors
from exofric._validate import checked_init
from exofric.errors import InputError, warn_implausible
from exofric.material._hyperelastic import (
    HYPERELASTIC_MODELS,
    MODES,
    STRESS_KINDS,
    HyperelasticModel,
    StabilityCheck,
    material_model,
)
from exofric.material._models import MaterialRangeWarning

if TYPE_CHECKING:
    import numpy as np
    import pandas as pd
    from numpy.typing import ArrayLike, NDArray

__all__ = ["MaterialFit", "ModeFit", "ModeStability", "fit_material"]

RESIDUALS = ("absolute", "relative")


@checked_init
@dataclass(frozen=True)
class ModeFit:
    """Data and goodness of fit of one test mode.

    Attributes
    ----------
    mode : str
        ``uniaxial``, ``biaxial`` or ``planar``.
    stretch : numpy.ndarray
        Stretches of the data (unitless).
    stress_mpa : numpy.ndarray
        Measured nominal (engineering) stress in MPa (converted from true stress if so given).
    fitted_mpa : numpy.ndarray
        The fitted model's nominal stress at the same stretches, MPa.
    r2 : float
        Coefficient of determination of the nominal stress (unitless; NaN for one point).
    rms_mpa : float
        Root-mean-square of ``fitted - measured`` in MPa.
    stress_kind : str
        How the data were given: ``engineering`` or ``true``.

    Examples
    --------
    >>> from exofric.material import fit_material, treloar_1944
    >>> fit = fit_material("neo-hookean", **treloar_1944())
    >>> fit.modes["uniaxial"].stretch.size
    24
    """

    mode: str
    stretch: NDArray[np.float64]
    stress_mpa: NDArray[np.float64]
    fitted_mpa: NDArray[np.float64]
    r2: float
    rms_mpa: float
    stress_kind: str = "engineering"

    @property
    def residual_mpa(self) -> NDArray[np.float64]:
        """``fitted - measured`` nominal stress per point, MPa."""
        return self.fitted_mpa - self.stress_mpa

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary: points, stretch range, R^2, RMS (MPa), stress kind.

        Returns
        -------
        dict
            Keys ``n_points``, ``stretch_min``, ``stretch_max``, ``r2``, ``rms_mpa``,
            ``stress_kind``.
        """
        return {"n_points": int(self.stretch.size), "stretch_min": float(self.stretch.min()),
                "stretch_max": float(self.stretch.max()), "r2": self.r2,
                "rms_mpa": self.rms_mpa, "stress_kind": self.stress_kind}


@checked_init
@dataclass(frozen=True)
class ModeStability:
    """Drucker stability of a fitted model along one homogeneous path, over a stretch range.

    Attributes
    ----------
    mode : str
        ``uniaxial``, ``biaxial`` or ``planar``.
    measured : bool
        Whether the fit had data of this mode (an unmeasured mode's instability is a warning).
    stretch_min, stretch_max : float
        The stretch range checked (unitless), 401 evenly spaced stretches.
    stable : bool
        ``dP/dl > 0`` over the whole range.
    unstable_from : float or None
        The unstable stretch nearest 1 (unitless), None when stable.

    Examples
    --------
    >>> from exofric.material import fit_material, treloar_1944
    >>> fit = fit_material("yeoh", uniaxial=treloar_1944()["uniaxial"])
    >>> fit.stability_report["uniaxial"].measured, fit.stability_report["planar"].measured
    (True, False)
    """

    mode: str
    measured: bool
    stretch_min: float
    stretch_max: float
    stable: bool
    unstable_from: float | None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict of the attributes (stretches unitless)."""
        return {"mode": self.mode, "measured": self.measured, "stretch_min": self.stretch_min,
                "stretch_max": self.stretch_max, "stable": self.stable,
                "unstable_from": self.unstable_from}


@checked_init
@dataclass(frozen=True)
class MaterialFit(DisplayMixin):
    """A hyperelastic model fitted to test data, with its uncertainty and stability.

    Attributes
    ----------
    model : HyperelasticModel
        The fitted model (parameters in MPa or unitless, d in 1/MPa).
    stderr : tuple of float
        Standard error of each parameter, same order and unit as ``model.params`` (NaN when
        there are no more points than parameters).
    correlation : numpy.ndarray
        Correlation matrix of the parameters (unitless, p x p).
    modes : dict of str to ModeFit
        Per mode fitted: data, fitted stress, R^2 and RMS (MPa).
    stability : StabilityCheck
        Drucker check (``dP/dl > 0``) of the measured modes, each over its data's stretch
        range (1 included); ``stretch_min``/``stretch_max`` span all modes.
    residuals : str
        ``absolute`` (MPa) or ``relative`` (unitless) residuals were minimised.
    cost : float
        Half the sum of squared residuals at the optimum (MPa^2 for absolute residuals).
    warnings : tuple of str
        What the fit warned about (a constraint or bound active, instability allowed or in an
        unmeasured mode, strong correlation).
    constrained : bool
        True when a stability constraint or a parameter bound is active at the optimum (the
        unconstrained least-squares optimum was not admissible).
    active_constraints : tuple of str
        Which ones, in words.
    stability_report : dict of str to ModeStability
        Per path (all three): stable or not over the report range (``stability_range``, by
        default each measured mode's data range widened by ``margin_rel``; for unmeasured modes
        that of all data), and whether the mode was measured.
    multistart : dict
        ``n_starts`` (local fits run), the RMS of the best, median and worst start
        (``rms_min_mpa``, ``rms_median_mpa``, ``rms_max_mpa``; ``_rel`` with relative
        residuals) and ``n_within_1pct`` (starts within 1 % of the best RMS).
    margin_rel : float
        The stability margin used (relative, in stretch).

    Examples
    --------
    >>> from exofric.material import fit_material, treloar_1944
    >>> fit = fit_material("yeoh", **treloar_1944())
    >>> fit.stability.stable, round(fit.modes["uniaxial"].r2, 3)
    (True, 0.995)
    """

    model: HyperelasticModel
    stderr: tuple[float, ...]
    correlation: NDArray[np.float64]
    modes: dict[str, ModeFit]
    stability: StabilityCheck
    residuals: str = "absolute"
    cost: float = 0.0
    warnings: tuple[str, ...] = field(default=())
    constrained: bool = False
    active_constraints: tuple[str, ...] = field(default=())
    stability_report: dict[str, ModeStability] = field(default_factory=dict)
    multistart: dict[str, Any] = field(default_factory=dict)
    margin_rel: float = 0.0

    @property
    def admissible(self) -> bool:
        """Shear modulus > 0 and every measured mode stable over its data range."""
        return self.model.shear_modulus_mpa > 0.0 and self.stability.stable

    @property
    def stretch_range(self) -> tuple[float, float]:
        """Smallest and largest stretch of the data, all modes (unitless), with 1 included."""
        lo = min([1.0, *(float(m.stretch.min()) for m in self.modes.values())])
        hi = max([1.0, *(float(m.stretch.max()) for m in self.modes.values())])
        return lo, hi

    def stress_mpa(self, mode: str, stretch: ArrayLike,
                   kind: str = "engineering") -> NDArray[np.float64]:
        """The fitted model's stress (MPa); warns outside the data's stretch range.

        A :class:`MaterialRangeWarning` says when a stretch lies outside the range of that
        mode's data (with 1 included), or when the mode had no data: the model then
        extrapolates.

        Parameters
        ----------
        mode : {'uniaxial', 'biaxial', 'planar'}
            The homogeneous test mode.
        stretch : array_like of float
            Stretch (unitless), > 0.
        kind : {'engineering', 'true'}
            Nominal or Cauchy stress.

        Returns
        -------
        numpy.ndarray
            Stress in MPa.
        """
        import numpy as np

        out = self.model.stress_mpa(mode, stretch, kind)
        lam = np.asarray(stretch, dtype=float)
        m = self.modes.get(mode)
        if m is None:
            warnings.warn(f"the fit had no {mode} data: its {mode} stress is a prediction",
                          MaterialRangeWarning, stacklevel=2)
        else:
            lo, hi = min(1.0, float(m.stretch.min())), max(1.0, float(m.stretch.max()))
            if np.any(lam < lo) or np.any(lam > hi):
                warnings.warn(f"{mode} stretch outside the fitted data's range {lo:g}-{hi:g}: "
                              "the model extrapolates", MaterialRangeWarning, stacklevel=2)
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: model, params (with units), standard errors, correlation, modes.

        Returns
        -------
        dict
            ``model``, ``params`` and ``stderr`` by name (``_mpa`` suffix: MPa),
            ``param_units``, ``correlation`` (``names``, ``matrix``), ``shear_modulus_mpa``,
            ``d_per_mpa``, ``bulk_modulus_mpa``, ``residuals``, ``modes`` (R^2, RMS in MPa,
            stretch range), ``stability``, ``stability_modes`` (per path: measured, range,
            stable, unstable_from), ``admissible``, ``constrained``, ``active_constraints``,
            ``stability_margin_pct``, ``multistart`` and ``warnings``.
        """
        names = self.model.param_names
        d = self.model.to_dict()
        d.update({
            "param_units": {n: "MPa" if n.endswith("_mpa") else "unitless" for n in names},
            "stderr": dict(zip(names, self.stderr, strict=True)),
            "correlation": {"names": list(names),
                            "matrix": [[float(v) for v in row] for row in self.correlation]},
            "residuals": self.residuals,
            "modes": {k: m.to_dict() for k, m in self.modes.items()},
            "stability": self.stability.to_dict(),
            "stability_modes": {k: v.to_dict() for k, v in self.stability_report.items()},
            "admissible": self.admissible,
            "constrained": self.constrained,
            "active_constraints": list(self.active_constraints),
            "stability_margin_pct": 100.0 * self.margin_rel,
            "multistart": dict(self.multistart),
            "warnings": list(self.warnings),
        })
        return d

    def to_frame(self) -> pd.DataFrame:
        """One row per data point: mode, stretch, measured and fitted stress, residual (MPa).

        Returns
        -------
        pandas.DataFrame
            Columns ``mode``, ``stretch``, ``stress_mpa``, ``fitted_mpa``, ``residual_mpa``.
        """
        import pandas as pd

        frames = [pd.DataFrame({"mode": k, "stretch": m.stretch, "stress_mpa": m.stress_mpa,
                                "fitted_mpa": m.fitted_mpa, "residual_mpa": m.residual_mpa})
                  for k, m in self.modes.items()]
        return pd.concat(frames, ignore_index=True)

    def plot(self, fig: Any | None = None) -> Any:
        """Data and fitted curves per mode (nominal stress, MPa) over a residual panel.

        Parameters
        ----------
        fig : matplotlib Figure, optional
            An empty figure to draw on (default a new one).

        Returns
        -------
        matplotlib Figure
        """
        from exofric.plots import plot_material_fit

        return plot_material_fit(self, fig)


def _mode_data(mode: str, data: Any, kind: str) -> tuple[NDArray[np.float64],
                                                        NDArray[np.float64]]:
    import numpy as np

    try:
        stretch, stress = data
        lam = np.asarray(stretch, dtype=float).ravel()
        p = np.asarray(stress, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{mode} must be a pair (stretch, stress_mpa) of number lists",
                         param=mode) from None
    if lam.size != p.size:
        raise InputError(f"{mode}: stretch and stress_mpa must have the same length, got "
                         f"{lam.size} and {p.size}", param=mode)
    if lam.size == 0:
        raise InputError(f"{mode}: no data points", param=mode)
    for name, a in (("stretch", lam), ("stress_mpa", p)):
        bad = np.flatnonzero(~np.isfinite(a))
        if bad.size:
            raise InputError(f"{mode}: {name} must be finite, got {a[bad[0]]} at index "
                             f"{bad[0]}", param=mode)
    bad = np.flatnonzero(lam <= 0.0)
    if bad.size:
        raise InputError(f"{mode}: stretch must be > 0 (unitless), got {lam[bad[0]]:g} at index "
                         f"{bad[0]}", param=mode)
    step = np.diff(lam)
    if lam.size > 1 and not (np.all(step > 0.0) or np.all(step < 0.0)):
        i = int(np.flatnonzero(step * (1 if step[0] > 0 else -1) <= 0.0)[0]) + 1
        raise InputError(f"{mode}: stretch must be strictly monotonic (one loading curve), got "
                         f"{lam[i - 1]:g} then {lam[i]:g} at index {i}", param=mode)
    wrong = np.flatnonzero((lam - 1.0) * p < 0.0)
    if 2 * wrong.size > lam.size:   # tension pulls, compression pushes: mostly the other sign
        # is a sign convention slipped (a few points: a tare offset, or an unstable curve that
        # falls through zero, which the stability check names)
        warn_implausible(f"{mode}: stress_mpa has the sign of the other direction at "
                         f"{wrong.size} of {lam.size} points (first: stretch "
                         f"{lam[wrong[0]]:g}, stress {p[wrong[0]]:g} MPa): check the sign "
                         "convention or a tare offset")
    if kind == "true":
        p = p / lam  # sigma = l P in the loaded direction of all three modes
    return lam, p


def _g0(data: dict[str, tuple[NDArray[np.float64], NDArray[np.float64]]]) -> float:
    """A shear-modulus estimate (MPa): neo-Hookean moduli of the points nearest l = 1."""
    import numpy as np

    est = []
    for mode, (lam, p) in data.items():
        l1, l2, l3 = lam, *({"uniaxial": (lam ** -0.5, lam ** -0.5), "biaxial": (lam, lam ** -2),
                             "planar": (np.ones_like(lam), 1 / lam)}[mode])
        k = l2 if mode == "uniaxial" else l3
        den = (l1 ** 2 - k ** 2) / lam
        ok = np.abs(den) > 1e-9
        g = p[ok] / den[ok]
        order = np.argsort(np.abs(np.log(lam[ok])))[:3]
        est.extend(g[order].tolist())
    g0 = float(np.median(est)) if est else 1.0
    return g0 if np.isfinite(g0) and g0 > 0 else 1.0


#: Ogden exponents combined (N at a time) for the multi-start; the best combinations by their
#: variable-projection cost (optimal mu for fixed exponents) become starts.
_OGDEN_GRID = (-12.0, -8.0, -5.0, -3.0, -2.0, -1.0, 1.0, 2.0, 3.0, 4.0, 6.0, 9.0, 13.0, 18.0)
#: Published-style starts (Ogden 1972 on Treloar: 1.3, 5, -2), always tried.
_OGDEN_CLASSIC: dict[int, list[tuple[float, ...]]] = {
    1: [(2.0,), (1.3,), (3.0,)],
    2: [(1.5, 5.0), (2.0, -2.0), (3.0, -1.0)],
    3: [(1.3, 5.0, -2.0), (2.0, 4.0, -2.0), (1.0, 3.0, -1.0)]}
_ALPHA_MAX = 30.0
#: The polish's relative tolerance on cost decrease, step and gradient (least_squares'
#: ftol, xtol, gtol; the exponent scan stops at 1e-9).
_POLISH_TOL = 1e-12
#: A Levenberg-Marquardt run checks every _SCAN_WINDOW iterations that its cost still falls
#: (a term whose mu dies crawls along its exponent toward the bound).
_SCAN_WINDOW = 25
#: The exponent scan runs first on at most this many points per mode (evenly spaced in the
#: data's order), then its best _SCAN_KEEP distinct runs continue on all of them.
_SCAN_POINTS = 120
_SCAN_KEEP = 8


def _resolve_model(model: Any, terms: int | None) -> str:
    """Canonical model name; ``ogden`` with ``terms`` (1-3, default 3) -> ``ogdenN``."""
    if not isinstance(model, str):
        raise InputError(f"model must be a model name, got {model!r}", param="model")
    name = model.strip().lower().replace("_", "-")
    name = {"neohookean": "neo-hookean", "mooneyrivlin": "mooney-rivlin"}.get(name, name)
    if terms is not None:
        if isinstance(terms, bool) or not isinstance(terms, (int, float)) or terms != int(terms) \
                or not 1 <= int(terms) <= 3:
            raise InputError(f"terms must be 1, 2 or 3 (Ogden terms), got {terms!r}",
                             param="terms")
        if not name.startswith("ogden"):
            raise InputError(f"terms applies only to the Ogden model, not {name}", param="terms")
        if name != "ogden" and name != f"ogden{int(terms)}":
            raise InputError(f"terms {int(terms)} contradicts model {name}: give model ogden "
                             "with terms, or ogden1..ogden3 alone", param="terms")
        name = f"ogden{int(terms)}"
    if name == "ogden":
        name = "ogden3"
    if name not in HYPERELASTIC_MODELS:
        raise InputError(f"model must be one of {', '.join(HYPERELASTIC_MODELS)} (or ogden "
                         f"with terms 1-3), got {model!r}", param="model")
    return name


def _widened(lo: float, hi: float, margin: float) -> tuple[float, float]:
    """A data range [lo, hi] (1 included) widened by the margin at the ends away from 1."""
    lo2 = lo / (1.0 + margin) if lo < 1.0 else lo
    hi2 = hi * (1.0 + margin) if hi > 1.0 else hi
    if not hi2 > lo2:
        hi2 = lo2 * (1.0 + max(margin, 1e-3))
    return lo2, hi2


class _Problem:
    """Residuals, Jacobian and stability constraints of one fit (all vectorised)."""

    def __init__(self, name: str, data: dict[str, tuple[Any, Any]], scale: Any,
                 margin: float) -> None:
        import numpy as np

        from exofric import defaults

        self.name = name
        self.data = data
        self.modes = list(data)
        self._rj_key: bytes | None = None
        self._rj_val: tuple[Any, Any] = (None, None)
        self.p = np.concatenate([p for _, p in data.values()])
        self.scale = scale
        self.target = self.p / scale
        self.n_par = len(HYPERELASTIC_MODELS[name])
        lam_all = np.concatenate([lam for lam, _ in data.values()])
        strain = float(np.max(np.abs(lam_all - 1.0)))
        secant = float(np.max(np.abs(self.p))) / strain if strain > 0 else 1.0
        self.secant = secant if np.isfinite(secant) and secant > 0 else 1.0
        self.tau = defaults.FIT_TANGENT_FLOOR_REL * self.secant
        self.data_range = {m: (min(1.0, float(lam.min())), max(1.0, float(lam.max())))
                           for m, (lam, _) in data.items()}
        self.range = {m: _widened(*r, margin) for m, r in self.data_range.items()}
        self.mu_max = min(defaults.FIT_OGDEN_MU_MAX_REL * self.secant, 1e4)
        n = int(defaults.FIT_CONSTRAINT_POINTS)
        self.grid = {m: np.linspace(*self.range[m], n) for m in self.modes}
        self.fine = {m: np.linspace(*self.range[m], 401) for m in self.modes}

    def violations(self, x: Any) -> dict[str, Any]:
        """Per mode, the fine-grid stretches where ``dP/dl < tau`` (the worst of each run)."""
        import numpy as np

        from exofric.material._kernels import tangent_jac

        out = {}
        for m in self.modes:
            t, _ = tangent_jac(self.name, m, self.fine[m], x)
            bad = (t - self.tau) / self.secant < -1e-9
            if bad.any():
                idx = np.flatnonzero(bad)
                runs = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)
                out[m] = np.array([self.fine[m][r[np.argmin(t[r])]] for r in runs])
        return out

    def refine(self, extra: dict[str, Any]) -> None:
        """Add stretches to the constraint grids."""
        import numpy as np

        for m, lam in extra.items():
            self.grid[m] = np.unique(np.concatenate([self.grid[m], lam]))

    def rj(self, x: Any) -> tuple[Any, Any]:
        """Residuals and their Jacobian at x (the last evaluation is cached)."""
        import numpy as np

        from exofric.material._kernels import stress_jac

        key = np.asarray(x, dtype=float).tobytes()
        if key == self._rj_key:
            return self._rj_val

        ps, js = [], []
        for m in self.modes:
            p, j = stress_jac(self.name, m, self.data[m][0], x)
            ps.append(p)
            js.append(j)
        with np.errstate(all="ignore"):
            r = np.concatenate(ps) / self.scale - self.target
            jac = np.vstack(js) / self.scale[:, None]
        bad = ~np.isfinite(r)
        if bad.any():
            r = np.where(bad, 1e6, r)
        jac = np.where(np.isfinite(jac), jac, 0.0)
        self._rj_key, self._rj_val = key, (r, jac)
        return r, jac

    def resid(self, x: Any) -> Any:
        return self.rj(x)[0]

    def jac(self, x: Any) -> Any:
        return self.rj(x)[1]

    def cons(self, x: Any) -> tuple[Any, Any]:
        """``(dP/dl - tau) / secant`` on every measured mode's grid, and its Jacobian."""
        import numpy as np

        from exofric.material._kernels import tangent_jac

        ts, js = [], []
        for m in self.modes:
            t, j = tangent_jac(self.name, m, self.grid[m], x)
            ts.append(t)
            js.append(j)
        return ((np.concatenate(ts) - self.tau) / self.secant,
                np.vstack(js) / self.secant)

    def subsampled(self, k: int) -> _Problem:
        """The same problem on at most ``k`` points per mode (evenly spaced indices, ends
        kept), with this one's bounds and constraint grids; itself when no mode has more."""
        import numpy as np

        if all(lam.size <= k for lam, _ in self.data.values()):
            return self
        keep, data = [], {}
        off = 0
        for m, (lam, p) in self.data.items():
            idx = np.unique(np.round(np.linspace(0, lam.size - 1, min(k, lam.size))).astype(int))
            data[m] = (lam[idx], p[idx])
            keep.append(off + idx)
            off += lam.size
        sub = _Problem(self.name, data, self.scale[np.concatenate(keep)], 0.0)
        sub.mu_max, sub.tau, sub.secant = self.mu_max, self.tau, self.secant
        sub.range, sub.grid, sub.fine = self.range, self.grid, self.fine
        return sub

    def full_batch(self, x: Any) -> tuple[Any, Any, Any]:
        """Ogden on all parameters, many rows of ``x`` (S x 2n) at once: half the squared
        residual norm (S,; inf where not finite), residuals (S, N) and Jacobian (S, N, 2n)."""
        import numpy as np

        from exofric.material._kernels import ogden_columns

        x = np.atleast_2d(np.asarray(x, dtype=float))
        mu, alpha = x[:, 0::2], x[:, 1::2]
        cols = [ogden_columns(m, self.data[m][0], alpha) for m in self.modes]
        with np.errstate(all="ignore"):
            psi = np.concatenate([c[0] for c in cols], axis=-2) / self.scale[:, None]
            dpsi = np.concatenate([c[1] for c in cols], axis=-2) / self.scale[:, None]
            res = (psi @ mu[..., None])[..., 0] - self.target
            jac = np.empty(psi.shape[:2] + (x.shape[1],))
            jac[..., 0::2] = psi
            jac[..., 1::2] = dpsi * mu[:, None, :]
            cost = 0.5 * np.einsum("sn,sn->s", res, res)
        ok = np.isfinite(cost) & np.all(np.isfinite(jac), axis=(1, 2))
        return np.where(ok, cost, np.inf), res, jac

    def vp_batch(self, alpha: Any) -> tuple[Any, Any, Any, Any]:
        """Variable projection for Ogden, for many exponent vectors at once (the rows of
        ``alpha``, S x n): half the squared residual norm (S,; inf where a column is not
        finite), residuals (S, N), Kaufman's Jacobian ``P_perp (dA/da_k) mu_k`` (S, N, n) and
        the best mu (S, n; MPa) by linear least squares within ``|mu_i| <= mu_max``.

        The columns are equilibrated (scaled to unit norm) before the QR: a large exponent's
        column is ~1e20 times another's at the largest stretch."""
        import numpy as np

        from exofric.material._kernels import ogden_columns

        alpha = np.atleast_2d(np.asarray(alpha, dtype=float))
        cols = [ogden_columns(m, self.data[m][0], alpha) for m in self.modes]
        with np.errstate(all="ignore"):
            a_mat = np.concatenate([c[0] for c in cols], axis=-2) / self.scale[:, None]
            d_mat = np.concatenate([c[1] for c in cols], axis=-2) / self.scale[:, None]
            norm = np.linalg.norm(a_mat, axis=1)
            finite = (np.all(np.isfinite(a_mat), axis=(1, 2)) & np.all(np.isfinite(d_mat),
                                                                      axis=(1, 2))
                      & np.all(np.isfinite(norm) & (norm > 0.0), axis=1))
            a_mat[~finite], d_mat[~finite], norm[~finite] = 1.0, 0.0, 1.0  # cost inf below
            a_eq = a_mat / norm[:, None, :]
            q, r_tri = np.linalg.qr(a_eq)
            diag = np.abs(np.diagonal(r_tri, axis1=1, axis2=2))
            well = diag.min(axis=1) > 1e-10
            r_tri[~well] = np.eye(alpha.shape[1])
            mu = np.linalg.solve(r_tri, (np.swapaxes(q, 1, 2) @ self.target)[..., None])[..., 0]
            mu /= norm
            dm = d_mat * mu[:, None, :]
            jac = dm - q @ (np.swapaxes(q, 1, 2) @ dm)
            over = np.any(np.abs(mu) > self.mu_max, axis=1) | ~well
            if over.any():
                mu[over], jac[over] = self._bounded_vp(a_eq[over], d_mat[over], norm[over])
            res = (a_mat @ mu[..., None])[..., 0] - self.target
            cost = 0.5 * np.einsum("sn,sn->s", res, res)
        cost = np.where(finite & np.isfinite(cost), cost, np.inf)
        return cost, res, jac, mu

    def _bounded_vp(self, a_eq: Any, d_mat: Any, norm: Any) -> tuple[Any, Any]:
        """Rows whose free mu passes its bound (or whose columns are nearly dependent): mu
        (S, n; MPa) by bounded linear least squares on the equilibrated columns ``a_eq``
        (column norms ``norm``) and the Jacobian with the bound mu held (projection on the
        free columns only)."""
        import numpy as np

        mu = self._bounded_mu(a_eq, self.mu_max * norm) / norm
        free = np.abs(mu) < self.mu_max * (1.0 - 1e-9)
        a_free = a_eq * free[:, None, :]
        dm = d_mat * mu[:, None, :]
        # projection on the free columns by their normal equations (identity on the held
        # ones, whose columns are zero here); the columns have unit norm
        eye = np.eye(mu.shape[1])
        gram = np.swapaxes(a_free, 1, 2) @ a_free + (~free)[:, :, None] * eye + 1e-13 * eye
        with np.errstate(all="ignore"):
            jac = dm - a_free @ np.linalg.solve(gram, np.swapaxes(a_free, 1, 2) @ dm)
        return mu, jac

    def _bounded_mu(self, a_mat: Any, bound: Any) -> Any:
        """Linear least squares ``a_mat z ~ target`` within ``|z| <= bound`` (S x n), every
        row of ``a_mat`` (S, N, n) at once: the convex problem's minimum is one of the 3^n
        ways of holding each z_i free or at a bound (n <= 3), all solved at once on the normal
        equations (a 1e-13 relative ridge keeps a singular block solvable); the feasible one
        of lowest cost."""
        import itertools

        import numpy as np

        g_mat = np.swapaxes(a_mat, 1, 2) @ a_mat
        b = np.swapaxes(a_mat, 1, 2) @ self.target
        n = b.shape[1]
        side = np.array(list(itertools.product((0.0, 1.0, -1.0), repeat=n)))  # (T, n)
        fixed = side != 0.0
        eye = np.eye(n)
        ridge = 1e-13 * np.trace(g_mat, axis1=1, axis2=2)[:, None, None, None] * eye
        # fixed rows of each system read z_k = +-bound_k, free rows the normal equations
        lhs = np.where(fixed[None, :, :, None], eye, g_mat[:, None] + ridge)
        rhs = np.where(fixed[None], side[None] * bound[:, None, :], b[:, None, :])
        with np.errstate(all="ignore"):
            z = np.linalg.solve(lhs, rhs[..., None])[..., 0]  # (S, T, n)
            cost = (np.einsum("stk,skl,stl->st", z, g_mat, z)
                    - 2.0 * np.einsum("sk,stk->st", b, z))
        feasible = (np.all(np.abs(z) <= bound[:, None, :] * (1.0 + 1e-12), axis=2)
                    & np.isfinite(cost))
        best = np.argmin(np.where(feasible, cost, np.inf), axis=1)
        return np.clip(z[np.arange(z.shape[0]), best], -bound, bound)

    def mu(self, x: Any) -> float:
        from exofric.material._hyperelastic import _shear_modulus

        return float(_shear_modulus(self.name, tuple(float(v) for v in x)))


def _bounds(name: str, secant: float) -> tuple[list[float], list[float]]:
    """Parameter bounds: C10 >= 0 (neo-Hookean, Yeoh); Ogden |alpha_i| <= 30 and |mu_i| <=
    ``FIT_OGDEN_MU_MAX_REL`` x the data's secant modulus (larger mu_i are cancelling terms)."""
    from exofric import defaults

    inf = float("inf")
    if name == "neo-hookean":
        return [0.0], [inf]
    if name == "mooney-rivlin":
        return [-inf, -inf], [inf, inf]
    if name == "yeoh":
        return [0.0, -inf, -inf], [inf, inf, inf]
    n = int(name[-1])
    m = min(defaults.FIT_OGDEN_MU_MAX_REL * secant, 1e4)
    return ([v for _ in range(n) for v in (-m, -_ALPHA_MAX)],
            [v for _ in range(n) for v in (m, _ALPHA_MAX)])


def _starts(prob: _Problem, g: float, n_keep: int | None) -> list[Any]:
    """Initial parameter vectors: one for the linear models, a multi-start for Ogden."""
    import numpy as np

    from exofric import defaults

    name = prob.name
    if name == "neo-hookean":
        return [np.array([g / 2])]
    if name == "mooney-rivlin":
        return [np.array([0.4 * g, 0.1 * g])]
    if name == "yeoh":
        return [np.array([g / 2, -1e-2 * g, 1e-4 * g])]
    n = int(name[-1])
    keep = int(defaults.FIT_OGDEN_STARTS[n] if n_keep is None else n_keep)
    patterns = _ogden_start_patterns(prob.subsampled(_SCAN_POINTS), n, keep)
    mu = prob.vp_batch(patterns)[3]
    return [np.ravel(np.column_stack([m, a])) for m, a in zip(mu, patterns, strict=True)]


def _ogden_start_patterns(prob: _Problem, n: int, keep: int) -> Any:
    """Ogden start exponents (rows, ``keep`` + up to 3): the variable-projection cost over
    every combination of n exponents of ``_OGDEN_GRID`` (all at once); its discrete local
    minima (no neighbour, one exponent one grid step away, is lower) mark the basins and come
    first, lowest first, then the best other combinations; the published-style patterns
    ``_OGDEN_CLASSIC`` are always added."""
    import itertools

    import numpy as np

    grid = np.asarray(_OGDEN_GRID)
    size = grid.size
    combos = np.array(list(itertools.combinations(range(size), n)))
    cost = prob.vp_batch(grid[combos])[0]
    dense = np.full((size,) * n, np.inf)
    dense[tuple(combos.T)] = cost
    is_min = np.isfinite(cost)
    for k in range(n):
        for step in (-1, 1):
            cand = combos.copy()
            cand[:, k] += step
            ok = (cand[:, k] >= 0) & (cand[:, k] < size)
            cand = np.sort(np.clip(cand, 0, size - 1), axis=1)
            ok &= np.all(np.diff(cand, axis=1) > 0, axis=1)
            nb = np.where(ok, dense[tuple(cand.T)], np.inf)
            is_min &= cost <= nb
    ranked = np.argsort(cost, kind="stable")
    minima = ranked[is_min[ranked]][:keep]
    picks = np.concatenate([minima, ranked[~is_min[ranked]][:keep - minima.size]])
    chosen = [tuple(float(v) for v in grid[combos[i]]) for i in picks]
    seen = {tuple(sorted(pat)) for pat in chosen}
    chosen += [pat for pat in _OGDEN_CLASSIC[n] if tuple(sorted(pat)) not in seen]
    return np.array(chosen)


def _feasible_start(name: str, g: float) -> Any:
    """A neo-Hookean-equivalent start (stable on every path)."""
    import numpy as np

    if name == "neo-hookean":
        return np.array([g / 2])
    if name == "mooney-rivlin":
        return np.array([g / 2, 0.0])
    if name == "yeoh":
        return np.array([g / 2, 0.0, 0.0])
    n = int(name[-1])
    x = [g, 2.0]
    for a in _OGDEN_CLASSIC[n][0][1:]:
        x += [0.0, a]
    return np.array(x)


def _admissible(prob: _Problem, x: Any) -> bool:
    """Shear modulus > 0 and ``dP/dl >= tau`` on the constraint grids and the fine grids."""
    import numpy as np

    c, _ = prob.cons(x)
    return bool(np.all(c >= -1e-9) and prob.mu(x) > 0.0 and not prob.violations(x))


def _slsqp(prob: _Problem, x0: Any, lo: Any, hi: Any, xs: Any) -> Any:
    """SLSQP on 0.5 |r|^2 subject to the stability constraints from ``x0`` (the parameters
    scaled by ``xs``); constraint stretches violated in between are added and it is run again
    (up to 4 times). The final point, clipped to the bounds."""
    import numpy as np
    from scipy.optimize import Bounds, minimize

    norm = max(float(prob.target @ prob.target), 1e-300)

    def f(z: Any) -> tuple[float, Any]:
        r, j = prob.rj(z * xs)
        return 0.5 * float(r @ r) / norm, (j.T @ r) * xs / norm

    cons = {"type": "ineq", "fun": lambda z: prob.cons(z * xs)[0],
            "jac": lambda z: prob.cons(z * xs)[1] * xs}
    bounds = Bounds(lo / xs, hi / xs)
    x = np.clip(x0, lo, hi)
    for _ in range(4):  # a coarse grid first; stretches violated in between are added
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            res = minimize(f, x / xs, jac=True, method="SLSQP", bounds=bounds,
                           constraints=[cons], options={"ftol": 1e-15, "maxiter": 500})
        x = np.clip(res.x * xs, lo, hi)
        extra = prob.violations(x) if np.all(np.isfinite(x)) else {}
        if not extra:
            break
        prob.refine(extra)
    return x


def _solve_constrained(prob: _Problem, x0s: list[Any], lo: Any, hi: Any, xs: Any,
                       fallback: Any) -> tuple[Any, float] | None:
    """SLSQP on 0.5 |r|^2 subject to the stability constraints, from several starts (the
    same start once), and from ``fallback`` (a start stable on every path) when none of them
    ends admissible; the lowest-cost admissible result (x, cost), or None."""
    import numpy as np

    best: tuple[Any, float] | None = None
    distinct: list[Any] = []
    for x0 in x0s:
        if not any(np.allclose(x0, y, rtol=1e-6, atol=0.0) for y in distinct):
            distinct.append(x0)
    for x0 in [*distinct, fallback]:
        if x0 is fallback and best is not None:
            break
        x = _slsqp(prob, x0, lo, hi, xs)
        if not np.all(np.isfinite(x)) or not _admissible(prob, x):
            continue
        r = prob.resid(x)
        cost = 0.5 * float(r @ r)
        if best is None or cost < best[1]:
            best = (x, cost)
    return best


def fit_material(
    model: str,
    uniaxial: Any = None,
    biaxial: Any = None,
    planar: Any = None,
    *,
    stress_kind: str | dict[str, str] = "engineering",
    residuals: str = "absolute",
    d: float | None = None,
    poisson: float = D.POISSON,
    allow_unstable: bool = False,
    terms: int | None = None,
    constrain: bool = True,
    stability_range: tuple[float, float] | None = None,
    n_starts: int | None = None,
) -> MaterialFit:
    """Fit a hyperelastic model to one or several homogeneous test modes at once.

    By default the fit is **constrained to admissible models**: initial shear modulus > 0 and
    Drucker-stable (``dP/dl`` at least ``FIT_TANGENT_FLOOR_REL`` x the data's secant modulus)
    along every measured mode over that mode's stretch range widened by
    ``defaults.FIT_STABILITY_MARGIN_REL`` (10 %). When the best unconstrained least-squares fit
    is admissible it is the answer; otherwise the constrained optimum (SLSQP from several
    starts) is, and the result says so (``constrained``, ``active_constraints``). Modes without
    data are checked over ``stability_range`` (default: the widened range of the data) and
    only warned about.

    Parameters
    ----------
    model : str
        Model name (see :func:`material_model`): ``neo-hookean``, ``mooney-rivlin``, ``yeoh``,
        ``ogden1``, ``ogden2``, ``ogden3``, or ``ogden`` with ``terms``.
    uniaxial, biaxial, planar : (array_like, array_like) or None
        Per test mode, ``(stretch, stress_mpa)``: stretch of the loaded direction (unitless,
        > 0, strictly monotonic) and its stress in MPa. At least one mode.
    stress_kind : {'engineering', 'true'} or dict
        How the stresses are given: nominal (force per undeformed area) or Cauchy (true);
        one for all modes or a dict per mode.
    residuals : {'absolute', 'relative'}
        Minimise ``P_model - P_data`` (MPa; default) or ``(P_model - P_data) / P_data``.
    d : float, optional
        Incompressibility parameter d of the result in 1/MPa (not fitted: the homogeneous
        tests are incompressible). Default from ``poisson`` and the fitted shear modulus.
    poisson : float
        Small-strain Poisson ratio nu in (0, 0.5) for the default d (``2 (1 - 2 nu) / mu``).
    allow_unstable : bool
        Fit without the stability constraints (bounds only) and accept a result that is
        Drucker-unstable within the data's stretch range, with a warning.
    terms : int, optional
        Ogden terms, 1-3, with ``model="ogden"`` (default 3).
    constrain : bool
        Impose the admissibility constraints (default). ``False``: bounds only, and a fit
        unstable within the data's range is an :class:`~exofric.errors.InputError` unless
        ``allow_unstable``.
    stability_range : (float, float), optional
        Stretch range (unitless, ``0 < lo < hi``) of the per-mode stability report; default the
        data's range widened by the margin (for unmeasured modes: of all data).
    n_starts : int, optional
        Ogden: how many exponent combinations start a local fit (the discrete local minima of
        the variable-projection cost over a grid of exponents, lowest first, then the best
        other combinations), besides three published-style starts (default
        ``defaults.FIT_OGDEN_STARTS``: 6, 10, 40 for 1-3 terms; they run at once).

    Returns
    -------
    MaterialFit

    Raises
    ------
    InputError
        Unknown model, bad data (stretch <= 0, not monotonic, lengths), fewer points than
        parameters, no mode given, no admissible fit found, or (``constrain=False``) an
        unstable fit without ``allow_unstable``.

    Examples
    --------
    >>> import numpy as np
    >>> stretch = np.linspace(1.1, 3.0, 8)
    >>> stress = 2 * 0.2 * (stretch - stretch**-2)       # neo-Hookean C10 = 0.2 MPa
    >>> fit = fit_material("neo-hookean", uniaxial=(stretch, stress))
    >>> round(fit.model.params[0], 6), fit.stability.stable, fit.constrained
    (0.2, True, False)
    """
    from exofric import defaults

    name = _resolve_model(model, terms)
    kinds, report_range = _check_options(residuals, stress_kind, stability_range, n_starts)
    data = _fit_data(name, {"uniaxial": uniaxial, "biaxial": biaxial, "planar": planar},
                     kinds, residuals)
    margin = float(defaults.FIT_STABILITY_MARGIN_REL)
    setup = _setup(name, data, residuals, margin)
    runs = _unconstrained_fits(setup, n_starts)
    x = runs.results[0][1]
    constrained = False
    if constrain and not allow_unstable and not _admissible(setup.prob, x):
        x = _constrained_fit(setup, runs, margin)
        constrained = True
    x = _canonical_order(name, x)
    notes: list[str] = []
    active = _active_constraints(setup, x, constrained)
    if active:
        constrained = True
        notes.append("constrained fit (" + "; ".join(active) + "): standard errors are "
                     "indicative only")
    cost, se, corr, notes_corr = _uncertainty(setup.prob, x)
    notes += notes_corr
    fitted = _fitted_model(name, x, d, poisson)
    mode_fits = _mode_fits(fitted, data, kinds)
    stab, notes_data = _data_stability(fitted, setup.prob, allow_unstable)
    report, notes_report = _stability_report(fitted, setup.prob, stab, report_range)
    notes += notes_data + notes_report
    for note in notes:
        warn_implausible(note)
    return MaterialFit(fitted, tuple(float(v) for v in se), corr, mode_fits, stab, residuals,
                       cost, tuple(notes), constrained=constrained,
                       active_constraints=tuple(active), stability_report=report,
                       multistart=_multistart_summary(runs.start_costs, setup.n_pts, residuals),
                       margin_rel=margin)


# --- fit_material's steps ------------------------------------------------------------------
# checks and data -> setup -> unconstrained multi-start -> constrained fit (when needed) ->
# active constraints -> uncertainty -> fitted model and per-mode fits -> stability -> result


def _stress_kinds(stress_kind: Any) -> dict[str, str]:
    """The stress kind (engineering/true) per mode, checked."""
    kinds = (dict(stress_kind) if isinstance(stress_kind, dict)
             else dict.fromkeys(MODES, stress_kind))
    for k, v in kinds.items():
        if k not in MODES or v not in STRESS_KINDS:
            raise InputError(f"stress_kind must be one of {', '.join(STRESS_KINDS)} (per mode: "
                             f"{', '.join(MODES)}), got {k}={v!r}", param="stress_kind")
    return kinds


def _report_range(stability_range: Any) -> tuple[float, float] | None:
    """The stability report's stretch range (unitless, ``0 < lo < hi <= 1000``), or None."""
    import numpy as np

    if stability_range is None:
        return None
    try:
        lo_r, hi_r = (float(v) for v in stability_range)
    except (TypeError, ValueError):
        raise InputError("stability_range must be two stretches lo,hi (unitless), got "
                         f"{stability_range!r}", param="stability_range") from None
    if not (np.isfinite(lo_r) and np.isfinite(hi_r) and 0.0 < lo_r < hi_r <= 1e3):
        raise InputError("stability_range must be two stretches 0 < lo < hi <= 1000 "
                         f"(unitless), got {lo_r:g},{hi_r:g}", param="stability_range")
    return lo_r, hi_r


def _check_options(residuals: str, stress_kind: Any, stability_range: Any,
                   n_starts: Any) -> tuple[dict[str, str], tuple[float, float] | None]:
    """The options checked: stress kind per mode and the report's stretch range (unitless)."""
    if residuals not in RESIDUALS:
        raise InputError(f"residuals must be one of {', '.join(RESIDUALS)}, got {residuals!r}",
                         param="residuals")
    kinds = _stress_kinds(stress_kind)
    report_range = _report_range(stability_range)
    if n_starts is not None and (isinstance(n_starts, bool) or not isinstance(n_starts, int)
                                 or not 1 <= n_starts <= 200):
        raise InputError(f"n_starts must be an integer in 1-200, got {n_starts!r}",
                         param="n_starts")
    return kinds, report_range


def _fit_data(name: str, given: dict[str, Any], kinds: dict[str, str],
              residuals: str) -> dict[str, tuple[NDArray[np.float64], NDArray[np.float64]]]:
    """Per mode given, stretch (unitless) and nominal stress (MPa), checked for this fit."""
    import numpy as np

    data = {m: _mode_data(m, v, kinds.get(m, "engineering"))
            for m, v in given.items() if v is not None}
    if not data:
        raise InputError("fit_material needs data of at least one mode (uniaxial, biaxial, "
                         "planar)", param="uniaxial")
    n_par = len(HYPERELASTIC_MODELS[name])
    n_pts = sum(lam.size for lam, _ in data.values())
    if n_pts < n_par:
        raise InputError(f"{name} has {n_par} parameters: it needs at least {n_par} data "
                         f"points, got {n_pts}", param="model")
    if n_pts == n_par:      # interpolated, not fitted: nothing left to judge the fit by
        warn_implausible(f"{name} has {n_par} parameter{'s' * (n_par > 1)} and the data "
                         f"{n_pts} point{'s' * (n_pts > 1)}: the curve passes through them "
                         "exactly, the standard errors and R^2 are undefined (nan)")
    if residuals == "relative":
        for m, (_, p) in data.items():
            zero = np.flatnonzero(p == 0.0)
            if zero.size:
                raise InputError(f"residuals 'relative' divides by the stress, but {m} has 0 at "
                                 f"index {zero[0]}: use 'absolute' or drop the point",
                                 param="residuals")
    return data


@dataclass(frozen=True)
class _Setup:
    """What travels through one fit: the problem, a shear-modulus estimate ``g0`` (MPa) and the
    parameter bounds ``lo``/``hi`` (MPa or unitless, as the parameters)."""

    name: str
    prob: _Problem
    g0: float
    lo: NDArray[np.float64]
    hi: NDArray[np.float64]

    @property
    def n_pts(self) -> int:
        """Data points of all modes."""
        return int(self.prob.target.size)


def _setup(name: str, data: dict[str, tuple[Any, Any]], residuals: str,
           margin: float) -> _Setup:
    """The fit's setup: residual scale (1 or the stress, MPa), problem, g0 (MPa), bounds."""
    import numpy as np

    p_all = np.concatenate([p for _, p in data.values()])
    scale = p_all if residuals == "relative" else np.ones_like(p_all)
    prob = _Problem(name, data, scale, margin)
    g0 = _g0(data)
    lo_b, hi_b = (np.asarray(b, dtype=float) for b in _bounds(name, prob.secant))
    return _Setup(name, prob, g0, lo_b, hi_b)


@dataclass(frozen=True)
class _Runs:
    """The unconstrained local fits: ``(cost, x)`` lowest cost first, the Ogden exponent
    scan's (empty for the other models) and the cost of every start run (MPa^2 or unitless)."""

    results: list[tuple[float, Any]]
    scanned: list[tuple[float, Any]]
    start_costs: list[float]


def _polish(setup: _Setup, x0: Any) -> tuple[float, Any] | None:
    """Bounded least squares on all parameters from ``x0``: ``(cost, x)``, or None."""
    import numpy as np
    from scipy.optimize import least_squares

    lo_b, hi_b, prob = setup.lo, setup.hi, setup.prob
    inner_lo = lo_b + 1e-12 * np.abs(np.nan_to_num(lo_b, posinf=0.0, neginf=0.0))
    inner_hi = hi_b - 1e-12 * np.abs(np.nan_to_num(hi_b, posinf=0.0, neginf=0.0))
    x0 = np.clip(x0, inner_lo, inner_hi)
    with np.errstate(all="ignore"):
        res = least_squares(prob.resid, x0, jac=prob.jac, bounds=(lo_b, hi_b), method="trf",
                            x_scale="jac", xtol=1e-12, ftol=1e-12, gtol=1e-12, max_nfev=300)
    if np.all(np.isfinite(res.x)) and np.isfinite(res.cost):
        return float(res.cost), res.x
    return None


def _lm_batch(fun: Any, x0: Any, lo: Any, hi: Any, max_iter: int = 300, tol: float = 1e-9,
              crawl: float = 1e-6) -> tuple[Any, Any]:
    """Levenberg-Marquardt on many starts at once (the rows of ``x0``), bounds by projection.

    ``fun(X) -> (cost, res, jac)`` for the rows of X (cost half the squared norm, inf where
    undefined). Each row keeps its own damping and stops when its cost decrease, step or
    gradient falls below ``tol`` (relative, as least_squares' ftol/xtol/gtol), after
    ``max_iter`` iterations, or when its cost fell by less than ``crawl`` (relative) over the
    last ``_SCAN_WINDOW`` iterations.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        The final rows and their costs.
    """
    import numpy as np

    x = np.clip(np.array(x0, dtype=float), lo, hi)
    cost, res, jac = fun(x)
    damp = np.full(x.shape[0], 1e-3)
    active = np.isfinite(cost)
    eye = np.eye(x.shape[1])
    cost_then = cost.copy()
    for it in range(1, max_iter + 1):
        if it % _SCAN_WINDOW == 0:  # crawling rows (a dying term) stop
            active &= cost < (1.0 - crawl) * cost_then
            cost_then = cost.copy()
        idx = np.flatnonzero(active)
        if not idx.size:
            break
        j = jac[idx]
        grad = np.einsum("snk,sn->sk", j, res[idx])
        hess = np.swapaxes(j, 1, 2) @ j
        diag = np.maximum(np.diagonal(hess, axis1=1, axis2=2), 1e-300)
        # a variable at a bound that the descent pushes outward is held there (its row and
        # column of the step's system decoupled, its step 0)
        held = (((x[idx] <= lo) & (grad > 0.0)) | ((x[idx] >= hi) & (grad < 0.0)))
        hold = held[:, :, None] | held[:, None, :]
        system = np.where(hold, eye, hess + damp[idx, None, None] * diag[:, :, None] * eye)
        with np.errstate(all="ignore"):
            step = np.linalg.solve(system, np.where(held, 0.0, -grad)[..., None])[..., 0]
        trial = np.clip(x[idx] + np.nan_to_num(step), lo, hi)
        c_new, r_new, j_new = fun(trial)
        ok = c_new < cost[idx]
        done = ((ok & (cost[idx] - c_new <= tol * cost[idx]))
                | (np.linalg.norm(trial - x[idx], axis=1)
                   <= tol * (tol + np.linalg.norm(x[idx], axis=1)))
                | (np.max(np.abs(grad), axis=1) <= tol * np.maximum(cost[idx], 1e-300)))
        acc = idx[ok]
        x[acc], cost[acc], res[acc], jac[acc] = trial[ok], c_new[ok], r_new[ok], j_new[ok]
        damp[idx] = np.where(ok, np.maximum(damp[idx] / 3.0, 1e-12), damp[idx] * 4.0)
        active[idx[done | (damp[idx] > 1e12)]] = False
    return x, cost


def _exponent_scan(setup: _Setup, starts: list[Any]) -> list[tuple[float, Any]]:
    """Ogden: every start run on the exponents alone (variable projection: mu by linear least
    squares), all starts at once: to convergence on at most ``_SCAN_POINTS`` points per mode,
    then the best ``_SCAN_KEEP`` distinct runs on all the data; ``(cost, x)`` of every run
    (cost on all the data), lowest cost first."""
    import numpy as np

    prob = setup.prob
    sub = prob.subsampled(_SCAN_POINTS)
    lim = _ALPHA_MAX - 1e-9

    def on(pr: _Problem) -> Any:
        return lambda a: pr.vp_batch(a)[:3]

    a, cost = _lm_batch(on(sub), np.array([x0[1::2] for x0 in starts], dtype=float), -lim, lim)
    a = _bound_probes(sub, a, cost, lim)
    if sub is not prob:
        cost = prob.vp_batch(a)[0]
        order = np.argsort(cost)
        _, first = np.unique(np.round(np.sort(a[order], axis=1), 3), axis=0, return_index=True)
        best = order[np.sort(first)[:_SCAN_KEEP]]
        a[best], _ = _lm_batch(on(prob), a[best], -lim, lim)
    cost, _, _, mu = prob.vp_batch(a)
    scanned: list[tuple[float, Any]] = []
    for i in np.flatnonzero(np.isfinite(cost) & np.all(np.isfinite(mu), axis=1)):
        x_full = np.empty(prob.n_par)
        x_full[1::2] = a[i]
        x_full[0::2] = mu[i]
        scanned.append((float(cost[i]), x_full))
    scanned.sort(key=lambda r: r[0])
    return scanned


def _bound_probes(prob: _Problem, a: Any, cost: Any, lim: float) -> Any:
    """A term fitting the last points alone creeps toward its exponent bound, its mu toward 0
    (slowly: the cost falls a little per step). Every run's exponents are tried at the bound,
    one at a time; those lower than their run are run from there and added (rows of ``a``)."""
    import numpy as np

    n_t = a.shape[1]
    probes = np.repeat(a, n_t, axis=0)
    rows = np.arange(probes.shape[0])
    k = np.tile(np.arange(n_t), a.shape[0])
    probes[rows, k] = np.copysign(lim, probes[rows, k])
    lower = prob.vp_batch(probes)[0] < np.repeat(cost, n_t)
    if not lower.any():
        return a
    more, _ = _lm_batch(lambda x: prob.vp_batch(x)[:3], probes[lower], -lim, lim)
    return np.vstack([a, more])


def _polish_ogden(setup: _Setup, xs: list[Any]) -> list[tuple[float, Any]]:
    """Ogden: bounded least squares on all parameters from each of ``xs`` at once;
    ``(cost, x)`` of the finite results."""
    import numpy as np

    if not xs:
        return []
    x, cost = _lm_batch(setup.prob.full_batch, np.array(xs), setup.lo, setup.hi,
                        tol=_POLISH_TOL, crawl=0.0)
    return [(float(c), xi) for c, xi in zip(cost, x, strict=True) if np.isfinite(c)]


def _unconstrained_fits(setup: _Setup, n_starts: int | None) -> _Runs:
    """The bounded least-squares fits from every start (Ogden: the exponent scan, its best few
    polished on all parameters); an InputError when none converged."""
    import numpy as np

    starts = _starts(setup.prob, setup.g0, n_starts)
    scanned: list[tuple[float, Any]] = []
    results: list[tuple[float, Any]] = []
    if setup.name.startswith("ogden"):
        scanned = _exponent_scan(setup, starts)
        # a scanned minimum is a local minimum of the full problem too (mu is optimal for its
        # exponents) when its mu lie inside the bounds; the best three are polished as well
        results = [(c, xr) for c, xr in scanned
                   if np.all(xr >= setup.lo) and np.all(xr <= setup.hi)]
        results += _polish_ogden(setup, [xr for _, xr in scanned[:3]])
        start_costs = [c for c, _ in scanned]
    else:
        results = [f for f in (_polish(setup, x0) for x0 in starts) if f is not None]
        start_costs = [c for c, _ in results]
    if not results:
        raise InputError(f"the {setup.name} fit did not converge from any start; try another "
                         "model", param="model")
    results.sort(key=lambda r: r[0])
    return _Runs(results, scanned, start_costs)


def _constrained_fit(setup: _Setup, runs: _Runs, margin: float) -> Any:
    """The admissible optimum (SLSQP from several starts, or an admissible unconstrained run
    if lower); an InputError when there is none."""
    import numpy as np

    name, prob, results = setup.name, setup.prob, runs.results
    ok = [(c, xr) for c, xr in results[:8] if _admissible(prob, xr)]
    xs = np.array([setup.g0 if n.endswith("_mpa") else 1.0 for n in HYPERELASTIC_MODELS[name]])
    x0s = [xr for _, xr in results[:3]]
    if name.startswith("ogden"):  # the exponent scan's next-best minimum too
        x0s += [xr for _, xr in runs.scanned[3:4]]
    found = _solve_constrained(prob, x0s, setup.lo, setup.hi, xs,
                               _feasible_start(name, setup.g0))
    if ok and (found is None or ok[0][0] <= found[1]):
        found = (ok[0][1], ok[0][0])
    if found is None:
        raise InputError(f"model: no admissible {name} fit found (shear modulus > 0 and "
                         f"dP/dl > 0 over the data's range + {margin:.0%}); use another "
                         "model or allow_unstable", param="model")
    return found[0]


def _canonical_order(name: str, x: Any) -> Any:
    """Ogden terms in a canonical order, exponent descending; other models unchanged."""
    import numpy as np

    if not name.startswith("ogden"):
        return x
    order = np.argsort(-x[1::2], kind="stable")
    return np.concatenate([x[2 * i:2 * i + 2] for i in order])


def _floors_hit(prob: _Problem, x: Any) -> list[str]:
    """In words, the stability constraints at their floor at x (per measured mode)."""
    import numpy as np

    active: list[str] = []
    c, _ = prob.cons(x)
    off = 0
    for m in prob.modes:
        grid = prob.grid[m]
        cm = c[off:off + grid.size]
        off += grid.size
        hit = np.flatnonzero(cm <= 1e-6)
        if hit.size:
            at_one = np.abs(grid[hit] - 1.0) < 1e-12
            if at_one.any():
                active.append(f"{m} small-strain modulus at its floor (the data pull the "
                              "shear modulus to <= 0)")
                hit = hit[~at_one]
        if hit.size:
            active.append(f"{m} dP/dl at its floor at stretch "
                          + ", ".join(f"{v:.3g}" for v in grid[hit][:3])
                          + (" ..." if hit.size > 3 else ""))
    return active


def _bounds_hit(setup: _Setup, x: Any) -> list[str]:
    """In words, the parameters at a bound at x."""
    import numpy as np

    lo_b, hi_b = setup.lo, setup.hi
    near_lo = np.isfinite(lo_b) & (np.abs(x - lo_b) <= 1e-9 * np.maximum(1, np.abs(lo_b)))
    near_hi = np.isfinite(hi_b) & (np.abs(x - hi_b) <= 1e-9 * np.maximum(1, np.abs(hi_b)))
    pnames = HYPERELASTIC_MODELS[setup.name]
    return [f"{pnames[i]} at its bound {lo_b[i] if near_lo[i] else hi_b[i]:g}"
            for i in np.flatnonzero(near_lo | near_hi)]


def _active_constraints(setup: _Setup, x: Any, constrained: bool) -> list[str]:
    """In words, the constraints (after a constrained fit) and the bounds active at x."""
    active = _floors_hit(setup.prob, x) if constrained else []
    return active + _bounds_hit(setup, x)


def _uncertainty(prob: _Problem, x: Any) -> tuple[float, Any, Any, list[str]]:
    """Cost (half the SSR: MPa^2 or unitless), standard errors and correlation matrix of the
    parameters at x, and a note when they are strongly correlated."""
    import numpy as np

    r_opt, jac = prob.rj(x)
    cost = 0.5 * float(r_opt @ r_opt)
    n_par = prob.n_par
    dof = int(prob.target.size) - n_par
    if dof > 0:
        cov = lsq_covariance(jac, 2.0 * cost / dof)
        se, corr = standard_errors(cov), correlation(cov)
    else:
        se = np.full(n_par, np.nan)
        corr = np.full((n_par, n_par), np.nan)
        np.fill_diagonal(corr, 1.0)
    notes: list[str] = []
    off_diag = np.abs(corr[~np.eye(n_par, dtype=bool)])
    if off_diag.size and np.nanmax(off_diag) > 0.99:
        notes.append(f"parameters strongly correlated (|r| = {np.nanmax(off_diag):.3f}): the data "
                     "do not pin each one down; add another test mode or a simpler model")
    return cost, se, corr, notes


def _fitted_model(name: str, x: Any, d: float | None, poisson: float) -> HyperelasticModel:
    """The fitted parameters as a checked model (d in 1/MPa); an InputError if invalid."""
    try:
        return material_model(name, x, d=d, poisson=poisson)
    except InputError as exc:
        raise InputError(f"the {name} fit gives an invalid material ({exc}); try another "
                         "model", param="model") from None


def _mode_fits(fitted: HyperelasticModel, data: dict[str, tuple[Any, Any]],
               kinds: dict[str, str]) -> dict[str, ModeFit]:
    """Per mode: data, fitted nominal stress (MPa), R^2 and RMS (MPa)."""
    import numpy as np

    mode_fits = {}
    for m, (lam, p) in data.items():
        f = np.asarray(fitted._stress(m, lam, "engineering"), dtype=float)
        ss_res = float(np.sum((f - p) ** 2))
        ss_tot = float(np.sum((p - p.mean()) ** 2))
        r2 = 1.0 - ss_res / ss_tot if p.size > 1 and ss_tot > 0 else float("nan")
        mode_fits[m] = ModeFit(m, lam, p, f, r2, float(np.sqrt(ss_res / p.size)),
                               kinds.get(m, "engineering"))
    return mode_fits


def _data_stability(fitted: HyperelasticModel, prob: _Problem,
                    allow_unstable: bool) -> tuple[StabilityCheck, list[str]]:
    """Drucker check of the measured modes over their data's stretch ranges: an InputError
    when unstable, unless allowed (then a note)."""
    first: dict[str, float | None] = dict.fromkeys(MODES)
    for m in prob.modes:
        chk = fitted.stability(*prob.data_range[m], modes=(m,))
        first[m] = chk.unstable_from[m]
    d_lo = min(r[0] for r in prob.data_range.values())
    d_hi = max(r[1] for r in prob.data_range.values())
    stab = StabilityCheck(all(v is None for v in first.values()), d_lo, d_hi, first, 401,
                          tuple(prob.modes))
    if stab.stable:
        return stab, []
    where = ", ".join(f"{k} from stretch {v:.3g}" for k, v in first.items() if v is not None)
    msg = (f"the {prob.name} fit is Drucker-unstable (dP/dl <= 0) inside the data's stretch "
           f"range: {where}")
    if not allow_unstable:
        raise InputError(f"model: {msg}; use another model, the constrained fit or "
                         "allow_unstable", param="model")
    return stab, [msg]


def _stability_report(fitted: HyperelasticModel, prob: _Problem, stab: StabilityCheck,
                      report_range: tuple[float, float] | None,
                      ) -> tuple[dict[str, ModeStability], list[str]]:
    """Per path (all three), stable or not over the report range (unitless), and notes for
    instabilities not already refused or noted."""
    all_lo = min(r[0] for r in prob.range.values())
    all_hi = max(r[1] for r in prob.range.values())
    report: dict[str, ModeStability] = {}
    notes: list[str] = []
    for m in MODES:
        lo_s, hi_s = report_range or prob.range.get(m, (all_lo, all_hi))
        chk = fitted.stability(lo_s, hi_s, modes=(m,))
        ms = ModeStability(m, m in prob.data, lo_s, hi_s, chk.unstable_from[m] is None,
                           chk.unstable_from[m])
        report[m] = ms
        if ms.stable or (m in prob.data and stab.unstable_from[m] is not None):
            continue
        if m in prob.data:
            notes.append(f"{m}: Drucker-unstable from stretch {ms.unstable_from:.3g}, outside "
                         f"the data ({prob.data_range[m][1]:.3g}): do not extrapolate there")
        else:
            notes.append(f"{m} (not measured): Drucker-unstable from stretch "
                         f"{ms.unstable_from:.3g} within {lo_s:.3g}-{hi_s:.3g}; the fit predicts "
                         f"{m} deformation only where it is stable: test that mode, or set "
                         "stability_range to the stretches your part reaches")
    return report, notes


def _multistart_summary(start_costs: list[float], n_pts: int, residuals: str) -> dict[str, Any]:
    """How the starts did: their number, RMS (MPa, or unitless for relative residuals) of the
    best, median and worst, and how many came within 1 % of the best."""
    import numpy as np

    start_rms = np.sqrt(2.0 * np.array(sorted(start_costs)) / n_pts)
    unit = "mpa" if residuals == "absolute" else "rel"
    return {"n_starts": len(start_costs), f"rms_min_{unit}": float(start_rms[0]),
            f"rms_median_{unit}": float(np.median(start_rms)),
            f"rms_max_{unit}": float(start_rms[-1]),
            "n_within_1pct": int(np.sum(start_rms <= start_rms[0] * 1.01))}
